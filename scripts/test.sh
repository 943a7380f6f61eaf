#!/usr/bin/env bash
# Builds fluidbed and runs every test: the Release build, then the unit and validation tests again
# under the address and undefined-behaviour sanitizers.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
# The extended runs (a quarter of an hour or more each: ctest --test-dir build -L extended) are
# left out here.
ctest --test-dir build --output-on-failure -j "$(nproc)" -LE extended
# The sanitizer build compiles only what its tests below run: no speed measurements (the
# benchmark kernels and the renderer's timer) and no long or extended test binaries.
BUILD_DIR=build-sanitize BUILD_TYPE=RelWithDebInfo scripts/build.sh -DFLUIDBED_SANITIZE=ON -DFLUIDBED_BENCHMARKS=OFF \
  -DFLUIDBED_LONG_TESTS=OFF
# The sanitizer run starts from the Release run's packed beds: the cache key is the scene, not
# the build, and both builds pack the same bits (the packed-*.state files of the two folders
# compared equal), so the sanitizers need not spend 2.5 minutes packing the paper's bed again
# before the tests that start from it (Packing.SettlesToThePeersBed still packs a bed under
# them). It also starts from the Release run's test times, so that ctest starts the longest
# tests first instead of leaving them for a tail on one core (a clean checkout has none).
mkdir -p build-sanitize/cache build-sanitize/Testing/Temporary
find build/cache -maxdepth 1 \( -name 'packed-*.state' -o -name 'umf-*.txt' \) \
  -exec cp {} build-sanitize/cache/ \;
cp build/Testing/Temporary/CTestCostData.txt build-sanitize/Testing/Temporary/
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build-sanitize --output-on-failure -j "$(nproc)" -LE long
# The engine/viewer pair under the thread sanitizer: only the engine and one small test binary
# (the engine thread, the snapshot hand-off, the command queue), in a folder of their own.
cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFLUIDBED_SANITIZE_THREAD=ON \
  -DFLUIDBED_BENCHMARKS=OFF > /dev/null
ninja -C build-tsan -j "$(nproc)" fluidbed_view_engine_tests
TSAN_OPTIONS="halt_on_error=1" build-tsan/tests/fluidbed_view_engine_tests
