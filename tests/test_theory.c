/* Tests of the theory module against the paper's Table 1, closed-form limits derived by hand,
 * independent quadratures of the definitions, and its refusals of bad input. */
#include "support.h"

#include "indentmap/status.h"
#include "indentmap/theory.h"
#include "theory/quadrature.h"

#include <float.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <string.h>

static const double PAPER_ALPHA = 80.0;
static const double PAPER_SLOPES[] = {0.01, 0.02, 0.04, 0.08, 0.16};

/* ---- helpers ---- */

static double erf_scale_pr(double rho_c)
{
    double beta;
    assert_int_equal(im_theory_erf_scale(rho_c, IM_THEORY_NORMALISATION_PR, IM_THEORY_K_DEFAULT, &beta), IM_OK);
    return beta;
}

static double variable_ratio(double beta)
{
    double ratio = NAN;
    int status = im_theory_cone_area_ratio_variable(beta, &ratio);
    if (status != IM_OK)
        fail_msg("eq. (12) at beta = %g: %s", beta, im_last_error());
    return ratio;
}

static double greenwood_ratio(double beta)
{
    double ratio = NAN;
    int status = im_theory_cone_area_ratio_greenwood(beta, &ratio);
    if (status != IM_OK)
        fail_msg("Greenwood at beta = %g: %s", beta, im_last_error());
    return ratio;
}

static double constant_ratio(double beta)
{
    double ratio = NAN;
    assert_int_equal(im_theory_cone_area_ratio_constant(beta, &ratio), IM_OK);
    return ratio;
}

static double log_spaced(double lo, double hi, int i, int count)
{
    return lo * pow(hi / lo, (double)i / (count - 1));
}

/* The test's own quadrature (GSL qags, tight tolerances); fails the test on a GSL error. */
static double integrate(double (*f)(double, void *), void *params, double lo, double hi)
{
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(2000);
    assert_non_null(w);
    gsl_function function = {.function = f, .params = params};
    double value, error;
    int status = gsl_integration_qags(&function, lo, hi, 0.0, 1e-13, 2000, w, &value, &error);
    gsl_integration_workspace_free(w);
    if (status != GSL_SUCCESS)
        fail_msg("test quadrature on [%g, %g]: %s", lo, hi, gsl_strerror(status));
    return value;
}

static void assert_failure_names(int status, int expected, const char *word)
{
    assert_int_equal(status, expected);
    if (!strstr(im_last_error(), word))
        fail_msg("message '%s' does not name '%s'", im_last_error(), word);
}

/* ---- the paper's numbers ---- */

/* Table 1: rho_c and the eq. (12) column for alpha = 80 degrees, to the printed decimals. */
static void table1_is_reproduced(void **state)
{
    (void)state;
    const double rho_printed[] = {17.63, 8.82, 4.41, 2.20, 1.10};
    const double eq12_printed[] = {0.998, 0.992, 0.969, 0.894, 0.719};
    for (int i = 0; i < 5; ++i) {
        im_theory_interface rough = im_theory_interface_default(PAPER_SLOPES[i]);
        double rho_c;
        assert_int_equal(im_theory_cone_rho(&rough, PAPER_ALPHA, &rho_c), IM_OK);
        assert_close(rho_c, rho_printed[i], 0.005);
        assert_close(variable_ratio(erf_scale_pr(rho_c)), eq12_printed[i], 0.0005);
    }
}

/* Eq. (7) with k = 2 is cot(alpha) / h'rms; E* cancels. */
static void rho_is_cot_alpha_over_slope(void **state)
{
    (void)state;
    im_theory_interface rough = im_theory_interface_default(0.037);
    rough.e_star = 123.0;
    double rho_c;
    assert_int_equal(im_theory_cone_rho(&rough, 63.0, &rho_c), IM_OK);
    assert_true(test_relative_difference(rho_c, tan((90.0 - 63.0) * M_PI / 180.0) / 0.037) < 1e-14);
    rough.k = 3.0; /* rho_c = p_m,c / p_rough grows with k */
    assert_int_equal(im_theory_cone_rho(&rough, 63.0, &rho_c), IM_OK);
    assert_true(test_relative_difference(rho_c, 1.5 * tan(27.0 * M_PI / 180.0) / 0.037) < 1e-14);
}

/* ---- two routes to eq. (12) ---- */

static void integral_form_matches_greenwood(void **state)
{
    (void)state;
    for (int i = 0; i < 41; ++i) {
        double rho_c = log_spaced(1e-4, 1e4, i, 41);
        double beta = erf_scale_pr(rho_c);
        double radial = variable_ratio(beta), greenwood = greenwood_ratio(beta);
        if (test_relative_difference(radial, greenwood) > 1e-8)
            fail_msg("rho_c = %g: eq. (12) %.17g, Greenwood %.17g", rho_c, radial, greenwood);
    }
    /* Manners and Greenwood's normalisation: a different beta for the same rho_c. */
    for (int i = 0; i < 9; ++i) {
        double rho_c = log_spaced(1e-3, 1e3, i, 9), beta;
        assert_int_equal(im_theory_erf_scale(rho_c, IM_THEORY_NORMALISATION_MG, 2.0, &beta), IM_OK);
        assert_true(test_relative_difference(variable_ratio(beta), greenwood_ratio(beta)) <= 1e-8);
    }
}

/* ---- limits derived by hand (see the header): small and large rho_c ---- */

/* Third-order terms: eq. (6) = rho - pi rho^3 / 12, eq. (12) = rho - pi^3 rho^3 / 48. */
static void small_rho_series(void **state)
{
    (void)state;
    const double rho_c = 1e-3, beta = erf_scale_pr(rho_c);
    double cube = rho_c * rho_c * rho_c;
    assert_true(test_relative_difference((rho_c - variable_ratio(beta)) / cube, M_PI * M_PI * M_PI / 48) < 1e-4);
    assert_true(test_relative_difference((rho_c - greenwood_ratio(beta)) / cube, M_PI * M_PI * M_PI / 48) < 1e-4);
    assert_true(test_relative_difference((rho_c - constant_ratio(beta)) / cube, M_PI / 12) < 1e-4);
}

