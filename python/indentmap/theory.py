"""The paper's theory, vectorised over numpy arrays (the library's theory.h).

Every function broadcasts its array arguments like a numpy ufunc and returns an array of their
broadcast shape (scalars in, a numpy float64 scalar out). ``k`` is eq. (2)'s constant (default 2); ``normalisation`` is 'pr' (the paper's,
Pastewka and Robbins) or 'mg' (Manners and Greenwood's).
"""
import json
import os

import numpy as np

from . import _core
from .solver import read_history


def _apply(name, a, b=0.0, **params):
    a, b = np.broadcast_arrays(np.asarray(a, dtype=float), np.asarray(b, dtype=float))
    out = _core.theory(name, np.array(a, order="C"), np.array(b, order="C"), params)
    return out[()] if out.ndim == 0 else out


def rho_c(slope, alpha=80.0, k=2.0):
    """Eq. (7): rho_c = k cot(alpha) / (2 h'rms) (inf for a smooth surface).

    ``slope`` h'rms (dimensionless), ``alpha`` the cone's semi-opening angle in degrees; both broadcast.

    Example: ``im.theory.rho_c(0.08)`` is 2.204 (alpha 80°, k 2)."""
    return _apply("rho_c", slope, alpha, k=float(k))


def beta(rho, normalisation="pr", k=2.0):
    """beta = p_m,c / p_n: sqrt(pi)/2 rho_c (pr) or sqrt(2) rho_c / k (mg).

    Example: ``im.theory.beta(im.theory.rho_c(0.08))`` is 1.953."""
    return _apply("beta", rho, normalisation=normalisation, k=float(k))


def area_ratio_eq6(b):
    """Eq. (6): A/A_cone for a constant contact density, as a function of beta.

    Example: ``im.theory.area_ratio_eq6(1.0)`` is erf(1) = 0.8427."""
    return _apply("area_ratio_eq6", b)


def area_ratio_eq12(b):
    """Eq. (12): A/A_cone with the local contact density gamma(r), as a function of beta.

    Example: ``im.theory.area_ratio_eq12([0.5, 1.0, 2.0])``; at beta 1 it is 0.7263."""
    return _apply("area_ratio_eq12", b)


def area_ratio_eq19(b):
    """Eq. (19): Greenwood's form of the same ratio.

    Example: ``im.theory.area_ratio_eq19(1.0)`` is 0.7263, as eq. (12)."""
    return _apply("area_ratio_eq19", b)


def area_ratio(slope, alpha=80.0, k=2.0, normalisation="pr"):
    """Eq. (12) from h'rms and the cone angle directly.

    Broadcasts over ``slope`` and ``alpha`` (degrees); n_p delta^2 / A_cone, dimensionless.

    Example: ``im.theory.area_ratio([0.01, 0.08, 0.16], alpha=80)``; at h'rms 0.08 it is 0.8945."""
    return area_ratio_eq12(beta(rho_c(slope, alpha, k), normalisation, k))


def gamma(b, r_over_a):
    """Eqs. (10)-(11): the local contact density erf(beta acosh(a / r)) for 0 <= r/a <= 1.

    Example: ``im.theory.gamma(1.0, 0.5)`` is 0.9375."""
    return _apply("gamma", b, r_over_a)


def cone_pressure(r_over_a):
    """Eq. (11) over p_m,c: p(r) / p_m,c = acosh(a / r).

    Example: ``im.theory.cone_pressure(0.5)`` is acosh(2) = 1.317."""
    return _apply("cone_pressure", r_over_a)


def flat_area_ratio(slope, p_mean, e_star=1.0, k=2.0, normalisation="pr"):
    """Eq. (1): A/A0 = erf(p_mean / p_n) for nominally flat contact.

    ``p_mean`` and ``e_star`` in one unit of stress.

    Example: ``im.theory.flat_area_ratio(0.1, 0.01)`` is 0.1979 (p_mean = E* / 100)."""
    return _apply("flat_area_ratio", slope, p_mean, e_star=float(e_star), k=float(k), normalisation=normalisation)


def sphere_area(slope, load, radius, e_star=1.0, k=2.0, normalisation="pr"):
    """Eq. (3): A = A_Hertz erf(p_s / p_n) for a sphere of radius R.

    ``load`` N in E* delta^2, ``radius`` in the units of delta; A in delta^2.

    Example: ``im.theory.sphere_area(0.1, 5.0, 100.0)`` is 91.0, below Hertz's 163.4."""
    return _apply("sphere_area", slope, load, radius=float(radius), e_star=float(e_star), k=float(k),
                  normalisation=normalisation)


def hertz_area(load, radius, e_star=1.0):
    """Hertz: pi (3 N R / (4 E*))^(2/3).

    Example: ``im.theory.hertz_area(5.0, 100.0)`` is 163.4 (delta^2, for N in E* delta^2)."""
    return _apply("hertz_area", load, radius=float(radius), e_star=float(e_star))


def cone_area(load, alpha=80.0, e_star=1.0):
    """Eq. (5): A_cone = 2 N / (E* cot(alpha)).

    Example: ``im.theory.cone_area(1.0)`` is 2 / cot(80°) = 11.34."""
    return _apply("cone_area", load, alpha=float(alpha), e_star=float(e_star))


