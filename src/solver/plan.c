#include "solver/engine.h"
#include "core/args.h"

#include "core/fft_threads.h"
#include "indentmap/gpu_config.h"
#include "indentmap/io.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

im_solver_options im_solver_options_default(void)
{
    return (im_solver_options){.e_star = 1,
                               .tol = im_quality_default_tolerance(),
                               .max_iterations = 10000,
                               .fft_measure = 0,
                               .wisdom_path = NULL,
                               .crop = 1,
                               .window_margin = 4,
                               .periodic = 0,
                               .hardness = 0,
                               .cascade = 1,
                               .precondition = 1};
}

/* The zone widened (P > 0) only with the Maugis-Dugdale law's adhesion, the only law with a Dugdale zone. */
static int check_adhesion_zone(const im_solver_options *o)
{
    if (!(isfinite(o->adhesion_zone) && o->adhesion_zone >= 0))
        return im_fail(IM_EINVAL,
                       "adhesion zone = %g: expected a finite number of patches P > 0 (0: the law as given)",
                       o->adhesion_zone);
    if (o->adhesion_zone > 0 && !(o->adhesion_work > 0))
        return im_fail(IM_EINVAL, "adhesion zone = %g patches without adhesion: expected a work and a range to widen",
                       o->adhesion_zone);
    if (o->adhesion_zone > 0 && o->adhesion_law != IM_ADHESION_MAUGIS_DUGDALE)
        return im_fail(IM_EINVAL,
                       "adhesion zone = %g patches with the %s law: expected the Maugis-Dugdale law (the only one "
                       "with a Dugdale zone to widen)",
                       o->adhesion_zone, im_adhesion_law_name(o->adhesion_law));
    return IM_OK;
}

/* Work and range both > 0 (adhesion) or both 0 (none). */
static int check_adhesion(const im_solver_options *o)
{
    if (!(isfinite(o->adhesion_work) && o->adhesion_work >= 0))
        return im_fail(IM_EINVAL, "adhesion work = %g: expected a finite work of adhesion w >= 0 (0: none)",
                       o->adhesion_work);
    if (!(isfinite(o->adhesion_range) && o->adhesion_range >= 0))
        return im_fail(IM_EINVAL, "adhesion range = %g: expected a finite gap delta_c > 0 (0: none)",
                       o->adhesion_range);
    if ((o->adhesion_work > 0) != (o->adhesion_range > 0))
        return im_fail(IM_EINVAL, "adhesion work = %g, range = %g: expected both > 0 (adhesion) or both 0 (none)",
                       o->adhesion_work, o->adhesion_range);
    if (!im_adhesion_law_name(o->adhesion_law))
        return im_fail(IM_EINVAL, "adhesion law = %d: expected IM_ADHESION_MAUGIS_DUGDALE or IM_ADHESION_EXPONENTIAL",
                       o->adhesion_law);
    if (o->adhesion_work > 0 && !(isfinite(o->adhesion_work / o->adhesion_range)))
        return im_fail(IM_EINVAL, "adhesion work = %g, range = %g: the stress w / delta_c is not finite",
                       o->adhesion_work, o->adhesion_range);
    return check_adhesion_zone(o);
}

int im_solver_options_check(const im_solver_options *o)
{
    ARG_REQUIRE(o, "options");
    if (!(isfinite(o->e_star) && o->e_star > 0))
        return im_fail(IM_EINVAL, "E* = %g: expected a finite modulus > 0", o->e_star);
    if (!(o->tol >= IM_SOLVER_TOL_MIN && o->tol <= IM_SOLVER_TOL_MAX))
        return im_fail(IM_EINVAL,
                       "tol = %g: expected %g <= tol <= %g (below, the relative residual is at double precision's "
                       "rounding)",
                       o->tol, IM_SOLVER_TOL_MIN, IM_SOLVER_TOL_MAX);
    if (o->max_iterations < 1)
        return im_fail(IM_EINVAL, "max_iterations = %d: expected >= 1", o->max_iterations);
    if (o->window_margin < 0)
        return im_fail(IM_EINVAL, "window_margin = %d: expected >= 0", o->window_margin);
    if (!(isfinite(o->hardness) && o->hardness >= 0))
        return im_fail(IM_EINVAL, "hardness = %g: expected a finite pressure cap H_p > 0 (0: none)", o->hardness);
    if (o->periodic != 0 && o->periodic != 1)
        return im_fail(IM_EINVAL, "periodic = %d: expected 0 or 1", o->periodic);
    if (o->cascade != 0 && o->cascade != 1)
        return im_fail(IM_EINVAL, "cascade = %d: expected 0 or 1", o->cascade);
    if (o->precondition != 0 && o->precondition != 1)
        return im_fail(IM_EINVAL, "precondition = %d: expected 0 or 1", o->precondition);
    if (o->device != IM_DEVICE_CPU && o->device != IM_DEVICE_GPU && o->device != IM_DEVICE_AUTO)
        return im_fail(IM_EINVAL, "device = %d: expected IM_DEVICE_CPU, IM_DEVICE_GPU or IM_DEVICE_AUTO", o->device);
    if (o->gpu_validation != 0 && o->gpu_validation != 1)
        return im_fail(IM_EINVAL, "gpu_validation = %d: expected 0 or 1", o->gpu_validation);
    return check_adhesion(o);
}

/* One corner term of Love's rectangle integral, X asinh(Y/|X|) + Y asinh(X/|Y|): the antiderivative
 * X ln(Y + r) + Y ln(X + r) less X ln|X| + Y ln|Y|, which cancel between corners. This form has no
 * cancellation when Y + r is small (Y < 0, |X| << |Y|), unlike the logarithms. */
