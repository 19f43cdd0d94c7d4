#!/usr/bin/env bash
# Configures and builds rockbench in Release into build/ (or $ROCKBENCH_BUILD_DIR).
# Extra arguments go to CMake, e.g. -DROCKBENCH_SANITIZE=ON.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${ROCKBENCH_BUILD_DIR:-build}
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build_dir" -j"$(nproc)"
