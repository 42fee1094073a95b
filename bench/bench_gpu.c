/* Benchmark of the GPU engine against the CPU engine (not a test).
 *
 *   bench_gpu [--cone 1024,2048,4096] [--periodic 1024,2048,4096,8192] [--history] [--repeats R]
 *             [--cpu-limit N] [--floor-limit N] [--counts 256,512]
 *
 * 1. Cold rough-cone solves on the whole n x n grid (no window crop: the padded transform is 2n x 2n):
 *    H 0.8, lambda_s 4, lambda_r n, h'rms 0.08, seed 1, an 80 deg cone on the centre to the approach
 *    whose smooth contact radius is n/5, displacement control, tol 1e-6 (the standard preset), from
 *    zero pressure (cascade start and preconditioner, as a first step of a history). Per engine: plan
 *    time, then the median of R solves' wall time, fine and coarse iterations, convolutions, wall time
 *    per fine iteration over the time of one VkFFT R2C + C2R pair of the padded grid on the same
 *    device (the GPU's floor), and the relative load difference and differing contact patches
 *    between the engines. The CPU engine runs with all OpenMP threads, up to n = --cpu-limit (2048).
 * 2. Periodic flat contact (im_flat_contact) of the same surfaces at mean pressure 0.004 E*
 *    (about 10% contact), plain PK as the periodic mode has it: the solve's time and the process's
 *    peak resident memory so far, then per-iteration time and its ratio to the unpadded pair (for
 *    n up to --floor-limit: the largest grids skip its planning and buffers).
 * 3. --history: the paper's 25-step history (512^2, approaches up to 31.5, window crop) on both.
 * 4. --counts: what does not depend on the device's speed, on the GPU engine alone: for a periodic
 *    cell under load (mean pressure 0.004 E*) and under the approach that load found, and for the cone
 *    of 1. under displacement and under the load that found, each solve's fine and coarse iterations,
 *    its submissions (the host's fence waits) in all and per fine iteration, and a hash of its
 *    pressures (FNV-1a of their bytes: equal hashes, bit-identical answers). Sections 1 and 2 print
 *    the submissions per fine iteration beside their times.
 * Prints the devices (Vulkan device name, threads) first. Figures go to docs/benchmarks.md.
 */
#include "bench_common.h"
#include "indentmap/gpu_config.h"
#include "indentmap/indenter.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>

#if IM_HAVE_GPU
#include "gpu/vulkan.h"
#include "solver/engine.h"
#include "solver/flat.h"

#define MAX_SIZES 8
#define MAX_REPEATS 9

static void die(int status, const char *what)
{
    fprintf(stderr, "bench_gpu: %s: %s (%s)\n", what, im_last_error(), im_strstatus(status));
    exit(1);
}

static int parse_sizes(const char *text, int *sizes)
{
    int count = 0;
    for (const char *c = text; *c && count < MAX_SIZES; ++count) {
        sizes[count] = atoi(c);
        const char *comma = strchr(c, ',');
        if (!comma)
            return count + 1;
        c = comma + 1;
    }
    return count;
}

static im_field *paper_surface(int n)
{
    im_surface_params p = im_surface_params_default();
    p.nx = p.ny = n;
    p.lambda_r = n;
    p.slope_rms = 0.08;
    p.seed = 1;
    im_field *s = NULL;
    int status = im_surface_generate(&p, &s);
    if (status != IM_OK)
        die(status, "surface");
    return s;
}

/* g0 = z(r) - h - min(z - h) for the cone on the centre of patch (n/2, n/2). */
static double *cone_gap(const im_field *s)
{
    im_indenter cone = im_indenter_cone(80);
    const size_t count = (size_t)s->nx * s->ny;
    double *g0 = malloc(sizeof(double) * count), lowest = INFINITY;
    for (int iy = 0; iy < s->ny; ++iy)
        for (int ix = 0; ix < s->nx; ++ix) {
            size_t i = (size_t)iy * s->nx + ix;
            g0[i] = im_indenter_height(&cone, (ix - s->nx / 2) * s->delta, (iy - s->ny / 2) * s->delta) - s->data[i];
            lowest = fmin(lowest, g0[i]);
        }
    for (size_t i = 0; i < count; ++i)
        g0[i] -= lowest;
    return g0;
}

