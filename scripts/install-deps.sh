#!/usr/bin/env bash
# Installs the Debian 12 packages that Exacity builds, runs and tests with, the npm
# validators and browser driver the tests run (tests/js), and the libraries exacity serve's
# page loads (web/), each pinned by its package-lock.json; only what is missing, so a second
# run costs nothing.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  g++ cmake ninja-build ccache pkg-config
  clang  # the fuzz preset and libFuzzer (scripts/fuzz.sh); its FuzzedDataProvider.h for the corpus replay
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libopenmesh-dev libembree-dev libopenimageio-dev libpng-dev openimageio-tools libopenexr-dev libtbb-dev
  nlohmann-json3-dev libcli11-dev libtinygltf-dev libcpp-httplib-dev
  libgtest-dev libgmock-dev libbenchmark-dev libgoogle-perftools-dev libgeos-dev
  libgdal-dev libproj-dev libosmium2-dev libexpat1-dev libbz2-dev zlib1g-dev
  python3 python3-shapely chromium osmium-tool
  slurm-wlm ffmpeg
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# Node.js with npm, from Debian unless the machine has it already.
command -v npm >/dev/null || missing+=(nodejs npm)

if ((${#missing[@]} > 0)); then
  sudo=()
  if [ "$(id -u)" -ne 0 ]; then sudo=(sudo); fi
  echo "exacity: installing ${missing[*]}" >&2
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq "${missing[@]}" >/dev/null
fi

# The glTF and CityJSON validators and puppeteer-core (which drives Debian's chromium, so
# it downloads no browser) for the tests, and OpenLayers and three.js for exacity serve's
# page, at the versions each package-lock.json names.
for folder in tests/js web; do
  if ! cmp -s $folder/package-lock.json $folder/node_modules/.installed-lock.json 2>/dev/null; then
    echo "exacity: installing $folder's npm packages (npm ci)" >&2
    PUPPETEER_SKIP_DOWNLOAD=1 npm ci --prefix $folder --no-audit --no-fund --loglevel=error >/dev/null
    cp $folder/package-lock.json $folder/node_modules/.installed-lock.json
  fi
done
