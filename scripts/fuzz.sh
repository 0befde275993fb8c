#!/usr/bin/env bash
# The fuzz campaign (docs/limits.md, Fuzzing): builds the libFuzzer targets (the fuzz
# preset: clang, ASan and UBSan) and runs each in turn for SECONDS on its seed corpus,
# one process at a time at low priority. The bar is the project's: any input ends in a
# result or one UserError within a minute and 1 GB, so libFuzzer reports as findings
#   crash-*    a crash, a sanitizer report, or an error that is not a UserError (exit 3)
#   timeout-*  one input running past a minute (a hang)
#   oom-*      the process past 1 GB of resident memory, or one allocation past it
# (slow-unit-* are inputs past 10 s: worth a look with the release build, not findings.)
# Findings land in build/fuzz/findings/TARGET; the log of each run, with its figures
# (executions, corpus size), in build/fuzz/logs/TARGET.log. The corpus grows in
# build/fuzz/corpus/TARGET (fuzz/corpus/TARGET, the committed seeds, is only read).
#
#   bash scripts/fuzz.sh [SECONDS per target, default 300] [TARGET ...]
#   targets: sketch grid grammar osm ogr library obj camera_path real city (default: all)
#
# A finding is replayed with build/fuzz/fuzz/TARGET_fuzzer FILE, minimised with
#   build/fuzz/fuzz/TARGET_fuzzer -minimize_crash=1 -max_total_time=120 FILE
# and, once fixed, added to fuzz/corpus/TARGET under a name that says what it is: the
# test build replays every file there (ctest -R fuzz_corpus), so CI keeps it fixed.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-300}
shift || true
targets=("$@")
((${#targets[@]})) || targets=(sketch grid grammar osm ogr library obj camera_path real city)

bash scripts/install-deps.sh  # clang among them
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz

# The longest input each format's mutations may make: room for a small sketch, extract or
# library, short enough that every execution stays fast. city reads a few hundred bytes
# as choices, not text.
declare -A max_len=([sketch]=16384 [grid]=4096 [grammar]=4096 [osm]=16384 [ogr]=8192 [library]=4096
  [obj]=8192 [camera_path]=2048 [real]=16384 [city]=512)
# Seconds one input may take: the bar's minute. The sanitizers make a run two to three
# times slower than the release build, and on a shared machine a reader's input that
# takes a quarter second of CPU can take 20 s of wall time, so a tighter limit would
# report the machine's load, not a hang.
timeout=60

# CGAL's arrangement iterators fail UBSan's vptr check inside CGAL (see tests/ubsan.supp).
export UBSAN_OPTIONS="suppressions=$PWD/tests/ubsan.supp:print_stacktrace=1:halt_on_error=1"
# A small quarantine keeps the resident memory libFuzzer measures close to the program's own.
export ASAN_OPTIONS="quarantine_size_mb=16:detect_leaks=0"
status=0
for t in "${targets[@]}"; do
  [ -f "fuzz/${t}_fuzzer.cpp" ] || { echo "exacity: no fuzz target $t" >&2; exit 2; }
  corpus=build/fuzz/corpus/$t findings=build/fuzz/findings/$t log=build/fuzz/logs/$t.log
  mkdir -p "$corpus" "$findings" build/fuzz/logs
  cp -n fuzz/corpus/"$t"/* "$corpus"/
  if [ "$t" = sketch ]; then cp -n examples/*.geojson examples/shapes/*.geojson "$corpus"/; fi
  echo "exacity: fuzzing $t for $seconds s (log: $log, findings: $findings)" >&2
  nice -n 10 build/fuzz/fuzz/"$t"_fuzzer "$corpus" \
    -max_total_time="$seconds" -timeout="$timeout" -rss_limit_mb=1024 -max_len="${max_len[$t]}" \
    -artifact_prefix="$findings"/ -print_final_stats=1 >"$log" 2>&1 || status=1
  grep -E '^stat::(number_of_executed_units|peak_rss_mb)|^(==[0-9]+== )?(ERROR|SUMMARY)|Test unit written' "$log" >&2 || true
  echo "exacity: $t corpus $(ls "$corpus" | wc -l) files, findings $(ls "$findings" | wc -l)" >&2
done
exit $status