/* Seconds per VkFFT R2C + C2R pair of px x py (median of 9 batches of 10 pairs). */
static double vkfft_pair_seconds(int px, int py)
{
    gpu_context *c = NULL;
    gpu_buffer real = {0}, modes = {0}, scratch = {0}; /* scratch: VkFFT's, in parts as the engine gives it */
    gpu_fft *fft = NULL;
    int status = gpu_context_open(GPU_ANY, 0, &c);
    if (status == IM_OK)
        status = gpu_buffer_create(c, gpu_fft_modes_bytes(px, py), 0, &real);
    if (status == IM_OK)
        status = gpu_buffer_create(c, gpu_fft_modes_bytes(px, py), 0, &modes);
    if (status == IM_OK)
        status = gpu_buffer_create(c, gpu_fft_modes_bytes(px, py), 0, &scratch);
    if (status == IM_OK)
        status = gpu_fft_create(c, px, py, &real, &modes, &scratch, &fft);
    if (status != IM_OK)
        die(status, "VkFFT floor");
    double batches[9];
    for (int b = -1; b < 9; ++b) { /* the first batch warms up */
        double start = bench_now();
        gpu_begin(c);
        for (int k = 0; k < 10; ++k) {
            gpu_fft_forward(c, fft);
            gpu_fft_inverse(c, fft);
        }
        if ((status = gpu_submit_wait(c)) != IM_OK)
            die(status, "VkFFT floor");
        if (b >= 0)
            batches[b] = (bench_now() - start) / 10;
    }
    gpu_fft_free(fft);
    gpu_buffer_free(c, &real);
    gpu_buffer_free(c, &modes);
    gpu_buffer_free(c, &scratch);
    gpu_context_close(c);
    return bench_median(batches, 9);
}

typedef struct cold_result {
    double plan_seconds, seconds, load;
    int iterations, coarse_iterations, convolutions;
    long submissions; /* the last solve's (GPU), -1 on the CPU */
    double *pressure;
} cold_result;

static cold_result cold_solves(int n, const double *g0, double approach, int device, int repeats)
{
    im_solver_options o = im_solver_options_default();
    o.device = device;
    im_solver_plan *plan = NULL;
    double start = bench_now();
    int status = im_solver_plan_create(n, n, 1.0, &o, &plan);
    if (status != IM_OK)
        die(status, "plan");
    cold_result r = {.plan_seconds = bench_now() - start};
    const size_t count = (size_t)n * n;
    double *u = malloc(sizeof(double) * count), times[MAX_REPEATS];
    r.pressure = malloc(sizeof(double) * count);
    for (int k = 0; k < repeats; ++k) {
        memset(r.pressure, 0, sizeof(double) * count);
        im_solve_result s;
        const long submitted = solver_engine_gpu_submissions(plan);
        if ((status = im_solver_solve(plan, g0, IM_CONTROL_DISPLACEMENT, approach, r.pressure, u, &s)) != IM_OK)
            die(status, "cold solve");
        times[k] = s.seconds;
        r = (cold_result){.plan_seconds = r.plan_seconds,
                          .load = s.load,
                          .iterations = s.iterations,
                          .coarse_iterations = s.coarse_iterations,
                          .convolutions = s.convolutions,
                          .submissions = submitted < 0 ? -1 : solver_engine_gpu_submissions(plan) - submitted,
                          .pressure = r.pressure};
    }
    r.seconds = bench_median(times, repeats);
    free(u);
    im_solver_plan_free(plan);
    return r;
}

static long contact_differences(const double *a, const double *b, size_t count)
{
    long differ = 0;
    for (size_t i = 0; i < count; ++i)
        differ += (a[i] > 0) != (b[i] > 0);
    return differ;
}

