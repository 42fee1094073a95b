"""Pictures from arrays: sizes, colours, figures, notebook display."""
import threading

import numpy as np
import pytest

import indentmap as im
from conftest import gil_held_share, run_cli

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


def test_contact_map_refuses_an_infinite_force():
    """A force is finite (NaN marks no data): +-Inf is refused naming the first such patch (x, y), not drawn in the
    over colour as a large force (S10); NaN stays the bad colour."""
    force = np.ones((4, 5))
    force[0, 0] = np.nan
    force[2, 3] = -np.inf  # row y = 2, column x = 3
    with pytest.raises(im.InvalidArgument, match=r"force -inf at patch \(3, 2\): expected a finite force"):
        im.contact_map(force)
    force[2, 3] = 1.0
    assert im.contact_map(force).rgba.shape == (4 * 2 + 4, 5 * 2 + 4, 4)


def test_contact_map_tension_on_the_blue_ramp():
    """Patches under tension (adhesion) take the C renderer's blue ramp: darker as the tension grows, blue
    over red and green, never the no-contact grey; the largest takes the ramp's darkest colour."""
    tensions = [0.05, 0.2, 0.4, 0.7, 1.0]
    force = np.array([[0.0] + [-t for t in tensions] + [0.5]])
    rgba = im.contact_map(force, scale=1).rgba[2, 2:-2, :3].astype(int)  # the one row of patches
    linear = np.where(rgba / 255 <= 0.04045, rgba / 255 / 12.92, ((rgba / 255 + 0.055) / 1.055) ** 2.4)
    luminance = linear @ np.array([0.2126, 0.7152, 0.0722])
    pulled = slice(1, 1 + len(tensions))
    assert (np.diff(luminance[pulled]) < 0).all()
    assert (rgba[pulled, 2] > rgba[pulled, 0]).all() and (rgba[pulled, 2] > rgba[pulled, 1]).all()
    assert not (rgba[pulled] == (230, 230, 230)).all(axis=1).any() and tuple(rgba[0]) == (230, 230, 230)
    darkest = im.contact_map(np.array([[-3.0]]), scale=1).rgba[2, 2, :3]
    assert tuple(rgba[len(tensions)]) == tuple(darkest)


def test_contact_map_defaults_to_the_frames_norm(rough64):
    """Forces default to every front end's map and norm (render contact, scenes, indent --frames): magma on a
    log norm over the two decades below the largest force; log=False is linear from 0."""
    force = np.clip(rough64 - np.median(rough64), 0.0, None)
    frames = im.contact_map(force, colormap="magma", log=True, vmin=0.01 * force.max(), vmax=force.max()).rgba
    assert (im.contact_map(force).rgba == frames).all()
    linear = im.contact_map(force, log=False, colormap="viridis").rgba
    assert (linear == im.contact_map(force, log=False, colormap="viridis", vmin=0.0, vmax=force.max()).rgba).all()
    assert not (linear == frames).all()
    figure = im.Figure([force])
    assert figure.norm == (0.01 * force.max(), force.max())  # the program's bounds, bit for bit (colormap.h)
    assert figure.style["colormap"] == "magma" and figure.style["log"]


def test_default_norms_are_the_programs_where_values_are_missing_or_one():
    """The norms are the library's (colormap.h: im_colormap_range_norm), as `render` gives them: a NaN force
    is left out (the largest finite force is the top), a flat surface v takes [v - 1, v + 1], and a vmin not
    below the top is refused as the program refuses it."""
    force = np.array([[0.0, 2.0, np.nan], [4.0, -1.0, 0.0]])
    assert im.Figure([force]).norm == (0.01 * 4.0, 4.0)
    assert im.contact_map(force, log=False).texts["Norm"] == "linear [0, 4]"
    assert im.height_map(np.full((4, 4), 3.0)).texts["Norm"] == "linear [2, 4]"
    with pytest.raises(im.InvalidArgument):
        im.height_map(np.full((4, 4), 3.0), vmin=5.0)


