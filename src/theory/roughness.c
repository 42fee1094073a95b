#include "indentmap/theory.h"

#include <math.h>

static double moment_angular_factor(int n)
{
    switch (n) {
    case 0: return 2.0 * M_PI;
    case 2: return M_PI;
    case 4: return 0.75 * M_PI;
    default: return NAN;
    }
}

double im_theory_moment(int n, double hurst, double q_r, double zeta, double x)
{
    if (!(hurst > 0.0 && hurst < 1.0) || !(q_r > 0.0) || !(zeta >= 1.0) || !(x >= 0.0 && x <= 1.0))
        return NAN;
    double plateau = (1.0 - pow(x, n + 2)) / (n + 2);
    double power_law = (pow(zeta, n - 2.0 * hurst) - 1.0) / (n - 2.0 * hurst);
    return moment_angular_factor(n) * pow(q_r, n - 2.0 * hurst) * (plateau + power_law);
}

double im_theory_height_rms_moments(double slope_rms, double hurst, double q_r, double zeta, double x)
{
    double m0 = im_theory_moment(0, hurst, q_r, zeta, x);
    double m2 = im_theory_moment(2, hurst, q_r, zeta, x);
    return slope_rms * sqrt(m0 / (2.0 * m2));
}

double im_theory_height_rms_eq15(double slope_rms, double hurst, double q_s, double zeta)
{
    return slope_rms * sqrt((1.0 - hurst) / hurst) * pow(zeta, hurst) / q_s;
}
