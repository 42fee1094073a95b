/* Benchmark of cold periodic (nominally flat) solves (not a test): issue 33's periodic goal.
 *
 *   bench_periodic [--n N] [--threads T] [--repeats R] [--tol T] [--pressure P_M] [--no-cascade]
 *                  [--no-precondition] [--compare]
 *
 * One periodic n x n rough cell (H 0.8, lambda_s 4, lambda_r n, h'rms 0.08, seed 1), g0 = max h - h,
 * solved cold at the mean pressure P_M (units of E*, default 0.004: about 10% contact) and then, as a
 * second solve, under the mean gap that the first one found (displacement control at its approach).
 * Prints per control, as medians of R repeats (default 3): fine-grid iterations, the cascade's coarse
 * iterations (all levels), the fine grid's convolutions, wall and CPU time of the solve (planning
 * apart), and CPU time per fine iteration over the CPU time of one forward + inverse FFT pair of the
 * n x n cell (the floor).
 * --compare solves each control once more by plain PK (no cascade, no preconditioner) and prints the
 * relative load and approach differences and the patches whose contact state differs. */
#include "bench_fft.h"
#include "bench_recipe.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define MAX_REPEATS 15

static void die(int status, const char *what)
{
    fprintf(stderr, "bench_periodic: %s: %s (%s)\n", what, im_last_error(), im_strstatus(status));
    exit(1);
}

typedef struct cell {
    int n;
    double *gap0, *pressure, *displacement;
} cell;

typedef struct timed_solve {
    im_solve_result result;
    double wall, cpu;
} timed_solve;

static timed_solve solve_cold(im_solver_plan *plan, const cell *c, enum im_control control, double target)
{
    memset(c->pressure, 0, sizeof(double) * (size_t)c->n * c->n);
    timed_solve t = {0};
    double wall = bench_now(), cpu = bench_cpu_now();
    int status = im_solver_solve(plan, c->gap0, control, target, c->pressure, c->displacement, &t.result);
    t.wall = bench_now() - wall;
    t.cpu = bench_cpu_now() - cpu;
    if (status != IM_OK)
        die(status, "im_solver_solve");
    return t;
}

static im_solver_plan *plan_of(int n, const im_solver_options *o)
{
    im_solver_plan *plan = NULL;
    int status = im_solver_plan_create(n, n, 1.0, o, &plan);
    if (status != IM_OK)
        die(status, "im_solver_plan_create");
    return plan;
}

static cell make_cell(int n)
{
    im_field *surface;
    int status = bench_paper_surface(n, &surface);
    if (status != IM_OK)
        die(status, "im_surface_generate");
    const size_t count = (size_t)n * n;
    cell c = {.n = n,
              .gap0 = malloc(sizeof(double) * count),
              .pressure = malloc(sizeof(double) * count),
              .displacement = malloc(sizeof(double) * count)};
    if (!c.gap0 || !c.pressure || !c.displacement)
        die(IM_ENOMEM, "cell");
    bench_cell_gap(surface, c.gap0);
    im_field_free(surface);
    return c;
}

/* The contact state of the last solve of c (p > 0), kept for the comparison. */
static unsigned char *contact_set(const cell *c)
{
    const size_t count = (size_t)c->n * c->n;
    unsigned char *set = malloc(count);
    if (!set)
        die(IM_ENOMEM, "contact set");
    for (size_t i = 0; i < count; ++i)
        set[i] = c->pressure[i] > 0;
    return set;
}

static void compare_with_plain(const cell *c, const im_solver_options *o, enum im_control control, double target,
                               const im_solve_result *fast)
{
    unsigned char *fast_set = contact_set(c);
    im_solver_options plain = *o;
    plain.cascade = plain.precondition = 0;
    im_solver_plan *plan = plan_of(c->n, &plain);
    timed_solve reference = solve_cold(plan, c, control, target);
    long differ = 0;
    for (size_t i = 0; i < (size_t)c->n * c->n; ++i)
        differ += fast_set[i] != (c->pressure[i] > 0);
    printf("  against plain PK (%d iterations, %.3f s): load rel. difference %.2e, approach rel. difference "
           "%.2e, contact patches differing %ld\n",
           reference.result.iterations, reference.wall, fabs(fast->load / reference.result.load - 1),
           fabs(fast->approach / reference.result.approach - 1), differ);
    im_solver_plan_free(plan);
    free(fast_set);
}

