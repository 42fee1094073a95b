/* indentmap/theory.h: the paper's theory.
 *
 * Entry points:
 *   im_theory_cone_*, im_theory_sphere_*, im_theory_flat_area_ratio, im_theory_punch_*
 *                                           contact area and pressure of rough punches (eqs. 1-12)
 *   im_theory_interface_default, im_theory_erf_scale, im_theory_fit_k   the rough interface's law
 *   im_theory_moment, im_theory_height_rms_*   roughness relations (eqs. 13-15)
 *   im_theory_md_sphere*, im_theory_jkr_cone*, im_theory_kendall_*   adhesive contacts
 *   im_theory_wavy*                         wavy surfaces' closed forms (tests' references)
 *
 * Contact area (eqs. 1-12 and the Appendix's eq. 19): the erf law of a nominally flat rough
 * contact, the sphere of Pastewka and Robbins, and the cone with a constant (eq. 6) or a
 * variable (eq. 12) local density of contact. Units: stresses in units of E* when E* = 1 (every
 * function that needs E* takes it), lengths in grid spacings delta (only ratios of lengths enter
 * here). The cone's semi-opening angle alpha is in DEGREES, 0 < alpha < 90 (the paper: 80).
 * h'rms = sqrt(<|grad h|^2>) >= 0 over both slope components, as in the paper.
 *
 * Errors: the int functions return IM_OK, or IM_EINVAL with a message naming the parameter and
 * its range; the quadratures may also return IM_ENOMEM, IM_ENUMERIC or IM_ENOCONV with GSL's
 * reason in the message. Outputs are written only on success. Nothing aborts: GSL's error handler
 * (one process-wide pointer) is switched off while a quadrature of the library runs and the
 * application's handler, whatever it was, is put back when it returns, so the application's
 * handler is never called for the library's errors, which become the project's status codes. An
 * application thread that calls GSL while another thread is inside an im_theory call finds the
 * handler off for that time; one that changes the handler then has its change undone.
 *
 * Roughness relations (eqs. 13-15): spectral moments of an isotropic power-law PSD
 * C(q) = A |q|^(-2(1+H)) on q_r < q < q_s with a roll-off plateau C(q_r) on q_0 < q < q_r, with
 * the magnification zeta = q_s / q_r and x = q_0 / q_r (x = 1: no plateau).
 *
 * Misuse (status.h): the int functions return IM_EINVAL for a NULL interface, punch, array or
 * output, naming the function and the argument.
 * Threads: thread-safe (each call keeps nothing); the GSL handler is switched as said above.
 */
#ifndef INDENTMAP_THEORY_H
#define INDENTMAP_THEORY_H

#include "indentmap/indenter.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Contact area: the erf law and its normalising pressure (eqs. 1, 2 and the Appendix) ---- */

/* Eq. (2)'s constant k in p_rough = h'rms E* / k; the paper takes k = 2. */
#define IM_THEORY_K_DEFAULT 2.0

/* The pressure p_n that normalises the erf law A/A0 = erf(p / p_n). */
typedef enum im_theory_normalisation {
    /* p_PR = 2 p_rough / sqrt(pi) = 2 E* h'rms / (sqrt(pi) k): Pastewka and Robbins, the paper's
     * eqs. (1), (3), (6), (10) and (12), whose erf argument sqrt(pi)/2 p / p_rough is p / p_PR. */
    IM_THEORY_NORMALISATION_PR = 0,
    /* p_MG = sqrt(2 V) = E* h'rms / sqrt(2): Manners and Greenwood, eq. (19); k plays no part.
     * With k = 2, p_MG = sqrt(pi / 2) p_PR. */
    IM_THEORY_NORMALISATION_MG = 1
} im_theory_normalisation;

/* The rough interface: what the erf law needs to know about the surface and the materials. */
typedef struct im_theory_interface {
    double slope_rms; /* h'rms >= 0; 0 is a smooth surface (full contact wherever p > 0) */
    double e_star;    /* plane-strain composite modulus E* > 0 (1: stresses in units of E*) */
    double k;         /* eq. (2)'s constant, > 0 */
    im_theory_normalisation normalisation;
} im_theory_interface;

