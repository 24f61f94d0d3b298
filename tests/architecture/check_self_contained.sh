#!/usr/bin/env bash
# A user who clones beamid has only the repository: no file of the product
# (code, tests, scripts, README, docs) may point to a path outside it.
# Usage: check_self_contained.sh SOURCE_DIR
set -euo pipefail
cd "${1:?usage: check_self_contained.sh SOURCE_DIR}"
# The pattern is spelt in pieces so that this file does not name such a path
# itself: a parent folder's "sh"+"ared" tree, or the workplace's "wo"+"rk" root.
parent='\.\./sh''ared'
workplace='/wo''rk/'
pattern="$parent|$workplace|sh""ared/(spec|seed)/"
# (.git is a file in a git worktree, pointing to the main clone.)
hits=$(grep -rnIE "$pattern" --exclude-dir=build --exclude-dir=.git --exclude=.git . || true)
if [ -n "$hits" ]; then
  echo "paths outside the repository:"
  echo "$hits"
  echo "0 passed, 1 failed"
  exit 1
fi
echo "1 passed, 0 failed"
