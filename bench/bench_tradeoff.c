/* Benchmark of the speed/accuracy trade (issue 7; not a test).
 *
 *   bench_tradeoff CSV_PATH PNG_PATH
 *   bench_tradeoff --plot CSV_PATH PNG_PATH   (the figure drawn again from a CSV this wrote, nothing measured)
 *
 * One physical problem: a 128 x 128 base box of the paper's surface family scaled down (H = 0.8,
 * lambda_s = 4 base cells, lambda_r = 128, h'rms = 0.08, seed 1), and the same box smooth (h = 0);
 * an 80 degree cone on the box centre, one load-controlled solve at the load whose smooth contact
 * area is A_cone = 3000 base cells. Knobs, each swept from a baseline (1x, tol 1e-6, margin 4,
 * crop on, 1 thread):
 *   refinement  the same band-limited surface on a grid 1x, 2x, 4x finer over the same box
 *               (im_surface_generate keeps every mode: spectral interpolation; the 2x and 4x
 *               surfaces agree with the 1x one at its sample points to 1e-10, tests/test_surface.c);
 *   tolerance   the solver's stopping tolerance 1e-2 .. 1e-10;
 *   window      margin 0, 4, 16 patches around the solve window, and crop off (whole surface);
 *   threads     2 OpenMP threads at 1x, 2x, 4x (tol 1e-6) against the baseline's 1.
 * Errors against truth:
 *   smooth  the closed forms: N at the closed-form approach w(N0) (a displacement-controlled
 *           solve) against N0, n_p delta^2 against A_cone(N0), and the patches of the 128 x 128
 *           base grid inside or outside the closed-form contact circle wrongly, and the pressure
 *           p(r) against (E* cot alpha / 2) acosh(a / r) over the patches with 0.2a < r < 0.8a
 *           (rms and max relative error);
 *   rough   the finest, tightest run (4x, tol 1e-11, crop off) as reference: A/A_cone, N at the
 *           reference's approach, and the symmetric difference of the contact maps sampled at the
 *           base patch centres (a refined grid's patch (r i, r j) sits on base patch (i, j)'s
 *           centre, because the cone axis is on a base sample point in the surface's frame).
 * The plotted error is the larger of the N and A/A_cone relative errors.
 * Every configuration runs in its own forked process: wall time is the median of 3 repeats of
 * (im_indentation_create + the load step), cold start each, planning included, and the whole sweep
 * is run 3 times, round after round, the median of the rounds kept; peak RSS is that
 * process's ru_maxrss (surface synthesis included, plus the few MiB the parent held at fork).
 * Output: CSV_PATH (one row per configuration, machine and threads in the header comment) and
 * PNG_PATH (error against CPU time per solve, log-log, per problem, with the Pareto frontier as a
 *   line; see cost() for why CPU rather than wall time).
 * Run it with OMP_WAIT_POLICY=passive on a shared machine: libgomp's default spin-waiting at
 * barriers stalled 2-thread solves by 1-4 s when other processes held the cores (measured).
 */
#include "bench_common.h"
#include "indentmap/indenter.h"
#include "indentmap/io.h"
#include "indentmap/plot.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <errno.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <string.h>
#include <sys/utsname.h>
#include <sys/wait.h>
#include <unistd.h>

#define BASE 128         /* base grid side */
#define AREA_CONE 3000.0 /* smooth contact area at the imposed load, base cells */
#define ALPHA 80.0
#define REPEATS 3
#define ROUNDS 3 /* the whole sweep, round after round */
#define MAX_CONFIGS 64

enum problem { SMOOTH = 0, ROUGH = 1 };
static const char *const problem_names[] = {"smooth", "rough"};

typedef struct config {
    const char *family;
    enum problem problem;
    int refine, margin, crop, threads;
    double tol;
} config;

