"""Array functions as documented: the PSD's shells and their counts, the theory broadcasting over every
array argument, surface files that hold missing points keeping them, and a unit a file leaves unstated
said."""
import os
import warnings

import numpy as np
import pytest

import indentmap as im


def test_psd_counts_every_wavevector_once_and_nan_marks_the_empty_shells():
    heights = im.generate(16, seed=2)
    q, c, counts = im.psd(heights, bins=200, counts=True)
    assert counts.dtype == np.int64 and counts.shape == q.shape == c.shape == (200,)
    assert counts.sum() == 16 * 16 - 1  # every wavevector but q = 0, the mean's
    empty = counts == 0
    assert empty.any() and not empty.all()
    np.testing.assert_array_equal(np.isnan(q), empty)
    np.testing.assert_array_equal(np.isnan(c), empty)


def test_psd_without_counts_is_the_pair_it_was():
    heights = im.generate(32, seed=4)
    q, c = im.psd(heights, bins=16)
    q3, c3, _ = im.psd(heights, bins=16, counts=True)
    np.testing.assert_array_equal(q, q3)
    np.testing.assert_array_equal(c, c3)


def test_area_ratio_broadcasts_over_alpha():
    slopes = np.array([[0.02], [0.08]])
    angles = np.array([60.0, 70.0, 80.0, 85.0])
    k = 2.0
    rho = k / np.tan(np.radians(angles)) / (2 * slopes)  # eq. (7) in closed form, shape (2, 4)
    np.testing.assert_allclose(im.theory.rho_c(slopes, alpha=angles, k=k), rho, rtol=1e-14)
    expected = im.theory.area_ratio_eq12(im.theory.beta(rho))
    ratio = im.theory.area_ratio(slopes, alpha=angles)
    assert ratio.shape == (2, 4)
    np.testing.assert_allclose(ratio, expected, rtol=1e-14)
    assert ratio[1, 2] == im.theory.area_ratio(0.08, alpha=80.0)


def test_write_keeps_missing_points_in_every_format(tmp_path):
    heights = np.arange(12.0).reshape(3, 4)
    heights[1, 2] = np.nan
    im.write(tmp_path / "s.npy", heights, delta=0.5, unit="um")
    np.testing.assert_array_equal(np.load(tmp_path / "s.npy"), heights)  # numpy's own reading: NaN where it was
    im.write(tmp_path / "s.txt", heights, delta=0.5, unit="um")
    np.testing.assert_array_equal(np.loadtxt(tmp_path / "s.txt", comments="#"), heights)
    for suffix in (".npy", ".txt", ".sdf", ".nc", ".gsf", ".x3p"):  # .x3p in its validity mask (finding R14)
        path = tmp_path / f"t{suffix}"
        im.write(path, heights, delta=0.5, unit="um")
        # the remedy in Python's words too (DA9: the message named the program's --fill only)
        with pytest.raises(im.FormatError, match=r"\(x=2, y=1\): a missing point.*fill=True"):
            im.read(path)
        filled = im.read(path, fill=True).heights
        assert np.isfinite(filled).all() and filled.shape == heights.shape


def test_write_refuses_what_no_format_can_hold(tmp_path):
    heights = np.zeros((3, 4))
    heights[1, 2] = np.inf
    for suffix in (".npy", ".gsf", ".x3p"):
        with pytest.raises(im.InvalidArgument, match=r"\(x=2, y=1\)"):
            im.write(tmp_path / f"s{suffix}", heights, delta=0.5, unit="um")
        assert not (tmp_path / f"s{suffix}").exists()


def test_read_warns_of_a_height_unit_the_file_does_not_state(tmp_path):
    """A Gwyddion text export without its `# Value units:` line (finding D8b): heights taken in the Width's
    unit, with a UserWarning naming the file and the unit, as `surface --stats` warns; none with the line or
    with height_unit."""
    source = os.path.join(os.environ.get("IM_SOURCE_DIR", ""), "tests", "data", "instruments", "matrix-3.txt")
    with open(source, encoding="utf-8") as original:
        lines = original.readlines()
    cut = tmp_path / "no-value-units.txt"
    cut.write_text("".join(line for line in lines if not line.startswith("# Value units:")), encoding="utf-8")
    with pytest.warns(UserWarning, match=r"no-value-units.txt: no '# Value units:' line: its heights are taken in µm"):
        taken = im.read(cut)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        stated = im.read(source)
        converted = im.read(cut, height_unit="m")
    assert taken.unit == stated.unit == converted.unit == "µm"
    np.testing.assert_allclose(taken.heights * 1e6, stated.heights, rtol=1e-12)
    np.testing.assert_array_equal(converted.heights, stated.heights)
