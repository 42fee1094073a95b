"""Indentation of a rough surface by a rigid punch (the library's solver.h)."""
import inspect
import json
import logging
import os
import warnings
from dataclasses import dataclass

import numpy as np

from . import _checks, _core
from .surface import _npy_order_code


@dataclass(frozen=True)
class Cone:
    """A cone of semi-opening angle ``alpha`` degrees (the paper: 80).

    Example: ``im.indent(h, im.Cone(70), approaches=[1.0])`` indents with a 70° cone."""
    alpha: float = 80.0


@dataclass(frozen=True)
class Sphere:
    """A sphere of radius ``radius`` (in the units of delta).

    Example: ``im.indent(h, im.Sphere(200), loads=[5.0])``; lengths in the units of delta."""
    radius: float


@dataclass(frozen=True)
class Flat:
    """A flat cylindrical punch of radius ``radius``.

    Example: ``im.indent(h, im.Flat(20), approaches=[0.5])``; the radius in the units of delta."""
    radius: float


def _punch_arguments(punch):
    """(kind, alpha, radius, profile array or None) for _core.Indentation."""
    if isinstance(punch, Cone):
        return "cone", _checks.real("Cone.alpha", punch.alpha), 1.0, None
    if isinstance(punch, Sphere):
        return "sphere", 80.0, _checks.real("Sphere.radius", punch.radius), None
    if isinstance(punch, Flat):
        return "flat", 80.0, _checks.real("Flat.radius", punch.radius), None
    if isinstance(punch, np.ndarray):
        return "profile", 80.0, 1.0, punch
    raise TypeError(f"punch: expected Cone, Sphere, Flat or a profile array, got {punch!r}")


def _axis_on_surface(axis, shape, delta):
    """(x, y) of the punch's axis, checked to be two numbers on the surface (as ``indent --x --y``): one
    beyond it would only fail at the first step, as contact reaching the edge."""
    if isinstance(axis, (str, bytes)) or not hasattr(axis, "__len__") or len(axis) != 2:
        raise TypeError(f"axis: expected (x, y), two numbers, got {axis!r}")
    x, y = _checks.real("axis x", axis[0]), _checks.real("axis y", axis[1])
    if len(shape) == 2:  # else the heights are refused, naming them
        width, height = shape[1] * delta, shape[0] * delta
        if not (0 <= x <= width and 0 <= y <= height):
            raise ValueError(f"axis = ({x:g}, {y:g}): the punch's axis lies outside the {shape[1]} x {shape[0]} "
                             f"surface (expected 0 <= x <= {width:g} and 0 <= y <= {height:g})")
    return x, y


# Indentation's options that label what is written and change no solve.
_UNIT_OPTIONS = ("length_unit", "e_star_unit")

# The integer columns of a history (history.h: im_history_integer_columns); every other column is float64.
_INTEGER_COLUMNS = frozenset(_core.history_integer_columns.split(","))


def _history_array(values):
    """A structured array of a history's rows given as its columns' numbers (history.h:
    im_history_row_values): history.csv's column names, the integer columns int64."""
    names = _core.history_columns.split(",")
    values = np.asarray(values, dtype=float).reshape(-1, len(names))
    history = np.empty(len(values), dtype=[(name, "i8" if name in _INTEGER_COLUMNS else "f8") for name in names])
    for i, name in enumerate(names):
        history[name] = values[:, i]
    return history


def read_history(path):
    """A history.csv (``indentmap indent``) or a scene's histories/member_FF_SEED.csv as the structured
    array ``indent`` returns: the same columns, names and values.

    Raises ``ValueError`` naming the file for other columns (another version's history), a
    line with too few values or bytes that are not UTF-8 text, ``OSError`` for a file that cannot be read.

    Example: ``h = im.read_history("out/history.csv"); h["load"]``."""
    with open(path, encoding="utf-8") as f:
        try:
            text = f.read()
        except UnicodeDecodeError as error:
            raise ValueError(f"{path}: byte {error.start} is not UTF-8 text: expected a history.csv") from None
    lines = [line for line in text.splitlines() if line and not line.startswith("#")]  # a scene's note
    return _history_array(_core.history_values("".join(line + "\n" for line in lines), str(path)))


