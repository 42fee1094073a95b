"""im.info() and im.formats() are the program's `info` and `formats`, byte for byte: one library text
(info.h) behind both."""
import os
import subprocess

import pytest

import indentmap as im
from conftest import run_cli


def test_info_is_the_programs(cli):
    for backend in ("auto", "osmesa"):
        assert im.info(backend) == run_cli(cli, "info", "--backend", backend).stdout
    assert im.info().startswith(f"indentmap {im.__version__}\nfftw: fftw-3")
    with pytest.raises(im.InvalidArgument, match="render backend 'vulkan': expected auto, egl or osmesa"):
        im.info("vulkan")


def test_solver_memory_is_the_programs(cli):
    """im.solver_memory is `info --memory`'s estimate (solver.h: im_solver_memory_needed), line for line."""
    listed = run_cli(cli, "info", "--memory", 256).stdout
    for periodic, mode in ((False, "half-space"), (True, "periodic")):
        ours = im.solver_memory(256, periodic=periodic)
        assert not ours["gpu"] and ours["device"] == "cpu" and ours["device_bytes"] == 0
        assert f"  {mode:<10} cpu: host {ours['host_bytes'] / 2**30:.3g} GiB\n" in listed
    with pytest.raises(ValueError, match="device 'tpu'"):
        im.solver_memory(256, device="tpu")


def test_formats_are_the_programs(cli, monkeypatch):
    reader = os.environ.get("INDENTMAP_GWYDDION_READER") or os.path.join(os.path.dirname(cli),
                                                                          "indentmap-gwyddion-read")
    if os.path.exists(reader):  # one reader for both: each finds its own beside itself otherwise
        monkeypatch.setenv("INDENTMAP_GWYDDION_READER", reader)
    ours, theirs = im.formats(), run_cli(cli, "formats").stdout
    assert ours == theirs
    assert ours.startswith("indentmap's own readers:\n  .npy ") and "\n  .x3p " in ours


def test_formats_name_a_reader_that_fails(cli, monkeypatch):
    monkeypatch.setenv("INDENTMAP_GWYDDION_READER", "/bin/false")
    with pytest.raises(im.FileError, match="/bin/false --formats failed or listed no module"):
        im.formats()
    program = subprocess.run([cli, "formats"], capture_output=True, text=True)
    assert program.returncode == 1 and "/bin/false --formats failed" in program.stderr
