#!/usr/bin/python3
"""Independent check of an exacity output folder with GEOS (through shapely).

Written apart from exacity's own exact validator so that a bug in one is caught by the
other: every polygon valid in the OGC sense, outer rings counter-clockwise and holes
clockwise, rings closed; zones, water and non-bridge road areas pairwise disjoint (their
overlaps have no area); bridges over water; buildings apart, or, nested, apart in
3D by the slabs they write; each piece of street clutter strictly inside a sidewalk or a lot
and in no carriageway, junction, water or building.

Usage: check_layers.py OUT_DIR   (exit 0 when every check holds, 1 otherwise)
"""
import json
import sys
import warnings
from fractions import Fraction as F
from pathlib import Path

from shapely.geometry import LineString, Point, Polygon, shape
from shapely.ops import unary_union
from shapely.strtree import STRtree

warnings.filterwarnings("ignore", message="STRtree will be changed")  # shapely 1.8 on Debian 12

AREA_TOLERANCE = 1e-6  # m²: GEOS computes overlaps in doubles


def load(path):
    doc = json.loads(path.read_text())
    assert doc["type"] == "FeatureCollection", f"{path}: not a FeatureCollection"
    return doc["features"]


def signed_area(ring):
    # Exact on the written doubles: a float sum gets the sign of tiny rings wrong.
    return sum(F(x0) * F(y1) - F(x1) * F(y0) for (x0, y0), (x1, y1) in zip(ring, ring[1:])) / 2


def nested_overlap(a, b):
    """Why two buildings whose footprints overlap may not (nesting); None when the
    slabs both write (heights from their floors, exact as fractions) prove that wherever
    they share the plan one lies wholly below the other."""
    stacks = []
    for props in (a, b):
        slabs, floor = props.get("slabs"), props.get("floor")
        if not slabs or floor is None:
            return "no slabs"
        if any(s["bottom"] >= s["top"] for s in slabs) or any(
                s["bottom"] != below["top"] for below, s in zip(slabs, slabs[1:])):
            return "slabs not stacked bottom to top"
        if slabs[0]["bottom"] > 0 or slabs[-1]["top"] != props.get("height"):
            return "slabs do not span its height"
        stacks.append([(F(floor) + F(s["bottom"]), F(floor) + F(s["top"]),
                        unary_union([Polygon(r) for r in s["outline"]])) for s in slabs])
    for lo, hi, plan in stacks[0]:
        for lo2, hi2, plan2 in stacks[1]:
            if lo <= hi2 and lo2 <= hi and plan.intersection(plan2).area > AREA_TOLERANCE:
                return f"slabs at {float(lo)}-{float(hi)} m and {float(lo2)}-{float(hi2)} m overlap in plan"
    return None


CLUTTER_KINDS = {"lamp", "sign", "traffic_light", "bench", "hydrant", "tree"}


def check_clutter(out):
    """vector/clutter.geojson: Points with unique ids and known kinds, each naming a road of
    roads.geojson, each strictly inside a sidewalk (not a bridge's) or a lot, and touching no
    carriageway, junction, water or building; a park's tree names no road and stands strictly
    inside a park zone."""
    problems = []
    roads = {f["properties"]["id"] for f in load(out / "vector" / "roads.geojson")}
    stands_on, keeps_off = [], []
    for f in load(out / "vector" / "road_areas.geojson"):
        on_sidewalk = f["properties"]["surface"] == "sidewalk" and not f["properties"]["bridge"]
        (stands_on if on_sidewalk else keeps_off).append(shape(f["geometry"]))
    stands_on += [shape(f["geometry"]) for f in load(out / "vector" / "lots.geojson")]
    for layer in ("water", "buildings"):
        keeps_off += [shape(f["geometry"]) for f in load(out / "vector" / f"{layer}.geojson")]
    parks = [shape(f["geometry"]) for f in load(out / "vector" / "zones.geojson") if f["properties"]["zone"] == "park"]
    on_tree, off_tree, park_tree = STRtree(stands_on), STRtree(keeps_off), STRtree(parks)
    ids = set()
    for i, f in enumerate(load(out / "vector" / "clutter.geojson")):
        name, props, g = f"clutter[{i}]", f["properties"], f["geometry"]
        if g["type"] != "Point":
            problems.append(f"{name}: geometry is {g['type']}, expected Point")
            continue
        if props.get("id") in ids:
            problems.append(f"{name}: id {props.get('id')} is not unique")
        ids.add(props.get("id"))
        if props.get("kind") not in CLUTTER_KINDS:
            problems.append(f"{name}: kind {props.get('kind')!r} is no clutter kind")
        in_park = props.get("kind") == "tree" and props.get("road") is None
        if not in_park and props.get("road") not in roads:
            problems.append(f"{name}: road {props.get('road')} names no centre line")
        if not 0 <= props.get("heading", -1) < 360:
            problems.append(f"{name}: heading {props.get('heading')} is not in [0, 360)")
        point = Point(g["coordinates"])
        if in_park:
            if not any(p.contains(point) for p in park_tree.query(point)):
                problems.append(f"{name}: at {g['coordinates']}, a park's tree not strictly inside a park")
        elif not any(p.contains(point) for p in on_tree.query(point)):
            problems.append(f"{name}: at {g['coordinates']}, not strictly inside a sidewalk or a lot")
        if any(p.intersects(point) for p in off_tree.query(point)):
            problems.append(f"{name}: at {g['coordinates']}, on a carriageway, junction, water or building")
    return problems