typedef struct outcome {
    int status;
    double seconds, cpu_seconds, rss_mib, plan_bytes; /* wall and CPU (all threads) per solve */
    int iterations, window_nx, window_ny;
    double approach, load, area_ratio; /* of the load step */
    long contact_patches;
    double load_at_w; /* N of the displacement step at the reference approach */
    double error_load, error_area, error;
    double error_p_rms, error_p_max; /* smooth: p(r) against the closed form; NaN for rough */
    long symmetric_difference;       /* base patches */
} outcome;

/* What the errors are measured against (closed forms, or the reference run). */
typedef struct truth {
    double load, approach, area_ratio;
    unsigned char map[BASE * BASE]; /* contact on the base grid */
} truth;

static double imposed_load(void)
{
    /* A_cone = 2N / (E* cot alpha) with E* = 1 */
    return 0.5 * AREA_CONE / tan(ALPHA * M_PI / 180.0);
}

static int make_surface(enum problem problem, int refine, im_field **out)
{
    const double delta = 1.0 / refine;
    if (problem == SMOOTH)
        return im_field_create(BASE * refine, BASE * refine, delta, out);
    im_surface_params p = im_surface_params_default();
    p.nx = p.ny = BASE * refine;
    p.delta = delta;
    p.lambda_s = 4.0 * refine;
    p.lambda_r = (double)BASE * refine;
    p.slope_rms = 0.08;
    p.seed = 1;
    return im_surface_generate(&p, out);
}

/* Contact on the base grid: patch (r i, r j) of the run's grid for base patch (i, j). */
static void base_contact_map(const im_field *force, int refine, unsigned char *map)
{
    for (int j = 0; j < BASE; ++j)
        for (int i = 0; i < BASE; ++i)
            map[j * BASE + i] = force->data[(size_t)refine * j * force->nx + (size_t)refine * i] > 0;
}

/* Relative error of the patch pressures p = f / delta^2 against the cone's closed form at approach
 * w, over the patches with 0.2a < r < 0.8a (r from the axis, which sits on sample (nx/2, ny/2)):
 * rms in *rms, largest in *max. */
static void pressure_error(const im_field *force, double w, double *rms, double *max)
{
    im_indenter cone = im_indenter_cone(ALPHA);
    const double a = im_indenter_contact_radius(&cone, w), d = force->delta;
    double sum = 0, worst = 0;
    long count = 0;
    for (int j = 0; j < force->ny; ++j)
        for (int i = 0; i < force->nx; ++i) {
            double r = d * hypot(i - force->nx / 2, j - force->ny / 2);
            if (r <= 0.2 * a || r >= 0.8 * a)
                continue;
            double exact = im_indenter_pressure(&cone, 1.0, w, r);
            double e = fabs(force->data[(size_t)j * force->nx + i] / (d * d) - exact) / exact;
            sum += e * e;
            worst = fmax(worst, e);
            ++count;
        }
    *rms = count ? sqrt(sum / count) : NAN;
    *max = count ? worst : NAN;
}

/* The base contact map of the run's last step and, for the smooth cone (approach w of the closed
 * form), the pressure errors. */
static int inspect_fields(const im_indentation *run, const config *c, double w, unsigned char *map, outcome *o)
{
    im_field *force = NULL;
    int status = im_indentation_fields(run, &force, NULL, NULL);
    if (status != IM_OK)
        return status;
    base_contact_map(force, c->refine, map);
    o->error_p_rms = o->error_p_max = NAN;
    if (c->problem == SMOOTH)
        pressure_error(force, w, &o->error_p_rms, &o->error_p_max);
    im_field_free(force);
    return IM_OK;
}

static long symmetric_difference(const unsigned char *a, const unsigned char *b)
{
    long n = 0;
    for (int i = 0; i < BASE * BASE; ++i)
        n += a[i] != b[i];
    return n;
}

static im_solver_options solver_options(const config *c)
{
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-8; /* the tolerance these figures were measured at (the default is 1e-6) */
    o.tol = c->tol;
    o.window_margin = c->margin;
    o.crop = c->crop;
    return o;
}

