/* Benchmark of the contact solver (not a test).
 *
 *   bench_solver [--repeats R] [--steps S] [--threads 1|2] [--no-extras] [--measure] [--plain] [--big]
 *
 * 1. The paper's configuration: 512 x 512, H = 0.8, lambda_s = 4, lambda_r = 512, h'rms = 0.08,
 *    seed 1, alpha = 80 deg, S (default 25) approaches up to w = 31.5 (n_p ~ 37000), displacement
 *    control, at 1 and 2 threads: time per step, iterations per step, time per iteration over the
 *    floor (one forward + one inverse FFT of the padded window with the same FFTW flags), total
 *    time (median of R repeats, default 3), peak memory (ru_maxrss).
 *    --threads runs one thread count only; at one thread the CPU-time ratio is also printed, which
 *    other processes sharing the cores disturb less. --measure plans with FFTW_MEASURE (solver
 *    and floor alike). --plain solves with plain Polonsky-Keer steps and cold starts from the
 *    local guess (no cascade, no preconditioner: the solver before issue 15).
 * 2. The same history under load control, imposing the loads found in 1, and under load control
 *    by a secant loop on w (skipped with --no-extras, like 3).
 * 3. FFTW planning: FFTW_ESTIMATE, FFTW_MEASURE without and with wisdom, and the per-iteration
 *    time each gives.
 * 4. With --big: a smooth 4096 x 4096 surface and a cone up to n_p ~ 10^6 (6 steps).
 */
#include "core/fft_threads.h"
#include "indentmap/indenter.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <fftw3.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#define MAX_REPEATS 15
#define MAX_STEPS 100

static void die(int status, const char *what)
{
    fprintf(stderr, "bench_solver: %s: %s (%s)\n", what, im_last_error(), im_strstatus(status));
    exit(1);
}

/* CPU time of the whole process: at one thread it is immune to other processes sharing the cores. */
static double cpu_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static double peak_memory_mib(void)
{
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return u.ru_maxrss / 1024.0;
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, n, sizeof *v, compare_doubles);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* Median time of one forward r2c + one inverse c2r transform of a px x py grid (wall time, or
 * CPU time when cpu is set). */
static double fft_pair_seconds(int px, int py, unsigned flags, int cpu)
{
    double *real = fftw_malloc(sizeof(double) * px * py);
    fftw_complex *modes = fftw_malloc(sizeof(fftw_complex) * py * (px / 2 + 1));
    fft_prepare_planner();
    fftw_plan f = fftw_plan_dft_r2c_2d(py, px, real, modes, flags);
    fftw_plan b = fftw_plan_dft_c2r_2d(py, px, modes, real, flags);
    for (int i = 0; i < px * py; ++i)
        real[i] = (i % 7) * 0.1;
    double t[9];
    for (int r = 0; r < 9; ++r) {
        double start = cpu ? cpu_seconds() : omp_get_wtime();
        for (int k = 0; k < 4; ++k) {
            fftw_execute(f);
            fftw_execute(b);
        }
        t[r] = ((cpu ? cpu_seconds() : omp_get_wtime()) - start) / 4;
    }
    fftw_destroy_plan(f);
    fftw_destroy_plan(b);
    fftw_free(real);
    fftw_free(modes);
    return median(t, 9);
}

typedef struct history_stats {
    double total_seconds, plan_seconds, seconds_per_iteration, cpu_per_iteration;
    long iterations, convolutions;
    long final_contacts;
    double loads[MAX_STEPS];
    im_window window;
} history_stats;

