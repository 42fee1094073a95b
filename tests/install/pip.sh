#!/usr/bin/env bash
# The one-command install: `pip install --no-build-isolation .` at the root of a copy of the source tree (its
# tracked and unignored files) builds the library and the Python package together into a fresh venv, with no
# library installed. The package must import from the venv, solve, read an HDF5 file (and an instrument's file
# where Gwyddion's reader is built) through the reading programs it ships, and draw a contact map.
#   pip.sh SOURCE_DIR PYTHON IM_GWYDDION(ON|OFF)
set -euo pipefail
source=$1 python=$2 gwyddion=$3
. "$source/tests/install/scratch.sh"
scratch_setup "$source" "$python"
start=$SECONDS
"$scratch/venv/bin/python" -m pip install --quiet --no-build-isolation --no-deps --no-index "$scratch/source"
echo "pip: installed in $((SECONDS - start)) s"
scratch_check "$source" "$gwyddion"
