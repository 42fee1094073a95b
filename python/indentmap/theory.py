"""The paper's theory, vectorised over numpy arrays (the library's theory.h).

Every function broadcasts its array arguments like a numpy ufunc and returns an array of their
broadcast shape (scalars in, a numpy float64 scalar out). ``k`` is eq. (2)'s constant (default 2); ``normalisation`` is 'pr' (the paper's,
Pastewka and Robbins) or 'mg' (Manners and Greenwood's).
"""
import numpy as np

from . import _core


def _apply(name, a, b=0.0, **params):
    a, b = np.broadcast_arrays(np.asarray(a, dtype=float), np.asarray(b, dtype=float))
    out = _core.theory(name, np.array(a, order="C"), np.array(b, order="C"), params)
    return out[()] if out.ndim == 0 else out


def rho_c(slope, alpha=80.0, k=2.0):
    """Eq. (7): rho_c = k cot(alpha) / (2 h'rms) (inf for a smooth surface)."""
    return _apply("rho_c", slope, alpha=float(alpha), k=float(k))


def beta(rho, normalisation="pr", k=2.0):
    """beta = p_m,c / p_n: sqrt(pi)/2 rho_c (pr) or sqrt(2) rho_c / k (mg)."""
    return _apply("beta", rho, normalisation=normalisation, k=float(k))


def area_ratio_eq6(b):
    """Eq. (6): A/A_cone for a constant contact density, as a function of beta."""
    return _apply("area_ratio_eq6", b)


def area_ratio_eq12(b):
    """Eq. (12): A/A_cone with the local contact density gamma(r), as a function of beta."""
    return _apply("area_ratio_eq12", b)


def area_ratio_eq19(b):
    """Eq. (19): Greenwood's form of the same ratio."""
    return _apply("area_ratio_eq19", b)


def area_ratio(slope, alpha=80.0, k=2.0, normalisation="pr"):
    """Eq. (12) from h'rms and the cone angle directly."""
    return area_ratio_eq12(beta(rho_c(slope, alpha, k), normalisation, k))


def gamma(b, r_over_a):
    """Eqs. (10)-(11): the local contact density erf(beta acosh(a / r)) for 0 <= r/a <= 1."""
    return _apply("gamma", b, r_over_a)


def cone_pressure(r_over_a):
    """Eq. (11) over p_m,c: p(r) / p_m,c = acosh(a / r)."""
    return _apply("cone_pressure", r_over_a)


def flat_area_ratio(slope, p_mean, e_star=1.0, k=2.0, normalisation="pr"):
    """Eq. (1): A/A0 = erf(p_mean / p_n) for nominally flat contact."""
    return _apply("flat_area_ratio", slope, p_mean, e_star=float(e_star), k=float(k), normalisation=normalisation)


def sphere_area(slope, load, radius, e_star=1.0, k=2.0, normalisation="pr"):
    """Eq. (3): A = A_Hertz erf(p_s / p_n) for a sphere of radius R."""
    return _apply("sphere_area", slope, load, radius=float(radius), e_star=float(e_star), k=float(k),
                  normalisation=normalisation)


def hertz_area(load, radius, e_star=1.0):
    """Hertz: pi (3 N R / (4 E*))^(2/3)."""
    return _apply("hertz_area", load, radius=float(radius), e_star=float(e_star))


def cone_area(load, alpha=80.0, e_star=1.0):
    """Eq. (5): A_cone = 2 N / (E* cot(alpha))."""
    return _apply("cone_area", load, alpha=float(alpha), e_star=float(e_star))


def fit_k(pressure_ratio, area_fraction):
    """k of eq. (2) fitted to nominally flat contact: A/A0 = erf(sqrt(pi)/2 k x) in x = p_m / (h'rms E*)
    (least squares, Gauss-Newton; theory.h: im_theory_fit_k). Returns a dict: k, its standard error
    k_error, k_linear (the slope of A/A0 = k x through the origin over A/A0 <= 0.5) with linear_points,
    and rms_residual. For a periodic history: x = load / (nx ny delta^2 h'rms E*), A/A0 = area_ratio."""
    x = np.ascontiguousarray(np.ravel(pressure_ratio), dtype=float)
    a = np.ascontiguousarray(np.ravel(area_fraction), dtype=float)
    return _core.fit_k(x, a)
