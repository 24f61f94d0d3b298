#!/usr/bin/env bash
# The folders are the architecture, and their dependencies point one way:
#   hb (models, error types) ← signal (recordings → phasors) ← solver/,
#   and inside solver/: estimation ← diagnosis ← report ← cli,
#   backbone (model-free, on signal only) ← report ← cli.
# An include against that direction fails this check, and so does a JSON or
# presentation library in an estimation header: the fit's interface is plain
# data, the file formats live in their *_io files.
# Usage: check_dependencies.sh SOURCE_DIR
set -euo pipefail
root=${1:?usage: check_dependencies.sh SOURCE_DIR}
cd "$root"
violations=0
forbid() {  # folder, pattern of a forbidden include, reason; files = *.h and *.cc unless $4 says otherwise
  local hits
  hits=$(grep -rnE --include="${4:-*.[hc]*}" "#include [\"<]($2)" "$1" || true)
  if [ -n "$hits" ]; then
    echo "$1 must not include $2 ($3):"
    echo "$hits"
    violations=$((violations + 1))
  fi
}
forbid hb 'signal/|solver/' "hb is the lowest library"
forbid signal 'solver/' "signal builds on hb only"
forbid solver/estimation 'solver/(backbone|diagnosis|report|cli)/' "estimation builds on hb and signal only"
forbid solver/backbone 'solver/(estimation|diagnosis|report|cli)/' "the measured backbone is model-free"
forbid solver/diagnosis 'solver/(backbone|report|cli)/' "diagnosis builds on estimation"
forbid solver/report 'solver/cli/' "the report is a library the cli uses"
forbid solver/estimation 'nlohmann/|fmt/|CLI/' "an estimation header is plain data" '*.h'
if [ "$violations" -eq 0 ]; then
  echo "1 passed, 0 failed"
else
  echo "0 passed, 1 failed"
  exit 1
fi