def _core_arguments(heights, punch, *, control, largest, delta, e_star, tol, max_iterations, crop, window_margin,
                    axis, device, hardness, periodic, slope_definition, adhesion_work, adhesion_range, quality,
                    plain_pk, measure, wisdom, adhesion_law, adhesion_zone):
    """Indentation's arguments checked and named as _core.Indentation and _core.indentation_window take them:
    (args, kwargs). The defaults are Indentation's signature's."""
    if tol is None:
        tol = _core.default_tol if quality is None else _core.quality_tolerance(_checks.text("quality", quality))
    if punch is None:
        if not periodic:
            raise ValueError("punch None (a rigid flat over the cell) needs periodic=True")
        ny, nx = np.shape(heights)
        punch = Flat(2.0 * np.hypot(nx, ny) * delta)  # wider than the cell: every nearest image
    kind, alpha, radius, profile = _punch_arguments(punch)
    delta = _checks.real("delta", delta)
    x, y = (None, None) if axis is None else _axis_on_surface(axis, np.shape(heights), delta)
    args = (heights, delta, kind, alpha, radius, _checks.text("control", control), _checks.real("largest", largest))
    return args, dict(e_star=_checks.real("e_star", e_star), tol=_checks.real("tol", tol),
                      max_iterations=_checks.c_int("max_iterations", max_iterations),
                      crop=_checks.flag("crop", crop), window_margin=_checks.integer("window_margin", window_margin),
                      x=x, y=y, profile=profile, device=_checks.text("device", device),
                      hardness=_checks.real("hardness", hardness), periodic=_checks.flag("periodic", periodic),
                      slope_definition=_checks.text("slope_definition", slope_definition or ""),
                      adhesion_work=_checks.real("adhesion_work", adhesion_work),
                      adhesion_range=_checks.real("adhesion_range", adhesion_range),
                      plain_pk=_checks.flag("plain_pk", plain_pk), measure=_checks.flag("measure", measure),
                      wisdom="" if wisdom is None else _checks.path("wisdom", wisdom),
                      adhesion_law=_checks.text("adhesion_law", adhesion_law),
                      adhesion_zone=_checks.real("adhesion_zone", adhesion_zone))


