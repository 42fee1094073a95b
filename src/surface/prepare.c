/* Preparation of measured surfaces: missing points, cropping, plane and curvature removal, and the
 * window for spectral estimates of non-periodic data (surface.h). */
#include "indentmap/surface.h"
#include "core/args.h"

#include "indentmap/status.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int im_surface_crop(const im_field *surface, int x0, int y0, int nx, int ny, im_field **out)
{
    ARG_VIEW(surface, "surface");
    ARG_REQUIRE(out, "out");
    *out = NULL;
    if (x0 < 0 || y0 < 0 || nx < 2 || ny < 2 || x0 > surface->nx - nx || y0 > surface->ny - ny)
        return im_fail(IM_EINVAL,
                       "crop %d,%d,%d,%d: expected X0,Y0,NX,NY with NX, NY >= 2 inside the %d x %d "
                       "grid",
                       x0, y0, nx, ny, surface->nx, surface->ny);
    int status = im_field_create(nx, ny, surface->delta, out);
    if (status != IM_OK)
        return status;
    memcpy((*out)->unit, surface->unit, sizeof surface->unit);
    for (int iy = 0; iy < ny; ++iy)
        memcpy((*out)->data + (size_t)iy * nx, surface->data + (size_t)(y0 + iy) * surface->nx + x0,
               (size_t)nx * sizeof *surface->data);
    return IM_OK;
}

/* One pass of the fill: every missing point with a known 4-neighbour takes their mean. Points filled
 * in this pass do not feed each other (they are marked in `next` and copied after), so the result
 * does not depend on the scan order. Returns how many were filled. */
static long fill_pass(im_field *f, double *next)
{
    long filled = 0;
    size_t count = im_field_count(f);
    memcpy(next, f->data, count * sizeof *next);
    for (int iy = 0; iy < f->ny; ++iy)
        for (int ix = 0; ix < f->nx; ++ix) {
            size_t i = (size_t)iy * f->nx + ix;
            if (!isnan(f->data[i]))
                continue;
            double sum = 0.0;
            int known = 0;
            const int dx[4] = {-1, 1, 0, 0}, dy[4] = {0, 0, -1, 1};
            for (int k = 0; k < 4; ++k) {
                int jx = ix + dx[k], jy = iy + dy[k];
                if (jx < 0 || jy < 0 || jx >= f->nx || jy >= f->ny)
                    continue;
                double v = f->data[(size_t)jy * f->nx + jx];
                if (!isnan(v)) {
                    sum += v;
                    ++known;
                }
            }
            if (known) {
                next[i] = sum / known;
                ++filled;
            }
        }
    memcpy(f->data, next, count * sizeof *next);
    return filled;
}

int im_surface_fill_missing(im_field *surface, long *filled)
{
    ARG_VIEW(surface, "surface");
    ARG_REQUIRE(filled, "filled");
    *filled = 0;
    size_t count = im_field_count(surface);
    for (size_t i = 0; i < count; ++i)
        if (isinf(surface->data[i]))
            return im_fail(IM_ENUMERIC, "value %g at (x=%zu, y=%zu): only NaN marks a missing point",
                           surface->data[i], i % (size_t)surface->nx, i / (size_t)surface->nx);
    double *next = malloc(count * sizeof *next);
    if (!next)
        return im_fail(IM_ENOMEM, "fill: allocation of %zu values failed", count);
    long pass;
    while ((pass = fill_pass(surface, next)) > 0)
        *filled += pass;
    free(next);
    if (isnan(surface->data[0])) /* no pass filled anything and points are still missing: all are */
        return im_fail(IM_ENUMERIC, "fill: every point is missing (NaN)");
    return IM_OK;
}

/* Discrete orthogonal polynomials of degree 0, 1, 2 on the points 0..n-1: 1, t, t^2 - <t^2>, with t
 * centred. On a full grid, products of those in x and in y are orthogonal, so each term of the fit
 * is a projection and needs no linear solve. */
static double basis(int degree, int i, int n)
{
    double t = i - 0.5 * (n - 1);
    double mean_t2 = ((double)n * n - 1.0) / 12.0;
    return degree == 0 ? 1.0 : degree == 1 ? t : t * t - mean_t2;
}

