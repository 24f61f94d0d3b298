#!/usr/bin/env bash
# Benchmark: `beamid identify` on every example campaign of
# examples/scenarios/paper_*.json, most of which hide an effect the paper's
# polynomial support does not hold (friction, clamp compliance, masses,
# sensor faults, clock error, ...). For each it simulates the test, extracts
# the phasors and identifies from acc1 and acc2 with acc3 held out, and
# tabulates identify's exit code (0: within the noise; 5: fitted, written,
# but missing the data beyond their noise), wall time, reduced chi-square
# and verdict. It fails if identify ends any campaign without a result file
# or with another exit code.
# Usage: bash scripts/identify_concealed_effects.sh [OUTPUT_DIR] [BEAMID]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="${1:-$root/build/identify_concealed_effects}"
beamid="${2:-$root/build/release/beamid}"
if [ ! -x "$beamid" ]; then
  echo "no beamid program at $beamid: build it (cmake --build build/release --target beamid) or give its path" >&2
  exit 2
fi
mkdir -p "$out"
table="$out/identify_concealed_effects.md"
{
  echo "| campaign | identify exit | identify wall time [s] | reduced chi-square | verdict |"
  echo "|---|---|---|---|---|"
} >"$table"
failures=0
for scenario in "$root"/examples/scenarios/paper_*.json; do
  name="$(basename "$scenario" .json)"
  work="$out/$name"
  rm -rf "$work"
  mkdir -p "$work"
  echo "== $name" >&2
  "$beamid" --quiet simulate "$scenario" -o "$work/campaign"
  "$beamid" --quiet extract "$work/campaign" -o "$work/phasors.json"
  status=0
  start=$(date +%s.%N)
  "$beamid" identify "$work/campaign" --phasors "$work/phasors.json" --fit acc1,acc2 --validate acc3 \
    -o "$work/result.json" >"$work/identify.txt" 2>&1 || status=$?
  end=$(date +%s.%N)
  seconds=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }')
  chi=$(sed -n 's/^  reduced chi-square \([^ ]*\) .*/\1/p' "$work/identify.txt" | head -n 1)
  verdict=$(sed -n 's/^  verdict: //p' "$work/identify.txt" | head -n 1)
  if [ ! -s "$work/result.json" ] || { [ "$status" -ne 0 ] && [ "$status" -ne 5 ]; }; then
    verdict="NO RESULT (exit $status): $(tail -n 1 "$work/identify.txt")"
    failures=$((failures + 1))
  fi
  echo "| $name | $status | $seconds | ${chi:-} | ${verdict//|/\\|} |" >>"$table"
done
cat "$table"
echo "wrote $table" >&2
[ "$failures" -eq 0 ]
