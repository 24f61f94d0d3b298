#!/usr/bin/env bash
# Runs the global-search tests once with each BLAS Debian offers to Ipopt's
# MUMPS: the reference BLAS and OpenBLAS (pthread build). The best fit must
# not depend on which one computes it (floating-point paths differ at the
# last bit). Each run selects its BLAS with LD_LIBRARY_PATH, so the system's
# own choice (update-alternatives libblas.so.3) is left as it was: installing
# OpenBLAS would make it Debian's default, and this script restores the
# earlier selection afterwards.
# Usage: bash scripts/check-blas.sh   (after scripts/test.sh has built build/release)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
arch=$(dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || echo x86_64-linux-gnu)
blas_alternative="libblas.so.3-${arch}"
lapack_alternative="liblapack.so.3-${arch}"
previous_blas=$(update-alternatives --query "$blas_alternative" | sed -n 's/^Value: //p')
previous_lapack=$(update-alternatives --query "$lapack_alternative" | sed -n 's/^Value: //p')
if ! dpkg-query -W -f='${Status}' libopenblas0-pthread 2>/dev/null | grep -q "install ok installed"; then
  echo "beamid: installing libopenblas0-pthread to compare BLAS libraries" >&2
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends libopenblas0-pthread
  "${sudo_cmd[@]}" update-alternatives --set "$blas_alternative" "$previous_blas" >/dev/null
  "${sudo_cmd[@]}" update-alternatives --set "$lapack_alternative" "$previous_lapack" >/dev/null
fi
test_binary=build/release/tests/solver_identify_slow_test
[ -x "$test_binary" ] || { echo "beamid: $test_binary is missing: run bash scripts/test.sh first" >&2; exit 2; }
status=0
for dir in "/usr/lib/${arch}/blas" "/usr/lib/${arch}/openblas-pthread"; do
  loaded=$(LD_LIBRARY_PATH="$dir" ldd "$test_binary" | awk '/libblas.so.3/ {print $3}')
  echo "== BLAS: $loaded"
  LD_LIBRARY_PATH="$dir" "$test_binary" --gtest_filter='*FarStarts*:*BranchRepair*' | grep -E "starts reached|old search|PASSED|FAILED" || status=1
done
exit $status
