"""Units carried into pictures (issue 29): a run in metres and pascals draws, in Python, the contact figure
that ``indentmap render contact`` draws from the run's force file, with the colour bar 'local force f / N'
and a scale bar in µm; a contact map's PNG carries the program's text chunks."""
import os
import sys

import numpy as np
import pytest

import indentmap as im
from conftest import run_cli
from test_cli_counterparts import VIEW3D_SIZE

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests"))
from figure_texts import png_texts  # noqa: E402  (the PNG text chunks, read independently of indentmap)

APPROACH = 2e-7  # metres


@pytest.fixture
def run_in_metres(cli, rough64, tmp_path):
    """The CLI's run on a surface of 0.1 µm patches read in metres with E* in Pa, and Python's force field
    and units of the same run."""
    im.write(tmp_path / "s.npy", 0.1 * rough64, delta=0.1, unit="µm")
    run_cli(cli, "indent", tmp_path / "s.npy", "--length-unit", "m", "--e-star", "1e9", "--e-star-unit", "Pa",
            "--approach", APPROACH, "--fields", "--out", tmp_path / "out")
    t = im.read(tmp_path / "s.npy", length_unit="m")
    run = im.Indentation(t.heights, im.Cone(80), largest=APPROACH, delta=t.delta, e_star=1e9, length_unit=t.unit,
                         e_star_unit="Pa")
    run.step(APPROACH)
    force = run.fields()[0]
    assert force.tobytes() == np.load(tmp_path / "out" / "force_0001.npy").tobytes()
    return t, run.units, force, tmp_path / "out" / "force_0001.npy"


def test_contact_figure_in_units_is_the_programs(cli, run_in_metres, tmp_path):
    t, units, force, force_file = run_in_metres
    assert (t.unit, units["force"]) == ("m", "N")
    run_cli(cli, "render", "contact", force_file, "--out", tmp_path / "cli.png")
    im.Figure([force], delta=t.delta, unit=t.unit, force_unit=units["force"]).save(tmp_path / "python.png")
    ours, theirs = im.Image.read(tmp_path / "python.png").rgba, im.Image.read(tmp_path / "cli.png").rgba
    assert ours.shape == theirs.shape and np.array_equal(ours, theirs)
    # the units are what makes them equal: the same field without them is labelled in E* δ² and δ
    im.Figure([force], delta=t.delta).save(tmp_path / "plain.png")
    plain = im.Image.read(tmp_path / "plain.png").rgba
    assert plain.shape != theirs.shape or not np.array_equal(plain, theirs)
    assert png_texts(tmp_path / "cli.png")["Quantity"] == "local force f / N"


def test_scale_bar_without_a_unit_counts_patches_as_the_programs(cli, rough64, tmp_path):
    """A spacing without a unit (finding R4): ``indentmap render`` draws its bar in patches ('10 δ' on 64
    patches); Python's Figure takes scale_bar in the unit of delta, so 1e-6 at delta = 1e-7 is those 10
    patches, the program's picture pixel for pixel (it was a bar '1e-06 δ' of 1e-6 patches)."""
    delta = 1e-7
    im.write(tmp_path / "s.npy", delta * rough64, delta=delta)
    run_cli(cli, "indent", tmp_path / "s.npy", "--approach", 2 * delta, "--fields", "--out", tmp_path / "out")
    force_file = tmp_path / "out" / "force_0001.npy"
    run_cli(cli, "render", "contact", force_file, "--out", tmp_path / "cli.png")
    force = np.load(force_file)
    theirs = im.Image.read(tmp_path / "cli.png").rgba
    for bar in (0.0, 10 * delta):  # automatic (10 patches on 64), and the same length in delta's unit
        im.Figure([force], delta=delta, scale_bar=bar).save(tmp_path / "python.png")
        ours = im.Image.read(tmp_path / "python.png").rgba
        assert ours.shape == theirs.shape and np.array_equal(ours, theirs), bar
    im.Figure([force], delta=delta, scale_bar=20 * delta).save(tmp_path / "longer.png")
    assert not np.array_equal(im.Image.read(tmp_path / "longer.png").rgba, theirs)  # the length does matter


def test_contact_map_texts_are_the_programs(cli, run_in_metres, tmp_path):
    t, units, force, force_file = run_in_metres
    run_cli(cli, "render", "contact", force_file, "--raw", "--out", tmp_path / "cli.png")
    image = im.contact_map(force, delta=t.delta, unit=t.unit, force_unit=units["force"])
    image.save(tmp_path / "python.png")
    theirs = png_texts(tmp_path / "cli.png")
    for record in ("Command", "Directory", "Inputs"):  # the program's command and input file; Python draws an array
        del theirs[record]
    assert image.texts == theirs == png_texts(tmp_path / "python.png")
    assert theirs["Quantity"] == "local force f / N"
    assert np.array_equal(image.rgba, im.Image.read(tmp_path / "cli.png").rgba)


