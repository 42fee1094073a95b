"""Provenance (issue 31): run_scene_from_record makes a scene's run again from its run.json alone, after its
scene file was edited, and refuses an input that changed since."""
import hashlib
import json

import numpy as np
import pytest

import indentmap as im

SCENE = """[scene]
name = provenance
[surfaces]
file = s.npy
[loading]
load_star = 580
[output]
table = yes
"""


def test_from_record_remakes_the_table_and_refuses_a_changed_input(tmp_path):
    rng = np.random.default_rng(4)
    np.save(tmp_path / "s.npy", rng.normal(scale=0.5, size=(64, 64)))
    scene = tmp_path / "s.ini"
    scene.write_text(SCENE)
    first = im.run_scene(scene, quiet=True, out=tmp_path / "a")
    record = json.loads((tmp_path / "a" / "run.json").read_text(encoding="utf-8"))
    assert record["scene_contents"]["sections"]["loading"] == {"load_star": "580"}
    assert record["inputs"][0]["sha256"] == hashlib.sha256((tmp_path / "s.npy").read_bytes()).hexdigest()

    scene.write_text(SCENE.replace("580", "300"))  # edited after the run: the record still holds 580
    again = im.run_scene_from_record(tmp_path / "a" / "run.json", out=tmp_path / "b", quiet=True)
    assert (tmp_path / "b" / "table1.csv").read_bytes() == (tmp_path / "a" / "table1.csv").read_bytes()
    assert again.endswith("b") and first.endswith("a")

    np.save(tmp_path / "s.npy", rng.normal(scale=0.5, size=(64, 64)))
    with pytest.raises(im.InvalidArgument, match="s.npy: \\[surfaces\\] file has changed since the run"):
        im.run_scene_from_record(tmp_path / "a" / "run.json", out=tmp_path / "c")