static void bench_cone(int n, int repeats, int cpu_limit)
{
    im_field *s = paper_surface(n);
    double *g0 = cone_gap(s);
    const double approach = M_PI * n / (10 * tan(80 * M_PI / 180));
    cold_result gpu = cold_solves(n, g0, approach, IM_DEVICE_GPU, repeats);
    double pair = vkfft_pair_seconds(2 * n, 2 * n);
    printf("cone %5d^2 gpu: plan %.3f s, solve %.4f s (median of %d), %d fine + %d coarse iterations, %d "
           "convolutions, %ld submissions (%.2f per fine iteration), %.3f ms per fine iteration = %.2f VkFFT "
           "pairs of %d^2 (%.3f ms), N = %.10g\n",
           n, gpu.plan_seconds, gpu.seconds, repeats, gpu.iterations, gpu.coarse_iterations, gpu.convolutions,
           gpu.submissions, (double)gpu.submissions / gpu.iterations, 1e3 * gpu.seconds / gpu.iterations,
           gpu.seconds / gpu.iterations / pair, 2 * n, 1e3 * pair, gpu.load);
    if (n <= cpu_limit) {
        cold_result cpu = cold_solves(n, g0, approach, IM_DEVICE_CPU, repeats);
        printf("cone %5d^2 cpu: plan %.3f s, solve %.4f s (median of %d, %d threads), %d fine + %d coarse "
               "iterations; gpu speed-up %.2fx; |dN|/N = %.2e, contact patches differing: %ld\n",
               n, cpu.plan_seconds, cpu.seconds, repeats, omp_get_max_threads(), cpu.iterations,
               cpu.coarse_iterations, cpu.seconds / gpu.seconds, fabs(cpu.load - gpu.load) / cpu.load,
               contact_differences(cpu.pressure, gpu.pressure, (size_t)n * n));
        free(cpu.pressure);
    }
    fflush(stdout);
    free(gpu.pressure);
    free(g0);
    im_field_free(s);
}

/* Prints the plan's seconds as soon as it is made (a 32768^2 cell's host work takes minutes: a run
 * stopped by a time limit still says how far it came). */
static void flat_solve(const im_field *s, int device, double *seconds, long *submissions, im_flat_result *out)
{
    im_solver_options o = im_solver_options_default();
    o.device = device;
    o.max_iterations = 5000; /* plain PK on large periodic grids: report what is left rather than wait */
    im_flat_contact *run = NULL;
    double start = bench_now();
    int status = im_flat_contact_create(s, &o, &run);
    if (status != IM_OK)
        die(status, "flat contact");
    printf("periodic %5d^2 %s: plan %.1f s\n", s->nx, device == IM_DEVICE_GPU ? "gpu" : "cpu", bench_now() - start);
    fflush(stdout);
    const long submitted = solver_engine_gpu_submissions(flat_contact_plan(run));
    start = bench_now();
    status = im_flat_contact_solve(run, 0.004, out);
    *seconds = bench_now() - start;
    *submissions = solver_engine_gpu_submissions(flat_contact_plan(run)) - submitted;
    if (status != IM_OK && status != IM_ENOCONV)
        die(status, "flat solve");
    im_flat_contact_free(run);
}

/* The process's peak resident memory so far, GiB (on lavapipe the device's memory is the host's too). */
static double peak_rss_gib(void)
{
    struct rusage usage;
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss / 1048576.0; /* KiB */
}