/* E* = 1, k = IM_THEORY_K_DEFAULT, the paper's normalisation p_PR. */
im_theory_interface im_theory_interface_default(double slope_rms);

/* Eq. (2): p_rough = h'rms E* / k (0 for a smooth surface). */
int im_theory_p_rough(const im_theory_interface *rough, double *p_rough);

/* p_n of the interface's normalisation (p_PR or p_MG above; 0 for a smooth surface). */
int im_theory_normalising_pressure(const im_theory_interface *rough, double *p_n);

/* Eq. (1), nominally flat contact: A/A0 = erf(p_mean / p_n), p_mean >= 0 in the units of E*.
 * A smooth surface (p_n = 0) gives 1 for p_mean > 0 and 0 for p_mean = 0. */
int im_theory_flat_area_ratio(const im_theory_interface *rough, double p_mean, double *ratio);

/* ---- The sphere, for comparison (eq. 3) ---- */

/* Hertz: A_Hertz = pi a^2 = pi (3 N R / (4 E*))^(2/3) for load N >= 0, radius R > 0, E* > 0. */
int im_theory_hertz_area(double load, double radius, double e_star, double *area);

/* Eq. (3): A = A_Hertz erf(p_s / p_n) with the Hertzian mean pressure p_s = N / A_Hertz (with the
 * PR normalisation this is the paper's erf(sqrt(pi)/2 p_s / p_rough)). N = 0 gives A = 0. */
int im_theory_sphere_area(const im_theory_interface *rough, double load, double radius, double *area);

/* The crossover load N_c at which N_c / A_Hertz = p_rough (eq. 2's, whatever the normalisation):
 * N_c = pi^3 (3/4)^2 (h'rms / k)^3 E* R^2; with k = 2 the paper's pi^3 (3/4)^2 (h'rms/2)^3 E* R^2.
 * Below N_c the rough, linear regime; above it the smooth Hertzian one. */
int im_theory_sphere_crossover_load(const im_theory_interface *rough, double radius, double *load);

/* ---- The cone (eqs. 4-12, 19) ----
 *
 * Everything dimensionless about the cone depends on one number, the erf scale
 * beta = p_m,c / p_n (the smooth cone's mean pressure over the normalising pressure):
 *   constant density, eq. (6):   A/A_cone = erf(beta)
 *   local density, eqs. (10-11): gamma(r) = erf(beta acosh(a / r))
 *   variable density, eq. (12):  A/A_cone = 2 int_0^1 s erf(beta acosh(1 / s)) ds,  s = r / a
 * With the PR normalisation beta = sqrt(pi)/2 rho_c and these are the paper's equations.
 *
 * Limits. Small beta: both area ratios -> (2/sqrt(pi)) beta, which is rho_c for PR, eq. (8):
 * the mean of acosh(a/r) over the disc is exactly 1 (the mean pressure is p_m,c), so constant
 * and variable density agree to first order. They part at third order, through the disc's mean
 * of acosh^3, pi^2/4 instead of 1: for PR, eq. (6) = rho_c - pi rho_c^3 / 12 + O(rho_c^5) and
 * eq. (12) = rho_c - pi^3 rho_c^3 / 48 + O(rho_c^5), so eq. (12) < eq. (6). Large beta:
 * 1 - eq. (6) = erfc(beta) ~ exp(-beta^2) / (beta sqrt(pi)), while the low pressure near the rim
 * keeps 1 - eq. (12) ~ 1 / (2 beta^2) - 1 / (2 beta^4) (= 2 / (pi rho_c^2) to leading order). */

/* Eq. (4): p_m,c = E* cot(alpha) / 2. */
int im_theory_cone_mean_pressure(double alpha_deg, double e_star, double *p_mean);

