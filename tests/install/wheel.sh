#!/usr/bin/env bash
# The wheel: `python3 -m build --wheel --no-isolation` (Debian's python3-build) on a copy of the source tree
# (tests/install/source.sh) builds one wheel holding the library, the extension and the reading programs; pip
# installs it into a fresh venv without an index, and the package there passes pip.sh's check (tests/install/check_installed.py).
#   wheel.sh SOURCE_DIR PYTHON IM_GWYDDION(ON|OFF) COPY_DIR
set -euo pipefail
source=$1 python=$2 gwyddion=$3
. "$source/tests/install/scratch.sh"
scratch_setup "$python" "$4"
start=$SECONDS
"$python" -m build --wheel --no-isolation --outdir "$scratch/dist" "$copy" >"$scratch/build.log" 2>&1 ||
  { tail -n 40 "$scratch/build.log"; exit 1; }
wheels=("$scratch"/dist/indentmap-*.whl)
[ ${#wheels[@]} -eq 1 ] && [ -f "${wheels[0]}" ] || { echo "wheel: expected one wheel, got: ${wheels[*]}"; exit 1; }
echo "wheel: $(basename "${wheels[0]}"), $(du -k "${wheels[0]}" | cut -f1) KiB, built in $((SECONDS - start)) s"
start=$SECONDS
"$scratch/venv/bin/python" -m pip install --quiet --no-deps --no-index "${wheels[0]}"
echo "wheel: installed in $((SECONDS - start)) s"
scratch_check "$source" "$gwyddion"
