"""Pictures: contact maps (the paper's Fig. 4) and height fields as RGBA arrays, and multi-panel
figures as PNG, PDF or SVG (the library's render.h and figure.h). One off-screen OpenGL context
(EGL, or OSMesa) is opened at the first picture; pictures are drawn without the GIL, from any thread,
one at a time."""
import inspect
import os
import tempfile
import warnings

from . import _checks, _core
from .solver import Cone, Flat, Sphere


def renderer():
    """The OpenGL backend and renderer in use: {'backend', 'gl_renderer', 'gl_version'}.

    ``Unsupported`` on a machine without an OpenGL 3.3 context.

    Example: ``im.renderer()["backend"]`` is 'egl' or 'osmesa'."""
    return _core.renderer()


def use_backend(backend):
    """Opens the OpenGL backend the pictures are drawn with from now on, as the program's ``--backend``:
    'auto' (EGL, else OSMesa: what the first picture opens without this call), 'egl' or 'osmesa' (the
    program's IM_RENDER_BACKEND is its own; Python does not read it). The context in use before is closed
    once no picture is being drawn with it. Returns ``renderer()``'s dict for the new one.

    ``InvalidArgument`` for another name; ``Unsupported`` when that backend opens no OpenGL 3.3 context
    (the one in use before stays).

    Example: ``im.use_backend("osmesa")["backend"]`` is 'osmesa'."""
    return _core.use_backend(_checks.text("backend", backend))


def _png_bytes(write):
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "picture.png")
        write(path)
        with open(path, "rb") as f:
            return f.read()


class Image:
    """A rendered picture: ``rgba`` is (height, width, 4) uint8, row 0 at the top. A notebook shows it.

    ``texts`` ({key: value} of str) are what the picture shows, written as the PNG's text chunks as
    ``indentmap render --raw`` writes them: ``contact_map`` and ``height_map`` set 'Software', 'Quantity'
    (the colour bar's label in the field's units, e.g. 'local force f / N'), 'Colormap', 'Norm' and
    'Pixels per patch'.

    Example: ``im.contact_map(force).save("contact.png")``; ``image.rgba[0, 0]`` is the top-left pixel."""

    def __init__(self, rgba, texts=None):
        self.rgba = rgba
        self.texts = dict(texts or {})

    @classmethod
    def read(cls, path):
        """An 8-bit RGB or RGBA PNG file as an Image (RGB made opaque): the program's pictures and frames
        as arrays. ``FileError`` or ``FormatError`` naming the file.

        Example: ``im.Image.read("output/indent/frames/contact_0001.png").rgba.shape``."""
        return cls(_core.read_png(path))

    def save(self, path):
        """Writes a PNG (atomically), with ``texts`` as its text chunks.

        ``FileError`` naming the path when it cannot be written.

        Example: ``im.height_map(h).save("heights.png")``."""
        _core.write_png(path, self.rgba, tuple(self.texts.items()))

    def _repr_png_(self):
        return _png_bytes(self.save)


def animate(frames, path, *, fps=5.0):
    """Writes ``frames`` (a list of Images or (height, width, 4) uint8 RGBA arrays, all of one size) as a looping
    animated GIF at ``path``, at ``fps`` frames per second (0.01 to 100), as ``indentmap render animate
    --out FILE.gif --fps F`` writes its frames (figure.h: im_animation_gif): one palette of at most 256
    colours made from all the frames' pixels, exact when they have no more. Given the program's PNG frames
    (``render animate --frames DIR``) read back with ``Image.read``, it writes the program's GIF byte for
    byte. ``ValueError`` naming the first frame that is not an RGBA array; ``InvalidArgument`` naming a
    frame of another size or ``fps``; ``FileError`` naming the path.

    Example: ``im.animate([im.contact_map(f["force"], vmax=top) for f in fields], "contact.gif")`` (one
    ``vmax`` for all, as the program's shared norm)."""
    fps = float(fps)
    if not 0.01 <= fps <= 100.0:
        raise _core.InvalidArgument(f"fps = {fps:g}: expected 0.01 <= fps <= 100 (as render --fps)")
    if not isinstance(frames, (list, tuple)):
        raise TypeError(f"frames: expected a list of Images or RGBA arrays, got {type(frames).__name__}")
    pictures = [frame.rgba if isinstance(frame, Image) else frame for frame in frames]
    _core.write_gif(path, pictures, 1.0 / fps)


