#!/usr/bin/python3
"""Writes the example model library: a few buildings, a tree and street clutter (a lamp, a stop
sign, a traffic light, a bench, a hydrant), as OBJ files with the quirks real model files
have (Y-up and Z-up, centimetres and millimetres, n-gons, negative indices, groups, doubled
faces, bases below zero, a front along +x), and library.json describing them.

Run from anywhere: python3 examples/models/make_models.py
"""
import json
import math
from pathlib import Path

HERE = Path(__file__).resolve().parent
MTL = {
    "plaster": (0.86, 0.80, 0.70), "brick": (0.62, 0.33, 0.25), "tiles": (0.45, 0.18, 0.14),
    "slate": (0.25, 0.26, 0.30), "glass": (0.35, 0.50, 0.62), "concrete": (0.66, 0.66, 0.64),
    "steel": (0.55, 0.58, 0.60), "door": (0.35, 0.22, 0.12), "bark": (0.30, 0.22, 0.15),
    "leaves": (0.22, 0.45, 0.18), "lamp": (0.95, 0.92, 0.75),
    "sign_red": (0.75, 0.08, 0.08), "sign_white": (0.92, 0.92, 0.90), "signal_red": (0.90, 0.10, 0.05),
    "signal_amber": (0.95, 0.65, 0.05), "signal_green": (0.10, 0.80, 0.30), "wood": (0.55, 0.38, 0.22),
    "hydrant": (0.80, 0.12, 0.10),
}


class Obj:
    """Faces given in Z-up metres, written in the file's own axes and unit."""

    def __init__(self, comment, up="z", unit=1.0, relative=False):
        self.lines = [f"# {comment}", "# written for Exacity by make_models.py", "mtllib library.mtl"]
        self.up, self.unit, self.relative = up, unit, relative
        self.count = 0

    def group(self, name):
        self.lines.append(f"g {name}")

    def material(self, name):
        self.lines.append(f"usemtl {name}")

    def face(self, points):
        for x, y, z in points:
            if self.up == "y":
                x, y, z = x, z, -y
            self.lines.append("v " + " ".join(f"{c / self.unit:.6g}" for c in (x, y, z)))
        n = len(points)
        if self.relative:  # negative indices count back from the last vertex
            self.lines.append("f " + " ".join(str(i - n) for i in range(n)))
        else:
            self.lines.append("f " + " ".join(f"{self.count + i + 1}//" if i % 2 else str(self.count + i + 1) for i in range(n)))
        self.count += n

    def save(self, name):
        (HERE / name).write_text("\n".join(self.lines) + "\n")


def box(o, x0, y0, z0, x1, y1, z1, sides="all"):
    """A closed box, outward faces counter-clockwise."""
    o.face([(x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)])  # bottom
    o.face([(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)])  # top
    o.face([(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)])  # front (-y)
    o.face([(x1, y1, z0), (x0, y1, z0), (x0, y1, z1), (x1, y1, z1)])  # back
    o.face([(x0, y1, z0), (x0, y0, z0), (x0, y0, z1), (x0, y1, z1)])  # left
    o.face([(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)])  # right


def gabled_house(name, w, d, wall, ridge, up, relative):
    o = Obj(f"{name}: a gabled house, {w} x {d} m, front towards -y", up=up, relative=relative)
    o.group("walls")
    o.material("plaster")
    x0, x1, y0, y1 = -w / 2, w / 2, -d / 2, d / 2
    o.face([(x0, y0, 0), (x0, y1, 0), (x1, y1, 0), (x1, y0, 0)])
    o.face([(x0, y0, 0), (x1, y0, 0), (x1, y0, wall), (x0, y0, wall)])
    o.face([(x1, y1, 0), (x0, y1, 0), (x0, y1, wall), (x1, y1, wall)])
    # gable ends as pentagons (n-gons)
    o.face([(x0, y1, 0), (x0, y0, 0), (x0, y0, wall), (x0, 0, ridge), (x0, y1, wall)])
    o.face([(x1, y0, 0), (x1, y1, 0), (x1, y1, wall), (x1, 0, ridge), (x1, y0, wall)])
    o.group("roof")
    o.material("tiles")
    o.face([(x0, y0, wall), (x1, y0, wall), (x1, 0, ridge), (x0, 0, ridge)])
    o.face([(x1, y1, wall), (x0, y1, wall), (x0, 0, ridge), (x1, 0, ridge)])
    o.group("door")
    o.material("door")
    box(o, -0.6, y0 - 0.3, 0, 0.6, y0, 2.2)
    return o


def l_house():
    o = Obj("house_l: an L-shaped flat-roofed house, Z-up, negative indices", up="z", relative=True)
    o.material("brick")
    pts = [(-6, -5), (6, -5), (6, 1), (0, 1), (0, 5), (-6, 5)]
    h = 6.5
    o.face([(x, y, 0) for x, y in reversed(pts)])  # floor: an n-gon, concave
    o.material("slate")
    o.face([(x, y, h) for x, y in pts])
    o.material("brick")
    for (ax, ay), (bx, by) in zip(pts, pts[1:] + pts[:1]):
        o.face([(ax, ay, 0), (bx, by, 0), (bx, by, h), (ax, ay, h)])
    o.material("door")
    box(o, -3.6, -5.3, 0, -2.4, -5, 2.2)
    return o