def fit_k(pressure_ratio, area_fraction):
    """k of eq. (2) fitted to nominally flat contact: A/A0 = erf(sqrt(pi)/2 k x) in x = p_m / (h'rms E*)
    (least squares, Gauss-Newton; theory.h: im_theory_fit_k). Returns a dict: k, its standard error
    k_error, k_linear (the slope of A/A0 = k x through the origin over A/A0 <= 0.5) with linear_points,
    and rms_residual. For a periodic history: x = load / (nx ny delta^2 h'rms E*), A/A0 = area_ratio.

    Example: ``x = np.linspace(0.05, 0.5, 10); im.theory.fit_k(x, im.theory.flat_area_ratio(1.0, x))["k"]``
    is 2.0."""
    x = np.ascontiguousarray(np.ravel(pressure_ratio), dtype=float)
    a = np.ascontiguousarray(np.ravel(area_fraction), dtype=float)
    return _core.fit_k(x, a)


def _record_number(record, block, key, path):
    """record[block][key] as a finite number, or ValueError naming it (as ``theory --fit-k``)."""
    fields = record.get(block)
    value = fields.get(key) if isinstance(fields, dict) else None
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not np.isfinite(value):
        raise ValueError(f"{path}: no number at {block}.{key}: expected the run.json of `indentmap indent --periodic` "
                         "(the cell's nx, ny and delta, the h'rms and E* the fit needs)")
    return value


def _periodic_run(path):
    """The cell's area, h'rms, E* and h'rms definition of a periodic run's record, checked as
    ``theory --fit-k`` checks it: periodic, without hardness or adhesion."""
    if not os.path.exists(path):
        raise ValueError(f"{path}: no run.json beside the history: the fit needs the cell (surface.nx, ny, delta), "
                         "the h'rms (theory_slope_rms.value) and E* (solver.e_star) that `indentmap indent "
                         "--periodic` records there")
    with open(path, encoding="utf-8") as f:
        record = json.load(f)
    if record.get("periodic") is not True:
        raise ValueError(f'{path}: not a periodic run ("periodic" is not true): k of eq. (2) is fitted to the '
                         "history of `indentmap indent SURFACE --periodic`")
    if _record_number(record, "solver", "hardness", path) > 0:
        raise ValueError(f"{path}: the run capped the pressure at solver.hardness: eq. (2) is the elastic law")
    if record.get("adhesion") is not None:
        raise ValueError(f'{path}: the run was adhesive ("adhesion"): eq. (2) is the repulsive law')
    nx, ny, delta = (_record_number(record, "surface", key, path) for key in ("nx", "ny", "delta"))
    if not (nx >= 1 and ny >= 1 and nx == int(nx) and ny == int(ny) and delta > 0):
        raise ValueError(f"{path}: surface.nx = {nx}, ny = {ny}, delta = {delta}: expected a grid")
    slope = record.get("theory_slope_rms")
    definition = slope.get("definition") if isinstance(slope, dict) else None
    if not isinstance(definition, str):
        raise ValueError(f"{path}: no text at theory_slope_rms.definition")
    # the cell's area as periodic_cell_area computes it (front.h), operation for operation
    return (float(nx) * ny * delta * delta, _record_number(record, "theory_slope_rms", "value", path),
            _record_number(record, "solver", "e_star", path), definition)


def fit_k_history(path):
    """k of eq. (2) over a periodic history written earlier, as ``indentmap theory --fit-k`` and the end of
    ``indent --periodic`` fit it: the history.csv at ``path`` (A/A0 = area_ratio against
    x = load / (nx ny delta^2) / (h'rms E*) over the steps with a positive load in partial contact: steps in
    full contact, A/A0 = 1, bound k without measuring it and are counted in full_contact_points) with the cell, h'rms and E*
    of the run.json beside it. Returns run.json's ``k_fit`` block as a dict, bit for bit (k_linear NaN
    where it is null): fit_k's keys with points, pressure_ratio_range, area_fraction_range, slope_rms and
    slope_rms_definition. ValueError naming the row for a history whose mean_gap is not finite (the
    half-space, a punch repeated with the cell), and naming what the run.json lacks or why its run is not
    one eq. (2) describes (not periodic, a hardness, adhesion).

    Example: ``im.indent(h, None, pressures=[0.002, 0.01], periodic=True)`` written by the program as
    ``out/history.csv``, then ``im.theory.fit_k_history("out/history.csv")["k"]``."""
    path = os.fspath(path)
    history = read_history(path)
    gapless = np.flatnonzero(~np.isfinite(history["mean_gap"]))
    if gapless.size:
        row = int(gapless[0]) + 1
        raise ValueError(f"{path}: row {row} (line {row + 1}) has no mean_gap (not finite): not the history of a "
                         "periodic cell under the rigid flat (`indentmap indent SURFACE --periodic` without --punch)")
    cell_area, slope_rms, e_star, definition = _periodic_run(os.path.join(os.path.dirname(path), "run.json"))
    loaded = history[history["load"] > 0]
    if loaded.size == 0:
        raise ValueError(f"{path}: k of eq. (2): no step with a positive load")
    # steps in full contact (A/A0 = 1) bound k without measuring it: left out and counted, as the program does
    full = loaded["area_ratio"] >= 1
    loaded, full_contact = loaded[~full], int(np.count_nonzero(full))
    if loaded.size == 0:
        raise ValueError(f"{path}: k of eq. (2): every step with a positive load is in full contact (A/A0 = 1, "
                         f"{full_contact} steps), which does not measure k: expected a step in partial contact "
                         "(a smaller load or pressure)")
    x = loaded["load"] / cell_area / (slope_rms * e_star)
    area = loaded["area_ratio"]
    fit = fit_k(x, area)
    fit.update(points=int(loaded.size), pressure_ratio_range=[float(x.min()), float(x.max())],
               area_fraction_range=[float(area.min()), float(area.max())], slope_rms=slope_rms,
               slope_rms_definition=definition, full_contact_points=full_contact)
    return fit
