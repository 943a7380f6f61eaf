#!/usr/bin/env bash
# Installs what fluidbed needs to build, test and make its pictures, from Debian's packages.
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
PACKAGES=(
  g++ cmake ninja-build pkg-config
  libtomlplusplus-dev   # scene files
  libcli11-dev          # command line
  nlohmann-json3-dev    # summary.json
  libeigen3-dev         # sparse solvers for the gas pressure correction
  libgtest-dev libgmock-dev libbenchmark-dev
  libstb-dev fonts-dejavu-core
)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