/* Eq. (8): ratio / rho_c -> 1, down to the smallest normal doubles, without underflow. */
static void small_rho_limit_is_eq8(void **state)
{
    (void)state;
    const double tiny[] = {1e-8, 1e-30, 1e-100, 1e-300, DBL_MIN};
    for (size_t i = 0; i < sizeof tiny / sizeof *tiny; ++i) {
        double beta = erf_scale_pr(tiny[i]);
        assert_close(variable_ratio(beta) / tiny[i], 1.0, 1e-12);
        assert_close(greenwood_ratio(beta) / tiny[i], 1.0, 1e-12);
        assert_close(constant_ratio(beta) / tiny[i], 1.0, 1e-12);
    }
    /* In physical terms: A -> rho_c A_cone = 2 N / (E* h'rms) for k = 2. */
    im_theory_interface rough = im_theory_interface_default(0.05);
    rough.e_star = 3.0;
    double area, cone_area, rho_c;
    assert_int_equal(im_theory_cone_area_small_rho(&rough, 7.0, &area), IM_OK);
    assert_true(test_relative_difference(area, 2.0 * 7.0 / (3.0 * 0.05)) < 1e-14);
    assert_int_equal(im_theory_cone_area(7.0, 89.99999, 3.0, &cone_area), IM_OK);
    assert_int_equal(im_theory_cone_rho(&rough, 89.99999, &rho_c), IM_OK);
    assert_true(test_relative_difference(variable_ratio(erf_scale_pr(rho_c)) * cone_area, area) < 1e-8);
}

/* Large beta: 1 - eq. (12) = 1 / (2 beta^2) - 1 / (2 beta^4) + O(beta^-6). */
static void large_rho_asymptote(void **state)
{
    (void)state;
    const double betas[] = {300.0, 1000.0};
    for (int i = 0; i < 2; ++i) {
        double b2 = betas[i] * betas[i], expected = 0.5 / b2 - 0.5 / (b2 * b2);
        assert_true(test_relative_difference(1.0 - variable_ratio(betas[i]), expected) < 1e-9);
        assert_true(test_relative_difference(1.0 - greenwood_ratio(betas[i]), expected) < 1e-9);
    }
}

/* ---- extremes: no NaN, no Inf, no abort ---- */

static void assert_ratio_sane(double beta)
{
    double v = variable_ratio(beta), g = greenwood_ratio(beta), c = constant_ratio(beta);
    if (!(v >= 0.0 && v <= 1.0 && g >= 0.0 && g <= 1.0 && c >= 0.0 && c <= 1.0))
        fail_msg("beta = %g: ratios %g %g %g outside [0, 1]", beta, v, g, c);
}

static void extremes_are_finite(void **state)
{
    (void)state;
    /* rho_c = 0 exactly and rho_c = infinity. */
    assert_true(variable_ratio(0.0) == 0.0 && greenwood_ratio(0.0) == 0.0 && constant_ratio(0.0) == 0.0);
    assert_true(variable_ratio(INFINITY) == 1.0 && greenwood_ratio(INFINITY) == 1.0);
    /* erf arguments far past 30, up to where 1 - ratio is below the last bit. */
    const double huge[] = {30.0, 100.0, 1e4, 1e6, 1e8, 1e10, 1e20, 1e150, 1e300, DBL_MAX};
    for (size_t i = 0; i < sizeof huge / sizeof *huge; ++i) {
        assert_ratio_sane(huge[i]);
        assert_close(variable_ratio(huge[i]), 1.0, 0.5 / (huge[i] * huge[i]) + DBL_EPSILON);
        assert_close(greenwood_ratio(huge[i]), 1.0, 0.5 / (huge[i] * huge[i]) + DBL_EPSILON);
    }
    /* A smooth surface: rho_c = infinity, full contact. */
    im_theory_interface smooth = im_theory_interface_default(0.0);
    double rho_c, beta;
    assert_int_equal(im_theory_cone_rho(&smooth, PAPER_ALPHA, &rho_c), IM_OK);
    assert_true(isinf(rho_c) && rho_c > 0);
    assert_int_equal(im_theory_erf_scale(rho_c, IM_THEORY_NORMALISATION_MG, 2.0, &beta), IM_OK);
    assert_true(variable_ratio(beta) == 1.0 && constant_ratio(beta) == 1.0);
    /* alpha -> 90 degrees: cot(alpha) -> 0, rho_c tiny but positive. */
    im_theory_interface rough = im_theory_interface_default(0.1);
    assert_int_equal(im_theory_cone_rho(&rough, 90.0 - 1e-13, &rho_c), IM_OK);
    assert_true(rho_c > 0.0 && rho_c < 1e-13);
    assert_close(variable_ratio(erf_scale_pr(rho_c)) / rho_c, 1.0, 1e-12);
    /* alpha -> 0: a needle, rho_c huge. */
    assert_int_equal(im_theory_cone_rho(&rough, 1e-300, &rho_c), IM_OK);
    assert_ratio_sane(erf_scale_pr(rho_c));
}

/* The application's GSL error handler: counts its calls. */
static int application_handler_calls;
static void application_gsl_handler(const char *reason, const char *file, int line, int gsl_errno)
{
    (void)reason, (void)file, (void)line, (void)gsl_errno;
    ++application_handler_calls;
}

static double not_a_number(double x, void *params)
{
    (void)x, (void)params;
    return NAN;
}

/* The library leaves GSL's handler as the application set it: installed after an im_theory call,
 * and not called for the library's own GSL errors (a quadrature of NaN, which qags reports), which
 * become statuses instead. */
