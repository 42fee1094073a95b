/* What single precision could buy the contact solver (issue 7; not a test). The solver is double
 * only; this measures, without a float solver, the two things that decide whether one would pay.
 *
 *   bench_float32 [--repeats R]
 *
 * 1. Speed: one forward r2c + inverse c2r 2-D FFTW pair of a padded grid in double (fftw) and in
 *    single (fftwf) precision, FFTW_ESTIMATE as the solver plans by default, at 1 and 2 OpenMP
 *    threads, for the padded grids of bench_tradeoff (256^2, 512^2, 1024^2: its 1x, 2x, 4x windows)
 *    and of the paper's configuration (750 x 756). Median of R repeats of a batch that lasts at
 *    least 0.2 s. From the float/double ratio s, the whole-solve speed-up if only the FFTs got
 *    faster (FFT share of an iteration 73% by perf): 1 / (0.27 + 0.73 / s); and an upper bound if
 *    the O(n) passes also halved (half the bytes): 1 / (0.27 / 2 + 0.73 / s).
 * 2. Accuracy: the paper's surface (512^2, H 0.8, h'rms 0.08, lambda_s 4, lambda_r 512, seed 1),
 *    80 degree cone, one displacement-controlled solve at w = 1.26 and at w = 31.5 (the first and
 *    last approaches of the paper's history) to tol 1e-11. Then the displacement of the converged
 *    pressure is recomputed by a float32 DC-FFT convolution (same kernel spectrum, rounded to
 *    float) and the solver's stopping rule, residual = max(rms over I_c of g, max over p = 0 of
 *    -g) / w, is evaluated with it: (a) u in float, the rest in double; (b) g = g0 - w + u summed in
 *    float too, as a float solver would. That residual is the floor a float32 solver cannot go
 *    below; it is compared with the presets' tolerances 1e-4 / 1e-6 / 1e-9. A double convolution by
 *    the same code checks that the difference is precision, not the code (residual ~1e-11).
 * Prints two CSV tables on stdout.
 */
#include "bench_common.h"
#include "core/fft_threads.h"
#include "indentmap/indenter.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"
#include "solver/plan.h"

#include <fftw3.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <string.h>

#define MAX_REPEATS 31
#define BATCH_SECONDS 0.2
#define FFT_SHARE 0.73

/* ---- 1. speed of the FFT pair ---- */

typedef struct pair_double {
    double *real;
    fftw_complex *modes;
    fftw_plan forward, backward;
} pair_double;

typedef struct pair_float {
    float *real;
    fftwf_complex *modes;
    fftwf_plan forward, backward;
} pair_float;

static void plan_double(pair_double *p, int px, int py)
{
    p->real = fftw_alloc_real((size_t)px * py);
    p->modes = fftw_alloc_complex((size_t)py * (px / 2 + 1));
    p->forward = fftw_plan_dft_r2c_2d(py, px, p->real, p->modes, FFTW_ESTIMATE);
    p->backward = fftw_plan_dft_c2r_2d(py, px, p->modes, p->real, FFTW_ESTIMATE);
    for (size_t i = 0; i < (size_t)px * py; ++i)
        p->real[i] = (double)(i % 7);
}

static void plan_float(pair_float *p, int px, int py)
{
    p->real = fftwf_alloc_real((size_t)px * py);
    p->modes = fftwf_alloc_complex((size_t)py * (px / 2 + 1));
    p->forward = fftwf_plan_dft_r2c_2d(py, px, p->real, p->modes, FFTW_ESTIMATE);
    p->backward = fftwf_plan_dft_c2r_2d(py, px, p->modes, p->real, FFTW_ESTIMATE);
    for (size_t i = 0; i < (size_t)px * py; ++i)
        p->real[i] = (float)(i % 7);
}

static void run_double(void *data)
{
    pair_double *p = data;
    fftw_execute(p->forward);
    fftw_execute(p->backward);
}

static void run_float(void *data)
{
    pair_float *p = data;
    fftwf_execute(p->forward);
    fftwf_execute(p->backward);
}

/* Median over repeats of the seconds per call of fn, each repeat a batch of >= BATCH_SECONDS. */
static double time_pair(void (*fn)(void *), void *data, int repeats)
{
    fn(data);
    double start = bench_now();
    fn(data);
    double once = fmax(bench_now() - start, 1e-6);
    int batch = (int)ceil(BATCH_SECONDS / once);
    double seconds[MAX_REPEATS];
    for (int r = 0; r < repeats; ++r) {
        start = bench_now();
        for (int k = 0; k < batch; ++k)
            fn(data);
        seconds[r] = (bench_now() - start) / batch;
    }
    return bench_median(seconds, repeats);
}

