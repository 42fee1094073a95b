#include "indentmap/surface.h"
#include "core/args.h"

#include "indentmap/status.h"

#include <math.h>
#include <stdlib.h>

void im_histogram_free(im_histogram *histogram)
{
    if (!histogram)
        return;
    free(histogram->centre);
    free(histogram->density);
    free(histogram);
}

/* Collects the samples of a quantity into a new array; *count receives their number. */
static double *collect_samples(const im_field *f, enum im_histogram_quantity quantity, size_t *count)
{
    size_t nx = (size_t)f->nx, ny = (size_t)f->ny, capacity = 2 * nx * ny;
    double *samples = malloc(capacity * sizeof *samples);
    if (!samples)
        return NULL;
    size_t n = 0;
    const double *h = f->data;
    double d = f->delta;
    for (size_t iy = 0; iy < ny; ++iy) {
        for (size_t ix = 0; ix < nx; ++ix) {
            size_t i = iy * nx + ix;
            if (quantity == IM_HIST_HEIGHT) {
                samples[n++] = h[i];
            } else if (quantity == IM_HIST_SLOPE) {
                if (ix + 1 < nx)
                    samples[n++] = (h[i + 1] - h[i]) / d;
                if (iy + 1 < ny)
                    samples[n++] = (h[i + nx] - h[i]) / d;
            } else if (ix > 0 && iy > 0 && ix + 1 < nx && iy + 1 < ny) {
                double laplacian = h[i - 1] + h[i + 1] + h[i - nx] + h[i + nx] - 4.0 * h[i];
                samples[n++] = 0.5 * laplacian / (d * d);
            }
        }
    }
    *count = n;
    return samples;
}

static void mean_and_sd(const double *x, size_t n, double *mean, double *sd)
{
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i)
        sum += x[i];
    *mean = sum / (double)n;
    double ss = 0.0;
    for (size_t i = 0; i < n; ++i)
        ss += (x[i] - *mean) * (x[i] - *mean);
    *sd = sqrt(ss / (double)n);
}

int im_surface_histogram(const im_field *surface, enum im_histogram_quantity quantity, int bins, im_histogram **out)
{
    ARG_VIEW(surface, "surface");
    ARG_REQUIRE(out, "out");
    *out = NULL;
    if (bins < 1 || bins > 1000000)
        return im_fail(IM_EINVAL, "histogram bins = %d: expected 1 to 1000000", bins);
    if (quantity != IM_HIST_HEIGHT && quantity != IM_HIST_SLOPE && quantity != IM_HIST_CURVATURE)
        return im_fail(IM_EINVAL,
                       "im_surface_histogram: quantity = %d: expected IM_HIST_HEIGHT, IM_HIST_SLOPE "
                       "or IM_HIST_CURVATURE",
                       (int)quantity);
    size_t n = 0;
    double *samples = collect_samples(surface, quantity, &n);
    im_histogram *hist = calloc(1, sizeof *hist);
    if (hist) {
        hist->centre = calloc((size_t)bins, sizeof *hist->centre);
        hist->density = calloc((size_t)bins, sizeof *hist->density);
    }
    if (!samples || !hist || !hist->centre || !hist->density) {
        free(samples);
        im_histogram_free(hist);
        return im_fail(IM_ENOMEM, "histogram: allocation failed");
    }
    if (n == 0) {
        free(samples);
        im_histogram_free(hist);
        return im_fail(IM_EINVAL, "histogram: grid %d x %d too small for this quantity", surface->nx, surface->ny);
    }
    double mean, sd;
    mean_and_sd(samples, n, &mean, &sd);
    double half_range = sd > 0.0 ? 5.0 * sd : 1.0;
    hist->bins = bins;
    hist->lo = mean - half_range;
    hist->hi = mean + half_range;
    double width = (hist->hi - hist->lo) / bins;
    for (size_t i = 0; i < n; ++i) {
        int bin = (int)floor((samples[i] - hist->lo) / width);
        bin = bin < 0 ? 0 : (bin >= bins ? bins - 1 : bin);
        hist->density[bin] += 1.0;
    }
    for (int b = 0; b < bins; ++b) {
        hist->centre[b] = hist->lo + (b + 0.5) * width;
        hist->density[b] /= (double)n * width;
    }
    free(samples);
    *out = hist;
    return IM_OK;
}
