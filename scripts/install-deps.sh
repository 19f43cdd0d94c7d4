#!/usr/bin/env bash
# Installs rockbench's build and test dependencies from Debian 12 packages (idempotent).
# The engines besides Bullet are optional to the build (a missing one is left out, and said so);
# the ones listed here are installed so that a set-up machine builds them all. clang-14,
# libclang-rt-14-dev (libFuzzer, ASan, UBSan) and llvm-14 (llvm-cov, llvm-profdata, the
# symbolizer) are for scripts/fuzz.sh and the test fuzz_short.
set -euo pipefail
packages=(build-essential cmake pkg-config
  libeigen3-dev libcli11-dev libtomlplusplus-dev nlohmann-json3-dev
  libgtest-dev libbenchmark-dev libgsl-dev libopenmpi-dev openmpi-bin
  libbullet-dev
  libode-dev libmujoco-dev libdart-dev libsiconos-kernel-dev libbox2d-dev
  libosmesa6-dev libpng-dev libfreetype-dev fonts-dejavu-core ffmpeg
  gnuplot-nox chromium
  clang-14 libclang-rt-14-dev llvm-14)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "rockbench: all Debian packages present"
  exit 0
fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "rockbench: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