static void time_size(int px, int py, int threads, int repeats)
{
    omp_set_num_threads(threads);
    fft_prepare_planner();
    pair_double d;
    pair_float f;
    plan_double(&d, px, py);
    plan_float(&f, px, py);
    double td = time_pair(run_double, &d, repeats), tf = time_pair(run_float, &f, repeats);
    double s = td / tf;
    printf("%dx%d,%d,%.4f,%.4f,%.2f,%.2f,%.2f\n", px, py, threads, 1e3 * td, 1e3 * tf, s,
           1 / (1 - FFT_SHARE + FFT_SHARE / s), 1 / ((1 - FFT_SHARE) / 2 + FFT_SHARE / s));
    fftw_destroy_plan(d.forward);
    fftw_destroy_plan(d.backward);
    fftw_free(d.real);
    fftw_free(d.modes);
    fftwf_destroy_plan(f.forward);
    fftwf_destroy_plan(f.backward);
    fftwf_free(f.real);
    fftwf_free(f.modes);
}

static void speed_table(int repeats)
{
    static const int sizes[][2] = {{256, 256}, {512, 512}, {1024, 1024}, {750, 756}};
    printf("padded,threads,fftw_pair_ms,fftwf_pair_ms,fft_speedup,solve_speedup_fft_only,"
           "solve_speedup_bound\n");
    for (int k = 0; k < 4; ++k)
        for (int t = 1; t <= 2; ++t)
            time_size(sizes[k][0], sizes[k][1], t, repeats);
}

/* ---- 2. accuracy of a float32 convolution ---- */

/* The converged state on the solve window: pressure, displacement, undeformed gap, approach. */
typedef struct state {
    int nx, ny;
    double w;
    double *p, *u, *g0;
} state;

/* u = K p on the plan's grid by a full padded r2c / c2r pair in float (the plan's kernel spectrum
 * rounded to float), returned in double. */
static void convolve_float(const im_solver_plan *plan, const double *p, double *u)
{
    const int px = plan->px, py = plan->py, nx = plan->nx, ny = plan->ny;
    const size_t modes = (size_t)py * (px / 2 + 1);
    float *real = fftwf_alloc_real((size_t)px * py);
    fftwf_complex *spectrum = fftwf_alloc_complex(modes);
    fftwf_plan forward = fftwf_plan_dft_r2c_2d(py, px, real, spectrum, FFTW_ESTIMATE);
    fftwf_plan backward = fftwf_plan_dft_c2r_2d(py, px, spectrum, real, FFTW_ESTIMATE);
    memset(real, 0, sizeof(float) * (size_t)px * py);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            real[(size_t)j * px + i] = (float)p[(size_t)j * nx + i];
    fftwf_execute(forward);
    for (size_t k = 0; k < modes; ++k) {
        spectrum[k][0] *= (float)plan->spectrum[k];
        spectrum[k][1] *= (float)plan->spectrum[k];
    }
    fftwf_execute(backward);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            u[(size_t)j * nx + i] = real[(size_t)j * px + i];
    fftwf_destroy_plan(forward);
    fftwf_destroy_plan(backward);
    fftwf_free(real);
    fftwf_free(spectrum);
}

/* The same convolution in double: checks the code path against the solver's u. */
static void convolve_double(const im_solver_plan *plan, const double *p, double *u)
{
    const int px = plan->px, py = plan->py, nx = plan->nx, ny = plan->ny;
    const size_t modes = (size_t)py * (px / 2 + 1);
    double *real = fftw_alloc_real((size_t)px * py);
    fftw_complex *spectrum = fftw_alloc_complex(modes);
    fftw_plan forward = fftw_plan_dft_r2c_2d(py, px, real, spectrum, FFTW_ESTIMATE);
    fftw_plan backward = fftw_plan_dft_c2r_2d(py, px, spectrum, real, FFTW_ESTIMATE);
    memset(real, 0, sizeof(double) * (size_t)px * py);
    for (int j = 0; j < ny; ++j)
        memcpy(real + (size_t)j * px, p + (size_t)j * nx, sizeof(double) * nx);
    fftw_execute(forward);
    for (size_t k = 0; k < modes; ++k) {
        spectrum[k][0] *= plan->spectrum[k];
        spectrum[k][1] *= plan->spectrum[k];
    }
    fftw_execute(backward);
    for (int j = 0; j < ny; ++j)
        memcpy(u + (size_t)j * nx, real + (size_t)j * px, sizeof(double) * nx);
    fftw_destroy_plan(forward);
    fftw_destroy_plan(backward);
    fftw_free(real);
    fftw_free(spectrum);
}

/* The stopping rule's residual for displacement u; in_float: g = g0 - w + u summed in float. */
static double residual(const state *s, const double *u, int in_float)
{
    double sum = 0, worst = 0;
    long contact = 0;
    for (size_t i = 0; i < (size_t)s->nx * s->ny; ++i) {
        double g = in_float ? (double)((float)s->g0[i] - (float)s->w + (float)u[i]) : s->g0[i] - s->w + u[i];
        if (s->p[i] > 0) {
            sum += g * g;
            ++contact;
        } else {
            worst = fmax(worst, -g);
        }
    }
    return fmax(contact ? sqrt(sum / contact) : 0, worst) / s->w;
}

