/* indentation.csv: the indentation analysis of the unloading branches of a history, written by every
 * front end that runs histories (front.h), with its load-displacement figure; the library's entry point to
 * both, im_history_write_analysis (history.h). */
#include "front/front.h"

#include "core/args.h"
#include "indentmap/io.h"
#include "indentmap/measure.h"
#include "indentmap/plot.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

const char ANALYSIS_COLUMNS[] = "branch,top_step,last_step,loading_from,approach_max,load_max,stiffness,epsilon,"
                                "contact_depth,area_projected,area_real,hardness_it,modulus_reduced,"
                                "residual_approach,work_in,work_out,dissipated,area_real_theory,stiffness_smooth";

enum { ANALYSIS_LINE_MAX = 640 };

/* The theory beside a branch, at its top load (the paper's erf local density is a theory of elastic,
 * repulsive contact: NaN when the top yielded or pulled): the real contact area of eq. (12) (the punch's
 * gamma integral, theory.h; NaN without a rough-surface theory, e.g. a profile punch) and the smooth
 * punch's unloading stiffness at that load, Sneddon's 2 E* a with pi a^2 = A_smooth(N), which the rough
 * contact approaches as its load grows (the paper's Fig. 6). */
static void theory_beside(const im_history_row *top, double e_star, double *area_real, double *stiffness)
{
    const im_step_result *r = &top->result;
    *area_real = *stiffness = NAN;
    if (r->yielding_patches > 0 || r->tensile_force > 0 || !(r->load > 0))
        return;
    *area_real = top->theory.area_smooth * top->theory.area_ratio_gamma;
    *stiffness = 2.0 * e_star * sqrt(top->theory.area_smooth / M_PI);
}

static int format_branch(int index, const im_unloading_branch *b, const im_history_row *rows, double delta,
                         double e_star, char *line, size_t size)
{
    const im_step_result *top = &rows[b->top_step - 1].result, *last = &rows[b->last_step - 1].result;
    /* dissipated in this cycle: from the state the loading started at (the origin: none) */
    const double before = b->loading_from > 0 ? rows[b->loading_from - 1].result.plastic_work : 0;
    double area_theory, stiffness_smooth;
    theory_beside(&rows[b->top_step - 1], e_star, &area_theory, &stiffness_smooth);
    return snprintf(line, size,
                    "%d,%d,%d,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,"
                    "%.17g\n",
                    index + 1, b->top_step, b->last_step, b->loading_from, b->approach_max, b->load_max, b->stiffness,
                    b->epsilon, b->contact_depth, b->area_projected, (double)top->contact_patches * delta * delta,
                    b->hardness, b->modulus, b->residual_approach, b->work_in, b->work_out,
                    last->plastic_work - before, area_theory, stiffness_smooth);
}

static int write_branches(const char *path, const im_unloading_branch *b, int found, const im_history_row *rows,
                          double delta, double e_star)
{
    size_t size = sizeof ANALYSIS_COLUMNS + 1 + (size_t)found * ANALYSIS_LINE_MAX, used = 0;
    char *text = malloc(size);
    if (!text)
        return im_fail(IM_ENOMEM, "indentation.csv of %d branches", found);
    used += (size_t)snprintf(text, size, "%s\n", ANALYSIS_COLUMNS);
    for (int k = 0; k < found; ++k)
        used += (size_t)format_branch(k, &b[k], rows, delta, e_star, text + used, size - used);
    int status = im_write_file_atomic(path, text, used);
    free(text);
    return status;
}

/* ---- the load-displacement figure ---- */

/* Segments of the history as polylines broken by NaN: loading ones (the approach rises, from the origin
 * at the first step) in one series, unloading ones in the other; 3 points per segment. */
typedef struct segments {
    double *x, *y;
    int n;
} segments;

static void add_segment(segments *s, double x0, double y0, double x1, double y1)
{
    const double points[3][2] = {{x0, y0}, {x1, y1}, {NAN, NAN}};
    for (int k = 0; k < 3; ++k, ++s->n) {
        s->x[s->n] = points[k][0];
        s->y[s->n] = points[k][1];
    }
}

/* from_origin: the first segment starts at (0, 0), the unloaded first touch; else at the first step (an
 * adhesive history may begin anywhere, below first touch too). */
static void split_segments(const im_history_row *rows, int count, int from_origin, segments *up, segments *down)
{
    double w0 = from_origin ? 0 : rows[0].result.approach, n0 = from_origin ? 0 : rows[0].result.load;
    for (int k = from_origin ? 0 : 1; k < count; ++k) {
        const double w = rows[k].result.approach, n = rows[k].result.load;
        add_segment(w >= w0 ? up : down, w0, n0, w, n);
        w0 = w;
        n0 = n;
    }
}

