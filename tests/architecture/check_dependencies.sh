#!/usr/bin/env bash
# The folders are the architecture: hb (models, error types) is the lowest
# library, signal (recordings → phasors) builds on hb, solver (fits,
# diagnosis, report, cli) on both. A header of a lower folder that includes a
# higher one would turn the dependencies around; this check fails on it.
# Usage: check_dependencies.sh SOURCE_DIR
set -euo pipefail
root=${1:?usage: check_dependencies.sh SOURCE_DIR}
cd "$root"
violations=0
check() {  # folder, forbidden include prefix
  local hits
  hits=$(grep -rn --include='*.h' --include='*.cc' "#include \"$2/" "$1" || true)
  if [ -n "$hits" ]; then
    echo "dependency against the intended direction ($1 must not include $2/):"
    echo "$hits"
    violations=$((violations + 1))
  fi
}
check hb signal
check hb solver
check signal solver
if [ "$violations" -eq 0 ]; then
  echo "1 passed, 0 failed"
else
  echo "0 passed, 1 failed"
  exit 1
fi
