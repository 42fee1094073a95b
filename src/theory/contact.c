/* Closed forms of the contact theory: the erf law, the sphere and the cone (eqs. 1-11). */
#include "indentmap/status.h"
#include "core/args.h"
#include "theory/cone.h"
#include "indentmap/theory.h"

#include <math.h>

static const double DEGREE = M_PI / 180.0;

im_theory_interface im_theory_interface_default(double slope_rms)
{
    return (im_theory_interface){.slope_rms = slope_rms,
                                 .e_star = 1.0,
                                 .k = IM_THEORY_K_DEFAULT,
                                 .normalisation = IM_THEORY_NORMALISATION_PR};
}

static int check_interface(const im_theory_interface *rough)
{
    if (!rough)
        return im_fail(IM_EINVAL, "rough interface: NULL");
    if (!(rough->slope_rms >= 0.0 && isfinite(rough->slope_rms)))
        return im_fail(IM_EINVAL, "h'rms = %g: expected a finite h'rms >= 0", rough->slope_rms);
    if (!(rough->e_star > 0.0 && isfinite(rough->e_star)))
        return im_fail(IM_EINVAL, "E* = %g: expected a finite E* > 0", rough->e_star);
    if (!(rough->k > 0.0 && isfinite(rough->k)))
        return im_fail(IM_EINVAL, "k = %g: expected a finite k > 0", rough->k);
    if (rough->normalisation != IM_THEORY_NORMALISATION_PR && rough->normalisation != IM_THEORY_NORMALISATION_MG)
        return im_fail(IM_EINVAL, "normalisation = %d: expected PR (%d) or MG (%d)", (int)rough->normalisation,
                       IM_THEORY_NORMALISATION_PR, IM_THEORY_NORMALISATION_MG);
    return IM_OK;
}

static int check_alpha(double alpha_deg)
{
    if (!(alpha_deg > 0.0 && alpha_deg < 90.0))
        return im_fail(IM_EINVAL, "alpha = %g: expected 0 < alpha < 90 degrees", alpha_deg);
    return IM_OK;
}

static int check_nonnegative(const char *name, double value)
{
    if (!(value >= 0.0 && isfinite(value)))
        return im_fail(IM_EINVAL, "%s = %g: expected a finite %s >= 0", name, value, name);
    return IM_OK;
}

static int check_positive(const char *name, double value)
{
    if (!(value > 0.0 && isfinite(value)))
        return im_fail(IM_EINVAL, "%s = %g: expected a finite %s > 0", name, value, name);
    return IM_OK;
}

/* cot(alpha) through cos/sin, so that it stays accurate (and positive) as alpha -> 90 degrees. */
static double cot_degrees(double alpha_deg) { return cos(alpha_deg * DEGREE) / sin(alpha_deg * DEGREE); }

/* erf(p / p_n), with the smooth limit p_n = 0 (full contact wherever p > 0). */
static double erf_law(double p, double p_n)
{
    if (p == 0.0)
        return 0.0;
    return p_n > 0.0 ? erf(p / p_n) : 1.0;
}

int im_theory_p_rough(const im_theory_interface *rough, double *p_rough)
{
    ARG_REQUIRE(rough, "rough");
    ARG_REQUIRE(p_rough, "p_rough");
    int status = check_interface(rough);
    if (status != IM_OK)
        return status;
    *p_rough = rough->slope_rms * rough->e_star / rough->k;
    return IM_OK;
}

int im_theory_normalising_pressure(const im_theory_interface *rough, double *p_n)
{
    ARG_REQUIRE(rough, "rough");
    ARG_REQUIRE(p_n, "p_n");
    int status = check_interface(rough);
    if (status != IM_OK)
        return status;
    if (rough->normalisation == IM_THEORY_NORMALISATION_PR)
        *p_n = 2.0 / sqrt(M_PI) * rough->slope_rms * rough->e_star / rough->k;
    else
        *p_n = rough->e_star * rough->slope_rms / M_SQRT2;
    return IM_OK;
}

int im_theory_flat_area_ratio(const im_theory_interface *rough, double p_mean, double *ratio)
{
    ARG_REQUIRE(rough, "rough");
    ARG_REQUIRE(ratio, "ratio");
    double p_n;
    int status = im_theory_normalising_pressure(rough, &p_n);
    if (status == IM_OK)
        status = check_nonnegative("p_mean", p_mean);
    if (status == IM_OK)
        *ratio = erf_law(p_mean, p_n);
    return status;
}

int im_theory_hertz_area(double load, double radius, double e_star, double *area)
{
    ARG_REQUIRE(area, "area");
    int status = check_nonnegative("N", load);
    if (status == IM_OK)
        status = check_positive("R", radius);
    if (status == IM_OK)
        status = check_positive("E*", e_star);
    if (status == IM_OK)
        *area = M_PI * pow(0.75 * load * radius / e_star, 2.0 / 3.0);
    return status;
}

int im_theory_sphere_area(const im_theory_interface *rough, double load, double radius, double *area)
{
    ARG_REQUIRE(rough, "rough");
    ARG_REQUIRE(area, "area");
    double p_n, hertz;
    int status = im_theory_normalising_pressure(rough, &p_n);
    if (status == IM_OK)
        status = im_theory_hertz_area(load, radius, rough->e_star, &hertz);
    if (status != IM_OK)
        return status;
    *area = load > 0.0 ? hertz * erf_law(load / hertz, p_n) : 0.0;
    return IM_OK;
}