static void bench_periodic(int n, int cpu_limit, int floor_limit)
{
    const double start = bench_now();
    im_field *s = paper_surface(n);
    printf("periodic %5d^2: surface %.1f s\n", n, bench_now() - start);
    im_flat_result gpu, cpu;
    double gpu_seconds, cpu_seconds;
    long submissions, cpu_submissions;
    flat_solve(s, IM_DEVICE_GPU, &gpu_seconds, &submissions, &gpu);
    printf("periodic %5d^2 gpu: %.3f s, %d iterations (residual %.2g), %ld submissions (%.2f per fine "
           "iteration), contact %.4f, host peak RSS %.2f GiB\n",
           n, gpu_seconds, gpu.iterations, gpu.residual, submissions, (double)submissions / gpu.iterations,
           gpu.area_fraction, peak_rss_gib());
    fflush(stdout);
    const double pair = n <= floor_limit ? vkfft_pair_seconds(n, n) : NAN;
    printf("periodic %5d^2 gpu: %.3f ms per iteration = %.2f VkFFT pairs of %d^2 (%.3f ms)\n", n,
           1e3 * gpu_seconds / gpu.iterations, gpu_seconds / gpu.iterations / pair, n, 1e3 * pair);
    if (n <= cpu_limit) {
        flat_solve(s, IM_DEVICE_CPU, &cpu_seconds, &cpu_submissions, &cpu);
        printf("periodic %5d^2 cpu: %.3f s (%d threads), %d iterations; gpu speed-up %.2fx; |dw|/w = %.2e, "
               "contact patches %ld vs %ld\n",
               n, cpu_seconds, omp_get_max_threads(), cpu.iterations, cpu_seconds / gpu_seconds,
               fabs(cpu.approach - gpu.approach) / fabs(cpu.approach), cpu.contact_patches, gpu.contact_patches);
    }
    fflush(stdout);
    im_field_free(s);
}

/* The paper's history (bench_solver's configuration): 25 approaches up to 31.5 on 512^2. */
static double history_seconds(int device, int *iterations)
{
    im_field *s = paper_surface(512);
    im_indenter cone = im_indenter_cone(80);
    im_solver_options o = im_solver_options_default();
    o.device = device;
    im_indentation *run = NULL;
    int status = im_indentation_create(s, &cone, IM_CONTROL_DISPLACEMENT, 31.5, &o, &run);
    if (status != IM_OK)
        die(status, "history");
    double start = bench_now();
    *iterations = 0;
    for (int k = 1; k <= 25; ++k) {
        im_step_result r;
        if ((status = im_indentation_step(run, 31.5 * k / 25, &r)) != IM_OK)
            die(status, "history step");
        *iterations += r.iterations;
    }
    double seconds = bench_now() - start;
    im_indentation_free(run);
    im_field_free(s);
    return seconds;
}

static void bench_history(void)
{
    int gpu_iterations, cpu_iterations;
    double gpu = history_seconds(IM_DEVICE_GPU, &gpu_iterations),
           cpu = history_seconds(IM_DEVICE_CPU, &cpu_iterations);
    printf("paper history 512^2, 25 steps: gpu %.3f s (%d iterations), cpu %.3f s (%d iterations, %d threads): "
           "gpu speed-up %.2fx\n",
           gpu, gpu_iterations, cpu, cpu_iterations, omp_get_max_threads(), cpu / gpu);
}

/* One cold GPU solve on plan, its counts printed under name; returns its result. */
static im_solve_result counted_solve(const char *name, int n, im_solver_plan *plan, const double *g0,
                                     enum im_control control, double target)
{
    const size_t count = (size_t)n * n;
    double *p = calloc(count, sizeof(double)), *u = malloc(sizeof(double) * count);
    im_solve_result r;
    const long submitted = solver_engine_gpu_submissions(plan);
    int status = im_solver_solve(plan, g0, control, target, p, u, &r);
    if (status != IM_OK)
        die(status, name);
    const long submissions = solver_engine_gpu_submissions(plan) - submitted;
    printf("counts %5d^2 %-22s %3d fine + %4d coarse iterations, %4d convolutions, %5ld submissions: %.2f per "
           "fine iteration, %.2f per iteration of all levels; pressures' hash %016llx\n",
           n, name, r.iterations, r.coarse_iterations, r.convolutions, submissions,
           (double)submissions / r.iterations, (double)submissions / (r.iterations + r.coarse_iterations),
           bench_bits_hash(p, count));
    fflush(stdout);
    free(p);
    free(u);
    return r;
}

