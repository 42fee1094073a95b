/* Benchmark of a solve's cost per iteration against the FFT floor (not a test): issue 33's "every solve
 * at 1.3x the FFT-pair floor per iteration".
 *
 *   bench_floor [--n N] [--repeats R] [--tol T] [--threads T] [--answers]   (T: 1, 2, or 0 for both, alternated)
 *
 * Four solve kinds on the paper's rough surface n x n (bench_recipe.h), each cold unless said:
 *   cone      the rough cone of bench_cold (80 deg, approach of smooth contact radius n / 5), non-periodic
 *   pressure  the periodic cell of bench_periodic under the mean pressure 0.004 E* (about 10% contact)
 *   gap       the same cell under the mean gap that the pressure solve found
 *   step      one step of the paper's history (bench_solver: 25 approaches up to 31.5 n / 512), the 13th,
 *             warm from the converged 12th
 * Every repeat runs each kind at each thread count in turn, and times one forward + inverse FFTW_ESTIMATE
 * pair (the solver's flags) of each grid a solve transforms (the padded window 2nx x 2ny and the window
 * itself, or the cell), so that load drifts over all alike. Printed per kind and thread count, as medians:
 * fine iterations, the transform pairs run on the fine grid (convolutions with K, preconditioner pairs M)
 * and on the cascade's coarser grids (also in K pairs of the fine grid, by their points), all of them per
 * fine iteration in K pairs ("K-pairs/it", exact counts; its floor one K pair and, preconditioned, an M
 * pair's nx ny / px py), wall and CPU time of the solve (planning apart), per-iteration CPU
 * time over the CPU time of one pair of K's grid ("pairs/it") and over the floor ("floor x"), and the peak
 * RSS of the
 * process after the kind's first solve (a running maximum: the cell's kinds run first, then the step and
 * the cone, whose padded grids are the larger). The floor of a fine iteration is what the algorithm needs
 * per iteration: one K pair, plus one M pair on the window's grid when every step is preconditioned (pair
 * times measured here, at the same thread count). The ratios are of CPU times, the work done, at both
 * thread counts: on a shared 2-core machine a 2-thread wall time measures the neighbours (the solver's
 * team shrinks to the free cores, core/team_size.c; FFTW's own pair does not). With --answers, one more
 * line per kind and thread count gives the last solve's answer to the bit (load, approach, contact
 * patches, largest pressure, and for a cell a hash of its pressures' bits), to compare builds by. */
#include "bench_fft.h"
#include "bench_recipe.h"
#include "indentmap/indenter.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "solver/plan.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

enum { MAX_REPEATS = 15, KINDS = 4, MOST_THREADS = 2 };
enum kind { CONE, PRESSURE, GAP, STEP };
static const char *const KIND_NAMES[KINDS] = {"cone", "pressure", "gap", "step"};

static void die(int status, const char *what)
{
    fprintf(stderr, "bench_floor: %s: %s (%s)\n", what, im_last_error(), im_strstatus(status));
    exit(1);
}

/* One timed solve: its counts and times. */
typedef struct measured {
    int iterations, coarse_iterations;
    long k_pairs, m_pairs, coarse_pairs;
    long long coarse_points; /* the grid points of the coarse pairs (their size in K pairs: over px py) */
    double wall, cpu;
    int nx, ny, px, py; /* the window (or cell) and the grid K is transformed on */
    double load, approach, max_pressure;
    long contact;
    unsigned long long pressure_hash; /* a cell's (FNV-1a over its pressures' bytes); 0 for a cone or a step */
} measured;

typedef struct pair_counts {
    long k, m, coarse;
    long long coarse_points;
} pair_counts;

static pair_counts pairs_now(void)
{
    return (pair_counts){solver_pairs_run(SOLVER_PAIR_K), solver_pairs_run(SOLVER_PAIR_M),
                         solver_pairs_run(SOLVER_PAIR_COARSE), solver_coarse_points_run()};
}

typedef struct stopwatch {
    double wall, cpu;
    pair_counts pairs;
} stopwatch;

static stopwatch start_watch(void) { return (stopwatch){bench_now(), bench_cpu_now(), pairs_now()}; }

/* The solve since w: its counts and times, and the grids its fine iterations transformed (a history
 * step's box, smaller than the indentation's window). */
static measured stop_watch(const stopwatch *w, int iterations, int coarse_iterations)
{
    const pair_counts now = pairs_now();
    measured m = {.iterations = iterations,
                  .coarse_iterations = coarse_iterations,
                  .k_pairs = now.k - w->pairs.k,
                  .m_pairs = now.m - w->pairs.m,
                  .coarse_pairs = now.coarse - w->pairs.coarse,
                  .coarse_points = now.coarse_points - w->pairs.coarse_points,
                  .wall = bench_now() - w->wall,
                  .cpu = bench_cpu_now() - w->cpu};
    solver_last_top_grid(&m.px, &m.py, &m.nx, &m.ny);
    return m;
}

