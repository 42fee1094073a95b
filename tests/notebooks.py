#!/usr/bin/python3
"""Executes every notebook under python/notebooks with Debian's jupyter-nbconvert (a cell that raises
fails it) and checks that each cell tagged 'expect-image' showed a PNG (image/png among its outputs).
   notebooks.py SOURCE_DIR     (PYTHONPATH must reach the built package)"""
import glob
import json
import os
import subprocess
import sys
import tempfile
import time

IMAGE_TAG = "expect-image"


def cells_missing_an_image(executed):
    """The indices of the cells tagged IMAGE_TAG that have no image/png output."""
    missing = []
    for index, cell in enumerate(executed["cells"]):
        if IMAGE_TAG not in cell.get("metadata", {}).get("tags", []):
            continue
        if not any("image/png" in output.get("data", {}) for output in cell.get("outputs", [])):
            missing.append(index)
    return missing


def tagged_cells(notebook):
    return sum(IMAGE_TAG in cell.get("metadata", {}).get("tags", []) for cell in notebook["cells"])


def execute(path, folder):
    """Runs the notebook into folder; returns the executed notebook, or None after printing why not."""
    result = subprocess.run(["jupyter-nbconvert", "--to", "notebook", "--execute", "--output-dir", folder, path],
                            capture_output=True, text=True)
    if result.returncode != 0:
        print(f"{path}: jupyter-nbconvert exit {result.returncode}\n{result.stderr[-4000:]}")
        return None
    with open(os.path.join(folder, os.path.basename(path))) as f:
        return json.load(f)


def check(path, folder):
    with open(path) as f:
        if tagged_cells(json.load(f)) == 0:
            print(f"{path}: no cell tagged '{IMAGE_TAG}': a notebook shows at least one picture")
            return False
    start = time.monotonic()
    executed = execute(path, folder)
    if executed is None:
        return False
    missing = cells_missing_an_image(executed)
    for index in missing:
        print(f"{path}: cell {index} is tagged '{IMAGE_TAG}' but showed no image/png")
    print(f"{os.path.basename(path)}: executed in {time.monotonic() - start:.1f} s")
    return not missing


def main():
    notebooks = sorted(glob.glob(os.path.join(sys.argv[1], "python", "notebooks", "*.ipynb")))
    if not notebooks:
        sys.exit(f"no notebooks under {sys.argv[1]}/python/notebooks")
    with tempfile.TemporaryDirectory() as folder:
        results = [check(path, folder) for path in notebooks]
    sys.exit(0 if all(results) else 1)


if __name__ == "__main__":
    main()