class Indentation:
    """An indentation history on one surface: planned once, stepped many times (warm starts).

    ``punch`` is Cone(), Sphere(R), Flat(a) or a user-given profile as a numpy array (indenter.h, "User-given
    profiles"; copied): an (n, 2) array of rows (r, z) is an axisymmetric profile (r from 0 strictly
    increasing, z from 0 non-decreasing, monotone cubic between samples, no contact beyond the last r); any
    other 2-D array (at least 3 x 3) is a height field z[y, x] on the surface's grid (spacing ``delta``)
    whose centre element [ny // 2, nx // 2] lies on the axis. Lengths in the units of ``delta``.

    ``control`` is 'displacement' (targets are approaches w, counted from first touch), 'load'
    (targets are loads N) or, with ``periodic=True``, 'mean_gap' (targets are mean gaps over the cell, the
    mean of max(g, 0): Persson's u-bar, each > 0); ``largest`` is the largest target the history will impose (it fixes the solve
    window). The surface is copied into the plan: the array may change afterwards. ``tol`` is the
    solver's relative residual (default 1e-6, the standard quality preset, as ``indentmap indent`` and
    scenes); ``quality`` names a preset instead, as ``indentmap indent --quality``: 'draft' (1e-5),
    'standard' (1e-6) or 'publication' (1e-9), which a ``tol`` given overrides. ``device`` is the solver's engine: 'cpu' (default), 'gpu' (the Vulkan compute engine) or
    'auto' (a hardware GPU when there is one), as ``indentmap indent --device``. Planning, steps and
    ``fields()`` run without the GIL; Ctrl-C during a step on the main thread stops it within one
    iteration and raises KeyboardInterrupt (the history keeps the last iterate as its next warm start).

    ``hardness`` H_p > 0 caps the pressure (perfect plasticity, ``indentmap indent --hardness``) and the
    history remembers it: each step adds the capped patches' overlap to a plastic depth and starts from
    the deformed surface, so unloading is elastic and reloading retraces it (docs/solver.md, "Hardness").
    Targets may go up and down; ``plastic()`` gives the plastic depth so far.

    ``periodic=True``: the heights are one period of a periodic surface (nominally flat contact, as
    ``indentmap indent --periodic``): the periodic half-space over the whole cell (mean u = 0), under any
    control, the punch repeated with the cell, or a rigid flat when ``punch`` is None; ``area_ratio`` is then A / A0
    and ``load_star`` NaN.

    ``adhesion_work`` w and ``adhesion_range`` delta_c (both > 0) make the surfaces attract (the
    Maugis-Dugdale law, ``indentmap indent --adhesion-work --adhesion-range``; docs/solver.md, "Adhesion"):
    displacement or load control on the half-space, mean-gap or load control (mean pressures) on a periodic
    cell; approaches and loads may then be negative down to -largest (the punch pulled away, the contact under
    tension); under load control a load beyond the pull-off force is refused (InvalidArgument naming it, a
    cell's as a mean pressure: the contact jumps out);
    ``adhesion(history, control)`` gives the pull-off where the steps passed it.
    ``adhesion_law='exponential'`` (``indent --adhesion-law exponential``) takes the smooth law instead: the
    tension (w / rho) exp(-g / rho) at a gap g, rho = ``adhesion_range``, w / rho in contact.
    ``adhesion_zone=P`` (``indent --adhesion-zone P``) solves instead the Maugis-Dugdale law of the same work
    whose Dugdale zone spans at least P patches, where the given one is narrower (a smoother law whose pull-off
    coarse grids resolve; docs/solver.md, "Across Tabor's mu"; ``indent_run``'s run.json states both laws).

    ``slope_definition`` is the h'rms of the history's theory columns: 'spectral' or 'fd' (forward
    differences); by default spectral for a periodic cell and fd otherwise (an array may be measured, and a
    measured surface's edges would count in its spectrum), as ``indentmap indent`` for a measured file. An
    array does not say that it was generated: for a generated surface, ``indent`` takes the definition its
    generator targeted (its file's sidecar: ``read_generator(path)["slope_definition"]``, 'spectral' or
    'finite-difference'), so pass that ('fd' for the latter) for its numbers.

    Units (``indentmap indent --length-unit --e-star-unit``): ``length_unit`` is the unit of ``delta``,
    the heights and every length (``read(path).unit``; "" for units of delta) and ``e_star_unit`` that
    of ``e_star`` ("" when unstated; "Pa" with "m" puts forces in N). They change no number: ``units``
    states them as ``indentmap indent``'s run.json does, and they label what is drawn or written from
    the history (``write_analysis(..., length_unit=run.units["length"], force_unit=run.units["force"])``).

    Solver options of ``indentmap indent``: ``plain_pk=True`` (``--plain-pk``) solves with plain
    Polonsky-Keer CG from the local guess, without the cascade start and the preconditioner (the same
    answers to the tolerance, slower); ``measure=True`` (``--measure``) plans the FFTs with FFTW_MEASURE
    (slower planning, faster steps); ``wisdom`` (``--wisdom FILE``, a path) is an FFTW wisdom file read
    before planning and updated after it, which implies ``measure``. Python reads no wisdom file
    unless given one (the program's default cache and ``IM_FFTW_WISDOM`` are its own); a file that is
    not FFTW wisdom, or cannot be replaced, raises ``InvalidArgument`` or ``FileError`` naming it. FFTW
    keeps what a measured plan learnt for the whole process: later plans in it may use it (the same
    answers to the tolerance, other last bits than an estimated run of the program).

    Example::

        t = im.read("scan.x3p", length_unit="m")
        run = im.Indentation(t.heights, im.Sphere(50e-6), control="load", largest=1e-3, delta=t.delta,
                             e_star=70e9, length_unit=t.unit, e_star_unit="Pa")
        run.step(1e-3)
        run.units["load"]  # 'N'
    """

    def __init__(self, heights, punch=Cone(), *, control="displacement", largest, delta=1.0, e_star=1.0,
                 tol=None, max_iterations=10000, crop=True, window_margin=4, axis=None, device="cpu",
                 hardness=0.0, periodic=False, slope_definition=None, adhesion_work=0.0, adhesion_range=0.0,
                 quality=None, length_unit="", e_star_unit="", plain_pk=False, measure=False, wisdom=None,
                 adhesion_law="maugis-dugdale", adhesion_zone=0.0):
        args, kwargs = _core_arguments(heights, punch, control=control, largest=largest, delta=delta, e_star=e_star,
                                       tol=tol, max_iterations=max_iterations, crop=crop,
                                       window_margin=window_margin, axis=axis, device=device, hardness=hardness,
                                       periodic=periodic, slope_definition=slope_definition,
                                       adhesion_work=adhesion_work, adhesion_range=adhesion_range, quality=quality,
                                       plain_pk=plain_pk, measure=measure, wisdom=wisdom,
                                       adhesion_law=adhesion_law, adhesion_zone=adhesion_zone)
        self._run = _core.Indentation(*args, **kwargs)
        self.units = json.loads(_core.units_record(_core.length_unit("length_unit", _checks.text("length_unit",
                                                                                               length_unit)),
                                                   _checks.text("e_star_unit", e_star_unit),
                                                   _checks.flag("periodic", periodic)))

    def step(self, target):
        """Solves the next step at approach, load or mean gap ``target``; returns its results as a dict.

        The dict holds the step's results (``approach``, ``load``, ``load_star``, ``contact_patches``,
        ``area_ratio``, ``mean_pressure``, ``max_pressure``, ``iterations``, ``residual``, ...), lengths in
        the units of delta and stresses in those of E*. ``NotConverged`` or ``EdgeContact`` when the step
        fails; the history keeps the steps before it.

        Example: ``run = im.Indentation(h, largest=2.0); run.step(1.0)["load"]``."""
        return self._run.step(float(target))

    def fields(self):
        """(force, gap, displacement) of the last step on the full grid, as new arrays: the displacement is
        computed on the whole grid (one convolution), not only in the solve window. Before any step they are
        those of an approach of 0: zero force and displacement, the undeformed gap from first touch.

        Example: ``force, gap, displacement = run.fields()``; ``force.sum()`` is the step's load."""
        return self._run.fields()

    def history(self):
        """The steps solved so far as a structured array with history.csv's columns (docs/solver.md):
        the solver's results, the theory beside them, the stiffness, the contact patches and the plastic
        memory, measured as ``indentmap indent`` measures them.

        Example: ``run.step(1.0); run.step(2.0); run.history()["area_ratio"]``."""
        return _history_array(self._run.history_values())

    def write_distributions(self, prefix):
        """Writes the last step's gap and contact-patch size distributions as ``indentmap indent
        --distributions`` writes each step's: ``prefix``_gaps.csv (the gap outside contact in units of the
        surface's h_rms, delta for a flat surface, in 50 bins), ``prefix``_patches.csv (patch sizes by octave)
        and ``prefix``_patch_list.csv (each patch's cells, area and perimeter in the length unit), atomically
        (docs/theory.md, "Gap and patch-size distributions"). ``InvalidArgument`` before the first step,
        ``FileError`` naming a file that cannot be written. The files are the program's for the same
        step, byte for byte.

        Example: ``run.step(2.0); run.write_distributions("out/distributions_0001")``."""
        self._run.write_distributions(os.fspath(prefix))

    def plastic(self):
        """The plastic depth accumulated so far on the full grid (units of delta; 0 without a hardness):
        the residual impression once the punch is withdrawn.

        Example: ``run = im.Indentation(h, largest=2.0, hardness=0.1); run.step(2.0); run.step(0.0);
        run.plastic().max()``."""
        return self._run.plastic()

    @property
    def window(self):
        """(x0, y0, nx, ny): the sub-grid that is solved.

        Example: ``x0, y0, nx, ny = run.window``; ``crop=False`` solves on the whole grid."""
        return self._run.window

    @staticmethod
    def window_for(heights, punch=Cone(), **options):
        """(x0, y0, nx, ny): the window ``Indentation(heights, punch, **options)`` would solve on, found
        without planning it or making its fields (solver.h: im_indentation_window_for; only the whole
        grid's undeformed gap is made): to size a run before making it. The options and errors are
        Indentation's, raised for the same arguments (``EdgeContact``, ``InvalidArgument``, ...); the
        window is the one ``indentmap indent`` states ("window [x0, x1) x [y0, y1)") and run.json records.

        Example: ``x0, y0, nx, ny = im.Indentation.window_for(h, im.Cone(80), largest=4.0)``."""
        bound = inspect.signature(Indentation).bind(heights, punch, **options)
        bound.apply_defaults()
        given = {name: value for name, value in bound.arguments.items() if name not in _UNIT_OPTIONS}
        args, kwargs = _core_arguments(**given)
        return _core.indentation_window(*args, **kwargs)

    def memory(self):
        """The memory of the run's plan as made, as ``solver_memory`` gives it (a dict of ``gpu``,
        ``host_bytes``, ``device_bytes``, ``device_memory``, ``device``, ``note``; solver.h:
        im_solver_plan_memory): the plan's grid is the window, and its options the repulsive problem's
        (no adhesion; a cap turns the cascade and the preconditioner off), not the run's. With
        device='auto' on the CPU, ``note`` says why (the GPU's memory too small).

        Example: ``run = im.Indentation(h, largest=2.0, device="gpu"); run.memory()["device_bytes"]``."""
        return self._run.memory()