/* Each branch's tangent at its top, from N = 0 to the top. */
static int tangents(const im_unloading_branch *b, int found, segments *t)
{
    int drawn = 0;
    for (int k = 0; k < found; ++k)
        if (isfinite(b[k].stiffness) && b[k].stiffness > 0) {
            add_segment(t, b[k].approach_max - b[k].load_max / b[k].stiffness, 0, b[k].approach_max, b[k].load_max);
            ++drawn;
        }
    return drawn;
}

static im_plot_series series_of(const segments *s, int palette, im_plot_line_style line, im_plot_marker marker,
                                const char *label)
{
    im_plot_series series = {.x = s->x,
                             .y = s->y,
                             .n = s->n,
                             .line = line,
                             .line_width = 1.2,
                             .marker = marker,
                             .marker_size = 3.5,
                             .label = label};
    im_plot_palette(palette, series.color);
    return series;
}

/* What a force-distance figure is called and what its series say. */
typedef struct figure_words {
    const char *file;         /* DIR/FILE.png and .pdf */
    const char *up, *down;    /* the rising and the falling segments */
    const char *construction; /* the grey dashed series (a tangent, a marker) */
    im_plot_legend legend;
} figure_words;

static const figure_words LOAD_DISPLACEMENT = {"load_displacement", "loading", "unloading", "tangent at the top (S)",
                                               IM_PLOT_LEGEND_UPPER_LEFT};
static const figure_words FORCE_DISTANCE = {"force_distance", "approach", "retraction", "pull-off",
                                            IM_PLOT_LEGEND_UPPER_LEFT};
static const figure_words FORCE_DISTANCE_HELD = {"force_distance", "approach", "retraction", "most tensile load held",
                                                 IM_PLOT_LEGEND_UPPER_LEFT};

/* A figure's axis labels in the run's units and the texts it carries (NULL: none). */
typedef struct figure_axes {
    char x_label[64], y_label[64];
    const run_figure_texts *texts;
} figure_axes;

static figure_axes axes_of(const char *length_unit, const char *force_unit, const run_figure_texts *texts)
{
    figure_axes axes = {.texts = texts};
    history_axis_labels(length_unit, force_unit, axes.x_label, axes.y_label, sizeof axes.x_label);
    return axes;
}

static int draw_figure(const char *dir, const figure_words *words, const segments *up, const segments *down,
                       const segments *construction, const figure_axes *axes)
{
    im_plot_series series[3];
    int n = 0;
    if (up->n > 0)
        series[n++] = series_of(up, 0, IM_PLOT_SOLID, IM_PLOT_MARKER_CIRCLE, words->up);
    if (down->n > 0)
        series[n++] = series_of(down, 1, IM_PLOT_SOLID, IM_PLOT_MARKER_SQUARE, words->down);
    if (construction->n > 0) {
        series[n] = series_of(construction, 0, IM_PLOT_DASHED,
                              construction->n == 1 ? IM_PLOT_MARKER_DIAMOND : IM_PLOT_MARKER_NONE,
                              words->construction);
        series[n].color[0] = series[n].color[1] = series[n].color[2] = 70; /* dark grey: a construction */
        ++n;
    }
    im_plot_panel panel = {.x = {.label = axes->x_label},
                           .y = {.label = axes->y_label},
                           .series = series,
                           .series_count = n,
                           .legend = words->legend};
    im_plot plot = im_plot_default();
    plot.texts = axes->texts ? axes->texts->texts : NULL;
    plot.text_count = axes->texts ? axes->texts->count : 0;
    plot.panels = &panel;
    plot.panel_width = 220;
    plot.panel_height = 160;
    int status = IM_OK;
    static const char *const SUFFIXES[2] = {".png", ".pdf"};
    for (int k = 0; k < 2 && status == IM_OK; ++k) {
        char name[64], path[4096];
        snprintf(name, sizeof name, "%s%s", words->file, SUFFIXES[k]);
        status = im_path_join(path, sizeof path, dir, name);
        if (status == IM_OK)
            status = im_plot_write(&plot, path);
    }
    return status;
}

