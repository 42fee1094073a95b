#include "indentmap/surface.h"
#include "core/args.h"

#include "indentmap/status.h"
#include "surface/spectrum.h"

#include <math.h>
#include <stdlib.h>

/* Sums in a fixed order: per-row partial sums in parallel, then rows in sequence. */
typedef double (*row_term)(const im_field *f, int iy);

static int ordered_sum_over_rows(const im_field *f, int rows, row_term term, double *sum)
{
    double *partial = malloc((size_t)rows * sizeof *partial);
    if (!partial)
        return im_fail(IM_ENOMEM, "statistics of a %d x %d surface: no memory for %d row sums", f->nx, f->ny, rows);
#pragma omp parallel for schedule(static)
    for (int iy = 0; iy < rows; ++iy)
        partial[iy] = term(f, iy);
    double total = 0.0;
    for (int iy = 0; iy < rows; ++iy)
        total += partial[iy];
    free(partial);
    *sum = total;
    return IM_OK;
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
    double sum_dx2 = 0.0, sum_dy2 = 0.0;
    int status = f->nx > 1 ? ordered_sum_over_rows(f, f->ny, row_dx_squared, &sum_dx2) : IM_OK;
    if (status == IM_OK && f->ny > 1)
        status = ordered_sum_over_rows(f, f->ny - 1, row_dy_squared, &sum_dy2);
    if (status != IM_OK)
        return status;
    double mean_dx2 = f->nx > 1 ? sum_dx2 / ((double)(f->nx - 1) * f->ny) : 0.0;
    double mean_dy2 = f->ny > 1 ? sum_dy2 / ((double)f->nx * (f->ny - 1)) : 0.0;
    *slope = sqrt(mean_dx2 + mean_dy2) / f->delta;
    if (!isfinite(*slope))
        return im_fail(IM_ENUMERIC,
                       "slope of a %d x %d surface: the squared height differences overflow "
                       "(heights of magnitude above ~1e154 in units of delta); rescale the heights",
                       f->nx, f->ny);
    return IM_OK;
}

static double weight_q2(double qx, double qy) { return qx * qx + qy * qy; }
static double weight_profile_q2(double qx, double qy) { return 0.5 * (qx * qx + qy * qy); }
static double weight_profile_q4(double qx, double qy) { return 0.5 * (qx * qx * qx * qx + qy * qy * qy * qy); }
static double weight_mean_curvature(double qx, double qy)
{
    double q2 = qx * qx + qy * qy;
    return 0.25 * q2 * q2;
}
static double weight_zero_mean(double qx, double qy) { return (qx == 0.0 && qy == 0.0) ? 0.0 : 1.0; }