class Plan:
    """The contact solver on an (ny, nx) grid of spacing ``delta``, for gaps of your own: planned once
    (FFTW plans, the influence kernel's spectrum), solved many times.

    ``solve(gap0, target)`` takes the undeformed gap at first touch (>= 0; +inf where the punch never
    touches) and an approach w (``control='displacement'``) or a load N (``control='load'``), optionally a
    warm-start ``pressure``; it returns (pressure, displacement, result dict) as new arrays. Solves run
    without the GIL, and so does creating a plan (the library serialises FFTW's planner). Ctrl-C during a solve
    on the main thread stops it within one iteration and raises KeyboardInterrupt; the plan stays usable.

    Example::

        plan = im.Plan(64)
        r = np.hypot(*np.meshgrid(np.arange(64) - 32.0, np.arange(64) - 32.0))
        pressure, displacement, result = plan.solve(r * np.tan(np.radians(10)), 2.0)
    """

    def __init__(self, nx, ny=None, *, delta=1.0, e_star=1.0, tol=_core.default_tol, max_iterations=10000,
                 device="cpu"):
        sides = [_checks.integer(name, value) for name, value in (("nx", nx), ("ny", nx if ny is None else ny))]
        for name, side in zip(("nx", "ny"), sides):
            if not 1 <= side <= _core.field_max_side:  # before C's int: 2**40 gave an OverflowError naming nothing
                raise _core.InvalidArgument(f"Plan: {name} = {side}: expected each side in [1, {_core.field_max_side}]")
        self._plan = _core.Plan(*sides, float(delta), float(e_star), float(tol),
                                _checks.c_int("max_iterations", max_iterations), str(device))

    def solve(self, gap0, target, control="displacement", pressure=None):
        """Solves the contact of the undeformed gap ``gap0`` ((ny, nx), >= 0 in the units of delta; +inf
        where the punch never touches) at approach ``target`` (``control='displacement'``) or load
        ``target`` ('load', in E* delta^2), from the warm start ``pressure`` when given. Returns
        (pressure, displacement, result dict) as new arrays, pressures in units of E*. ``NotConverged`` when
        the tolerance is not reached; ``ValueError`` naming ``gap0`` or ``pressure`` for an array of another
        grid, and ``control`` for one other than 'displacement' or 'load' (mean gaps are an
        ``Indentation``'s, ``periodic=True``); ``NumericError`` naming the first gap that is negative or NaN;
        ``InvalidArgument`` for a target or warm start out of range.

        Example: ``pressure, displacement, result = plan.solve(gap0, 2.0); result["load"]``."""
        if control not in ("displacement", "load"):
            raise ValueError(f"control {control!r}: expected 'displacement' or 'load' (mean gaps: "
                             "Indentation(..., periodic=True, control='mean_gap'))")
        return self._plan.solve(gap0, float(target), control=control, pressure=pressure)

    def memory(self):
        """The memory of this plan as made, as ``solver_memory`` gives it for its grid and options (solver.h:
        im_solver_plan_memory; a dict of ``gpu``, ``host_bytes``, ``device_bytes``, ``device_memory``,
        ``device``, ``note``).

        Example: ``im.Plan(256, device="gpu").memory()["device_bytes"]``."""
        return self._plan.memory()


