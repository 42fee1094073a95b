/* Indentation histories of every surface of an ensemble ([loading] steps), and the paper's
 * figures drawn from them: Fig. 5 (A / delta^2 against w), Fig. 6 (N against w) and Fig. 7
 * (A / A_cone against N*, mean and +- one standard deviation). */
#include "indentmap/io.h"
#include "indentmap/plot.h"
#include "indentmap/status.h"
#include "indentmap/theory.h"
#include "front/front.h"
#include "scene/scene_internal.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static int allocate_history(scene_member *m, int steps)
{
    m->history = calloc((size_t)steps, sizeof *m->history);
    m->approach = calloc((size_t)steps, sizeof *m->approach);
    m->history_load = calloc((size_t)steps, sizeof *m->history_load);
    m->history_load_star = calloc((size_t)steps, sizeof *m->history_load_star);
    m->history_area_ratio = calloc((size_t)steps, sizeof *m->history_area_ratio);
    m->history_patches = calloc((size_t)steps, sizeof *m->history_patches);
    if (!m->history || !m->approach || !m->history_load || !m->history_load_star || !m->history_area_ratio ||
        !m->history_patches)
        return im_fail(IM_ENOMEM, "history: allocation failed");
    return IM_OK;
}

/* The figures' columns of the member's rows (m->history[0..m->steps)). */
static void spread_rows(scene_member *m)
{
    for (int i = 0; i < m->steps; ++i) {
        const im_step_result *r = &m->history[i].result;
        m->approach[i] = r->approach;
        m->history_load[i] = r->load;
        m->history_load_star[i] = r->load_star;
        m->history_patches[i] = r->contact_patches;
        m->history_area_ratio[i] = r->area_ratio;
    }
}

static int history_path(const im_scene *scene, const scene_member *m, char *path, size_t size)
{
    char relative[96];
    snprintf(relative, sizeof relative, "histories/member_%02d_%llu.csv", m->family, (unsigned long long)m->seed);
    return scene_output_path(scene, relative, path, size);
}

/* The rows of a history as written to its file, after the header line: the column names, then a
 * line per step (front.h: the history schema `indent` writes too), into *rows (caller frees). */
static int history_rows(const scene_member *m, char **rows, size_t *length)
{
    char *text = NULL;
    *rows = NULL;
    FILE *stream = open_memstream(&text, length);
    if (!stream)
        return im_fail(IM_ENOMEM, "history rows: allocation failed");
    fprintf(stream, "%s\n", HISTORY_COLUMNS);
    for (int i = 0; i < m->steps; ++i) {
        char line[HISTORY_LINE_MAX];
        history_format(&m->history[i], line, sizeof line);
        fputs(line, stream);
    }
    if (fclose(stream) != 0) {
        free(text);
        return im_fail(IM_ENOMEM, "history rows: allocation failed");
    }
    *rows = text;
    return IM_OK;
}

/* A history: a header line with the member, its key, its row count and the checksum of the rest
 * of the file (so that --resume can tell a whole history from one cut short or damaged), then
 * the rows. */
static int write_history(const im_scene *scene, const scene_member *m)
{
    char path[IM_SCENE_PATH];
    size_t length = 0;
    char *rows = NULL;
    int status = history_path(scene, m, path, sizeof path);
    if (status == IM_OK)
        status = history_rows(m, &rows, &length);
    im_atomic_file file;
    if (status == IM_OK)
        status = im_atomic_open(&file, path);
    if (status != IM_OK) {
        free(rows);
        return status;
    }
    fprintf(file.stream, "# family %d, h'rms %.17g, seed %llu, h_rms %.17g, key %016" PRIx64 ", rows %d, checksum %016"
            PRIx64 "\n", m->family, scene->slopes[m->family], (unsigned long long)m->seed, m->height_rms,
            scene_result_key(scene, m->family, m->seed, SCENE_RESULT_HISTORY), m->steps, scene_checksum(rows, length));
    fwrite(rows, 1, length, file.stream);
    free(rows);
    return im_atomic_commit(&file);
}

/* Whether a kept history's text is whole: its header's row count and checksum match the rows,
 * which parse with the one history reader (front.h: this version's columns, every row whole and
 * finite); on success its rows are in m. */