def apartment():
    o = Obj("apartment: a block of flats in millimetres, Y-up", up="y", unit=0.001)
    o.material("concrete")
    box(o, -10, -6, 0, 10, 6, 18)
    o.material("glass")
    for k in range(5):  # balconies on the front, one per floor
        z = 3 + 3 * k
        box(o, -8, -7.2, z, 8, -6, z + 0.3)
    return o


def office_tower():
    o = Obj("office_tower: podium and tower, Z-up, base 2 m below zero", up="z")
    o.material("concrete")
    box(o, -12, -12, -2, 12, 12, 8)
    o.material("glass")
    box(o, -8, -8, 8, 8, 8, 62)
    o.material("steel")
    box(o, -3, -3, 62, 3, 3, 66)
    return o


def warehouse():
    o = Obj("warehouse: sawtooth roof, with doubled faces as some exporters write them", up="y")
    w, d, h = 40, 24, 8
    o.material("steel")
    x0, x1, y0, y1 = -w / 2, w / 2, -d / 2, d / 2
    o.face([(x0, y0, 0), (x0, y1, 0), (x1, y1, 0), (x1, y0, 0)])
    o.face([(x0, y0, 0), (x1, y0, 0), (x1, y0, h), (x0, y0, h)])
    o.face([(x0, y0, 0), (x1, y0, 0), (x1, y0, h), (x0, y0, h)])  # doubled
    o.face([(x1, y1, 0), (x0, y1, 0), (x0, y1, h), (x1, y1, h)])
    teeth = 4
    step = d / teeth
    left, right = [(x0, y1, 0), (x0, y0, 0), (x0, y0, h)], [(x1, y0, 0), (x1, y1, 0)]
    for k in range(teeth):
        ya, yb = y0 + k * step, y0 + (k + 1) * step
        left += [(x0, yb, h + 2.5), (x0, yb, h)] if k < teeth - 1 else [(x0, yb, h + 2.5)]
    o.face(left)
    rpts = [(x1, y0, 0), (x1, y1, 0), (x1, y1, h + 2.5)]
    for k in reversed(range(teeth)):
        ya = y0 + k * step
        rpts += [(x1, ya, h), (x1, ya, h + 2.5)] if k > 0 else [(x1, ya, h)]
    o.face(rpts)
    o.material("slate")
    for k in range(teeth):
        ya, yb = y0 + k * step, y0 + (k + 1) * step
        o.face([(x0, ya, h), (x1, ya, h), (x1, yb, h + 2.5), (x0, yb, h + 2.5)])  # slope
        o.material("glass")
        o.face([(x1, yb, h), (x0, yb, h), (x0, yb, h + 2.5), (x1, yb, h + 2.5)]) if k < teeth - 1 else None
        o.material("slate")
    return o


def tree():
    o = Obj("tree: trunk and crown as separate objects, Y-up", up="y")
    o.lines.append("o trunk")
    o.material("bark")
    n = 6
    ring = [(0.25 * math.cos(2 * math.pi * i / n), 0.25 * math.sin(2 * math.pi * i / n)) for i in range(n)]
    for (ax, ay), (bx, by) in zip(ring, ring[1:] + ring[:1]):
        o.face([(ax, ay, 0), (bx, by, 0), (bx, by, 3), (ax, ay, 3)])
    o.lines.append("o crown")
    o.material("leaves")
    r, c = 2.5, 5.0
    top, bottom = (0, 0, c + r), (0, 0, c - r)
    ring = [(r * math.cos(2 * math.pi * i / 8), r * math.sin(2 * math.pi * i / 8), c) for i in range(8)]
    for a, b in zip(ring, ring[1:] + ring[:1]):
        o.face([a, b, top])
        o.face([b, a, bottom])
    return o


def street_lamp():
    o = Obj("street_lamp: a pole with an arm over the road side (-y), in centimetres, Z-up", up="z", unit=0.01)
    o.material("steel")
    box(o, -0.1, -0.1, 0, 0.1, 0.1, 6)
    box(o, -0.05, -1.2, 5.8, 0.05, 0.1, 5.9)
    o.material("lamp")
    box(o, -0.2, -1.4, 5.5, 0.2, -0.9, 5.8)
    return o


def prism(o, corners, z0, z1):
    """A closed upright prism over a counter-clockwise polygon (x, y), sides as quads."""
    o.face([(x, y, z0) for x, y in reversed(corners)])
    o.face([(x, y, z1) for x, y in corners])
    for (ax, ay), (bx, by) in zip(corners, corners[1:] + corners[:1]):
        o.face([(ax, ay, z0), (bx, by, z0), (bx, by, z1), (ax, ay, z1)])