static double corner_term(double x, double y)
{
    double t = 0;
    if (x != 0)
        t += x * asinh(y / fabs(x));
    if (y != 0)
        t += y * asinh(x / fabs(y));
    return t;
}

double im_influence_square(double x, double y, double delta, double e_star)
{
    double a = 0.5 * delta;
    double sum = corner_term(x + a, y + a) - corner_term(x + a, y - a) - corner_term(x - a, y + a) +
                 corner_term(x - a, y - a);
    return sum / (M_PI * e_star);
}

/* A level's tables on the host (kernel, spectrum, the preconditioner's spectrum): what every
 * engine's plan computes, before it knows where it runs. */
static double table_bytes(int nx, int ny, int periodic)
{
    const double n = (double)nx * ny, small = 0.5 * ny * (nx + 2), spectrum = periodic ? small : 2.0 * ny * (nx + 1);
    return 8 * (n + spectrum + small);
}

/* The temporaries while the tables are computed: the padded grid and its modes (4 n + 4 n reals),
 * or, periodic, the modes the kernel is transformed back from (n). */
static double temporary_bytes(int nx, int ny, int periodic) { return 8.0 * nx * ny * (periodic ? 1 : 8); }

/* What a convolution reads on the CPU engine: the padded rows and the padded modes (a periodic plan's
 * are a quarter: an upper bound). */
static double convolution_array_bytes(int nx, int ny)
{
    const double rows = 2.0 * nx * ny, modes = 2.0 * ny * (nx + 1);
    return 8 * (rows + 2 * modes);
}

/* The CPU engine's arrays of one level (a padded grid): the convolution's, 3 work arrays, changes (long +
 * double), the rows K t is read from, the preconditioner's grid and modes. */
static double cpu_array_bytes(int nx, int ny)
{
    const double n = (double)nx * ny, rows = 2 * n;
    return convolution_array_bytes(nx, ny) + 8 * (n * 4 + rows + 2 * n);
}

/* A convolution's plan at its peak: its tables with their temporaries while they are computed (padded:
 * the spectrum alone), or its spectrum with the convolution's arrays (made once the rest of the tables
 * is freed: finish_engine). */
static double convolution_bytes(int nx, int ny, int periodic)
{
    const double spectrum = 8.0 * (periodic ? 0.5 * ny * (nx + 2) : 2.0 * ny * (nx + 1));
    const double tables = periodic ? table_bytes(nx, ny, 1) : spectrum;
    return fmax(tables + temporary_bytes(nx, ny, periodic), spectrum + convolution_array_bytes(nx, ny));
}

/* One level's CPU plan, without the coarser levels: its tables, its arrays, and the padded grid the
 * kernel is sampled on while they are all held (compute_kernel transforms it into the arrays' modes). */
static double level_bytes(int nx, int ny)
{
    return table_bytes(nx, ny, 0) + cpu_array_bytes(nx, ny) + 0.5 * temporary_bytes(nx, ny, 0);
}

/* What a level's plan needs on the host before it knows its engine: the whole CPU plan when it asks
 * for the CPU (with its coarser levels, as before the GPU engine), else the tables and their
 * temporaries (the CPU engine's arrays are checked when such a plan stays on the CPU). */
static double planning_bytes(int nx, int ny, const im_solver_options *o, int convolution_only)
{
    if (o->device == IM_DEVICE_CPU && convolution_only)
        return convolution_bytes(nx, ny, o->periodic);
    if (o->device == IM_DEVICE_CPU)
        return im_solver_plan_bytes(nx, ny);
    return table_bytes(nx, ny, o->periodic) + temporary_bytes(nx, ny, o->periodic);
}

double im_solver_plan_bytes(int nx, int ny)
{
    ARG_SIDES_OR(nx, ny, NAN);
    int cx, cy;
    if (!solver_cascade_sides(nx, ny, 0, &cx, &cy)) /* a periodic plan with an odd side has none: an upper bound */
        return level_bytes(nx, ny);
    /* the coarse levels (about a third more) and each level's coarse gap, pressure, displacement */
    return level_bytes(nx, ny) + 8 * 3.0 * cx * cy + im_solver_plan_bytes(cx, cy);
}

/* A GPU plan's host memory at its peak, level by level from the finest; `held` is what the finer
 * levels keep meanwhile. A level's tables stay until they are on the device (keep_host_k0): beside
 * their temporaries while computed, then beside what attaching it adds (`attach`: the top level's
 * staging buffers, and its device buffers when the device's memory is the host's); its cascade arrays
 * (coarse gap, pressure, displacement) stay beside its coarser levels. */
static double gpu_host_bytes(int nx, int ny, const im_solver_options *o, double held, double attach)
{
    double peak = held + table_bytes(nx, ny, o->periodic) + fmax(temporary_bytes(nx, ny, o->periodic), attach);
    int cx, cy;
    if (o->cascade && solver_cascade_sides(nx, ny, o->periodic, &cx, &cy))
        peak = fmax(peak, gpu_host_bytes(cx, cy, o, held + attach + 8 * 3.0 * cx * cy, 0));
    return peak;
}

