#!/usr/bin/env bash
# Concealed friction, end to end: simulate a campaign whose support holds a
# Jenkins friction element (the campaign states only the nominal beam),
# extract the phasors, identify the paper's polynomial support, then
# diagnose: locate the misfit, refit every candidate physics, name the cause;
# and the HTML report of the diagnosis.
# Usage: bash examples/concealed_friction/run.sh [OUTPUT_DIR] [BEAMID]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
out="${1:-$root/build/concealed_friction}"
beamid="${2:-$root/build/release/beamid}"
if [ $# -lt 2 ] && [ ! -x "$beamid" ]; then cmake --build "$root/build/release" --target beamid; fi
mkdir -p "$out"
step() { printf '\n== %s\n' "$*"; }

step "1. simulate the test (a Jenkins friction element hidden in the support; 3 levels, 39 steps)"
rm -rf "$out/campaign"
"$beamid" simulate "$here/scenario.json" -o "$out/campaign"

step "2. extract harmonic phasors of every step"
"$beamid" extract "$out/campaign" -o "$out/phasors.json"

step "3. identify the paper's polynomial support from acc1 and acc2; acc3 held out"
# Exit code 5: fitted and written, but the polynomial misses the data beyond
# their noise, which is what this example is about.
status=0
"$beamid" identify "$out/campaign" --phasors "$out/phasors.json" --fit acc1,acc2 --validate acc3 \
  -o "$out/result.json" || status=$?
if [ "$status" -ne 0 ] && [ "$status" -ne 5 ]; then exit "$status"; fi

step "4. diagnose: where the model misses, and which left-out physics explains it"
"$beamid" diagnose "$out/campaign" --phasors "$out/phasors.json" --fit acc1,acc2 --validate acc3 \
  --result "$out/result.json" -o "$out/diagnosis.json" --curves "$out/frc"

step "5. the report"
screenshot=()
if command -v chromium >/dev/null; then screenshot=(--screenshot "$out/report.png"); fi
"$beamid" report "$out/diagnosis.json" --campaign "$out/campaign" -o "$out/report.html" "${screenshot[@]}"

printf '\nDone. Open %s in a browser.\n' "$out/report.html"
