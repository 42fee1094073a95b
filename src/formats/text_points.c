/* x y z points in a text file, placed on the regular grid they sample. */
#include "formats/text_points.h"

#include "core/sort.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The distinct values of one column (every third value from `first`), sorted, into *distinct. */
static int distinct_values(const double *values, long points, int first, double **distinct, long *count)
{
    double *sorted = malloc((size_t)points * sizeof *sorted);
    if (!sorted)
        return im_fail(IM_ENOMEM, "x y z points: allocation failed");
    for (long k = 0; k < points; ++k)
        sorted[k] = values[3 * k + first];
    sort_doubles(sorted, (size_t)points);
    long n = 0;
    for (long k = 0; k < points; ++k)
        if (n == 0 || sorted[k] != sorted[n - 1])
            sorted[n++] = sorted[k];
    *distinct = sorted;
    *count = n;
    return IM_OK;
}

/* The step of equally spaced sorted values (to 1e-6 of a step, as text rounds them), or 0 if they are not. */
static double regular_step(const double *sorted, long count)
{
    if (count < 2 || !isfinite(sorted[0]) || !isfinite(sorted[count - 1]))
        return 0.0;
    double step = (sorted[count - 1] - sorted[0]) / (double)(count - 1);
    for (long k = 0; k < count; ++k)
        if (fabs(sorted[k] - (sorted[0] + (double)k * step)) > 1e-6 * step)
            return 0.0;
    return step;
}

typedef struct grid_axis {
    double start, step;
    long count;
} grid_axis;

static int axis_of_column(const double *values, long points, int column, grid_axis *axis)
{
    double *distinct = NULL;
    int status = distinct_values(values, points, column, &distinct, &axis->count);
    if (status != IM_OK)
        return status;
    axis->start = distinct[0];
    axis->step = regular_step(distinct, axis->count);
    free(distinct);
    return IM_OK;
}

static int not_a_grid(const char *path, const grid_axis *x, const grid_axis *y, long points, const char *why)
{
    return im_fail(IM_EFORMAT,
                   "%s: 3 columns, read as x y z points, but they are not a regular grid (%ld distinct "
                   "x, %ld distinct y, %ld points: %s); expected each (x, y) of a regular grid once (a map as a "
                   "matrix needs at least 4 columns)",
                   path, x->count, y->count, points, why);
}

/* Places each point's z at its (x, y) node; a node met twice is refused. */
static int place_points(const char *path, const double *values, long points, const grid_axis *x, const grid_axis *y,
                        im_field *field)
{
    unsigned char *taken = calloc((size_t)points, 1);
    if (!taken)
        return im_fail(IM_ENOMEM, "x y z points: allocation failed");
    int status = IM_OK;
    for (long k = 0; k < points && status == IM_OK; ++k) {
        long ix = lround((values[3 * k] - x->start) / x->step), iy = lround((values[3 * k + 1] - y->start) / y->step);
        if (ix < 0 || ix >= x->count || iy < 0 || iy >= y->count) { /* cannot be: the axes hold every value */
            status = im_fail(IM_EFORMAT, "%s: point %ld lies off the grid", path, k + 1);
            break;
        }
        size_t node = (size_t)iy * (size_t)x->count + (size_t)ix;
        if (taken[node])
            status = im_fail(IM_EFORMAT,
                             "%s: point %ld repeats (x, y) = (%.9g, %.9g): expected each node of the "
                             "grid once",
                             path, k + 1, values[3 * k], values[3 * k + 1]);
        taken[node] = 1;
        field->data[node] = values[3 * k + 2];
    }
    free(taken);
    return status;
}

/* x and y must be numbers: a NaN among them sorts anywhere and would place a point outside the grid. */
static int check_finite_positions(const char *path, const double *values, long points)
{
    for (long k = 0; k < points; ++k)
        if (!isfinite(values[3 * k]) || !isfinite(values[3 * k + 1]))
            return im_fail(IM_EFORMAT,
                           "%s: point %ld has (x, y) = (%g, %g): expected finite positions (a missing "
                           "height is a NaN z)",
                           path, k + 1, values[3 * k], values[3 * k + 1]);
    return IM_OK;
}

int text_points_grid(const char *path, const double *values, long points, im_field **out, surface_stated *stated)
{
    *out = NULL;
    grid_axis x, y;
    int status = check_finite_positions(path, values, points);
    if (status == IM_OK)
        status = axis_of_column(values, points, 0, &x);
    if (status == IM_OK)
        status = axis_of_column(values, points, 1, &y);
    if (status != IM_OK)
        return status;
    if (x.count * y.count != points)
        return not_a_grid(path, &x, &y, points, "distinct x times distinct y is not the number of points");
    if (!(x.step > 0.0) || !(y.step > 0.0))
        return not_a_grid(path, &x, &y, points, "x or y not equally spaced");
    if (x.count < 3 || y.count < 3)
        return im_fail(IM_EFORMAT,
                       "%s: x y z points on a %ld x %ld grid: a line scan (a 1-D profile), not a map; a 2-D "
                       "contact needs heights on a grid of at least 3 x 3",
                       path, x.count, y.count);
    if (x.count > IM_FIELD_MAX_SIDE || y.count > IM_FIELD_MAX_SIDE)
        return im_fail(IM_EFORMAT, "%s: x y z points on a %ld x %ld grid: expected at most %d a side", path, x.count,
                       y.count, IM_FIELD_MAX_SIDE);
    im_field *field = NULL;
    status = im_field_create((int)x.count, (int)y.count, 1.0, &field);
    if (status == IM_OK)
        status = place_points(path, values, points, &x, &y, field);
    if (status != IM_OK) {
        im_field_free(field);
        return status;
    }
    *stated = (surface_stated){.spacing_keys = "the steps of the x and y columns",
                               .lateral_key = "--unit",
                               .height_key = "--height-unit"};
    stated->units.delta_x = x.step;
    stated->units.delta_y = y.step;
    *out = field;
    return IM_OK;
}