static int history_is_whole(char *text, scene_member *m, int capacity, uint64_t *key, char *why, size_t why_size)
{
    uint64_t checksum = 0;
    int rows = -1, used = 0;
    char *body = strchr(text, '\n');
    if (!body || sscanf(text, "# family %*d, h'rms %*g, seed %*u, h_rms %lf, key %" SCNx64 ", rows %d, checksum %"
                        SCNx64 "%n", &m->height_rms, key, &rows, &checksum, &used) != 4 || text + used != body) {
        snprintf(why, why_size, "its first line is not a history header with a row count and checksum; or an older version wrote it");
        return 0;
    }
    ++body;
    if (!history_parse(body, m->history, capacity, &m->steps, why, why_size))
        return 0;
    if (m->steps != rows || rows < 1) {
        snprintf(why, why_size, "%d rows where its header says %d", m->steps, rows);
        return 0;
    }
    if (scene_checksum(body, strlen(body)) != checksum) {
        snprintf(why, why_size, "its rows do not match the checksum of its header: edited");
        return 0;
    }
    spread_rows(m);
    return 1;
}

/* Reads a history an earlier run wrote; 0 if there is none, if it is damaged (cut short, a NaN,
 * a checksum that does not match), of another version's columns, or made from other inputs (its
 * key differs): those are solved again, with a notice. */
static int read_history(const im_scene *scene, scene_member *m)
{
    char path[IM_SCENE_PATH], why[160];
    if (history_path(scene, m, path, sizeof path) != IM_OK || access(path, F_OK) != 0)
        return 0;
    char *text = NULL;
    /* a row is at most HISTORY_LINE_MAX characters; far more is not a history */
    size_t limit = 4096 + (size_t)scene->step_count * HISTORY_LINE_MAX;
    if (im_read_text_file(path, limit, &text, NULL) != IM_OK)
        return scene_kept_damaged(path, im_last_error());
    uint64_t key = 0;
    int whole = history_is_whole(text, m, scene->step_count, &key, why, sizeof why);
    free(text);
    if (!whole) {
        m->steps = 0;
        return scene_kept_damaged(path, why);
    }
    return scene_key_matches(path, key, scene_result_key(scene, m->family, m->seed, SCENE_RESULT_HISTORY));
}

/* The target of step i: an approach, or the load at N* = steps[i]. */
static double step_target(const im_scene *scene, int i, double delta)
{
    return scene->control == IM_CONTROL_LOAD ? scene_load_for_n_star(scene, scene->steps[i], delta) : scene->steps[i];
}

/* Step i of a history. At load_star (load control) the table's state is taken instead of solving
 * it again (what the table does not keep is unknown in the row: -1 and NaN, front.h); without a
 * table, that step's force is kept for the panels. */
static int load_star_step(const im_scene *scene, im_indentation *run, scene_member *m, int i, double delta,
                          im_step_result *step)
{
    int at_load_star = i == scene_load_star_step(scene);
    const scene_member *known = m->at_load_star;
    if (at_load_star && known) {
        *step = (im_step_result){.approach = known->load_star_approach, .load = known->load, .load_star = known->load_star,
                                 .contact_patches = known->contact_patches, .area_ratio = known->area_ratio,
                                 .mean_pressure = NAN, .max_pressure = NAN, .iterations = -1, .convolutions = -1,
                                 .residual = NAN, .seconds = NAN, .coarse_iterations = -1};
        m->step_reused = 1;
        return IM_OK;
    }
    int status = im_indentation_step(run, step_target(scene, i, delta), step);
    if (status == IM_OK && at_load_star && scene_keeps_force(scene, m))
        status = im_indentation_fields(run, &m->force, NULL, NULL);
    return status;
}

/* Solves the member's history. Contact reaching the surface's edge fails it (IM_EEDGE, with the
 * step): the scene asked for every step, and the pre-flight check (limits.c) refuses the steps
 * whose smooth contact leaves the surface before any work. Each step is measured as `indent`
 * measures it (front.h: history_measure), with the theory of the family's h'rms. */