int solver_memory_choose(int nx, int ny, const im_solver_options *o, const solver_gpu_estimate *gpu,
                         im_solver_memory *out)
{
    const double gib = 1073741824.0;
    if (gpu->device_bytes > gpu->device_memory && o->device == IM_DEVICE_AUTO) {
        snprintf(out->note, sizeof out->note,
                 "device auto: a %d x %d solve needs %.3g GiB of device memory and %s has %.3g GiB: solved on "
                 "the CPU",
                 nx, ny, gpu->device_bytes / gib, gpu->device, gpu->device_memory / gib);
        return IM_OK;
    }
    const double attach = gpu->staging_bytes + (gpu->software ? gpu->device_bytes : 0);
    *out = (im_solver_memory){.gpu = 1,
                              .host_bytes = gpu_host_bytes(nx, ny, o, 0, attach),
                              .device_bytes = gpu->device_bytes,
                              .device_memory = gpu->device_memory};
    snprintf(out->device, sizeof out->device, "%s", gpu->device);
    if (gpu->device_bytes <= gpu->device_memory)
        return IM_OK;
    return im_fail(IM_ENOMEM,
                   "a %d x %d solve needs %.3g GiB of device memory (its fields, transforms and cascade levels) "
                   "and %s has %.3g GiB; use device cpu or auto, or a smaller grid",
                   nx, ny, gpu->device_bytes / gib, gpu->device, gpu->device_memory / gib);
}

#if !IM_HAVE_GPU
static int no_gpu_engine(void)
{
    return im_fail(IM_EUNSUPPORTED, "device = gpu: this build has no GPU engine (built without IM_GPU: Vulkan, "
                                    "glslang and VkFFT were not found; scripts/setup.sh installs them)");
}
#endif

#if IM_HAVE_GPU
/* Whether the GPU engine declined a plan that device = auto (or a cascade level of a plan on the GPU)
 * then solves on the CPU: it cannot do it (no hardware GPU, a size VkFFT does not transform) or the
 * device's memory would not hold it. Anything else (a bad INDENTMAP_GPU_* setting) is an error. */
static int gpu_declined(int status) { return status == IM_EUNSUPPORTED || status == IM_ENOMEM; }
#endif

/* The GPU's estimate and choice (solver_memory_choose); auto without a GPU engine or a GPU: the CPU. */
static int gpu_memory_needed(int nx, int ny, const im_solver_options *o, im_solver_memory *out)
{
#if IM_HAVE_GPU
    solver_gpu_estimate gpu;
    int status = solver_engine_gpu_estimate(nx, ny, o, &gpu);
    if (status != IM_OK)
        return o->device == IM_DEVICE_AUTO && gpu_declined(status) ? IM_OK : status;
    return solver_memory_choose(nx, ny, o, &gpu, out);
#else
    (void)nx, (void)ny, (void)out;
    return o->device == IM_DEVICE_AUTO ? IM_OK : no_gpu_engine();
#endif
}

int im_solver_memory_needed(int nx, int ny, const im_solver_options *options, im_solver_memory *out)
{
    ARG_REQUIRE(out, "out");
    *out = (im_solver_memory){.host_bytes = NAN};
    ARG_SIDES(nx, ny);
    im_solver_options o = options ? *options : im_solver_options_default();
    int status = im_solver_options_check(&o);
    if (status != IM_OK)
        return status;
    solver_plan_options(&o);
    const double cpu_bytes = o.cascade ? im_solver_plan_bytes(nx, ny) : level_bytes(nx, ny); /* no coarse levels */
    *out = (im_solver_memory){.host_bytes = cpu_bytes, .device = "cpu"};
    return o.device == IM_DEVICE_CPU ? IM_OK : gpu_memory_needed(nx, ny, &o, out);
}

int solver_convolution_memory_needed(int nx, int ny, const im_solver_options *options, im_solver_memory *out)
{
    int status = im_solver_memory_needed(nx, ny, options, out);
    if (status == IM_OK && !out->gpu)
        out->host_bytes = convolution_bytes(nx, ny, options->periodic);
    return status;
}

int im_solver_plan_memory(const im_solver_plan *plan, im_solver_memory *out)
{
    ARG_REQUIRE(out, "out");
    *out = (im_solver_memory){.host_bytes = NAN};
    ARG_REQUIRE(plan, "plan");
    if (plan->convolution_only && plan->engine == &solver_engine_cpu) {
        *out = (im_solver_memory){.host_bytes = convolution_bytes(plan->nx, plan->ny, plan->options.periodic),
                                  .device = "cpu"};
        return IM_OK;
    }
    return im_solver_memory_needed(plan->nx, plan->ny, &plan->options, out);
}

const char *im_solver_wisdom_file(const im_solver_options *o)
{
    return o && o->wisdom_path && o->wisdom_path[0] ? o->wisdom_path : NULL; /* NULL options: none */
}

int im_solver_wisdom_check(const im_solver_options *o)
{
    ARG_REQUIRE(o, "options");
    const char *path = im_solver_wisdom_file(o);
    if (!path)
        return IM_OK;
    enum im_file_kind kind;
    int status = im_file_kind_of(path, &kind);
    if (status == IM_OK && kind != IM_KIND_NONE && kind != IM_KIND_WISDOM)
        status = im_fail(IM_EINVAL, "%s holds %s, not FFTW wisdom", path, im_file_kind_name(kind));
    if (status == IM_OK)
        status = im_output_check(path);
    if (status == IM_OK)
        return IM_OK;
    char reason[512];
    snprintf(reason, sizeof reason, "%s", im_last_error());
    return im_fail(status,
                   "wisdom file %s: %s; it is neither read nor replaced (name a new file, or wisdom this "
                   "program wrote)",
                   path, reason);
}

/* Wisdom files hold a few kilobytes per transform size; anything far larger is not one. */
static const size_t WISDOM_MAX_BYTES = (size_t)64 << 20;