def stop_sign():
    o = Obj("stop_sign: a pole and an octagonal plate facing the traffic (-y), in millimetres, Z-up", up="z",
            unit=0.001)
    o.material("steel")
    box(o, -0.03, -0.03, 0, 0.03, 0.03, 2.3)
    # The plate: an octagon 0.75 m across standing in the x-z plane, as a thin slab.
    r = 0.375 / math.cos(math.pi / 8)
    octagon = [(r * math.cos(math.pi / 8 + i * math.pi / 4), 1.95 + r * math.sin(math.pi / 8 + i * math.pi / 4))
               for i in range(8)]
    o.material("sign_red")
    o.face([(x, -0.05, z) for x, z in reversed(octagon)])  # front, one n-gon
    o.material("sign_white")
    o.face([(x, -0.03, z) for x, z in octagon])  # back
    for (ax, az), (bx, bz) in zip(octagon, octagon[1:] + octagon[:1]):
        o.face([(ax, -0.05, az), (bx, -0.05, bz), (bx, -0.03, bz), (ax, -0.03, az)])
    return o


def traffic_light():
    o = Obj("traffic_light: a pole and a signal head facing -y, Y-up", up="y")
    o.material("steel")
    box(o, -0.07, -0.07, 0, 0.07, 0.07, 2.6)
    o.material("slate")
    box(o, -0.18, -0.2, 2.6, 0.18, 0.12, 3.6)
    for k, colour in enumerate(["signal_green", "signal_amber", "signal_red"]):
        o.material(colour)
        z = 2.7 + 0.3 * k
        box(o, -0.1, -0.26, z, 0.1, -0.2, z + 0.2)
    return o


def bench():
    o = Obj("bench: legs, seat and back, its front along +x (the library says so), Z-up", up="z", relative=True)
    o.material("steel")
    for x in (-0.2, 0.15):
        for y in (-0.8, 0.75):
            box(o, x, y, 0, x + 0.05, y + 0.05, 0.45)
    o.material("wood")
    box(o, -0.22, -0.85, 0.45, 0.22, 0.85, 0.5)
    box(o, -0.25, -0.85, 0.5, -0.2, 0.85, 0.9)
    return o


def hydrant():
    o = Obj("hydrant: a red octagonal post with a cap, in centimetres, Y-up", up="y", unit=0.01)
    o.material("hydrant")
    ring = [(0.12 * math.cos(i * math.pi / 4), 0.12 * math.sin(i * math.pi / 4)) for i in range(8)]
    prism(o, ring, 0, 0.6)
    prism(o, [(0.7 * x, 0.7 * y) for x, y in ring], 0.6, 0.75)
    box(o, -0.05, -0.2, 0.35, 0.05, -0.12, 0.45)  # the outlet, to the front
    return o


def main():
    models = [
        ("house_gabled.obj", gabled_house("house_gabled", 9, 8, 5.5, 8.5, "y", False),
         {"zones": ["residential"], "up": "y", "weight": 3, "scale": [0.9, 1.15]}),
        ("house_wide.obj", gabled_house("house_wide", 13, 9, 4.5, 7.5, "z", True),
         {"zones": ["residential"], "up": "z", "weight": 2}),
        ("house_l.obj", l_house(), {"zones": ["residential"], "up": "z", "weight": 2}),
        ("apartment.obj", apartment(), {"zones": ["residential", "commercial"], "up": "y", "unit": "mm", "weight": 1}),
        ("office_tower.obj", office_tower(), {"zones": ["commercial"], "up": "z", "weight": 2, "scale": [0.8, 1.2]}),
        ("warehouse.obj", warehouse(), {"zones": ["industrial"], "up": "y", "weight": 1, "scale": [0.8, 1.3]}),
        ("tree.obj", tree(), {"zones": ["residential", "commercial", "industrial"], "kind": "tree", "up": "y",
                              "scale": [0.7, 1.3]}),
        # Street clutter: without "zones" it dresses every zone's streets but water.
        ("street_lamp.obj", street_lamp(), {"kind": "lamp", "up": "z", "unit": "cm", "spacing": 30, "offset": 0.6,
                                            "scale": [1, 1]}),
        ("stop_sign.obj", stop_sign(), {"kind": "sign", "up": "z", "unit": "mm", "offset": 0.5, "scale": [1, 1]}),
        ("traffic_light.obj", traffic_light(), {"kind": "traffic_light", "up": "y", "offset": 0.6, "scale": [1, 1]}),
        ("bench.obj", bench(), {"kind": "bench", "zones": ["residential", "commercial", "park"], "up": "z",
                                "front": "+x", "spacing": 60, "offset": 1.2, "side": "alternate", "scale": [1, 1]}),
        ("hydrant.obj", hydrant(), {"kind": "hydrant", "up": "y", "unit": "cm", "spacing": 90, "offset": 0.4,
                                    "side": "alternate", "scale": [1, 1]}),
    ]
    entries = []
    for file, obj, props in models:
        obj.save(file)
        entries.append({"name": Path(file).stem, "file": file, **props})
    (HERE / "library.mtl").write_text("".join(f"newmtl {k}\nKd {r} {g} {b}\n\n" for k, (r, g, b) in MTL.items()))
    (HERE / "library.json").write_text(json.dumps({"models": entries}, indent=2) + "\n")


if __name__ == "__main__":
    main()