static int solve_history(const im_scene *scene, const im_scene_run_options *run_options, scene_member *m,
                         const im_field *surface)
{
    im_indenter punch = scene_punch(scene);
    im_theory_interface rough = scene_theory_interface(scene, scene->slopes[m->family]);
    im_solver_options options = scene_solver_options(scene);
    im_indentation *run = NULL;
    double largest = step_target(scene, scene->step_count - 1, surface->delta);
    int status = im_indentation_create(surface, &punch, scene->control, largest, &options, &run);
    for (int i = 0; i < scene->step_count && status == IM_OK; ++i) {
        if (scene_stop_signal(run_options)) {
            status = IM_EINTERRUPTED; /* abandoned: the caller reports the interruption */
            break;
        }
        int from_table = i == scene_load_star_step(scene) && m->at_load_star;
        status = load_star_step(scene, run, m, i, surface->delta, &m->history[i].result);
        if (status == IM_EEDGE) /* a history short of the scene's steps would be drawn as if whole */
            im_fail_context(status, "step %d of %d (%s %g; the scene asks for every step: use a larger grid (n) or "
                            "smaller steps)", i + 1,
                            scene->step_count, scene->control == IM_CONTROL_LOAD ? "N*" : "approach", scene->steps[i]);
        if (status == IM_OK) /* a step taken from the table has no state of the run to measure */
            status = history_measure(&punch, &rough, from_table ? NULL : run, m->history, i);
        if (status == IM_OK)
            m->steps = i + 1;
    }
    im_indentation_free(run);
    spread_rows(m);
    return status;
}

int scene_history_member(const im_scene *scene, const im_scene_run_options *options, scene_member *m)
{
    int status = allocate_history(m, scene->step_count);
    if (status != IM_OK)
        return status;
    if (options->resume && read_history(scene, m)) {
        m->origin = SCENE_READ_BACK;
        return IM_OK;
    }
    im_field *surface = NULL;
    status = scene_surface(scene, m->family, m->seed, &surface);
    im_surface_stats stats;
    if (status == IM_OK)
        status = im_surface_statistics(surface, &stats);
    if (status == IM_OK) {
        m->height_rms = stats.height_rms;
        status = solve_history(scene, options, m, surface);
    }
    im_field_free(surface);
    return status == IM_OK ? write_history(scene, m) : status;
}

/* ---- figures ---- */

enum { THEORY_POINTS = 101, COMMON_POINTS = 40 };

typedef struct figure_data {
    im_plot_panel panels[IM_SCENE_MAX_FAMILIES];
    im_plot_series series[IM_SCENE_MAX_FAMILIES][IM_SCENE_MAX_FAMILIES + 3];
    char titles[IM_SCENE_MAX_FAMILIES][64];
    double theory_w[THEORY_POINTS], theory_smooth[THEORY_POINTS];
    double theory_eq12[IM_SCENE_MAX_FAMILIES][THEORY_POINTS];
} figure_data;

static double cone_cot(const im_scene *scene) { return 1.0 / tan(scene->alpha_degrees * M_PI / 180.0); }

static double largest_approach(const scene_member *members, int count)
{
    double w = 0.0;
    for (int i = 0; i < count; ++i)
        for (int k = 0; k < members[i].steps; ++k)
            w = fmax(w, members[i].approach[k]);
    return w > 0.0 ? w : 1.0;
}

/* A smooth cone's closed forms against w (Love): A / delta^2 = pi a^2 / delta^2, a = 2 w / (pi cot alpha),
 * or N / (E* delta^2) = 2 w^2 / (pi delta^2 cot alpha). */
static void fill_theory(const im_scene *scene, figure_data *d, double w_max, int load, double delta)
{
    double c = cone_cot(scene);
    for (int i = 0; i < THEORY_POINTS; ++i) {
        double w = w_max * i / (THEORY_POINTS - 1), a = 2.0 * w / (M_PI * c);
        d->theory_w[i] = w;
        d->theory_smooth[i] = load ? 2.0 * w * w / (M_PI * c * delta * delta) : M_PI * a * a / (delta * delta);
    }
}

static im_plot_series thin_line(const double *x, const double *y, int n, int family, int families)
{
    im_plot_series s = {.x = x, .y = y, .n = n, .line = IM_PLOT_SOLID, .line_width = 0.5};
    im_plot_family_color(family, families, s.color);
    return s;
}

/* Fig. 5 (load = 0: A / delta^2) or Fig. 6 (load = 1: N / (E* delta^2)) against w, a panel per
 * family: every surface thin, the smooth theory thick, and for Fig. 5 eq. (12) dashed. */
