"""Run by a venv's python outside the source tree (tests/install/pip.sh, wheel.sh): the installed package
imports from the venv (its extension not linked with libindentmap.so, the reading programs beside it), solves,
reads an HDF5 file (and an instrument's file where Gwyddion's reader is built) and draws a contact map.
   check_installed.py SOURCE_DIR IM_GWYDDION(ON|OFF)"""
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
print("installed: indentmap", im.__version__, "from", package, "solved, read and drew")
