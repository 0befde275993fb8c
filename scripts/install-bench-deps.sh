#!/usr/bin/env bash
# Installs what the Cycles comparison (benchmarks/cycles/) needs beyond
# scripts/install-deps.sh: Debian's blender (Cycles, and its glTF importer). Not run by CI,
# which the comparison is not part of; only what is missing, so a second run costs nothing.
set -euo pipefail

packages=(blender)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} > 0)); then
  sudo=()
  if [ "$(id -u)" -ne 0 ]; then sudo=(sudo); fi
  echo "exacity: installing ${missing[*]}" >&2
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
