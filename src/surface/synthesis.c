#include "indentmap/surface.h"
#include "core/args.h"

#include "core/random.h"
#include "indentmap/status.h"
#include "surface/spectrum.h"
#include "surface/synthesis.h"

#include <math.h>
#include <stdio.h>

im_surface_params im_surface_params_default(void)
{
    im_surface_params params = {
        .nx = 512,
        .ny = 512,
        .delta = 1.0,
        .hurst = 0.8,
        .lambda_s = 4.0,
        .lambda_r = 512.0,
        .lambda_0 = 0.0,
        .target = IM_TARGET_SLOPE,
        .slope_rms = 0.08,
        .height_rms = 1.0,
        .slope_definition = IM_SLOPE_SPECTRAL,
        .seed = 1,
    };
    return params;
}

int im_surface_params_check(const im_surface_params *p)
{
    ARG_REQUIRE(p, "params");
    if (p->nx < 2 || p->ny < 2 || p->nx > IM_FIELD_MAX_SIDE || p->ny > IM_FIELD_MAX_SIDE)
        return im_fail(IM_EINVAL, "grid %d x %d: expected each side in [2, %d]", p->nx, p->ny, IM_FIELD_MAX_SIDE);
    if (!(p->delta > 0.0) || !isfinite(p->delta))
        return im_fail(IM_EINVAL, "delta = %g: expected a finite value > 0", p->delta);
    if (!(p->hurst > 0.0 && p->hurst < 1.0))
        return im_fail(IM_EINVAL, "hurst = %g: expected 0 < H < 1", p->hurst);
    if (!(p->lambda_s >= 2.0) || !isfinite(p->lambda_s))
        return im_fail(IM_EINVAL,
                       "lambda_s = %g: expected a finite value >= 2 (grid spacings; "
                       "shorter waves do not exist on the grid)",
                       p->lambda_s);
    if (!(p->lambda_r > p->lambda_s) || !isfinite(p->lambda_r))
        return im_fail(IM_EINVAL, "lambda_r = %g: expected a finite value > lambda_s = %g", p->lambda_r, p->lambda_s);
    if (!isfinite(p->lambda_0))
        return im_fail(IM_EINVAL, "lambda_0 = %g: expected a finite value", p->lambda_0);
    if (p->target == IM_TARGET_SLOPE && (!(p->slope_rms >= 0.0) || !isfinite(p->slope_rms)))
        return im_fail(IM_EINVAL, "slope (h'rms) = %g: expected a finite value >= 0", p->slope_rms);
    if (p->target == IM_TARGET_HEIGHT && (!(p->height_rms >= 0.0) || !isfinite(p->height_rms)))
        return im_fail(IM_EINVAL, "height-rms = %g: expected a finite value >= 0", p->height_rms);
    return IM_OK;
}

double im_surface_generate_bytes(int nx, int ny)
{
    ARG_SIDES_OR(nx, ny, NAN);
    double cells = (double)nx * (double)ny;
    /* the field, its half spectrum, and the inverse transform's work copy */
    return cells * sizeof(double) + 2.0 * (nx / 2 + 1) * (double)ny * 2.0 * sizeof(double);
}

/* Cutoff wave numbers of the spectrum. */
typedef struct spectrum_band {
    double q_0, q_r, q_s, exponent;
} spectrum_band;

static spectrum_band band_of(const im_surface_params *p)
{
    spectrum_band band;
    band.q_s = 2.0 * M_PI / (p->lambda_s * p->delta);
    band.q_r = 2.0 * M_PI / (p->lambda_r * p->delta);
    band.q_0 = p->lambda_0 > p->lambda_r ? 2.0 * M_PI / (p->lambda_0 * p->delta) : band.q_r;
    band.exponent = -2.0 * (1.0 + p->hurst);
    return band;
}

/* The continuous PSD shape (without its prefactor) at wave number q. */
static double psd_shape(const spectrum_band *b, double q)
{
    if (q > b->q_s || q < b->q_0 || q == 0.0)
        return 0.0;
    return pow(fmax(q, b->q_r), b->exponent);
}

/* The PSD averaged over the cell of the reciprocal lattice around (qx, qy). A discrete mode stands
 * for the power of its whole cell, so the discrete spectrum's moments are those of the continuous
 * one (eq. 13): sampling C at the cell centre instead over-weights the longest waves, where a cell
 * straddles q_r, and gives h_rms about 40% above eq. (15) for the paper's surfaces. The average is a
 * 16 x 16 midpoint rule where C varies within the cell (near the origin, across a cutoff) and the
 * centre value elsewhere (relative error below 1e-3 there). */
static double psd_cell_average(const spectrum_band *b, double qx, double qy, double dqx, double dqy)
{
    enum { SUBSAMPLES = 16, SMOOTH_FROM_CELLS = 32 };
    double q = hypot(qx, qy), half_diagonal = 0.5 * hypot(dqx, dqy);
    int near_cutoff = fabs(q - b->q_s) < half_diagonal || fabs(q - b->q_r) < half_diagonal ||
                      fabs(q - b->q_0) < half_diagonal;
    if (!near_cutoff && q >= SMOOTH_FROM_CELLS * fmax(dqx, dqy))
        return psd_shape(b, q);
    double sum = 0.0;
    for (int i = 0; i < SUBSAMPLES; ++i)
        for (int j = 0; j < SUBSAMPLES; ++j)
            sum += psd_shape(b, hypot(qx + dqx * ((i + 0.5) / SUBSAMPLES - 0.5),
                                      qy + dqy * ((j + 0.5) / SUBSAMPLES - 0.5)));
    return sum / (SUBSAMPLES * SUBSAMPLES);
}

