"""Pictures: contact maps (the paper's Fig. 4) and height fields as RGBA arrays, and multi-panel
figures as PNG, PDF or SVG (the library's render.h and figure.h). One off-screen OpenGL context
(EGL, or OSMesa) is opened at the first picture; pictures are drawn without the GIL, from any thread,
one at a time."""
import os
import tempfile

import numpy as np

from . import _core


def renderer():
    """The OpenGL backend and renderer in use: {'backend', 'gl_renderer', 'gl_version'}."""
    return _core.renderer()


def _png_bytes(write):
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "picture.png")
        write(path)
        with open(path, "rb") as f:
            return f.read()


class Image:
    """A rendered picture: ``rgba`` is (height, width, 4) uint8, row 0 at the top. A notebook shows it."""

    def __init__(self, rgba):
        self.rgba = rgba

    def save(self, path):
        """Writes a PNG (atomically)."""
        _core.write_png(path, self.rgba)

    def _repr_png_(self):
        return _png_bytes(self.save)


def _contact_norm(force, vmin, vmax, log):
    largest = float(np.max(force)) if np.size(force) else 0.0
    vmax = vmax if vmax is not None else (largest if largest > 0 else 1.0)
    vmin = vmin if vmin is not None else (vmax / 100.0 if log else 0.0)  # two decades, as the frames'
    return vmin, vmax


def contact_map(force, *, delta=1.0, colormap="magma", vmin=None, vmax=None, log=True, scale=2,
                circle_radius=0.0, circle_centre=None):
    """Patches in contact (force > 0) coloured by their force, the others grey; optionally the smooth
    contact circle (radius and centre in patches). The defaults are every front end's for forces (``indentmap
    render contact``, scenes, ``indent --frames``): magma on a log norm from a hundredth of the largest force
    to it; ``log=False``: linear from 0."""
    lo, hi = _contact_norm(force, vmin, vmax, log)
    cx, cy = (float("nan"), float("nan")) if circle_centre is None else circle_centre
    return Image(_core.render(force, float(delta), height_map=False, colormap=colormap, vmin=lo, vmax=hi, log=log,
                              scale=int(scale), circle_radius=float(circle_radius), circle_x=cx, circle_y=cy,
                              contact=None))


def height_map(heights, *, delta=1.0, colormap="viridis", vmin=None, vmax=None, scale=2, contact=None):
    """Heights coloured and hill-shaded; ``contact`` (forces) outlines the patches in contact."""
    lo = float(np.min(heights)) if vmin is None else vmin
    hi = float(np.max(heights)) if vmax is None else vmax
    if not hi > lo:
        hi = lo + 1.0
    return Image(_core.render(heights, float(delta), height_map=True, colormap=colormap, vmin=lo, vmax=hi, log=False,
                              scale=int(scale), circle_radius=0.0, circle_x=0.0, circle_y=0.0, contact=contact))


class Figure:
    """Panels of force fields with one shared norm and colour bar, like the paper's Fig. 4.

    ``Figure(fields, columns=3, labels=['(a)', ...], titles=[...])``; ``save('fig.pdf')`` writes PNG,
    PDF or SVG by extension; a notebook shows it as PNG. Norm defaults as ``contact_map``'s (magma, log).
    """

    def __init__(self, fields, *, delta=1.0, columns=None, labels=None, titles=None, colormap="magma", vmin=None,
                 vmax=None, log=True, scale=2, circle_radius=0.0, colorbar_label="local force f / (E* δ²)",
                 dpi=300.0, scale_bar=0.0):
        self.fields = [np.asarray(f, dtype=float) for f in fields]
        if not self.fields:
            raise ValueError("Figure: no fields")
        largest = max(float(np.max(f)) for f in self.fields)
        self.norm = _contact_norm(np.array([largest]), vmin, vmax, log)
        self.columns = len(self.fields) if columns is None else int(columns)
        self.labels, self.titles = labels, titles
        self.style = dict(height_map=False, colormap=colormap, log=log, scale=int(scale),
                          circle_radius=float(circle_radius), circle_x=float("nan"), circle_y=float("nan"),
                          contact=None)
        self.delta, self.colorbar_label, self.dpi, self.scale_bar = float(delta), colorbar_label, dpi, scale_bar

    def save(self, path):
        """Writes the figure (atomically); the format follows the extension: .png, .pdf or .svg."""
        labels = None if self.labels is None else list(self.labels)
        titles = None if self.titles is None else list(self.titles)
        _core.figure(path, self.fields, self.delta, labels, titles, self.columns, self.colorbar_label,
                     float(self.dpi), float(self.scale_bar), vmin=self.norm[0], vmax=self.norm[1], **self.style)

    def _repr_png_(self):
        return _png_bytes(self.save)