def _contact_norm(forces, what, vmin, vmax, log, clip=0.0):
    """(vmin, vmax) of the norm the force fields share, the library's for every front end (colormap.h:
    im_colormap_range_norm): 0 .. the largest finite force (1 without any; with ``clip`` P, the 100 - P
    percentile of the forces > 0), a log norm over the two decades below it, as the frames'; ``what`` names the
    fields in a TypeError."""
    return _core.norm_range(forces, what, False, vmin, vmax, bool(log), float(clip))


def _picture_texts(quantity, unit, colormap, norm, log, scale=None):
    """The text chunks of a picture, as ``indentmap render --raw`` writes them (but its record of the command:
    'Command', 'Directory' and 'Inputs'); a 3-D view (``scale`` None) has no pixels per patch."""
    texts = {"Software": f"indentmap {_core.library_version}", "Quantity": _core.colorbar_label(quantity, unit),
             "Colormap": colormap, "Norm": f"{'log' if log else 'linear'} [{norm[0]:.9g}, {norm[1]:.9g}]"}
    if scale is not None:
        texts["Pixels per patch"] = str(int(scale))
    return texts


def contact_map(force, *, delta=1.0, colormap="magma", vmin=None, vmax=None, log=True, clip=0.0, scale=2,
                circle_radius=0.0, circle_centre=None, unit="", force_unit=""):
    """Patches in contact (force > 0) coloured by their force, the others grey; optionally the smooth
    contact circle (radius and centre in patches). The defaults are every front end's for forces (``indentmap
    render contact``, scenes, ``indent --frames``): magma on a log norm from a hundredth of the largest force
    to it; ``log=False``: linear from 0; ``clip`` P (percent, [0, 50), ``render --clip``) tops it at the 100 - P
    percentile of the forces > 0 instead (a needle asperity's force), the forces above in the top colour. ``unit`` is the length unit of ``delta`` and ``force_unit`` that of the forces
    (``read(path).unit`` and ``Indentation(...).units["force"]``; "" for units of delta and E* δ²): the
    Image's 'Quantity' text then says 'local force f / N' as the program's pictures do.

    Returns an Image; ``InvalidArgument`` for a bad colour map or norm or an infinite force (a force is finite,
    NaN marks no data; the first such patch (x, y) named), ``Unsupported`` without OpenGL.

    Example: ``im.contact_map(force, delta=t.delta, unit=t.unit, force_unit=run.units["force"],
    log=True).texts["Quantity"]`` is 'local force f / N' for a run in m and Pa."""
    lo, hi = _contact_norm([force], "field", vmin, vmax, log, clip)
    cx, cy = (float("nan"), float("nan")) if circle_centre is None else circle_centre
    return Image(_core.render(force, float(delta), height_map=False, colormap=colormap, vmin=lo, vmax=hi, log=log,
                              scale=int(scale), circle_radius=float(circle_radius), circle_x=cx, circle_y=cy,
                              contact=None, unit=_core.length_unit("unit", unit)),
                 _picture_texts("force", force_unit, colormap, (lo, hi), log, scale))