/* One create + step; keeps the run in *kept when kept is not NULL. */
static int solve_once(const im_field *surface, const config *c, enum im_control control, double target,
                      im_step_result *step, im_indentation **kept)
{
    im_indenter cone = im_indenter_cone(ALPHA);
    im_solver_options o = solver_options(c);
    im_indentation *run = NULL;
    int status = im_indentation_create(surface, &cone, control, target, &o, &run);
    if (status == IM_OK)
        status = im_indentation_step(run, target, step);
    if (status == IM_OK && kept)
        *kept = run;
    else
        im_indentation_free(run);
    return status;
}

/* CPU seconds of this process, all threads. */
static double cpu_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double relative(double value, double reference) { return fabs(value - reference) / fabs(reference); }

/* Runs one configuration (in the child process): timing, errors against truth, and the run's
 * base contact map in map_out (may be NULL). */
static int measure(const config *c, const truth *t, outcome *o, unsigned char *map_out)
{
    omp_set_num_threads(c->threads);
    im_field *surface = NULL;
    int status = make_surface(c->problem, c->refine, &surface);
    if (status != IM_OK)
        return status;
    const double n0 = imposed_load();
    double seconds[REPEATS], cpu[REPEATS];
    im_step_result step;
    im_indentation *run = NULL;
    for (int k = 0; k < REPEATS && status == IM_OK; ++k) {
        double start = bench_now(), cpu_start = cpu_now();
        status = solve_once(surface, c, IM_CONTROL_LOAD, n0, &step, k == REPEATS - 1 ? &run : NULL);
        seconds[k] = bench_now() - start;
        cpu[k] = cpu_now() - cpu_start;
    }
    if (status != IM_OK) {
        im_field_free(surface);
        return status;
    }
    unsigned char map[BASE * BASE];
    status = inspect_fields(run, c, t->approach, map, o);
    im_window w = im_indentation_window(run);
    im_indentation_free(run);
    o->seconds = bench_median(seconds, REPEATS);
    o->cpu_seconds = bench_median(cpu, REPEATS);
    o->plan_bytes = im_solver_plan_bytes(w.nx, w.ny);
    o->window_nx = w.nx;
    o->window_ny = w.ny;
    o->iterations = step.iterations;
    o->approach = step.approach;
    o->load = step.load;
    o->area_ratio = step.area_ratio;
    o->contact_patches = step.contact_patches;
    if (status == IM_OK) {
        im_step_result at_w;
        status = solve_once(surface, c, IM_CONTROL_DISPLACEMENT, t->approach, &at_w, NULL);
        o->load_at_w = at_w.load;
    }
    im_field_free(surface);
    o->error_load = relative(o->load_at_w, t->load);
    o->error_area = relative(o->area_ratio, t->area_ratio);
    o->error = fmax(o->error_load, o->error_area);
    o->symmetric_difference = symmetric_difference(map, t->map);
    if (map_out)
        memcpy(map_out, map, sizeof map);
    o->rss_mib = bench_peak_rss_mib();
    return status;
}

/* Runs measure() in a forked process so that its peak RSS is its own. */
static int measure_in_child(const config *c, const truth *t, outcome *o, unsigned char *map_out)
{
    int fds[2];
    if (pipe(fds) != 0)
        return im_fail(IM_EIO, "pipe: %s", strerror(errno));
    pid_t pid = fork();
    if (pid < 0)
        return im_fail(IM_EIO, "fork: %s", strerror(errno));
    if (pid == 0) {
        close(fds[0]);
        outcome mine = {0};
        unsigned char map[BASE * BASE];
        mine.status = measure(c, t, &mine, map);
        if (mine.status != IM_OK)
            fprintf(stderr, "bench_tradeoff: %s %s: %s\n", problem_names[c->problem], c->family, im_last_error());
        int ok = write(fds[1], &mine, sizeof mine) == (ssize_t)sizeof mine &&
                 write(fds[1], map, sizeof map) == (ssize_t)sizeof map;
        _exit(ok ? 0 : 1);
    }
    close(fds[1]);
    unsigned char map[BASE * BASE];
    int ok = read(fds[0], o, sizeof *o) == (ssize_t)sizeof *o && read(fds[0], map, sizeof map) == (ssize_t)sizeof map;
    close(fds[0]);
    int child;
    waitpid(pid, &child, 0);
    if (!ok || !WIFEXITED(child) || WEXITSTATUS(child) != 0)
        return im_fail(IM_EIO, "the child measuring %s %s failed", problem_names[c->problem], c->family);
    if (map_out)
        memcpy(map_out, map, sizeof map);
    return o->status;
}