def test_clip_cuts_numpys_percentiles_of_the_finite_values(rough64):
    """clip=P (render --clip): heights from np.percentile's P to its 100 - P over the finite values (NaN left out),
    forces up to the 100 - P percentile of those > 0 (the log norm two decades below it), for contact_map and a
    Figure's panels together; clip=0 is the default picture, bit for bit; [0, 50) or InvalidArgument."""
    heights = rough64.copy()
    heights[0, :] = 0.0  # a row of dropouts
    heights[5, 5], heights[9, 9], heights[7, 3] = np.nan, 40.0, -np.inf  # a missing point, a spike
    finite = heights[np.isfinite(heights)]
    for clip in (0.5, 2.0, 25.0):
        lo, hi = np.percentile(finite, [clip, 100 - clip])
        assert im.height_map(heights, clip=clip).texts["Norm"] == f"linear [{lo:.9g}, {hi:.9g}]"
    assert (im.height_map(heights, clip=0).rgba == im.height_map(heights).rgba).all()
    force = np.clip(rough64 - np.median(rough64), 0.0, None)
    force[3, 3] = 100 * force.max()  # a needle asperity
    top = np.percentile(force[force > 0], 99)
    assert im.contact_map(force, clip=1).texts["Norm"] == f"log [{top / 100:.9g}, {top:.9g}]"
    both = np.percentile(np.concatenate([force[force > 0], 2 * force[force > 0]]), 95)
    assert im.Figure([force, 2 * force], clip=5).norm == pytest.approx((both / 100, both), rel=1e-15)
    with pytest.raises(im.InvalidArgument, match="percent"):
        im.height_map(heights, clip=50)


def test_height_map_says_when_outliers_set_its_range(cli, tmp_path):
    """A relief of 1e-5 with dropouts (0) and spikes (3e-4): height_map warns as render height notes (findings
    S9), the same measured sentence from the same C function (colormap.h: im_colormap_outlier_note), in Python's
    words for the remedy; not with clip= or vmin=/vmax=, nor for a plain relief."""
    import math
    import subprocess
    import warnings
    values = [0.0 if i < 10 else 3e-4 if i % 131 == 7 else math.nan if i % 293 == 5 else
              1e-5 + 5e-6 * math.sin(0.05 * i) for i in range(1200)]
    heights = np.array(values).reshape(30, 40)
    np.save(tmp_path / "spiky.npy", heights)
    said = subprocess.run([cli, "render", "height", str(tmp_path / "spiky.npy"), "--out", str(tmp_path / "s.png")],
                          capture_output=True, text=True, check=True).stderr
    with pytest.warns(UserWarning) as warned:
        im.height_map(heights)
    assert len(warned) == 1
    note = str(warned[0].message)
    assert note.endswith("; clip=1 cuts 1% of the values at each end (or set vmin=/vmax=)")
    assert f"spiky.npy: {note.split('; clip=')[0]}; --clip 1 cuts 1% " in said
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        im.height_map(heights, clip=1)
        im.height_map(heights, vmin=0.0, vmax=3e-4)
        im.height_map(np.nan_to_num(np.where(heights > 1e-4, 1e-5, heights), nan=1e-5) + 1e-5 * np.eye(30, 40))


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


@pytest.mark.parametrize("call", ["contact_map", "height_map", "figure", "save"])
def test_drawing_releases_the_gil(call, tmp_path):
    """Pictures, figures and PNG files are drawn and written without the GIL, on the thread that asks (issue
    32: a render held the GIL throughout, and the context drew only on the thread that drew first)."""
    heights = im.generate(1024, slope=0.1, seed=3)
    force = np.maximum(heights, 0.0)
    im.renderer()  # the context opens once, with the GIL
    work = {"contact_map": lambda: im.contact_map(force, scale=2),
            "height_map": lambda: im.height_map(heights, scale=2, contact=force),
            "figure": lambda: im.Figure([force[:512, :512]] * 4, columns=2).save(tmp_path / "f.png"),
            "save": lambda: im.Image(np.full((2048, 2048, 4), 7, np.uint8)).save(tmp_path / "i.png")}[call]
    share, pause, duration = gil_held_share(lambda: work)
    # Held through the call, the GIL would stop this thread for the whole of it.
    assert share < 0.5, f"main thread paused {pause:.3f} s of a {duration:.3f} s {call}"


def test_pictures_from_threads_equal_those_of_one_thread(rough64):
    """Threads drawing at once take turns on the one context and draw what one thread draws."""
    force = np.maximum(rough64, 0.0)
    draws = [lambda: im.contact_map(force, scale=3, circle_radius=9.0).rgba,
             lambda: im.height_map(rough64, contact=force).rgba] * 4
    expected = [draw() for draw in draws]
    got = [None] * len(draws)
    threads = [threading.Thread(target=lambda k=k: got.__setitem__(k, draws[k]())) for k in range(len(draws))]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert all(g is not None and np.array_equal(g, e) for g, e in zip(got, expected))


