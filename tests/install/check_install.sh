#!/usr/bin/env bash
# Installs the build tree into an empty prefix and uses only that prefix:
# the installed program answers --version and runs an installed example from
# a folder of its own; a project that knows nothing but the prefix finds the
# libraries with find_package(beamid), compiles against the installed
# headers, links and runs; nothing installed names the source or build tree.
# With PYTHON (the interpreter the module was built for; "none": no module)
# the prefix is a virtual environment that sees the system's packages
# (numpy), as docs/python.md installs it: its python imports beamid and
# traces a backbone, and so does PYTHON with only the prefix's
# site-packages on PYTHONPATH.
# Usage: check_install.sh BUILD_FOLDER SOURCE_FOLDER [PYTHON]
set -euo pipefail
build=$(cd "$1" && pwd)
source=$(cd "$2" && pwd)
python=${3:-none}
python_note=""
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix="$work/prefix"

if [ "$python" != none ]; then "$python" -m venv --without-pip --system-site-packages "$prefix"; fi
cmake --install "$build" --prefix "$prefix" >/dev/null
version=$(grep -m1 -o 'project(beamid VERSION [0-9.]*' "$source/CMakeLists.txt" | cut -d' ' -f3)
[ "$("$prefix/bin/beamid" --version)" = "beamid $version" ] || {
  echo "installed beamid --version gives '$("$prefix/bin/beamid" --version)', expected 'beamid $version'"; exit 1; }
for f in share/doc/beamid/README.md share/doc/beamid/LICENSE share/doc/beamid/formats.md \
         share/beamid/examples/paper_setup/model.json include/beamid/hb/scenario.h \
         include/beamid/solver/backbone/measured_backbone.h lib/cmake/beamid/beamidConfig.cmake; do
  [ -f "$prefix/$f" ] || { echo "not installed: $f"; exit 1; }
done
[ -x "$prefix/share/beamid/examples/paper_setup/run.sh" ] || { echo "examples/paper_setup/run.sh not executable"; exit 1; }
[ ! -e "$prefix/include/beamid/solver/cli" ] || { echo "the program's own headers were installed"; exit 1; }
[ ! -e "$prefix/include/beamid/solver/python" ] || { echo "the Python module's own headers were installed"; exit 1; }
if grep -rIl -e "$source" -e "$build" "$prefix" >/dev/null; then
  echo "installed files name the source or build tree:"; grep -rIl -e "$source" -e "$build" "$prefix"; exit 1
fi

# The installed program on an installed example, in a folder of its own.
mkdir "$work/run"
(cd "$work/run" && "$prefix/bin/beamid" frc "$prefix/share/beamid/examples/paper_setup/model.json" \
   --force-N 0.5 --from-hz 50 --to-hz 58 -o out/frc >/dev/null)
[ -s "$work/run/out/frc.json" ] || { echo "installed beamid frc wrote no out/frc.json"; ls -R "$work/run"; exit 1; }

# The Python package, from a folder of its own, with nothing of the build on the path.
if [ "$python" != none ]; then
  script='import beamid, sys; b = beamid.model_backbone(sys.argv[1], points=5); print(beamid.__version__, len(b["frequency_hz"]))'
  model="$prefix/share/beamid/examples/paper_setup/model.json"
  expected="$version 5"
  answer=$(cd "$work/run" && env -u PYTHONPATH "$prefix/bin/python" -c "$script" "$model")
  [ "$answer" = "$expected" ] || { echo "the environment's python printed '$answer', expected '$expected'"; exit 1; }
  site=$(ls -d "$prefix"/lib/python3*/site-packages)
  [ -f "$site/beamid/__init__.py" ] || { echo "not installed: the package beamid under $site"; exit 1; }
  answer=$(cd "$work/run" && PYTHONPATH="$site" "$python" -c "$script" "$model")
  [ "$answer" = "$expected" ] || { echo "$python with PYTHONPATH=$site printed '$answer', expected '$expected'"; exit 1; }
  python_note=", import beamid in the environment and on PYTHONPATH"
fi

# A project of its own, on the prefix alone.
mkdir "$work/consumer"
cat >"$work/consumer/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.22)
project(consumer LANGUAGES CXX)
set(CMAKE_CXX_STANDARD 20)
find_package(beamid 0.1 REQUIRED)
add_executable(consumer main.cc)
target_link_libraries(consumer PRIVATE beamid::solver)
CMAKE
cat >"$work/consumer/main.cc" <<'CPP'
#include <iostream>
#include "hb/scenario.h"
#include "hb/version.h"
int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const beamid::hb::Scenario scenario = beamid::hb::ReadScenario(argv[1]);
  std::cout << beamid::kVersion << " " << scenario.levels.size() << "\n";
}
CPP
cmake -S "$work/consumer" -B "$work/consumer/build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/consumer/build" >/dev/null
levels=$(grep -c '"label"' "$source/examples/scenarios/paper_base.json" || true)
answer=$("$work/consumer/build/consumer" "$prefix/share/beamid/examples/scenarios/paper_base.json")
[ "$answer" = "$version $levels" ] || { echo "the consumer printed '$answer', expected '$version $levels'"; exit 1; }
echo "installed into $prefix: beamid $version, an example run, a project built on find_package(beamid)$python_note"
