/* One default norm over several fields (colormap.h, "one norm over several fields"): the contact maps
 * and height maps of `render`, the frames of scenes and of `indent --frames`, the panels of a scene's
 * figure, the 3-D views and Python's pictures all take their norm, and their shared tension norm, from
 * here. */
#include "indentmap/colormap.h"
#include "core/args.h"
#include "core/sort.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

im_colormap_range im_colormap_range_empty(im_colormap_values values)
{
    return (im_colormap_range){.values = values, .lo = INFINITY, .hi = -INFINITY};
}

/* Whether a field's value is one a range of this kind gathers, and as what (*v): heights every finite
 * value, forces those > 0, tensions -f of those < 0. */
static int gathered(im_colormap_values values, double value, double *v)
{
    *v = values == IM_COLORMAP_TENSIONS ? -value : value;
    return isfinite(*v) && (values == IM_COLORMAP_HEIGHTS || *v > 0.0);
}

int im_colormap_range_add(im_colormap_range *range, const im_field *field)
{
    ARG_REQUIRE(range, "range");
    ARG_VIEW(field, "field");
    for (size_t i = 0; i < im_field_count(field); ++i) {
        double v;
        if (gathered(range->values, field->data[i], &v)) {
            range->lo = fmin(range->lo, v);
            range->hi = fmax(range->hi, v);
        }
    }
    return IM_OK;
}

/* The percentile of values[0..n) (n > 0; reordered), numpy.percentile's default: the order statistics at
 * ranks floor(r) and floor(r) + 1 interpolated linearly, r = percent / 100 (n - 1). */
static double percentile(double *values, size_t n, double percent)
{
    const double rank = percent / 100.0 * (double)(n - 1);
    const size_t k = (size_t)floor(rank);
    select_doubles(values, n, k);
    if (rank == (double)k)
        return values[k];
    double above = INFINITY; /* the next order statistic: the smallest of those after rank k */
    for (size_t i = k + 1; i < n; ++i)
        above = fmin(above, values[i]);
    return values[k] + (rank - (double)k) * (above - values[k]);
}

/* The values of the fields (valid views) a range of this kind gathers, in one array (*values NULL when there is none). */
static int gather_values(im_colormap_values values, im_field *const *fields, int count, double **gathered_values,
                         size_t *n)
{
    size_t total = 0;
    for (int i = 0; i < count; ++i)
        total += im_field_count(fields[i]);
    *n = 0;
    *gathered_values = total ? malloc(total * sizeof **gathered_values) : NULL;
    if (total && !*gathered_values)
        return im_fail(IM_ENOMEM, "im_colormap_range_clipped: %zu values: out of memory", total);
    for (int i = 0; i < count; ++i)
        for (size_t j = 0; j < im_field_count(fields[i]); ++j)
            *n += gathered(values, fields[i]->data[j], &(*gathered_values)[*n]);
    return IM_OK;
}

int im_colormap_range_clipped(im_colormap_values values, im_field *const *fields, int count, double percent,
                              im_colormap_range *range)
{
    ARG_REQUIRE(range, "range");
    ARG_REQUIRE(fields || count == 0, "fields");
    if (count < 0 || !(percent >= 0.0 && percent < 50.0) || values < IM_COLORMAP_FORCES ||
        values > IM_COLORMAP_TENSIONS)
        return im_fail(IM_EINVAL,
                       "im_colormap_range_clipped: count %d, percent %g, values %d: expected count >= 0, percent "
                       "in [0, 50) and a kind of values of colormap.h",
                       count, percent, (int)values);
    for (int i = 0; i < count; ++i)
        ARG_VIEW(fields[i], "fields");
    double *gathered_values;
    size_t n;
    int status = gather_values(values, fields, count, &gathered_values, &n);
    if (status != IM_OK)
        return status;
    *range = im_colormap_range_empty(values);
    if (n) {
        range->lo = percentile(gathered_values, n, percent);
        range->hi = percentile(gathered_values, n, 100.0 - percent);
    }
    free(gathered_values);
    return IM_OK;
}

