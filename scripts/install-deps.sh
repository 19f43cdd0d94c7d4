#!/usr/bin/env bash
# Installs rockbench's build and test dependencies from Debian 12 packages (idempotent).
# The engines besides Bullet are optional to the build (a missing one is left out, and said so);
# the ones listed here are installed so that a set-up machine builds them all.
set -euo pipefail
packages=(build-essential cmake pkg-config
  libeigen3-dev libcli11-dev libtomlplusplus-dev nlohmann-json3-dev
  libgtest-dev libbenchmark-dev libgsl-dev libopenmpi-dev openmpi-bin
  libbullet-dev
  libode-dev libmujoco-dev libdart-dev libsiconos-kernel-dev
  libosmesa6-dev libpng-dev libfreetype-dev fonts-dejavu-core ffmpeg
  gnuplot-nox chromium)
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
