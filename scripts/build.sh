#!/usr/bin/env bash
# Configures and builds fluidbed (Release) in build/; pass extra CMake options as arguments.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${BUILD_DIR:-build}"
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" "$@" > /dev/null
ninja -C "$BUILD_DIR" -j "$(nproc)"