/* Eq. (5): A_cone = 2 N / (E* cot(alpha)) for load N >= 0. */
int im_theory_cone_area(double load, double alpha_deg, double e_star, double *area);

/* Eq. (7) for any k: rho_c = p_m,c / p_rough = k cot(alpha) / (2 h'rms) (cot(alpha) / h'rms for
 * k = 2); independent of E* and of the load. A smooth surface gives +INFINITY. */
int im_theory_cone_rho(const im_theory_interface *rough, double alpha_deg, double *rho_c);

/* beta = p_m,c / p_n from rho_c >= 0 (+INFINITY allowed): sqrt(pi)/2 rho_c for PR, sqrt(2) rho_c / k
 * for MG (k > 0). */
int im_theory_erf_scale(double rho_c, im_theory_normalisation normalisation, double k, double *beta);

/* Eq. (8), generalised to either normalisation: A ~ (2/sqrt(pi)) beta A_cone = 2 N / (sqrt(pi) p_n),
 * the small-beta limit of eqs. (6) and (12) (k N / (E* h'rms) for PR). Needs h'rms > 0, N >= 0. */
int im_theory_cone_area_small_rho(const im_theory_interface *rough, double load, double *area);

/* Eq. (6), constant density: erf(beta), beta >= 0 (+INFINITY gives 1). */
int im_theory_cone_area_ratio_constant(double beta, double *ratio);

/* Eq. (12), variable density, integrated in the radius as written (in t = 1 - r/a, so that the
 * rim lies where doubles are dense): adaptive Gauss-Kronrod with Wynn extrapolation (GSL qags),
 * which copes with the integrand's endpoint singularities (the square root acosh(1/s) ~ sqrt(2 t)
 * at the rim, the logarithm of acosh(1/s) at the apex). For beta > 1 it integrates the complement
 * 2 int s erfc(...) ds instead, only where beta acosh(1/s) < 27 (beyond, erfc < 1e-318), so that
 * the narrow rim of partial contact is never missed. Relative accuracy about 1e-12. beta = 0
 * gives 0 exactly; from beta = 1e8 on (and for +INFINITY) the ratio is 1 exactly, because
 * 1 - ratio <= 1 / (2 beta^2) rounds away. beta >= 0. */
int im_theory_cone_area_ratio_variable(double beta, double *ratio);

/* The same ratio by Greenwood's quadrature (the Appendix), an independent route to eq. (12):
 * 2 int_0^inf sinh(q) / cosh^3(q) erf(beta q) dq, which is eq. (19), int f_P(p) erf(p / p_n) dp,
 * with the cone's pressure distribution F_P = tanh^2(p / p_m,c). The integrand is smooth; the same
 * complement for beta > 1 and the same ends as eq. (12) above. */
int im_theory_cone_area_ratio_greenwood(double beta, double *ratio);

/* Eq. (11) divided by p_m,c: p(r) / p_m,c = acosh(a / r) for 0 <= r/a <= 1 (+INFINITY at the apex,
 * 0 at the rim). */
int im_theory_cone_pressure(double r_over_a, double *p_over_mean);

/* Eqs. (10)-(11): the local density of contact gamma(r) = erf(beta acosh(a / r)), the paper's
 * Fig. 1, for beta >= 0 and 0 <= r/a <= 1. gamma = 1 at the apex (beta > 0), 0 at the rim. */
int im_theory_cone_contact_density(double beta, double r_over_a, double *gamma);