/* Complex Gaussian of unit variance E|z|^2 = 1 for the mode (kx, ky); the mode (-kx, -ky) gets
 * the conjugate, so the surface is real. */
static double complex mode_amplitude(uint64_t seed, int kx, int ky)
{
    int canonical = kx > 0 || (kx == 0 && ky > 0);
    int ckx = canonical ? kx : -kx, cky = canonical ? ky : -ky;
    uint64_t key = hash3(seed, ckx, cky);
    double u1 = uniform_open0(mix64(key ^ 0x1u));
    double u2 = uniform_open0(mix64(key ^ 0x2u));
    double radius = sqrt(-log(u1)); /* |z|^2 exponential with mean 1: Box-Muller */
    double complex z = radius * cexp(2.0 * M_PI * I * u2);
    return canonical ? z : conj(z);
}

static int is_nyquist(int k, int n) { return n % 2 == 0 && (k == n / 2 || k == -n / 2); }

double complex surface_mode_coefficient(const im_surface_params *p, int kx, int ky, double qx_step, double qy_step)
{
    /* Nyquist modes have no well-defined slope (and no conjugate partner): no power. */
    if ((kx == 0 && ky == 0) || is_nyquist(kx, p->nx) || is_nyquist(ky, p->ny))
        return 0.0;
    spectrum_band band = band_of(p);
    double shape = psd_cell_average(&band, kx * qx_step, ky * qy_step, qx_step, qy_step);
    return shape > 0.0 ? sqrt(shape) * mode_amplitude(p->seed, kx, ky) : 0.0;
}

static void fill_spectrum(const im_surface_params *p, surface_spectrum *s)
{
#pragma omp parallel for schedule(static)
    for (int jy = 0; jy < s->ny; ++jy)
        for (int jx = 0; jx < s->half_nx; ++jx)
            s->coefficients[(size_t)jy * s->half_nx + jx] =
                surface_mode_coefficient(p, spectrum_kx(jx), spectrum_ky(s, jy), s->qx_step, s->qy_step);
}

static double weight_one(double qx, double qy)
{
    (void)qx;
    (void)qy;
    return 1.0;
}
static double weight_q2(double qx, double qy) { return qx * qx + qy * qy; }

static void scale_field(im_field *field, double factor)
{
    size_t count = im_field_count(field);
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < count; ++i)
        field->data[i] *= factor;
}

/* The value of the target quantity for the unscaled surface. */
static int measure_target(const im_surface_params *p, const surface_spectrum *s, const im_field *field, double *value)
{
    if (p->target == IM_TARGET_HEIGHT || p->slope_definition == IM_SLOPE_SPECTRAL) {
        double power = 0.0;
        int status = spectrum_weighted_power(s, p->target == IM_TARGET_HEIGHT ? weight_one : weight_q2, &power);
        *value = sqrt(power);
        return status;
    }
    return im_surface_slope_rms(field, IM_SLOPE_FINITE_DIFFERENCE, value);
}

int im_surface_generate(const im_surface_params *p, im_field **out)
{
    ARG_REQUIRE(p, "params");
    ARG_REQUIRE(out, "out");
    *out = NULL;
    int status = im_surface_params_check(p);
    if (status != IM_OK)
        return status;
    char what[64];
    snprintf(what, sizeof what, "synthesis of a %d x %d surface", p->nx, p->ny);
    status = im_memory_check(im_surface_generate_bytes(p->nx, p->ny), what);
    if (status != IM_OK)
        return status;
    surface_spectrum spectrum;
    status = surface_spectrum_alloc(p->nx, p->ny, p->delta, &spectrum);
    if (status != IM_OK)
        return status;
    im_field *field = NULL;
    status = im_field_create(p->nx, p->ny, p->delta, &field);
    if (status == IM_OK) {
        fill_spectrum(p, &spectrum);
        status = surface_spectrum_to_field(&spectrum, field);
    }
    double current = 0.0;
    if (status == IM_OK)
        status = measure_target(p, &spectrum, field, &current);
    surface_spectrum_release(&spectrum);
    if (status != IM_OK) {
        im_field_free(field);
        return status;
    }
    double wanted = p->target == IM_TARGET_HEIGHT ? p->height_rms * p->delta : p->slope_rms;
    if (!(current > 0.0)) {
        im_field_free(field);
        return im_fail(IM_EINVAL,
                       "no Fourier mode lies between lambda_s = %g and lambda_0 = %g on "
                       "a %d x %d grid: the surface would be flat",
                       p->lambda_s, fmax(p->lambda_0, p->lambda_r), p->nx, p->ny);
    }
    scale_field(field, wanted / current);
    *out = field;
    return IM_OK;
}