static im_solver_plan *gpu_plan(int n, int periodic)
{
    im_solver_options o = im_solver_options_default();
    o.device = IM_DEVICE_GPU;
    o.periodic = periodic;
    im_solver_plan *plan = NULL;
    int status = im_solver_plan_create(n, n, 1.0, &o, &plan);
    if (status != IM_OK)
        die(status, "plan");
    return plan;
}

/* 4. the counts of a periodic cell and of the cone, under both controls */
static void bench_counts(int n)
{
    im_field *s = paper_surface(n);
    const size_t count = (size_t)n * n;
    double *g0 = malloc(sizeof(double) * count), highest = -INFINITY;
    for (size_t i = 0; i < count; ++i)
        highest = fmax(highest, s->data[i]);
    for (size_t i = 0; i < count; ++i)
        g0[i] = highest - s->data[i];
    im_solver_plan *plan = gpu_plan(n, 1);
    im_solve_result r = counted_solve("periodic, load", n, plan, g0, IM_CONTROL_LOAD, 0.004 * (double)count);
    counted_solve("periodic, approach", n, plan, g0, IM_CONTROL_DISPLACEMENT, r.approach);
    im_solver_plan_free(plan);
    free(g0);
    g0 = cone_gap(s);
    plan = gpu_plan(n, 0);
    r = counted_solve("cone, approach", n, plan, g0, IM_CONTROL_DISPLACEMENT, M_PI * n / (10 * tan(80 * M_PI / 180)));
    counted_solve("cone, load", n, plan, g0, IM_CONTROL_LOAD, r.load);
    im_solver_plan_free(plan);
    free(g0);
    im_field_free(s);
}

int main(int argc, char **argv)
{
    int cones[MAX_SIZES] = {1024, 2048, 4096}, periodic[MAX_SIZES] = {1024, 2048, 4096};
    int counts[MAX_SIZES];
    int cone_count = 3, periodic_count = 3, repeats = 3, history = 0, cpu_limit = 2048, floor_limit = 1 << 30;
    int count_count = 0;
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--cone") == 0 && i + 1 < argc)
            cone_count = parse_sizes(argv[++i], cones);
        else if (strcmp(argv[i], "--periodic") == 0 && i + 1 < argc)
            periodic_count = parse_sizes(argv[++i], periodic);
        else if (strcmp(argv[i], "--repeats") == 0 && i + 1 < argc)
            repeats = atoi(argv[++i]);
        else if (strcmp(argv[i], "--cpu-limit") == 0 && i + 1 < argc)
            cpu_limit = atoi(argv[++i]);
        else if (strcmp(argv[i], "--floor-limit") == 0 && i + 1 < argc)
            floor_limit = atoi(argv[++i]);
        else if (strcmp(argv[i], "--counts") == 0 && i + 1 < argc)
            count_count = parse_sizes(argv[++i], counts);
        else if (strcmp(argv[i], "--history") == 0)
            history = 1;
        else {
            fprintf(stderr, "usage: bench_gpu [--cone LIST] [--periodic LIST] [--history] [--repeats R] "
                            "[--cpu-limit N] [--floor-limit N] [--counts LIST]\n");
            return 2;
        }
    }
    repeats = repeats < 1 ? 1 : (repeats > MAX_REPEATS ? MAX_REPEATS : repeats);
    char devices[4096];
    if (gpu_devices_describe(devices, sizeof devices) == IM_OK)
        printf("Vulkan devices:\n%s", devices);
    printf("OpenMP threads: %d\n", omp_get_max_threads());
    fflush(stdout);
    for (int k = 0; k < cone_count; ++k)
        bench_cone(cones[k], repeats, cpu_limit);
    for (int k = 0; k < periodic_count; ++k)
        bench_periodic(periodic[k], cpu_limit / 2, floor_limit);
    if (history)
        bench_history();
    for (int k = 0; k < count_count; ++k)
        bench_counts(counts[k]);
    printf("peak host memory: %.0f MiB\n", bench_peak_rss_mib());
    return 0;
}
#else
int main(void)
{
    fprintf(stderr, "bench_gpu: built without IM_GPU\n");
    return 2;
}
#endif