/* R cold solves of one control; prints the medians and returns the last result. */
static im_solve_result run_control(im_solver_plan *plan, const cell *c, const im_solver_options *o, int repeats,
                                   enum im_control control, double target, double floor, int compare)
{
    double wall[MAX_REPEATS], cpu[MAX_REPEATS];
    timed_solve t = {0};
    for (int r = 0; r < repeats; ++r) {
        t = solve_cold(plan, c, control, target);
        wall[r] = t.wall;
        cpu[r] = t.cpu;
    }
    const im_solve_result *s = &t.result;
    const double cpu_median = bench_median(cpu, repeats);
    printf("n %d, threads %d, tol %g, cascade %d, precondition %d, %s control: fine iterations %d, coarse "
           "iterations %d, convolutions %d, wall %.3f s, CPU %.3f s (medians of %d), %.2f FFT pairs per fine "
           "iteration (pair %.3f ms); approach %.12g, load %.12g, n_p %ld\n",
           c->n, omp_get_max_threads(), o->tol, o->cascade, o->precondition,
           control == IM_CONTROL_LOAD ? "mean-pressure" : "mean-gap", s->iterations, s->coarse_iterations,
           s->convolutions, bench_median(wall, repeats), cpu_median, repeats, cpu_median / floor / s->iterations,
           1e3 * floor, s->approach, s->load, s->contact_patches);
    if (compare)
        compare_with_plain(c, o, control, target, s);
    return *s;
}

static void usage(void)
{
    fprintf(stderr, "usage: bench_periodic [--n N] [--threads T] [--repeats R] [--tol T] [--pressure P_M] "
                    "[--no-cascade] [--no-precondition] [--compare]\n");
    exit(2);
}

int main(int argc, char **argv)
{
    int n = 512, threads = 1, repeats = 3, compare = 0;
    double tol = 1e-8, mean_pressure = 0.004;
    im_solver_options o = im_solver_options_default();
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--n") == 0 && i + 1 < argc)
            n = atoi(argv[++i]);
        else if (strcmp(argv[i], "--threads") == 0 && i + 1 < argc)
            threads = atoi(argv[++i]);
        else if (strcmp(argv[i], "--repeats") == 0 && i + 1 < argc)
            repeats = atoi(argv[++i]);
        else if (strcmp(argv[i], "--tol") == 0 && i + 1 < argc)
            tol = atof(argv[++i]);
        else if (strcmp(argv[i], "--pressure") == 0 && i + 1 < argc)
            mean_pressure = atof(argv[++i]);
        else if (strcmp(argv[i], "--no-cascade") == 0)
            o.cascade = 0;
        else if (strcmp(argv[i], "--no-precondition") == 0)
            o.precondition = 0;
        else if (strcmp(argv[i], "--compare") == 0)
            compare = 1;
        else
            usage();
    }
    if (n < 64 || threads < 1 || repeats < 1 || repeats > MAX_REPEATS || !(tol > 0 && tol < 1) ||
        !(mean_pressure > 0)) {
        fprintf(stderr,
                "bench_periodic: expected n >= 64, threads >= 1, 1 <= repeats <= %d, 0 < tol < 1, "
                "P_M > 0\n",
                MAX_REPEATS);
        return 2;
    }
    setvbuf(stdout, NULL, _IOLBF, 0);
    omp_set_num_threads(threads);
    o.tol = tol;
    o.periodic = 1;
    cell c = make_cell(n);
    im_solver_plan *plan = plan_of(n, &o);
    const double floor = bench_fft_pair_time(n, n).cpu;
    im_solve_result loaded = run_control(plan, &c, &o, repeats, IM_CONTROL_LOAD, mean_pressure * n * n, floor,
                                         compare);
    run_control(plan, &c, &o, repeats, IM_CONTROL_DISPLACEMENT, loaded.approach, floor, compare);
    printf("  peak RSS %.1f MiB\n", bench_peak_rss_mib());
    im_solver_plan_free(plan);
    free(c.gap0);
    free(c.pressure);
    free(c.displacement);
    return 0;
}
