#include "indentmap/surface.h"
#include "core/args.h"

#include "indentmap/status.h"
#include "surface/spectrum.h"

#include <math.h>
#include <stdlib.h>

void im_psd_free(im_psd *psd)
{
    if (!psd)
        return;
    free(psd->q);
    free(psd->c);
    free(psd->counts);
    free(psd);
}

static im_psd *psd_alloc(int bins)
{
    im_psd *psd = calloc(1, sizeof *psd);
    if (!psd)
        return NULL;
    psd->bins = bins;
    psd->q = calloc((size_t)bins, sizeof *psd->q);
    psd->c = calloc((size_t)bins, sizeof *psd->c);
    psd->counts = calloc((size_t)bins, sizeof *psd->counts);
    if (!psd->q || !psd->c || !psd->counts) {
        im_psd_free(psd);
        return NULL;
    }
    return psd;
}

/* Accumulates one stored entry into its logarithmic bin (serial: the sums stay in order). */
static void accumulate(im_psd *psd, const surface_spectrum *s, double log_lo, double log_width, double psd_scale,
                       int jx, int jy, double *q_sum)
{
    double qx = spectrum_kx(jx) * s->qx_step, qy = spectrum_ky(s, jy) * s->qy_step;
    double q = hypot(qx, qy);
    if (q == 0.0)
        return;
    int bin = (int)floor((log(q) - log_lo) / log_width);
    if (bin < 0)
        bin = 0;
    if (bin >= psd->bins)
        bin = psd->bins - 1;
    double complex c = s->coefficients[(size_t)jy * s->half_nx + jx];
    double weight = spectrum_weight(s, jx);
    psd->c[bin] += weight * psd_scale * (creal(c) * creal(c) + cimag(c) * cimag(c));
    q_sum[bin] += weight * q;
    psd->counts[bin] += (long)weight;
}

int im_surface_psd(const im_field *surface, int bins, im_psd **out)
{
    ARG_VIEW(surface, "surface");
    ARG_REQUIRE(out, "out");
    *out = NULL;
    if (bins < 1 || bins > 100000)
        return im_fail(IM_EINVAL, "psd bins = %d: expected 1 to 100000", bins);
    surface_spectrum s;
    int status = surface_spectrum_of(surface, &s);
    if (status != IM_OK)
        return status;
    im_psd *psd = psd_alloc(bins);
    double *q_sum = calloc((size_t)bins, sizeof *q_sum);
    if (!psd || !q_sum) {
        im_psd_free(psd);
        free(q_sum);
        surface_spectrum_release(&s);
        return im_fail(IM_ENOMEM, "psd: allocation failed");
    }
    double q_lo = fmin(s.qx_step, s.qy_step);
    double q_hi = hypot(s.qx_step * (surface->nx / 2), s.qy_step * (surface->ny / 2));
    double log_lo = log(q_lo) - 1e-9, log_width = (log(q_hi) - log_lo) / bins * (1.0 + 1e-12);
    /* C = |h~|^2 / A with h~ = delta^2 DFT(h) = delta^2 N H and A = N delta^2: C = delta^2 N |H|^2 */
    double psd_scale = surface->delta * surface->delta * (double)im_field_count(surface);
    for (int jy = 0; jy < s.ny; ++jy)
        for (int jx = 0; jx < s.half_nx; ++jx)
            accumulate(psd, &s, log_lo, log_width, psd_scale, jx, jy, q_sum);
    for (int i = 0; i < bins; ++i) {
        psd->q[i] = psd->counts[i] ? q_sum[i] / psd->counts[i] : NAN;
        psd->c[i] = psd->counts[i] ? psd->c[i] / psd->counts[i] : NAN;
    }
    free(q_sum);
    surface_spectrum_release(&s);
    *out = psd;
    return IM_OK;
}

int im_psd_fit_exponent(const im_psd *psd, double q_min, double q_max, double *exponent)
{
    ARG_REQUIRE(psd, "psd");
    ARG_REQUIRE(exponent, "exponent");
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int used = 0;
    for (int i = 0; i < psd->bins; ++i) {
        if (!psd->counts[i] || psd->q[i] < q_min || psd->q[i] > q_max || !(psd->c[i] > 0.0))
            continue;
        double x = log(psd->q[i]), y = log(psd->c[i]);
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
        ++used;
    }
    if (used < 2)
        return im_fail(IM_EINVAL, "psd fit: %d non-empty bins in q = [%g, %g]; expected at least 2", used, q_min,
                       q_max);
    *exponent = (used * sxy - sx * sy) / (used * sxx - sx * sx);
    return IM_OK;
}