static void application_gsl_handler_is_kept(void **state)
{
    (void)state;
    application_handler_calls = 0;
    gsl_error_handler_t *before = gsl_set_error_handler(application_gsl_handler);
    double ratio, value;
    assert_int_equal(im_theory_cone_area_ratio_variable(0.5, &ratio), IM_OK);
    assert_int_not_equal(theory_integrate(not_a_number, NULL, 0.0, 1.0, "NaN", &value), IM_OK);
    assert_int_equal(application_handler_calls, 0);
    assert_ptr_equal(gsl_set_error_handler(before), application_gsl_handler);
    /* the application's handler really is GSL's: a bad argument of the application's own call reaches it */
    gsl_set_error_handler(application_gsl_handler);
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(10);
    gsl_function f = {.function = not_a_number, .params = NULL};
    assert_int_not_equal(gsl_integration_qags(&f, 0, 1, 0, 1e-10, 100, w, &value, &ratio), GSL_SUCCESS);
    gsl_integration_workspace_free(w);
    assert_int_equal(application_handler_calls, 1);
    gsl_set_error_handler(before);
}

/* ---- eq. (12) against eq. (6): the paper's Fig. 2 ---- */

static void variable_density_lies_below_constant(void **state)
{
    (void)state;
    double largest_gap = 0.0;
    for (int i = 0; i < 81; ++i) {
        double beta = erf_scale_pr(log_spaced(1e-4, 1e4, i, 81));
        double gap = constant_ratio(beta) - variable_ratio(beta);
        if (!(gap > 0.0))
            fail_msg("beta = %g: eq. (6) - eq. (12) = %g, expected > 0", beta, gap);
        largest_gap = fmax(largest_gap, gap);
    }
    /* The gap vanishes at both ends, (pi^3/48 - pi/12) rho^3 and 2 / (pi rho^2) ... */
    assert_true(constant_ratio(erf_scale_pr(1e-4)) - variable_ratio(erf_scale_pr(1e-4)) < 1e-12);
    assert_true(constant_ratio(erf_scale_pr(1e4)) - variable_ratio(erf_scale_pr(1e4)) < 1e-8);
    /* ... and is of the order of 10% in between, as Fig. 2 shows. */
    assert_true(largest_gap > 0.05 && largest_gap < 0.2);
}

/* ---- the local density gamma(r) of eqs. (10)-(11) ---- */

typedef struct physical_cone {
    double e_star, alpha_deg, slope_rms, k, a;
} physical_cone;

/* gamma(r) from its definition with dimensional quantities: the smooth cone's pressure
 * p(r) = (E* cot(alpha) / 2) ln((a + sqrt(a^2 - r^2)) / r) in the erf law of eq. (10). */
static double gamma_definition(double r, void *params)
{
    const physical_cone *c = params;
    double p_mean = 0.5 * c->e_star / tan(c->alpha_deg * M_PI / 180.0);
    double p = p_mean * log((c->a + sqrt(c->a * c->a - r * r)) / r);
    return erf(0.5 * sqrt(M_PI) * p / (c->slope_rms * c->e_star / c->k));
}

static double gamma_library(const physical_cone *c, double r)
{
    im_theory_interface rough = {c->slope_rms, c->e_star, c->k, IM_THEORY_NORMALISATION_PR};
    double rho_c, beta, gamma;
    assert_int_equal(im_theory_cone_rho(&rough, c->alpha_deg, &rho_c), IM_OK);
    assert_int_equal(im_theory_erf_scale(rho_c, rough.normalisation, rough.k, &beta), IM_OK);
    assert_int_equal(im_theory_cone_contact_density(beta, r / c->a, &gamma), IM_OK);
    return gamma;
}

static double disc_weighted_gamma(double r, void *params) { return 2.0 * M_PI * r * gamma_definition(r, params); }

static void gamma_matches_definition(void **state)
{
    (void)state;
    physical_cone cone = {2.5, 80.0, 0.04, 2.0, 3.7};
    for (int i = 1; i < 100; ++i) {
        double r = cone.a * i / 100.0;
        assert_close(gamma_library(&cone, r), gamma_definition(r, &cone), 1e-14);
    }
    assert_true(gamma_library(&cone, 0.0) == 1.0 && gamma_library(&cone, cone.a) == 0.0);
    /* Its integral over the disc of radius a, divided by pi a^2, is eq. (12), whatever a is. */
    double disc_mean = integrate(disc_weighted_gamma, &cone, 0.0, cone.a) / (M_PI * cone.a * cone.a);
    double rho_c = 1.0 / tan(80.0 * M_PI / 180.0) / 0.04;
    assert_true(test_relative_difference(disc_mean, variable_ratio(erf_scale_pr(rho_c))) < 1e-9);
}

static double disc_weighted_pressure_power(double s, void *params)
{
    double p;
    assert_int_equal(im_theory_cone_pressure(s, &p), IM_OK);
    return 2.0 * s * pow(p, *(const double *)params);
}

/* Eq. (11): the pressure's mean over the disc is p_m,c (eq. 4), its third moment pi^2/4 p_m,c^3
 * (which sets eq. 12's cubic term); the rim is free, the apex singular. */
static void cone_pressure_moments(void **state)
{
    (void)state;
    double power = 1.0;
    assert_close(integrate(disc_weighted_pressure_power, &power, 0.0, 1.0), 1.0, 1e-12);
    power = 3.0;
    assert_close(integrate(disc_weighted_pressure_power, &power, 0.0, 1.0), M_PI * M_PI / 4.0, 1e-11);
    double p;
    assert_int_equal(im_theory_cone_pressure(1.0, &p), IM_OK);
    assert_true(p == 0.0);
    assert_int_equal(im_theory_cone_pressure(0.0, &p), IM_OK);
    assert_true(isinf(p));
    /* Next to the rim acosh(1/s) = sqrt(2 (1 - s)) (1 + O(1 - s)), to full precision. */
    assert_int_equal(im_theory_cone_pressure(1.0 - 0x1p-40, &p), IM_OK);
    assert_true(test_relative_difference(p, sqrt(2.0 * 0x1p-40)) < 1e-11);
}