def height_map(heights, *, delta=1.0, colormap="viridis", vmin=None, vmax=None, clip=0.0, scale=2, contact=None,
               unit="", quantity="height"):
    """Heights coloured and hill-shaded; ``contact`` (forces) outlines the patches in contact. ``unit`` is
    the length unit of ``delta`` and the heights ("" for units of delta); ``quantity`` what they are:
    'height', or a field of ``indent``: 'gap', 'displacement' or 'plastic' (the Image's 'Quantity' text,
    e.g. 'gap g / µm'). The norm is linear over the smallest .. largest finite height ([v - 1, v + 1] for a
    flat surface v), as ``indentmap render height`` draws it; ``clip`` P (percent, [0, 50), ``render --clip``)
    cuts P % of the finite heights at each end (the P and 100 - P percentiles, numpy.percentile's), for a scan
    whose few spikes or dropouts would make it one colour, the heights beyond in the ends' colours; ``vmin`` /
    ``vmax`` replace its ends. Where a few outliers set that range (the central 98 % of the heights span less
    than a twentieth of it) and neither ``clip`` nor ``vmin``/``vmax`` is given, a ``UserWarning`` says so and
    suggests ``clip=1``, the notice ``render height`` prints.

    Returns an Image; errors as ``contact_map``'s (``vmin`` not below the top, ``clip`` outside [0, 50):
    ``InvalidArgument``).

    Example: ``im.height_map(t.heights, delta=t.delta, unit=t.unit, contact=force).save("h.png")``."""
    lo, hi = _core.norm_range([heights], "field", True, vmin, vmax, False, float(clip))  # as render height's
    unit = _core.length_unit("unit", unit)
    if not clip and vmin is None and vmax is None:  # render height's notice, in Python's words
        note, _, percent = _core.outlier_note([heights], "field", unit)
        if note:
            warnings.warn(f"{note}; clip={percent:g} cuts {percent:g}% of the values at each end (or set vmin=/vmax=)",
                          stacklevel=2)
    return Image(_core.render(heights, float(delta), height_map=True, colormap=colormap, vmin=lo, vmax=hi, log=False,
                              scale=int(scale), circle_radius=0.0, circle_x=0.0, circle_y=0.0, contact=contact,
                              unit=unit),
                 _picture_texts(quantity, unit, colormap, (lo, hi), False, scale))


class Figure:
    """Panels of force fields with one shared norm and colour bar, like the paper's Fig. 4.

    ``Figure(fields, columns=3, labels=['(a)', ...], titles=[...])``; ``save('fig.pdf')`` writes PNG,
    PDF or SVG by extension; a notebook shows it as PNG. Norm defaults as ``contact_map``'s (magma, log; ``clip``
    over all the panels' forces). ``unit`` (the length unit of ``delta``) and
    ``force_unit`` label the scale bar ('10 µm') and the colour bar ('local force f / N') as
    ``indentmap render contact`` labels a force file of that run; ``colorbar_label`` overrides the
    colour bar's. ``scale_bar`` is the bar's length in the unit of ``delta`` (0: a 1-2-5 length near a
    fifth of a panel; negative: no bar); without ``unit`` the bar is drawn and labelled in patches, as
    the program draws a spacing without a unit: ``delta=1e-7, scale_bar=5e-6`` gives '50 δ'. Patches under tension (force < 0, adhesion) are drawn on the tension ramp, its range 0 to the
    largest tension of all the panels, with a second bar ('tensile force −f / N') when any panel has tension,
    as ``render contact`` draws them.

    Example: ``im.Figure([f1, f2], columns=2, labels=["(a)", "(b)"], delta=t.delta, unit=t.unit,
    force_unit="N").save("fig4.pdf")``.
    """

    def __init__(self, fields, *, delta=1.0, columns=None, labels=None, titles=None, colormap="magma", vmin=None,
                 vmax=None, log=True, clip=0.0, scale=2, circle_radius=0.0, colorbar_label=None,
                 dpi=300.0, scale_bar=0.0, unit="", force_unit=""):
        self.fields = [_core.heights_array(f, "panel field") for f in fields]
        if not self.fields:
            raise ValueError("Figure: no fields")
        self.norm = _contact_norm(self.fields, "panel field", vmin, vmax, log, clip)
        self.columns = len(self.fields) if columns is None else int(columns)
        self.labels, self.titles = labels, titles
        self.style = dict(height_map=False, colormap=colormap, log=log, scale=int(scale),
                          circle_radius=float(circle_radius), circle_x=float("nan"), circle_y=float("nan"),
                          contact=None, unit=_core.length_unit("unit", unit))
        if colorbar_label is None:
            colorbar_label = _core.colorbar_label("force", force_unit)
        self.tension_label = _core.colorbar_label("tension", force_unit)
        self.delta, self.colorbar_label, self.dpi = float(delta), colorbar_label, dpi
        # without a unit the bar counts patches (δ), as `indentmap render` draws a spacing without one: a
        # length in delta's unit is that many deltas (finding R4: 5e-6 at delta 1e-7 drew '5e-06 δ')
        bar = float(scale_bar)
        self.scale_bar = bar / self.delta if bar > 0 and self.delta > 0 and not self.style["unit"] else bar

    def save(self, path):
        """Writes the figure (atomically); the format follows the extension: .png, .pdf or .svg.
        ``InvalidArgument`` for another extension or panels that do not fill whole rows, ``FileError`` naming
        a path that cannot be written.

        Example: ``im.Figure([force], delta=t.delta, unit=t.unit, force_unit="N").save("contact.svg")``."""
        labels = None if self.labels is None else list(self.labels)
        titles = None if self.titles is None else list(self.titles)
        _core.figure(path, self.fields, self.delta, labels, titles, self.columns, self.colorbar_label,
                     self.tension_label, float(self.dpi), float(self.scale_bar), vmin=self.norm[0], vmax=self.norm[1], **self.style)

    def _repr_png_(self):
        return _png_bytes(self.save)