int im_surface_slope_rms(const im_field *surface, enum im_slope_definition definition, double *slope_rms)
{
    ARG_VIEW(surface, "surface");
    ARG_REQUIRE(slope_rms, "slope_rms");
    if (definition != IM_SLOPE_SPECTRAL && definition != IM_SLOPE_FINITE_DIFFERENCE)
        return im_fail(IM_EINVAL,
                       "im_surface_slope_rms: definition = %d: expected IM_SLOPE_SPECTRAL or "
                       "IM_SLOPE_FINITE_DIFFERENCE",
                       (int)definition);
    if (definition == IM_SLOPE_FINITE_DIFFERENCE)
        return slope_rms_finite_difference(surface, slope_rms);
    surface_spectrum spectrum;
    int status = surface_spectrum_of(surface, &spectrum);
    if (status != IM_OK)
        return status;
    double power = 0.0;
    status = spectrum_weighted_power(&spectrum, weight_q2, &power);
    surface_spectrum_release(&spectrum);
    *slope_rms = sqrt(power);
    return status;
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

/* The moments, h_rms, spectral h'rms, curvature and Nayak's parameter from the spectrum. */
static int spectral_statistics(const surface_spectrum *spectrum, im_surface_stats *stats)
{
    double slope2 = 0.0, curvature2 = 0.0;
    int status = spectrum_weighted_power(spectrum, weight_zero_mean, &stats->m0);
    if (status == IM_OK)
        status = spectrum_weighted_power(spectrum, weight_profile_q2, &stats->m2);
    if (status == IM_OK)
        status = spectrum_weighted_power(spectrum, weight_profile_q4, &stats->m4);
    if (status == IM_OK)
        status = spectrum_weighted_power(spectrum, weight_q2, &slope2);
    if (status == IM_OK)
        status = spectrum_weighted_power(spectrum, weight_mean_curvature, &curvature2);
    stats->height_rms = sqrt(stats->m0);
    stats->slope_rms_spectral = sqrt(slope2);
    stats->curvature_rms = sqrt(curvature2);
    stats->nayak = stats->m2 > 0.0 ? stats->m0 * stats->m4 / (stats->m2 * stats->m2) : NAN;
    return status;
}

/* The statistics square heights (and their spectrum sums n^2 of them), so heights must stay far
 * below sqrt(DBL_MAX) ~ 1e154: beyond, they overflowed to NaN statistics or to a slope reported as
 * an allocation failure. No surface in any length unit comes near this bound. */
static const double LARGEST_HEIGHT = 1e100;

int im_surface_check_height_range(const im_field *surface, const char *what)
{
    ARG_VIEW(surface, "surface");
    for (size_t i = 0; i < im_field_count(surface); ++i)
        if (fabs(surface->data[i]) > LARGEST_HEIGHT)
            return im_fail(IM_EINVAL,
                           "%s: height %g at (x=%zu, y=%zu): expected |h| <= %g (rescale the heights: their "
                           "squares must not overflow)",
                           what ? what : "surface", surface->data[i], i % (size_t)surface->nx,
                           i / (size_t)surface->nx, LARGEST_HEIGHT);
    return IM_OK;
}

int im_surface_statistics(const im_field *surface, im_surface_stats *stats)
{
    ARG_VIEW(surface, "surface");
    ARG_REQUIRE(stats, "stats");
    int status = im_field_check_finite(surface, "surface");
    if (status == IM_OK)
        status = im_surface_check_height_range(surface, NULL);
    if (status != IM_OK)
        return status;
    surface_spectrum spectrum;
    status = surface_spectrum_of(surface, &spectrum);
    if (status != IM_OK)
        return status;
    status = spectral_statistics(&spectrum, stats);
    surface_spectrum_release(&spectrum);
    double sum = 0.0;
    if (status == IM_OK)
        status = ordered_sum_over_rows(surface, surface->ny, row_sum, &sum);
    if (status != IM_OK)
        return status;
    stats->mean = sum / (double)im_field_count(surface);
    height_extremes(surface, &stats->height_min, &stats->height_max);
    return slope_rms_finite_difference(surface, &stats->slope_rms_fd);
}

int im_surface_statistics_tapered(const im_field *surface, const im_taper *window, im_surface_stats *stats)
{
    ARG_VIEW(surface, "surface");
    ARG_REQUIRE(stats, "stats");
    int status = im_surface_statistics(surface, stats);
    if (status != IM_OK || window->kind == IM_TAPER_NONE)
        return status;
    im_field *windowed = NULL;
    im_surface_stats spectral;
    status = im_surface_tapered(surface, window, &windowed);
    if (status == IM_OK)
        status = im_surface_statistics(windowed, &spectral);
    im_field_free(windowed);
    if (status != IM_OK)
        return status;
    stats->slope_rms_spectral = spectral.slope_rms_spectral;
    stats->curvature_rms = spectral.curvature_rms;
    stats->m0 = spectral.m0;
    stats->m2 = spectral.m2;
    stats->m4 = spectral.m4;
    stats->nayak = spectral.nayak;
    return IM_OK;
}
