"""Rough surfaces: synthesis, statistics, spectra and files (the library's surface.h and formats.h)."""
import json
import os
import warnings
from typing import NamedTuple

import numpy as np

from . import _checks, _core
from ._core import FormatError


class Topography(NamedTuple):
    """Heights read from a file: ``heights[y, x]``, the grid spacing and its unit ("" if none).

    Example: ``t = im.read("scan.x3p"); t.heights.shape, t.delta, t.unit``."""
    heights: np.ndarray
    delta: float
    unit: str


class Generated(NamedTuple):
    """A generated surface with its provenance: ``heights[y, x]`` in units of ``delta``, the grid spacing,
    and ``generator``, the record ``indentmap surface --out`` writes in its sidecar for the same parameters
    (a dict: nx, ny, delta, hurst, lambda_s, lambda_r, lambda_0, target, slope_rms, height_rms,
    slope_definition, seed; ``read_generator``).

    Example: ``s = im.generate_recorded(256, slope=0.1, seed=7)``, then
    ``im.write("s.npy", s.heights, s.delta, generator=s.generator)``."""
    heights: np.ndarray
    delta: float
    generator: dict


def _generator_arguments(n, m, delta, hurst, lambda_s, lambda_r, lambda_0, slope, height_rms, slope_definition,
                         seed):
    """generate's arguments, checked, as the library's generator takes them."""
    n = _checks.integer("n", n)
    m = n if m is None else _checks.integer("m", m)
    lambda_r = float(max(n, m)) if lambda_r is None else _checks.real("lambda_r", lambda_r)  # the longer side
    lambda_0 = _checks.real("lambda_0", lambda_0)
    if lambda_0 != 0 and not lambda_0 >= lambda_r:  # a longest wave shorter than the roll-off: no plateau
        raise ValueError(f"lambda_0 = {lambda_0:g}: expected >= lambda_r = {lambda_r:g} (lambda_0 > lambda_r adds "
                         "a roll-off plateau; 0, the default, none)")
    return (n, m, _checks.real("delta", delta), _checks.real("hurst", hurst), _checks.real("lambda_s", lambda_s),
            lambda_r, lambda_0, _checks.real("slope", slope),
            None if height_rms is None else _checks.real("height_rms", height_rms),
            _checks.text("slope_definition", slope_definition), _checks.seed(seed))


def generate(n=512, m=None, *, delta=1.0, hurst=0.8, lambda_s=4.0, lambda_r=None, lambda_0=0.0, slope=0.08,
             height_rms=None, slope_definition="spectral", seed=1):
    """An isotropic self-affine Gaussian surface (the paper's section 2.2) as an (m, n) array.

    The same seed gives the same surface for any thread count. ``slope`` is the target h'rms
    (``slope_definition`` 'spectral' or 'fd'), or give ``height_rms`` (in units of delta) instead.
    ``lambda_r`` defaults to the longer side, max(n, m), as ``indentmap surface``'s; ``lambda_0 > lambda_r`` adds a roll-off plateau. ``seed`` is an integer in
    [0, 2^64 - 1]. An argument of the wrong kind raises TypeError, a value out of its range ValueError
    (``InvalidArgument`` from the library), naming the parameter and what was expected.

    Returns a new (m, n) float64 array of heights in units of delta. The array does not say that it was
    generated: ``generate_recorded`` gives it with its generator's record, for ``write`` to keep.

    Example: ``h = im.generate(256, hurst=0.8, slope=0.1, seed=7)``.
    """
    return _core.generate(*_generator_arguments(n, m, delta, hurst, lambda_s, lambda_r, lambda_0, slope, height_rms,
                                                slope_definition, seed))


