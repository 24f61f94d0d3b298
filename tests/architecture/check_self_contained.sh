#!/usr/bin/env bash
# A user who clones beamid has only the repository: no file of the product
# (code, tests, scripts, README, docs) may point to a path outside it.
# Usage: check_self_contained.sh SOURCE_DIR
set -euo pipefail
cd "${1:?usage: check_self_contained.sh SOURCE_DIR}"
pattern='\.\./shared|/work/|shared/spec/|shared/seed/'
hits=$(grep -rnIE "$pattern" --exclude-dir=build --exclude-dir=.git --exclude=check_self_contained.sh . || true)
if [ -n "$hits" ]; then
  echo "paths outside the repository:"
  echo "$hits"
  echo "0 passed, 1 failed"
  exit 1
fi
echo "1 passed, 0 failed"