/* Subtracts the projection of f onto basis(px, x) basis(py, y). */
static void remove_term(im_field *f, int px, int py)
{
    double dot = 0.0, norm = 0.0;
    for (int iy = 0; iy < f->ny; ++iy) {
        double by = basis(py, iy, f->ny);
        for (int ix = 0; ix < f->nx; ++ix) {
            double b = basis(px, ix, f->nx) * by;
            dot += b * f->data[(size_t)iy * f->nx + ix];
            norm += b * b;
        }
    }
    if (norm == 0.0)
        return;
    double coefficient = dot / norm;
    for (int iy = 0; iy < f->ny; ++iy) {
        double by = basis(py, iy, f->ny);
        for (int ix = 0; ix < f->nx; ++ix)
            f->data[(size_t)iy * f->nx + ix] -= coefficient * basis(px, ix, f->nx) * by;
    }
}

int im_surface_detrend(im_field *surface, enum im_detrend detrend)
{
    ARG_VIEW(surface, "surface");
    if (detrend != IM_DETREND_NONE && detrend != IM_DETREND_PLANE && detrend != IM_DETREND_CURVATURE)
        return im_fail(IM_EINVAL,
                       "im_surface_detrend: detrend = %d: expected IM_DETREND_NONE, _PLANE or "
                       "_CURVATURE",
                       (int)detrend);
    int status = im_field_check_finite(surface, "detrend");
    if (status != IM_OK)
        return status;
    /* a huge height is named where the file holds it, here where the caller still names the file: the fit
     * spreads it (or its overflow) over every point, and undetrended the statistics met it unnamed */
    status = im_surface_check_height_range(surface,
                                           detrend == IM_DETREND_NONE ? "surface" : "surface before detrending");
    if (status != IM_OK || detrend == IM_DETREND_NONE)
        return status;
    static const int TERMS[6][2] = {{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1, 1}, {0, 2}};
    int terms = detrend == IM_DETREND_CURVATURE ? 6 : 3;
    for (int t = 0; t < terms; ++t)
        remove_term(surface, TERMS[t][0], TERMS[t][1]);
    return IM_OK;
}

/* The window's value at point i of n: Hann sin^2(pi (i + 1/2) / n), or Tukey with a cosine taper
 * over the fraction alpha of the length (alpha / 2 at each end) and 1 between. */
static double window_value(const im_taper *window, int i, int n)
{
    double u = (i + 0.5) / n; /* in (0, 1) */
    if (window->kind == IM_TAPER_HANN)
        return sin(M_PI * u) * sin(M_PI * u);
    if (window->kind == IM_TAPER_TUKEY && window->alpha > 0.0) {
        double edge = fmin(u, 1.0 - u), half = 0.5 * window->alpha;
        return edge >= half ? 1.0 : sin(0.5 * M_PI * edge / half) * sin(0.5 * M_PI * edge / half);
    }
    return 1.0;
}

int im_surface_tapered(const im_field *surface, const im_taper *window, im_field **out)
{
    ARG_VIEW(surface, "surface");
    ARG_REQUIRE(out, "out");
    if (window->kind == IM_TAPER_TUKEY && !(window->alpha >= 0.0 && window->alpha <= 1.0))
        return im_fail(IM_EINVAL, "Tukey window alpha = %g: expected 0 <= alpha <= 1", window->alpha);
    int status = im_field_clone(surface, out);
    if (status != IM_OK)
        return status;
    im_field *f = *out;
    size_t count = im_field_count(f);
    double mean = 0.0, power = 0.0;
    for (size_t i = 0; i < count; ++i)
        mean += f->data[i];
    mean /= (double)count;
    for (int iy = 0; iy < f->ny; ++iy)
        for (int ix = 0; ix < f->nx; ++ix) {
            double w = window_value(window, ix, f->nx) * window_value(window, iy, f->ny);
            f->data[(size_t)iy * f->nx + ix] = w * (f->data[(size_t)iy * f->nx + ix] - mean);
            power += w * w;
        }
    double scale = 1.0 / sqrt(power / (double)count); /* keeps the mean power of the data */
    for (size_t i = 0; i < count; ++i)
        f->data[i] *= scale;
    return IM_OK;
}