/* ---- the erf law, its normalisations, the sphere ---- */

static void normalising_pressures(void **state)
{
    (void)state;
    im_theory_interface rough = {0.08, 4.0, 2.0, IM_THEORY_NORMALISATION_PR};
    double p_rough, p_pr, p_mg;
    assert_int_equal(im_theory_p_rough(&rough, &p_rough), IM_OK);
    assert_true(test_relative_difference(p_rough, 0.08 * 4.0 / 2.0) < 1e-15);
    assert_int_equal(im_theory_normalising_pressure(&rough, &p_pr), IM_OK);
    rough.normalisation = IM_THEORY_NORMALISATION_MG;
    assert_int_equal(im_theory_normalising_pressure(&rough, &p_mg), IM_OK);
    /* The Appendix: p_MG = sqrt(2 V), V = E*^2 h'rms^2 / 4, and p_MG = sqrt(pi/2) p_PR for k = 2. */
    assert_true(test_relative_difference(p_mg, sqrt(2.0 * 0.25 * 16.0 * 0.08 * 0.08)) < 1e-15);
    assert_true(test_relative_difference(p_mg, sqrt(M_PI / 2.0) * p_pr) < 1e-15);
    /* The erf scale agrees with p_m,c / p_n computed from the pressures. */
    double p_mean, rho_c, beta;
    assert_int_equal(im_theory_cone_mean_pressure(75.0, 4.0, &p_mean), IM_OK);
    assert_int_equal(im_theory_cone_rho(&rough, 75.0, &rho_c), IM_OK);
    assert_int_equal(im_theory_erf_scale(rho_c, IM_THEORY_NORMALISATION_MG, 2.0, &beta), IM_OK);
    assert_true(test_relative_difference(beta, p_mean / p_mg) < 1e-14);
    assert_int_equal(im_theory_erf_scale(rho_c, IM_THEORY_NORMALISATION_PR, 2.0, &beta), IM_OK);
    assert_true(test_relative_difference(beta, p_mean / p_pr) < 1e-14);
}

/* Eq. (1): linear below, A/A0 ~ p_m / p_rough (PR), saturating above. */
static void flat_erf_law(void **state)
{
    (void)state;
    im_theory_interface rough = {0.1, 1.0, 2.0, IM_THEORY_NORMALISATION_PR};
    double ratio;
    assert_int_equal(im_theory_flat_area_ratio(&rough, 1e-6, &ratio), IM_OK);
    assert_true(test_relative_difference(ratio, 1e-6 / 0.05) < 1e-9);
    assert_int_equal(im_theory_flat_area_ratio(&rough, 10.0, &ratio), IM_OK);
    assert_true(ratio == 1.0);
    assert_int_equal(im_theory_flat_area_ratio(&rough, 0.0, &ratio), IM_OK);
    assert_true(ratio == 0.0);
    rough.slope_rms = 0.0;
    assert_int_equal(im_theory_flat_area_ratio(&rough, 1e-300, &ratio), IM_OK);
    assert_true(ratio == 1.0);
}

/* Eq. (3), Hertz and the crossover load N_c (k = 2: the paper's pi^3 (3/4)^2 (h'/2)^3 E* R^2). */
static void sphere(void **state)
{
    (void)state;
    const double radius = 50.0, e_star = 2.0, slope = 0.1;
    im_theory_interface rough = {slope, e_star, 2.0, IM_THEORY_NORMALISATION_PR};
    double n_c, hertz, area;
    assert_int_equal(im_theory_sphere_crossover_load(&rough, radius, &n_c), IM_OK);
    assert_true(test_relative_difference(n_c, pow(M_PI, 3) * 9.0 / 16.0 * pow(slope / 2.0, 3) * e_star * radius *
                                                  radius) < 1e-14);
    /* At N_c the Hertzian mean pressure equals p_rough, so A / A_Hertz = erf(sqrt(pi) / 2). */
    assert_int_equal(im_theory_hertz_area(n_c, radius, e_star, &hertz), IM_OK);
    assert_true(test_relative_difference(n_c / hertz, slope * e_star / 2.0) < 1e-13);
    assert_int_equal(im_theory_sphere_area(&rough, n_c, radius, &area), IM_OK);
    assert_true(test_relative_difference(area / hertz, erf(sqrt(M_PI) / 2.0)) < 1e-13);
    /* Hertz: a^3 = 3 N R / (4 E*). */
    double a = cbrt(3.0 * 10.0 * radius / (4.0 * e_star));
    assert_int_equal(im_theory_hertz_area(10.0, radius, e_star, &hertz), IM_OK);
    assert_true(test_relative_difference(hertz, M_PI * a * a) < 1e-14);
    /* Far below N_c: linear, A = N / p_rough; far above: Hertz. */
    assert_int_equal(im_theory_sphere_area(&rough, 1e-9 * n_c, radius, &area), IM_OK);
    assert_true(test_relative_difference(area, 1e-9 * n_c / (slope * e_star / 2.0)) < 1e-5);
    assert_int_equal(im_theory_sphere_area(&rough, 1e6 * n_c, radius, &area), IM_OK);
    assert_int_equal(im_theory_hertz_area(1e6 * n_c, radius, e_star, &hertz), IM_OK);
    assert_true(test_relative_difference(area, hertz) < 1e-14);
    assert_int_equal(im_theory_sphere_area(&rough, 0.0, radius, &area), IM_OK);
    assert_true(area == 0.0);
}

/* Eqs. (4)-(5): p_m,c = E* cot(alpha) / 2 and N = p_m,c A_cone. */
static void cone_closed_forms(void **state)
{
    (void)state;
    double p_mean, area;
    assert_int_equal(im_theory_cone_mean_pressure(45.0, 3.0, &p_mean), IM_OK);
    assert_close(p_mean, 1.5, 1e-15);
    assert_int_equal(im_theory_cone_area(12.0, 80.0, 1.0, &area), IM_OK);
    assert_true(test_relative_difference(area, 2.0 * 12.0 * tan(80.0 * M_PI / 180.0)) < 1e-14);
}