def generate_recorded(n=512, m=None, *, delta=1.0, hurst=0.8, lambda_s=4.0, lambda_r=None, lambda_0=0.0, slope=0.08,
                      height_rms=None, slope_definition="spectral", seed=1):
    """``generate``'s surface (the same arguments, the same heights) with its provenance: a ``Generated``
    (heights, delta, generator), ``generator`` being the record ``indentmap surface --out`` writes in its
    sidecar for the same parameters (``lambda_0`` in effect: ``lambda_r`` without a plateau).

    ``write(path, s.heights, s.delta, generator=s.generator)`` writes the file with that sidecar, so that ``indentmap indent``, scenes'
    ``file =`` and ``indent_run`` take it as the generated, periodic surface it is (the spectral h'rms,
    as for the program's file: docs/theory.md), and ``read_generator(path)`` gives the record back.

    Example: ``s = im.generate_recorded(128, slope=0.1, seed=11)``, then
    ``im.write("s.npy", s.heights, s.delta, generator=s.generator)``."""
    arguments = _generator_arguments(n, m, delta, hurst, lambda_s, lambda_r, lambda_0, slope, height_rms,
                                     slope_definition, seed)
    return Generated(_core.generate(*arguments), arguments[2], json.loads(_core.generator_record(*arguments)))


def read_generator(path):
    """The generator's record in the sidecar PATH.json of a surface file (a dict, as ``Generated.generator``),
    or None when the file has no sidecar or its sidecar names no generator (a measured surface, or one
    written without ``generator``). ``indentmap indent`` takes the h'rms definition the generator targeted
    (the record's ``slope_definition``) for a file whose sidecar names one, and scenes' ``file =`` the
    spectral one when every file's names a generator of spectral h'rms; an array has no sidecar, so
    ``Indentation`` and ``indent`` take forward differences unless told: with ``g = im.read_generator(path)``,
    ``slope_definition={"spectral": "spectral", "finite-difference": "fd"}[g["slope_definition"]] if g else
    None`` gives ``indent``'s numbers.
    ``FormatError`` names a sidecar that is not a JSON object. The seed is the unsigned 64-bit integer
    ``--seed`` takes (0 to 2**64 - 1), also from a file of an earlier build, which wrote a seed of 2**63 or
    more as its two's complement, a negative integer.

    Example: ``im.read_generator("s.npy")["seed"]``."""
    sidecar = os.fsencode(_checks.path("path", path)) + b".json"
    try:
        with open(sidecar, "rb") as stream:
            record = json.load(stream)
    except FileNotFoundError:
        return None
    except ValueError as error:
        raise FormatError(f"{os.fsdecode(sidecar)}: not a JSON sidecar ({error})") from None
    if not isinstance(record, dict):
        raise FormatError(f"{os.fsdecode(sidecar)}: expected a JSON object, the sidecar of a surface file")
    generator = record.get("generator")
    seed = generator.get("seed") if isinstance(generator, dict) else None
    if type(seed) is int and -2**63 <= seed < 0:  # an earlier build's two's complement of a seed >= 2**63
        generator = dict(generator, seed=seed + 2**64)
    return generator


def statistics(heights, delta=1.0, window="none", alpha=0.5):
    """Mean, h_rms, h'rms (``slope_rms_spectral``: the band-limited interpolant's; ``slope_rms_fd``: forward
    differences), curvature rms, the profile moments m0, m2, m4, Nayak's parameter and the height range.

    ``window`` ('none', 'hann' or 'tukey' with the tapered fraction ``alpha``) takes the spectral quantities
    from a windowed copy: use it, after ``prepare``, for measured (non-periodic) data, whose plain spectral
    h'rms is dominated by the step at the edges of the periodic box. Synthesised surfaces are periodic:
    no window.

    Returns a dict of these numbers (lengths in the units of ``delta``); ``NumericError`` for a
    NaN or infinite height.

    Example: ``im.statistics(im.generate(128))["slope_rms_spectral"]`` is 0.08."""
    return _core.statistics(heights, float(delta), window, float(alpha))


