# Shared by pip.sh and wheel.sh (sourced): the copy of the source tree they build in, a fresh venv in a scratch
# folder, and the check of the package installed there.

# copy_source SOURCE_DIR COPY_DIR: COPY_DIR made anew with the tree's tracked and unignored files.
copy_source() {
  rm -rf "$2" && mkdir -p "$2" || return 1
  git -C "$1" ls-files -z --cached --others --exclude-standard |
    tar -C "$1" --null --files-from=- --ignore-failed-read -cf - | tar -C "$2" -xf -
}

# scratch_setup PYTHON COPY_DIR: $copy, the copy of the source tree made by the fixture install_source
# (tests/install/source.sh), and $scratch/venv (with Debian's numpy: --system-site-packages), the scratch folder
# removed at exit.
scratch_setup() {
  copy=$2
  [ -f "$copy/setup.py" ] || { echo "no copy of the source tree in '$copy': expected tests/install/source.sh's"; exit 1; }
  scratch=$(mktemp -d)
  trap 'rm -rf "$scratch"' EXIT
  "$1" -m venv --system-site-packages "$scratch/venv"
}

# scratch_check SOURCE_DIR IM_GWYDDION: the venv's package, run from outside the source tree.
scratch_check() {
  (cd "$scratch" && env -u PYTHONPATH -u INDENTMAP_HDF5_READER -u INDENTMAP_GWYDDION_READER \
    "$scratch/venv/bin/python" "$1/tests/install/check_installed.py" "$1" "$2")
}
