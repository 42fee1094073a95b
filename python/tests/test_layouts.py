"""Layouts of files other programs write (issue 25): .npy arrays indexed [x, y], as SurfaceTopography's
heights() are, and .gsf files in metres, as Gwyddion writes and reads them."""
import json

import numpy as np
import pytest

import indentmap as im


def xy_array():
    """A 128 x 64 surface as SurfaceTopography holds it: h[x, y], shape (128, 64)."""
    x, y = np.meshgrid(np.arange(128), np.arange(64), indexing="ij")
    return 0.01 * x - 0.003 * y + 0.05 * np.sin(0.3 * x) * np.cos(0.2 * y)


def test_npy_order_xy_transposes(tmp_path):
    h = xy_array()
    path = tmp_path / "xy.npy"
    np.save(path, h)
    assert im.read(path).heights.shape == (128, 64)  # rows along y: read as 64 x 128
    top = im.read(path, npy_order="xy")
    assert top.heights.shape == (64, 128)
    np.testing.assert_array_equal(top.heights, h.T)  # heights[y, x] = h[x, y]
    np.save(path, np.asfortranarray(h))  # the order is of the indices, not of the memory
    np.testing.assert_array_equal(im.read(path, npy_order="xy").heights, h.T)


def test_sidecar_order_and_the_keyword_over_it(tmp_path):
    h = xy_array()
    path = tmp_path / "st.npy"
    np.save(path, h)
    (tmp_path / "st.npy.json").write_text(json.dumps({"delta": 2.5e-8, "unit": "m", "order": "xy"}))
    top = im.read(path)
    np.testing.assert_array_equal(top.heights, h.T)
    assert top.delta == 2.5e-8 and top.unit == "m"
    assert im.read(path, npy_order="yx").heights.shape == (128, 64)
    with pytest.raises(ValueError, match="npy_order 'x': expected 'yx', 'xy' or None"):
        im.read(path, npy_order="x")


def test_gsf_is_written_in_metres(tmp_path):
    heights = im.generate(32, slope=0.05, lambda_s=2, seed=6) * 0.05  # micrometres
    path = tmp_path / "s.gsf"
    im.write(path, heights, delta=0.05, unit="um")
    assert b"\nXYUnits = m\nZUnits = m\n" in path.read_bytes()[:256]
    top = im.read(path)
    assert top.unit == "m" and top.delta == pytest.approx(5e-8, rel=1e-15)
    np.testing.assert_allclose(top.heights, heights * 1e-6, rtol=1e-7, atol=0)