/* Closed-form truth of the smooth cone: N0, w(N0), A/A_cone = 1, the disc of radius a(N0) around
 * the axis, which sits on base sample (BASE/2, BASE/2) in the surface's frame. */
static void smooth_truth(truth *t)
{
    im_indenter cone = im_indenter_cone(ALPHA);
    t->load = imposed_load();
    t->approach = im_indenter_approach_for_load(&cone, 1.0, t->load);
    t->area_ratio = 1.0;
    double a = im_indenter_contact_radius(&cone, t->approach);
    for (int j = 0; j < BASE; ++j)
        for (int i = 0; i < BASE; ++i)
            t->map[j * BASE + i] = hypot(i - BASE / 2, j - BASE / 2) < a;
}

/* The rough reference: the finest, tightest run (4x, tol 1e-11, whole surface). */
static const config rough_reference = {"reference", ROUGH, 4, 4, 0, 2, 1e-11};

/* Its own load step gives w_ref; N(w_ref) = N0 to its tolerance by construction. */
static int rough_truth(truth *t, outcome *reference)
{
    config c = rough_reference;
    truth none;
    smooth_truth(&none); /* placeholder approach for the child's displacement step */
    int status = measure_in_child(&c, &none, reference, t->map);
    t->load = imposed_load();
    t->approach = reference->approach;
    t->area_ratio = reference->area_ratio;
    return status;
}

static int add(config *list, int n, const char *family, enum problem p, int refine, double tol, int margin, int crop,
               int threads)
{
    list[n] = (config){family, p, refine, margin, crop, threads, tol};
    return n + 1;
}

static int config_list(enum problem p, config *list)
{
    static const double tols[] = {1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-8, 1e-9, 1e-10};
    int n = 0;
    for (int k = 0; k < (int)(sizeof tols / sizeof *tols); ++k)
        n = add(list, n, "tolerance", p, 1, tols[k], 4, 1, 1);
    for (int refine = 1; refine <= 4; refine *= 2) {
        if (refine > 1)
            n = add(list, n, "refinement-tol-1e-4", p, refine, 1e-4, 4, 1, 1);
        n = add(list, n, "refinement", p, refine, 1e-6, 4, 1, 1);
    }
    static const int margins[] = {0, 4, 16};
    for (int k = 0; k < 3; ++k)
        n = add(list, n, "window", p, 1, 1e-6, margins[k], 1, 1);
    n = add(list, n, "window", p, 1, 1e-6, 4, 0, 1);
    for (int refine = 1; refine <= 4; refine *= 2)
        n = add(list, n, "threads", p, refine, 1e-6, 4, 1, 2);
    return n;
}

/* ---- output ---- */

typedef struct measured {
    config config;
    outcome outcome;
    int on_frontier;
} measured;

/* Errors within this fraction count as equal: the achieved load, hence A/A_cone, differs by a few
 * ulp-scale amounts between tolerances that find the same contact set. */
#define SAME_ERROR 1e-3

/* The cost plotted and used for the frontier: CPU seconds per solve (all threads). On the shared
 * 2-core machine wall times of 20-200 ms moved by 2-4x with other engineers' load; CPU time moved
 * far less, and at one thread (every knob but threads) it is the wall time of a quiet machine.
 * Wall time is in the CSV beside it and decides the threads knob, whose 2-thread points spend
 * more CPU for less wall time. */
static double cost(const outcome *o) { return o->cpu_seconds; }