def _step_targets(name, values):
    """A history's targets as a 1-D float64 array (a number is one step). Strings and arrays of more than one
    dimension are refused naming the argument: numpy alone reads "12" as 12 and [[1, 2]] as two steps."""
    array = np.asarray(values)
    if array.dtype.kind not in "biuf":
        raise TypeError(f"{name}: expected real numbers, got an array of {array.dtype}")
    if array.ndim > 1:
        raise ValueError(f"{name}: shape {array.shape}: expected a number or a 1-D sequence of steps")
    return array.astype(float).ravel()


def indent(heights, punch=Cone(), *, approaches=None, loads=None, pressures=None, mean_gaps=None, fields=False,
           distributions=None, **options):
    """Solves a history of approaches (displacement control), loads (load control) or mean gaps.

    Returns a structured array with one row per step and history.csv's columns (``read_history`` reads a
    history.csv into the same array); with ``fields=True``,
    also a list of dicts {'force', 'gap', 'displacement'} per step ('plastic' too with a hardness).
    ``options`` go to Indentation. Targets may go up and down (``np.r_[2:8:4j, 7:0:8j]`` loads to 8 and
    unloads): ``unloading(history, punch)`` then gives the indentation analysis. ``pressures`` (with
    ``periodic=True``): mean pressures over the cell instead of loads, as ``indent --pressure``;
    ``mean_gaps`` (with ``periodic=True``): mean gaps over the cell, as ``indent --mean-gap``.
    ``distributions``, a folder (made if missing): each step's distributions written there as
    ``indent --distributions`` writes them, distributions_NNNN_{gaps,patches,patch_list}.csv
    (``Indentation.write_distributions``). The units of the history's columns are
    ``Indentation(...).units`` for the same ``length_unit`` and ``e_star_unit`` options.

    Example: ``h = im.indent(im.generate(128, seed=3), approaches=np.linspace(0.5, 4, 8))``, then
    ``h["load"]`` and ``h["area_ratio"]``; errors are those of ``Indentation`` and its steps
    (``NotConverged``, ``EdgeContact``).
    """
    if sum(t is not None for t in (approaches, loads, pressures, mean_gaps)) != 1:
        raise ValueError("give one of approaches, loads, pressures and mean_gaps")
    if mean_gaps is not None and not options.get("periodic", False):
        raise ValueError("mean_gaps (mean gaps over the cell) need periodic=True")
    name = next(name for name, given in (("approaches", approaches), ("loads", loads), ("pressures", pressures),
                                         ("mean_gaps", mean_gaps)) if given is not None)
    if pressures is not None:
        if not options.get("periodic", False):
            raise ValueError("pressures (mean pressures over the cell) need periodic=True; give loads otherwise")
        ny, nx = np.shape(heights)
        loads = _step_targets(name, pressures) * (nx * ny * options.get("delta", 1.0) ** 2)
    control, targets = ("load", loads) if loads is not None else ("mean_gap", mean_gaps) if mean_gaps is not None \
        else ("displacement", approaches)
    targets = _step_targets(name, targets)
    if targets.size == 0:
        raise ValueError("no steps")
    if control == "mean_gap" and not np.all(targets > 0):  # refused now, not after the steps before it
        step = int(np.argmin(targets > 0))
        raise ValueError(f"mean_gaps: step {step + 1} is {targets[step]:g}: expected mean gaps > 0 (at 0 the cell is "
                         "in full contact)")
    run = Indentation(heights, punch, control=control,
                      largest=float(np.abs(targets).max()), **options)
    if distributions is not None:
        os.makedirs(distributions, exist_ok=True)
    per_step = []
    for step, target in enumerate(targets, start=1):
        run.step(target)
        if distributions is not None:
            run.write_distributions(os.path.join(distributions, f"distributions_{step:04d}"))
        if fields:
            step_fields = dict(zip(("force", "gap", "displacement"), run.fields()))
            if options.get("hardness", 0) > 0:
                step_fields["plastic"] = run.plastic()
            per_step.append(step_fields)
    history = run.history()
    return (history, per_step) if fields else history



