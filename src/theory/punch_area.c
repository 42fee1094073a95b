/* The local density of contact of any axisymmetric punch (the paper's closing remark): the smooth
 * pressures of the cone, the sphere and the flat punch, gamma(r), and A / A_smooth by quadrature.
 * The sphere and the flat punch are integrated in u = sqrt(1 - s^2) (see theory.h), where the
 * sphere's pressure is linear and the flat punch's edge singularity becomes a bounded erf. */
#include "indentmap/status.h"
#include "core/args.h"
#include "indentmap/theory.h"
#include "theory/cone.h"
#include "theory/quadrature.h"

#include <math.h>

/* As for the cone: the ratio itself up to this erf scale, its complement above. */
static const double COMPLEMENT_ABOVE = 1.0;
/* erfc(x) < 1e-318 for x >= 27. */
static const double ERFC_NEGLIGIBLE = 27.0;
/* The sphere leaves 1 - ratio ~ 1 / (2 b^2) out of contact, below 2^-54 from b = 1e8 on. */
static const double SPHERE_SATURATED_FROM = 1e8;
/* Hertz's peak pressure over the mean, and Boussinesq's pressure at the centre over the mean. */
static const double HERTZ_PEAK = 1.5;
static const double BOUSSINESQ_CENTRE = 0.5;

static int check_kind(enum im_punch_kind kind)
{
    if (kind != IM_PUNCH_CONE && kind != IM_PUNCH_SPHERE && kind != IM_PUNCH_FLAT)
        return im_fail(IM_EINVAL, "punch kind %d: expected cone (%d), sphere (%d) or flat (%d)", (int)kind,
                       IM_PUNCH_CONE, IM_PUNCH_SPHERE, IM_PUNCH_FLAT);
    return IM_OK;
}

int im_theory_punch_pressure(enum im_punch_kind kind, double r_over_a, double *p_over_mean)
{
    ARG_REQUIRE(p_over_mean, "p_over_mean");
    int status = check_kind(kind);
    if (status != IM_OK)
        return status;
    if (!(r_over_a >= 0.0 && r_over_a <= 1.0))
        return im_fail(IM_EINVAL, "r/a = %g: expected 0 <= r/a <= 1", r_over_a);
    /* sqrt((1 - s)(1 + s)) keeps its digits near the rim, where 1 - s^2 would not */
    double root = sqrt((1.0 - r_over_a) * (1.0 + r_over_a));
    switch (kind) {
    case IM_PUNCH_SPHERE: *p_over_mean = HERTZ_PEAK * root; break;
    case IM_PUNCH_FLAT: *p_over_mean = root > 0.0 ? BOUSSINESQ_CENTRE / root : INFINITY; break;
    default: *p_over_mean = theory_acosh_inverse(r_over_a); break;
    }
    return IM_OK;
}

int im_theory_punch_contact_density(enum im_punch_kind kind, double beta, double r_over_a, double *gamma)
{
    ARG_REQUIRE(gamma, "gamma");
    double p_over_mean = 0.0;
    int status = theory_check_erf_scale(beta);
    if (status == IM_OK)
        status = im_theory_punch_pressure(kind, r_over_a, &p_over_mean);
    if (status != IM_OK)
        return status;
    /* no pressure or beta = 0: no contact, also where the other factor is infinite */
    *gamma = (beta == 0.0 || p_over_mean == 0.0) ? 0.0 : erf(beta * p_over_mean);
    return IM_OK;
}

/* u erf(beta P(u)) / beta and u erfc(beta P(u)) in u = sqrt(1 - s^2), P = p / p_m. */
static double sphere_integrand(double u, void *params)
{
    return u * theory_erf_over_beta(*(const double *)params, HERTZ_PEAK * u);
}

static double sphere_complement_integrand(double u, void *params)
{
    return u * erfc(*(const double *)params * HERTZ_PEAK * u);
}

static double flat_integrand(double u, void *params)
{
    return u > 0.0 ? u * theory_erf_over_beta(*(const double *)params, BOUSSINESQ_CENTRE / u) : 0.0;
}

/* The same in v = log u: u^2 erf(beta / (2u)) / beta. */
static double flat_log_integrand(double v, void *params)
{
    double u = exp(v);
    return u * flat_integrand(u, params);
}

