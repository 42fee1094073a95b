/* Benchmark of one cold contact solve (not a test): the configuration of issue 15.
 *
 *   bench_cold [--n N] [--threads T] [--repeats R] [--tol T] [--no-cascade] [--no-precondition] [--compare]
 *
 * A rough surface n x n (H 0.8, lambda_s 4, lambda_r n, h'rms 0.08, seed 1) indented by an 80 deg
 * cone to the approach whose smooth contact radius is n/5, displacement control, from a cold start
 * (the first step of a history). Prints, as medians of R repeats (default 3): fine-grid iterations,
 * the iterations of the cascade's coarser levels, wall and CPU time of the solve (planning apart),
 * CPU time per fine iteration over the CPU time of one forward + inverse FFT pair of the padded window
 * (the floor), the wall and CPU time of that pair at the same thread count (its 1- to 2-thread ratio
 * is the floor's speed-up), and the process's peak memory. CPU time is the figure to trust on a shared
 * machine at one thread. --no-cascade starts from the local guess, --no-precondition takes plain PK steps (both:
 * the solver before issue 15). --compare solves once more with both off and prints the relative
 * load difference and the patches whose contact state differs. --measure plans with FFTW_MEASURE (the
 * planning time of the first plan is printed: later ones of the same sizes reuse the process's wisdom).
 */
#include "bench_fft.h"
#include "bench_recipe.h"
#include "indentmap/indenter.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <string.h>

#define MAX_REPEATS 15

static void die(int status, const char *what)
{
    fprintf(stderr, "bench_cold: %s: %s (%s)\n", what, im_last_error(), im_strstatus(status));
    exit(1);
}

typedef struct cold_solve {
    im_step_result step;
    int coarse_iterations;
    double wall, cpu, plan_seconds;
    im_window window;
    im_field *force;
} cold_solve;

static cold_solve solve_cold(const im_field *surface, double approach, const im_solver_options *o, int keep)
{
    im_indenter cone = im_indenter_cone(80);
    im_indentation *run = NULL;
    int status = im_indentation_create(surface, &cone, IM_CONTROL_DISPLACEMENT, approach, o, &run);
    if (status != IM_OK)
        die(status, "im_indentation_create");
    cold_solve c = {.window = im_indentation_window(run),
                    .plan_seconds = im_solver_plan_seconds(im_indentation_plan(run))};
    double wall = bench_now(), cpu = bench_cpu_now();
    if ((status = im_indentation_step(run, approach, &c.step)) != IM_OK)
        die(status, "im_indentation_step");
    c.wall = bench_now() - wall;
    c.cpu = bench_cpu_now() - cpu;
    c.coarse_iterations = c.step.coarse_iterations;
    if (keep && (status = im_indentation_fields(run, &c.force, NULL, NULL)) != IM_OK)
        die(status, "im_indentation_fields");
    im_indentation_free(run);
    return c;
}

/* Patches in contact in one force field and not in the other. */
static long contact_differences(const im_field *a, const im_field *b)
{
    long differ = 0;
    for (size_t i = 0; i < im_field_count(a); ++i)
        differ += (a->data[i] > 0) != (b->data[i] > 0);
    return differ;
}