/* ---- roughness: eq. (13) against its definition ---- */

typedef struct spectrum {
    int n;
    double hurst, q_r, q_s, q_0, q;
} spectrum;

static double angular_integrand(double theta, void *params)
{
    const spectrum *s = params;
    return pow(s->q * cos(theta), s->n);
}

/* C(q) q int_0^2pi (q cos theta)^n dtheta, with C = q^(-2(1+H)) above q_r and C(q_r) below. */
static double radial_moment_integrand(double q, void *params)
{
    spectrum *s = params;
    s->q = q;
    double angular = integrate(angular_integrand, s, 0.0, 2.0 * M_PI);
    double c = pow(fmax(q, s->q_r), -2.0 * (1.0 + s->hurst));
    return c * q * angular;
}

static void moments_match_their_definition(void **state)
{
    (void)state;
    gsl_set_error_handler_off();
    const double q_r = 2.0 * M_PI / 512.0, zeta = 128.0;
    const double xs[] = {1.0, 0.5, 0.25};
    for (int n = 0; n <= 4; n += 2) {
        for (int j = 0; j < 3; ++j) {
            spectrum s = {n, 0.8, q_r, zeta * q_r, xs[j] * q_r, 0.0};
            double direct = integrate(radial_moment_integrand, &s, s.q_r, s.q_s);
            if (xs[j] < 1.0)
                direct += integrate(radial_moment_integrand, &s, s.q_0, s.q_r);
            double closed = im_theory_moment(n, 0.8, q_r, zeta, xs[j]);
            if (test_relative_difference(closed, direct) > 1e-10)
                fail_msg("m%d, x = %g: eq. (13) %.17g, quadrature %.17g", n, xs[j], closed, direct);
        }
    }
}

/* ---- other punches: the local density of contact of the sphere and the flat punch ---- */

enum { LEGENDRE_ORDER = 24, LEGENDRE_PANELS = 48 };