static int plot_against_approach(const im_scene *scene, const scene_member *members, int count, int load)
{
    static figure_data d;
    memset(&d, 0, sizeof d);
    double delta = scene->surface.delta, e_star = scene->modulus;
    fill_theory(scene, &d, largest_approach(members, count), load, delta);
    double *scaled = malloc(sizeof *scaled * (size_t)count * (size_t)scene->step_count);
    if (!scaled)
        return im_fail(IM_ENOMEM, "fig5/fig6: allocation failed");
    for (int f = 0; f < scene->family_count; ++f) {
        int n = 0;
        for (int i = 0; i < count; ++i) {
            const scene_member *m = &members[i];
            double *y = scaled + (size_t)i * scene->step_count;
            if (m->family != f || m->steps == 0 || n >= IM_SCENE_MAX_FAMILIES)
                continue;
            for (int k = 0; k < m->steps; ++k)
                y[k] = load ? m->history_load[k] / (e_star * delta * delta) : (double)m->history_patches[k];
            d.series[f][n] = thin_line(m->approach, y, m->steps, f, scene->family_count);
            d.series[f][n].label = n == 0 ? "surfaces" : NULL;
            ++n;
        }
        im_plot_series smooth = {.x = d.theory_w, .y = d.theory_smooth, .n = THEORY_POINTS, .line = IM_PLOT_SOLID,
                                 .line_width = 2.0, .label = "smooth (Love)"};
        d.series[f][n++] = smooth;
        if (!load && scene->slopes[f] > 0.0) {
            double ratio = scene_eq12(scene, scene->slopes[f], NULL);
            for (int i = 0; i < THEORY_POINTS; ++i)
                d.theory_eq12[f][i] = ratio * d.theory_smooth[i];
            im_plot_series eq12 = {.x = d.theory_w, .y = d.theory_eq12[f], .n = THEORY_POINTS,
                                   .line = IM_PLOT_DASHED, .line_width = 1.0, .label = "eq. (12)"};
            im_plot_palette(1, eq12.color);
            d.series[f][n++] = eq12;
        }
        scene_family_title(scene, f, d.titles[f], sizeof d.titles[f]);
        d.panels[f] = (im_plot_panel){.x = {IM_PLOT_LINEAR, 0, 0, "approach w / δ"},
                                      .y = {IM_PLOT_LINEAR, 0, 0, load ? "load N / (E* δ²)" : "contact area A / δ²"},
                                      .series = d.series[f], .series_count = n, .title = d.titles[f],
                                      .legend = f == scene->family_count - 1 ? IM_PLOT_LEGEND_UPPER_LEFT
                                                                             : IM_PLOT_LEGEND_HIDDEN};
    }
    im_plot plot = im_plot_default();
    plot.columns = scene_panel_columns(scene->family_count);
    plot.rows = scene->family_count / plot.columns;
    plot.panels = d.panels;
    int status = scene_write_png_pdf(scene, load ? "fig6" : "fig5", scene_draw_plot, &plot);
    free(scaled);
    return status;
}

/* Linear interpolation of y(x) at x0 on increasing x; NaN outside. */
static double interpolate(const double *x, const double *y, int n, double x0)
{
    for (int k = 1; k < n; ++k)
        if (x0 >= x[k - 1] && x0 <= x[k])
            return x[k] > x[k - 1] ? y[k - 1] + (y[k] - y[k - 1]) * (x0 - x[k - 1]) / (x[k] - x[k - 1]) : y[k];
    return NAN;
}

/* Fig. 7: A / A_cone against N* for each rough family: the mean over its surfaces (solid) and
 * +- one standard deviation (dotted), on the N* range every surface reached. */
