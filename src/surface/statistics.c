#include "indentmap/surface.h"

#include "indentmap/status.h"
#include "surface/spectrum.h"

#include <math.h>
#include <stdlib.h>

/* Sums in a fixed order: per-row partial sums in parallel, then rows in sequence. */
typedef double (*row_term)(const im_field *f, int iy);

static double ordered_sum_over_rows(const im_field *f, int rows, row_term term)
{
    double *partial = malloc((size_t)rows * sizeof *partial);
    if (!partial)
        return NAN;
#pragma omp parallel for schedule(static)
    for (int iy = 0; iy < rows; ++iy)
        partial[iy] = term(f, iy);
    double total = 0.0;
    for (int iy = 0; iy < rows; ++iy)
        total += partial[iy];
    free(partial);
    return total;
}

static double row_sum(const im_field *f, int iy)
{
    const double *row = f->data + (size_t)iy * f->nx;
    double sum = 0.0;
    for (int ix = 0; ix < f->nx; ++ix)
        sum += row[ix];
    return sum;
}

static double row_dx_squared(const im_field *f, int iy)
{
    const double *row = f->data + (size_t)iy * f->nx;
    double sum = 0.0;
    for (int ix = 0; ix + 1 < f->nx; ++ix)
        sum += (row[ix + 1] - row[ix]) * (row[ix + 1] - row[ix]);
    return sum;
}

static double row_dy_squared(const im_field *f, int iy)
{
    const double *row = f->data + (size_t)iy * f->nx, *next = row + f->nx;
    double sum = 0.0;
    for (int ix = 0; ix < f->nx; ++ix)
        sum += (next[ix] - row[ix]) * (next[ix] - row[ix]);
    return sum;
}

static int slope_rms_finite_difference(const im_field *f, double *slope)
{
    double mean_dx2 = f->nx > 1 ? ordered_sum_over_rows(f, f->ny, row_dx_squared) /
                                      ((double)(f->nx - 1) * f->ny) : 0.0;
    double mean_dy2 = f->ny > 1 ? ordered_sum_over_rows(f, f->ny - 1, row_dy_squared) /
                                      ((double)f->nx * (f->ny - 1)) : 0.0;
    *slope = sqrt(mean_dx2 + mean_dy2) / f->delta;
    return isfinite(*slope) ? IM_OK : im_fail(IM_ENOMEM, "slope: allocation failed");
}

static double weight_q2(double qx, double qy) { return qx * qx + qy * qy; }
static double weight_profile_q2(double qx, double qy) { return 0.5 * (qx * qx + qy * qy); }
static double weight_profile_q4(double qx, double qy)
{
    return 0.5 * (qx * qx * qx * qx + qy * qy * qy * qy);
}
static double weight_mean_curvature(double qx, double qy)
{
    double q2 = qx * qx + qy * qy;
    return 0.25 * q2 * q2;
}
static double weight_zero_mean(double qx, double qy) { return (qx == 0.0 && qy == 0.0) ? 0.0 : 1.0; }

int im_surface_slope_rms(const im_field *surface, enum im_slope_definition definition,
                         double *slope_rms)
{
    if (definition == IM_SLOPE_FINITE_DIFFERENCE)
        return slope_rms_finite_difference(surface, slope_rms);
    surface_spectrum spectrum;
    int status = surface_spectrum_of(surface, &spectrum);
    if (status != IM_OK)
        return status;
    *slope_rms = sqrt(spectrum_weighted_power(&spectrum, weight_q2));
    surface_spectrum_release(&spectrum);
    return IM_OK;
}

static void height_extremes(const im_field *f, double *lo, double *hi)
{
    double min = INFINITY, max = -INFINITY;
    size_t count = im_field_count(f);
#pragma omp parallel for reduction(min : min) reduction(max : max) schedule(static)
    for (size_t i = 0; i < count; ++i) {
        min = fmin(min, f->data[i]);
        max = fmax(max, f->data[i]);
    }
    *lo = min;
    *hi = max;
}

/* The statistics square heights (and their spectrum sums n^2 of them), so heights must stay far
 * below sqrt(DBL_MAX) ~ 1e154: beyond, they overflowed to NaN statistics or to a slope reported as
 * an allocation failure. No surface in any length unit comes near this bound. */
static const double LARGEST_HEIGHT = 1e100;

static int check_height_range(const im_field *surface)
{
    for (size_t i = 0; i < im_field_count(surface); ++i)
        if (fabs(surface->data[i]) > LARGEST_HEIGHT)
            return im_fail(IM_EINVAL, "surface: height %g at (x=%zu, y=%zu): expected |h| <= %g (rescale the "
                           "heights: their squares must not overflow)", surface->data[i], i % (size_t)surface->nx,
                           i / (size_t)surface->nx, LARGEST_HEIGHT);
    return IM_OK;
}

int im_surface_statistics(const im_field *surface, im_surface_stats *stats)
{
    int status = im_field_check_finite(surface, "surface");
    if (status == IM_OK)
        status = check_height_range(surface);
    if (status != IM_OK)
        return status;
    surface_spectrum spectrum;
    status = surface_spectrum_of(surface, &spectrum);
    if (status != IM_OK)
        return status;
    stats->mean = ordered_sum_over_rows(surface, surface->ny, row_sum) / (double)im_field_count(surface);
    stats->m0 = spectrum_weighted_power(&spectrum, weight_zero_mean);
    stats->height_rms = sqrt(stats->m0);
    stats->m2 = spectrum_weighted_power(&spectrum, weight_profile_q2);
    stats->m4 = spectrum_weighted_power(&spectrum, weight_profile_q4);
    stats->slope_rms_spectral = sqrt(spectrum_weighted_power(&spectrum, weight_q2));
    stats->curvature_rms = sqrt(spectrum_weighted_power(&spectrum, weight_mean_curvature));
    stats->nayak = stats->m2 > 0.0 ? stats->m0 * stats->m4 / (stats->m2 * stats->m2) : NAN;
    surface_spectrum_release(&spectrum);
    height_extremes(surface, &stats->height_min, &stats->height_max);
    return slope_rms_finite_difference(surface, &stats->slope_rms_fd);
}
