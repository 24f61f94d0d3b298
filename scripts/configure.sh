#!/usr/bin/env bash
# Configures a build folder. A new one gets Ninja, which compiles a test's
# file while the libraries it links are still being built and so keeps
# every core busy to the end (Make waits for each library first); a folder
# configured earlier keeps its own generator, which CMake cannot change.
# Usage: bash scripts/configure.sh BUILD_FOLDER [CMAKE_OPTION ...]
set -euo pipefail
cd "$(dirname "$0")/.."
folder=$1
shift
generator=()
if [ ! -f "$folder/CMakeCache.txt" ]; then generator=(-G Ninja); fi
cmake "${generator[@]}" -S . -B "$folder" "$@" >/dev/null
