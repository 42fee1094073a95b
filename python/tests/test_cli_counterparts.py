"""The Python counterparts of the program's options that issue 29 found missing (cli_parity.py): for the same
inputs Python's results equal the program's files, and units given to Python come back as the program
writes them."""
import json
import os
import subprocess
import sys

import numpy as np
import pytest

import indentmap as im
from conftest import run_cli


def test_read_units_convert_as_indent_does(cli, rough64, tmp_path):
    """read(unit=, height_unit=, length_unit=) is indent --unit --height-unit --length-unit: spacing in
    micrometres and heights in nanometres, solved in metres, give the program's history to the bit."""
    im.write(tmp_path / "s.npy", rough64, delta=0.5)  # no unit stated
    t = im.read(tmp_path / "s.npy", unit="um", height_unit="nm", length_unit="m")
    assert t.unit == "m" and t.delta == pytest.approx(0.5e-6, rel=1e-15)
    np.testing.assert_allclose(t.heights, rough64 * 1e-9, rtol=1e-15)
    run_cli(cli, "indent", tmp_path / "s.npy", "--unit", "um", "--height-unit", "nm", "--length-unit", "m",
            "--approach", "2e-9,4e-9", "--out", tmp_path / "out")
    ours = im.indent(t.heights, approaches=[2e-9, 4e-9], delta=t.delta)
    theirs = im.read_history(tmp_path / "out" / "history.csv")
    for name in ("approach", "load", "contact_patches", "area_ratio"):
        np.testing.assert_array_equal(ours[name], theirs[name], err_msg=name)
    with pytest.raises(ValueError, match="height_unit 'furlong': expected a length unit"):
        im.read(tmp_path / "s.npy", height_unit="furlong")
    with pytest.raises(im.FormatError):  # no unit to convert from
        im.read(tmp_path / "s.npy", length_unit="m")


@pytest.mark.parametrize("periodic", [False, True])
def test_units_are_run_json_units(cli, rough64, tmp_path, periodic):
    """Indentation(length_unit=, e_star_unit=).units is indent's run.json "units" block: loads in N for Pa
    and m, every column's unit."""
    im.write(tmp_path / "s.npy", rough64, delta=1e-6, unit="m")
    flags = ["--periodic", "--load", "1e-3"] if periodic else ["--approach", "1e-6"]
    run_cli(cli, "indent", tmp_path / "s.npy", "--e-star", "1e9", "--e-star-unit", "Pa", *flags, "--out",
            tmp_path / "out")
    with open(tmp_path / "out" / "run.json", encoding="utf-8") as f:
        recorded = json.load(f)["units"]
    run = im.Indentation(rough64, None if periodic else im.Cone(), control="load" if periodic else "displacement",
                         largest=1e-3, delta=1e-6, e_star=1e9, periodic=periodic, length_unit="m", e_star_unit="Pa")
    assert run.units == recorded
    assert run.units["load"] == "N" and run.units["columns"]["stiffness"] == "N / m"
    bare = im.Indentation(rough64, largest=1.0)
    assert bare.units["load"] == "E* δ²" and bare.units["length"] == "delta"


def test_distributions_are_the_programs_files(cli, rough64, tmp_path):
    im.write(tmp_path / "s.npy", rough64)
    run_cli(cli, "indent", tmp_path / "s.npy", "--approach", "1,2.5", "--distributions", "--out", tmp_path / "cli")
    im.indent(rough64, approaches=[1, 2.5], distributions=tmp_path / "py")
    names = sorted(name for name in os.listdir(tmp_path / "cli") if name.startswith("distributions_"))
    assert len(names) == 6 and sorted(os.listdir(tmp_path / "py")) == names
    for name in names:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    with pytest.raises(im.InvalidArgument, match="no step solved yet"):
        im.Indentation(rough64, largest=1.0).write_distributions(tmp_path / "none")


def test_plain_pk_is_the_programs(cli, rough64, tmp_path):
    """plain_pk=True is indent --plain-pk: the same history to the bit, with no coarse iterations."""
    im.write(tmp_path / "s.npy", rough64)
    run_cli(cli, "indent", tmp_path / "s.npy", "--approach", "1,2", "--plain-pk", "--out", tmp_path / "out")
    theirs = im.read_history(tmp_path / "out" / "history.csv")
    run = im.Indentation(rough64, largest=2.0, plain_pk=True)
    steps = [run.step(w) for w in (1.0, 2.0)]
    ours = run.history()
    for name in ("load", "iterations", "convolutions", "contact_patches"):
        np.testing.assert_array_equal(ours[name], theirs[name], err_msg=name)
    assert all(step["coarse_iterations"] == 0 for step in steps)
    cascaded = im.indent(rough64, approaches=[1.0, 2.0])
    assert not np.array_equal(cascaded["convolutions"], ours["convolutions"])
    np.testing.assert_allclose(cascaded["load"], ours["load"], rtol=1e-5)


