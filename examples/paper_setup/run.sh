#!/usr/bin/env bash
# The paper's experiment end to end, on simulated recordings of its set-up:
# simulate a three-level stepped-sine test, extract phasors, identify the
# support from acc1 and acc2, predict the held-out acc3 (the paper's Fig. 4,
# at every step), the measured and model backbones, the diagnosis, and one
# HTML report with the plots.
# Usage: bash examples/paper_setup/run.sh [OUTPUT_DIR] [BEAMID]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
out="${1:-$root/build/demo}"
beamid="${2:-$root/build/release/beamid}"
mkdir -p "$out"
step() { printf '\n== %s\n' "$*"; }

step "1. simulate the test (the paper's set-up, 3 force levels, 99 steps; ~10 s)"
rm -rf "$out/campaign"
"$beamid" simulate "$root/examples/scenarios/paper_base.json" -o "$out/campaign"

step "2. extract harmonic phasors of every step"
"$beamid" extract "$out/campaign" -H 5 -o "$out/phasors.json" --csv "$out/phasors.csv"

step "3. identify k1, k2, k3, c from acc1 and acc2; acc3 held out"
"$beamid" identify "$out/campaign" --fit acc1,acc2 --validate acc3 -o "$out/result.json"

step "4. predict acc3 (x = 0.57 m) at every step and compare (the paper's Fig. 4)"
"$beamid" predict "$out/result.json" --campaign "$out/campaign" --x 0.57 -o "$out/prediction_acc3.json"

step "5. measured backbone (model-free) with the identified model's backbone"
"$beamid" backbone --measured "$out/campaign" --channel acc3 --result "$out/result.json" -o "$out/backbone"
if command -v gnuplot >/dev/null; then
  # The paths as arguments, not pasted into gnuplot code (a quote in them would end the string).
  gnuplot -c "$root/scripts/plot_backbone.gp" "$out/backbone" "$out/backbone.png" && echo "plot: $out/backbone.png"
fi

report_input="$out/result.json"
if "$beamid" diagnose --help >/dev/null 2>&1; then
  step "6. diagnose: is anything left out of the model?"
  "$beamid" diagnose "$out/campaign" --fit acc1,acc2 --validate acc3 --result "$out/result.json" -o "$out/diagnosis.json"
  report_input="$out/diagnosis.json"
fi

step "7. the report"
screenshot=()
if command -v chromium >/dev/null; then screenshot=(--screenshot "$out/report.png"); fi
"$beamid" report "$report_input" --campaign "$out/campaign" -o "$out/report.html" "${screenshot[@]}"

printf '\nDone. Open %s in a browser.\n' "$out/report.html"
