#!/usr/bin/env bash
# Fuzzes every reader of user files with libFuzzer under AddressSanitizer and
# UBSan: campaign.json, CSV recordings, universal files (UFF 58), .mat and
# HDF5 recordings, phasor tables, model files, scenarios, and the files beamid
# writes and reads back: phasors.json, result.json, diagnosis.json and
# batch.json (tests/fuzz/*_fuzzer.cc).
# Usage: bash scripts/fuzz.sh [SECONDS_PER_READER]   (default 600)
#        FUZZ_RUNS=N bash scripts/fuzz.sh            (N inputs per reader with a fixed seed: what CI runs)
# A finding stops the script with the reader's name and the input that
# crashed it (build/fuzz/findings/); executions per reader are printed.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh  # clang and libFuzzer (libclang-rt-14-dev) among them
seconds=${1:-600}
build=build/fuzz
CXX=clang++ bash scripts/configure.sh "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBEAMID_FUZZ=ON -DBUILD_TESTING=OFF
cmake --build "$build" -j"$(nproc)" >/dev/null
corpus="$build/corpus"
"$build/tests/fuzz/write_seeds" "$corpus"
mkdir -p "$corpus/model_file_fuzzer" "$corpus/scenario_fuzzer" "$build/findings"
cp examples/paper_setup/model.json "$corpus/model_file_fuzzer/"
cp examples/scenarios/*.json examples/concealed_friction/scenario.json "$corpus/scenario_fuzzer/" 2>/dev/null || true
# Files of a real 3-step run (simulate, extract, identify, diagnose), kept small.
for name in phasor_json_fuzzer result_json_fuzzer diagnosis_json_fuzzer; do
  mkdir -p "$corpus/$name"
  cp tests/fuzz/seeds/$name/* "$corpus/$name/"
done
export ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1
# The HDF5 library's own losses on damaged files (tests/fuzz/lsan_suppressions.txt).
export LSAN_OPTIONS="suppressions=$PWD/tests/fuzz/lsan_suppressions.txt"
passed=0
for fuzzer in "$build"/tests/fuzz/*_fuzzer; do
  name=$(basename "$fuzzer")
  if [ -n "${FUZZ_RUNS:-}" ]; then
    inputs=$FUZZ_RUNS
    # The .mat/HDF5 reader reads each input first in a child process of its own
    # (signal/array_file.h), about 0.1 s an input: a tenth as many inputs.
    if [ "$name" = array_file_fuzzer ]; then inputs=$(((FUZZ_RUNS + 9) / 10)); fi
    limit=(-runs="$inputs" -seed=1)
  else
    limit=(-max_total_time="$seconds")
  fi
  log="$build/$name.log"
  if ! "$fuzzer" "${limit[@]}" -max_len=65536 -timeout=10 -rss_limit_mb=2048 \
      -artifact_prefix="$build/findings/$name-" "$corpus/$name" >"$log" 2>&1; then
    echo "FINDING in $name (input in $build/findings/, log $log):"
    tail -40 "$log"
    echo "fuzz: $passed passed, 1 failed"
    exit 1
  fi
  runs=$(grep -o "Done [0-9]* runs" "$log" | tail -1 || true)
  echo "$name: ${runs:-done}, no finding"
  passed=$((passed + 1))
done
echo "fuzz: $passed passed, 0 failed"