def in_a_child(code, cwd):
    """Runs code in a fresh interpreter: FFTW's wisdom is the process's, and a measured plan's would reach the
    later estimated plans of this one (other last bits than the program's)."""
    result = subprocess.run([sys.executable, "-c", "import numpy as np, json, pytest, indentmap as im\n" + code],
                            cwd=cwd, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr


def test_measure_and_wisdom(tmp_path):
    """measure=True and wisdom=FILE plan with FFTW_MEASURE (the same answers to the tolerance); the wisdom file
    is written, then read by the next plan; a file that is not wisdom is refused, naming it."""
    in_a_child("""
s = im.generate(64, slope=0.1, seed=2)
estimated = im.indent(s, approaches=[1.5])
measured = im.indent(s, approaches=[1.5], measure=True)
np.testing.assert_allclose(measured["load"], estimated["load"], rtol=1e-5)
im.indent(s, approaches=[1.5], wisdom="wisdom")
assert open("wisdom").read().startswith("(fftw-")
again = im.indent(s, approaches=[1.5], wisdom="wisdom")
np.testing.assert_allclose(again["load"], estimated["load"], rtol=1e-5)
open("notes", "w").write("not wisdom\\n")
with pytest.raises(im.Error, match="notes"):
    im.indent(s, approaches=[1.5], wisdom="notes")
""", tmp_path)


SCENE = """[scene]
name = wisdom
[surfaces]
file = s.npy
[punch]
periodic = yes
[loading]
steps = 0.002:0.004:2
"""


def test_run_scene_wisdom(tmp_path):
    """run_scene(wisdom=FILE) is run --wisdom FILE: the file is written and the record says wisdom was
    used; without it (run --no-wisdom) none is."""
    np.save(tmp_path / "s.npy", np.random.default_rng(4).normal(scale=0.5, size=(64, 64)))
    (tmp_path / "s.ini").write_text(SCENE)
    in_a_child("""
im.run_scene("s.ini", quiet=True, out="a", wisdom="wisdom")
im.run_scene("s.ini", quiet=True, out="b")
assert open("wisdom").read().startswith("(fftw-")
assert json.load(open("a/run.json", encoding="utf-8"))["solver"]["fftw_wisdom"] is True
assert json.load(open("b/run.json", encoding="utf-8"))["solver"]["fftw_wisdom"] is False
open("notes", "w").write("not wisdom\\n")
with pytest.raises(im.Error, match="notes"):
    im.run_scene("s.ini", quiet=True, out="c", wisdom="notes")
""", tmp_path)


VIEW3D_SIZE = ["--width", "160", "--height", "96", "--samples", "1", "--mesh-side", "48"]


@pytest.mark.parametrize("options, keywords", [
    ([], {}),
    (["--punch", "sphere", "--radius", "20", "--linear", "--colormap", "viridis", "--azimuth", "60",
      "--exaggeration", "3", "--punch-mode", "opaque", "--x", "30", "--y", "20"],
     dict(punch=im.Sphere(20), log=False, colormap="viridis", azimuth=60, exaggeration=3, punch_mode="opaque",
          axis=(30, 20))),
    (["--punch", "none", "--ortho", "--elevation", "80", "--vmax", "0.05", "--distance", "3"],
     dict(punch=None, ortho=True, elevation=80, vmax=0.05, distance=3)),
])
def test_view3d_is_the_programs_image(cli, rough64, tmp_path, options, keywords):
    """view3d(...) has the pixels of render view3d --raw for the same heights, forces, displacement and options."""
    history, fields = im.indent(rough64, approaches=[2.0], fields=True)
    im.write(tmp_path / "s.npy", rough64)
    for name in ("force", "displacement"):
        np.save(tmp_path / f"{name}.npy", fields[0][name])
    run_cli(cli, "render", "view3d", tmp_path / "s.npy", "--force", tmp_path / "force.npy", "--displacement",
            tmp_path / "displacement.npy", "--raw", "--out", tmp_path / "v.png", *VIEW3D_SIZE, *options)
    ours = im.view3d(rough64, force=fields[0]["force"], displacement=fields[0]["displacement"], width=160,
                     height=96, samples=1, mesh_side=48, **keywords)
    theirs = im.Image.read(tmp_path / "v.png")
    assert ours.rgba.shape == (96, 160, 4)
    assert ours.rgba.tobytes() == theirs.rgba.tobytes()
    assert len(np.unique(ours.rgba.reshape(-1, 4), axis=0)) > 20  # a picture, not a blank


def test_view3d_draws_tension_as_the_program(cli, rough64, tmp_path):
    """Patches under tension on the tension ramp over 0 .. the largest tension, as render view3d --raw
    (they were drawn on a ramp over 0 .. 1: 29 pixels differed here)."""
    force = np.zeros_like(rough64)
    force[20:40, 20:40] = 0.01
    force[25:30, 25:30] = -0.02
    im.write(tmp_path / "s.npy", rough64)
    np.save(tmp_path / "force.npy", force)
    run_cli(cli, "render", "view3d", tmp_path / "s.npy", "--force", tmp_path / "force.npy", "--raw", "--out",
            tmp_path / "v.png", "--elevation", "80", *VIEW3D_SIZE)
    ours = im.view3d(rough64, force=force, elevation=80, width=160, height=96, samples=1, mesh_side=48)
    assert ours.rgba.tobytes() == im.Image.read(tmp_path / "v.png").rgba.tobytes()


def test_view3d_refuses_what_the_program_refuses(rough64):
    with pytest.raises(ValueError, match="punch_mode 'glass'"):
        im.view3d(rough64, punch_mode="glass")
    with pytest.raises(im.InvalidArgument, match="elevation"):
        im.view3d(rough64, elevation=0.0, width=32, height=32)
    with pytest.raises(ValueError, match="displacement: shape"):
        im.view3d(rough64, displacement=np.zeros((3, 3)))
