#!/usr/bin/python3
"""Writes the nesting example's model library (nesting's 3D occupancy grid): a gateway (a
beam on two pillars) and a T on one pillar, whose overhangs leave room under them, and two
small models that fit there: a kiosk and a hut. OBJ files in Z-up metres, each part a closed
box with its faces wound counter-clockwise seen from outside, and library.json naming them.

Run from anywhere: python3 examples/nesting/make_models.py
"""
import json
from pathlib import Path

HERE = Path(__file__).resolve().parent
COLOURS = {"stone": (0.70, 0.66, 0.58), "roof": (0.42, 0.20, 0.16), "wood": (0.55, 0.40, 0.25),
           "glass": (0.40, 0.55, 0.65)}


class Model:
    def __init__(self, comment):
        self.lines = [f"# {comment}", "# written for Exacity by examples/nesting/make_models.py",
                      "mtllib library.mtl"]
        self.vertices = 0

    def material(self, name):
        self.lines.append(f"usemtl {name}")

    def polygon(self, corners):
        """One face: its corners counter-clockwise seen from outside."""
        for x, y, z in corners:
            self.lines.append(f"v {x:g} {y:g} {z:g}")
        self.lines.append("f " + " ".join(str(self.vertices + k + 1) for k in range(len(corners))))
        self.vertices += len(corners)

    def cuboid(self, x0, y0, z0, x1, y1, z1):
        """A closed box from (x0, y0, z0) to (x1, y1, z1)."""
        self.polygon([(x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)])  # underside
        self.polygon([(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)])  # top
        self.polygon([(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)])  # -y
        self.polygon([(x1, y1, z0), (x0, y1, z0), (x0, y1, z1), (x1, y1, z1)])  # +y
        self.polygon([(x0, y1, z0), (x0, y0, z0), (x0, y0, z1), (x0, y1, z1)])  # -x
        self.polygon([(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)])  # +x

    def save(self, name):
        (HERE / name).write_text("\n".join(self.lines) + "\n")


def gateway():
    """A beam 20 m long, 8 m deep and 3 m thick on two pillars 3 m wide: 7 m clear under it."""
    m = Model("gateway: a beam on two pillars")
    m.material("stone")
    m.cuboid(-10, -4, 0, -7, 4, 7)
    m.cuboid(7, -4, 0, 10, 4, 7)
    m.cuboid(-10, -4, 7, 10, 4, 10)
    m.save("gateway.obj")


def tee():
    """A T: a slab 16 m by 10 m, 3 m thick, on one pillar 4 m square: 6 m clear under it."""
    m = Model("tee: a slab on one pillar")
    m.material("stone")
    m.cuboid(-2, -2, 0, 2, 2, 6)
    m.material("glass")
    m.cuboid(-8, -5, 6, 8, 5, 9)
    m.save("tee.obj")


def kiosk():
    """A box 3 m square and 2.5 m high."""
    m = Model("kiosk")
    m.material("wood")
    m.cuboid(-1.5, -1.5, 0, 1.5, 1.5, 2.5)
    m.save("kiosk.obj")


def hut():
    """A hut 4 m by 3 m, walls 3 m high under a gabled roof to 4.5 m."""
    m = Model("hut")
    m.material("wood")
    m.cuboid(-2, -1.5, 0, 2, 1.5, 3)
    m.material("roof")
    m.polygon([(-2, -1.5, 3), (2, -1.5, 3), (2, 0, 4.5), (-2, 0, 4.5)])  # front slope
    m.polygon([(2, 1.5, 3), (-2, 1.5, 3), (-2, 0, 4.5), (2, 0, 4.5)])  # back slope
    m.polygon([(-2, 1.5, 3), (-2, -1.5, 3), (-2, 0, 4.5)])  # gables
    m.polygon([(2, -1.5, 3), (2, 1.5, 3), (2, 0, 4.5)])
    m.save("hut.obj")


def main():
    gateway(), tee(), kiosk(), hut()
    (HERE / "library.mtl").write_text(
        "".join(f"newmtl {n}\nKd {r} {g} {b}\n" for n, (r, g, b) in COLOURS.items()))
    entries = [{"name": "gateway", "file": "gateway.obj", "zones": ["commercial"], "up": "z", "weight": 1},
               {"name": "tee", "file": "tee.obj", "zones": ["commercial"], "up": "z", "weight": 1},
               {"name": "kiosk", "file": "kiosk.obj", "zones": ["commercial"], "up": "z", "weight": 3},
               {"name": "hut", "file": "hut.obj", "zones": ["commercial"], "up": "z", "weight": 2},
               # The street dressed with the example library's street clutter.
               {"name": "street_lamp", "file": "../models/street_lamp.obj", "kind": "lamp", "up": "z", "unit": "cm",
                "spacing": 20, "offset": 0.6, "scale": [1, 1]},
               {"name": "bench", "file": "../models/bench.obj", "kind": "bench", "up": "z", "front": "+x",
                "spacing": 25, "offset": 1.2, "side": "alternate", "scale": [1, 1]},
               {"name": "hydrant", "file": "../models/hydrant.obj", "kind": "hydrant", "up": "y", "unit": "cm",
                "spacing": 45, "offset": 0.4, "side": "alternate", "scale": [1, 1]}]
    (HERE / "library.json").write_text(json.dumps({"models": entries}, indent=2) + "\n")


if __name__ == "__main__":
    main()
