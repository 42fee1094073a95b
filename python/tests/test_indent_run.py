"""indent_run is the program's run (indent.h: im_indent_run): the same folder as `indentmap indent`."""
import json
import logging
import os

import numpy as np
import pytest

import indentmap as im
from conftest import run_cli

# What differs between two runs of the same options: timings, and what only the program records (its
# command line, in run.json's arguments, the figures' texts and the page that shows run.json).
TIMINGS = {"seconds", "plan_seconds"}
ONLY_THE_PROGRAMS = {"arguments"}


def history_without_seconds(path):
    rows = [line.split(",") for line in open(path, encoding="utf-8").read().splitlines()]
    i = rows[0].index("seconds")
    return [r[:i] + r[i + 1:] for r in rows]


def record_without(path, keys):
    def strip(x):
        if isinstance(x, dict):
            return {k: strip(v) for k, v in x.items() if k not in keys}
        return [strip(v) for v in x] if isinstance(x, list) else x
    return strip(json.load(open(path, encoding="utf-8")))


def assert_same_folder(cli_out, py_out):
    assert sorted(os.listdir(cli_out)) == sorted(os.listdir(py_out))
    for name in os.listdir(cli_out):
        a, b = os.path.join(cli_out, name), os.path.join(py_out, name)
        if name == "history.csv":
            assert history_without_seconds(a) == history_without_seconds(b)
        elif name == "run.json":
            assert record_without(a, TIMINGS | ONLY_THE_PROGRAMS) == record_without(b, TIMINGS | ONLY_THE_PROGRAMS)
        elif name.endswith((".npy", ".csv", ".npy.json")):
            assert open(a, "rb").read() == open(b, "rb").read(), name


def test_the_programs_folder_for_a_loading_cycle(cli, tmp_path):
    """A smooth cone loaded and unloaded with a hardness and fields: the same files, the same history,
    fields, indentation analysis and record; each step said to log and progress."""
    run_cli(cli, "indent", "--smooth", "--n", "64", "--approach", "1:4:3,3:0:3", "--hardness", "0.1", "--fields",
            "--out", tmp_path / "cli")
    lines, done = [], []
    out = im.indent_run(None, tmp_path / "py", im.Cone(80), approaches=np.r_[1:4:3j, 3:0:3j], n=64, hardness=0.1,
                        fields=True, log=lambda level, text: lines.append((level, text)),
                        progress=lambda stage, i, total: done.append((stage, i, total)))
    assert out == str(tmp_path / "py")
    assert_same_folder(tmp_path / "cli", tmp_path / "py")
    assert os.path.exists(tmp_path / "py" / "indentation.csv")
    assert json.load(open(tmp_path / "py" / "run.json", encoding="utf-8"))["arguments"] == []
    assert done == [("steps", i, 6) for i in range(1, 7)]
    steps = [text for level, text in lines if level == logging.INFO and text.startswith("step ")]
    assert len(steps) == 6 and steps[0].startswith("step 1: w = 1  N = ")


def test_the_programs_folder_for_a_periodic_file(cli, tmp_path):
    """A generated surface file as a periodic cell under mean pressures (the rigid flat): the k fit and
    the record as the program's."""
    run_cli(cli, "surface", "--n", "64", "--seed", "4", "--out", tmp_path / "cell.npy")
    run_cli(cli, "indent", tmp_path / "cell.npy", "--periodic", "--pressure", "0.01,0.03", "--out", tmp_path / "cli")
    im.indent_run(tmp_path / "cell.npy", tmp_path / "py", None, pressures=[0.01, 0.03], periodic=True,
                  log=lambda level, text: None)
    assert_same_folder(tmp_path / "cli", tmp_path / "py")
    assert "k_fit" in json.load(open(tmp_path / "py" / "run.json", encoding="utf-8"))


def test_the_programs_folder_for_a_file_read_and_prepared(cli, tmp_path):
    """A measured-like file read with the program's options (spacing and height units, missing points
    filled) and prepared (a block cropped, rows aligned, a plane removed): the same folder as the program's
    with --unit --height-unit --fill --crop --align --detrend."""
    rng = np.random.default_rng(7)
    heights = 20.0 * rng.standard_normal((56, 60)) + np.arange(60)[None, :] * 3.0 + np.arange(56)[:, None] * 2.0
    heights[10, 12] = heights[30, 41] = np.nan
    im.write(tmp_path / "scan.npy", heights, delta=0.25, unit="")
    run_cli(cli, "indent", tmp_path / "scan.npy", "--unit", "um", "--height-unit", "nm", "--fill", "--crop",
            "4,6,48,40", "--align", "median", "--detrend", "plane", "--approach", "0.3,0.6", "--out", tmp_path / "cli")
    im.indent_run(tmp_path / "scan.npy", tmp_path / "py", im.Cone(80), approaches=[0.3, 0.6], unit="um",
                  height_unit="nm", fill=True, region=(4, 6, 48, 40), align="median", detrend="plane",
                  log=lambda level, text: None)
    assert_same_folder(tmp_path / "cli", tmp_path / "py")
    surface = json.load(open(tmp_path / "py" / "run.json", encoding="utf-8"))["surface"]
    assert (surface["nx"], surface["ny"], surface["unit"]) == (48, 40, "µm")
    assert surface["preparation"] == "plane removed, cropped to 48 x 40 at (4, 6), rows aligned (median), " \
                                     "2 missing points filled"
    assert int(history_without_seconds(tmp_path / "py" / "history.csv")[2][4]) > 20  # contact patches


def test_the_programs_errors(tmp_path):
    """A file that cannot be read and a punch the program refuses raise with the program's messages."""
    with pytest.raises(im.Error, match="nothere.npy: cannot open"):
        im.indent_run(tmp_path / "nothere.npy", tmp_path / "out", approaches=[1.0], log=lambda level, text: None)
    with pytest.raises(im.Error, match="radius"):
        im.indent_run(None, tmp_path / "out", im.Sphere(-1.0), approaches=[1.0], n=16, log=lambda level, text: None)
    with pytest.raises(ValueError, match="give one of approaches"):
        im.indent_run(None, tmp_path / "out", approaches=[1.0], loads=[1.0])
    im.write(tmp_path / "flat.npy", np.zeros((16, 16)))
    for bad, message in ((dict(height_unit="inch"), "height_unit 'inch': expected a length unit"),
                         (dict(align="rows"), "align 'rows': expected"), (dict(detrend="cubic"), "detrend 'cubic'"),
                         (dict(npy_order="zx"), "npy_order 'zx'"), (dict(region=(0, 0, 8)), r"region \(0, 0, 8\)")):
        with pytest.raises(ValueError, match=message):
            im.indent_run(tmp_path / "flat.npy", tmp_path / "out", approaches=[1.0], log=lambda level, text: None,
                          **bad)