static double flat_complement_integrand(double u, void *params)
{
    return u > 0.0 ? u * erfc(*(const double *)params * BOUSSINESQ_CENTRE / u) : 0.0;
}

/* Where the complement's integrand is not zero in double precision: u < ERFC_NEGLIGIBLE / (b P')
 * for the sphere, u > beta / (2 ERFC_NEGLIGIBLE) for the flat punch. */
static void complement_interval(enum im_punch_kind kind, double beta, double *lo, double *hi)
{
    if (kind == IM_PUNCH_SPHERE) {
        *lo = 0.0;
        *hi = fmin(1.0, ERFC_NEGLIGIBLE / (HERTZ_PEAK * beta));
    } else {
        *lo = fmin(1.0, BOUSSINESQ_CENTRE * beta / ERFC_NEGLIGIBLE);
        *hi = 1.0;
    }
}

int im_theory_punch_area_ratio(enum im_punch_kind kind, double beta, double *ratio)
{
    ARG_REQUIRE(ratio, "ratio");
    int status = check_kind(kind);
    if (status == IM_OK)
        status = theory_check_erf_scale(beta);
    if (status != IM_OK)
        return status;
    if (kind == IM_PUNCH_CONE)
        return im_theory_cone_area_ratio_variable(beta, ratio);
    if (beta == 0.0 || (kind == IM_PUNCH_SPHERE && beta >= SPHERE_SATURATED_FROM)) {
        *ratio = beta == 0.0 ? 0.0 : 1.0;
        return IM_OK;
    }
    const int sphere = kind == IM_PUNCH_SPHERE;
    double integral;
    if (beta <= COMPLEMENT_ABOVE && sphere) {
        status = theory_integrate(sphere_integrand, &beta, 0.0, 1.0, "Hertz's gamma integral", &integral);
        if (status == IM_OK)
            *ratio = 2.0 * beta * integral;
        return status;
    }
    if (beta <= COMPLEMENT_ABOVE) {
        /* The flat punch's gamma turns from linear to saturated around u = beta, a feature that the
         * adaptive rule does not see from [0, 1] when beta is small (its 21-point estimates on the
         * first intervals miss it: a relative error of beta / 12 at beta = 1e-6, reported as 1e-14).
         * So [0, beta] is an interval of its own, and [beta, 1] is integrated in log u, where the
         * tail c^2 / (3 u^2) of the transition spans unit widths. */
        double near_rim, inside;
        status = theory_integrate(flat_integrand, &beta, 0.0, beta, "Boussinesq's gamma integral near the rim",
                                  &near_rim);
        if (status == IM_OK)
            status = theory_integrate(flat_log_integrand, &beta, log(beta), 0.0, "Boussinesq's gamma integral",
                                      &inside);
        if (status == IM_OK)
            *ratio = 2.0 * beta * (near_rim + inside);
        return status;
    }
    double lo, hi;
    complement_interval(kind, beta, &lo, &hi);
    status = theory_integrate(sphere ? sphere_complement_integrand : flat_complement_integrand, &beta, lo, hi,
                              sphere ? "Hertz's gamma complement" : "Boussinesq's gamma complement", &integral);
    if (status == IM_OK)
        *ratio = 1.0 - 2.0 * integral;
    return status;
}

int im_theory_punch_mean_pressure(enum im_punch_kind kind, double size, double load, double e_star, double *p_mean)
{
    ARG_REQUIRE(p_mean, "p_mean");
    int status = check_kind(kind);
    if (status != IM_OK)
        return status;
    if (kind == IM_PUNCH_CONE)
        return im_theory_cone_mean_pressure(size, e_star, p_mean);
    if (!(load > 0.0 && isfinite(load)))
        return im_fail(IM_EINVAL, "N = %g: expected a finite load N > 0", load);
    if (!(size > 0.0 && isfinite(size)))
        return im_fail(IM_EINVAL, "%s = %g: expected a finite radius > 0", kind == IM_PUNCH_SPHERE ? "R" : "a", size);
    double area = M_PI * size * size;
    if (kind == IM_PUNCH_SPHERE)
        status = im_theory_hertz_area(load, size, e_star, &area);
    if (status == IM_OK)
        *p_mean = load / area;
    return status;
}
