#!/usr/bin/env bash
# Builds beamid and runs its whole test suite, then rebuilds with
# AddressSanitizer + UBSan and runs the fast tests under them, then runs
# every file reader under libFuzzer for a fixed number of inputs.
# Usage: bash scripts/test.sh            (what CI runs)
#        SKIP_SANITIZERS=1 SKIP_FUZZ=1 bash scripts/test.sh
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs=$(nproc)

bash scripts/configure.sh build/release -DCMAKE_BUILD_TYPE=Release
cmake --build build/release -j"$jobs"
ctest --test-dir build/release -j"$jobs" --output-on-failure --timeout 600

if [ "${SKIP_SANITIZERS:-0}" != "1" ]; then
  bash scripts/configure.sh build/sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBEAMID_SANITIZE=ON -DBUILD_BENCHMARKS=OFF
  # Only what `ctest -L fast` runs: the program and the fast tests.
  cmake --build build/sanitize -j"$jobs" --target beamid_fast_tests
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --test-dir build/sanitize -j"$jobs" -L fast --output-on-failure --timeout 600
fi

# Every reader of user files under libFuzzer (ASan + UBSan), a fixed number
# of inputs from a fixed seed, so that the run is repeatable; scripts/fuzz.sh
# without FUZZ_RUNS fuzzes for minutes per reader.
if [ "${SKIP_FUZZ:-0}" != "1" ]; then
  FUZZ_RUNS=5000 bash scripts/fuzz.sh
fi
