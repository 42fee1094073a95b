/* The cone's contact area ratio with a variable density of contact: eq. (12) in the radius, and
 * Greenwood's quadrature form of eq. (19) in q = p / p_m,c, two independent routes to the same
 * number. Eq. (12) is integrated in the distance from the rim t = 1 - r/a rather than in s = r/a,
 * so that the square-root singularity at the rim lies at t = 0, where doubles are dense (near
 * s = 1 the adaptive rule would run out of representable subintervals). Both routes integrate
 * the ratio itself for beta <= 1 and its complement 1 - ratio above, so that neither loses
 * digits to cancellation nor misses the narrow rim of partial contact. */
#include "indentmap/status.h"
#include "core/args.h"
#include "indentmap/theory.h"
#include "theory/cone.h"
#include "theory/quadrature.h"

#include <math.h>

/* Up to this erf scale the ratio is integrated, above it its complement. */
static const double COMPLEMENT_ABOVE = 1.0;
/* erfc(x) < 1e-318 for x >= 27: the complement's integrand is zero in double precision beyond. */
static const double ERFC_NEGLIGIBLE = 27.0;
/* Below this argument erf(x) = 2 x / sqrt(pi) to double precision (relative error x^2 / 3). */
static const double ERF_LINEAR_BELOW = 1e-9;
/* 1 - ratio <= 1 / (2 beta^2) (Greenwood's weight sinh q / cosh^3 q is at most q, and
 * 2 int_0^inf q erfc(beta q) dq = 1 / (2 beta^2)), which is below 2^-54 from beta = 1e8 on: there
 * the ratio rounds to 1 exactly (and far beyond, the complement's interval would underflow). */
static const double SATURATED_FROM = 1e8;
/* sinh q / cosh^3 q < 4 exp(-2 q): beyond q = 40 Greenwood's integrand adds less than 1e-32 of
 * the ratio (whose integrand is erf(beta q) <= 2 beta q / sqrt(pi) times that). */
static const double GREENWOOD_TAIL = 40.0;

double theory_erf_over_beta(double beta, double x)
{
    double argument = beta * x;
    return argument < ERF_LINEAR_BELOW ? M_2_SQRTPI * x : erf(argument) / beta;
}

/* s erf(beta acosh(1/s)) / beta at s = 1 - t. */
static double radial_integrand(double t, void *params)
{
    return (1.0 - t) * theory_erf_over_beta(*(const double *)params, theory_acosh_inverse_from_rim(t));
}

static double radial_complement_integrand(double t, void *params)
{
    return (1.0 - t) * erfc(*(const double *)params * theory_acosh_inverse_from_rim(t));
}

/* sinh q / cosh^3 q written so that it neither overflows nor divides infinities. */
static double greenwood_weight(double q)
{
    double sech = 1.0 / cosh(q);
    return tanh(q) * sech * sech;
}

static double greenwood_integrand(double q, void *params)
{
    return greenwood_weight(q) * theory_erf_over_beta(*(const double *)params, q);
}

static double greenwood_complement_integrand(double q, void *params)
{
    return greenwood_weight(q) * erfc(*(const double *)params * q);
}

/* Ends shared by both routes: IM_OK and *done = 1 when beta is 0 or the ratio rounds to 1. */
static int area_ratio_ends(double beta, double *ratio, int *done)
{
    int status = theory_check_erf_scale(beta);
    *done = status != IM_OK || beta == 0.0 || beta >= SATURATED_FROM;
    if (status == IM_OK && *done)
        *ratio = beta == 0.0 ? 0.0 : 1.0;
    return status;
}

int im_theory_cone_area_ratio_variable(double beta, double *ratio)
{
    ARG_REQUIRE(ratio, "ratio");
    int done;
    int status = area_ratio_ends(beta, ratio, &done);
    if (done)
        return status;
    double integral;
    if (beta <= COMPLEMENT_ABOVE) {
        status = theory_integrate(radial_integrand, &beta, 0.0, 1.0, "eq. (12) in 1 - r/a", &integral);
        if (status == IM_OK)
            *ratio = 2.0 * beta * integral;
        return status;
    }
    /* Where beta acosh(1/s) >= ERFC_NEGLIGIBLE, i.e. t >= 1 - 1 / cosh(x) = 2 sinh^2(x/2) / cosh(x)
     * with x = ERFC_NEGLIGIBLE / beta, the contact is full in double precision. */
    double x = ERFC_NEGLIGIBLE / beta, half_sinh = sinh(0.5 * x);
    double partial_contact_width = 2.0 * half_sinh * half_sinh / cosh(x);
    status = theory_integrate(radial_complement_integrand, &beta, 0.0, partial_contact_width,
                              "eq. (12) complement in 1 - r/a", &integral);
    if (status == IM_OK)
        *ratio = 1.0 - 2.0 * integral;
    return status;
}

int im_theory_cone_area_ratio_greenwood(double beta, double *ratio)
{
    ARG_REQUIRE(ratio, "ratio");
    int done;
    int status = area_ratio_ends(beta, ratio, &done);
    if (done)
        return status;
    double integral;
    if (beta <= COMPLEMENT_ABOVE) {
        status = theory_integrate(greenwood_integrand, &beta, 0.0, GREENWOOD_TAIL, "Greenwood's quadrature",
                                  &integral);
        if (status == IM_OK)
            *ratio = 2.0 * beta * integral;
        return status;
    }
    status = theory_integrate(greenwood_complement_integrand, &beta, 0.0, ERFC_NEGLIGIBLE / beta,
                              "Greenwood's quadrature complement", &integral);
    if (status == IM_OK)
        *ratio = 1.0 - 2.0 * integral;
    return status;
}
