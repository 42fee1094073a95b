"""Indentation.window_for and the plans' memory() (solver.h: im_indentation_window_for,
im_solver_plan_memory) against the program and the engine: the window `indent` states and records for the
same surface and punch, and the bytes the GPU engine itself refuses a plan for, at the estimate's edge."""
import json

import numpy as np
import pytest

import indentmap as im
from conftest import run_cli

CASES = [  # (punch, its indent options, control, targets): a cone, a sphere under load, a flat punch
    (im.Cone(80), [], "displacement", "1,2.5"),
    (im.Sphere(60), ["--punch", "sphere", "--radius", "60"], "load", "20,80"),
    (im.Flat(14), ["--punch", "flat", "--radius", "14"], "displacement", "0.5"),
]


@pytest.fixture(scope="module")
def rough128():
    return im.generate(128, slope=0.08, seed=3)


@pytest.mark.parametrize("punch, flags, control, targets", CASES)
def test_window_for_is_indents(cli, rough128, tmp_path, punch, flags, control, targets):
    """The window found before any plan is the one `indent` solves on for the same surface and punch (run.json's
    "window"), smaller than the grid, and the one the Indentation then made has."""
    im.write(tmp_path / "s.npy", rough128)
    run_cli(cli, "indent", tmp_path / "s.npy", *flags, f"--{'load' if control == 'load' else 'approach'}", targets,
            "--no-wisdom", "--out", tmp_path / "out")
    window = json.loads((tmp_path / "out" / "run.json").read_text(encoding="utf-8"))["window"]
    largest = max(float(t) for t in targets.split(","))
    ours = im.Indentation.window_for(rough128, punch, control=control, largest=largest)
    assert ours == (window["x0"], window["y0"], window["nx"], window["ny"])
    assert ours[2] < 128 and ours[3] < 128
    assert im.Indentation(rough128, punch, control=control, largest=largest).window == ours


def test_window_for_takes_indentations_options_and_errors(rough128):
    """The options change the window as they change the run's (crop=False: the whole grid; a margin widens it),
    units change nothing, and bad arguments raise what Indentation raises."""
    assert im.Indentation.window_for(rough128, largest=2.0, crop=False) == (0, 0, 128, 128)
    narrow = im.Indentation.window_for(rough128, largest=2.0, length_unit="m", e_star_unit="Pa")
    wide = im.Indentation.window_for(rough128, largest=2.0, window_margin=12)
    assert wide[2] > narrow[2] and wide[3] > narrow[3]
    with pytest.raises(TypeError, match="unexpected keyword argument 'bogus'"):
        im.Indentation.window_for(rough128, largest=2.0, bogus=1)
    for bad in (dict(largest=-1.0), dict(largest=2.0, axis=(500, 3))):
        with pytest.raises(Exception) as theirs:
            im.Indentation(rough128, **bad)
        with pytest.raises(type(theirs.value), match=str(theirs.value)[:40].replace("(", r"\(").replace(")", r"\)")):
            im.Indentation.window_for(rough128, **bad)


def test_plan_memory_is_the_plans_grid_on_the_cpu(rough128):
    """On the CPU a run's plan is its window's: memory() is solver_memory() of the window's sides, less than
    the whole grid's; a Plan's is solver_memory() of its own sides."""
    run = im.Indentation(rough128, largest=2.0)
    _, _, nx, ny = run.window
    assert run.memory() == im.solver_memory(nx, ny)
    assert run.memory()["host_bytes"] < im.solver_memory(128)["host_bytes"]
    assert im.Plan(96, 48).memory() == im.solver_memory(96, 48)


def test_plan_memory_is_what_the_gpu_engine_refuses_at(rough128, monkeypatch):
    """A capped adhesive run on the GPU solves the repulsive problem on its window without cascade: memory()'s
    device bytes are those the engine counts for that plan, so a device that may fill exactly that many holds
    it and one a byte smaller refuses it (OutOfMemory); the run's own options on its window would need more."""
    options = dict(largest=2.0, hardness=0.5, adhesion_work=0.05, adhesion_range=0.6, device="gpu")
    try:
        run = im.Indentation(rough128, **options)
    except im.Unsupported as e:
        pytest.skip(f"no GPU engine or device: {e}")
    ours = run.memory()
    _, _, nx, ny = run.window
    assert ours["gpu"] and ours["device"] != "cpu" and nx < 128 and ny < 128
    assert ours["device_bytes"] < im.solver_memory(nx, ny, device="gpu")["device_bytes"]
    assert im.Plan(64, device="gpu").memory() == im.solver_memory(64, device="gpu")
    monkeypatch.setenv("INDENTMAP_GPU_MAX_MEMORY", str(int(ours["device_bytes"])))
    assert im.Indentation(rough128, **options).memory() == dict(ours, device_memory=ours["device_bytes"])
    monkeypatch.setenv("INDENTMAP_GPU_MAX_MEMORY", str(int(ours["device_bytes"]) - 1))
    with pytest.raises(im.OutOfMemory, match=f"solver grid {nx} x {ny} needs"):
        im.Indentation(rough128, **options)