/* ---- Any axisymmetric punch: the local density of contact (beyond the paper) ----
 *
 * The paper's closing remark generalised: gamma(r) = erf(p(r) / p_n) with the smooth pressure p(r)
 * of the punch, and A / A_smooth = (1 / (pi a^2)) int_0^a 2 pi r gamma(r) dr, where A_smooth = pi a^2
 * is the smooth contact area at the same load (A_cone, A_Hertz, the flat punch's pi a^2). With
 * s = r / a the smooth pressures divided by their mean p_m = N / A_smooth are
 *     cone (Love):        acosh(1 / s)                 (p_m = p_m,c, eq. 4)
 *     sphere (Hertz):     (3/2) sqrt(1 - s^2)          (p_m = N / A_Hertz, eq. 3's p_s)
 *     flat (Boussinesq):  1 / (2 sqrt(1 - s^2))        (p_m = N / (pi a^2); infinite at the rim)
 * so that, as for the cone, everything depends on one number, beta = p_m / p_n; with the PR
 * normalisation beta = sqrt(pi)/2 p_m / p_rough (im_theory_erf_scale with rho = p_m / p_rough).
 * The constant-density approximation is erf(beta) for every punch (eq. 3 for the sphere, eq. 6 for
 * the cone: im_theory_cone_area_ratio_constant). For small beta every punch gives
 * A / A_smooth ~ (2 / sqrt(pi)) beta, the linear erf law at the mean pressure. Unlike the cone, the
 * sphere and the flat punch have closed forms (derived in docs/theory.md; the tests check them):
 *     sphere, b = 3 beta / 2:  erf(b) (1 - 1 / (2 b^2)) + exp(-b^2) / (b sqrt(pi))
 *     flat,   c = beta / 2:    erf(c) + 2 c exp(-c^2) / sqrt(pi) - 2 c^2 erfc(c)
 * The flat punch's edge singularity saturates gamma at the rim (gamma -> 1) and makes it the most
 * nearly uniform of the three: 1 - A / A_smooth ~ 8 exp(-beta^2 / 4) / (beta^3 sqrt(pi)), whereas
 * the sphere's vanishing pressure at the rim leaves 1 / (2 b^2) out of contact. */

/* p(r) / p_m of the punch's smooth contact at s = r / a in [0, 1] (+INFINITY at the cone's apex
 * and the flat punch's rim, 0 at the cone's and the sphere's rims). IM_EINVAL for s outside
 * [0, 1] or an unknown kind. */
int im_theory_punch_pressure(enum im_punch_kind kind, double r_over_a, double *p_over_mean);

/* gamma(r) = erf(beta p(r) / p_m) for beta = p_m / p_n >= 0 and s = r / a in [0, 1]; 0 where the
 * pressure or beta is 0, 1 where the pressure is infinite (beta > 0). */
int im_theory_punch_contact_density(enum im_punch_kind kind, double beta, double r_over_a, double *gamma);

/* A / A_smooth = 2 int_0^1 s gamma(s) ds for beta = p_m / p_n >= 0. The cone is eq. (12)
 * (im_theory_cone_area_ratio_variable). The sphere and the flat punch are integrated by GSL's qags
 * in u = sqrt(1 - s^2) (s ds = -u du), which removes the rim's square-root singularity and turns the
 * flat punch's infinite edge pressure into erf(beta / (2 u)) -> 1 as u -> 0, a bounded integrand:
 * A / A_smooth = 2 int_0^1 u erf(beta P(u)) du with P = 3u/2 (sphere) or 1 / (2u) (flat). Above
 * beta = 1 the complement 1 - A / A_smooth is integrated instead, only where erfc is representable,
 * as for the cone. Relative accuracy about 1e-12; beta = 0 gives 0, a ratio within rounding of 1
 * gives 1. Errors as the cone's. */
int im_theory_punch_area_ratio(enum im_punch_kind kind, double beta, double *ratio);

/* The smooth mean pressure p_m = N / A_smooth of a punch at load N > 0: the cone's p_m,c (alpha in
 * degrees in `size`), N / A_Hertz for a sphere of radius `size`, N / (pi a^2) for a flat punch of
 * radius a = `size` (E* in e_star; lengths and loads in consistent units). */
int im_theory_punch_mean_pressure(enum im_punch_kind kind, double size, double load, double e_star, double *p_mean);

/* ---- Measuring k (eq. 2) on nominally flat contact ----
 * Eq. (1) with p_rough = h'rms E* / k reads A/A0 = erf(sqrt(pi)/2 k x) in the dimensionless mean
 * pressure x = p_m / (h'rms E*), linear (A/A0 ~ k x) for small x. */

