#!/usr/bin/python3
"""Checks an exacity city.city.json against the CityJSON 2.0 JSON schemas, and beyond them:
every vertex index in range, no ring repeating a vertex, every building shell closed (each
edge used once in each direction) after quantisation.

Usage: check_cityjson.py CITY_JSON SCHEMA_DIR   (exit 0 when everything holds)
"""
import json
import sys
import warnings
from collections import Counter
from pathlib import Path

warnings.filterwarnings("ignore", category=DeprecationWarning)
import jsonschema  # noqa: E402


def main(city_file, schema_dir):
    city = json.loads(Path(city_file).read_text())
    schema_dir = Path(schema_dir).resolve()
    schema = json.loads((schema_dir / "cityjson.schema.json").read_text())
    # Every schema under its $id, so references resolve here and nothing is fetched.
    store = {}
    for f in schema_dir.glob("*.schema.json"):
        doc = json.loads(f.read_text())
        store[doc.get("$id", f.name)] = doc
    resolver = jsonschema.RefResolver(base_uri=schema.get("$id", schema_dir.as_uri() + "/"), referrer=schema, store=store)
    validator = jsonschema.Draft7Validator(schema, resolver=resolver)
    problems = [f"schema: {e.message} at {list(e.absolute_path)[:6]}" for e in validator.iter_errors(city)][:10]

    n = len(city["vertices"])

    def rings(boundaries):
        if boundaries and isinstance(boundaries[0], int):
            yield boundaries
        else:
            for b in boundaries:
                yield from rings(b)

    for oid, obj in city["CityObjects"].items():
        for g in obj.get("geometry", []):
            for r in rings(g["boundaries"]):
                if any(i < 0 or i >= n for i in r):
                    problems.append(f"{oid}: vertex index out of range")
                if len(set(r)) != len(r) or len(r) < 3:
                    problems.append(f"{oid}: a ring repeats a vertex or has under 3")
            if g["type"] == "Solid":
                edges = Counter()
                for surface in g["boundaries"][0]:
                    for r in surface:
                        for a, b in zip(r, r[1:] + r[:1]):
                            edges[(a, b)] += 1
                if any(edges[(b, a)] != c for (a, b), c in edges.items()):
                    problems.append(f"{oid}: lod {g['lod']} shell is not closed")
    for p in problems[:20]:
        print("problem:", p)
    print(f"{city_file}: {len(city['CityObjects'])} city objects, {n} vertices, "
          f"{'ok' if not problems else f'{len(problems)} problems'}")
    return 0 if not problems else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