/* Marks the points no other point beats in both time and error (error 0: the reference, left out). */
static void mark_frontier(measured *m, int n)
{
    for (int i = 0; i < n; ++i) {
        const outcome *a = &m[i].outcome;
        m[i].on_frontier = a->status == IM_OK && a->error > 0;
        for (int j = 0; j < n && m[i].on_frontier; ++j) {
            const outcome *b = &m[j].outcome;
            if (j != i && b->status == IM_OK && b->error > 0 && cost(b) <= cost(a) &&
                b->error <= a->error * (1 + SAME_ERROR) &&
                (cost(b) < cost(a) || b->error < a->error * (1 - SAME_ERROR)))
                m[i].on_frontier = 0;
        }
    }
}

static void csv_row(FILE *f, const measured *m)
{
    const config *c = &m->config;
    const outcome *o = &m->outcome;
    fprintf(f,
            "%s,%s,%d,%.0e,%d,%d,%d,%d,%.6g,%.6g,%.6g,%ld,%.6g,%.6g,%.3e,%.3e,%.3e,%.3e,%.3e,%ld,%d,%dx%d,"
            "%.6f,%.6f,%.1f,%.3f,%d\n",
            problem_names[c->problem], c->family, c->refine, c->tol, c->margin, c->crop, c->threads, o->status,
            o->approach, o->load, o->area_ratio, o->contact_patches, o->load_at_w, o->area_ratio, o->error_load,
            o->error_area, o->error, o->error_p_rms, o->error_p_max, o->symmetric_difference, o->iterations,
            o->window_nx, o->window_ny, o->seconds, o->cpu_seconds, o->rss_mib, o->plan_bytes / 1048576.0,
            m->on_frontier);
}

/* The 1-minute load average (/proc/loadavg), NAN where unreadable. */
static double load_average(void)
{
    double load = NAN;
    FILE *f = fopen("/proc/loadavg", "r");
    if (f && fscanf(f, "%lf", &load) != 1)
        load = NAN;
    if (f)
        fclose(f);
    return load;
}

static double load_at_start;

static int write_csv(const char *path, const measured *m, int n)
{
    char *text = NULL;
    size_t size = 0;
    FILE *f = open_memstream(&text, &size);
    if (!f)
        return im_fail(IM_ENOMEM, "open_memstream for %s", path);
    struct utsname u;
    uname(&u);
    fprintf(f, "# bench_tradeoff: %s %s %s, %ld online cores; threads per row in column threads\n", u.sysname,
            u.release, u.machine, sysconf(_SC_NPROCESSORS_ONLN));
    const char *wait = getenv("OMP_WAIT_POLICY");
    fprintf(f, "# OMP_WAIT_POLICY=%s; load average (1 min) %.2f at the start, %.2f at the end\n",
            wait ? wait : "(unset)", load_at_start, load_average());
    fprintf(f,
            "# base %d x %d box, H 0.8, lambda_s 4 base cells, h'rms 0.08, seed 1; cone %g deg; load N0 = %.6g "
            "(A_cone = %g base cells), E* = 1\n",
            BASE, BASE, ALPHA, imposed_load(), AREA_CONE);
    fprintf(f,
            "# wall: median over %d rounds of the median of %d repeats of create + load step (planning included); "
            "rss: ru_maxrss of the "
            "forked process per row; error = max(error_N, error_A); symdiff in base patches\n",
            ROUNDS, REPEATS);
    fprintf(f, "# error_p_rms/max: smooth cone, relative error of p(r) against (E* cot alpha / 2) acosh(a/r) over "
               "0.2a < r < 0.8a (nan for rough); rough reference: 4x, tol 1e-11, crop off\n");
    fprintf(f, "problem,family,refine,tol,margin,crop,threads,status,approach,load,area_ratio,contact_patches,"
               "load_at_w_ref,A_over_Acone,error_N,error_A,error,error_p_rms,error_p_max,symdiff,iterations,window,"
               "wall_s,cpu_s,rss_mib,"
               "plan_mib,frontier\n");
    for (int i = 0; i < n; ++i)
        csv_row(f, &m[i]);
    fclose(f);
    int status = im_write_file_atomic(path, text, size);
    free(text);
    return status;
}