_PUNCH_MODES = {"translucent": 0, "opaque": 1, "cutaway": 2, "none": 3}


def _view3d_punch(punch):
    """(kind, alpha, radius) of view3d's punch: a Cone, Sphere or Flat of the solver, or None."""
    if punch is None:
        return "none", 80.0, 1.0
    kinds = {Cone: "cone", Sphere: "sphere", Flat: "flat"}
    if type(punch) not in kinds:
        raise TypeError(f"punch: expected Cone(), Sphere(R), Flat(a) or None, got {punch!r}")
    return kinds[type(punch)], getattr(punch, "alpha", 80.0), getattr(punch, "radius", 1.0)


def view3d(heights, *, force=None, displacement=None, delta=1.0, punch=Cone(), axis=None,
           punch_mode="translucent", azimuth=20.0, elevation=35.0, distance=None, fov=30.0, ortho=False,
           ortho_height=0.0, exaggeration=1.0, width=1920, height=1080, samples=4, mesh_side=384,
           colormap="magma", vmin=None, vmax=None, log=True):
    """The deformed surface in 3-D, as ``indentmap render view3d --raw`` draws it: an Image (a notebook
    shows it; ``Image.save`` writes the PNG), the same pixels as the program's for the same inputs.

    ``heights`` (ny, nx), in the units of ``delta``, minus ``displacement`` u when given (``indent``'s
    fields, positive into the half-space): the drawn surface is heights - u. Patches with ``force`` > 0
    are coloured by it through the norm, the others light grey (tensile ones light blue). ``punch``:
    Cone(alpha), Sphere(R), Flat(a) (lengths in the units of delta) or None, resting on the drawn heights,
    its axis at ``axis`` (x, y) (default: the centre of patch (nx/2, ny/2)), drawn ``punch_mode``
    'translucent', 'opaque', 'cutaway' or 'none'. Camera: ``azimuth`` (degrees; 0 looks from the map's
    bottom edge), ``elevation`` (1..90 degrees), ``distance`` in grid sides (None: the nearest that shows
    it all), ``fov`` (degrees), or ``ortho=True`` with ``ortho_height`` (patches; 0: fit).
    ``exaggeration`` scales heights; ``width`` x ``height`` pixels, ``samples`` (1, 2, 4 or 8) per pixel,
    ``mesh_side`` cells along the longer side. Norm: ``colormap`` (magma, viridis, cividis, inferno,
    grey), ``log=True`` from ``vmax`` / 100 (``--log``, the default) or linear from 0 (``--linear``),
    ``vmax`` the largest force by default. Values out of range raise ``InvalidArgument`` naming them;
    a machine without OpenGL 3.3 raises ``Unsupported``.

    Example: ``h, f = im.indent(s, approaches=[3.0], fields=True); im.view3d(s, force=f[0]["force"],
    displacement=f[0]["displacement"], exaggeration=4)``."""
    drawn = _core.heights_array(heights, "heights")
    if displacement is not None:
        u = _core.heights_array(displacement, "displacement")
        if u.shape != drawn.shape:
            raise ValueError(f"displacement: shape {u.shape}, expected the heights' {drawn.shape}")
        drawn = drawn - u
    if punch_mode not in _PUNCH_MODES:
        raise ValueError(f"punch_mode {punch_mode!r}: expected one of {list(_PUNCH_MODES)}")
    lo, hi = _contact_norm([] if force is None else [force], "force", vmin, vmax, log)
    kind, alpha, radius = _view3d_punch(punch)
    return Image(_core.view3d(drawn, float(delta), force, kind, float(alpha), float(radius),
                              None if axis is None else tuple(axis), punch_mode=_PUNCH_MODES[punch_mode],
                              azimuth=float(azimuth), elevation=float(elevation),
                              distance=None if distance is None else float(distance), fov=float(fov),
                              ortho=bool(ortho), ortho_height=float(ortho_height), exaggeration=float(exaggeration),
                              width=int(width), pixels_high=int(height), samples=int(samples),
                              mesh_side=int(mesh_side), colormap=colormap, vmin=float(lo), vmax=float(hi),
                              log=bool(log)))