/* The paper's cell and surface at one size, and the approaches the kinds solve at. */
typedef struct problem {
    int n;
    double tol;
    im_field *surface;
    double *gap0, *pressure, *displacement; /* the periodic cell's */
    double cell_approach;                   /* the mean-pressure solve's answer: the gap kind's target */
} problem;

static double cone_approach(int n) { return M_PI * n / (10 * tan(80 * M_PI / 180)); }
static double history_approach(int n, int step) { return 31.5 * n / 512 * step / 25; }

static measured solve_indentation(const problem *pb, enum kind kind)
{
    im_indenter cone = im_indenter_cone(80);
    im_solver_options o = im_solver_options_default();
    o.tol = pb->tol;
    const double w = kind == CONE ? cone_approach(pb->n) : history_approach(pb->n, 13);
    const double window_approach = kind == CONE ? w : history_approach(pb->n, 25);
    im_indentation *run = NULL;
    int status = im_indentation_create(pb->surface, &cone, IM_CONTROL_DISPLACEMENT, window_approach, &o, &run);
    im_step_result s;
    if (status == IM_OK && kind == STEP)
        status = im_indentation_step(run, history_approach(pb->n, 12), &s);
    if (status != IM_OK)
        die(status, KIND_NAMES[kind]);
    stopwatch watch = start_watch();
    if ((status = im_indentation_step(run, w, &s)) != IM_OK)
        die(status, KIND_NAMES[kind]);
    measured m = stop_watch(&watch, s.iterations, s.coarse_iterations);
    m.load = s.load, m.approach = s.approach, m.max_pressure = s.max_pressure, m.contact = s.contact_patches;
    im_indentation_free(run);
    return m;
}

static measured solve_cell(problem *pb, enum kind kind)
{
    const int n = pb->n;
    im_solver_options o = im_solver_options_default();
    o.tol = pb->tol;
    o.periodic = 1;
    im_solver_plan *plan = NULL;
    int status = im_solver_plan_create(n, n, 1.0, &o, &plan);
    if (status != IM_OK)
        die(status, "im_solver_plan_create");
    memset(pb->pressure, 0, sizeof(double) * (size_t)n * n);
    const enum im_control control = kind == PRESSURE ? IM_CONTROL_LOAD : IM_CONTROL_DISPLACEMENT;
    const double target = kind == PRESSURE ? 0.004 * n * n : pb->cell_approach;
    im_solve_result s;
    stopwatch watch = start_watch();
    if ((status = im_solver_solve(plan, pb->gap0, control, target, pb->pressure, pb->displacement, &s)) != IM_OK)
        die(status, KIND_NAMES[kind]);
    measured m = stop_watch(&watch, s.iterations, s.coarse_iterations);
    m.load = s.load, m.approach = s.approach, m.max_pressure = s.max_pressure, m.contact = s.contact_patches;
    m.pressure_hash = bench_bits_hash(pb->pressure, (size_t)n * n);
    if (kind == PRESSURE)
        pb->cell_approach = s.approach;
    im_solver_plan_free(plan);
    return m;
}

static measured solve_kind(problem *pb, enum kind kind)
{
    return kind == CONE || kind == STEP ? solve_indentation(pb, kind) : solve_cell(pb, kind);
}

static problem make_problem(int n, double tol)
{
    problem pb = {.n = n, .tol = tol};
    int status = bench_paper_surface(n, &pb.surface);
    if (status != IM_OK)
        die(status, "im_surface_generate");
    const size_t count = (size_t)n * n;
    pb.gap0 = malloc(sizeof(double) * count);
    pb.pressure = malloc(sizeof(double) * count);
    pb.displacement = malloc(sizeof(double) * count);
    if (!pb.gap0 || !pb.pressure || !pb.displacement)
        die(IM_ENOMEM, "cell");
    bench_cell_gap(pb.surface, pb.gap0);
    return pb;
}

/* A kind's repeats at one thread count, with the pair times measured beside them. */
typedef struct series {
    measured last;
    double wall[MAX_REPEATS], cpu[MAX_REPEATS], k_pair[MAX_REPEATS], m_pair[MAX_REPEATS];
    double peak_rss;
} series;

