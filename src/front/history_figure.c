/* DIR/history.{png,pdf}: a run's history drawn as the paper draws it (front.h, "The history figure"). */
#include "front/front.h"

#include "indentmap/io.h"
#include "indentmap/plot.h"
#include "indentmap/status.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

enum { THEORY_POINTS = 64 };

void history_axis_labels(const char *length_unit, const char *force_unit, char *x_label, char *y_label, size_t size)
{
    snprintf(x_label, size, "approach w (%s)", length_unit[0] ? length_unit : "δ");
    snprintf(y_label, size, "load N (%s)", force_unit[0] ? force_unit : "E^{*} δ^{2}");
}

/* What the figure plots: its axes, its measured points and up to two theory curves. */
typedef struct history_plot {
    double *x, *y, *theory_x, *theory[2];
    int points, theory_points;
    const char *theory_label[2];
    char x_label[96], y_label[96];
} history_plot;

static int any_finite(const im_history_row *rows, int count, int field_offset)
{
    for (int i = 0; i < count; ++i)
        if (isfinite(*(const double *)((const char *)&rows[i] + field_offset)))
            return 1;
    return 0;
}

/* A periodic cell: the contact fraction A / A0 against the mean pressure p_m = N / A0 and, under a rigid
 * flat, eq. (1) from 0 to the largest pressure. */
static int periodic_plot(const history_figure *h, history_plot *p)
{
    double largest = 0.0;
    for (int i = 0; i < h->count; ++i) {
        p->x[i] = h->rows[i].result.load / h->cell_area;
        p->y[i] = h->rows[i].result.area_ratio;
        largest = fmax(largest, p->x[i]);
    }
    p->points = h->count;
    snprintf(p->x_label, sizeof p->x_label, "mean pressure p_{m} (%s)",
             h->pressure_unit[0] ? h->pressure_unit : "E^{*}");
    snprintf(p->y_label, sizeof p->y_label, "contact fraction A / A_{0}");
    if (!h->flat_theory || !(largest > 0.0))
        return IM_OK;
    p->theory_points = THEORY_POINTS;
    p->theory_label[0] = "eq. (1)";
    int status = IM_OK;
    for (int k = 0; k < THEORY_POINTS && status == IM_OK; ++k) {
        p->theory_x[k] = largest * k / (THEORY_POINTS - 1);
        status = im_theory_flat_area_ratio(h->flat_theory, p->theory_x[k], &p->theory[0][k]);
    }
    return status;
}

/* The smooth punch's words: the area it is measured against, N*'s definition and the theory's equations. */
static void punch_words(enum im_punch_kind kind, const char **area, const char **load_star, const char **theory)
{
    const int cone = kind == IM_PUNCH_CONE;
    *area = cone ? "A_{cone}" : "A_{Hertz}";
    *load_star = cone ? "N* = 2N / (δ² E* cot α)" : "N* = A_{Hertz}(N) / δ²";
    theory[0] = cone ? "eq. (12)" : "γ integral";
    theory[1] = cone ? "eq. (6)" : "eq. (3)";
}

/* A cone or a sphere on the half-space (Fig. 7): A / A_smooth against N*, with the theory columns. */
static void area_plot(const history_figure *h, history_plot *p)
{
    const char *area, *load_star, *theory[2];
    punch_words(h->punch->kind, &area, &load_star, theory);
    for (int i = 0; i < h->count; ++i) {
        p->x[i] = p->theory_x[i] = h->rows[i].result.load_star;
        p->y[i] = h->rows[i].result.area_ratio;
        p->theory[0][i] = h->rows[i].theory.area_ratio_gamma;
        p->theory[1][i] = h->rows[i].theory.area_ratio_constant;
    }
    p->points = h->count;
    snprintf(p->x_label, sizeof p->x_label, "%s", load_star);
    snprintf(p->y_label, sizeof p->y_label, "A / %s", area);
    if (!h->theory || !any_finite(h->rows, h->count, offsetof(im_history_row, theory.area_ratio_gamma)))
        return;
    p->theory_points = h->count;
    p->theory_label[0] = theory[0];
    p->theory_label[1] = theory[1];
}

