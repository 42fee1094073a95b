#include "surface/spectrum.h"

#include "core/fft_threads.h"
#include "indentmap/status.h"

#include <fftw3.h>
#include <stdlib.h>
#include <string.h>

static void destroy_plan(fftw_plan plan)
{
    fft_planner_lock();
    fftw_destroy_plan(plan);
    fft_planner_unlock();
}

int surface_spectrum_alloc(int nx, int ny, double delta, surface_spectrum *out)
{
    memset(out, 0, sizeof *out);
    out->nx = nx;
    out->ny = ny;
    out->half_nx = nx / 2 + 1;
    out->qx_step = 2.0 * M_PI / (nx * delta);
    out->qy_step = 2.0 * M_PI / (ny * delta);
    size_t count = (size_t)out->half_nx * (size_t)ny;
    char what[64];
    snprintf(what, sizeof what, "spectrum of a %d x %d grid", nx, ny);
    int status = im_memory_check((double)count * sizeof(double complex), what);
    if (status != IM_OK)
        return status;
    out->coefficients = fftw_malloc(count * sizeof(double complex));
    if (!out->coefficients)
        return im_fail(IM_ENOMEM, "%s: allocation failed", what);
    memset(out->coefficients, 0, count * sizeof(double complex));
    return IM_OK;
}

void surface_spectrum_release(surface_spectrum *spectrum)
{
    fftw_free(spectrum->coefficients);
    spectrum->coefficients = NULL;
}

int surface_spectrum_of(const im_field *field, surface_spectrum *out)
{
    int status = surface_spectrum_alloc(field->nx, field->ny, field->delta, out);
    if (status != IM_OK)
        return status;
    size_t count = im_field_count(field);
    double *input = fftw_malloc(count * sizeof *input);
    if (!input) {
        surface_spectrum_release(out);
        return im_fail(IM_ENOMEM, "spectrum: allocation of the transform input failed");
    }
    fft_planner_lock();
    fft_prepare_planner();
    fftw_plan plan = fftw_plan_dft_r2c_2d(field->ny, field->nx, input, (fftw_complex *)out->coefficients,
                                          FFTW_ESTIMATE);
    fft_planner_unlock();
    memcpy(input, field->data, count * sizeof *input);
    fftw_execute(plan);
    destroy_plan(plan);
    fftw_free(input);
    size_t spectrum_count = (size_t)out->half_nx * (size_t)out->ny;
    double scale = 1.0 / (double)count;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < spectrum_count; ++i)
        out->coefficients[i] *= scale;
    return IM_OK;
}

int surface_spectrum_to_field(const surface_spectrum *spectrum, im_field *field)
{
    size_t spectrum_count = (size_t)spectrum->half_nx * (size_t)spectrum->ny;
    double complex *work = fftw_malloc(spectrum_count * sizeof *work);
    if (!work)
        return im_fail(IM_ENOMEM, "inverse transform: allocation of the work spectrum failed");
    fft_planner_lock();
    fft_prepare_planner();
    /* c2r transforms overwrite their input: plan and run on a copy. */
    fftw_plan plan = fftw_plan_dft_c2r_2d(field->ny, field->nx, (fftw_complex *)work, field->data, FFTW_ESTIMATE);
    fft_planner_unlock();
    memcpy(work, spectrum->coefficients, spectrum_count * sizeof *work);
    fftw_execute(plan);
    destroy_plan(plan);
    fftw_free(work);
    return IM_OK;
}

int spectrum_weighted_power(const surface_spectrum *s, double (*weight)(double qx, double qy), double *power)
{
    double *row_sums = calloc((size_t)s->ny, sizeof *row_sums);
    if (!row_sums)
        return im_fail(IM_ENOMEM, "spectral moment of a %d x %d surface: no memory for %d row sums", s->half_nx,
                       s->ny, s->ny);
#pragma omp parallel for schedule(static)
    for (int jy = 0; jy < s->ny; ++jy) {
        double qy = spectrum_ky(s, jy) * s->qy_step;
        double sum = 0.0;
        for (int jx = 0; jx < s->half_nx; ++jx) {
            double complex c = s->coefficients[(size_t)jy * s->half_nx + jx];
            double power = creal(c) * creal(c) + cimag(c) * cimag(c);
            sum += spectrum_weight(s, jx) * weight(spectrum_kx(jx) * s->qx_step, qy) * power;
        }
        row_sums[jy] = sum;
    }
    double total = 0.0;
    for (int jy = 0; jy < s->ny; ++jy)
        total += row_sums[jy];
    free(row_sums);
    *power = total;
    return IM_OK;
}
