#!/usr/bin/env bash
# Installs the Debian packages beamid needs, only those that are missing
# (idempotent: a second run installs nothing and needs no network).
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libfftw3-dev coinor-libipopt-dev libgtest-dev libbenchmark-dev
  nlohmann-json3-dev libcli11-dev libfmt-dev gnuplot-nox librsvg2-bin zlib1g-dev libssl-dev
  libmatio-dev libhdf5-dev
  chromium
  slurm-wlm munge
  clang libclang-rt-14-dev
  python3-dev pybind11-dev python3-numpy python3-pandas python3-matplotlib
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "beamid: installing missing Debian packages: ${missing[*]}" >&2
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