/* The text of a wisdom file, read within bounds (FFTW's own reader spun forever on /dev/zero);
 * *text stays NULL when there is no file yet. */
static int read_wisdom(const char *path, char **text)
{
    *text = NULL;
    if (!path || access(path, F_OK) != 0)
        return IM_OK;
    int status = im_read_text_file(path, WISDOM_MAX_BYTES, text, NULL);
    return status == IM_OK ? IM_OK : im_fail_context(status, "FFTW wisdom");
}

/* Imports the wisdom in text (NULL or empty: none); 0 when FFTW rejects it. Planner lock held. FFTW's
 * threads must be set up first: wisdom carries a signature of the planner's registered algorithms,
 * which fftw_init_threads extends, so wisdom written by a threaded planner is rejected before it. */
static int import_wisdom(const char *text)
{
    fft_prepare_planner();
    return !text || !text[0] || fftw_import_wisdom_from_string(text);
}

int im_solver_wisdom_verify(const im_solver_options *o)
{
    ARG_REQUIRE(o, "options");
    const char *path = im_solver_wisdom_file(o);
    int status = im_solver_wisdom_check(o);
    char *text = NULL;
    if (status == IM_OK)
        status = read_wisdom(path, &text);
    if (status != IM_OK)
        return status;
    fft_planner_lock();
    int accepted = import_wisdom(text);
    fft_planner_unlock();
    free(text);
    return accepted ? IM_OK
                    : im_fail(IM_EFORMAT,
                              "wisdom file %s: FFTW rejects it (damaged, or written by another FFTW "
                              "version)",
                              path);
}

/* Writes the accumulated wisdom atomically, so concurrent runs never read a torn file. What the file
 * holds now is merged in first: another run may have added sizes since this one read it (a run that
 * replaces the file between this read and the rename loses them; they are measured again when next
 * needed). Planner lock held. */
static int export_wisdom(const char *path)
{
    char *current = NULL;
    if (read_wisdom(path, &current) == IM_OK)
        import_wisdom(current); /* rejected text (damaged) is simply replaced */
    free(current);
    char *text = fftw_export_wisdom_to_string();
    if (!text)
        return im_fail(IM_ENOMEM, "exporting FFTW wisdom");
    int status = im_write_file_atomic(path, text, strlen(text));
    fftw_free(text);
    return status == IM_OK ? IM_OK : im_fail_context(status, "FFTW wisdom %s", path);
}

static int make_fft_plans(im_solver_plan *p)
{
    const char *wisdom = im_solver_wisdom_file(&p->options);
    int checked = im_solver_wisdom_check(&p->options);
    if (checked != IM_OK)
        return checked;
    char *wisdom_text;
    int read = read_wisdom(wisdom, &wisdom_text);
    if (read != IM_OK)
        return read;
    p->measured = p->options.fft_measure || wisdom != NULL;
    unsigned flags = p->measured ? FFTW_MEASURE : FFTW_ESTIMATE;
    const int mx = p->px / 2 + 1, row_length[1] = {p->px}, column_length[1] = {p->py};
    fft_planner_lock();         /* ensembles plan from several threads */
    import_wisdom(wisdom_text); /* damaged or stale wisdom just means none (im_solver_wisdom_verify tells) */
    free(wisdom_text);
    fft_prepare_planner();
    /* ny real rows of length px -> the first ny complex rows of length mx; then, in place, mx
     * columns of length py */
    p->rows_forward = fftw_plan_many_dft_r2c(1, row_length, p->ny, p->rows_in, NULL, 1, p->px, p->modes, NULL, 1, mx,
                                             flags);
    p->columns_forward = fftw_plan_many_dft(1, column_length, mx, p->modes, NULL, mx, 1, p->modes, NULL, mx, 1,
                                            FFTW_FORWARD, flags);
    p->columns_backward = fftw_plan_many_dft(1, column_length, mx, p->modes, NULL, mx, 1, p->modes, NULL, mx, 1,
                                             FFTW_BACKWARD, flags);
    p->rows_backward = fftw_plan_many_dft_c2r(1, row_length, p->ny, p->modes, NULL, 1, mx, p->rows_out, NULL, 1,
                                              p->px, flags);
    if (p->preconditioned) { /* a convolution's plan has none */
        p->precondition_forward = fftw_plan_dft_r2c_2d(p->ny, p->nx, p->preconditioned, p->precondition_modes, flags);
        p->precondition_backward = fftw_plan_dft_c2r_2d(p->ny, p->nx, p->precondition_modes, p->preconditioned,
                                                        flags);
    }
    int status = wisdom ? export_wisdom(wisdom) : IM_OK;
    fft_planner_unlock();
    if (!p->rows_forward || !p->columns_forward || !p->columns_backward || !p->rows_backward ||
        (p->preconditioned && (!p->precondition_forward || !p->precondition_backward)))
        return im_fail(IM_ENOMEM, "FFTW could not plan a %d x %d transform", p->px, p->py);
    return status;
}

static long wrapped_offset(long j, long n, long padded) { return j <= n ? j : padded - j; }

void solver_execute_once(fftw_plan plan)
{
    fftw_execute(plan);
    fft_planner_lock();
    fftw_destroy_plan(plan);
    fft_planner_unlock();
}

/* M = 1 / the spectrum of K wrapped periodically on the nx x ny grid (offsets min(j, n - j)): the
 * inverse of a circulant close to K, positive where that spectrum is (0 elsewhere). The wrapped
 * kernel into `wrapped`, transformed by `forward` into `spectrum`. */
