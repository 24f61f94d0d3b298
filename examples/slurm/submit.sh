#!/usr/bin/env bash
# Submits the identification of many campaigns to Slurm: a job array with one
# task per campaign (beamid_array.sbatch), then the summary once every task
# has ended (beamid_collect.sbatch). Prints the two job ids.
#
# Usage: bash examples/slurm/submit.sh CAMPAIGN_LIST OUTPUT [beamid batch options...]
#   CAMPAIGN_LIST  a text file, one campaign folder per line (e.g. ls -d specimens/* > campaigns.txt)
#   OUTPUT         the results' folder, shared by the nodes
#   options        as `beamid batch` takes them: --fit acc1,acc2 --validate acc3 ...
# Environment: BEAMID (the program, else beamid on PATH); SBATCH_ARGS (more sbatch
# options for both jobs, e.g. "--partition=short --time=00:30:00"), split on spaces.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
list=$1
output=$2
shift 2
tasks=$(grep -c . "$list" || true)
if [ "$tasks" -eq 0 ]; then echo "submit.sh: $list names no campaign" >&2; exit 2; fi
mkdir -p "$output"
read -r -a extra <<< "${SBATCH_ARGS:-}"
array=$(sbatch --parsable "${extra[@]}" --array=0-$((tasks - 1)) --chdir="$output" \
  "$here/beamid_array.sbatch" "$(realpath "$list")" "$(realpath "$output")" "$@")
collect=$(sbatch --parsable "${extra[@]}" --dependency=afterany:"${array%%;*}" --chdir="$output" \
  "$here/beamid_collect.sbatch" "$(realpath "$output")")
echo "array job $array ($tasks campaigns), summary job $collect: $output/summary.csv when it ends"
