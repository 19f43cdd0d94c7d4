#!/usr/bin/env bash
# Command 2: builds (if needed) and runs the whole test suite with CTest.
#   scripts/test.sh             Release build in build/
#   scripts/test.sh --sanitize  AddressSanitizer + UndefinedBehaviorSanitizer build in build-asan/
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = "--sanitize" ]; then
  export ROCKBENCH_BUILD_DIR=build-asan
  # Mesa (OSMesa) keeps driver-global allocations until exit: not ours (tests/lsan.supp).
  export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0"
  scripts/build.sh -DROCKBENCH_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo -DROCKBENCH_BUILD_BENCH=OFF
else
  scripts/build.sh
fi
ctest --test-dir "${ROCKBENCH_BUILD_DIR:-build}" --output-on-failure -j2
