#!/usr/bin/env bash
# Builds beamid and runs its main job on the built-in example, the paper's
# set-up (examples/paper_setup/run.sh): simulated three-level test, phasors,
# identification from acc1 and acc2, prediction of acc3, backbones, diagnosis
# and an HTML report. Outputs go to build/demo/ (or the folder given).
# Usage: bash scripts/demo.sh [OUTPUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/configure.sh build/release -DCMAKE_BUILD_TYPE=Release
cmake --build build/release -j"$(nproc)" --target beamid
bash examples/paper_setup/run.sh "${1:-build/demo}" build/release/beamid