typedef struct im_theory_k_fit {
    double k;            /* least-squares k of A/A0 = erf(sqrt(pi)/2 k x) over all points */
    double k_error;      /* its standard error, sqrt(RSS / (n - 1) / sum J^2), J = dA/dk; 0 for one point */
    double k_linear;     /* least-squares slope of A/A0 = k x through the origin, over A/A0 <= 0.5 */
    int linear_points;   /* how many points that slope used (0: none, k_linear NaN) */
    double rms_residual; /* rms of A/A0 - erf(...) at the fitted k */
} im_theory_k_fit;

/* Fits k to count >= 1 points (x_i > 0 finite, 0 <= A_i <= 1) by Gauss-Newton from the linear
 * estimate; the erf law is monotone in k, so the 1-D least-squares problem has one minimum.
 * IM_EINVAL naming the first bad point, IM_ENOCONV if Gauss-Newton does not settle in 100 steps. */
int im_theory_fit_k(const double *pressure_ratio, const double *area_fraction, int count, im_theory_k_fit *out);

/* ---- The theory beside a simulated history ----
 * Per step of an indentation (approach w from first touch, load N), the smooth punch's closed forms
 * and the rough-contact area ratios, written as the theory columns of every history file. */

/* The column names of im_theory_step, in order (CSV). */
#define IM_THEORY_STEP_COLUMNS "load_smooth,area_smooth,area_ratio_constant,area_ratio_gamma"

typedef struct im_theory_step {
    double load_smooth;         /* the smooth punch's N(w): Love (cone), Hertz, Boussinesq (flat) */
    double area_smooth;         /* A_smooth(N): A_cone (eq. 5), A_Hertz, pi a^2; 0 at N = 0 */
    double area_ratio_constant; /* erf(p_m / p_n) at p_m = N / A_smooth: eq. (6) (cone), eq. (3)
                                   (sphere); NaN at N = 0, 1 on a smooth surface */
    double area_ratio_gamma;    /* the local density's integral: eq. (12) (cone), the Hertz or
                                   Boussinesq gamma integral; NaN at N = 0, 1 on a smooth surface */
} im_theory_step;
/* For a user-given profile punch (indenter.h) load_smooth and area_smooth are Sneddon's
 * (axisymmetric; NaN for a 2-D profile) and both area ratios are NaN (the rough-contact theory is
 * for the cone, the sphere and the flat punch). */

/* The theory of a step for punch (indenter.h; lengths in its units, loads in E* length^2) on the
 * rough interface (its E*, k and normalisation). w, N >= 0. IM_EINVAL for a bad punch, interface,
 * w or N; a quadrature's status otherwise. */
int im_theory_step_columns(const im_indenter *punch, const im_theory_interface *rough, double approach, double load,
                           im_theory_step *out);

/* ---- Wavy surfaces in the periodic half-space (docs/theory.md, "Wavy surfaces") ----
 * Closed forms for a rigid flat pressed on one period L of an elastic wavy surface at nominal mean
 * pressure p_m (E* and lengths in consistent units). Each takes the pressure as a ratio and returns
 * an area fraction A/A0, NaN for a ratio outside the stated range. */

/* 1-D, h = Delta cos(2 pi x / L) (Westergaard; Johnson, Contact Mechanics, 13.2): the exact contact
 * fraction 2a / L = (2 / pi) asin(sqrt(p_m / p*)), p* = pi E* Delta / L, for 0 <= p_m / p* <= 1. */
double im_theory_wavy1d_area_fraction(double pressure_ratio);