static const char *const families[] = {"tolerance", "refinement", "refinement-tol-1e-4", "window", "threads"};
static const char *const legend_labels[] = {"tolerance (1x)", "refinement (1x, 2x, 4x)", "refinement, tol 10^{-4}",
                                            "window margin, crop", "2 threads (1x, 2x, 4x)"};
#define FAMILIES 5

/* One panel's series: one marker series per knob family, the frontier as a line. */
typedef struct panel_data {
    double x[FAMILIES + 1][MAX_CONFIGS], y[FAMILIES + 1][MAX_CONFIGS];
    im_plot_series series[FAMILIES + 1];
} panel_data;

static double plotted_error(const outcome *o) { return o->status == IM_OK && o->error > 0 ? o->error : NAN; }

static int by_time(const void *a, const void *b)
{
    const double *p = a, *q = b;
    return (p[0] > q[0]) - (p[0] < q[0]);
}

static void fill_panel(panel_data *d, const measured *m, int n)
{
    static const im_plot_marker markers[] = {IM_PLOT_MARKER_SQUARE, IM_PLOT_MARKER_CIRCLE, IM_PLOT_MARKER_CIRCLE,
                                             IM_PLOT_MARKER_TRIANGLE, IM_PLOT_MARKER_DIAMOND};
    for (int f = 0; f < FAMILIES; ++f) {
        int k = 0;
        for (int i = 0; i < n; ++i)
            if (strcmp(m[i].config.family, families[f]) == 0) {
                d->x[f][k] = cost(&m[i].outcome);
                d->y[f][k++] = plotted_error(&m[i].outcome);
            }
        im_plot_series *s = &d->series[f];
        *s = (im_plot_series){.x = d->x[f],
                              .y = d->y[f],
                              .n = k,
                              .line = IM_PLOT_NO_LINE,
                              .marker = markers[f],
                              .marker_size = f == 2 ? 4 : 5,
                              .label = legend_labels[f]};
        im_plot_palette(f, s->color);
    }
    double pairs[MAX_CONFIGS][2];
    int k = 0;
    for (int i = 0; i < n; ++i)
        if (m[i].on_frontier) {
            pairs[k][0] = cost(&m[i].outcome);
            pairs[k++][1] = m[i].outcome.error;
        }
    qsort(pairs, (size_t)k, sizeof pairs[0], by_time);
    for (int i = 0; i < k; ++i) {
        d->x[FAMILIES][i] = pairs[i][0];
        d->y[FAMILIES][i] = pairs[i][1];
    }
    d->series[FAMILIES] = (im_plot_series){.x = d->x[FAMILIES],
                                           .y = d->y[FAMILIES],
                                           .n = k,
                                           .line = IM_PLOT_SOLID,
                                           .label = "Pareto frontier"};
}

static int write_plot(const char *path, const measured *smooth, int ns, const measured *rough, int nr)
{
    static panel_data data[2];
    fill_panel(&data[0], smooth, ns);
    fill_panel(&data[1], rough, nr);
    im_plot_panel panels[2];
    const char *titles[] = {"smooth cone vs closed form", "rough (h'_{rms} = 0.08) vs 4x, tol 10^{-11}"};
    const char *labels[] = {"(a)", "(b)"};
    for (int p = 0; p < 2; ++p)
        panels[p] =
            (im_plot_panel){.x = {IM_PLOT_LOG, 0.01, 3, "CPU time per solve (s, all threads)"},
                            .y = {IM_PLOT_LOG, 1e-7, 1, "relative error, max(N, A/A_{cone})"},
                            .series = data[p].series,
                            .series_count = FAMILIES + 1,
                            .label = labels[p],
                            .title = titles[p],
                            /* one legend for both panels, in the empty lower left of (a) (no point below 1e-4) */
                            .legend = p == 0 ? IM_PLOT_LEGEND_LOWER_LEFT : IM_PLOT_LEGEND_HIDDEN,
                            .legend_title = "knob varied (else 1x, tol 10^{-6}, 1 thread)"};
    im_plot plot = im_plot_default();
    plot.columns = 2;
    plot.panels = panels;
    plot.panel_width = 200;
    plot.panel_height = 170;
    plot.dpi = 200;
    return im_plot_write(&plot, path);
}