def prepare(heights, detrend="plane", fill=False, align="none"):
    """A prepared copy of measured heights: missing points (NaN) refused with the first one's position, or
    with ``fill=True`` filled from their known neighbours (rim inwards); then the scan lines (rows)
    aligned (``align='median'``, 'mean' or 'line': each row's offset or tilt removed, as ``--align``
    does); then the least-squares plane (``detrend='plane'``: mean and tilt) or quadric ('curvature':
    also the bow) removed ('none': kept). Crop with numpy slicing. Returns (heights, number of points
    filled).

    ``InvalidArgument`` names the first missing point without ``fill`` and an unknown ``detrend`` or
    ``align``.

    Example: ``heights, filled = im.prepare(im.read("scan.x3p", fill=True).heights, align="median")``."""
    return _core.prepare(heights, detrend, bool(fill), align)


def psd(heights, delta=1.0, bins=64, counts=False):
    """The radially averaged power spectral density: (q, C_iso(q)) as two arrays, and with ``counts=True``
    a third, the number of wavevectors averaged in each shell (int64; they sum to the grid's points less
    one, the mean's).

    q = 2 pi / wavelength in inverse units of ``delta`` (each shell's mean |q|), C_iso = |h~(q)|^2 / A in
    length^4 (Jacobs, Junge and Pastewka 2017), in ``bins`` shells of equal width in log q from the
    grid's lowest q to its highest. A shell that no wavevector of the grid falls in (count 0: at the
    low end, where the grid's q are sparse on a log scale) has q and C NaN.

    Example: ``q, c = im.psd(im.generate(256), bins=32); ok = np.isfinite(c)``, then
    ``np.polyfit(np.log(q[ok]), np.log(c[ok]), 1)[0]`` is about -2(1 + H)."""
    q, c, shell_counts = _core.psd(heights, float(delta), int(bins))
    return (q, c, shell_counts) if counts else (q, c)


_QUANTITIES = {"height": 0, "slope": 1, "curvature": 2}


def histogram(heights, quantity="height", bins=64, delta=1.0):
    """Probability density of heights (about the mean), slopes (both components) or curvatures:
    (bin centres, density).

    Example: ``x, density = im.histogram(h, "slope", bins=50)``; ``np.trapz(density, x)`` is about 1."""
    if quantity not in _QUANTITIES:
        raise ValueError(f"quantity {quantity!r}: expected one of {sorted(_QUANTITIES)}")
    return _core.histogram(heights, float(delta), _QUANTITIES[quantity], int(bins))


_NPY_ORDERS = {None: 0, "yx": 1, "xy": 2}


def _npy_order_code(npy_order):
    """``npy_order`` as the library's enum im_npy_order; ValueError naming it otherwise."""
    if npy_order not in _NPY_ORDERS:
        raise ValueError(f"npy_order {npy_order!r}: expected 'yx', 'xy' or None (the sidecar's order, else yx)")
    return _NPY_ORDERS[npy_order]