/* 2-D, h = Delta (cos(2 pi x / L) + cos(2 pi y / L)): complete contact from p^ = 2 pi E* Delta / L
 * on (the sum of two 1-D modes; exact). pressure_ratio = p_m / p^ in (0, 1].
 * Light load (Johnson, Greenwood & Higginson 1985): each crest a Hertzian sphere of radius
 * R = L^2 / (4 pi^2 Delta) carrying p_m L^2: A/A0 = pi (3 p_m / (8 pi p^))^(2/3) (leading order in
 * a/L; the neighbours' correction is O((a/L)^2)). */
double im_theory_wavy2d_light_area_fraction(double pressure_ratio);

/* Near complete contact: one hole per period around the trough, a penny-shaped crack closing
 * smoothly (zero stress intensity) in the complete contact's pressure p_m - p^ + p^ (pi r / L)^2:
 * 1 - A/A0 = (3 / (2 pi)) (1 - p_m / p^) (leading order in 1 - p_m / p^; JGH's form). */
double im_theory_wavy2d_near_full_area_fraction(double pressure_ratio);

/* ---- Adhesion: the smooth references of the adhesive solver (issue 27; solver.h, "Adhesion") ----
 * The Maugis-Dugdale law: a constant tensile stress sigma0 = w / delta_c wherever the gap is at most
 * delta_c (the solver's adhesion_range), the work of adhesion w = sigma0 delta_c. Units as above: E* a
 * stress, w a stress times a length, lengths (R, a, delta_c, approaches) in one unit, loads in E* times
 * length^2. Loads are signed (negative: the punch is pulled); an approach is that of distant points,
 * 0 where the undeformed surfaces touch (the solver's w; negative: pulled away). Derivations and
 * sources in docs/theory.md, "Adhesion". */

typedef struct im_theory_adhesion {
    double e_star; /* E* > 0 */
    double work;   /* w > 0: the work of adhesion */
    double range;  /* delta_c > 0: the gap over which sigma0 = w / delta_c pulls (the JKR forms below,
                      the limit delta_c -> 0, do not use it) */
} im_theory_adhesion;

/* A point of an adhesive contact: contact radius a, the adhesive zone's outer radius c >= a (c = a for
 * the JKR forms), signed load N and approach delta. */
typedef struct im_theory_adhesive_point {
    double contact_radius;
    double zone_radius;
    double load;
    double approach;
} im_theory_adhesive_point;

/* Maugis's transition parameter of a sphere (paraboloid z = r^2 / (2R)) of radius R > 0:
 * lambda = 2 sigma0 (R / (pi w K^2))^(1/3), K = 4 E* / 3 (lambda > 5: JKR; lambda < 0.1: DMT). */
int im_theory_maugis_lambda(const im_theory_adhesion *law, double radius, double *lambda);

/* The Maugis-Dugdale sphere (Maugis 1992, in Johnson & Greenwood's 1997 reduced form) at contact
 * radius a > 0: with K = 4 E* / 3, A = a (K / (pi w R^2))^(1/3) and m = c / a, s = sqrt(m^2 - 1),
 *   lambda A^2 / 2 [s + (m^2 - 2) atan s] + 4 lambda^2 A / 3 [s atan s - m + 1] = 1   (m by Brent)
 *   N / (pi w R) = A^3 - lambda A^2 [s + m^2 atan s]
 *   delta (K^2 / (pi^2 w^2 R))^(1/3) = A^2 - 4 lambda A s / 3.
 * Large lambda gives JKR (N = 4 E* a^3 / (3 R) - sqrt(8 pi w E* a^3), delta = a^2 / R - sqrt(2 pi w a / E*)),
 * small lambda DMT (Hertz's N(a) less 2 pi w R, delta = a^2 / R). lambda by im_theory_maugis_lambda. */
int im_theory_md_sphere(const im_theory_adhesion *law, double radius, double contact_radius,
                        im_theory_adhesive_point *out);

/* The sphere's pull-off under load control: the least load of the curve above (-3/2 pi w R at large
 * lambda, -2 pi w R at small), found by golden section in a over (0, 3 L], L = (pi w R^2 / K)^(1/3)
 * (the search's lower end is 1e-4 L). Its contact radius exceeds the separation's (below), so it lies on
 * the branch fixed grips follow: the least load of a displacement-controlled retraction is the same. */