static void invert_wrapped_kernel(im_solver_plan *p, double *wrapped, fftw_plan forward, fftw_complex *spectrum)
{
    const int nx = p->nx, ny = p->ny;
    const size_t modes = (size_t)ny * (nx / 2 + 1);
#pragma omp parallel for schedule(static)
    for (int jy = 0; jy < ny; ++jy)
        for (int jx = 0; jx < nx; ++jx)
            wrapped[(size_t)jy * nx + jx] =
                p->kernel[(size_t)(jy <= ny - jy ? jy : ny - jy) * nx + (jx <= nx - jx ? jx : nx - jx)];
    fftw_execute(forward);
    const double scale = 1.0 / ((double)nx * ny);
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < modes; ++k) {
        double re = spectrum[k][0];
        p->inverse_spectrum[k] = re > 0 ? scale / re : 0;
    }
}

/* The preconditioner's spectrum: through the CPU engine's own plan where it has one (measured with
 * its wisdom, so that a run's numbers do not depend on when the wisdom was read), else a one-off
 * plan on temporaries (a GPU plan has no CPU arrays to lend). */
static int compute_preconditioner(im_solver_plan *p)
{
    if (p->precondition_forward) {
        invert_wrapped_kernel(p, p->preconditioned, p->precondition_forward, p->precondition_modes);
        return IM_OK;
    }
    const int nx = p->nx, ny = p->ny;
    double *wrapped = fftw_malloc(sizeof(double) * (size_t)nx * ny);
    fftw_complex *spectrum = fftw_malloc(sizeof(fftw_complex) * (size_t)ny * (nx / 2 + 1));
    fft_planner_lock();
    fftw_plan forward = wrapped && spectrum ? fftw_plan_dft_r2c_2d(ny, nx, wrapped, spectrum, FFTW_ESTIMATE) : NULL;
    fft_planner_unlock();
    if (forward) {
        invert_wrapped_kernel(p, wrapped, forward, spectrum);
        fft_planner_lock();
        fftw_destroy_plan(forward);
        fft_planner_unlock();
    }
    fftw_free(wrapped);
    fftw_free(spectrum);
    return forward ? IM_OK : im_fail(IM_ENOMEM, "solver plan %d x %d: preconditioner transform", nx, ny);
}

/* Samples K on the grid (for direct sums, where the plan keeps the table) and on the padded grid with
 * wrap-around offsets (so that it is even and its spectrum real), then transforms it once with a one-off
 * plan: into the CPU engine's modes where the plan has them (its peak is then level_bytes'), else on
 * temporaries (a GPU plan has no CPU arrays to lend; a convolution's makes them after). */
static int compute_kernel(im_solver_plan *p)
{
    const int nx = p->nx, ny = p->ny, px = p->px, py = p->py, mx = px / 2 + 1;
    const double e = p->options.e_star, d = p->delta;
    double *padded = fftw_malloc(sizeof(double) * (size_t)px * py);
    fftw_complex *own_modes = p->modes ? NULL : fftw_malloc(sizeof(fftw_complex) * (size_t)py * mx);
    fftw_complex *modes = p->modes ? p->modes : own_modes;
    fft_planner_lock();
    fftw_plan transform = padded && modes ? fftw_plan_dft_r2c_2d(py, px, padded, modes, FFTW_ESTIMATE) : NULL;
    fft_planner_unlock();
    if (!transform) {
        fftw_free(padded);
        fftw_free(own_modes);
        return im_fail(IM_ENOMEM, "solver plan %d x %d: kernel transform", nx, ny);
    }
    /* K on the grid's offsets is the padded grid's first nx x ny block (and the kernel table where the
     * plan keeps one); the wrapped offsets beyond it repeat it, and only offsets nx or ny are new. */
#pragma omp parallel for schedule(static)
    for (int iy = 0; iy < ny; ++iy) {
        for (int ix = 0; ix < nx; ++ix)
            padded[(size_t)iy * px + ix] = im_influence_square(ix * d, iy * d, d, e);
        if (p->kernel)
            memcpy(p->kernel + (size_t)iy * nx, padded + (size_t)iy * px, sizeof(double) * nx);
    }
#pragma omp parallel for schedule(static)
    for (int jy = 0; jy < py; ++jy) {
        long dy = wrapped_offset(jy, ny, py);
        for (int jx = jy < ny ? nx : 0; jx < px; ++jx) {
            long dx = wrapped_offset(jx, nx, px);
            padded[(size_t)jy * px + jx] = dx < nx && dy < ny ? padded[(size_t)dy * px + dx]
                                                              : im_influence_square(dx * d, dy * d, d, e);
        }
    }
    solver_execute_once(transform);
    fftw_free(padded);
    const double scale = 1.0 / ((double)px * py);
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < (size_t)py * mx; ++k)
        p->spectrum[k] = modes[k][0] * scale;
    fftw_free(own_modes);
    return p->inverse_spectrum ? compute_preconditioner(p) : IM_OK;
}

/* The tables every engine takes from a plan: K on the grid, its spectrum and the preconditioner's; a
 * convolution's padded plan on the CPU makes its spectrum alone (the periodic kernel computes all three
 * at once, and another engine may take them). */
