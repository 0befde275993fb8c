#!/usr/bin/env bash
# Quick start, step 1: install what is missing, build Exacity (Release) and generate the
# default example city into out/town, with its still, overview and minimap in out/town/render.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release
./build/release/cli/exacity generate examples/town.geojson -o out/town --render
echo "exacity: outputs are in $(pwd)/out/town (vector/*.geojson, map.svg, city.obj, city.glb, city.city.json, render/*.png, report.json)"
