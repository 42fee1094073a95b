"""check_scene: the program's `run --check` (docs/scenes.md, "Checking a scene"): the same report but for the
machine's free memory and disk, which change between two calls; the run's errors; nothing written."""
import os
import subprocess

import pytest

import indentmap as im

SCENE = """[scene]
name = checked
output = out
[surfaces]
n = 32
slopes = 0, 0.08
seeds = 1:2
[punch]
shape = cone
alpha = 80
[loading]
control = load
load_star = 100
steps = 20:100:3
[output]
table = yes
plots = fig5
"""


def steady(report):
    """The report without the lines that state the machine's free memory and disk at that moment."""
    return [line for line in report.splitlines() if not line.startswith(("  memory:", "  disk:", "  address space:"))]


def test_check_scene_is_the_programs(cli, tmp_path):
    (tmp_path / "checked.ini").write_text(SCENE)
    report = im.check_scene(str(tmp_path / "checked.ini"))
    env = dict(os.environ, IM_FFTW_WISDOM="")  # Python's wisdom=None: none
    program = subprocess.run([cli, "run", str(tmp_path / "checked.ini"), "--check"], cwd=tmp_path, env=env, check=True,
                             capture_output=True, text=True).stdout
    assert report.startswith("indentmap run --check: scene checked would run\n")
    assert "  histories/member_01_2.csv\n" in report and "  fig5.pdf\n" in report
    assert steady(report) == steady(program)
    assert sorted(os.listdir(tmp_path)) == ["checked.ini"]  # nothing written


def test_check_scene_refuses_as_the_run(tmp_path):
    (tmp_path / "bad.ini").write_text(SCENE.replace("seeds = 1:2", "seeds = 1:2\nhurts = 0.8"))
    with pytest.raises(im.FormatError, match=r"bad.ini:8: .*'hurts'"):
        im.check_scene(str(tmp_path / "bad.ini"))
    (tmp_path / "big.ini").write_text(SCENE.replace("n = 32", "n = 65536"))
    with pytest.raises(im.OutOfMemory, match="this scene needs about"):
        im.check_scene(str(tmp_path / "big.ini"))
    assert sorted(os.listdir(tmp_path)) == ["bad.ini", "big.ini"]


def test_check_scene_non_utf8_folder(tmp_path):
    """A path that is not UTF-8 comes back as Python's os.fsdecode has it (surrogate escapes), not an error."""
    folder = os.fsencode(tmp_path) + b"/caf\xe9"
    os.mkdir(folder)
    with open(folder + b"/checked.ini", "w") as scene:
        scene.write(SCENE)
    report = im.check_scene(os.fsdecode(folder + b"/checked.ini"))
    assert "  scene " + os.fsdecode(folder + b"/checked.ini") + "\n" in report
    assert os.listdir(folder) == [b"checked.ini"]  # nothing written