int im_theory_md_sphere_pull_off(const im_theory_adhesion *law, double radius, im_theory_adhesive_point *out);

/* The separation under displacement control: the point of least approach (JKR's fixed-grip
 * separation at -5/6 pi w R at large lambda). Below lambda ~ 0.94 the contact shrinks to nothing without a
 * jump: the least approach is at a -> 0, returned at the search's lower end 1e-4 L. */
int im_theory_md_sphere_separation(const im_theory_adhesion *law, double radius, im_theory_adhesive_point *out);

/* The load at approach delta on the branch that displacement control follows (the contact radius above
 * the separation's); NaN below the separation's approach (separated). */
int im_theory_md_sphere_load_at_approach(const im_theory_adhesion *law, double radius, double approach, double *load);

/* Kendall (1971), the adhesive flat punch of radius a > 0 (the JKR limit: law->range unused): in full
 * contact N = 2 E* a delta (Boussinesq), until the edge crack's energy release rate
 * N^2 / (8 pi a^3 E*) reaches w: pull-off at N_c = -sqrt(8 pi a^3 E* w), delta_c = -sqrt(2 pi w a / E*),
 * under load and displacement control alike (the crack grows unstably inwards). */
int im_theory_kendall_pull_off(const im_theory_adhesion *law, double punch_radius, im_theory_adhesive_point *out);

/* The flat punch's load at approach delta: 2 E* a delta from Kendall's delta_c on, NaN below it. */
int im_theory_kendall_load_at_approach(const im_theory_adhesion *law, double punch_radius, double approach,
                                       double *load);

/* The JKR cone (Maugis & Barquins 1981; Love's cone z = r cot(alpha), alpha the semi-opening angle in
 * degrees, with Kendall's flat punch superposed and the energy balance G = w; law->range unused):
 *   N = (pi / 2) E* cot(alpha) a^2 - sqrt(8 pi E* w a^3),   delta = (pi / 2) cot(alpha) a - sqrt(2 pi w a / E*). */
int im_theory_jkr_cone(const im_theory_adhesion *law, double alpha_deg, double contact_radius,
                       im_theory_adhesive_point *out);

/* The JKR cone's pull-off (least load; on the fixed-grip branch too): a_c = 18 w / (pi E* cot^2 alpha),
 * N_c = -54 w^2 / (pi E* cot^3 alpha). */
int im_theory_jkr_cone_pull_off(const im_theory_adhesion *law, double alpha_deg, im_theory_adhesive_point *out);

/* ---- Roughness (eqs. 13-15) ---- */

/* Eq. (13) divided by the prefactor A: m_n / A = T(n) q_r^(n - 2H) ((1 - x^(n+2)) / (n + 2)
 * + (zeta^(n - 2H) - 1) / (n - 2H)), T(0) = 2 pi, T(2) = pi, T(4) = 3 pi / 4; n in {0, 2, 4}.
 * Returns NaN for any other n or for parameters outside 0 < H < 1, q_r > 0, zeta >= 1,
 * 0 <= x <= 1. */
double im_theory_moment(int n, double hurst, double q_r, double zeta, double x);

/* h_rms of a surface with the given h'rms from the exact moments of eq. (13):
 * h_rms = h'rms sqrt(m0 / (2 m2)). */
double im_theory_height_rms_moments(double slope_rms, double hurst, double q_r, double zeta, double x);

/* The paper's eq. (15), the large-zeta approximation of eq. (14) without roll-off:
 * h_rms ~ h'rms sqrt((1 - H) / H) zeta^H / q_s. It drops zeta^(2H - 2) against 1, which for the
 * paper's surfaces (H = 0.8, zeta = 128) makes it 7.5% lower than the exact moments. */
double im_theory_height_rms_eq15(double slope_rms, double hurst, double q_s, double zeta);

#ifdef __cplusplus
}
#endif

#endif
