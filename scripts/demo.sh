#!/usr/bin/env bash
# Builds beamid and runs its main job on the built-in example, the paper's
# set-up (examples/paper_setup): frequency response curves at three force
# levels and the backbone, with a plot. Outputs go to build/demo/.
# Usage: bash scripts/demo.sh
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/release -j"$(nproc)" --target beamid
out=build/demo
mkdir -p "$out"
model=examples/paper_setup/model.json
echo "== beamid on the paper's set-up ($model)"
build/release/beamid frc "$model" --force-N 1,2,4 --from-hz 50 --to-hz 58 -o "$out/frc"
build/release/beamid backbone "$model" --max-theta-rad 0.02 -o "$out/backbone"
if command -v gnuplot >/dev/null; then
  gnuplot -e "frc='$out/frc.csv'; bb='$out/backbone.csv'; channel='acc3'; out='$out/frc_acc3.png'" scripts/plot_frc.gp
  echo "plot: $out/frc_acc3.png"
fi