/* The index of the field whose values reach farthest beyond the central range. */
static int farthest_outlier(im_field *const *fields, int count, const im_colormap_range *central)
{
    int farthest = 0;
    double reach = -INFINITY;
    for (int i = 0; i < count; ++i) {
        im_colormap_range own = im_colormap_range_empty(IM_COLORMAP_HEIGHTS);
        im_colormap_range_add(&own, fields[i]);
        const double beyond = fmax(central->lo - own.lo, own.hi - central->hi);
        if (beyond > reach)
            reach = beyond, farthest = i;
    }
    return farthest;
}

int im_colormap_outlier_note(im_field *const *fields, int count, char *text, size_t size, int *farthest)
{
    ARG_REQUIRE(fields || count == 0, "fields");
    ARG_REQUIRE(text, "text");
    ARG_REQUIRE(farthest, "farthest");
    if (size == 0 || count < 0)
        return im_fail(IM_EINVAL,
                       "im_colormap_outlier_note: size %zu, count %d: expected room for the text and "
                       "count >= 0",
                       size, count);
    text[0] = '\0';
    *farthest = -1;
    im_colormap_range full = im_colormap_range_empty(IM_COLORMAP_HEIGHTS), central;
    int status = IM_OK;
    for (int i = 0; i < count && status == IM_OK; ++i)
        status = im_colormap_range_add(&full, fields[i]);
    if (status == IM_OK)
        status = im_colormap_range_clipped(IM_COLORMAP_HEIGHTS, fields, count, IM_COLORMAP_OUTLIER_PERCENT, &central);
    if (status != IM_OK)
        return status;
    const double whole = full.hi - full.lo, bulk = central.hi - central.lo;
    if (!(bulk * IM_COLORMAP_OUTLIER_SHARE < whole))
        return IM_OK;
    const char *unit = fields[0]->value_unit[0] ? fields[0]->value_unit : fields[0]->unit; /* count > 0 here */
    const char *space = unit[0] ? " " : "";
    snprintf(text, size,
             "a few outliers set the colour range: the central %g%% of the values span %.3g%s%s of its %.3g%s%s, "
             "%.0f of the 256 colours",
             100.0 - 2.0 * IM_COLORMAP_OUTLIER_PERCENT, bulk, space, unit, whole, space, unit,
             ceil(256.0 * bulk / whole));
    *farthest = farthest_outlier(fields, count, &central);
    return IM_OK;
}

/* The range's default bounds: what it gathered, or its kind's defaults where that is empty or one value. */
static int default_bounds(const im_colormap_range *range, double *lo, double *hi)
{
    switch (range->values) {
    case IM_COLORMAP_FORCES:
    case IM_COLORMAP_TENSIONS:
        *lo = 0.0;
        *hi = range->hi > 0.0 ? range->hi : 1.0;
        return IM_OK;
    case IM_COLORMAP_HEIGHTS: {
        const double middle = isfinite(range->lo) ? range->lo : 0.0;
        *lo = range->hi > range->lo ? range->lo : middle - 1.0;
        *hi = range->hi > range->lo ? range->hi : middle + 1.0;
        return IM_OK;
    }
    default:
        return im_fail(IM_EINVAL,
                       "im_colormap_range_norm: values = %d: expected IM_COLORMAP_FORCES, "
                       "IM_COLORMAP_HEIGHTS or IM_COLORMAP_TENSIONS",
                       (int)range->values);
    }
}

im_colormap im_colormap_range_norm(const im_colormap_range *range, im_colormap_id map, double vmin, double vmax,
                                   int logarithmic)
{
    im_colormap norm = im_colormap_make(map, NAN, NAN);
    double lo = NAN, hi = NAN;
    ARG_REQUIRE_OR(range, "range", norm);
    if (default_bounds(range, &lo, &hi) != IM_OK)
        return norm;
    norm.hi = isnan(vmax) ? hi : vmax;
    norm.lo = !isnan(vmin) ? vmin : logarithmic && norm.hi > 0.0 ? 0.01 * norm.hi : lo;
    norm.logarithmic = logarithmic;
    return norm;
}