/* max |a - b| / max |b| and ||a - b|| / ||b|| over n values */
static void relative_difference(const double *a, const double *b, size_t n, double *max, double *rms)
{
    double top = 0, diff = 0, sq = 0, sqb = 0;
    for (size_t i = 0; i < n; ++i) {
        top = fmax(top, fabs(b[i]));
        diff = fmax(diff, fabs(a[i] - b[i]));
        sq += (a[i] - b[i]) * (a[i] - b[i]);
        sqb += b[i] * b[i];
    }
    *max = diff / top;
    *rms = sqrt(sq / sqb);
}

/* Copies the window of the run's last step into s (p = f / delta^2, u, g0 = g - u + w). */
static int take_state(const im_indentation *run, double w, state *s)
{
    im_field *force = NULL, *gap = NULL, *disp = NULL;
    int status = im_indentation_fields(run, &force, &gap, &disp);
    if (status != IM_OK)
        return status;
    im_window win = im_indentation_window(run);
    const size_t n = (size_t)win.nx * win.ny;
    *s = (state){
        win.nx, win.ny, w, malloc(n * sizeof(double)), malloc(n * sizeof(double)), malloc(n * sizeof(double))};
    const double d2 = force->delta * force->delta;
    for (int j = 0; j < win.ny; ++j)
        for (int i = 0; i < win.nx; ++i) {
            size_t k = (size_t)j * win.nx + i, f = (size_t)(win.y0 + j) * force->nx + (win.x0 + i);
            s->p[k] = force->data[f] / d2;
            s->u[k] = disp->data[f];
            s->g0[k] = gap->data[f] - disp->data[f] + w;
        }
    im_field_free(force);
    im_field_free(gap);
    im_field_free(disp);
    return IM_OK;
}

static void free_state(state *s)
{
    free(s->p);
    free(s->u);
    free(s->g0);
}

static void report_accuracy(const im_indentation *run, const im_step_result *r, double w)
{
    state s;
    if (take_state(run, w, &s) != IM_OK)
        return;
    const size_t n = (size_t)s.nx * s.ny;
    double *u32 = malloc(n * sizeof(double)), *u64 = malloc(n * sizeof(double));
    const im_solver_plan *plan = im_indentation_plan(run);
    convolve_float(plan, s.p, u32);
    convolve_double(plan, s.p, u64);
    double max32, rms32, max64, rms64;
    relative_difference(u32, s.u, n, &max32, &rms32);
    relative_difference(u64, s.u, n, &max64, &rms64);
    printf("%g,%dx%d,%ld,%d,%.3e,%.3e,%.3e,%.3e,%.3e,%.3e,%.3e,%.3e\n", w, s.nx, s.ny, r->contact_patches,
           r->iterations, r->residual, residual(&s, s.u, 0), residual(&s, u64, 0), residual(&s, u32, 0),
           residual(&s, u32, 1), max32, rms32, rms64);
    free(u32);
    free(u64);
    free_state(&s);
}

static int accuracy_at(const im_field *surface, double w)
{
    im_indenter cone = im_indenter_cone(80);
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-8; /* the tolerance these figures were measured at (the default is 1e-6) */
    o.tol = 1e-11;
    im_indentation *run = NULL;
    im_step_result r;
    int status = im_indentation_create(surface, &cone, IM_CONTROL_DISPLACEMENT, w, &o, &run);
    if (status == IM_OK)
        status = im_indentation_step(run, w, &r);
    if (status == IM_OK)
        report_accuracy(run, &r, w);
    im_indentation_free(run);
    return status;
}

static int accuracy_table(void)
{
    im_surface_params sp = im_surface_params_default();
    sp.nx = sp.ny = 512;
    sp.hurst = 0.8;
    sp.slope_rms = 0.08;
    sp.lambda_s = 4;
    sp.lambda_r = 512;
    sp.seed = 1;
    im_field *surface = NULL;
    int status = im_surface_generate(&sp, &surface);
    printf("w,window,contact_patches,iterations,solver_residual,residual_u64,residual_u64_same_code,"
           "residual_u32,residual_u32_g32,u32_max_rel_error,u32_rms_rel_error,u64_same_code_rms_rel_error\n");
    for (int k = 0; k < 2 && status == IM_OK; ++k)
        status = accuracy_at(surface, k == 0 ? 1.26 : 31.5);
    im_field_free(surface);
    return status;
}

int main(int argc, char **argv)
{
    int repeats = 5;
    if (argc == 3 && strcmp(argv[1], "--repeats") == 0)
        repeats = atoi(argv[2]);
    if (repeats < 1 || repeats > MAX_REPEATS || (argc != 1 && argc != 3)) {
        fprintf(stderr, "usage: bench_float32 [--repeats R (1..%d)]\n", MAX_REPEATS);
        return 2;
    }
    printf("# OMP_WAIT_POLICY=%s\n", getenv("OMP_WAIT_POLICY") ? getenv("OMP_WAIT_POLICY") : "(unset)");
    speed_table(repeats);
    omp_set_num_threads(2);
    if (accuracy_table() != IM_OK) {
        fprintf(stderr, "bench_float32: %s\n", im_last_error());
        return 1;
    }
    return 0;
}