/* Any other run (Fig. 6): the load N against the approach w, with the smooth punch's N(w). */
static void load_plot(const history_figure *h, history_plot *p)
{
    for (int i = 0; i < h->count; ++i) {
        p->x[i] = p->theory_x[i] = h->rows[i].result.approach;
        p->y[i] = h->rows[i].result.load;
        p->theory[0][i] = h->rows[i].theory.load_smooth;
    }
    p->points = h->count;
    history_axis_labels(h->length_unit, h->force_unit, p->x_label, p->y_label, sizeof p->x_label);
    if (h->theory && any_finite(h->rows, h->count, offsetof(im_history_row, theory.load_smooth))) {
        p->theory_points = h->count;
        p->theory_label[0] = "smooth punch";
    }
}

static int choose_plot(const history_figure *h, history_plot *p)
{
    if (h->cell_area > 0.0)
        return periodic_plot(h, p);
    const int smooth_area = h->punch->kind == IM_PUNCH_CONE || h->punch->kind == IM_PUNCH_SPHERE;
    if (smooth_area && any_finite(h->rows, h->count, offsetof(im_history_row, result.area_ratio)))
        area_plot(h, p);
    else
        load_plot(h, p);
    return IM_OK;
}

static int draw(const char *dir, const history_plot *p, const run_figure_texts *texts)
{
    im_plot_series series[3] = {{.x = p->x,
                                 .y = p->y,
                                 .n = p->points,
                                 .line_width = 1.0,
                                 .marker = IM_PLOT_MARKER_CIRCLE,
                                 .marker_size = 3.5,
                                 .label = "this run"}};
    im_plot_palette(0, series[0].color);
    int n = 1;
    for (int k = 0; k < 2 && p->theory_points > 0 && p->theory_label[k]; ++k, ++n) {
        series[n] = (im_plot_series){.x = p->theory_x,
                                     .y = p->theory[k],
                                     .n = p->theory_points,
                                     .line = k == 0 ? IM_PLOT_SOLID : IM_PLOT_DASHED,
                                     .line_width = 1.2,
                                     .label = p->theory_label[k]};
        im_plot_palette(1, series[n].color);
    }
    im_plot_panel panel = {.x = {.label = p->x_label},
                           .y = {.label = p->y_label},
                           .series = series,
                           .series_count = n};
    im_plot plot = im_plot_default();
    plot.panels = &panel;
    plot.panel_width = 220;
    plot.panel_height = 160;
    plot.texts = texts ? texts->texts : NULL;
    plot.text_count = texts ? texts->count : 0;
    static const char *const NAMES[2] = {"history.png", "history.pdf"};
    int status = IM_OK;
    for (int k = 0; k < 2 && status == IM_OK; ++k) {
        char path[4096];
        status = im_path_join(path, sizeof path, dir, NAMES[k]);
        if (status == IM_OK)
            status = im_plot_write(&plot, path);
    }
    return status;
}

int history_figure_write(const char *dir, const history_figure *h)
{
    if (h->count < 1)
        return IM_OK;
    const size_t room = (size_t)(h->count > THEORY_POINTS ? h->count : THEORY_POINTS);
    history_plot p = {.x = malloc(sizeof(double) * 5 * room)};
    if (!p.x)
        return im_fail(IM_ENOMEM, "history figure of %d steps", h->count);
    p.y = p.x + room, p.theory_x = p.x + 2 * room, p.theory[0] = p.x + 3 * room, p.theory[1] = p.x + 4 * room;
    int status = choose_plot(h, &p);
    if (status == IM_OK)
        status = draw(dir, &p, h->texts);
    free(p.x);
    return status;
}