def _run_punch(punch, periodic):
    """The punch options of _core.indent_run: Cone, Sphere, Flat, a profile file's path, or None (a
    periodic cell's rigid flat)."""
    if punch is None:
        if not periodic:
            raise ValueError("punch None (a rigid flat over the cell) needs periodic=True")
        return {"punch_given": 0}
    if isinstance(punch, (str, bytes, os.PathLike)):
        return {"kind": "profile", "profile": _checks.path("punch", punch), "punch_given": 1}
    if isinstance(punch, np.ndarray):
        raise TypeError("punch: indent_run takes a profile file's path (as indent --profile), not an array")
    kind, alpha, radius, _ = _punch_arguments(punch)
    return {"kind": kind, "alpha": alpha, "radius": radius, "punch_given": 1}


def _file_options(surface, channel, fill, resample_square, npy_order, height_unit, length_unit, region, align,
                  detrend):
    """indent_run's options of how the surface file is read and prepared, checked and named."""
    options = dict(surface=_checks.path("surface", surface), channel="" if channel is None else str(channel),
                   fill=int(_checks.flag("fill", fill)),
                   resample_square=int(_checks.flag("resample_square", resample_square)),
                   npy_order=_npy_order_code(npy_order), height_unit=_checks.text("height_unit", height_unit),
                   length_unit=_checks.text("length_unit", length_unit), align=_checks.text("align", align),
                   detrend=_checks.text("detrend", detrend))
    if region is not None:
        if len(region) != 4:
            raise ValueError(f"region {region!r}: expected (x0, y0, nx, ny)")
        options["region"] = tuple(_checks.integer("region", v) for v in region)
    return options