static history_stats run_history(const im_field *s, const im_indenter *cone, enum im_control control,
                                 const double *targets, int steps, const im_solver_options *o, int verbose)
{
    history_stats h = {0};
    im_indentation *run = NULL;
    double start = omp_get_wtime();
    int status = im_indentation_create(s, cone, control, targets[steps - 1], o, &run);
    if (status != IM_OK)
        die(status, "im_indentation_create");
    h.plan_seconds = omp_get_wtime() - start;
    h.window = im_indentation_window(run);
    double solve = 0, cpu_start = cpu_seconds();
    for (int k = 0; k < steps; ++k) {
        im_step_result r;
        status = im_indentation_step(run, targets[k], &r);
        if (status != IM_OK)
            die(status, "im_indentation_step");
        solve += r.seconds;
        h.iterations += r.iterations;
        h.convolutions += r.convolutions;
        h.loads[k] = r.load;
        h.final_contacts = r.contact_patches;
        if (verbose)
            printf("  step %2d  w %8.4f  N %12.6g  n_p %7ld  A/A0 %.4f  it %4d  conv %4d  %.3f s\n", k + 1,
                   r.approach, r.load, r.contact_patches, r.area_ratio, r.iterations, r.convolutions, r.seconds);
    }
    h.total_seconds = omp_get_wtime() - start;
    h.seconds_per_iteration = solve / h.iterations;
    h.cpu_per_iteration = (cpu_seconds() - cpu_start) / h.iterations;
    im_indentation_free(run);
    return h;
}

/* Load control by an outer secant loop on w around displacement-controlled solves (each warm-
 * started from the last), to compare with Polonsky-Keer's own load control. Stops when N is within
 * 1e-7 of the target (relative). Returns the total CG iterations. */
static long secant_history(const im_field *s, const im_indenter *cone, const double *loads, int steps,
                           double largest_approach, int *solves)
{
    im_indentation *run = NULL;
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-8; /* the tolerance these figures were measured at (the default is 1e-6) */
    int status = im_indentation_create(s, cone, IM_CONTROL_DISPLACEMENT, largest_approach, &o, &run);
    if (status != IM_OK)
        die(status, "im_indentation_create");
    long iterations = 0;
    double w_prev = 0, n_prev = 0;
    *solves = 0;
    for (int k = 0; k < steps; ++k) {
        double target = loads[k];
        double wa = w_prev, na = n_prev;
        double wb = k == 0 ? im_indenter_approach_for_load(cone, 1.0, target) : w_prev * sqrt(target / n_prev);
        for (int it = 0; it < 50; ++it) {
            im_step_result r;
            wb = fmin(wb, largest_approach);
            if ((status = im_indentation_step(run, wb, &r)) != IM_OK)
                die(status, "secant step");
            iterations += r.iterations;
            ++*solves;
            if (fabs(r.load / target - 1) <= 1e-7)
                break;
            double wc = wb + (target - r.load) * (wb - wa) / (r.load - na);
            wa = wb;
            na = r.load;
            wb = wc;
        }
        w_prev = wb;
        n_prev = target;
    }
    im_indentation_free(run);
    return iterations;
}

static int plain_solver; /* --plain */

