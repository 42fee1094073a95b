/* Indentation histories of every surface of an ensemble ([loading] steps), gathered for the
 * paper's figures drawn from them (paper/history_figures.c): Fig. 5 (A / delta^2 against w),
 * Fig. 6 (N against w) and Fig. 7 (A / A_cone against N*, mean and +- one standard deviation). */
#include "indentmap/io.h"
#include "scene/contents.h"
#include "indentmap/status.h"
#include "indentmap/theory.h"
#include "front/front.h"
#include "paper/figures.h"
#include "scene/ensemble.h"
#include "scene/histories.h"
#include "scene/history_theory.h"
#include "scene/key.h"
#include "scene/labels.h"
#include "scene/outputs.h"
#include "scene/periodic.h"
#include "scene/plots.h"
#include "scene/progress.h"
#include "scene/punch.h"
#include "scene/surfaces.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static int allocate_history(scene_member *m, int steps)
{
    m->history = calloc((size_t)steps, sizeof *m->history);
    return m->history ? IM_OK : im_fail(IM_ENOMEM, "history: allocation failed");
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
    fprintf(stream, "%s\n", im_history_columns());
    for (int i = 0; i < m->steps; ++i) {
        char line[IM_HISTORY_LINE_MAX];
        im_history_format(&m->history[i], line, sizeof line);
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
    fprintf(file.stream,
            "# family %d, h'rms %.17g, seed %llu, h_rms %.17g, key %016" PRIx64 ", rows %d, checksum %016" PRIx64
            "\n",
            m->family, scene->slopes[m->family], (unsigned long long)m->seed, m->height_rms,
            scene_result_key(scene, m->family, m->seed, SCENE_RESULT_HISTORY), m->steps,
            scene_checksum(rows, length));
    fwrite(rows, 1, length, file.stream);
    free(rows);
    return im_atomic_commit(&file);
}

/* Whether a kept history's text is whole: its header's row count and checksum match the rows,
 * which parse with the one history reader (front.h: this version's columns, every row whole and
 * finite); on success its rows are in m. */
static int history_is_whole(char *text, int area, scene_member *m, int capacity, uint64_t *key, char *why,
                            size_t why_size)
{
    uint64_t checksum = 0;
    int rows = -1, used = 0;
    char *body = strchr(text, '\n');
    if (!body ||
        sscanf(text, "# family %*d, h'rms %*g, seed %*u, h_rms %lf, key %" SCNx64 ", rows %d, checksum %" SCNx64 "%n",
               &m->height_rms, key, &rows, &checksum, &used) != 4 ||
        text + used != body) {
        snprintf(why, why_size,
                 "its first line is not a history header with a row count and checksum; or an older version wrote "
                 "it");
        return 0;
    }
    ++body;
    if (!im_history_parse(body, area, m->history, capacity, &m->steps, why, why_size))
        return 0;
    if (m->steps != rows || rows < 1) {
        snprintf(why, why_size, "%d rows where its header says %d", m->steps, rows);
        return 0;
    }
    if (scene_checksum(body, strlen(body)) != checksum) {
        snprintf(why, why_size, "its rows do not match the checksum of its header: edited");
        return 0;
    }
    return 1;
}

/* Reads a history an earlier run wrote; 0 if there is none, if it is damaged (cut short, a NaN,
 * a checksum that does not match), of another version's columns, or made from other inputs (its
 * key differs): those are solved again, with a notice. */
static int read_history(const im_scene *scene, const im_scene_run_options *options, scene_member *m)
{
    char path[IM_SCENE_PATH], why[160];
    if (history_path(scene, m, path, sizeof path) != IM_OK || access(path, F_OK) != 0)
        return 0;
    char *text = NULL;
    /* a row is at most IM_HISTORY_LINE_MAX characters; far more is not a history */
    size_t limit = 4096 + (size_t)scene->step_count * IM_HISTORY_LINE_MAX;
    if (im_read_text_file(path, limit, &text, NULL) != IM_OK)
        return scene_kept_damaged(options, path, im_last_error());
    uint64_t key = 0;
    int area = scene->periodic                                  ? IM_HISTORY_AREA_CELL
               : scene_punch(scene).kind != IM_PUNCH_PROFILE_2D ? IM_HISTORY_AREA_SMOOTH
                                                                : IM_HISTORY_AREA_NONE;
    int whole = history_is_whole(text, area, m, scene->step_count, &key, why, sizeof why);
    free(text);
    if (!whole) {
        m->steps = 0;
        return scene_kept_damaged(options, path, why);
    }
    return scene_key_matches(options, path, key, scene_result_key(scene, m->family, m->seed, SCENE_RESULT_HISTORY));
}

/* The target of step i: an approach, the load at N* = steps[i] (the load steps[i] itself with adhesion), or
 * in the periodic mode the load of the mean pressure steps[i] over the cell (as `indent --periodic
 * --pressure`) or the mean gap steps[i]. */
static double step_target(const im_scene *scene, int i, const im_field *surface)
{
    if (scene->control == IM_CONTROL_MEAN_GAP || scene_steps_are_loads(scene))
        return scene->steps[i];
    if (scene->periodic)
        return scene->steps[i] * periodic_cell_area(surface);
    return scene->control == IM_CONTROL_LOAD ? scene_load_for_n_star(scene, scene->steps[i], surface->delta)
                                             : scene->steps[i];
}

double scene_largest_step(const im_scene *scene, const im_field *surface)
{
    double largest = 0; /* a history with a hardness may go down, one with adhesion below 0 */
    for (int i = 0; i < scene->step_count; ++i)
        largest = fmax(largest, fabs(step_target(scene, i, surface)));
    return largest;
}

/* What a step of the scene's list is. */
static const char *step_name(const im_scene *scene)
{
    if (scene->periodic)
        return scene->control == IM_CONTROL_MEAN_GAP ? "mean gap" : "mean pressure";
    if (scene_steps_are_loads(scene))
        return "load";
    return scene->control == IM_CONTROL_LOAD ? "N*" : "approach";
}

/* Step i of a history. At load_star (load control) the table's state is taken instead of solving
 * it again (what the table does not keep is unknown in the row: -1 and NaN, front.h); without a
 * table, that step's force is kept for the panels. */
static int load_star_step(const im_scene *scene, im_indentation *run, scene_member *m, int i, const im_field *surface,
                          im_step_result *step)
{
    int at_load_star = i == scene_load_star_step(scene);
    const scene_member *known = m->at_load_star;
    /* with a hardness the step is solved all the same: the run must remember its plastic flow */
    if (at_load_star && known && !(scene->hardness > 0)) {
        *step = (im_step_result){.approach = known->load_star_approach,
                                 .load = known->load,
                                 .load_star = known->load_star,
                                 .contact_patches = known->contact_patches,
                                 .area_ratio = known->area_ratio,
                                 .mean_pressure = NAN,
                                 .max_pressure = NAN,
                                 .iterations = -1,
                                 .convolutions = -1,
                                 .residual = NAN,
                                 .seconds = NAN,
                                 .coarse_iterations = -1,
                                 .yielding_patches = 0,
                                 .plastic_depth = 0,
                                 .plastic_work = 0,
                                 .residual_approach = 0,
                                 .mean_gap = NAN};
        m->step_reused = 1;
        return IM_OK;
    }
    int status = im_indentation_step(run, step_target(scene, i, surface), step);
    if (status == IM_OK && at_load_star && scene_keeps_force(scene, m))
        status = im_indentation_fields(run, &m->force, NULL, NULL);
    return status;
}

/* Solves the member's history. Contact reaching the surface's edge fails it (IM_EEDGE, with the
 * step): the scene asked for every step, and the pre-flight check (limits.c) refuses the steps
 * whose smooth contact leaves the surface before any work. Each step is measured as `indent`
 * measures it (history.h: im_history_measure), with the theory of the family's h'rms. */
static int solve_history(const im_scene *scene, const im_scene_run_options *run_options, scene_member *m,
                         const im_field *surface)
{
    im_indenter punch = scene_member_punch(scene, surface);
    im_theory_interface rough = scene_theory_interface(scene, scene->slopes[m->family]);
    const im_theory_interface *theory = scene->periodic ? NULL : &rough; /* as indent: none for a cell */
    im_solver_options options = scene_solver_options(scene);
    im_indentation *run = NULL;
    int status = im_indentation_create(surface, &punch, scene->control, scene_largest_step(scene, surface), &options,
                                       &run);
    for (int i = 0; i < scene->step_count && status == IM_OK; ++i) {
        if (scene_stop_signal(run_options)) {
            status = IM_EINTERRUPTED; /* abandoned: the caller reports the interruption */
            break;
        }
        int from_table = i == scene_load_star_step(scene) && m->at_load_star;
        status = load_star_step(scene, run, m, i, surface, &m->history[i].result);
        if (status == IM_EEDGE) /* a history short of the scene's steps would be drawn as if whole */
            im_fail_context(status,
                            "step %d of %d (%s %g; the scene asks for every step: use a larger grid (n) or "
                            "smaller steps)",
                            i + 1, scene->step_count, step_name(scene), scene->steps[i]);
        else if (status != IM_OK && status != IM_EINTERRUPTED &&
                 scene_steps_are_loads(scene)) /* past the pull-off: which step of the list */
            im_fail_context(status, "step %d of %d (load %g)", i + 1, scene->step_count, scene->steps[i]);
        if (status == IM_OK) /* a step taken from the table has no state of the run to measure */
            status = im_history_measure(&punch, theory, from_table ? NULL : run, options.tol, m->history, i);
        if (status == IM_OK && scene_periodic_writes_steps(scene, m))
            status = scene_periodic_step_files(scene, m, run, i + 1, surface);
        if (status == IM_OK)
            m->steps = i + 1;
    }
    im_indentation_free(run);
    return status;
}

int scene_history_member_kept(const im_scene *scene, const im_scene_run_options *options, scene_member *m)
{
    if (!m->history && allocate_history(m, scene->step_count) != IM_OK)
        return 0;
    return !scene_periodic_writes_steps(scene, m) && read_history(scene, options, m);
}

int scene_history_member(const im_scene *scene, const im_scene_run_options *options, scene_member *m)
{
    int status = allocate_history(m, scene->step_count);
    if (status != IM_OK)
        return status;
    if (options->resume && scene_history_member_kept(scene, options, m)) {
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

/* ---- figures (paper/figures.h builds them from the histories gathered here) ---- */

enum { THEORY_POINTS = 101 };
_Static_assert((int)PAPER_MAX_PANELS >= (int)IM_SCENE_MAX_FAMILIES, "a figure has a panel per family");

/* The members' histories and the families' titles, as the figure builders take them: the columns
 * they draw, read from the members' rows while the figures are made. */
typedef struct gathered_histories {
    paper_histories h;
    char titles[IM_SCENE_MAX_FAMILIES][64];
    const char *title_of[IM_SCENE_MAX_FAMILIES];
    double eq12[IM_SCENE_MAX_FAMILIES];
    double *columns; /* approach, load, load_star and area_ratio of every member's steps, in turn */
    long *patches;
} gathered_histories;

static double cone_cot(const im_scene *scene) { return 1.0 / tan(scene->alpha_degrees * M_PI / 180.0); }

static void free_gathered(gathered_histories *g)
{
    if (g) {
        free((void *)g->h.members);
        free(g->columns);
        free(g->patches);
    }
    free(g);
}

/* The figure's view of member m, its columns at offset `at` of g's (total steps in all). */
static paper_history member_columns(gathered_histories *g, const scene_member *m, size_t at, size_t total)
{
    double *approach = g->columns + at, *load = approach + total, *load_star = load + total;
    double *area_ratio = load_star + total;
    for (int i = 0; i < m->steps; ++i) {
        const im_step_result *r = &m->history[i].result;
        approach[i] = r->approach;
        load[i] = r->load;
        load_star[i] = r->load_star;
        area_ratio[i] = r->area_ratio;
        g->patches[at + (size_t)i] = r->contact_patches;
    }
    return (paper_history){m->family, m->steps, approach, load, load_star, area_ratio, g->patches + at};
}

/* *out (freed with free_gathered) holds the members' columns. */
static int gather_histories(const im_scene *scene, const scene_member *members, int count, gathered_histories **out)
{
    size_t total = 0;
    for (int i = 0; i < count; ++i)
        total += (size_t)members[i].steps;
    gathered_histories *g = calloc(1, sizeof *g);
    paper_history *views = g ? calloc((size_t)count + 1, sizeof *views) : NULL;
    if (g) {
        g->h.members = views;
        g->columns = calloc(4 * total + 1, sizeof *g->columns);
        g->patches = calloc(total + 1, sizeof *g->patches);
    }
    if (!views || !g->columns || !g->patches) {
        free_gathered(g);
        return im_fail(IM_ENOMEM, "history figures: allocation failed");
    }
    size_t at = 0;
    for (int i = 0; i < count; ++i) {
        views[i] = member_columns(g, &members[i], at, total);
        at += (size_t)members[i].steps;
    }
    for (int f = 0; f < scene->family_count; ++f) {
        scene_family_title(scene, f, g->titles[f], sizeof g->titles[f]);
        g->title_of[f] = g->titles[f];
        g->eq12[f] = scene->slopes[f] > 0.0 ? scene_eq12(scene, scene->slopes[f], NULL) : NAN;
    }
    g->h = (paper_histories){.source = scene->path,
                             .family_count = scene->family_count,
                             .slopes = scene->slopes,
                             .titles = g->title_of,
                             .eq12 = g->eq12,
                             .members = views,
                             .count = count,
                             .delta = scene->surface.delta,
                             .e_star = scene->modulus,
                             .cot_alpha = cone_cot(scene)};
    *out = g;
    return IM_OK;
}

static int draw_against_approach(const im_scene *scene, const void *h, const paper_file *file)
{
    (void)scene;
    return paper_figure_against_approach(h, 0, file);
}

static int draw_load_against_approach(const im_scene *scene, const void *h, const paper_file *file)
{
    (void)scene;
    return paper_figure_against_approach(h, 1, file);
}

static int draw_area_ratio_against_load(const im_scene *scene, const void *h, const paper_file *file)
{
    (void)scene;
    return paper_figure_area_ratio_against_load(h, file);
}

/* Fig. 5 (load = 0) or Fig. 6 (load = 1). */
static int plot_against_approach(const im_scene *scene, const gathered_histories *g, int load)
{
    return scene_write_png_pdf(scene, load ? "fig6" : "fig5",
                               load ? draw_load_against_approach : draw_against_approach, &g->h);
}

/* Fig. 7 and fig7.csv, the numbers it plots. */
static int plot_area_ratio_against_load(const im_scene *scene, const gathered_histories *g)
{
    im_atomic_file file;
    int status = scene_open_output(scene, "fig7.csv", &file);
    if (status != IM_OK)
        return status;
    status = paper_write_area_ratio_statistics(&g->h, file.stream);
    if (status != IM_OK) {
        im_atomic_abort(&file);
        return status;
    }
    status = im_atomic_commit(&file);
    return status == IM_OK ? scene_write_png_pdf(scene, "fig7", draw_area_ratio_against_load, &g->h) : status;
}

/* The sphere's rough families: N_c and the theory over the range of N / N_c their surfaces span. */
typedef struct sphere_theory {
    paper_sphere_family families[IM_SCENE_MAX_FAMILIES];
    double x[IM_SCENE_MAX_FAMILIES][THEORY_POINTS], constant[IM_SCENE_MAX_FAMILIES][THEORY_POINTS];
    double gamma[IM_SCENE_MAX_FAMILIES][THEORY_POINTS];
    int count;
    const paper_histories *h;
} sphere_theory;

/* The range of N / N_c over the surfaces of family f that the figure draws. */
static void sphere_load_range(const paper_histories *h, int f, double n_c, double *lo, double *hi)
{
    int n = 0;
    *lo = INFINITY, *hi = 0.0;
    for (int i = 0; i < h->count; ++i) {
        const paper_history *m = &h->members[i];
        if (m->family != f || m->steps == 0 || n >= PAPER_MAX_SURFACE_LINES)
            continue;
        for (int k = paper_first_resolved_step(m); k < m->steps; ++k) {
            *lo = fmin(*lo, m->load[k] / n_c);
            *hi = fmax(*hi, m->load[k] / n_c);
        }
        ++n;
    }
}

static int sphere_family(const im_scene *scene, const paper_histories *h, int f, sphere_theory *t)
{
    int p = t->count;
    im_theory_interface rough = im_theory_interface_default(scene->slopes[f]);
    rough.e_star = scene->modulus;
    double n_c = NAN, lo, hi;
    int status = im_theory_sphere_crossover_load(&rough, scene->radius, &n_c);
    if (status == IM_OK)
        sphere_load_range(h, f, n_c, &lo, &hi);
    if (status == IM_OK && !(hi > lo))
        status = im_fail(IM_EINVAL,
                         "%s: plots = sphere: the surfaces of h'rms %g reach %d contact patches (the "
                         "grid's resolution) at fewer than two of [loading] steps: raise the loads",
                         scene->path, scene->slopes[f], PAPER_MIN_PATCHES);
    for (int k = 0; k < THEORY_POINTS && status == IM_OK && hi > lo; ++k) {
        double load = n_c * lo * pow(hi / lo, (double)k / (THEORY_POINTS - 1));
        im_theory_step theory;
        status = scene_history_theory_row(scene, scene->slopes[f], 0.0, load, &theory);
        t->x[p][k] = load / n_c;
        t->constant[p][k] = theory.area_ratio_constant;
        t->gamma[p][k] = theory.area_ratio_gamma;
    }
    t->families[p] = (paper_sphere_family){f, n_c, THEORY_POINTS, t->x[p], t->constant[p], t->gamma[p]};
    ++t->count;
    return status;
}

static int draw_sphere_regimes(const im_scene *scene, const void *data, const paper_file *file)
{
    (void)scene;
    const sphere_theory *t = data;
    return paper_figure_sphere_regimes(t->h, t->families, t->count, file);
}

/* Pastewka and Robbins' three regimes for a sphere: A / A_Hertz against N / N_c for each rough
 * family (every surface thin) beside eq. (3) and the integral of the local density of contact
 * with Hertz's pressure, on log axes: one asperity at small loads, the linear rough regime, and
 * the crossover to Hertz above N_c. */
static int plot_sphere_regimes(const im_scene *scene, const gathered_histories *g)
{
    sphere_theory *t = calloc(1, sizeof *t);
    if (!t)
        return im_fail(IM_ENOMEM, "sphere figure: allocation failed");
    t->h = &g->h;
    int status = IM_OK;
    for (int f = 0; f < scene->family_count && status == IM_OK; ++f)
        if (scene->slopes[f] > 0.0)
            status = sphere_family(scene, &g->h, f, t);
    if (status == IM_OK && t->count == 0)
        status = im_fail(IM_EINVAL, "%s: plots = sphere needs a rough family", scene->path);
    if (status == IM_OK)
        status = scene_write_png_pdf(scene, "sphere_regimes", draw_sphere_regimes, t);
    free(t);
    return status;
}

/* The figures [output] plots asks for, from the ensemble's histories. */
static int plot_histories(const im_scene *scene, const scene_member *members, int count)
{
    gathered_histories *g = NULL;
    int status = gather_histories(scene, members, count, &g);
    if (status == IM_OK && scene_wants_plot(scene, IM_SCENE_PLOT_FIG5))
        status = plot_against_approach(scene, g, 0);
    if (status == IM_OK && scene_wants_plot(scene, IM_SCENE_PLOT_FIG6))
        status = plot_against_approach(scene, g, 1);
    if (status == IM_OK && scene_wants_plot(scene, IM_SCENE_PLOT_FIG7))
        status = plot_area_ratio_against_load(scene, g);
    if (status == IM_OK && scene_wants_plot(scene, IM_SCENE_PLOT_SPHERE))
        status = plot_sphere_regimes(scene, g);
    free_gathered(g);
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

/* Whether the histories unload (steps that go down, with a hardness's memory): then each member's
 * indentation analysis is written. Not in the periodic mode, as `indent --periodic` (Oliver-Pharr's
 * areas are a punch's on a half-space), nor with adhesion (its summary is another). */
int scene_histories_unload(const im_scene *scene)
{
    for (int i = 1; i < scene->step_count && scene->hardness > 0 && !scene->periodic; ++i)
        if (scene->steps[i] < scene->steps[i - 1])
            return 1;
    return 0;
}

/* A member's note of why a branch's S is NaN (front.h: analysis_notes), a stage line naming its file. */
typedef struct member_note {
    const im_scene_run_options *options;
    const char *file;
} member_note;

static void say_note(void *user, const char *note)
{
    const member_note *m = user;
    scene_progress(m->options, "histories: %s: %s", m->file, note);
}

/* indentation/member_FF_SEED.csv: the analysis of a member's unloading branches, indent's
 * indentation.csv (front.h: analysis_write_table), drawn again from the history by every run, and why a
 * branch's S is NaN. */
static int write_indentation(const im_scene *scene, const im_scene_run_options *options, const scene_member *m)
{
    char relative[96], path[IM_SCENE_PATH];
    snprintf(relative, sizeof relative, "indentation/member_%02d_%llu.csv", m->family, (unsigned long long)m->seed);
    im_indenter punch = scene_punch(scene);
    int branches = 0, status = scene_output_path(scene, relative, path, sizeof path);
    if (status == IM_OK)
        status = analysis_write_table(path, &punch, m->history, m->steps, scene->surface.delta, scene->modulus,
                                      &branches);
    member_note note = {options, relative};
    if (status == IM_OK && branches > 0)
        status = analysis_notes(&punch, m->history, m->steps, say_note, &note);
    return status == IM_OK ? IM_OK : im_fail_context(status, "%s", relative);
}

static int write_indentations(const im_scene *scene, const im_scene_run_options *options, const scene_member *members,
                              int count)
{
    char folder[IM_SCENE_PATH];
    int status = scene_output_path(scene, "indentation", folder, sizeof folder);
    if (status == IM_OK)
        status = im_make_directories(folder);
    for (int i = 0; i < count && status == IM_OK; ++i)
        status = write_indentation(scene, options, &members[i]);
    if (status == IM_OK)
        scene_progress(options, "histories: the indentation analysis of %d surface%s in indentation/", count,
                       count == 1 ? "" : "s");
    return status;
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
        return im_fail(IM_EINVAL,
                       "%s: plots fig5, fig6 and fig7 need [loading] steps (approaches, or N* "
                       "values with control = load)",
                       scene->path);
    scene_member *members = NULL;
    int count = 0;
    int status = scene_ensemble_prepare(scene, "histories", &members, &count);
    if (status == IM_OK) {
        scene_link_table(scene, reuse, members, count);
        scene_progress(options, "histories: %d surface%s x %d step%s", count, count == 1 ? "" : "s",
                       scene->step_count, scene->step_count == 1 ? "" : "s");
        status = scene_ensemble_run(scene, options, "histories", members, count, scene_history_member, reuse->ranks);
    }
    if (status == IM_OK)
        report_histories(options, members, count);
    scene_reuse_take_forces(reuse, members, count, SCENE_RESULT_HISTORY);
    if (status == IM_OK && scene_histories_unload(scene))
        status = write_indentations(scene, options, members, count);
    if (status == IM_OK && scene->periodic)
        status = scene_periodic_results(scene, options, members, count);
    if (status == IM_OK)
        status = plot_histories(scene, members, count);
    if (status == IM_OK) /* last: it takes the rows the steps above read */
        scene_periodic_keep_rows(scene, reuse, members, count);
    scene_members_free(members, count);
    return status;
}