/* ---- the figure drawn again from a CSV (--plot) ---- */

/* The index of column name in the CSV's header line, -1 if absent. */
static int column_of(const char *header, const char *name)
{
    int index = 0;
    for (const char *at = header; at; at = strchr(at, ','), at = at ? at + 1 : NULL, ++index)
        if (strncmp(at, name, strlen(name)) == 0 && strchr(",\n", at[strlen(name)]))
            return index;
    return -1;
}

/* Field i of a CSV line (no quoting: this program's rows have none), copied into out. */
static void field_of(const char *line, int i, char *out, size_t size)
{
    for (; i > 0 && line; --i)
        line = strchr(line, ',') ? strchr(line, ',') + 1 : NULL;
    snprintf(out, size, "%.*s", line ? (int)strcspn(line, ",\n") : 0, line ? line : "");
}

/* A family's name as the plot matches it (families[]), NULL for the reference or an unknown one. */
static const char *known_family(const char *name)
{
    for (int f = 0; f < FAMILIES; ++f)
        if (strcmp(name, families[f]) == 0)
            return families[f];
    return NULL;
}

enum { CSV_PROBLEM, CSV_FAMILY, CSV_STATUS, CSV_ERROR, CSV_CPU, CSV_FRONTIER, CSV_COLUMNS };

/* One row into the smooth or rough list (the reference row left out): what the plot draws. */
static void read_row(const char *line, const int *columns, measured *smooth, int *ns, measured *rough, int *nr)
{
    char text[CSV_COLUMNS][64];
    for (int c = 0; c < CSV_COLUMNS; ++c)
        field_of(line, columns[c], text[c], sizeof text[c]);
    const char *family = known_family(text[CSV_FAMILY]);
    int is_rough = strcmp(text[CSV_PROBLEM], "rough") == 0;
    int *n = is_rough ? nr : ns;
    if (!family || *n >= MAX_CONFIGS)
        return;
    measured *m = is_rough ? &rough[(*n)++] : &smooth[(*n)++];
    *m = (measured){.config = {.family = family, .problem = is_rough ? ROUGH : SMOOTH},
                    .outcome = {.status = atoi(text[CSV_STATUS]),
                                .error = atof(text[CSV_ERROR]),
                                .cpu_seconds = atof(text[CSV_CPU])},
                    .on_frontier = atoi(text[CSV_FRONTIER])};
}

static int plot_from_csv(const char *csv, const char *png)
{
    static const char *const names[CSV_COLUMNS] = {"problem", "family", "status", "error", "cpu_s", "frontier"};
    static measured smooth[MAX_CONFIGS], rough[MAX_CONFIGS];
    int columns[CSV_COLUMNS], ns = 0, nr = 0, header = 0;
    char line[1024];
    FILE *f = fopen(csv, "r");
    if (!f)
        return im_fail(IM_EIO, "%s: %s", csv, strerror(errno));
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '#')
            continue;
        for (int c = 0; !header && c < CSV_COLUMNS; ++c)
            if ((columns[c] = column_of(line, names[c])) < 0) {
                fclose(f);
                return im_fail(IM_EFORMAT, "%s: no column %s: expected a CSV bench_tradeoff wrote", csv, names[c]);
            }
        if (header++)
            read_row(line, columns, smooth, &ns, rough, &nr);
    }
    fclose(f);
    if (ns == 0 || nr == 0)
        return im_fail(IM_EFORMAT, "%s: %d smooth and %d rough rows: expected both", csv, ns, nr);
    return write_plot(png, smooth, ns, rough, nr);
}