static int allocate_tables(im_solver_plan *p, int cpu)
{
    const size_t n = (size_t)p->nx * p->ny, modes = (size_t)p->py * (p->px / 2 + 1);
    const int all = !(p->convolution_only && cpu && !p->options.periodic);
    p->spectrum = fftw_malloc(sizeof(double) * modes);
    if (all) {
        p->kernel = fftw_malloc(sizeof(double) * n);
        p->inverse_spectrum = fftw_malloc(sizeof(double) * (size_t)p->ny * (p->nx / 2 + 1));
    }
    if (!p->spectrum || (all && (!p->kernel || !p->inverse_spectrum)))
        return im_fail(IM_ENOMEM, "solver plan %d x %d: kernel tables", p->nx, p->ny);
    return IM_OK;
}

/* A convolution's arrays: the padded rows, in and out, and the padded modes. */
static int allocate_convolution_arrays(im_solver_plan *p, const char *what)
{
    size_t rows = (size_t)p->px * p->ny, modes = (size_t)p->py * (p->px / 2 + 1);
    p->rows_in = p->rows_out = fftw_malloc(sizeof(double) * rows);
    p->modes = fftw_malloc(sizeof(fftw_complex) * modes);
    if (!p->rows_in || !p->modes)
        return im_fail(IM_ENOMEM, "%s: convolution arrays: allocation failed", what);
    return IM_OK;
}

/* The CPU engine's work arrays (engine_cpu.c), checked against the memory left first. */
static int allocate_cpu_arrays(im_solver_plan *p)
{
    char what[64];
    snprintf(what, sizeof what, "solver plan %d x %d", p->nx, p->ny);
    const double bytes = p->convolution_only ? convolution_array_bytes(p->nx, p->ny) : cpu_array_bytes(p->nx, p->ny);
    int status = im_memory_check(bytes, what);
    if (status != IM_OK || p->convolution_only)
        return status == IM_OK ? allocate_convolution_arrays(p, what) : status;
    size_t n = (size_t)p->nx * p->ny, rows = (size_t)p->px * p->ny, modes = (size_t)p->py * (p->px / 2 + 1);
    p->direction = fftw_malloc(sizeof(double) * n);
    p->gap = fftw_malloc(sizeof(double) * n);
    p->changed = malloc(sizeof(long) * n);
    p->changed_value = malloc(sizeof(double) * n);
    p->preconditioned = fftw_malloc(sizeof(double) * n);
    p->precondition_modes = fftw_malloc(sizeof(fftw_complex) * (size_t)p->ny * (p->nx / 2 + 1));
    p->rows_in = fftw_malloc(sizeof(double) * rows);
    p->rows_out = fftw_malloc(sizeof(double) * rows);
    p->modes = fftw_malloc(sizeof(fftw_complex) * modes);
    if (!p->direction || !p->gap || !p->changed || !p->changed_value || !p->preconditioned ||
        !p->precondition_modes || !p->rows_in || !p->rows_out || !p->modes)
        return im_fail(IM_ENOMEM, "%s: CPU engine arrays: allocation failed", what);
    memset(p->direction, 0, sizeof(double) * n);
    return IM_OK;
}

/* The CPU engine's arrays and FFTW plans, for a plan that stays on the CPU. */
static int make_cpu_engine(im_solver_plan *p)
{
    int status = allocate_cpu_arrays(p);
    if (status == IM_OK)
        status = make_fft_plans(p);
    if (status == IM_OK) /* after planning, which may scribble on the arrays: the zeros the pruning relies on */
        memset(p->rows_in, 0, sizeof(double) * (size_t)p->px * p->ny);
    return status;
}

/* A GPU plan's host side after its tables went to the device: K(0) alone (pk.c's Winkler start and
 * step length), as the MPI plan keeps it; the device holds the rest. */
static int keep_host_k0(im_solver_plan *p)
{
    double *k0 = fftw_malloc(sizeof(double));
    if (!k0)
        return im_fail(IM_ENOMEM, "solver plan %d x %d", p->nx, p->ny);
    *k0 = p->kernel[0];
    fftw_free(p->kernel);
    fftw_free(p->spectrum);
    fftw_free(p->inverse_spectrum);
    p->kernel = k0;
    p->spectrum = p->inverse_spectrum = NULL;
    return IM_OK;
}

/* A convolution's plan on the CPU after its spectrum is made: the kernel table (direct sums) and the
 * preconditioner's spectrum that another engine might have taken are not read. */
static void drop_solver_tables(im_solver_plan *p)
{
    fftw_free(p->kernel);
    fftw_free(p->inverse_spectrum);
    p->kernel = p->inverse_spectrum = NULL;
}

/* The host side of a plan whose tables were computed on temporaries: the CPU engine's arrays (a
 * convolution's made only once its other tables are freed, so that its peak is either, not both), or
 * K(0) alone beside another engine. */
static int finish_engine(im_solver_plan *p)
{
    if (p->engine != &solver_engine_cpu)
        return keep_host_k0(p);
    if (p->convolution_only)
        drop_solver_tables(p);
    return make_cpu_engine(p);
}

int im_device_parse(const char *word, int *device)
{
    ARG_REQUIRE(word, "word");
    ARG_REQUIRE(device, "device");
    static const char *const names[] = {[IM_DEVICE_CPU] = "cpu", [IM_DEVICE_GPU] = "gpu", [IM_DEVICE_AUTO] = "auto"};
    for (int k = 0; k < 3; ++k)
        if (word && strcmp(word, names[k]) == 0) {
            *device = k;
            return IM_OK;
        }
    return im_fail(IM_EINVAL, "device '%s': expected cpu, gpu or auto", word ? word : "(null)");
}

const char *im_solver_plan_device(const im_solver_plan *p)
{
    ARG_REQUIRE_OR(p, "plan", NULL);
#if IM_HAVE_GPU
    if (p->gpu)
        return solver_engine_gpu_device(p);
#endif
    return p->engine->name; /* "cpu", or "mpi" for a distributed solver's plan */
}

