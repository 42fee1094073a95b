"""Pictures from arrays: sizes, colours, figures, notebook display."""
import numpy as np
import pytest

import indentmap as im

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def test_contact_map_pixels():
    force = np.zeros((8, 10))
    force[2, 3] = 1.0  # row y = 2, column x = 3
    rgba = im.contact_map(force, scale=4).rgba
    assert rgba.shape == (8 * 4 + 4, 10 * 4 + 4, 4)  # 2-pixel boundary on each side
    # y up: row y = 2 of 8 is the 6th row of patches from the top
    top, left = 2 + (8 - 1 - 2) * 4, 2 + 3 * 4
    patch = rgba[top:top + 4, left:left + 4, :3]
    background = rgba[2 + 1, 2 + 1, :3]
    assert (patch == patch[0, 0]).all() and not (patch[0, 0] == background).all()
    assert tuple(background) == (230, 230, 230)


def test_height_map_and_png(tmp_path, rough64):
    picture = im.height_map(rough64, scale=1)
    assert picture.rgba.shape[:2] == (64 + 4, 64 + 4)
    png = picture._repr_png_()
    assert png.startswith(PNG_SIGNATURE)
    picture.save(tmp_path / "h.png")
    assert (tmp_path / "h.png").read_bytes() == png


def test_figure_formats(tmp_path, rough64):
    run = im.Indentation(rough64, largest=2.0)
    run.step(1.0)
    first = run.fields()[0]
    run.step(2.0)
    second = run.fields()[0]
    figure = im.Figure([first, second], columns=2, labels=["(a)", "(b)"], colormap="magma", log=True)
    assert figure._repr_png_().startswith(PNG_SIGNATURE)
    for suffix, magic in ((".pdf", b"%PDF"), (".svg", b"<?xml")):
        figure.save(tmp_path / f"f{suffix}")
        assert (tmp_path / f"f{suffix}").read_bytes().startswith(magic)
    with pytest.raises(im.InvalidArgument, match="panels"):
        im.Figure([first, second, first], columns=2).save(tmp_path / "g.png")
    with pytest.raises(im.InvalidArgument):
        im.contact_map(first, colormap="rainbow")
