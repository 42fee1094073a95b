/* Tick values of colour bars and plot axes. */
#include "typeset/ticks.h"

#include <math.h>

/* The 1-2-5 step giving about `target` intervals over span. */
static double nice_step(double span, double target)
{
    double raw = span / target, magnitude = pow(10.0, floor(log10(raw)));
    const double multiples[] = {1.0, 2.0, 5.0, 10.0};
    for (int i = 0; i < 4; ++i)
        if (multiples[i] * magnitude >= raw * 0.999999)
            return multiples[i] * magnitude;
    return 10.0 * magnitude;
}

static int linear_ticks(double lo, double hi, double target, double *ticks, int capacity)
{
    double span = hi - lo, step = nice_step(span, target);
    int count = 0;
    for (double k = ceil(lo / step - 1e-9); count < capacity && k * step <= hi + 1e-9 * span; k += 1.0) {
        double v = k * step;
        ticks[count++] = fabs(v) < 1e-12 * span ? 0.0 : v;
    }
    return count;
}

/* Decades, or 1-2-5 multiples when fewer than min_decades decades lie in [lo, hi]. */
static int log_ticks(double lo, double hi, int min_decades, double *ticks, int capacity)
{
    int count = 0;
    for (double e = ceil(log10(lo) - 1e-9); count < capacity && pow(10.0, e) <= hi * (1 + 1e-9); e += 1.0)
        ticks[count++] = pow(10.0, e);
    if (count >= min_decades)
        return count;
    count = 0;
    const double multiples[] = {1.0, 2.0, 5.0};
    for (double e = floor(log10(lo)); e <= ceil(log10(hi)); e += 1.0)
        for (int i = 0; i < 3 && count < capacity; ++i) {
            double v = multiples[i] * pow(10.0, e);
            if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9))
                ticks[count++] = v;
        }
    return count;
}

int typeset_ticks_between(double lo, double hi, int logarithmic, double target, double *ticks, int capacity)
{
    if (capacity < 1 || !(hi > lo) || (logarithmic && !(lo > 0.0)))
        return 0;
    return logarithmic ? log_ticks(lo, hi, 2, ticks, capacity) : linear_ticks(lo, hi, target, ticks, capacity);
}

int typeset_colour_bar_ticks(double lo, double hi, int logarithmic, double *ticks, int capacity)
{
    if (!logarithmic || capacity < 1 || !(hi > lo) || !(lo > 0.0))
        return typeset_ticks_between(lo, hi, logarithmic, 5.0, ticks, capacity);
    /* A colour bar over under three decades would show one or two labels: 1-2-5 there (a plot axis
     * has its minor ticks and keeps decades from two on). */
    return log_ticks(lo, hi, 3, ticks, capacity);
}
