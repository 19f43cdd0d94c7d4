#!/usr/bin/env bash
# Installs rockbench's build and test dependencies from Debian 12 packages (idempotent).
# The engines besides Bullet are optional to the build (a missing one is left out, and said so);
# the ones listed here are installed so that a set-up machine builds them all. clang-14,
# libclang-rt-14-dev (libFuzzer, ASan, UBSan) and llvm-14 (llvm-cov, llvm-profdata, the
# symbolizer) are for scripts/fuzz.sh and the test fuzz_short. python3 runs the Python example
# engine (examples/python_housner) and its tests. pybind11-dev and python3-dev build the Python
# module (python/, docs/python.md); numpy is its arrays, pandas its DataFrames, pytest its tests,
# nbclient, nbformat and ipykernel run the notebook (examples/notebooks), matplotlib draws it;
# the Python tests look for left-over workers with procps's pgrep. Then the external engines'
# own packages: Node.js (Debian's nodejs and npm, only where no `node` is installed: a newer Node from elsewhere is kept)
# and `npm ci` in engines/rapier (skipped while node_modules matches the lockfile).
set -euo pipefail
cd "$(dirname "$0")/.."
packages=(build-essential cmake pkg-config
  libeigen3-dev libcli11-dev libtomlplusplus-dev nlohmann-json3-dev
  libgtest-dev libbenchmark-dev libgsl-dev libopenmpi-dev openmpi-bin
  libbullet-dev
  libode-dev libmujoco-dev libdart-dev libsiconos-kernel-dev libbox2d-dev
  libosmesa6-dev libpng-dev libfreetype-dev fonts-dejavu-core ffmpeg
  gnuplot-nox chromium
  clang-14 libclang-rt-14-dev llvm-14
  python3 python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pandas python3-pytest
  python3-matplotlib python3-nbclient python3-nbformat python3-ipykernel procps)
command -v node >/dev/null 2>&1 || packages+=(nodejs npm)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "rockbench: all Debian packages present"
else
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  echo "rockbench: installing ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# Rapier (engines/rapier, an external engine): its npm packages, pinned by package-lock.json.
# The stamp is the lockfile's checksum as of the last successful `npm ci`.
lock=engines/rapier/package-lock.json
stamp=engines/rapier/node_modules/.rockbench-lock.sha256
if [ "$(cat "$stamp" 2>/dev/null)" = "$(sha256sum "$lock" | cut -d' ' -f1)" ]; then
  echo "rockbench: engines/rapier node_modules up to date"
else
  echo "rockbench: npm ci in engines/rapier"
  npm ci --prefix engines/rapier --no-audit --no-fund --loglevel=error
  sha256sum "$lock" | cut -d' ' -f1 > "$stamp"
fi