int im_theory_sphere_crossover_load(const im_theory_interface *rough, double radius, double *load)
{
    ARG_REQUIRE(rough, "rough");
    ARG_REQUIRE(load, "load");
    double p_rough;
    int status = im_theory_p_rough(rough, &p_rough);
    if (status == IM_OK)
        status = check_positive("R", radius);
    if (status != IM_OK)
        return status;
    /* N / (pi (3 N R / (4 E*))^(2/3)) = p_rough solved for N. */
    double e_star = rough->e_star;
    *load = pow(M_PI, 3) * 0.5625 * pow(p_rough / e_star, 3) * e_star * radius * radius;
    return IM_OK;
}

int im_theory_cone_mean_pressure(double alpha_deg, double e_star, double *p_mean)
{
    ARG_REQUIRE(p_mean, "p_mean");
    int status = check_alpha(alpha_deg);
    if (status == IM_OK)
        status = check_positive("E*", e_star);
    if (status == IM_OK)
        *p_mean = 0.5 * e_star * cot_degrees(alpha_deg);
    return status;
}

int im_theory_cone_area(double load, double alpha_deg, double e_star, double *area)
{
    ARG_REQUIRE(area, "area");
    double p_mean;
    int status = im_theory_cone_mean_pressure(alpha_deg, e_star, &p_mean);
    if (status == IM_OK)
        status = check_nonnegative("N", load);
    if (status == IM_OK)
        *area = load / p_mean;
    return status;
}

int im_theory_cone_rho(const im_theory_interface *rough, double alpha_deg, double *rho_c)
{
    ARG_REQUIRE(rough, "rough");
    ARG_REQUIRE(rho_c, "rho_c");
    double p_rough, p_mean;
    int status = im_theory_p_rough(rough, &p_rough);
    if (status == IM_OK)
        status = im_theory_cone_mean_pressure(alpha_deg, rough->e_star, &p_mean);
    if (status == IM_OK)
        *rho_c = p_rough > 0.0 ? p_mean / p_rough : INFINITY;
    return status;
}

int im_theory_erf_scale(double rho_c, im_theory_normalisation normalisation, double k, double *beta)
{
    ARG_REQUIRE(beta, "beta");
    if (!(rho_c >= 0.0))
        return im_fail(IM_EINVAL, "rho_c = %g: expected rho_c >= 0", rho_c);
    if (!(k > 0.0 && isfinite(k)))
        return im_fail(IM_EINVAL, "k = %g: expected a finite k > 0", k);
    /* beta = p_m,c / p_n = rho_c p_rough / p_n. */
    if (normalisation == IM_THEORY_NORMALISATION_PR)
        *beta = 0.5 * sqrt(M_PI) * rho_c;
    else if (normalisation == IM_THEORY_NORMALISATION_MG)
        *beta = M_SQRT2 * rho_c / k;
    else
        return im_fail(IM_EINVAL, "normalisation = %d: expected PR (%d) or MG (%d)", (int)normalisation,
                       IM_THEORY_NORMALISATION_PR, IM_THEORY_NORMALISATION_MG);
    return IM_OK;
}

int im_theory_cone_area_small_rho(const im_theory_interface *rough, double load, double *area)
{
    ARG_REQUIRE(rough, "rough");
    ARG_REQUIRE(area, "area");
    double p_n;
    int status = im_theory_normalising_pressure(rough, &p_n);
    if (status == IM_OK && !(p_n > 0.0))
        status = im_fail(IM_EINVAL, "h'rms = %g: the small-rho_c limit needs h'rms > 0", rough->slope_rms);
    if (status == IM_OK)
        status = check_nonnegative("N", load);
    if (status == IM_OK)
        *area = 2.0 * load / (sqrt(M_PI) * p_n);
    return status;
}

int theory_check_erf_scale(double beta)
{
    if (!(beta >= 0.0))
        return im_fail(IM_EINVAL, "beta = %g: expected an erf scale beta = p_m,c / p_n >= 0", beta);
    return IM_OK;
}

int im_theory_cone_area_ratio_constant(double beta, double *ratio)
{
    ARG_REQUIRE(ratio, "ratio");
    int status = theory_check_erf_scale(beta);
    if (status == IM_OK)
        *ratio = erf(beta);
    return status;
}

/* acosh(1/s) = log((1 + sqrt(1 - s^2)) / s) = log1p((t + sqrt(t (1 + s))) / s) with t = 1 - s:
 * every operation is relatively accurate, also where t is tiny. */
static double acosh_inverse(double s, double t) { return s == 0.0 ? INFINITY : log1p((t + sqrt(t * (1.0 + s))) / s); }

double theory_acosh_inverse(double s) { return acosh_inverse(s, 1.0 - s); }

double theory_acosh_inverse_from_rim(double t) { return acosh_inverse(1.0 - t, t); }

int im_theory_cone_pressure(double r_over_a, double *p_over_mean)
{
    ARG_REQUIRE(p_over_mean, "p_over_mean");
    if (!(r_over_a >= 0.0 && r_over_a <= 1.0))
        return im_fail(IM_EINVAL, "r/a = %g: expected 0 <= r/a <= 1", r_over_a);
    *p_over_mean = theory_acosh_inverse(r_over_a);
    return IM_OK;
}

int im_theory_cone_contact_density(double beta, double r_over_a, double *gamma)
{
    ARG_REQUIRE(gamma, "gamma");
    double p_over_mean = 0.0;
    int status = theory_check_erf_scale(beta);
    if (status == IM_OK)
        status = im_theory_cone_pressure(r_over_a, &p_over_mean);
    if (status != IM_OK)
        return status;
    /* beta = 0 or the rim (p = 0): no contact, also where the other factor is infinite. */
    *gamma = (beta == 0.0 || p_over_mean == 0.0) ? 0.0 : erf(beta * p_over_mean);
    return IM_OK;
}