def read(path, channel=None, fill=False, resample_square=False, npy_order=None, *, unit="", height_unit="",
         length_unit=""):
    """Reads a surface file (.npy with its sidecar, .gsf, .sdf, .nc, .x3p, text, or an instrument's file
    through Gwyddion's file modules when the build has them: ``indentmap formats`` lists them): a
    Topography (heights, delta, unit), heights and spacing both in ``unit`` ("" when the file gives
    none). ``channel`` (an index or a title) chooses the channel of a multi-channel instrument file
    (default: the first holding heights); ``fill=True`` fills missing (masked) points from their
    neighbours, which are refused otherwise, as ``indent --fill`` does.

    ``npy_order`` says which index of a .npy array is x: ``"yx"`` (rows are y, as ``heights`` here are
    indexed [y, x]) or ``"xy"`` (the first index is x, as SurfaceTopography's ``heights()``: such an
    array is transposed); None (default) takes the sidecar's ``"order"``, else ``"yx"``. Other
    formats ignore it.

    Pixels whose x and y spacings differ by at most 2^-16 of their mean (what rounding in headers and
    float32 storage explains) are read as square, of their mean spacing; a text header that prints its
    extents with fewer digits (Gwyddion's "# Width: 87.6 µm") widens that to what the digits leave open,
    up to 0.002. Beyond that a FormatError names
    both spacings, unless ``resample_square=True``: then the heights are resampled bilinearly onto
    square pixels of the finer spacing, within the stored extent (more rows or columns; ``delta`` is
    that spacing).

    Units, as ``indentmap indent --unit --height-unit --length-unit`` (and ``surface --stats --height-unit``)
    take them: length units m, cm, mm, µm (or um), nm, pm or Å; "" (default) keeps the file's.
    ``unit`` is the unit of the spacing, overriding the file's; ``height_unit`` the unit of the heights
    (default: the spacing's), converted into the spacing's; ``length_unit`` converts spacing and heights
    into it (the file's unit must be known: ``FormatError`` otherwise). A name that is no length unit
    raises ValueError naming the parameter. The Topography's ``unit`` is the one the heights are in. A
    unit taken that the file does not state (a Gwyddion text export without ``# Value units:``: heights
    in its Width's unit) gives a ``UserWarning`` naming the file and the unit, unless ``height_unit`` is given.

    Example: ``t = im.read("scan.npy", unit="um", length_unit="m")`` gives heights and ``t.delta`` in
    metres, ``t.unit == "m"``; ``im.indent(t.heights, delta=t.delta, length_unit=t.unit, e_star=1e9,
    e_star_unit="Pa", loads=[1e-6])`` then records loads in N."""
    heights, delta, unit, assumed = _core.read_surface(
        path, "" if channel is None else str(channel), bool(fill), bool(resample_square), _npy_order_code(npy_order),
        _checks.text("unit", unit), _checks.text("height_unit", height_unit), _checks.text("length_unit", length_unit))
    if assumed:  # a unit the file does not state, as `indentmap surface --stats` warns
        warnings.warn(f"{os.fsdecode(path)}: {assumed} (height_unit= states theirs)", stacklevel=2)
    return Topography(heights, delta, unit)


def write(path, heights, delta=1.0, unit="", *, generator=None):
    """Writes heights (in ``unit``, as the spacing ``delta``) as .npy, .gsf, .sdf, .nc, .x3p or a text
    matrix, by extension, atomically; the format records the spacing and unit (a .npy in its sidecar
    PATH.json). NaN heights (missing points) are kept by every format (.x3p in its validity mask), and
    ``read`` takes them back as missing (refused, or filled with ``fill=True``). A path that is a symbolic
    link is written through: its target is replaced, the link stays.

    ``generator``: the record of the generator that made the heights (``generate_recorded``'s, or
    ``read_generator``'s of another file): the sidecar PATH.json is then, for any format, the one
    ``indentmap surface --out`` writes (the record, the grid and the statistics: for the same surface the
    same bytes), and ``indentmap indent``, scenes and ``indent_run`` read the file as that generated
    surface. The record must hold exactly its keys, of their types and in range, for the heights' shape
    (nx, ny) and ``delta``, without NaN heights: else ``InvalidArgument`` (``NumericError`` for NaN)
    naming ``generator`` and the key; a record that is not a dict raises TypeError.

    ``FileError`` when the file cannot be written (nothing is left); ``InvalidArgument`` for an
    unknown extension, an infinite height (naming the first one's x, y), or a loop of links.

    Example: ``im.write("surface.x3p", h, delta=0.5, unit="µm")``."""
    _core.write_surface(path, heights, float(delta), unit, None if generator is None else _generator_text(generator))


def _generator_text(generator):
    """A generator record (a dict) as the JSON text the library parses and checks."""
    if not isinstance(generator, dict):
        raise TypeError(f"generator: expected a dict, the generator's record (Generated.generator), got "
                        f"{type(generator).__name__}")
    try:
        return json.dumps(generator, allow_nan=False)
    except (TypeError, ValueError) as error:
        raise ValueError(f"generator: expected a record of numbers and strings ({error})") from None