static int plot_area_ratio_against_load(const im_scene *scene, const scene_member *members, int count)
{
    static figure_data d;
    static double grid[IM_SCENE_MAX_FAMILIES][COMMON_POINTS], mean[IM_SCENE_MAX_FAMILIES][COMMON_POINTS];
    static double lo[IM_SCENE_MAX_FAMILIES][COMMON_POINTS], hi[IM_SCENE_MAX_FAMILIES][COMMON_POINTS];
    memset(&d, 0, sizeof d);
    int panels = 0;
    for (int f = 0; f < scene->family_count; ++f) {
        if (!(scene->slopes[f] > 0.0))
            continue;
        double start = 0.0, end = INFINITY;
        for (int i = 0; i < count; ++i)
            if (members[i].family == f && members[i].steps > 1) {
                start = fmax(start, members[i].history_load_star[0]);
                end = fmin(end, members[i].history_load_star[members[i].steps - 1]);
            }
        if (!(end > start))
            continue;
        for (int k = 0; k < COMMON_POINTS; ++k) {
            double x = start + (end - start) * k / (COMMON_POINTS - 1), sum = 0, sum_sq = 0;
            int n = 0;
            for (int i = 0; i < count; ++i) {
                const scene_member *m = &members[i];
                double y = m->family == f ? interpolate(m->history_load_star, m->history_area_ratio, m->steps, x) : NAN;
                if (isnan(y))
                    continue;
                sum += y;
                sum_sq += y * y;
                ++n;
            }
            double mu = sum / n, sd = n > 1 ? sqrt(fmax(0.0, (sum_sq - n * mu * mu) / (n - 1))) : 0.0;
            grid[panels][k] = x;
            mean[panels][k] = mu;
            lo[panels][k] = mu - sd;
            hi[panels][k] = mu + sd;
        }
        im_plot_series series[3] = {
            {.x = grid[panels], .y = mean[panels], .n = COMMON_POINTS, .line = IM_PLOT_SOLID, .label = "mean"},
            {.x = grid[panels], .y = lo[panels], .n = COMMON_POINTS, .line = IM_PLOT_DOTTED, .label = "± 1 sd"},
            {.x = grid[panels], .y = hi[panels], .n = COMMON_POINTS, .line = IM_PLOT_DOTTED}};
        for (int s = 0; s < 3; ++s)
            d.series[panels][s] = series[s];
        scene_family_title(scene, f, d.titles[panels], sizeof d.titles[panels]);
        d.panels[panels] = (im_plot_panel){.x = {IM_PLOT_LINEAR, 0, 0, "N* = 2N / (δ² E* cot α)"},
                                           .y = {IM_PLOT_LINEAR, 0, 0, "A / A_{cone}"}, .series = d.series[panels],
                                           .series_count = 3, .title = d.titles[panels]};
        ++panels;
    }
    if (panels == 0)
        return im_fail(IM_EINVAL, "%s: fig7 needs a rough family whose surfaces share a range of N*", scene->path);
    im_plot plot = im_plot_default();
    plot.columns = scene_panel_columns(panels);
    plot.rows = panels / plot.columns;
    plot.panels = d.panels;
    return scene_write_png_pdf(scene, "fig7", scene_draw_plot, &plot);
}

/* Pastewka and Robbins' three regimes for a sphere: A / A_Hertz against N / N_c for each rough
 * family (every surface thin) beside eq. (3) and the integral of the local density of contact
 * with Hertz's pressure, on log axes: one asperity at small loads, the linear rough regime, and
 * the crossover to Hertz above N_c. */
