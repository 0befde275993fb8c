#!/usr/bin/env bash
# Installs the Debian 12 packages that Exacity builds, runs and tests with; only the
# missing ones, so a second run costs nothing.
set -euo pipefail

packages=(
  g++ cmake ninja-build ccache pkg-config
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libopenmesh-dev libembree-dev libopenimageio-dev openimageio-tools libopenexr-dev libtbb-dev
  nlohmann-json3-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  python3 python3-shapely python3-jsonschema
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  exit 0
fi

sudo=()
if [ "$(id -u)" -ne 0 ]; then sudo=(sudo); fi
echo "exacity: installing ${missing[*]}" >&2
"${sudo[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq "${missing[@]}" >/dev/null
