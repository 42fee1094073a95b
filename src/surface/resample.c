/* Resampling a grid of rectangular pixels onto square ones (surface.h: im_surface_resample_square).
 *
 * The new nodes are j * delta along each axis, delta the finer of the two spacings, as far as the
 * old grid reaches: no node lies beyond the old grid's last one, so nothing is extrapolated. Along
 * the finer axis the nodes are the old ones (weight 0 on the next point); along the coarser one each
 * node lies between two old points and takes their linear blend. A value with weight 0 is not read,
 * so that a missing point (NaN) spreads only to the nodes whose blend it enters. */
#include "indentmap/surface.h"
#include "core/args.h"

#include "indentmap/status.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Where node j of the new grid falls on one axis of the old: between point `first` and the next,
 * at the fraction `weight` (0: on `first` itself). */
typedef struct node_place {
    int first;
    double weight;
} node_place;

/* Nodes of spacing `fine` that fit on an axis of n points spaced `coarse` (>= fine): the old
 * extent (n - 1) coarse, less a rounding's worth so that an extent of exactly k fine spacings
 * keeps its last node. */
static double nodes_on_axis(int n, double coarse, double fine)
{
    double spans = (double)(n - 1) * (coarse / fine);
    return floor(spans * (1.0 + 4.0 * DBL_EPSILON)) + 1.0;
}

/* The places of `count` new nodes, spacing `fine`, on an axis of n old points spaced `spacing`. */
static node_place *place_nodes(int count, int n, double spacing, double fine)
{
    node_place *places = malloc((size_t)count * sizeof *places);
    if (!places)
        return NULL;
    double step = fine / spacing; /* exactly 1 on the finer axis: its nodes are the old points */
    for (int j = 0; j < count; ++j) {
        double at = fmin(j * step, n - 1.0);
        int first = (int)at < n - 1 ? (int)at : (n > 1 ? n - 2 : 0);
        places[j] = (node_place){first, at - first};
    }
    return places;
}

/* (1 - w) a + w b, reading neither value when its weight is 0. */
static double blend(const double *a, const double *b, double w)
{
    return w == 0.0 ? *a : w == 1.0 ? *b : (1.0 - w) * *a + w * *b;
}

/* Node (px, py): the blend along x of the old rows py.first and the next, blended along y. */
static double node_value(const im_field *old, node_place px, node_place py)
{
    const double *row = old->data + (size_t)py.first * (size_t)old->nx + px.first;
    double lower = blend(row, row + (px.weight > 0.0), px.weight);
    if (py.weight == 0.0)
        return lower;
    const double *next = row + old->nx;
    double upper = blend(next, next + (px.weight > 0.0), px.weight);
    return blend(&lower, &upper, py.weight);
}

/* IM_OK with the new grid's sides, or IM_EINVAL when a side would exceed IM_FIELD_MAX_SIDE. */
static int square_grid_sides(const im_field *field, double delta_x, double delta_y, int *nx, int *ny)
{
    double fine = fmin(delta_x, delta_y);
    double sides[2] = {nodes_on_axis(field->nx, delta_x, fine), nodes_on_axis(field->ny, delta_y, fine)};
    if (sides[0] > IM_FIELD_MAX_SIDE || sides[1] > IM_FIELD_MAX_SIDE)
        return im_fail(IM_EINVAL,
                       "resampling %d x %d pixels of %g x %g onto square pixels of %g: %.0f x %.0f "
                       "nodes, more than %d along a side",
                       field->nx, field->ny, delta_x, delta_y, fine, sides[0], sides[1], IM_FIELD_MAX_SIDE);
    *nx = (int)sides[0];
    *ny = (int)sides[1];
    return IM_OK;
}

/* Fills `out` from `field` through the node places along x and y. */
static void interpolate(const im_field *field, const node_place *along_x, const node_place *along_y, im_field *out)
{
#pragma omp parallel for schedule(static) if ((size_t)out->nx * (size_t)out->ny > 65536)
    for (int j = 0; j < out->ny; ++j)
        for (int i = 0; i < out->nx; ++i)
            out->data[(size_t)j * (size_t)out->nx + i] = node_value(field, along_x[i], along_y[j]);
}

int im_surface_resample_square(const im_field *field, double delta_x, double delta_y, im_field **out)
{
    ARG_VIEW(field, "field");
    ARG_REQUIRE(out, "out");
    *out = NULL;
    if (!(delta_x > 0.0 && delta_y > 0.0 && isfinite(delta_x) && isfinite(delta_y)))
        return im_fail(IM_EINVAL, "resample: spacings %g and %g: expected finite values > 0", delta_x, delta_y);
    int nx = 0, ny = 0;
    int status = square_grid_sides(field, delta_x, delta_y, &nx, &ny);
    if (status == IM_OK)
        status = im_field_create(nx, ny, fmin(delta_x, delta_y), out);
    if (status != IM_OK)
        return status;
    memcpy((*out)->unit, field->unit, sizeof field->unit);
    memcpy((*out)->value_unit, field->value_unit, sizeof field->value_unit);
    node_place *along_x = place_nodes(nx, field->nx, delta_x, (*out)->delta);
    node_place *along_y = place_nodes(ny, field->ny, delta_y, (*out)->delta);
    if (along_x && along_y)
        interpolate(field, along_x, along_y, *out);
    else
        status = im_fail(IM_ENOMEM, "resample: allocation of the node places failed");
    free(along_x);
    free(along_y);
    if (status != IM_OK) {
        im_field_free(*out);
        *out = NULL;
    }
    return status;
}