int main(int argc, char **argv)
{
    int n = 512, threads = 1, repeats = 3, compare = 0, cascade = 1, precondition = 1, measure = 0;
    double tol = 1e-8;
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--n") == 0 && i + 1 < argc)
            n = atoi(argv[++i]);
        else if (strcmp(argv[i], "--threads") == 0 && i + 1 < argc)
            threads = atoi(argv[++i]);
        else if (strcmp(argv[i], "--repeats") == 0 && i + 1 < argc)
            repeats = atoi(argv[++i]);
        else if (strcmp(argv[i], "--tol") == 0 && i + 1 < argc)
            tol = atof(argv[++i]);
        else if (strcmp(argv[i], "--no-cascade") == 0)
            cascade = 0;
        else if (strcmp(argv[i], "--no-precondition") == 0)
            precondition = 0;
        else if (strcmp(argv[i], "--compare") == 0)
            compare = 1;
        else if (strcmp(argv[i], "--measure") == 0)
            measure = 1;
        else {
            fprintf(stderr, "usage: bench_cold [--n N] [--threads T] [--repeats R] [--tol T] [--no-cascade] "
                            "[--no-precondition] [--compare] [--measure]\n");
            return 2;
        }
    }
    if (n < 64 || threads < 1 || repeats < 1 || repeats > MAX_REPEATS || !(tol > 0 && tol < 1)) {
        fprintf(stderr, "bench_cold: expected n >= 64, threads >= 1, 1 <= repeats <= %d, 0 < tol < 1\n", MAX_REPEATS);
        return 2;
    }
    setvbuf(stdout, NULL, _IOLBF, 0);
    omp_set_num_threads(threads);
    im_field *surface;
    int status = bench_paper_surface(n, &surface);
    if (status != IM_OK)
        die(status, "im_surface_generate");
    /* Love's cone: a = 2 w tan(alpha) / pi, so a = n / 5 at w = pi n cot(alpha) / 10 */
    const double approach = M_PI * n / (10 * tan(80 * M_PI / 180));
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-8; /* the tolerance these figures were measured at (the default is 1e-6) */
    o.tol = tol;
    o.cascade = cascade;
    o.precondition = precondition;
    o.fft_measure = measure;
    double wall[MAX_REPEATS], cpu[MAX_REPEATS], first_plan = -1;
    cold_solve c = {0};
    for (int r = 0; r < repeats; ++r) {
        c = solve_cold(surface, approach, &o, compare && r == 0);
        if (first_plan < 0) /* later plans of the same sizes find the process's wisdom */
            first_plan = c.plan_seconds;
        if (r > 0 || !compare)
            continue;
        im_solver_options plain = o;
        plain.cascade = plain.precondition = 0;
        cold_solve reference = solve_cold(surface, approach, &plain, 1);
        printf("against the plain PK solve (%d iterations): load rel. difference %.2e, contact patches "
               "differing %ld (n_p %ld vs %ld)\n",
               reference.step.iterations, fabs(c.step.load / reference.step.load - 1),
               contact_differences(c.force, reference.force), c.step.contact_patches, reference.step.contact_patches);
        im_field_free(reference.force);
        im_field_free(c.force);
    }
    for (int r = 0; r < repeats; ++r) {
        c = solve_cold(surface, approach, &o, 0);
        wall[r] = c.wall;
        cpu[r] = c.cpu;
    }
    const bench_pair_time pair = bench_fft_pair_time(2 * c.window.nx, 2 * c.window.ny);
    const double floor = pair.cpu;
    const double cpu_median = bench_median(cpu, repeats);
    printf("n %d, threads %d, tol %g, cascade %d, precondition %d: window %d x %d, w %.4f, n_p %ld, N %.10g\n", n,
           threads, tol, o.cascade, o.precondition, c.window.nx, c.window.ny, approach, c.step.contact_patches,
           c.step.load);
    printf("  fine iterations %d (convolutions %d), coarse iterations %d, wall %.3f s, CPU %.3f s (median of %d), "
           "CPU %.1f FFT pairs (%.2f per fine iteration; pair %.2f ms), peak RSS %.1f MiB\n",
           c.step.iterations, c.step.convolutions, c.coarse_iterations, bench_median(wall, repeats), cpu_median,
           repeats, cpu_median / floor, cpu_median / floor / c.step.iterations, 1e3 * floor, bench_peak_rss_mib());
    printf("  FFT pair of the padded window %d x %d: wall %.3f ms, CPU %.3f ms (medians of %d)\n", 2 * c.window.nx,
           2 * c.window.ny, 1e3 * pair.wall, 1e3 * pair.cpu, BENCH_PAIR_REPEATS);
    printf("  planning %.3f s wall (FFTW_%s, the first plan of the process)\n", first_plan,
           measure ? "MEASURE" : "ESTIMATE");
    im_field_free(surface);
    return 0;
}
