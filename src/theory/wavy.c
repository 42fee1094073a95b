/* Closed forms for wavy surfaces in the periodic half-space (theory.h). */
#include "indentmap/theory.h"

#include <math.h>

double im_theory_wavy1d_area_fraction(double pressure_ratio)
{
    if (!(pressure_ratio >= 0.0 && pressure_ratio <= 1.0))
        return NAN;
    return 2.0 / M_PI * asin(sqrt(pressure_ratio));
}

double im_theory_wavy2d_light_area_fraction(double pressure_ratio)
{
    if (!(pressure_ratio > 0.0 && pressure_ratio <= 1.0))
        return NAN;
    /* Hertz: a^3 = 3 P R / (4 E*) with P = p_m L^2, R = L^2 / (4 pi^2 Delta), p_m = y 2 pi E* Delta / L
     * gives (a / L)^3 = 3 y / (8 pi) */
    return M_PI * pow(3.0 * pressure_ratio / (8.0 * M_PI), 2.0 / 3.0);
}

double im_theory_wavy2d_near_full_area_fraction(double pressure_ratio)
{
    if (!(pressure_ratio > 0.0 && pressure_ratio <= 1.0))
        return NAN;
    /* the hole of radius b: the integral of r p(r) / sqrt(b^2 - r^2) over [0, b] vanishes for
     * p(r) = -d + c r^2, so b^2 = 3 d / (2 c), with d = p^ - p_m and c = p^ pi^2 / L^2 */
    return 1.0 - 3.0 / (2.0 * M_PI) * (1.0 - pressure_ratio);
}