class View3DFigure:
    """The 3-D view in the figure ``indentmap render view3d --out`` draws (without ``--raw``): ``view3d``'s
    image under its title (``title``, then the vertical exaggeration: 'indented, heights × 4'), beside the
    force's colour bar (and the tension's where the force has any) labelled in ``force_unit``
    (``Indentation(...).units["force"]``; "" for E* δ², the program's label), at ``dpi``. ``options`` are
    ``view3d``'s (heights, force, camera, punch, norm, size). ``save(path)`` writes PNG, PDF or SVG by
    extension; a notebook shows it as PNG. ``image`` is the 3-D view itself (an Image).

    Errors as ``view3d``'s; ``save`` raises ``InvalidArgument`` for another extension or a ``dpi`` outside
    (0, 2400], ``FileError`` naming a path that cannot be written.

    Example: ``im.View3DFigure(s, force=f[0]["force"], displacement=f[0]["displacement"], exaggeration=4,
    title="indented", dpi=150).save("view.pdf")``."""

    def __init__(self, heights, *, title=None, dpi=300.0, force_unit="", **options):
        bound = inspect.signature(view3d).bind(heights, **options)
        bound.apply_defaults()
        view = bound.arguments
        self.image = view3d(heights, **options)
        self.force = view["force"]
        self.norm = _contact_norm([] if self.force is None else [self.force], "force", view["vmin"], view["vmax"],
                                  view["log"])
        self.texts = _picture_texts("force", force_unit, view["colormap"], self.norm, view["log"])
        self.style = dict(title=_checks.text("title", title or ""), exaggeration=float(view["exaggeration"]),
                          colormap=view["colormap"], log=bool(view["log"]), dpi=float(dpi),
                          unit=_checks.text("force_unit", force_unit))

    def save(self, path):
        """Writes the figure (atomically); PNG, PDF or SVG by the extension.

        Example: ``figure.save("view.png")``."""
        _core.view3d_figure(path, self.image.rgba, self.force, tuple(self.texts.items()), vmin=float(self.norm[0]),
                            vmax=float(self.norm[1]), **self.style)

    def _repr_png_(self):
        return _png_bytes(self.save)