def indent_run(surface, out, punch=Cone(), *, approaches=None, loads=None, pressures=None, mean_gaps=None, n=512,
               m=None, delta=None, unit="", height_unit="", length_unit="", channel=None, fill=False,
               resample_square=False, npy_order=None, region=None, align="none", detrend="none", axis=None, e_star=1.0, e_star_unit="", hardness=0.0, quality=None,
               tol=None, max_iterations=10000, crop=True, periodic=False, slope_definition=None, adhesion_work=0.0,
               adhesion_range=0.0, adhesion_law="maugis-dugdale", adhesion_zone=0.0, device="cpu", plain_pk=False,
               measure=False, wisdom=None, fields=False, frames=False, distributions=False, page_embed=False, backend="auto",
               progress=None, log=None):
    """Makes the run ``indentmap indent`` makes, into the folder ``out``, and returns ``out``: the same
    library call (indent.h: im_indent_run), so the same files: history.csv, run.json, index.html, the
    history figure, the indentation analysis of an unloading history, adhesion's force-distance figure,
    with ``fields`` the step fields, with ``frames`` frames/contact_NNNN.png, with ``distributions`` the
    distributions of each step (docs/solver.md). run.json records no arguments (a Python run is made
    again by its script, not ``indent --from-record``) and its figures no command.

    ``surface``: a surface file's path, or None for a flat ``n`` x ``m`` grid of spacing ``delta`` (1 by
    default) in ``unit``; ``delta`` given with a file overrides its spacing (``indent --delta``). A file
    is read as ``read`` reads it (``unit``, ``height_unit``, ``length_unit``, ``channel``, ``fill``,
    ``resample_square``, ``npy_order``); ``region=(x0, y0, nx, ny)`` indents that block of it (``indent
    --crop``), its rows aligned (``align``) and then detrended (``detrend``) as ``prepare`` does, but
    none by default, as ``indent``. ``punch``:
    ``Cone``, ``Sphere``, ``Flat``, a profile file's path (``indent --profile``) or, with ``periodic``, None
    for the rigid flat on the whole cell. One of ``approaches``, ``loads``, ``pressures`` (periodic: mean
    pressures) or ``mean_gaps`` (periodic). ``quality`` names the tolerance's preset unless ``tol`` is given.
    The other options are ``Indentation``'s and ``indent``'s of the same names.

    The run's lines go to ``log(level, message)``, by default the ``indentmap`` logger: the surface's and
    each step's line at ``logging.INFO``, warnings and failures after the steps at ``logging.WARNING``;
    ``progress("steps", done, total)`` after each step. Errors are raised as ``indentmap.Error``
    subclasses with the program's messages (the steps before a failing one are in ``out``/history.csv);
    Ctrl-C raises KeyboardInterrupt before the next step.

    Example: ``im.indent_run("surface.npy", "out", im.Cone(80), approaches=np.linspace(0.5, 4, 8))``."""
    if sum(t is not None for t in (approaches, loads, pressures, mean_gaps)) != 1:
        raise ValueError("give one of approaches, loads, pressures and mean_gaps")
    name, control, targets = next(given for given in (("approaches", "displacement", approaches),
                                                      ("loads", "load", loads), ("pressures", "load", pressures),
                                                      ("mean_gaps", "mean_gap", mean_gaps)) if given[2] is not None)
    targets = _step_targets(name, targets)
    plain_pk = _checks.flag("plain_pk", plain_pk)
    options = dict(_run_punch(punch, periodic), out=_checks.path("out", out), control=control,
                   pressures=int(pressures is not None), nx=_checks.integer("n", n),
                   ny=_checks.integer("m", n if m is None else m), unit=_checks.text("unit", unit),
                   e_star=_checks.real("e_star", e_star), e_star_unit=_checks.text("e_star_unit", e_star_unit),
                   hardness=_checks.real("hardness", hardness),
                   max_iterations=_checks.c_int("max_iterations", max_iterations),
                   crop=int(_checks.flag("crop", crop)), periodic=int(_checks.flag("periodic", periodic)),
                   slope_definition=_checks.text("slope_definition", slope_definition or ""),
                   adhesion_work=_checks.real("adhesion_work", adhesion_work),
                   adhesion_range=_checks.real("adhesion_range", adhesion_range),
                   adhesion_law=_checks.text("adhesion_law", adhesion_law),
                   adhesion_zone=_checks.real("adhesion_zone", adhesion_zone), device=_checks.text("device", device),
                   cascade=int(not plain_pk), precondition=int(not plain_pk), fft_measure=int(_checks.flag("measure", measure)),
                   fields=int(_checks.flag("fields", fields)), frames=int(_checks.flag("frames", frames)),
                   distributions=int(_checks.flag("distributions", distributions)),
                   page_embed=int(_checks.flag("page_embed", page_embed)), backend=_checks.text("backend", backend))
    if surface is not None:
        options.update(_file_options(surface, channel, fill, resample_square, npy_order, height_unit, length_unit,
                                     region, align, detrend))
    if delta is not None:
        options["delta" if surface is None else "delta_x"] = _checks.real("delta", delta)
    if quality is not None:
        options["quality"] = _checks.text("quality", quality)
    if tol is not None or quality is not None:
        options["tol"] = _checks.real("tol", tol) if tol is not None else _core.quality_tolerance(quality)
        options["tol_given"] = int(tol is not None)
    if wisdom is not None:
        options["wisdom"] = _checks.path("wisdom", wisdom)
    if axis is not None:
        options["x"], options["y"] = (_checks.real("axis x", axis[0]), _checks.real("axis y", axis[1]))
    return _core.indent_run(options, targets, progress, logging.getLogger("indentmap").log if log is None else log)

UNLOADING_DTYPE = np.dtype([("branch", "i4"), ("top_step", "i4"), ("last_step", "i4"), ("loading_from", "i4"),
                            ("approach_max", "f8"), ("load_max", "f8"), ("stiffness", "f8"), ("epsilon", "f8"),
                            ("contact_depth", "f8"), ("area_projected", "f8"), ("area_real", "f8"),
                            ("hardness_it", "f8"), ("modulus_reduced", "f8"), ("residual_approach", "f8"),
                            ("work_in", "f8"), ("work_out", "f8"), ("dissipated", "f8"),
                            ("area_real_theory", "f8"), ("stiffness_smooth", "f8")])


def _theory_beside(history, top, e_star):
    """eq. (12)'s real area and the smooth punch's stiffness 2 E* sqrt(A_smooth / pi) at a branch's top load
    (row index top), NaN where the top yielded, pulled or carries nothing (the theory is elastic, repulsive)."""
    if history["yielding_patches"][top] > 0 or history["tensile_force"][top] > 0 or not history["load"][top] > 0:
        return np.nan, np.nan
    area = history["area_smooth"][top]
    return area * history["area_ratio_gamma"][top], 2.0 * e_star * np.sqrt(area / np.pi)