static int plot_sphere_regimes(const im_scene *scene, const scene_member *members, int count)
{
    static figure_data d;
    static double theory_x[IM_SCENE_MAX_FAMILIES][THEORY_POINTS], theory_y[IM_SCENE_MAX_FAMILIES][THEORY_POINTS];
    static double theory_gamma[IM_SCENE_MAX_FAMILIES][THEORY_POINTS];
    memset(&d, 0, sizeof d);
    double *scaled = malloc(sizeof *scaled * (size_t)count * (size_t)scene->step_count);
    if (!scaled)
        return im_fail(IM_ENOMEM, "sphere figure: allocation failed");
    int panels = 0, status = IM_OK;
    for (int f = 0; f < scene->family_count && status == IM_OK; ++f) {
        if (!(scene->slopes[f] > 0.0))
            continue;
        im_theory_interface rough = im_theory_interface_default(scene->slopes[f]);
        rough.e_star = scene->modulus;
        double n_c = NAN, lo = INFINITY, hi = 0.0;
        status = im_theory_sphere_crossover_load(&rough, scene->radius, &n_c);
        int n = 0;
        for (int i = 0; i < count && status == IM_OK; ++i) {
            const scene_member *m = &members[i];
            double *x = scaled + (size_t)i * scene->step_count;
            if (m->family != f || m->steps == 0 || n >= IM_SCENE_MAX_FAMILIES)
                continue;
            for (int k = 0; k < m->steps; ++k) {
                x[k] = m->history_load[k] / n_c;
                lo = fmin(lo, x[k]);
                hi = fmax(hi, x[k]);
            }
            d.series[panels][n] = thin_line(x, m->history_area_ratio, m->steps, f, scene->family_count);
            d.series[panels][n].label = n == 0 ? "surfaces" : NULL;
            ++n;
        }
        for (int k = 0; k < THEORY_POINTS && status == IM_OK && hi > lo; ++k) {
            double load = n_c * lo * pow(hi / lo, (double)k / (THEORY_POINTS - 1));
            im_theory_step theory;
            status = scene_history_theory_row(scene, scene->slopes[f], 0.0, load, &theory);
            theory_x[panels][k] = load / n_c;
            theory_y[panels][k] = theory.area_ratio_constant;
            theory_gamma[panels][k] = theory.area_ratio_gamma;
        }
        im_plot_series eq3 = {.x = theory_x[panels], .y = theory_y[panels], .n = THEORY_POINTS,
                              .line = IM_PLOT_SOLID, .line_width = 2.0, .label = "eq. (3)"};
        d.series[panels][n++] = eq3;
        im_plot_series gamma = {.x = theory_x[panels], .y = theory_gamma[panels], .n = THEORY_POINTS,
                                .line = IM_PLOT_DASHED, .line_width = 2.0, .label = "γ integral"};
        d.series[panels][n++] = gamma;
        scene_family_title(scene, f, d.titles[panels], sizeof d.titles[panels]);
        d.panels[panels] = (im_plot_panel){.x = {IM_PLOT_LOG, 0, 0, "N / N_{c}"},
                                           .y = {IM_PLOT_LOG, 0, 0, "A / A_{Hertz}"}, .series = d.series[panels],
                                           .series_count = n, .title = d.titles[panels],
                                           .legend = IM_PLOT_LEGEND_LOWER_RIGHT};
        ++panels;
    }
    if (status == IM_OK && panels == 0)
        status = im_fail(IM_EINVAL, "%s: plots = sphere needs a rough family", scene->path);
    if (status == IM_OK) {
        im_plot plot = im_plot_default();
        plot.columns = scene_panel_columns(panels);
        plot.rows = panels / plot.columns;
        plot.panels = d.panels;
        status = scene_write_png_pdf(scene, "sphere_regimes", scene_draw_plot, &plot);
    }
    free(scaled);
    return status;
}

void scene_link_table(const im_scene *scene, const scene_reuse *reuse, scene_member *members, int count)
{
    if (scene_load_star_step(scene) < 0)
        return;
    for (int i = 0; i < count; ++i)
        for (int k = 0; k < reuse->table_count; ++k)
            if (reuse->table[k].family == members[i].family && reuse->table[k].seed == members[i].seed &&
                reuse->table[k].status == IM_OK)
                members[i].at_load_star = &reuse->table[k];
}

static void report_histories(const im_scene_run_options *options, const scene_member *members, int count)
{
    int reused = 0;
    for (int i = 0; i < count; ++i)
        reused += members[i].step_reused;
    scene_report_origins(options, "histories", members, count);
    if (reused)
        scene_progress(options, "histories: %d steps at load_star taken from the table", reused);
}

int scene_run_histories(const im_scene *scene, const im_scene_run_options *options, scene_reuse *reuse)
{
    if (scene->step_count < 1)
        return im_fail(IM_EINVAL, "%s: plots fig5, fig6 and fig7 need [loading] steps (approaches, or N* "
                       "values with control = load)", scene->path);
    scene_member *members = NULL;
    int count = 0;
    int status = scene_ensemble_prepare(scene, "histories", &members, &count);
    if (status == IM_OK) {
        scene_link_table(scene, reuse, members, count);
        scene_progress(options, "histories: %d surfaces x %d steps", count, scene->step_count);
        status = scene_ensemble_run(scene, options, members, count, scene_history_member);
    }
    if (status == IM_OK)
        report_histories(options, members, count);
    scene_reuse_take_forces(reuse, members, count);
    if (status == IM_OK && scene_wants_plot(scene, IM_SCENE_PLOT_FIG5))
        status = plot_against_approach(scene, members, count, 0);
    if (status == IM_OK && scene_wants_plot(scene, IM_SCENE_PLOT_FIG6))
        status = plot_against_approach(scene, members, count, 1);
    if (status == IM_OK && scene_wants_plot(scene, IM_SCENE_PLOT_FIG7))
        status = plot_area_ratio_against_load(scene, members, count);
    if (status == IM_OK && scene_wants_plot(scene, IM_SCENE_PLOT_SPHERE))
        status = plot_sphere_regimes(scene, members, count);
    scene_members_free(members, count);
    return status;
}
