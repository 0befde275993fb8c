#!/usr/bin/env bash
# Quick start, step 2: install what is missing, build the test configuration (assertions
# and CGAL's preconditions on, warnings as errors) and run the whole test suite; then the
# unit suites and three end-to-end tests again under AddressSanitizer and UBSan.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-deps.sh
cmake --workflow --preset test
cmake --workflow --preset asan