def unloading(history, punch=Cone(), *, delta=1.0, e_star=1.0):
    """The indentation analysis of a history's unloading branches: one row per branch, with the columns of
    ``indentmap indent``'s indentation.csv (docs/solver.md, "Indentation analysis"): Oliver-Pharr's S, h_c,
    A_p, H_IT and E_r with the punch's own area function, the real area n_p delta^2 at the top, the residual
    approach, the works in and out and the dissipation, then the theory beside them at an elastic top: eq.
    (12)'s real area and the smooth punch's stiffness (``e_star``: the history's E*). ``history`` is what
    ``indent`` returns.

    Returns a structured array (one row per branch; none without an unloading branch). A branch whose
    stiffness fit reaches past the touch has S (and what follows from it) NaN and gives a ``UserWarning``
    saying so and what to do, the line ``indentmap indent`` prints.

    Example: ``h = im.indent(s, approaches=np.r_[1:4:4j, 3.5:0:8j], hardness=0.1);
    im.unloading(h)["hardness_it"]``."""
    kind, alpha, radius, profile = _punch_arguments(punch)
    history = np.asarray(history)
    branches = _core.unloading(kind, alpha, radius, np.ascontiguousarray(history["approach"], dtype=float),
                               np.ascontiguousarray(history["load"], dtype=float),
                               np.ascontiguousarray(history["residual_approach"], dtype=float), profile,
                               float(delta))
    table = np.zeros(len(branches), dtype=UNLOADING_DTYPE)
    for i, b in enumerate(branches):
        if b["note"]:  # why S is NaN and what to do, as indentmap indent says it
            warnings.warn(b["note"], stacklevel=2)
        before = history["plastic_work"][b["loading_from"] - 1] if b["loading_from"] > 0 else 0.0
        area_theory, stiffness_smooth = _theory_beside(history, b["top_step"] - 1, e_star)
        row = dict(b, branch=i + 1, area_real=history["contact_patches"][b["top_step"] - 1] * delta * delta,
                   dissipated=history["plastic_work"][b["last_step"] - 1] - before, area_real_theory=area_theory,
                   stiffness_smooth=stiffness_smooth)
        table[i] = tuple(row[name] for name in UNLOADING_DTYPE.names)
    return table


def write_analysis(history, out, punch=Cone(), *, delta=1.0, e_star=1.0, length_unit="", force_unit="E* δ²"):
    """Writes the indentation analysis ``indentmap indent`` writes beside its history (history.h:
    im_history_write_analysis), when the history holds an unloading branch: ``out``/indentation.csv (the rows
    ``unloading`` returns) and the load-displacement figure ``out``/load_displacement.png and .pdf (N against w,
    loading and unloading segments in two colours, each branch's tangent at its top), the folder ``out`` made
    if it is missing. ``history``: the
    array ``indent`` returns or a history.csv path; ``delta`` and ``e_star`` as the run's; the axes' units
    as indent states them (defaults: a surface without units). Returns the number of unloading branches
    (0: nothing written). The files are the program's for the same run, byte for byte.

    Example: ``im.write_analysis("out/history.csv", "analysis", im.Cone(80))``."""
    if isinstance(history, (str, bytes, os.PathLike)):
        history = read_history(history)
    history = np.asarray(history)
    if history.dtype.names != tuple(_core.history_columns.split(",")):
        raise ValueError("history: expected the array indent returns (history.csv's columns) or a history.csv path")
    kind, alpha, radius, profile = _punch_arguments(punch)
    os.makedirs(out, exist_ok=True)
    values = np.column_stack([history[name].astype(float) for name in history.dtype.names])
    return _core.write_analysis(os.fspath(out), kind, alpha, radius, profile, values,
                                _checks.real("delta", delta), _checks.real("e_star", e_star),
                                _checks.text("length_unit", length_unit), _checks.text("force_unit", force_unit))


def adhesion(history, control="displacement"):
    """The pull-off of an adhesive history (``Indentation(..., adhesion_work=, adhesion_range=)``) as
    ``indentmap indent`` states it in run.json's "adhesion" block: a dict of ``most_tensile_load`` (-min N,
    positive; NaN when nothing pulls) at ``most_tensile_approach``; ``pull_off_force`` and ``pull_off_approach``,
    the same where the steps passed the pull-off (``control``, the control the history was solved under,
    'displacement' or 'mean_gap', and a later step's load above it), NaN otherwise (under 'load' control the
    contact held every load it was given: a load below the pull-off is refused, naming the least load it holds);
    ``jump_in_approach`` (first contact on approach after none), ``jump_out_approach`` (last contact retracting
    before none), ``work_done`` (sum of N dw by trapezoids) with ``hysteresis_error``, an estimate of their
    error (a work within it is not resolved by the steps: finer steps around the jumps resolve it), and
    ``hysteresis_work``, the work lost: ``work_done`` where the history closes a loop (its last step at the first
    approach, or both without force), NaN otherwise (a retraction alone loses nothing).

    Example: ``h = im.indent(s, im.Sphere(40), approaches=[1, 0, -1], adhesion_work=0.02,
    adhesion_range=0.5); im.adhesion(h)["pull_off_force"]``."""
    if control not in ("displacement", "load", "mean_gap"):
        raise ValueError(f"control: {control!r}: expected 'displacement', 'load' or 'mean_gap' (the history's)")
    history = np.asarray(history)
    return _core.adhesion(np.ascontiguousarray(history["approach"], dtype=float),
                          np.ascontiguousarray(history["load"], dtype=float),
                          np.ascontiguousarray(history["contact_patches"], dtype=float), control == "load")