/* Whether a plan is on the CPU engine whatever opens: it asks for the CPU, or its finer level is there. */
static int cpu_only(const im_solver_plan *p, const im_solver_plan *finer)
{
    return p->options.device == IM_DEVICE_CPU || (finer && finer->engine == &solver_engine_cpu);
}

/* Moves the plan onto the GPU engine when its options ask for it (auto: when a hardware GPU opens;
 * otherwise it stays on the CPU, silently, as documented). */
static int choose_engine(im_solver_plan *p, const im_solver_plan *finer)
{
    if (cpu_only(p, finer))
        return IM_OK;
#if IM_HAVE_GPU
    int status = solver_engine_gpu_attach(p, finer);
    /* a cascade level VkFFT cannot transform or the device cannot hold is solved on the CPU (a quarter
     * of the finer level's size) */
    if (gpu_declined(status) && (finer || p->options.device == IM_DEVICE_AUTO))
        return IM_OK;
    return status;
#else
    if (p->options.device == IM_DEVICE_AUTO)
        return IM_OK;
    return no_gpu_engine();
#endif
}

void solver_plan_options(im_solver_options *o)
{
    if (o->hardness > 0)
        o->cascade = o->precondition = 0;
}

/* A solver plan's level, or (convolution_only) a convolution's plan. */
static int create_plan(int nx, int ny, double delta, const im_solver_options *options, const im_solver_plan *finer,
                       int convolution_only, im_solver_plan **out)
{
    *out = NULL;
    im_solver_options o = options ? *options : im_solver_options_default();
    int status = im_solver_options_check(&o);
    if (status != IM_OK)
        return status;
    if (o.adhesion_work > 0)
        return im_fail(IM_EINVAL,
                       "adhesion work = %g: adhesion acts in an indentation (im_indentation_create); a "
                       "solver plan solves the repulsive problem (expected adhesion_work = 0)",
                       o.adhesion_work);
    if (nx < 1 || ny < 1 || nx > IM_FIELD_MAX_SIDE || ny > IM_FIELD_MAX_SIDE)
        return im_fail(IM_EINVAL, "solver grid %d x %d: expected sides in [1, %d]", nx, ny, IM_FIELD_MAX_SIDE);
    if (!(isfinite(delta) && delta > 0))
        return im_fail(IM_EINVAL, "delta = %g: expected a finite patch side > 0", delta);
    char what[64];
    snprintf(what, sizeof what, "solver plan %d x %d", nx, ny);
    if ((status = im_memory_check(planning_bytes(nx, ny, &o, convolution_only), what)) != IM_OK)
        return status;
    im_solver_plan *p = calloc(1, sizeof *p);
    if (!p)
        return im_fail(IM_ENOMEM, "%s", what);
    solver_plan_options(&o);
    /* periodic: the circular convolution on the grid itself */
    const int pad = o.periodic ? 1 : 2;
    *p = (im_solver_plan){.engine = &solver_engine_cpu,
                          .nx = nx,
                          .ny = ny,
                          .px = pad * nx,
                          .py = pad * ny,
                          .delta = delta,
                          .options = o,
                          .convolution_only = convolution_only,
                          .cascade_level = finer ? finer->cascade_level + 1 : 0};
    double start = omp_get_wtime();
    /* A CPU solver plan makes its FFTW plans first, as before the GPU engine: its tables then come from
     * the same wisdom whenever it was read. Other plans compute the tables on temporaries, for the device,
     * and so does a convolution's (FFTW_ESTIMATE, no wisdom of its own; finish_engine). */
    const int cpu = cpu_only(p, finer), arrays_first = cpu && !convolution_only;
    status = allocate_tables(p, cpu);
    if (status == IM_OK && arrays_first)
        status = make_cpu_engine(p);
    if (status == IM_OK)
        status = o.periodic ? solver_periodic_kernel(p) : compute_kernel(p);
    /* Direct summation costs ~nx ny multiply-adds per changed patch, a convolution ~c px py log2(px py)
     * (px py = 4 nx ny padded, nx ny periodic): the crossover is 1.5 px py / (nx ny) log2(px py) patches.
     * Measured at 375 x 378, one thread: 0.035 ms per patch against 4.4 ms per padded convolution, a
     * crossover near 125 patches; on periodic cells of 256^2-1024^2, 27-55 patches (docs/benchmarks.md,
     * "Per-iteration cost against the FFT floor"), where the padded rule's 108-132 cost up to 12% of a
     * periodic solve's time in direct sums. */
    const double transformed = (double)p->px * p->py;
    p->direct_limit = (long)(1.5 * transformed / ((double)nx * ny) * log2(transformed));
    if (status == IM_OK && !cpu)
        status = choose_engine(p, finer);
    /* on the CPU (a convolution's plan, auto without a GPU, or a level VkFFT cannot transform), or K(0)
     * beside the device */
    if (status == IM_OK && !arrays_first)
        status = finish_engine(p);
    p->options.wisdom_path = NULL; /* not owned: used while planning only */
    if (status == IM_OK)
        status = solver_cascade_create(p);
    if (status != IM_OK) {
        im_solver_plan_free(p);
        return status;
    }
    p->plan_seconds = omp_get_wtime() - start;
    *out = p;
    return IM_OK;
}

int solver_plan_create_level(int nx, int ny, double delta, const im_solver_options *options,
                             const im_solver_plan *finer, im_solver_plan **out)
{
    return create_plan(nx, ny, delta, options, finer, 0, out);
}

