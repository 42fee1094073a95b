/* One default norm over several fields (colormap.h, "one norm over several fields"): the contact maps
 * and height maps of `render`, the frames of scenes and of `indent --frames`, the panels of a scene's
 * figure, the 3-D views and Python's pictures all take their norm, and their shared tension norm, from
 * here. */
#include "indentmap/colormap.h"
#include "core/args.h"

#include <math.h>

im_colormap_range im_colormap_range_empty(im_colormap_values values)
{
    return (im_colormap_range){.values = values, .lo = INFINITY, .hi = -INFINITY};
}

int im_colormap_range_add(im_colormap_range *range, const im_field *field)
{
    ARG_REQUIRE(range, "range");
    ARG_VIEW(field, "field");
    const int positive = range->values != IM_COLORMAP_HEIGHTS; /* forces > 0, tensions -f > 0 */
    const double sign = range->values == IM_COLORMAP_TENSIONS ? -1.0 : 1.0;
    for (size_t i = 0; i < im_field_count(field); ++i) {
        double v = sign * field->data[i];
        if (isfinite(v) && (!positive || v > 0.0)) {
            range->lo = fmin(range->lo, v);
            range->hi = fmax(range->hi, v);
        }
    }
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