static int write_figure(const char *dir, const im_unloading_branch *b, int found, const im_history_row *rows,
                        int count, const figure_axes *axes)
{
    segments up = {0}, down = {0}, tangent = {0};
    const size_t room = 3 * (size_t)count + 3;
    up.x = malloc(sizeof(double) * 6 * room);
    if (!up.x)
        return im_fail(IM_ENOMEM, "load-displacement figure of %d steps", count);
    up.y = up.x + room, down.x = up.x + 2 * room, down.y = up.x + 3 * room;
    tangent.x = up.x + 4 * room, tangent.y = up.x + 5 * room;
    split_segments(rows, count, 1, &up, &down);
    tangents(b, found, &tangent);
    int status = draw_figure(dir, &LOAD_DISPLACEMENT, &up, &down, &tangent, axes);
    free(up.x);
    return status;
}

/* ---- both, from one analysis ---- */

/* The unloading branches of rows[0..count) (measure.h) into *found (count of them at most; the caller
 * frees it), their number into *branches. */
static int measure_branches(const im_indenter *punch, const im_history_row *rows, int count,
                            im_unloading_branch **found, int *branches)
{
    *branches = 0;
    double *columns = malloc(sizeof(double) * 3 * (size_t)count);
    *found = malloc(sizeof **found * (size_t)count);
    int status = columns && *found ? IM_OK : im_fail(IM_ENOMEM, "indentation analysis of %d steps", count);
    for (int k = 0; status == IM_OK && k < count; ++k) {
        columns[k] = rows[k].result.approach;
        columns[count + k] = rows[k].result.load;
        columns[2 * count + k] = rows[k].result.residual_approach;
    }
    if (status == IM_OK)
        status = im_measure_unloading(punch, columns, columns + count, columns + 2 * count, count, *found, count,
                                      branches);
    free(columns);
    return status;
}

int analysis_notes(const im_indenter *punch, const im_history_row *rows, int count, analysis_say *say, void *user)
{
    if (count < 2)
        return IM_OK;
    im_unloading_branch *found = NULL;
    int branches = 0, status = measure_branches(punch, rows, count, &found, &branches);
    for (int k = 0; status == IM_OK && k < branches; ++k) {
        char note[512];
        status = im_measure_unloading_note(&found[k], note, sizeof note);
        if (status == IM_OK && note[0])
            say(user, note);
    }
    free(found);
    return status;
}

int analysis_write_table(const char *path, const im_indenter *punch, const im_history_row *rows, int count,
                         double delta, double e_star, int *branches)
{
    *branches = 0;
    if (count < 2)
        return IM_OK;
    im_unloading_branch *found = NULL;
    int status = measure_branches(punch, rows, count, &found, branches);
    if (status == IM_OK && *branches > 0)
        status = write_branches(path, found, *branches, rows, delta, e_star);
    free(found);
    return status;
}

int analysis_write(const char *dir, const im_indenter *punch, const im_history_row *rows, int count, double delta,
                   double e_star, const char *length_unit, const char *force_unit, const run_figure_texts *texts,
                   int *branches)
{
    const figure_axes axes = axes_of(length_unit, force_unit, texts);
    *branches = 0;
    if (count < 2)
        return IM_OK;
    char path[4096];
    im_unloading_branch *found = NULL;
    int status = im_path_join(path, sizeof path, dir, "indentation.csv");
    if (status == IM_OK)
        status = measure_branches(punch, rows, count, &found, branches);
    if (status == IM_OK && *branches > 0)
        status = write_branches(path, found, *branches, rows, delta, e_star);
    if (status == IM_OK && *branches > 0)
        status = write_figure(dir, found, *branches, rows, count, &axes);
    free(found);
    return status;
}

int im_history_write_analysis(const char *dir, const im_indenter *punch, const im_history_row *rows, int count,
                              double delta, double e_star, const char *length_unit, const char *force_unit,
                              int *branches)
{
    ARG_REQUIRE(dir, "dir");
    ARG_REQUIRE(punch, "punch");
    ARG_REQUIRE(rows, "rows");
    ARG_REQUIRE(length_unit, "length_unit");
    ARG_REQUIRE(force_unit, "force_unit");
    ARG_REQUIRE(branches, "branches");
    *branches = 0;
    if (count < 0)
        return im_fail(IM_EINVAL, "im_history_write_analysis: count = %d: expected >= 0", count);
    return analysis_write(dir, punch, rows, count, delta, e_star, length_unit, force_unit, NULL, branches);
}

/* ---- adhesion: the summary and the force-distance figure ---- */

