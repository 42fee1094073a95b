/* Tick values of colour bars and plot axes. */
#include "figure/ticks.h"

#include "indentmap/figure.h"

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

static int log_ticks(double lo, double hi, double *ticks, int capacity)
{
    int count = 0;
    for (double e = ceil(log10(lo) - 1e-9); count < capacity && pow(10.0, e) <= hi * (1 + 1e-9); e += 1.0)
        ticks[count++] = pow(10.0, e);
    if (count >= 3)
        return count; /* fewer decades would leave a bar with one or two labels: 1-2-5 instead */
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

int im_figure_ticks_between(double lo, double hi, int logarithmic, double target, double *ticks, int capacity)
{
    if (capacity < 1 || !(hi > lo) || (logarithmic && !(lo > 0.0)))
        return 0;
    return logarithmic ? log_ticks(lo, hi, ticks, capacity) : linear_ticks(lo, hi, target, ticks, capacity);
}

int im_figure_ticks(const im_colormap *colormap, double *ticks, int capacity)
{
    return im_figure_ticks_between(colormap->lo, colormap->hi, colormap->logarithmic, 5.0, ticks, capacity);
}