def test_height_map_quantity_in_its_unit(cli, run_in_metres, tmp_path):
    """A gap field of the run: the program names it from its sidecar, Python from quantity=."""
    t, _units, _force, force_file = run_in_metres
    gap_file = force_file.with_name("gap_0001.npy")
    run_cli(cli, "render", "height", gap_file, "--raw", "--out", tmp_path / "cli.png")
    gap = im.read(gap_file)
    image = im.height_map(gap.heights, delta=gap.delta, unit=gap.unit, quantity="gap")
    assert image.texts["Quantity"] == png_texts(tmp_path / "cli.png")["Quantity"] == "gap g / m"
    assert im.height_map(t.heights, delta=t.delta).texts["Quantity"] == "height h / δ"


def test_unknown_quantity_and_unit_are_named():
    with pytest.raises(im.InvalidArgument, match="quantity 'pressure': expected force, height, gap"):
        im.height_map(np.zeros((4, 4)), quantity="pressure")
    with pytest.raises(ValueError, match="unit 'furlong': expected a length unit"):
        im.contact_map(np.zeros((4, 4)), unit="furlong")


def test_adhesive_figure_is_the_programs(cli, rough64, tmp_path):
    """Forces under tension (adhesion) in two panels, the second's tension half the first's: the Figure draws
    them on one tension range, 0 to the largest tension of both, with the second bar 'tensile force −f / N',
    pixel for pixel as ``render contact`` draws the two force files."""
    im.write(tmp_path / "s.npy", 0.1 * rough64, delta=0.1, unit="µm")
    run_cli(cli, "indent", tmp_path / "s.npy", "--length-unit", "m", "--e-star", "1e9", "--e-star-unit", "Pa",
            "--adhesion-work", "5", "--adhesion-range", "6e-8", "--approach", f"{APPROACH},0", "--fields",
            "--out", tmp_path / "out")
    first = np.load(tmp_path / "out" / "force_0001.npy")
    halved = 0.5 * np.load(tmp_path / "out" / "force_0002.npy")
    np.save(tmp_path / "halved.npy", halved)
    (tmp_path / "halved.npy.json").write_bytes((tmp_path / "out" / "force_0002.npy.json").read_bytes())
    assert first.min() < 0 and 0 > halved.min() > first.min()
    run_cli(cli, "render", "contact", tmp_path / "out" / "force_0001.npy", tmp_path / "halved.npy",
            "--out", tmp_path / "cli.png")
    t = im.read(tmp_path / "s.npy", length_unit="m")
    im.Figure([first, halved], delta=t.delta, unit=t.unit, force_unit="N", labels=["(a)", "(b)"]).save(
        tmp_path / "python.png")
    ours, theirs = im.Image.read(tmp_path / "python.png").rgba, im.Image.read(tmp_path / "cli.png").rgba
    assert ours.shape == theirs.shape and np.array_equal(ours, theirs)


@pytest.mark.parametrize("tension", [False, True])
def test_view3d_figure_is_the_programs(cli, rough64, tmp_path, tension):
    """View3DFigure(...).save has the pixels of render view3d --out (title, dpi, exaggeration, colour bars)."""
    history, fields = im.indent(rough64, approaches=[2.0], fields=True)
    force = fields[0]["force"].copy()
    if tension:
        force[30:34, 30:34] = -force.max() / 3
    im.write(tmp_path / "s.npy", rough64)
    np.save(tmp_path / "force.npy", force)
    run_cli(cli, "render", "view3d", tmp_path / "s.npy", "--force", tmp_path / "force.npy", "--out",
            tmp_path / "v.png", "--title", "indented", "--dpi", "150", "--exaggeration", "2", *VIEW3D_SIZE)
    figure = im.View3DFigure(rough64, force=force, exaggeration=2, title="indented", dpi=150, width=160, height=96,
                             samples=1, mesh_side=48)
    figure.save(tmp_path / "p.png")
    ours, theirs = im.Image.read(tmp_path / "p.png").rgba, im.Image.read(tmp_path / "v.png").rgba
    assert ours.shape == theirs.shape and ours.shape[1] > 160  # a figure around the 96 x 160 image
    assert ours.tobytes() == theirs.tobytes()
    texts = png_texts(tmp_path / "p.png")
    assert texts["Vertical exaggeration"] == png_texts(tmp_path / "v.png")["Vertical exaggeration"]
    assert texts["Quantity"] == "local force f / (E* δ²)"
    assert figure._repr_png_().startswith(b"\x89PNG")


def test_view3d_figure_in_units(rough64, tmp_path):
    im.View3DFigure(rough64, force=np.maximum(rough64, 0), force_unit="N", width=64, height=48, samples=1,
                    mesh_side=32).save(tmp_path / "n.png")
    assert png_texts(tmp_path / "n.png")["Quantity"] == "local force f / N"
    with pytest.raises(im.InvalidArgument, match="dpi"):
        im.View3DFigure(rough64, dpi=0, width=64, height=48).save(tmp_path / "z.png")