def main(out):
    problems = []
    polygons = []  # (name, kind, shapely polygon)
    properties = {}  # name -> the feature's properties
    for layer in ("zones", "water", "road_areas", "blocks", "lots", "buildings"):
        for i, f in enumerate(load(out / "vector" / f"{layer}.geojson")):
            name = f"{layer}[{i}]"
            g = f["geometry"]
            if g["type"] != "Polygon":
                problems.append(f"{name}: geometry is {g['type']}, expected Polygon")
                continue
            rings = g["coordinates"]
            for k, ring in enumerate(rings):
                if len(ring) < 4 or ring[0] != ring[-1]:
                    problems.append(f"{name}: ring {k} is not closed")
                area = signed_area(ring)
                if (k == 0) != (area > 0):
                    problems.append(f"{name}: ring {k} has the wrong orientation (signed area {float(area)})")
            poly = Polygon(rings[0], rings[1:])
            if not poly.is_valid:
                from shapely.validation import explain_validity
                problems.append(f"{name}: invalid: {explain_validity(poly)}")
            kind = "bridge" if f["properties"].get("bridge") else layer
            if layer == "zones" and f["properties"].get("zone") == "park":
                kind = "park"
            polygons.append((name, kind, poly))
            properties[name] = f["properties"]
    for i, f in enumerate(load(out / "vector" / "roads.geojson")):
        line = LineString(f["geometry"]["coordinates"])
        if not line.is_valid or line.length <= 0:
            problems.append(f"roads[{i}]: invalid centre line")

    # Two tilings: zones, water and road areas; blocks, parks, water and road areas. And
    # lots apart from each other and from roads.
    for kinds in ({"zones", "park", "water", "road_areas"}, {"blocks", "park", "water", "road_areas"},
                  {"lots", "road_areas", "water"}, {"buildings", "road_areas", "water"}):
        surfaces = [(n, p) for n, k, p in polygons if k in kinds and p.is_valid]
        tree = STRtree([p for _, p in surfaces])
        index = {id(p): i for i, (_, p) in enumerate(surfaces)}
        for i, (name, poly) in enumerate(surfaces):
            for other in tree.query(poly):
                j = index[id(other)]
                if j <= i:
                    continue
                overlap = poly.intersection(other).area
                if overlap <= AREA_TOLERANCE:
                    continue
                other_name = surfaces[j][0]
                if name.startswith("buildings") and other_name.startswith("buildings"):
                    why = nested_overlap(properties[name], properties[other_name])
                    if why:
                        problems.append(f"{name} and {other_name} overlap by {overlap} m² ({why})")
                    continue
                problems.append(f"{name} and {other_name} overlap by {overlap} m²")
    water = [p for _, k, p in polygons if k == "water" and p.is_valid]
    for name, kind, poly in polygons:
        if kind == "bridge" and poly.is_valid:
            covered = sum(poly.intersection(w).area for w in water)
            if poly.area - covered > AREA_TOLERANCE:
                problems.append(f"{name}: bridge not over water ({poly.area - covered} m² on land)")

    blocks = {f["properties"]["id"]: shape(f["geometry"]) for f in load(out / "vector" / "blocks.geojson")}
    for i, f in enumerate(load(out / "vector" / "lots.geojson")):
        outside = shape(f["geometry"]).difference(blocks[f["properties"]["block"]]).area
        if outside > AREA_TOLERANCE:
            problems.append(f"lots[{i}]: {outside} m² outside its block {f['properties']['block']}")

    lots = {f["properties"]["id"]: shape(f["geometry"]) for f in load(out / "vector" / "lots.geojson")}
    road_areas = [shape(f["geometry"]) for f in load(out / "vector" / "road_areas.geojson")]
    tree = STRtree(road_areas)
    for i, (lot_id, lot) in enumerate(lots.items()):
        near = tree.query(lot)  # shapely 1.8: the geometries themselves
        if not any(lot.boundary.intersection(r.boundary).length > 1e-6 for r in near):
            problems.append(f"lot {lot_id}: shares no edge with a road area")
    for i, f in enumerate(load(out / "vector" / "buildings.geojson")):
        footprint = shape(f["geometry"])
        if f["properties"].get("mapped"):
            # A mapped building stands as drawn, across lots or on none, but keeps off the streets.
            on_streets = sum(footprint.intersection(r).area for r in tree.query(footprint))
            if on_streets > AREA_TOLERANCE:
                problems.append(f"buildings[{i}]: mapped, {on_streets} m² on road areas")
            continue
        if f["properties"].get("lot") not in lots:
            problems.append(f"buildings[{i}]: not mapped and on no lot of lots.geojson")
            continue
        outside = footprint.difference(lots[f["properties"]["lot"]]).area
        if outside > AREA_TOLERANCE:
            problems.append(f"buildings[{i}]: {outside} m² outside its lot {f['properties']['lot']}")

    problems += check_clutter(out)
    for p in problems:
        print("problem:", p)
    print(f"{out}: {len(polygons)} polygons, {'ok' if not problems else f'{len(problems)} problems'}")
    return 0 if not problems else 1


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1])))