static void paper_configuration(int repeats, int steps, int only_threads, int extras, int measure)
{
    im_surface_params p = im_surface_params_default(); /* 512^2, H 0.8, 4 / 512, h'rms 0.08, seed 1 */
    im_field *s = NULL;
    int status = im_surface_generate(&p, &s);
    if (status != IM_OK)
        die(status, "im_surface_generate");
    im_indenter cone = im_indenter_cone(80);
    double approaches[MAX_STEPS], loads[MAX_STEPS];
    for (int k = 0; k < steps; ++k)
        approaches[k] = 31.5 * (k + 1) / steps;
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-8; /* the tolerance these figures were measured at (the default is 1e-6) */
    o.fft_measure = measure;
    if (plain_solver)
        o.cascade = o.precondition = 0;
    const unsigned flags = measure ? FFTW_MEASURE : FFTW_ESTIMATE;
    printf("FFTW planning: %s (the floor uses the same)\n", measure ? "FFTW_MEASURE" : "FFTW_ESTIMATE");
    printf("== paper configuration: 512 x 512, H 0.8, lambda_s 4, lambda_r 512, h'rms 0.08, seed 1, "
           "alpha 80, %d approaches to w = 31.5, tol %g ==\n",
           steps, o.tol);
    for (int threads = 1; threads <= 2; ++threads) {
        if (only_threads && threads != only_threads)
            continue;
        omp_set_num_threads(threads);
        /* the floor is timed right after each repeat, so that both see the same machine load */
        double totals[MAX_REPEATS], per_it[MAX_REPEATS], floors[MAX_REPEATS], ratios[MAX_REPEATS];
        double cpu_ratios[MAX_REPEATS], cpu_totals[MAX_REPEATS];
        history_stats h = {0};
        for (int r = 0; r < repeats; ++r) {
            h = run_history(s, &cone, IM_CONTROL_DISPLACEMENT, approaches, steps, &o, r == 0 && threads == 1);
            totals[r] = h.total_seconds;
            per_it[r] = h.seconds_per_iteration;
            floors[r] = fft_pair_seconds(2 * h.window.nx, 2 * h.window.ny, flags, 0);
            ratios[r] = per_it[r] / floors[r];
            cpu_totals[r] = h.cpu_per_iteration * h.iterations;
            if (threads == 1)
                cpu_ratios[r] = h.cpu_per_iteration / fft_pair_seconds(2 * h.window.nx, 2 * h.window.ny, flags, 1);
        }
        memcpy(loads, h.loads, sizeof(double) * steps);
        double t_it = median(per_it, repeats), total = median(totals, repeats), floor = median(floors, repeats);
        double ratio = median(ratios, repeats);
        if (threads == 1)
            printf("  CPU time (1 thread): steps %.3f s (median), per iteration / FFT pair, median ratio %.3f\n",
                   median(cpu_totals, repeats), median(cpu_ratios, repeats));
        printf("threads %d: window %d x %d (padded %d x %d), final n_p %ld\n", threads, h.window.nx, h.window.ny,
               2 * h.window.nx, 2 * h.window.ny, h.final_contacts);
        printf("  total %.3f s (median of %d), per step %.4f s, iterations %ld (%.1f per step), "
               "convolutions per iteration %.3f\n",
               total, repeats, total / steps, h.iterations, (double)h.iterations / steps,
               (double)h.convolutions / h.iterations);
        printf("  per iteration %.3f ms, FFT pair floor %.3f ms, median ratio %.3f, peak RSS so far %.1f MiB\n",
               1e3 * t_it, 1e3 * floor, ratio, peak_memory_mib());
    }
    if (!extras) {
        im_field_free(s);
        return;
    }
    omp_set_num_threads(2);
    history_stats hl = run_history(s, &cone, IM_CONTROL_LOAD, loads, steps, &o, 0);
    history_stats hd = run_history(s, &cone, IM_CONTROL_DISPLACEMENT, approaches, steps, &o, 0);
    printf("load control (same loads, 2 threads): iterations %ld vs %ld under displacement control, "
           "time %.3f s vs %.3f s, window %d x %d\n",
           hl.iterations, hd.iterations, hl.total_seconds, hd.total_seconds, hl.window.nx, hl.window.ny);
    int solves;
    long secant = secant_history(s, &cone, loads, steps, 1.05 * approaches[steps - 1], &solves);
    printf("load control by a secant loop on w: %ld iterations in %d displacement solves\n", secant, solves);
    im_field_free(s);
}

static void planning_costs(void)
{
    omp_set_num_threads(2);
    char wisdom[] = "/tmp/bench_solver_wisdom_XXXXXX";
    int fd = mkstemp(wisdom);
    if (fd >= 0)
        close(fd);
    unlink(wisdom);
    printf("== FFTW planning, 375 x 378 window (the paper run's), 2 threads ==\n");
    const char *labels[] = {"FFTW_ESTIMATE", "FFTW_MEASURE, no wisdom", "FFTW_MEASURE, wisdom from file"};
    for (int mode = 0; mode < 3; ++mode) {
        im_solver_options o = im_solver_options_default();
        o.tol = 1e-8; /* the tolerance these figures were measured at (the default is 1e-6) */
        o.fft_measure = mode > 0;
        o.wisdom_path = mode > 0 ? wisdom : NULL;
        fftw_forget_wisdom(); /* mode 2 gets its wisdom from the file only */
        im_solver_plan *plan = NULL;
        int status = im_solver_plan_create(375, 378, 1.0, &o, &plan);
        if (status != IM_OK)
            die(status, "im_solver_plan_create");
        double *p = calloc(375 * 378, sizeof(double)), *u = calloc(375 * 378, sizeof(double)), t[7];
        for (int i = 0; i < 375 * 378; ++i)
            p[i] = (i % 5) * 0.01;
        for (int r = 0; r < 7; ++r) {
            double start = omp_get_wtime();
            for (int k = 0; k < 5; ++k)
                im_solver_convolve(plan, p, u);
            t[r] = (omp_get_wtime() - start) / 5;
        }
        printf("  %-32s plan %.3f s, convolution %.3f ms\n", labels[mode], im_solver_plan_seconds(plan),
               1e3 * median(t, 7));
        free(p);
        free(u);
        im_solver_plan_free(plan);
    }
    unlink(wisdom);
}

