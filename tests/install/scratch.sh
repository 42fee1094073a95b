# Shared by pip.sh and wheel.sh (sourced): a copy of the source tree and a fresh venv in a scratch folder, and
# the check of the package installed there.

# scratch_setup SOURCE_DIR PYTHON: $scratch/source (the tree's tracked and unignored files), $scratch/venv (with
# Debian's numpy: --system-site-packages), the folder removed at exit.
scratch_setup() {
  scratch=$(mktemp -d)
  trap 'rm -rf "$scratch"' EXIT
  mkdir "$scratch/source"
  git -C "$1" ls-files -z --cached --others --exclude-standard |
    tar -C "$1" --null --files-from=- --ignore-failed-read -cf - | tar -C "$scratch/source" -xf -
  "$2" -m venv --system-site-packages "$scratch/venv"
}

# scratch_check SOURCE_DIR IM_GWYDDION: the venv's package, run from outside the source tree.
scratch_check() {
  (cd "$scratch" && env -u PYTHONPATH -u INDENTMAP_HDF5_READER -u INDENTMAP_GWYDDION_READER \
    "$scratch/venv/bin/python" "$1/tests/install/check_installed.py" "$1" "$2")
}