static void report(const config *c, const outcome *o, int status)
{
    fprintf(stderr,
            "%s %-10s %dx tol %.0e margin %2d crop %d threads %d: %.4f s (CPU %.4f s), error %.3e (N %.2e, A %.2e), "
            "p %.2e, symdiff %ld, %d it, rss %.1f MiB%s\n",
            problem_names[c->problem], c->family, c->refine, c->tol, c->margin, c->crop, c->threads, o->seconds,
            o->cpu_seconds, o->error, o->error_load, o->error_area, o->error_p_rms, o->symmetric_difference,
            o->iterations, o->rss_mib, status == IM_OK ? "" : " FAILED");
}

/* Measures every configuration ROUNDS times, round by round (so that a burst of load on the shared
 * machine hits different configurations in different rounds); wall time: the median of the
 * rounds' medians. The errors are deterministic. */
static int run_problem(enum problem p, const truth *t, measured *m)
{
    config list[MAX_CONFIGS];
    int n = config_list(p, list), failed[MAX_CONFIGS] = {0};
    static double seconds[MAX_CONFIGS][ROUNDS], cpu[MAX_CONFIGS][ROUNDS];
    for (int r = 0; r < ROUNDS; ++r)
        for (int i = 0; i < n; ++i) {
            m[i].config = list[i];
            failed[i] |= measure_in_child(&list[i], t, &m[i].outcome, NULL) != IM_OK;
            seconds[i][r] = m[i].outcome.seconds;
            cpu[i][r] = m[i].outcome.cpu_seconds;
        }
    for (int i = 0; i < n; ++i) {
        m[i].outcome.seconds = bench_median(seconds[i], ROUNDS);
        m[i].outcome.cpu_seconds = bench_median(cpu[i], ROUNDS);
        report(&list[i], &m[i].outcome, failed[i] ? IM_EIO : IM_OK);
    }
    mark_frontier(m, n);
    return n;
}
int main(int argc, char **argv)
{
    if (argc == 4 && strcmp(argv[1], "--plot") == 0) {
        int status = plot_from_csv(argv[2], argv[3]);
        if (status != IM_OK)
            fprintf(stderr, "bench_tradeoff: %s\n", im_last_error());
        return status == IM_OK ? 0 : 1;
    }
    if (argc != 3) {
        fprintf(stderr, "usage: bench_tradeoff CSV_PATH PNG_PATH\n       bench_tradeoff --plot CSV_PATH PNG_PATH\n");
        return 2;
    }
    double start = bench_now();
    load_at_start = load_average();
    static measured smooth[MAX_CONFIGS], rough[MAX_CONFIGS + 1];
    truth t;
    smooth_truth(&t);
    int ns = run_problem(SMOOTH, &t, smooth);
    outcome reference;
    int status = rough_truth(&t, &reference);
    if (status != IM_OK) {
        fprintf(stderr, "bench_tradeoff: rough reference: %s\n", im_last_error());
        return 1;
    }
    fprintf(stderr, "rough reference (4x, tol 1e-11, crop off): w %.6g, A/A_cone %.6g, n_p %ld, %.3f s\n",
            reference.approach, reference.area_ratio, reference.contact_patches, reference.seconds);
    int nr = run_problem(ROUGH, &t, rough);
    reference.error = reference.error_load = reference.error_area = 0;
    reference.symmetric_difference = 0;
    reference.load_at_w = t.load;
    rough[nr++] = (measured){rough_reference, reference, 0};
    static measured all[2 * MAX_CONFIGS + 1];
    memcpy(all, smooth, ns * sizeof *smooth);
    memcpy(all + ns, rough, nr * sizeof *rough);
    status = write_csv(argv[1], all, ns + nr);
    if (status == IM_OK)
        status = write_plot(argv[2], smooth, ns, rough, nr - 1);
    if (status != IM_OK) {
        fprintf(stderr, "bench_tradeoff: %s\n", im_last_error());
        return 1;
    }
    fprintf(stderr, "total %.1f s\n", bench_now() - start);
    return 0;
}
