/* Scan-line alignment: AFM images are taken line by line along x, and each line's height offset (or
 * tilt) drifts with the feedback, which shows as streaks across every contact map; aligning the rows
 * removes it, as Gwyddion's Align Rows and SurfaceTopography's scan_line_align do. */
#include "indentmap/surface.h"
#include "core/args.h"

#include "core/sort.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The median of n values (scratch holds n doubles; the values are left as they were). */
static double median_of(const double *values, int n, double *scratch)
{
    memcpy(scratch, values, (size_t)n * sizeof *scratch);
    sort_doubles(scratch, (size_t)n);
    return n % 2 ? scratch[n / 2] : 0.5 * (scratch[n / 2 - 1] + scratch[n / 2]);
}

static double mean_of(const double *values, int n)
{
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
        sum += values[i];
    return sum / n;
}

/* Subtracts the row's least-squares line a + b (x - x_mid) and returns a (its level). */
static double remove_line(double *row, int n)
{
    double mid = 0.5 * (n - 1), slope_sum = 0.0, weight = 0.0, level = mean_of(row, n);
    for (int i = 0; i < n; ++i) {
        slope_sum += (i - mid) * (row[i] - level);
        weight += (i - mid) * (i - mid);
    }
    double slope = weight > 0.0 ? slope_sum / weight : 0.0;
    for (int i = 0; i < n; ++i)
        row[i] -= slope * (i - mid);
    return level;
}

/* Each row's level (median or mean) is subtracted and the mean of the levels added back, so that the
 * surface keeps its mean height; LINE also removes each row's tilt. */
int im_surface_align_rows(im_field *surface, enum im_row_alignment how)
{
    ARG_VIEW(surface, "surface");
    if (how < IM_ALIGN_NONE || how > IM_ALIGN_LINE)
        return im_fail(IM_EINVAL, "im_surface_align_rows: how = %d: expected none, median, mean or line", (int)how);
    if (how == IM_ALIGN_NONE)
        return IM_OK;
    int status = im_field_check_finite(surface, "surface (align rows after missing points are filled)");
    if (status == IM_OK) /* named where the file holds it, before a row's level moves it */
        status = im_surface_check_height_range(surface, "surface before aligning rows");
    double *levels = status == IM_OK ? malloc((size_t)surface->ny * sizeof *levels) : NULL;
    double *scratch = levels ? malloc((size_t)surface->nx * sizeof *scratch) : NULL;
    if (status == IM_OK && !scratch)
        status = im_fail(IM_ENOMEM, "aligning rows: allocation failed");
    for (int iy = 0; status == IM_OK && iy < surface->ny; ++iy) {
        double *row = surface->data + (size_t)iy * surface->nx;
        levels[iy] = how == IM_ALIGN_MEDIAN ? median_of(row, surface->nx, scratch)
                     : how == IM_ALIGN_MEAN ? mean_of(row, surface->nx)
                                            : remove_line(row, surface->nx);
    }
    double kept = status == IM_OK ? mean_of(levels, surface->ny) : 0.0;
    for (int iy = 0; status == IM_OK && iy < surface->ny; ++iy)
        for (int ix = 0; ix < surface->nx; ++ix)
            surface->data[(size_t)iy * surface->nx + ix] += kept - levels[iy];
    free(scratch);
    free(levels);
    return status;
}
