#!/usr/bin/env bash
# The folders are the architecture, and their dependencies point one way:
#   hb (models, error types) ← signal (recordings → phasors) ← solver/,
#   and inside solver/: estimation ← diagnosis ← report ← workflow ← cli,
#   diagnosis ← live (a test followed while it runs) ← workflow,
#   backbone (model-free, on signal only) ← report ← workflow ← cli,
#   and workflow ← python (the Python module, beside cli).
# The workflows (the use cases) print nothing and know no command line: no
# CLI11 and no solver/cli/ in solver/workflow/.
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
forbid solver/estimation 'solver/(backbone|diagnosis|report|workflow|cli)/' "estimation builds on hb and signal only"
forbid solver/backbone 'solver/(estimation|diagnosis|report|workflow|cli)/' "the measured backbone is model-free"
forbid solver/diagnosis 'solver/(backbone|report|workflow|cli)/' "diagnosis builds on estimation"
forbid solver/live 'solver/(backbone|report|workflow|cli)/' "the live analysis builds on estimation and diagnosis"
forbid solver/report 'solver/(workflow|cli)/' "the report is a library the workflows and the cli use"
forbid solver/workflow 'solver/cli/|CLI/' "a workflow is called by the cli, never the other way"
forbid solver/estimation 'nlohmann/|fmt/|CLI/' "an estimation header is plain data" '*.h'
# The Python module (solver/python) stands beside the program, on the workflows.
for folder in hb signal solver/estimation solver/backbone solver/diagnosis solver/live solver/report solver/workflow solver/cli; do
  forbid "$folder" 'solver/python/|pybind11/' "the Python module uses the workflows, never the other way"
done
forbid solver/python 'solver/cli/|CLI/' "the Python module calls the workflows as the program does, not the program"
# A workflow prints nothing: what it tells goes to its RunObserver.
prints=$(grep -rnE 'fmt::print|std::(cout|cerr|clog)|(^|[^a-z_])(f?printf|f?puts|fwrite)\(' solver/workflow || true)
if [ -n "$prints" ]; then
  echo "solver/workflow must not print (tell the RunObserver, or return it in the outcome):"
  echo "$prints"
  violations=$((violations + 1))
fi
if [ "$violations" -eq 0 ]; then
  echo "1 passed, 0 failed"
else
  echo "0 passed, 1 failed"
  exit 1
fi