int solver_convolution_plan_create(int nx, int ny, double delta, const im_solver_options *options,
                                   im_solver_plan **out)
{
    return create_plan(nx, ny, delta, options, NULL, 1, out);
}

int im_solver_plan_create(int nx, int ny, double delta, const im_solver_options *options, im_solver_plan **out)
{
    ARG_REQUIRE(out, "out");
    ARG_SIDES(nx, ny);
    return solver_plan_create_level(nx, ny, delta, options, NULL, out);
}

void im_solver_plan_free(im_solver_plan *p)
{
    if (!p)
        return;
    if (p->engine)
        p->engine->free(p);
    fftw_plan plans[6] = {p->rows_forward,  p->columns_forward,      p->columns_backward,
                          p->rows_backward, p->precondition_forward, p->precondition_backward};
    fft_planner_lock();
    for (int i = 0; i < 6; ++i)
        if (plans[i])
            fftw_destroy_plan(plans[i]);
    fft_planner_unlock();
    fftw_free(p->kernel);
    fftw_free(p->direction);
    fftw_free(p->gap);
    free(p->changed);
    free(p->changed_value);
    fftw_free(p->spectrum);
    fftw_free(p->inverse_spectrum);
    fftw_free(p->preconditioned);
    fftw_free(p->precondition_modes);
    if (p->rows_out != p->rows_in) /* a convolution's plan has one array for both */
        fftw_free(p->rows_out);
    fftw_free(p->rows_in);
    fftw_free(p->modes);
    solver_cascade_free(p);
    free(p);
}

double im_solver_plan_seconds(const im_solver_plan *p)
{
    ARG_REQUIRE_OR(p, "plan", NAN);
    return p->plan_seconds;
}

int im_solver_plan_measured(const im_solver_plan *p)
{
    ARG_REQUIRE_OR(p, "plan", 0);
    return p->measured;
}

void solver_multiply_modes(fftw_complex *modes, const double *spectrum, size_t count)
{
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < count; ++k) {
        modes[k][0] *= spectrum[k];
        modes[k][1] *= spectrum[k];
    }
}

static _Atomic long pairs_run[SOLVER_PAIR_KINDS];
static _Atomic long long coarse_points_run;
static _Atomic int last_top_grid[4];

void solver_count_pair(const im_solver_plan *plan, enum solver_pair_kind kind)
{
    atomic_fetch_add_explicit(&pairs_run[plan->cascade_level ? SOLVER_PAIR_COARSE : kind], 1, memory_order_relaxed);
    if (plan->cascade_level) {
        const long long points = kind == SOLVER_PAIR_K ? (long long)plan->px * plan->py
                                                       : (long long)plan->nx * plan->ny;
        atomic_fetch_add_explicit(&coarse_points_run, points, memory_order_relaxed);
    }
    if (plan->cascade_level || kind != SOLVER_PAIR_K)
        return;
    const int grid[4] = {plan->px, plan->py, plan->nx, plan->ny};
    for (int k = 0; k < 4; ++k)
        atomic_store_explicit(&last_top_grid[k], grid[k], memory_order_relaxed);
}

void solver_last_top_grid(int *px, int *py, int *nx, int *ny)
{
    int *out[4] = {px, py, nx, ny};
    for (int k = 0; k < 4; ++k)
        *out[k] = atomic_load_explicit(&last_top_grid[k], memory_order_relaxed);
}

long solver_pairs_run(enum solver_pair_kind kind)
{
    return atomic_load_explicit(&pairs_run[kind], memory_order_relaxed);
}

long long solver_coarse_points_run(void) { return atomic_load_explicit(&coarse_points_run, memory_order_relaxed); }

void solver_convolve_rows(im_solver_plan *p)
{
    const size_t mx = p->px / 2 + 1, count = (size_t)p->py * mx;
    solver_count_pair(p, SOLVER_PAIR_K);
    fftw_execute(p->rows_forward);
#pragma omp parallel for schedule(static)
    for (int iy = p->ny; iy < p->py; ++iy) /* the zero rows of the padding, overwritten last time */
        memset(p->modes + (size_t)iy * mx, 0, sizeof(fftw_complex) * mx);
    fftw_execute(p->columns_forward);
    solver_multiply_modes(p->modes, p->spectrum, count);
    fftw_execute(p->columns_backward);
    fftw_execute(p->rows_backward);
}

void im_solver_convolve(im_solver_plan *p, const double *pressure, double *displacement)
{
    ARG_REQUIRE_OR(p, "plan", );
    ARG_REQUIRE_OR(pressure, "pressure", );
    ARG_REQUIRE_OR(displacement, "displacement", );
    p->engine->convolve_arrays(p, pressure, displacement);
}

void solver_add_point_loads(const im_solver_plan *p, const long *index, const double *value, long count,
                            double *displacement)
{
    const int nx = p->nx, ny = p->ny;
#pragma omp parallel for schedule(static)
    for (int iy = 0; iy < ny; ++iy) {
        double *row = displacement + (size_t)iy * nx;
        for (long k = 0; k < count; ++k) {
            int kx = (int)(index[k] % nx), ky = (int)(index[k] / nx);
            const double *krow = p->kernel + (size_t)abs(iy - ky) * nx;
            const double v = value[k];
            for (int ix = 0; ix < kx; ++ix) /* left of the load: offset kx - ix */
                row[ix] += v * krow[kx - ix];
            for (int ix = kx; ix < nx; ++ix)
                row[ix] += v * krow[ix - kx];
        }
    }
}