int analysis_measure_adhesion(const im_history_row *rows, int count, enum im_control control,
                              im_adhesion_summary *summary)
{
    if (count < 1)
        return im_fail(IM_EINVAL, "adhesion summary: no step solved");
    double *columns = malloc(sizeof(double) * 2 * (size_t)count);
    long *contact = malloc(sizeof(long) * (size_t)count);
    int status = columns && contact ? IM_OK : im_fail(IM_ENOMEM, "adhesion summary of %d steps", count);
    for (int k = 0; status == IM_OK && k < count; ++k) {
        columns[k] = rows[k].result.approach;
        columns[count + k] = rows[k].result.load;
        contact[k] = rows[k].result.contact_patches;
    }
    if (status == IM_OK)
        status = im_measure_adhesion(columns, columns + count, contact, count, control == IM_CONTROL_LOAD, summary);
    free(columns);
    free(contact);
    return status;
}

/* What the work line says: the work done without a loop, the loop's lost work, or that the steps do not
 * resolve it. */
static void describe_work(const im_adhesion_summary *summary, const im_history_row *rows, int done, char *work,
                          size_t size)
{
    const im_step_result *first = &rows[0].result, *last = &rows[done - 1].result;
    if (isnan(summary->hysteresis_work)) /* no loop (measure.h): a retraction alone is the work done */
        snprintf(work, size,
                 "work done %.6g (+- %.2g; sum of N dw), no loss: the history does not return to where it began "
                 "(w = %.6g, N = %.6g at the first step; w = %.6g, N = %.6g at the last)",
                 summary->work_done, summary->hysteresis_error, first->approach, first->load, last->approach,
                 last->load);
    else if (fabs(summary->hysteresis_work) > summary->hysteresis_error)
        snprintf(work, size, "work lost %.6g (+- %.2g, the steps' trapezoids)", summary->hysteresis_work,
                 summary->hysteresis_error);
    else /* the loop lies between the steps: its sign and size are the trapezoids' error */
        snprintf(work, size,
                 "work lost not resolved by the steps: %.6g within the trapezoids' error +- %.2g (finer steps "
                 "around the jumps resolve it)",
                 summary->hysteresis_work, summary->hysteresis_error);
}

void analysis_describe_adhesion(const im_adhesion_summary *summary, const im_history_row *rows, int done,
                                enum im_control control, const char *dir, char *line, size_t size)
{
    char work[512], figure[4200] = "";
    describe_work(summary, rows, done, work, sizeof work);
    if (dir)
        snprintf(figure, sizeof figure, "; %s/force_distance.png and .pdf", dir);
    /* -min N is the pull-off only where the steps passed it (T16: load control's -3 was said as the pull-off
     * while the step refused at -6 named the least load the contact holds, -5.43) */
    const int pull_off = isfinite(summary->pull_off_force);
    const char *why_not = pull_off                     ? ""
                          : control != IM_CONTROL_LOAD ? " (not the pull-off: no later step's load rises above it)"
                                                       : " (not the pull-off: load control holds each load given; a "
                                                         "load below the pull-off is refused, naming the least load "
                                                         "the contact holds)";
    snprintf(line, size,
             "adhesion: %s %.6g at w = %.6g%s; jump-in at w = %.6g, last contact retracting at w = %.6g; %s%s",
             pull_off ? "pull-off force" : "most tensile load held", summary->most_tensile_load,
             summary->most_tensile_approach, why_not, summary->jump_in_approach, summary->jump_out_approach, work,
             figure);
}

int analysis_write_adhesion(const char *dir, const im_history_row *rows, int count, enum im_control control,
                            const char *length_unit, const char *force_unit, const run_figure_texts *texts,
                            im_adhesion_summary *summary)
{
    int status = analysis_measure_adhesion(rows, count, control, summary);
    if (status != IM_OK)
        return status;
    const size_t room = 3 * (size_t)count + 3;
    double *plot = malloc(sizeof(double) * 6 * room);
    if (!plot)
        return im_fail(IM_ENOMEM, "force-distance figure of %d steps", count);
    segments up = {plot, plot + room, 0}, down = {plot + 2 * room, plot + 3 * room, 0};
    segments marker = {plot + 4 * room, plot + 5 * room, 0};
    if (isfinite(summary->most_tensile_load)) {
        marker.x[0] = summary->most_tensile_approach;
        marker.y[0] = -summary->most_tensile_load;
        marker.n = 1;
    }
    split_segments(rows, count, 0, &up, &down);
    const figure_axes axes = axes_of(length_unit, force_unit, texts);
    status = draw_figure(dir, isfinite(summary->pull_off_force) ? &FORCE_DISTANCE : &FORCE_DISTANCE_HELD, &up, &down,
                         &marker, &axes);
    free(plot);
    return status;
}
