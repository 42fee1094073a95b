#!/usr/bin/env bash
# The fixture install_source (CMakeLists.txt): one copy of the source tree (its tracked and unignored files) for
# install_pip and install_wheel, which build in it one after the other. setup.py keeps its CMake build in the
# copy's build-pip/, so the first of them compiles the library and the second rebuilds nothing, as a second
# install does; both still run setup.py's configure, build and packaging (pip install ., python3 -m build).
#   source.sh SOURCE_DIR COPY_DIR
set -euo pipefail
. "$1/tests/install/scratch.sh"
copy_source "$1" "$2"
[ -f "$2/setup.py" ] || { echo "source.sh: no setup.py in the copy $2"; exit 1; }