/* The test's own Gauss-Legendre rule in long double: nodes by Newton's iteration on P_n. */
static void legendre_rule(long double node[LEGENDRE_ORDER], long double weight[LEGENDRE_ORDER])
{
    const int n = LEGENDRE_ORDER;
    for (int i = 0; i < n; ++i) {
        long double x = cosl(M_PI * (i + 0.75L) / (n + 0.5L)), derivative = 0;
        for (int iteration = 0; iteration < 100; ++iteration) {
            long double p0 = 1, p1 = x;
            for (int k = 2; k <= n; ++k) {
                long double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            derivative = n * (x * p1 - p0) / (x * x - 1);
            long double step = p1 / derivative;
            x -= step;
            if (fabsl(step) < 1e-19L)
                break;
        }
        node[i] = x;
        weight[i] = 2 / ((1 - x * x) * derivative * derivative);
    }
}

/* A / A_smooth = 2 int_0^1 s gamma(s) ds in s = cos(phi), where both the sphere's square-root
 * rim and the flat punch's infinite edge pressure are smooth: 2 int cos sin erf(b P(sin)) dphi,
 * composite Gauss-Legendre on panels halving towards the rim phi = 0 (the flat punch's gamma turns
 * from erf(beta / 2) to 1 where sin(phi) ~ beta), then one panel down to 0. */
static double own_area_ratio(enum im_punch_kind kind, double beta)
{
    long double node[LEGENDRE_ORDER], weight[LEGENDRE_ORDER], sum = 0;
    legendre_rule(node, weight);
    long double hi = (long double)M_PI / 2;
    for (int j = 0; j <= LEGENDRE_PANELS; ++j) {
        long double lo = j < LEGENDRE_PANELS ? hi / 2 : 0, half = (hi - lo) / 2;
        for (int i = 0; i < LEGENDRE_ORDER; ++i) {
            long double phi = lo + half * (node[i] + 1), s = sinl(phi);
            long double pressure = kind == IM_PUNCH_SPHERE ? 1.5L * s : 0.5L / s;
            sum += weight[i] * half * 2 * cosl(phi) * s * erfl(beta * pressure);
        }
        hi = lo;
    }
    return (double)sum;
}

static double punch_ratio(enum im_punch_kind kind, double beta)
{
    double ratio = NAN;
    if (im_theory_punch_area_ratio(kind, beta, &ratio) != IM_OK)
        fail_msg("punch %d at beta = %g: %s", (int)kind, beta, im_last_error());
    return ratio;
}

/* Closed forms derived by hand (docs/theory.md): with u = sqrt(1 - s^2) the sphere's ratio is
 * 2 int_0^1 u erf(b u) du, b = 3 beta / 2, and the flat punch's 2 int_0^1 u erf(c / u) du, c = beta / 2,
 * both integrable by parts. */
static double hertz_closed_form(double beta)
{
    double b = 1.5 * beta;
    return erf(b) * (1.0 - 0.5 / (b * b)) + exp(-b * b) / (b * sqrt(M_PI));
}

static double boussinesq_closed_form(double beta)
{
    double c = 0.5 * beta;
    return erf(c) + 2.0 * c * exp(-c * c) / sqrt(M_PI) - 2.0 * c * c * erfc(c);
}

/* GSL's qags in u against the test's long double Gauss-Legendre in theta, from the linear regime
 * (where the closed form cancels) to saturation. */
static void hertz_gamma_integral_matches_own_quadrature(void **state)
{
    (void)state;
    for (int i = 0; i < 41; ++i) {
        double beta = log_spaced(1e-3, 30.0, i, 41), ours = own_area_ratio(IM_PUNCH_SPHERE, beta);
        double library = punch_ratio(IM_PUNCH_SPHERE, beta);
        if (test_relative_difference(library, ours) > 1e-12)
            fail_msg("sphere beta = %g: library %.17g, own quadrature %.17g", beta, library, ours);
        if (beta > 0.1 && test_relative_difference(library, hertz_closed_form(beta)) > 1e-12)
            fail_msg("sphere beta = %g: library %.17g, closed form %.17g", beta, library, hertz_closed_form(beta));
    }
}

static void boussinesq_gamma_integral_matches_own_quadrature(void **state)
{
    (void)state;
    for (int i = 0; i < 41; ++i) {
        double beta = log_spaced(1e-3, 30.0, i, 41), ours = own_area_ratio(IM_PUNCH_FLAT, beta);
        double library = punch_ratio(IM_PUNCH_FLAT, beta);
        if (test_relative_difference(library, ours) > 1e-12)
            fail_msg("flat beta = %g: library %.17g, own quadrature %.17g", beta, library, ours);
        if (test_relative_difference(library, boussinesq_closed_form(beta)) > 1e-12)
            fail_msg("flat beta = %g: library %.17g, closed form %.17g", beta, library, boussinesq_closed_form(beta));
    }
}

/* The flat punch's limits: the linear erf law at the mean pressure,
 * 2 beta / sqrt(pi) - beta^2 / 2 + beta^3 / (6 sqrt(pi)) (no beta^4 term),
 * for small beta; for large beta the edge singularity leaves only 8 exp(-beta^2/4) / (beta^3 sqrt(pi))
 * (1 - 12 / beta^2) out of contact, far less than the sphere's 2 / (9 beta^2). */
static void flat_punch_limits(void **state)
{
    (void)state;
    for (double beta = 1e-8; beta < 2e-3; beta *= 10.0) {
        double series = 2.0 * beta / sqrt(M_PI) - 0.5 * beta * beta + beta * beta * beta / (6.0 * sqrt(M_PI));
        if (test_relative_difference(punch_ratio(IM_PUNCH_FLAT, beta), series) > 1e-11)
            fail_msg("flat beta = %g: %.17g, series %.17g", beta, punch_ratio(IM_PUNCH_FLAT, beta), series);
    }
    for (double beta = 4.0; beta <= 8.0; beta += 2.0) {
        /* the closed form's complement without cancellation: (1 + 2c^2) erfc(c) - 2c exp(-c^2) / sqrt(pi) */
        double c = 0.5 * beta, missing = 1.0 - punch_ratio(IM_PUNCH_FLAT, beta);
        double expected = (1.0 + 2.0 * c * c) * erfc(c) - 2.0 * c * exp(-c * c) / sqrt(M_PI);
        double asymptote = 8.0 * exp(-c * c) / (beta * beta * beta * sqrt(M_PI));
        if (fabs(missing - expected) > 1e-12 * expected + 4.0 * DBL_EPSILON)
            fail_msg("flat beta = %g: 1 - ratio %.6g, closed form %.6g", beta, missing, expected);
        assert_true(test_relative_difference(expected, asymptote * (1.0 - 12.0 / (beta * beta))) <
                    200.0 / pow(beta, 4));
    }
    for (double beta = 20.0; beta <= 50.0; beta += 10.0) {
        double sphere_missing = 1.0 - punch_ratio(IM_PUNCH_SPHERE, beta);
        assert_true(test_relative_difference(sphere_missing, 2.0 / (9.0 * beta * beta)) < 1e-9);
    }
    assert_true(punch_ratio(IM_PUNCH_FLAT, 60.0) == 1.0);
    assert_true(punch_ratio(IM_PUNCH_SPHERE, 1e9) == 1.0);
    assert_true(punch_ratio(IM_PUNCH_FLAT, 0.0) == 0.0);
}

/* Every punch's ratio starts as the erf law at its mean pressure: the disc's mean of p / p_m is 1. */
static void every_punch_is_linear_at_small_beta(void **state)
{
    (void)state;
    const enum im_punch_kind kinds[] = {IM_PUNCH_CONE, IM_PUNCH_SPHERE, IM_PUNCH_FLAT};
    for (int k = 0; k < 3; ++k) {
        double beta = 1e-7, ratio = punch_ratio(kinds[k], beta);
        assert_true(test_relative_difference(ratio, 2.0 * beta / sqrt(M_PI)) < 1e-6);
        assert_true(punch_ratio(kinds[k], 1.3) < constant_ratio(1.3)); /* erf is concave */
    }
    assert_true(punch_ratio(IM_PUNCH_CONE, 2.0) == variable_ratio(2.0));
}

/* gamma(r) from the smooth pressures: Hertz's 3/2 sqrt(1 - s^2), Boussinesq's 1 / (2 sqrt(1 - s^2)),
 * Love's acosh(1/s); the mean pressure of each punch at a load. */
static void punch_pressures_and_densities(void **state)
{
    (void)state;
    double p, gamma;
    assert_int_equal(im_theory_punch_pressure(IM_PUNCH_SPHERE, 0.6, &p), IM_OK);
    assert_true(test_relative_difference(p, 1.5 * 0.8) < 1e-15);
    assert_int_equal(im_theory_punch_pressure(IM_PUNCH_FLAT, 0.6, &p), IM_OK);
    assert_true(test_relative_difference(p, 0.5 / 0.8) < 1e-15);
    assert_int_equal(im_theory_punch_pressure(IM_PUNCH_FLAT, 1.0, &p), IM_OK);
    assert_true(isinf(p));
    assert_int_equal(im_theory_punch_contact_density(IM_PUNCH_FLAT, 0.7, 1.0, &gamma), IM_OK);
    assert_true(gamma == 1.0);
    assert_int_equal(im_theory_punch_contact_density(IM_PUNCH_SPHERE, 0.7, 1.0, &gamma), IM_OK);
    assert_true(gamma == 0.0);
    assert_int_equal(im_theory_punch_contact_density(IM_PUNCH_SPHERE, 0.7, 0.6, &gamma), IM_OK);
    assert_true(test_relative_difference(gamma, erf(0.7 * 1.2)) < 1e-15);
    double cone;
    assert_int_equal(im_theory_punch_contact_density(IM_PUNCH_CONE, 0.7, 0.3, &gamma), IM_OK);
    assert_int_equal(im_theory_cone_contact_density(0.7, 0.3, &cone), IM_OK);
    assert_true(gamma == cone);
    double hertz;
    assert_int_equal(im_theory_punch_mean_pressure(IM_PUNCH_SPHERE, 50.0, 7.0, 2.0, &p), IM_OK);
    assert_int_equal(im_theory_hertz_area(7.0, 50.0, 2.0, &hertz), IM_OK);
    assert_true(test_relative_difference(p, 7.0 / hertz) < 1e-15);
    assert_int_equal(im_theory_punch_mean_pressure(IM_PUNCH_FLAT, 3.0, 7.0, 2.0, &p), IM_OK);
    assert_true(test_relative_difference(p, 7.0 / (M_PI * 9.0)) < 1e-15);
    assert_failure_names(im_theory_punch_area_ratio((enum im_punch_kind)9, 1.0, &p), IM_EINVAL, "punch");
    assert_failure_names(im_theory_punch_area_ratio(IM_PUNCH_FLAT, -1.0, &p), IM_EINVAL, "beta");
    assert_failure_names(im_theory_punch_pressure(IM_PUNCH_SPHERE, 1.5, &p), IM_EINVAL, "r/a");
    assert_failure_names(im_theory_punch_mean_pressure(IM_PUNCH_SPHERE, 50.0, 0.0, 1.0, &p), IM_EINVAL, "N");
    assert_failure_names(im_theory_punch_mean_pressure(IM_PUNCH_FLAT, -1.0, 1.0, 1.0, &p), IM_EINVAL, "a");
}

/* The theory columns of a history step: Love's, Hertz's and Boussinesq's N(w), A_smooth(N) and the
 * area ratios at the smooth mean pressure, each against its closed form written out here. */
static void step_columns_are_the_closed_forms(void **state)
{
    (void)state;
    im_theory_interface rough = im_theory_interface_default(0.08);
    rough.e_star = 2.5;
    im_theory_step step;
    im_indenter cone = im_indenter_cone(80.0);
    const double cot = tan(10.0 * M_PI / 180.0), w = 3.0, load = 40.0;
    assert_int_equal(im_theory_step_columns(&cone, &rough, w, load, &step), IM_OK);
    assert_true(test_relative_difference(step.load_smooth, 2.0 * 2.5 * w * w / (M_PI * cot)) < 1e-14);
    assert_true(test_relative_difference(step.area_smooth, 2.0 * load / (2.5 * cot)) < 1e-14);
    double beta = erf_scale_pr(cot / 0.08); /* eq. (7): independent of the load */
    assert_true(test_relative_difference(step.area_ratio_gamma, variable_ratio(beta)) < 1e-14);
    assert_true(test_relative_difference(step.area_ratio_constant, erf(beta)) < 1e-14);

    im_indenter sphere = im_indenter_sphere(500.0);
    assert_int_equal(im_theory_step_columns(&sphere, &rough, w, load, &step), IM_OK);
    assert_true(test_relative_difference(step.load_smooth, 4.0 / 3.0 * 2.5 * sqrt(500.0) * pow(w, 1.5)) < 1e-14);
    double hertz = M_PI * pow(0.75 * load * 500.0 / 2.5, 2.0 / 3.0), p_rough = 0.08 * 2.5 / 2.0;
    assert_true(test_relative_difference(step.area_smooth, hertz) < 1e-14);
    beta = erf_scale_pr(load / hertz / p_rough);
    assert_true(test_relative_difference(step.area_ratio_gamma, hertz_closed_form(beta)) < 1e-12);
    assert_true(test_relative_difference(step.area_ratio_constant, erf(beta)) < 1e-14);

    im_indenter flat = im_indenter_flat(20.0);
    assert_int_equal(im_theory_step_columns(&flat, &rough, w, load, &step), IM_OK);
    assert_true(test_relative_difference(step.load_smooth, 2.0 * 20.0 * 2.5 * w) < 1e-14);
    beta = erf_scale_pr(load / (M_PI * 400.0) / p_rough);
    assert_true(test_relative_difference(step.area_ratio_gamma, boussinesq_closed_form(beta)) < 1e-12);

    assert_int_equal(im_theory_step_columns(&flat, &rough, 0.0, 0.0, &step), IM_OK);
    assert_true(step.load_smooth == 0.0 && step.area_smooth == 0.0 && isnan(step.area_ratio_gamma));
    rough.slope_rms = 0.0; /* smooth: full contact */
    assert_int_equal(im_theory_step_columns(&sphere, &rough, w, load, &step), IM_OK);
    assert_true(step.area_ratio_gamma == 1.0 && step.area_ratio_constant == 1.0);
    assert_failure_names(im_theory_step_columns(&flat, &rough, -1.0, 1.0, &step), IM_EINVAL, "w = ");
}

/* ---- measuring k ---- */

/* A synthetic A(p) curve with a planted k: the fit recovers it to rounding; with a deterministic
 * +-0.004 scatter, within three standard errors, and the error bar covers the scatter. */
static void k_fit_recovers_planted_k(void **state)
{
    (void)state;
    enum { POINTS = 24 };
    const double planted = 2.37;
    double x[POINTS], area[POINTS], noisy[POINTS];
    for (int i = 0; i < POINTS; ++i) {
        x[i] = 0.025 * (i + 1);
        area[i] = erf(0.5 * sqrt(M_PI) * planted * x[i]);
        noisy[i] = fmin(1.0, area[i] + (i % 2 ? 0.004 : -0.004) * (i % 3 ? 1.0 : -1.0));
    }
    im_theory_k_fit fit;
    assert_int_equal(im_theory_fit_k(x, area, POINTS, &fit), IM_OK);
    if (test_relative_difference(fit.k, planted) > 1e-12)
        fail_msg("k = %.17g, planted %.17g", fit.k, planted);
    assert_true(fit.k_error < 1e-12 && fit.rms_residual < 1e-14);
    /* the linear slope over A/A0 <= 0.5 (x <= 0.227 here) is below k: erf bends down */
    assert_int_equal(fit.linear_points, 9);
    assert_true(fit.k_linear < planted && fit.k_linear > 0.9 * planted);
    assert_int_equal(im_theory_fit_k(x, noisy, POINTS, &fit), IM_OK);
    assert_true(fabs(fit.k - planted) < 3.0 * fit.k_error);
    assert_true(fit.k_error > 1e-3 && fit.k_error < 0.05);
    assert_close(fit.rms_residual, 0.004, 0.001);
    /* the paper's k = 2 is not what this curve says */
    assert_true(fabs(fit.k - 2.0) > 10.0 * fit.k_error);
}

static void k_fit_refusals(void **state)
{
    (void)state;
    double x[2] = {0.1, 0.2}, area[2] = {0.2, 1.5};
    im_theory_k_fit fit;
    assert_failure_names(im_theory_fit_k(x, area, 2, &fit), IM_EINVAL, "A/A0 = 1.5");
    x[0] = -1.0;
    assert_failure_names(im_theory_fit_k(x, area, 1, &fit), IM_EINVAL, "x = p_m");
    assert_failure_names(im_theory_fit_k(x, area, 0, &fit), IM_EINVAL, "0 points");
}

/* ---- refusals ---- */

static void bad_input_is_refused(void **state)
{
    (void)state;
    double out;
    assert_failure_names(im_theory_cone_area_ratio_variable(-1.0, &out), IM_EINVAL, "beta");
    assert_failure_names(im_theory_cone_area_ratio_greenwood(NAN, &out), IM_EINVAL, "beta");
    assert_failure_names(im_theory_cone_area_ratio_constant(-0.1, &out), IM_EINVAL, "beta");
    assert_failure_names(im_theory_cone_contact_density(1.0, 1.5, &out), IM_EINVAL, "r/a");
    assert_failure_names(im_theory_cone_pressure(-0.1, &out), IM_EINVAL, "r/a");
    assert_failure_names(im_theory_erf_scale(-2.0, IM_THEORY_NORMALISATION_PR, 2.0, &out), IM_EINVAL, "rho_c");
    assert_failure_names(im_theory_erf_scale(2.0, IM_THEORY_NORMALISATION_MG, 0.0, &out), IM_EINVAL, "k");
    assert_failure_names(im_theory_erf_scale(2.0, (im_theory_normalisation)7, 2.0, &out), IM_EINVAL, "normalisation");
    const double bad_alpha[] = {0.0, 90.0, -5.0, 120.0, NAN};
    im_theory_interface rough = im_theory_interface_default(0.1);
    for (int i = 0; i < 5; ++i) {
        assert_failure_names(im_theory_cone_rho(&rough, bad_alpha[i], &out), IM_EINVAL, "alpha");
        assert_failure_names(im_theory_cone_mean_pressure(bad_alpha[i], 1.0, &out), IM_EINVAL, "alpha");
    }
    rough.slope_rms = -0.01;
    assert_failure_names(im_theory_cone_rho(&rough, 80.0, &out), IM_EINVAL, "h'rms");
    rough = im_theory_interface_default(0.1);
    rough.e_star = 0.0;
    assert_failure_names(im_theory_p_rough(&rough, &out), IM_EINVAL, "E*");
    rough = im_theory_interface_default(0.1);
    rough.k = -2.0;
    assert_failure_names(im_theory_normalising_pressure(&rough, &out), IM_EINVAL, "k");
    rough = im_theory_interface_default(0.0);
    assert_failure_names(im_theory_cone_area_small_rho(&rough, 1.0, &out), IM_EINVAL, "h'rms");
    rough = im_theory_interface_default(0.1);
    assert_failure_names(im_theory_sphere_area(&rough, -1.0, 1.0, &out), IM_EINVAL, "N");
    assert_failure_names(im_theory_hertz_area(1.0, 0.0, 1.0, &out), IM_EINVAL, "R");
    assert_failure_names(im_theory_flat_area_ratio(&rough, INFINITY, &out), IM_EINVAL, "p_mean");
    assert_failure_names(im_theory_cone_area(-3.0, 80.0, 1.0, &out), IM_EINVAL, "N");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(table1_is_reproduced),
        cmocka_unit_test(rho_is_cot_alpha_over_slope),
        cmocka_unit_test(integral_form_matches_greenwood),
        cmocka_unit_test(small_rho_series),
        cmocka_unit_test(small_rho_limit_is_eq8),
        cmocka_unit_test(large_rho_asymptote),
        cmocka_unit_test(extremes_are_finite),
        cmocka_unit_test(application_gsl_handler_is_kept),
        cmocka_unit_test(variable_density_lies_below_constant),
        cmocka_unit_test(gamma_matches_definition),
        cmocka_unit_test(cone_pressure_moments),
        cmocka_unit_test(normalising_pressures),
        cmocka_unit_test(flat_erf_law),
        cmocka_unit_test(sphere),
        cmocka_unit_test(cone_closed_forms),
        cmocka_unit_test(moments_match_their_definition),
        cmocka_unit_test(bad_input_is_refused),
        cmocka_unit_test(hertz_gamma_integral_matches_own_quadrature),
        cmocka_unit_test(boussinesq_gamma_integral_matches_own_quadrature),
        cmocka_unit_test(flat_punch_limits),
        cmocka_unit_test(every_punch_is_linear_at_small_beta),
        cmocka_unit_test(punch_pressures_and_densities),
        cmocka_unit_test(step_columns_are_the_closed_forms),
        cmocka_unit_test(k_fit_recovers_planted_k),
        cmocka_unit_test(k_fit_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
