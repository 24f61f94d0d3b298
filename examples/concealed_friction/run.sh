#!/usr/bin/env bash
# Concealed friction, end to end: simulate a campaign whose support holds a
# Jenkins friction element (the campaign states only the nominal beam),
# extract the phasors, identify the paper's polynomial support, then
# diagnose: locate the misfit, refit every candidate physics, name the cause.
# Usage: bash examples/concealed_friction/run.sh [OUT_DIR]   (from the repository root)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
beamid="$root/build/release/beamid"
out="${1:-$root/build/concealed_friction}"
[ -x "$beamid" ] || cmake --build "$root/build/release" --target beamid
rm -rf "$out"
mkdir -p "$out"
time "$beamid" simulate "$here/scenario.json" -o "$out/campaign"
time "$beamid" extract "$out/campaign" -o "$out/phasors.json"
# Exit code 5: fitted and written, but the polynomial misses the data beyond
# their noise, which is what this example is about.
time "$beamid" identify "$out/campaign" --phasors "$out/phasors.json" --fit acc1,acc2 --validate acc3 \
  -o "$out/result.json" || [ $? -eq 5 ]
time "$beamid" diagnose "$out/campaign" --phasors "$out/phasors.json" --fit acc1,acc2 --validate acc3 \
  -o "$out/diagnosis.json" --curves "$out/frc"
jq '{selected, verdict, truth: "jenkins_stiffness 50 N*m/rad, jenkins_slip_moment 0.15 N*m"}' "$out/diagnosis.json"
