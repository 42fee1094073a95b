"""A punch from a user-given profile array: the same bits as ``indentmap indent --punch profile``, and the
cone's answer when the profile is a sampled cone (indenter.h, "User-given profiles")."""
import csv

import numpy as np
import pytest

import indentmap as im
from conftest import run_cli

COT80 = 1.0 / np.tan(np.radians(80.0))


def cone_table(samples=5, r_max=40.0):
    r = np.linspace(0.0, r_max, samples)
    return np.column_stack([r, r * COT80])


def cone_field(side=41):
    offset = np.arange(side) - side // 2
    return np.hypot(offset[None, :], offset[:, None]) * COT80


def history_rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def assert_same_bits(rows, history):
    for k, row in enumerate(rows):
        for name in ("approach", "load", "max_pressure", "mean_pressure"):
            assert float(row[name]) == history[k][name], name  # printed with 17 digits: exact
        for name in ("load_star", "area_ratio"):
            assert float(row[name]) == history[k][name] or (np.isnan(float(row[name])) and np.isnan(history[k][name]))
        assert int(row["contact_patches"]) == history[k]["contact_patches"]
        assert int(row["iterations"]) == history[k]["iterations"]


def test_table_bit_for_bit_with_the_cli(cli, rough64, tmp_path):
    table = cone_table()
    np.savetxt(tmp_path / "tip.csv", table, delimiter=",", fmt="%.17g", header="r,z")
    im.write(tmp_path / "s.npy", rough64)
    run_cli(cli, "indent", tmp_path / "s.npy", "--approach", "0.5,1.5", "--punch", "profile", "--profile",
            tmp_path / "tip.csv", "--fields", "--out", tmp_path / "out")
    history, fields = im.indent(rough64, table, approaches=[0.5, 1.5], fields=True)
    assert_same_bits(history_rows(tmp_path / "out" / "history.csv"), history)
    saved = np.load(tmp_path / "out" / "force_0002.npy")
    assert saved.tobytes() == fields[1]["force"].tobytes()


def test_field_bit_for_bit_with_the_cli(cli, rough64, tmp_path):
    field = cone_field()
    np.save(tmp_path / "tip.npy", field)
    im.write(tmp_path / "s.npy", rough64)
    run_cli(cli, "indent", tmp_path / "s.npy", "--load", "3,9", "--punch", "profile", "--profile",
            tmp_path / "tip.npy", "--out", tmp_path / "out")
    history = im.indent(rough64, field, loads=[3, 9])
    assert_same_bits(history_rows(tmp_path / "out" / "history.csv"), history)
    assert np.isnan(history["area_ratio"]).all()  # no smooth-contact A(N) for a 2-D profile


@pytest.mark.parametrize("profile", [cone_table(), cone_table(9, 60.0), cone_field()],
                         ids=["table", "finer table", "field"])
def test_sampled_cone_is_the_cone(rough64, profile):
    approaches = [0.5, 1.0, 2.0]
    ours = im.indent(rough64, profile, approaches=approaches)
    cone = im.indent(rough64, im.Cone(80), approaches=approaches)
    assert (ours["contact_patches"] == cone["contact_patches"]).all()
    np.testing.assert_allclose(ours["load"], cone["load"], rtol=1e-7)


def test_profile_refusals(rough64):
    with pytest.raises(im.InvalidArgument, match="sample 2.*non-decreasing"):
        im.indent(rough64, np.array([[0, 0], [1, 0.5], [2, 0.4], [3, 1.0]]), approaches=[1])
    with pytest.raises(im.InvalidArgument, match="sample 1.*strictly increasing"):
        im.indent(rough64, np.array([[0, 0], [-1, 0.5], [2, 0.6]]), approaches=[1])
    with pytest.raises(im.InvalidArgument, match="sample 1"):
        im.indent(rough64, np.array([[0, 0], [1, np.nan], [2, 0.6]]), approaches=[1])
    with pytest.raises(im.InvalidArgument, match="2 samples"):
        im.indent(rough64, np.array([[0, 0], [1, 0.5]]), approaches=[1])
    with pytest.raises(im.InvalidArgument, match="3 x 3"):
        im.indent(rough64, np.zeros((2, 5)), approaches=[1])
    with pytest.raises(TypeError, match="profile"):
        im.indent(rough64, np.array([["0", "a"]] * 3), approaches=[1])