@pytest.fixture
def restores_auto():
    yield
    im.use_backend("auto")


def test_use_backend_opens_the_one_named(restores_auto, rough64):
    assert im.use_backend("osmesa")["backend"] == "osmesa"
    assert im.renderer()["backend"] == "osmesa"
    assert im.contact_map(np.maximum(rough64, 0)).rgba.shape == (64 * 2 + 4, 64 * 2 + 4, 4)
    with pytest.raises(im.InvalidArgument, match="render backend 'vulkan': expected auto, egl or osmesa"):
        im.use_backend("vulkan")
    assert im.renderer()["backend"] == "osmesa"  # a refused name leaves the one in use


FRAMED_SCENE = """[scene]
name = framed
output = {output}
[surfaces]
n = 32
hurst = 0.8
lambda_s = 4
slopes = 0.08
seeds = 1
[punch]
shape = cone
alpha = 80
[loading]
control = load
load_star = 200
[output]
frames = yes
frame_count = 2
"""


def test_run_scene_renders_with_the_backend_named(tmp_path):
    scene = tmp_path / "framed.ini"
    scene.write_text(FRAMED_SCENE.format(output=tmp_path / "out"))
    lines = []
    im.run_scene(scene, backend="osmesa", log=lambda level, message: lines.append(message))
    assert any(line.startswith("rendering with osmesa") for line in lines), lines
    with pytest.raises(im.InvalidArgument, match="render backend 'vulkan': expected auto, egl or osmesa"):
        im.run_scene(scene, out=tmp_path / "never", backend="vulkan")
    assert not (tmp_path / "never").exists()


def test_a_topography_where_a_field_is_expected_names_what_to_pass(tmp_path):
    """Figure and view3d converted their fields in Python, where numpy spoke of a ragged sequence."""
    im.write(str(tmp_path / "s.npy"), np.arange(64.0).reshape(8, 8) / 64)
    top = im.read(str(tmp_path / "s.npy"))
    for what, call in (("field", lambda: im.contact_map(top)), ("field", lambda: im.height_map(top)),
                       ("panel field", lambda: im.Figure([top])), ("heights", lambda: im.view3d(top)),
                       ("displacement", lambda: im.view3d(top.heights, displacement=top))):
        with pytest.raises(TypeError, match=what + r": got a Topography .*top\.heights"):
            call()



def test_animate_writes_the_programs_gif_from_its_frames(cli, tmp_path, rough64):
    """render animate's GIF from Python (redteam5 P4: Python had no animation): the program's PNG frames read
    back and animated at the same fps are its GIF, byte for byte; errors name the frame and fps."""
    fields = im.indent(rough64, approaches=[0.5, 1.0, 1.5], fields=True)[1]
    inputs = []
    for i, field in enumerate(fields):
        inputs.append(tmp_path / f"force_{i}.npy")
        np.save(inputs[-1], field["force"])
    run_cli(cli, "render", "animate", *inputs, "--frames", tmp_path / "frames", "--fps", 4,
            "--out", tmp_path / "cli.gif")
    frames = [im.Image.read(tmp_path / "frames" / f"contact_{i:04d}.png") for i in range(len(fields))]
    im.animate(frames, tmp_path / "python.gif", fps=4)
    assert (tmp_path / "python.gif").read_bytes() == (tmp_path / "cli.gif").read_bytes()
    with pytest.raises(ValueError, match=r"frames\[1\]: expected an \(height, width, 4\) uint8 RGBA array"):
        im.animate([frames[0], np.zeros((4, 4))], tmp_path / "bad.gif")
    with pytest.raises(TypeError, match=r"frames: expected a list of Images or RGBA arrays, got int"):
        im.animate(5, tmp_path / "bad.gif")
    with pytest.raises(im.InvalidArgument, match=r"fps = 0: expected 0.01 <= fps <= 100"):
        im.animate(frames, tmp_path / "bad.gif", fps=0)
    with pytest.raises(im.InvalidArgument, match=r"frame 1 is \d+ x \d+ \(or empty\): expected"):
        im.animate([frames[0], im.contact_map(fields[0]["force"])], tmp_path / "bad.gif")
    with pytest.raises(im.InvalidArgument, match=r"frame 0 is 0 x 0: expected at least 1 x 1 pixels"):
        im.animate([np.zeros((0, 0, 4), np.uint8)], tmp_path / "empty.gif")
    assert not (tmp_path / "empty.gif").exists()
