"""The Python package and the command line run the same library: the same inputs give the same bits."""
import csv
import io
import json
import warnings

import numpy as np
import pytest

import indentmap as im
from conftest import run_cli


def read_history(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def test_indent_history_and_fields_bit_for_bit(cli, rough64, tmp_path):
    im.write(tmp_path / "s.npy", rough64)
    run_cli(cli, "indent", tmp_path / "s.npy", "--approach", "0.5,1,2", "--fields", "--out", tmp_path / "out")
    history, fields = im.indent(rough64, im.Cone(80), approaches=[0.5, 1, 2], fields=True)
    rows = read_history(tmp_path / "out" / "history.csv")
    assert len(rows) == 3
    for k, row in enumerate(rows):
        for name in ("approach", "load", "load_star", "area_ratio", "mean_pressure", "max_pressure"):
            assert float(row[name]) == history[k][name], name  # printed with 17 digits: exact
        for name in ("contact_patches", "iterations", "convolutions"):
            assert int(row[name]) == history[k][name], name
        for name in ("force", "gap", "displacement"):
            saved = np.load(tmp_path / "out" / f"{name}_{k + 1:04d}.npy")
            assert saved.dtype == np.float64 and saved.shape == fields[k][name].shape
            assert saved.tobytes() == fields[k][name].tobytes(), name


def test_one_history_schema(cli, rough64, tmp_path):
    """indent's array has history.csv's columns, names and values (the theory, the stiffness, the patches,
    the plastic memory included), and read_history reads the CLI's file into the same array."""
    im.write(tmp_path / "s.npy", rough64)
    run_cli(cli, "indent", tmp_path / "s.npy", "--approach", "0.5:2:4,1.5", "--hardness", "0.3", "--out",
            tmp_path / "out")
    ours = im.indent(rough64, im.Cone(80), approaches=[0.5, 1, 1.5, 2, 1.5], hardness=0.3)
    theirs = im.read_history(tmp_path / "out" / "history.csv")
    assert ours.dtype == theirs.dtype and ours.dtype.names == tuple(im._core.history_columns.split(","))
    assert len(ours) == len(theirs) == 5
    for name in ours.dtype.names:
        if name != "seconds":
            np.testing.assert_array_equal(ours[name], theirs[name], err_msg=name)
    assert np.isfinite(ours["stiffness"][2]) and np.isnan(ours["stiffness"][:2]).all()
    # the theory's h'rms: forward differences by default for an array (as indent for a file), spectral on request
    fd = im.indent(rough64, im.Cone(80), approaches=[1.0], slope_definition="fd")
    spectral = im.indent(rough64, im.Cone(80), approaches=[1.0], slope_definition="spectral")
    default = im.indent(rough64, im.Cone(80), approaches=[1.0])
    assert default["area_ratio_gamma"][0] == fd["area_ratio_gamma"][0] != spectral["area_ratio_gamma"][0]
    with pytest.raises(ValueError, match="slope_definition 'sobel'"):
        im.Indentation(rough64, largest=1.0, slope_definition="sobel")
    (tmp_path / "old.csv").write_text("step,approach\n1,2\n")
    with pytest.raises(ValueError, match="not this version's history columns"):
        im.read_history(tmp_path / "old.csv")
    with pytest.raises(ValueError, match=r"s\.npy: byte 0 is not UTF-8 text: expected a history\.csv"):
        im.read_history(tmp_path / "s.npy")  # was a bare UnicodeDecodeError naming no file


def test_load_control_sphere_bit_for_bit(cli, rough64, tmp_path):
    im.write(tmp_path / "s.npy", rough64)
    run_cli(cli, "indent", tmp_path / "s.npy", "--punch", "sphere", "--radius", "40", "--load", "2,8",
            "--fields", "--out", tmp_path / "out")
    history, fields = im.indent(rough64, im.Sphere(40), loads=[2, 8], fields=True)
    rows = read_history(tmp_path / "out" / "history.csv")
    assert [float(r["load"]) for r in rows] == list(history["load"])
    assert np.load(tmp_path / "out" / "force_0002.npy").tobytes() == fields[1]["force"].tobytes()


def test_loading_unloading_with_hardness_bit_for_bit(cli, rough64, tmp_path):
    """A cycle with the cap's memory: the same history, plastic fields and indentation analysis."""
    im.write(tmp_path / "s.npy", rough64)
    run_cli(cli, "indent", tmp_path / "s.npy", "--approach", "1:3:3,2.5:0:6", "--hardness", "0.05", "--fields",
            "--out", tmp_path / "out")
    approaches = np.r_[np.linspace(1, 3, 3), np.linspace(2.5, 0, 6)]
    history, fields = im.indent(rough64, im.Cone(80), approaches=approaches, hardness=0.05, fields=True)
    rows = read_history(tmp_path / "out" / "history.csv")
    for k, row in enumerate(rows):
        for name in ("approach", "load", "plastic_depth", "plastic_work", "residual_approach"):
            assert float(row[name]) == history[k][name], name
        assert int(row["yielding_patches"]) == history[k]["yielding_patches"]
    assert history["plastic_work"][2] > 0 and (history["plastic_work"][3:] == history["plastic_work"][2]).all()
    saved = np.load(tmp_path / "out" / "plastic_0009.npy")
    assert saved.tobytes() == fields[8]["plastic"].tobytes() and saved.max() == history["plastic_depth"][8]
    table = im.unloading(history, im.Cone(80))
    with open(tmp_path / "out" / "indentation.csv") as f:
        csv_rows = list(csv.DictReader(f))
    assert len(table) == len(csv_rows) == 1
    for name in im.solver.UNLOADING_DTYPE.names:
        np.testing.assert_array_equal(float(csv_rows[0][name]), table[0][name], err_msg=name)
    assert table[0]["top_step"] == 3 and table[0]["last_step"] == 9 and table[0]["residual_approach"] > 0
    # the top yielded: the elastic theory is not beside it
    assert np.isnan(table[0]["area_real_theory"]) and np.isnan(table[0]["stiffness_smooth"])


def test_stiffness_past_the_touch_says_why_as_the_cli(cli, rough64, tmp_path):
    """An unloading in steps too large (1:3:3 then 2, 1, 0 with a hardness: withdrawn by w = 1) has S NaN, and
    Python warns why and what to do in the words indent prints (findings R3: a NaN alone told neither)."""
    im.write(tmp_path / "s.npy", rough64)
    said = run_cli(cli, "indent", tmp_path / "s.npy", "--approach", "1:3:3,2:0:3", "--hardness", "0.05", "--out",
                   tmp_path / "out").stdout
    history = im.read_history(tmp_path / "out" / "history.csv")
    with pytest.warns(UserWarning) as warned:
        table = im.unloading(history, im.Cone(80))
    assert np.isnan(table[0]["stiffness"]) and np.isnan(table[0]["hardness_it"])
    notes = [str(w.message) for w in warned]
    assert len(notes) == 1 and "unload in smaller steps that keep at least three points in contact" in notes[0]
    assert f"indentation analysis: {notes[0]}\n" in said
    finer = im.indent(rough64, im.Cone(80), approaches=[1, 2, 3, 2.8, 2.6, 2.4], hardness=0.05)
    with warnings.catch_warnings():  # a fit above the touch is measured, and says nothing
        warnings.simplefilter("error")
        assert np.isfinite(im.unloading(finer, im.Cone(80))["stiffness"]).all()


def test_elastic_unloading_with_theory_bit_for_bit(cli, rough64, tmp_path):
    """An elastic load-unload cycle of a cone at E* = 2: indentation.csv's theory beside the branch (eq. (12)'s
    area, the smooth stiffness) is Python's unloading(), and is the theory module's own numbers."""
    im.write(tmp_path / "s.npy", rough64)
    run_cli(cli, "indent", tmp_path / "s.npy", "--e-star", "2", "--approach", "1:3:3,2.5:1:4", "--out", tmp_path / "out")
    history = im.read_history(tmp_path / "out" / "history.csv")
    table = im.unloading(history, im.Cone(80), e_star=2.0)
    with open(tmp_path / "out" / "indentation.csv") as f:
        csv_rows = list(csv.DictReader(f))
    assert len(table) == len(csv_rows) == 1
    for name in im.solver.UNLOADING_DTYPE.names:
        np.testing.assert_array_equal(float(csv_rows[0][name]), table[0][name], err_msg=name)
    top = table[0]["top_step"] - 1
    load = history["load"][top]
    smooth_area = im.theory.cone_area(load, 80.0, e_star=2.0)
    assert table[0]["stiffness_smooth"] == pytest.approx(2 * 2.0 * np.sqrt(smooth_area / np.pi), rel=1e-14)
    import json
    slope = json.load(open(tmp_path / "out" / "run.json"))["theory_slope_rms"]["value"]
    ratio = im.theory.area_ratio(slope, 80.0)  # eq. (12): load-independent for a cone
    assert 0.5 < ratio < 1 and table[0]["area_real_theory"] == pytest.approx(smooth_area * ratio, rel=1e-9)


def test_adhesion_bit_for_bit(cli, rough64, tmp_path):
    """An adhesive approach and retraction of a sphere on the rough surface: the same history (tension, the
    adhesive and repulsive patches), the same net force field, and adhesion() equal to run.json's block."""
    import json
    im.write(tmp_path / "s.npy", rough64)
    run_cli(cli, "indent", tmp_path / "s.npy", "--punch", "sphere", "--radius", "40", "--adhesion-work", "0.02",
            "--adhesion-range", "0.5", "--approach", "-0.5:1.5:3,1:-1:5", "--fields", "--out", tmp_path / "out")
    approaches = np.r_[np.linspace(-0.5, 1.5, 3), np.linspace(1, -1, 5)]
    history, fields = im.indent(rough64, im.Sphere(40), approaches=approaches, adhesion_work=0.02,
                                adhesion_range=0.5, fields=True)
    theirs = im.read_history(tmp_path / "out" / "history.csv")
    for name in history.dtype.names:
        if name != "seconds":
            np.testing.assert_array_equal(history[name], theirs[name], err_msg=name)
    assert (history["load"] < 0).any() and (history["tensile_force"] > 0).any()
    assert np.load(tmp_path / "out" / "force_0008.npy").tobytes() == fields[7]["force"].tobytes()
    record = json.loads((tmp_path / "out" / "run.json").read_text())["adhesion"]
    summary = im.adhesion(history)
    for name, value in summary.items():
        assert value == record[name] or (np.isnan(value) and record[name] is None), name


def test_adhesion_zone_bit_for_bit(cli, rough64, tmp_path):
    """adhesion_zone as indent --adhesion-zone: the widened law's history (l = 4.9 patches widened to 8), to the
    bit, which differs from the law as given."""
    im.write(tmp_path / "s.npy", rough64)
    run_cli(cli, "indent", tmp_path / "s.npy", "--punch", "sphere", "--radius", "40", "--adhesion-work", "0.02",
            "--adhesion-range", "0.5", "--adhesion-zone", "8", "--approach", "1,-0.5", "--out", tmp_path / "out")
    options = dict(approaches=[1, -0.5], adhesion_work=0.02, adhesion_range=0.5)
    widened = im.indent(rough64, im.Sphere(40), adhesion_zone=8, **options)
    theirs = im.read_history(tmp_path / "out" / "history.csv")
    for name in widened.dtype.names:
        if name != "seconds":
            np.testing.assert_array_equal(widened[name], theirs[name], err_msg=name)
    assert not np.array_equal(widened["load"], im.indent(rough64, im.Sphere(40), **options)["load"])


def test_adhesion_with_hardness_bit_for_bit(cli, rough64, tmp_path):
    """Adhesion with a hardness (indent --hardness --adhesion-work): the same history as the program's, yielding
    and pulling, the same plastic depth field, no net pressure above the hardness; on a periodic cell under mean
    gaps the same rows too, yielding."""
    im.write(tmp_path / "s.npy", rough64)
    options = dict(adhesion_work=0.02, adhesion_range=0.5, hardness=0.05)
    run_cli(cli, "indent", tmp_path / "s.npy", "--punch", "sphere", "--radius", "40", "--adhesion-work", "0.02",
            "--adhesion-range", "0.5", "--hardness", "0.05", "--approach", "-0.5:1.5:3,1:-1:5", "--fields", "--out",
            tmp_path / "out")
    approaches = np.r_[np.linspace(-0.5, 1.5, 3), np.linspace(1, -1, 5)]
    history, fields = im.indent(rough64, im.Sphere(40), approaches=approaches, fields=True, **options)
    theirs = im.read_history(tmp_path / "out" / "history.csv")
    for name in history.dtype.names:
        if name != "seconds":
            np.testing.assert_array_equal(history[name], theirs[name], err_msg=name)
    assert (history["yielding_patches"] > 0).any() and (history["tensile_force"] > 0).any()
    assert (history["max_pressure"] <= 0.05 * (1 + 1e-12)).all()
    assert np.load(tmp_path / "out" / "plastic_0008.npy").tobytes() == fields[7]["plastic"].tobytes()
    run_cli(cli, "indent", tmp_path / "s.npy", "--periodic", "--adhesion-work", "0.02", "--adhesion-range", "0.5",
            "--hardness", "0.05", "--mean-gap", "0.6,0.3,0.5", "--out", tmp_path / "cell")
    history = im.indent(rough64, None, mean_gaps=[0.6, 0.3, 0.5], periodic=True, **options)
    theirs = im.read_history(tmp_path / "cell" / "history.csv")
    for name in history.dtype.names:
        if name != "seconds":
            np.testing.assert_array_equal(history[name], theirs[name], err_msg=name)
    assert (history["yielding_patches"] > 0).any() and (history["max_pressure"] <= 0.05 * (1 + 1e-12)).all()


def test_adhesion_under_load_control_bit_for_bit(cli, rough64, tmp_path):
    """Adhesion under load control (indent --load with negative loads): the same history as the program's, and a
    load beyond the pull-off refused by both, naming it."""
    im.write(tmp_path / "s.npy", rough64)
    options = dict(adhesion_work=0.02, adhesion_range=0.5)
    run_cli(cli, "indent", tmp_path / "s.npy", "--punch", "sphere", "--radius", "40", "--adhesion-work", "0.02",
            "--adhesion-range", "0.5", "--load", "1,0,-0.3", "--out", tmp_path / "out")
    history = im.indent(rough64, im.Sphere(40), loads=[1.0, 0.0, -0.3], **options)
    theirs = im.read_history(tmp_path / "out" / "history.csv")
    for name in history.dtype.names:
        if name != "seconds":
            np.testing.assert_array_equal(history[name], theirs[name], err_msg=name)
    assert history["load"][-1] == pytest.approx(-0.3, rel=1e-5) and history["tensile_force"][-1] > 0
    with pytest.raises(im.InvalidArgument, match="pull-off force under load control"):
        im.indent(rough64, im.Sphere(40), loads=[1.0, -100.0], **options)
    with pytest.raises(im.InvalidArgument, match="mean-gap or load control on a periodic cell"):
        im.Indentation(rough64, None, control="displacement", largest=1.0, periodic=True, **options)


def test_exponential_adhesion_bit_for_bit(cli, rough64, tmp_path):
    """The exponential law on the periodic cell under mean-gap control, approached and pulled back: Python's
    history is the CLI's (--adhesion-law exponential) bit for bit, with tension, and run.json names the law."""
    import json
    im.write(tmp_path / "s.npy", rough64)
    gaps = [float(g) for g in np.std(rough64) * np.array([1.5, 0.5, 1.0, 2.0])]
    run_cli(cli, "indent", tmp_path / "s.npy", "--periodic", "--mean-gap", ",".join(repr(g) for g in gaps),
            "--adhesion-work", "0.02", "--adhesion-range", "0.5", "--adhesion-law", "exponential", "--out",
            tmp_path / "out")
    history = im.indent(rough64, None, mean_gaps=gaps, periodic=True, adhesion_work=0.02, adhesion_range=0.5,
                        adhesion_law="exponential")
    theirs = im.read_history(tmp_path / "out" / "history.csv")
    for name in history.dtype.names:
        if name != "seconds":
            np.testing.assert_array_equal(history[name], theirs[name], err_msg=name)
    assert (history["tensile_force"] > 0).all() and (history["contact_patches"][1] > 0)
    assert json.loads((tmp_path / "out" / "run.json").read_text())["adhesion"]["law"] == "exponential"


def test_periodic_bit_for_bit(cli, rough64, tmp_path):
    """indent --periodic --pressure and indent(..., periodic=True, pressures=...): the same rows and forces."""
    im.write(tmp_path / "s.npy", rough64)
    run_cli(cli, "indent", tmp_path / "s.npy", "--periodic", "--pressure", "0.002,0.01", "--fields", "--out",
            tmp_path / "out")
    history, fields = im.indent(rough64, None, pressures=[0.002, 0.01], periodic=True, fields=True)
    rows = read_history(tmp_path / "out" / "history.csv")
    for k, row in enumerate(rows):
        for name in ("approach", "load", "area_ratio", "mean_pressure", "max_pressure"):
            assert float(row[name]) == history[k][name], name
        assert np.isnan(history[k]["load_star"]) and history[k]["area_ratio"] == history[k]["contact_patches"] / 64**2
        assert np.load(tmp_path / "out" / f"force_{k + 1:04d}.npy").tobytes() == fields[k]["force"].tobytes()
    # k of eq. (2): the CLI's run.json and theory.fit_k over the same history, h'rms spectral
    record = json.load(open(tmp_path / "out" / "run.json"))["k_fit"]
    slope = im.statistics(rough64)["slope_rms_spectral"]
    fit = im.theory.fit_k(history["load"] / (64 * 64 * slope), history["area_ratio"])
    assert abs(fit["k"] - record["k"]) <= 1e-12 * record["k"] and abs(fit["k_error"] - record["k_error"]) <= 1e-9


def test_fit_k_history_bit_for_bit(cli, rough64, tmp_path):
    """theory.fit_k_history over a periodic run's history.csv and run.json: run.json's k_fit and `theory
    --fit-k --format csv` (17 digits) to the bit; a half-space history refused naming mean_gap."""
    im.write(tmp_path / "s.npy", rough64)
    run_cli(cli, "indent", tmp_path / "s.npy", "--periodic", "--pressure", "0.002,0.006,0.01", "--out",
            tmp_path / "out")
    ours = im.theory.fit_k_history(tmp_path / "out" / "history.csv")
    record = json.loads((tmp_path / "out" / "run.json").read_text())["k_fit"]
    assert ours.keys() == record.keys()
    for name, value in record.items():
        assert ours[name] == value or (value is None and np.isnan(ours[name])), name
    printed = run_cli(cli, "theory", "--fit-k", tmp_path / "out" / "history.csv", "--format", "csv").stdout
    row = next(csv.DictReader(io.StringIO(printed)))
    for name in ("k", "k_error", "rms_residual", "k_linear", "slope_rms"):
        assert float(row[name]) == ours[name], name
    assert int(row["points"]) == ours["points"] == 3 and int(row["linear_points"]) == ours["linear_points"]
    # steps in full contact (A/A0 = 1) left out and counted, as the program does (redteam4)
    run_cli(cli, "indent", tmp_path / "s.npy", "--periodic", "--pressure", "0.01,1,10", "--out", tmp_path / "full")
    ours = im.theory.fit_k_history(tmp_path / "full" / "history.csv")
    record = json.loads((tmp_path / "full" / "run.json").read_text())["k_fit"]
    assert ours.keys() == record.keys() and ours["points"] == 1 and ours["full_contact_points"] == 2, ours
    assert all(ours[name] == value or (value is None and np.isnan(ours[name])) for name, value in record.items())
    run_cli(cli, "indent", tmp_path / "s.npy", "--approach", "0.5,1", "--out", tmp_path / "half")
    with pytest.raises(ValueError, match=r"row 1 \(line 2\) has no mean_gap"):
        im.theory.fit_k_history(tmp_path / "half" / "history.csv")
    (tmp_path / "out" / "run.json").unlink()
    with pytest.raises(ValueError, match="no run.json beside the history"):
        im.theory.fit_k_history(tmp_path / "out" / "history.csv")


def test_write_analysis_files_are_the_cli_ones(cli, rough64, tmp_path):
    """write_analysis of Python's history and of the CLI's history.csv: indent's indentation.csv byte for
    byte, load_displacement.png and .pdf drawn byte for byte; only their metadata differ: indent's figures
    carry its command and inputs (issue 31), the PDF its creation date."""
    im.write(tmp_path / "s.npy", rough64)
    run_cli(cli, "indent", tmp_path / "s.npy", "--approach", "1:3:3,2.5:1:3", "--out", tmp_path / "out")
    history = im.indent(rough64, im.Cone(80), approaches=[1, 2, 3, 2.5, 1.75, 1])
    assert im.write_analysis(history, tmp_path / "py") == 1
    assert im.write_analysis(tmp_path / "out" / "history.csv", tmp_path / "csv", im.Cone(80)) == 1
    def png_drawing(path):  # every chunk but the text chunks
        data, chunks, at = path.read_bytes(), [], 8
        while at < len(data):
            length = int.from_bytes(data[at:at + 4], "big")
            if data[at + 4:at + 8] not in (b"tEXt", b"zTXt", b"iTXt"):
                chunks.append(data[at:at + 12 + length])
            at += 12 + length
        return b"".join(chunks)

    def pdf_drawing(path):  # the pages, before cairo's information dictionary and the cross-references
        data = path.read_bytes()
        return data[:data.index(b"<< /Producer")]

    assert b"Command" in (tmp_path / "out" / "load_displacement.png").read_bytes()
    for folder in ("py", "csv"):
        name = "indentation.csv"
        assert (tmp_path / folder / name).read_bytes() == (tmp_path / "out" / name).read_bytes(), folder
        png = tmp_path / folder / "load_displacement.png"
        assert png_drawing(png) == png_drawing(tmp_path / "out" / "load_displacement.png"), folder
        pdf = tmp_path / folder / "load_displacement.pdf"
        assert pdf_drawing(pdf) == pdf_drawing(tmp_path / "out" / "load_displacement.pdf"), folder
    assert im.write_analysis(history[:3], tmp_path / "loading") == 0 and not any((tmp_path / "loading").iterdir())
    with pytest.raises(ValueError, match="history.csv's columns"):
        im.write_analysis(np.zeros(3), tmp_path / "bad")


def test_a_mean_gap_of_zero_is_refused_before_any_step(rough64):
    """as indent --mean-gap: it was refused at its step, after the steps before it were solved"""
    with pytest.raises(ValueError, match=r"mean_gaps: step 2 is 0: expected mean gaps > 0"):
        im.indent(rough64, None, mean_gaps=[0.4, 0.0], periodic=True, max_iterations=1)


def test_periodic_mean_gap_bit_for_bit(cli, rough64, tmp_path):
    """indent --periodic --mean-gap and indent(..., periodic=True, mean_gaps=...): the same rows, with a
    hardness (the searched approach) and unloading; the mean gap reached is the one imposed."""
    im.write(tmp_path / "s.npy", rough64)
    run_cli(cli, "indent", tmp_path / "s.npy", "--periodic", "--hardness", "0.05", "--mean-gap", "0.4,0.2,0.4",
            "--out", tmp_path / "out")
    history = im.indent(rough64, None, mean_gaps=[0.4, 0.2, 0.4], periodic=True, hardness=0.05)
    theirs = im.read_history(tmp_path / "out" / "history.csv")
    for name in history.dtype.names:
        if name != "seconds":
            np.testing.assert_array_equal(history[name], theirs[name], err_msg=name)
    np.testing.assert_allclose(history["mean_gap"], [0.4, 0.2, 0.4], rtol=1e-6)
    assert history["yielding_patches"][1] > 0 and history["plastic_work"][2] == history["plastic_work"][1]
    with pytest.raises(ValueError, match="periodic=True"):
        im.indent(rough64, im.Cone(), mean_gaps=[0.4])


def test_synthesis_and_statistics_match_the_cli(cli, tmp_path):
    run_cli(cli, "surface", "--n", "48", "--hurst", "0.7", "--slope", "0.05", "--seed", "9", "--out",
            tmp_path / "s.npy")
    ours = im.generate(48, hurst=0.7, slope=0.05, seed=9)
    assert np.load(tmp_path / "s.npy").tobytes() == ours.tobytes()
    assert im.read(tmp_path / "s.npy").heights.tobytes() == ours.tobytes()


def test_theory_matches_the_cli(cli):
    out = run_cli(cli, "theory", "--alpha", "80", "--slope", "0.01,0.08,0.16", "--format", "csv").stdout
    rows = list(csv.DictReader(io.StringIO(out)))
    slopes = np.array([float(r["slope"]) for r in rows])
    eq12 = np.array([float(r["area_ratio_eq12"]) for r in rows])
    eq6 = np.array([float(r["area_ratio_eq6"]) for r in rows])
    rho = im.theory.rho_c(slopes, alpha=80)
    beta = im.theory.beta(rho)
    np.testing.assert_allclose(im.theory.area_ratio_eq12(beta), eq12, rtol=1e-12)
    np.testing.assert_allclose(im.theory.area_ratio_eq6(beta), eq6, rtol=1e-12)


def test_instrument_file_channels(cli):
    """An instrument file through Gwyddion's modules: the default channel is the first holding
    heights; by title or by index the same other one, with Gwyddion's rms; a channel that is not
    heights is refused."""
    import os
    data = os.path.join(os.environ.get("IM_SOURCE_DIR", ""), "tests", "data", "instruments")
    if "not in this build" in run_cli(cli, "formats").stdout:
        pytest.skip("this build has no indentmap-gwyddion-read")
    di3 = os.path.join(data, "di-3.di")
    default = im.read(di3)
    assert default.heights.shape == (256, 256) and default.unit == "m"
    assert abs(default.delta - 1e-5 / 256) < 1e-20
    by_title, by_index = im.read(di3, channel="Height"), im.read(di3, channel=3)
    assert by_title.heights.tobytes() == by_index.heights.tobytes()
    assert by_title.heights.tobytes() != default.heights.tobytes()
    assert abs(by_title.heights.std() - 2.64003e-07) < 2e-12  # Gwyddion 2.62's rms of that channel
    with pytest.raises(im.FormatError, match="holds values in 'deg'"):
        im.read(di3, channel="Phase")


def test_instrument_file_orientation_matches_gwyddions_export(cli):
    """The Nanoscope scan through Gwyddion's module and Gwyddion's own text export of its ZSensor channel
    (plane-levelled) are one surface, row for row: they differ by a plane alone (to the export's rounding),
    which a flip or transpose would not (h'rms cannot tell these apart)."""
    import os
    data = os.path.join(os.environ.get("IM_SOURCE_DIR", ""), "tests", "data", "instruments")
    if "not in this build" in run_cli(cli, "formats").stdout:
        pytest.skip("this build has no indentmap-gwyddion-read")
    export = im.read(os.path.join(data, "matrix-3.txt"))
    scan = im.read(os.path.join(data, "di-3.di"))
    assert export.unit == "µm" and scan.unit == "m"

    def off_plane(d):
        y, x = np.mgrid[0:d.shape[0], 0:d.shape[1]]
        a = np.c_[np.ones(d.size), x.ravel(), y.ravel()]
        c, *_ = np.linalg.lstsq(a, d.ravel(), rcond=None)
        return np.abs(d.ravel() - a @ c).max()

    same = export.heights - scan.heights * 1e6
    assert off_plane(same) < 1e-5  # µm: the export's 6 digits
    for moved in (scan.heights[::-1], scan.heights[:, ::-1], scan.heights.T):
        assert off_plane(export.heights - moved * 1e6) > 0.1


def test_periodic_adhesion_bit_for_bit(cli, rough64, tmp_path):
    """Adhesion on a periodic cell (mean-gap control): indent --periodic --mean-gap --adhesion-work and
    indent(..., periodic=True, mean_gaps=..., adhesion_work=...) give the same rows, under tension too, and the
    cell's A/A0 whenever it has contact; under mean pressures (load control) the same rows too, into tension, and
    a tension beyond the cell's pull-off refused by both, naming the mean pressure."""
    im.write(tmp_path / "s.npy", rough64)
    run_cli(cli, "indent", tmp_path / "s.npy", "--periodic", "--mean-gap", "1.6:0.8:3,1:1.8:3", "--adhesion-work",
            "0.02", "--adhesion-range", "0.5", "--out", tmp_path / "out")
    gaps = np.r_[np.linspace(1.6, 0.8, 3), np.linspace(1, 1.8, 3)]
    history = im.indent(rough64, None, mean_gaps=gaps, periodic=True, adhesion_work=0.02, adhesion_range=0.5)
    theirs = im.read_history(tmp_path / "out" / "history.csv")
    for name in history.dtype.names:
        if name != "seconds":
            np.testing.assert_array_equal(history[name], theirs[name], err_msg=name)
    assert (history["tensile_force"] > 0).any()
    in_contact = history["contact_patches"] > 0
    np.testing.assert_array_equal(history["area_ratio"][in_contact], history["contact_patches"][in_contact] / 64**2)
    run_cli(cli, "indent", tmp_path / "s.npy", "--periodic", "--pressure", "0.004,0.001,-0.0005",
            "--adhesion-work", "0.002", "--adhesion-range", "0.5", "--out", tmp_path / "pressures")
    options = dict(periodic=True, adhesion_work=0.002, adhesion_range=0.5)
    history = im.indent(rough64, None, pressures=[0.004, 0.001, -0.0005], **options)
    theirs = im.read_history(tmp_path / "pressures" / "history.csv")
    for name in history.dtype.names:
        if name != "seconds":
            np.testing.assert_array_equal(history[name], theirs[name], err_msg=name)
    assert history["tensile_force"][-1] > 0 and history["load"][-1] < 0
    with pytest.raises(im.InvalidArgument, match="mean pressure -0.01 .*the cell's pull-off under load control"):
        im.indent(rough64, None, pressures=[0.004, -0.01], **options)
