/* Eq. (2)'s k measured: least squares of the erf law A/A0 = erf(sqrt(pi)/2 k x) to nominally flat
 * contact, x = p_m / (h'rms E*). */
#include "indentmap/status.h"
#include "core/args.h"
#include "indentmap/theory.h"

#include <math.h>

enum { GAUSS_NEWTON_STEPS = 100 };
/* The linear regime the paper quotes: "up to area ratios of the order of 50%". */
static const double LINEAR_UP_TO = 0.5;
static const double SETTLED = 1e-14;

static int check_points(const double *x, const double *area, int count)
{
    if (!x || !area || count < 1)
        return im_fail(IM_EINVAL, "k fit: %d points: expected at least one (x, A/A0) pair", count);
    for (int i = 0; i < count; ++i) {
        if (!(x[i] > 0.0 && isfinite(x[i])))
            return im_fail(IM_EINVAL, "k fit: point %d: x = p_m / (h'rms E*) = %g: expected a finite x > 0", i, x[i]);
        if (!(area[i] >= 0.0 && area[i] <= 1.0))
            return im_fail(IM_EINVAL, "k fit: point %d: A/A0 = %g: expected 0 <= A/A0 <= 1", i, area[i]);
    }
    return IM_OK;
}

/* Slope through the origin of the points with A/A0 <= 0.5; NaN if none. */
static double linear_slope(const double *x, const double *area, int count, int *used)
{
    double xy = 0.0, xx = 0.0;
    *used = 0;
    for (int i = 0; i < count; ++i)
        if (area[i] <= LINEAR_UP_TO) {
            xy += x[i] * area[i];
            xx += x[i] * x[i];
            ++*used;
        }
    return *used ? xy / xx : NAN;
}

/* Sums over the points at k: residual squares, J^2 and J r with J = dA/dk = x exp(-z^2), z = sqrt(pi)/2 k x. */
static void normal_equation(const double *x, const double *area, int count, double k, double *squares, double *jj,
                            double *jr)
{
    *squares = *jj = *jr = 0.0;
    for (int i = 0; i < count; ++i) {
        double z = 0.5 * sqrt(M_PI) * k * x[i], r = area[i] - erf(z), j = x[i] * exp(-z * z);
        *squares += r * r;
        *jj += j * j;
        *jr += j * r;
    }
}

int im_theory_fit_k(const double *pressure_ratio, const double *area_fraction, int count, im_theory_k_fit *out)
{
    ARG_REQUIRE(pressure_ratio, "pressure_ratio");
    ARG_REQUIRE(area_fraction, "area_fraction");
    ARG_REQUIRE(out, "out");
    int status = check_points(pressure_ratio, area_fraction, count);
    if (status != IM_OK)
        return status;
    im_theory_k_fit fit = {0};
    fit.k_linear = linear_slope(pressure_ratio, area_fraction, count, &fit.linear_points);
    double k = fit.k_linear;
    if (!(k > 0.0)) /* no point at or below 50%, or no contact anywhere: start from k = 1 */
        k = 1.0;
    double squares, jj, jr;
    for (int step = 0;; ++step) {
        normal_equation(pressure_ratio, area_fraction, count, k, &squares, &jj, &jr);
        if (!(jj > 0.0))
            return im_fail(IM_ENOCONV, "k fit: the erf law is saturated at k = %g on every point", k);
        double change = jr / jj;
        /* keep k > 0: at most halve it in one step */
        k = change < -0.5 * k ? 0.5 * k : k + change;
        if (fabs(change) <= SETTLED * k)
            break;
        if (step == GAUSS_NEWTON_STEPS)
            return im_fail(IM_ENOCONV, "k fit: Gauss-Newton did not settle in %d steps (k = %g)", step, k);
    }
    normal_equation(pressure_ratio, area_fraction, count, k, &squares, &jj, &jr);
    fit.k = k;
    fit.k_error = count > 1 ? sqrt(squares / (count - 1) / jj) : 0.0;
    fit.rms_residual = sqrt(squares / count);
    *out = fit;
    return IM_OK;
}
