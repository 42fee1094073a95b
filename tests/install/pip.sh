#!/usr/bin/env bash
# The one-command install: `pip install --no-build-isolation .` at the root of a copy of the source tree (its
# tracked and unignored files) builds the library and the Python package together into a fresh venv, with no
# library installed. The package must import from the venv, solve, read an HDF5 file (and an instrument's file
# where Gwyddion's reader is built) through the reading programs it ships, and draw a contact map.
#   pip.sh SOURCE_DIR PYTHON IM_GWYDDION(ON|OFF)
set -euo pipefail
source=$1 python=$2 gwyddion=$3
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
mkdir "$scratch/source"
git -C "$source" ls-files -z --cached --others --exclude-standard |
  tar -C "$source" --null --files-from=- --ignore-failed-read -cf - | tar -C "$scratch/source" -xf -
"$python" -m venv --system-site-packages "$scratch/venv"
start=$SECONDS
"$scratch/venv/bin/python" -m pip install --quiet --no-build-isolation --no-deps --no-index "$scratch/source"
echo "pip: installed in $((SECONDS - start)) s"
cd "$scratch"  # not the source tree: the package must be the venv's
env -u PYTHONPATH -u INDENTMAP_HDF5_READER -u INDENTMAP_GWYDDION_READER "$scratch/venv/bin/python" - \
  "$source" "$gwyddion" <<'PY'
import os, subprocess, sys
import indentmap as im
source, gwyddion = sys.argv[1], sys.argv[2] == "ON"
package = os.path.dirname(im._core.__file__)
assert package.startswith(sys.prefix + "/"), f"indentmap._core from {package}, not the venv {sys.prefix}"
assert "libindentmap" not in subprocess.run(["ldd", im._core.__file__], capture_output=True, text=True).stdout
for program in ["indentmap-hdf5-read"] + ["indentmap-gwyddion-read"] * gwyddion:
    assert os.access(os.path.join(package, program), os.X_OK), f"no {program} in {package}"
history, fields = im.indent(im.generate(32, slope=0.05, lambda_s=2), approaches=[1.0], fields=True)
assert history["contact_patches"][0] > 0
assert im.read(f"{source}/fuzz/corpus/hdf5/valid_4x3_double.h5").heights.size == 12
if gwyddion:
    assert im.read(f"{source}/tests/data/instruments/10x10-one_channel_without_name.ibw").heights.shape == (10, 10)
picture = im.contact_map(fields[-1]["force"])
assert picture.rgba.shape[2] == 4 and picture.rgba[..., :3].std() > 0, picture.rgba.shape
print("pip: indentmap", im.__version__, "from", package, "solved, read and drew")
PY