static void report(const series *s, enum kind kind, int n, int threads, int repeats)
{
    double wall[MAX_REPEATS], cpu[MAX_REPEATS], k_pair[MAX_REPEATS], m_pair[MAX_REPEATS];
    memcpy(wall, s->wall, sizeof wall);
    memcpy(cpu, s->cpu, sizeof cpu);
    memcpy(k_pair, s->k_pair, sizeof k_pair);
    memcpy(m_pair, s->m_pair, sizeof m_pair);
    const measured *m = &s->last;
    const double t = bench_median(wall, repeats), c = bench_median(cpu, repeats);
    const double kp = bench_median(k_pair, repeats), mp = bench_median(m_pair, repeats);
    const int it = m->iterations;
    const double per_iteration = c / it;
    /* the pairs the algorithm needs per fine iteration: K t, and M g where every step is preconditioned */
    const double floor = kp + (m->m_pairs >= it ? mp : 0);
    /* the transforms counted exactly, in K pairs of the fine grid (an M pair: nx ny / px py of one) */
    const double k_grid = (double)m->px * m->py, m_share = m->nx * (double)m->ny / k_grid;
    const double coarse = m->coarse_points / k_grid;
    printf("%-8s n %4d threads %d: grid %dx%d, it %3d (coarse %4d), pairs K %3ld M %3ld coarse %4ld (%.1f K), "
           "K-pairs/it %.2f (floor %.2f), wall %.4f s, CPU %.4f s, K pair %.3f ms, M pair %.3f ms, pairs/it %.2f, "
           "floor x %.2f, peak RSS %.1f MiB\n",
           KIND_NAMES[kind], n, threads, m->nx, m->ny, it, m->coarse_iterations, m->k_pairs, m->m_pairs,
           m->coarse_pairs, coarse, (m->k_pairs + m->m_pairs * m_share + coarse) / it,
           1 + (m->m_pairs >= it ? m_share : 0), t, c, 1e3 * kp, 1e3 * mp, per_iteration / kp, per_iteration / floor,
           s->peak_rss);
}

static void report_answer(const measured *m, enum kind kind, int n, int threads)
{
    printf("answer %-8s n %4d threads %d: load %.17g approach %.17g contact %ld max %.17g hash %016llx\n",
           KIND_NAMES[kind], n, threads, m->load, m->approach, m->contact, m->max_pressure, m->pressure_hash);
}

int main(int argc, char **argv)
{
    int n = 512, repeats = 3, only_threads = 0, answers = 0;
    double tol = 1e-8;
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--n") == 0 && i + 1 < argc)
            n = atoi(argv[++i]);
        else if (strcmp(argv[i], "--repeats") == 0 && i + 1 < argc)
            repeats = atoi(argv[++i]);
        else if (strcmp(argv[i], "--tol") == 0 && i + 1 < argc)
            tol = atof(argv[++i]);
        else if (strcmp(argv[i], "--threads") == 0 && i + 1 < argc)
            only_threads = atoi(argv[++i]);
        else if (strcmp(argv[i], "--answers") == 0)
            answers = 1;
        else {
            fprintf(stderr, "usage: bench_floor [--n N] [--repeats R] [--tol T] [--threads 0|1|2] [--answers]\n");
            return 2;
        }
    }
    if (n < 64 || n % 2 || repeats < 1 || repeats > MAX_REPEATS || !(tol > 0 && tol < 1) || only_threads < 0 ||
        only_threads > MOST_THREADS) {
        fprintf(stderr, "bench_floor: expected an even n >= 64, 1 <= repeats <= %d, 0 < tol < 1, threads 0, 1 or 2\n",
                MAX_REPEATS);
        return 2;
    }
    setvbuf(stdout, NULL, _IOLBF, 0);
    problem pb = make_problem(n, tol);
    static series runs[MOST_THREADS][KINDS];
    const enum kind order[KINDS] = {PRESSURE, GAP, STEP, CONE}; /* the smaller grids first (peak RSS) */
    for (int r = 0; r < repeats; ++r)
        for (int threads = 1; threads <= MOST_THREADS; ++threads) {
            if (only_threads && threads != only_threads)
                continue;
            omp_set_num_threads(threads);
            for (int k = 0; k < KINDS; ++k) {
                series *s = &runs[threads - 1][order[k]];
                s->last = solve_kind(&pb, order[k]);
                s->wall[r] = s->last.wall;
                s->cpu[r] = s->last.cpu;
                s->k_pair[r] = bench_fft_pair_time(s->last.px, s->last.py).cpu;
                s->m_pair[r] = bench_fft_pair_time(s->last.nx, s->last.ny).cpu;
                if (r == 0)
                    s->peak_rss = bench_peak_rss_mib();
            }
        }
    for (int threads = 1; threads <= MOST_THREADS; ++threads)
        for (int k = 0; k < KINDS; ++k)
            if (!only_threads || threads == only_threads)
                report(&runs[threads - 1][order[k]], order[k], n, threads, repeats);
    for (int threads = 1; threads <= MOST_THREADS && answers; ++threads)
        for (int k = 0; k < KINDS; ++k)
            if (!only_threads || threads == only_threads)
                report_answer(&runs[threads - 1][order[k]].last, order[k], n, threads);
    im_field_free(pb.surface);
    free(pb.gap0);
    free(pb.pressure);
    free(pb.displacement);
    return 0;
}
