/* What an indentation experiment measures (see measure.h). */
#include "indentmap/measure.h"
#include "core/args.h"

#include "indentmap/status.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int check_history(const double *w, const double *n, int count)
{
    if (!w || !n || count < 2)
        return im_fail(IM_EINVAL, "stiffness: %d steps: expected at least 2", count);
    const double direction = w[1] > w[0] ? 1.0 : -1.0; /* loading, or unloading */
    for (int i = 0; i < count; ++i) {
        if (!isfinite(w[i]) || !isfinite(n[i]))
            return im_fail(IM_EINVAL, "stiffness: step %d: w = %g, N = %g: expected finite values", i, w[i], n[i]);
        if (i > 0 && !(direction * (w[i] - w[i - 1]) > 0))
            return im_fail(IM_EINVAL,
                           "stiffness: step %d: w = %g after %g: expected strictly increasing (loading) "
                           "or strictly decreasing (unloading) approaches",
                           i, w[i], w[i - 1]);
    }
    return IM_OK;
}

/* The derivative at x[j] of the parabola through (x[k], y[k]), k = a, a + 1, a + 2 (Lagrange). */
static double parabola_slope(const double *x, const double *y, int a, int j)
{
    double s = 0.0;
    for (int k = a; k < a + 3; ++k) {
        double numerator = 0.0, denominator = 1.0;
        for (int m = a; m < a + 3; ++m) {
            if (m == k)
                continue;
            denominator *= x[k] - x[m];
            double product = 1.0;
            for (int l = a; l < a + 3; ++l)
                if (l != k && l != m)
                    product *= x[j] - x[l];
            numerator += product;
        }
        s += y[k] * numerator / denominator;
    }
    return s;
}

int im_measure_stiffness(const double *approach, const double *load, int count, double *stiffness)
{
    ARG_REQUIRE(approach, "approach");
    ARG_REQUIRE(load, "load");
    ARG_REQUIRE(stiffness, "stiffness");
    int status = check_history(approach, load, count);
    if (status != IM_OK)
        return status;
    if (count == 2) {
        stiffness[0] = stiffness[1] = (load[1] - load[0]) / (approach[1] - approach[0]);
        return IM_OK;
    }
    for (int j = 0; j < count; ++j) {
        int first = j == 0 ? 0 : (j == count - 1 ? count - 3 : j - 1);
        stiffness[j] = parabola_slope(approach, load, first, j);
    }
    return IM_OK;
}

double im_measure_sneddon_modulus(double stiffness, double area)
{
    return stiffness >= 0.0 && area > 0.0 ? 0.5 * sqrt(M_PI) * stiffness / sqrt(area) : NAN;
}

/* The statistics, from the patches' list (distributions.c). */
int im_measure_contact_patches(const im_field *force, im_contact_patches *out, long **sizes)
{
    ARG_VIEW(force, "force");
    ARG_REQUIRE(out, "out");
    if (!force || !force->data)
        return im_fail(IM_EINVAL, "contact patches: no force field");
    im_patch *list = NULL;
    long count = 0;
    int status = im_measure_patch_list(force, &list, &count);
    if (status != IM_OK)
        return status;
    im_contact_patches s = {.patches = count};
    long edges = 0, *cells = sizes && count > 0 ? malloc(sizeof *cells * (size_t)count) : NULL;
    if (sizes && count > 0 && !cells) {
        free(list);
        return im_fail(IM_ENOMEM, "contact patch sizes (%ld patches)", count);
    }
    for (long i = 0; i < count; ++i) {
        s.cells += list[i].cells;
        edges += list[i].edges;
        if (list[i].cells > s.largest)
            s.largest = list[i].cells;
        if (cells)
            cells[i] = list[i].cells;
    }
    free(list);
    s.mean_area = s.patches ? (double)s.cells / s.patches * force->delta * force->delta : 0.0;
    s.perimeter = edges * force->delta;
    *out = s;
    if (sizes)
        *sizes = cells;
    return IM_OK;
}

int im_measure_gap_histogram(const im_field *gap, double gap_max, int bins, long *counts)
{
    ARG_VIEW(gap, "gap");
    ARG_REQUIRE(counts, "counts");
    if (!gap || !gap->data || !counts)
        return im_fail(IM_EINVAL, "gap histogram: no gap field or counts");
    if (!(gap_max > 0.0 && isfinite(gap_max)) || bins < 1)
        return im_fail(IM_EINVAL, "gap histogram: gap_max = %g, bins = %d: expected gap_max > 0 and bins >= 1",
                       gap_max, bins);
    memset(counts, 0, sizeof *counts * (size_t)bins);
    for (size_t i = 0; i < (size_t)gap->nx * gap->ny; ++i) {
        double g = gap->data[i];
        if (isnan(g) || g >= gap_max)
            continue;
        int bin = g <= 0.0 ? 0 : (int)(g / gap_max * bins);
        ++counts[bin < bins ? bin : bins - 1];
    }
    return IM_OK;
}
