#!/usr/bin/env python3
"""Writes village.osm: a small OpenStreetMap extract made up for Exacity (no real place).

A primary road with a river south of it, a grid of residential streets 200 m apart, a residential area
(a closed way) with a park and a pond inside, a retail area (a multipolygon relation with a
courtyard), and what Exacity leaves out: a footway and a road in a tunnel. Drawn in metres
around lon 10, lat 48 and written in lon/lat, as OSM is.
"""
import math
from pathlib import Path

LON0, LAT0 = 10.0, 48.0
M_PER_DEG_LAT = 111_195.0
M_PER_DEG_LON = M_PER_DEG_LAT * math.cos(math.radians(LAT0))

nodes, ways, relations = [], [], []


def node(x, y):
    nodes.append((len(nodes) + 1, LON0 + x / M_PER_DEG_LON, LAT0 + y / M_PER_DEG_LAT))
    return nodes[-1][0]


def way(points, tags, closed=False):
    refs = [node(x, y) for x, y in points]
    if closed:
        refs.append(refs[0])
    ways.append((100 + len(ways), refs, tags))
    return ways[-1][0]


# Streets share their junction nodes, as mapped streets do.
grid = {(x, y): node(x, y) for x in (0, 200, 400, 600) for y in (0, 200, 400)}
west, east = node(-60, 0), node(660, 0)
ways.append((100 + len(ways), [west, grid[0, 0], grid[200, 0], grid[400, 0], grid[600, 0], east],
             {"highway": "primary", "lanes": "4", "name": "Hauptstrasse"}))
for x in (0, 200, 400, 600):
    ways.append((100 + len(ways), [grid[x, 0], grid[x, 200], grid[x, 400]], {"highway": "residential", "width": "7 m"}))
for y, name in ((200, "Mittelweg"), (400, "Waldweg")):
    ways.append((100 + len(ways), [grid[0, y], grid[200, y], grid[400, y], grid[600, y]],
                 {"highway": "residential", "name": name}))
way([(0, 100), (200, 100)], {"highway": "footway"})
way([(200, 300), (400, 300)], {"highway": "residential", "tunnel": "yes"})
way([(-80, -120), (300, -110), (700, -130)], {"waterway": "river", "width": "14"})
way([(0, 0), (400, 0), (400, 400), (0, 400)], {"landuse": "residential"}, closed=True)
way([(40, 240), (160, 240), (160, 360), (40, 360)], {"leisure": "park", "name": "Dorfpark"}, closed=True)
way([(250, 250), (330, 250), (330, 330), (250, 330)], {"natural": "water"}, closed=True)
outer = way([(400, 0), (600, 0), (600, 400), (400, 400)], {}, closed=True)
inner = way([(450, 150), (550, 150), (550, 250), (450, 250)], {}, closed=True)
relations.append((900, [("way", outer, "outer"), ("way", inner, "inner")], {"type": "multipolygon", "landuse": "retail"}))

lines = ['<?xml version="1.0" encoding="UTF-8"?>', '<osm version="0.6" generator="examples/osm/make_village.py">']
for i, lon, lat in nodes:
    lines.append(f'  <node id="{i}" version="1" lat="{lat:.7f}" lon="{lon:.7f}"/>')
for i, refs, tags in ways:
    lines.append(f'  <way id="{i}" version="1">')
    lines += [f'    <nd ref="{r}"/>' for r in refs]
    lines += [f'    <tag k="{k}" v="{v}"/>' for k, v in tags.items()]
    lines.append("  </way>")
for i, members, tags in relations:
    lines.append(f'  <relation id="{i}" version="1">')
    lines += [f'    <member type="{t}" ref="{r}" role="{role}"/>' for t, r, role in members]
    lines += [f'    <tag k="{k}" v="{v}"/>' for k, v in tags.items()]
    lines.append("  </relation>")
lines.append("</osm>")
Path(__file__).with_name("village.osm").write_text("\n".join(lines) + "\n")
