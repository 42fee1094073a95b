#!/usr/bin/env bash
# The one-command install: `pip install --no-build-isolation .` at the root of a copy of the source tree (its
# tracked and unignored files; tests/install/source.sh) builds the library and the Python package together into a
# fresh venv, with no library installed. The package must import from the venv, solve, read an HDF5 file (and an
# instrument's file where Gwyddion's reader is built) through the reading programs it ships, and draw a contact map.
#   pip.sh SOURCE_DIR PYTHON IM_GWYDDION(ON|OFF) COPY_DIR
set -euo pipefail
source=$1 python=$2 gwyddion=$3
. "$source/tests/install/scratch.sh"
scratch_setup "$python" "$4"
start=$SECONDS
"$scratch/venv/bin/python" -m pip install --quiet --no-build-isolation --no-deps --no-index --no-cache-dir "$copy"
echo "pip: installed in $((SECONDS - start)) s"
scratch_check "$source" "$gwyddion"