static void big_cone(void)
{
    omp_set_num_threads(2);
    im_field *s = NULL;
    int status = im_field_create(4096, 4096, 1.0, &s);
    if (status != IM_OK)
        die(status, "im_field_create");
    im_indenter cone = im_indenter_cone(80);
    /* n_p = pi a^2 = 1e6 at a = 564, w = a pi cot(alpha) / 2 */
    const double w_max = 564.2 * M_PI / tan(80 * M_PI / 180) / 2;
    double approaches[6];
    for (int k = 0; k < 6; ++k)
        approaches[k] = w_max * (k + 1) / 6;
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-8; /* the tolerance these figures were measured at (the default is 1e-6) */
    printf("== smooth 4096 x 4096, cone alpha 80, 6 approaches to w = %.2f, 2 threads ==\n", w_max);
    history_stats h = run_history(s, &cone, IM_CONTROL_DISPLACEMENT, approaches, 6, &o, 1);
    double floor = fft_pair_seconds(2 * h.window.nx, 2 * h.window.ny, FFTW_ESTIMATE, 0);
    printf("window %d x %d: total %.1f s (planning %.2f s), iterations %ld, per iteration %.1f ms, floor %.1f ms "
           "(ratio %.2f), final n_p %ld, peak RSS %.0f MiB\n",
           h.window.nx, h.window.ny, h.total_seconds, h.plan_seconds, h.iterations, 1e3 * h.seconds_per_iteration,
           1e3 * floor, h.seconds_per_iteration / floor, h.final_contacts, peak_memory_mib());
    im_field_free(s);
}

int main(int argc, char **argv)
{
    int repeats = 3, steps = 25, big = 0, only_threads = 0, extras = 1, measure = 0;
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--repeats") == 0 && i + 1 < argc)
            repeats = atoi(argv[++i]);
        else if (strcmp(argv[i], "--steps") == 0 && i + 1 < argc)
            steps = atoi(argv[++i]);
        else if (strcmp(argv[i], "--big") == 0)
            big = 1;
        else if (strcmp(argv[i], "--threads") == 0 && i + 1 < argc)
            only_threads = atoi(argv[++i]);
        else if (strcmp(argv[i], "--no-extras") == 0)
            extras = 0;
        else if (strcmp(argv[i], "--measure") == 0)
            measure = 1;
        else if (strcmp(argv[i], "--plain") == 0)
            plain_solver = 1;
        else {
            fprintf(stderr, "usage: bench_solver [--repeats R] [--steps S] [--threads 1|2] [--no-extras] [--measure] "
                            "[--plain] [--big]\n");
            return 2;
        }
    }
    if (repeats < 1 || repeats > MAX_REPEATS || steps < 1 || steps > MAX_STEPS) {
        fprintf(stderr, "bench_solver: expected 1 <= repeats <= %d and 1 <= steps <= %d\n", MAX_REPEATS, MAX_STEPS);
        return 2;
    }
    setvbuf(stdout, NULL, _IOLBF, 0);
    printf("machine: %d processors; FFTW %s\n", omp_get_num_procs(), fftw_version);
    paper_configuration(repeats, steps, only_threads, extras, measure);
    if (extras)
        planning_costs();
    if (big)
        big_cone();
    printf("peak RSS %.1f MiB\n", peak_memory_mib());
    return 0;
}
