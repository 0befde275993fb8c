#!/usr/bin/env bash
# Builds the libFuzzer targets (the fuzz preset: clang, with ASan and UBSan) and runs each
# for SECONDS on its seed corpus in fuzz/corpus, copied to build/fuzz/corpus so the run can
# add to it. A finding (crash-*, timeout-*, oom-*) lands in build/fuzz/findings/TARGET;
# rerun it with build/fuzz/fuzz/TARGET_fuzzer FILE.
#
#   bash scripts/fuzz.sh [SECONDS per target, default 300] [TARGET ...]
#   targets: sketch obj library real city grid grammar camera_path (default: all)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-300}
shift || true
targets=("$@")
((${#targets[@]})) || targets=(sketch obj library real city grid grammar camera_path)

bash scripts/install-deps.sh
if ! command -v clang++ >/dev/null; then
  sudo=()
  if [ "$(id -u)" -ne 0 ]; then sudo=(sudo); fi
  echo "exacity: installing clang for the fuzz build" >&2
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq clang >/dev/null
fi
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz

# CGAL's arrangement iterators fail UBSan's vptr check inside CGAL (see tests/ubsan.supp).
export UBSAN_OPTIONS="suppressions=$PWD/tests/ubsan.supp:print_stacktrace=1"
status=0
for t in "${targets[@]}"; do
  corpus=build/fuzz/corpus/$t findings=build/fuzz/findings/$t
  mkdir -p "$corpus" "$findings"
  cp -n fuzz/corpus/"$t"/* "$corpus"/
  if [ "$t" = sketch ]; then cp -n examples/*.geojson examples/shapes/*.geojson "$corpus"/; fi
  echo "exacity: fuzzing $t for $seconds s" >&2
  build/fuzz/fuzz/"$t"_fuzzer "$corpus" -max_total_time="$seconds" -timeout=120 -rss_limit_mb=8192 \
    -artifact_prefix="$findings"/ -print_final_stats=1 || status=1
done
exit $status
