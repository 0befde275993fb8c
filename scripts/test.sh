#!/usr/bin/env bash
# Quick start, step 2: install what is missing, build the test configuration (assertions
# and CGAL's preconditions on, warnings as errors) and run the whole test suite; then every
# test labelled unit or e2e again under AddressSanitizer and UBSan (tests/CMakeLists.txt).
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-deps.sh
cmake --workflow --preset test
cmake --workflow --preset asan
