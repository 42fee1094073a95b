/* Beyond the paper: eq. (2)'s k measured on surfaces pressed flat, A / A0 against x = p_m /
 * (h'rms E*) per family beside erf with the fitted k and with the paper's k = 2. */
#include "paper/figures.h"

#include "indentmap/plot.h"
#include "indentmap/status.h"
#include "indentmap/theory.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

enum { THEORY_POINTS = 81 };

typedef struct flat_k_figure {
    double grid[THEORY_POINTS], fitted[PAPER_MAX_PANELS][THEORY_POINTS], paper[THEORY_POINTS];
    im_plot_series series[PAPER_MAX_PANELS][3];
    im_plot_panel panels[PAPER_MAX_PANELS];
    char titles[PAPER_MAX_PANELS][96];
} flat_k_figure;

static void flat_k_panel(const paper_flat_family *f, flat_k_figure *d, int i)
{
    for (int j = 0; j < THEORY_POINTS; ++j)
        d->fitted[i][j] = erf(0.5 * sqrt(M_PI) * f->k * d->grid[j]);
    d->series[i][0] = (im_plot_series){.x = f->x,
                                       .y = f->area,
                                       .n = f->points,
                                       .line = IM_PLOT_NO_LINE,
                                       .marker = IM_PLOT_MARKER_CIRCLE,
                                       .marker_size = 2.5,
                                       .label = "surfaces"};
    d->series[i][1] = (im_plot_series){.x = d->grid,
                                       .y = d->fitted[i],
                                       .n = THEORY_POINTS,
                                       .line = IM_PLOT_SOLID,
                                       .line_width = 1.5,
                                       .label = "erf, fitted k"};
    d->series[i][2] = (im_plot_series){.x = d->grid,
                                       .y = d->paper,
                                       .n = THEORY_POINTS,
                                       .line = IM_PLOT_DOTTED,
                                       .line_width = 1.5,
                                       .label = "erf, k = 2"};
    snprintf(d->titles[i], sizeof d->titles[i], "h'_{rms} = %g: k = %.3f ± %.3f", f->slope, f->k, f->k_error);
    d->panels[i] = (im_plot_panel){.x = {IM_PLOT_LINEAR, 0, 0, "p_{m} / (h'_{rms} E*)"},
                                   .y = {IM_PLOT_LINEAR, 0, 0, "A / A_{0}"},
                                   .series = d->series[i],
                                   .series_count = 3,
                                   .title = d->titles[i],
                                   .legend = IM_PLOT_LEGEND_LOWER_RIGHT};
}

int paper_figure_flat_k(const paper_flat_family *families, int count, double x_max, const paper_file *file)
{
    if (count < 1 || count > PAPER_MAX_PANELS)
        return im_fail(IM_EINVAL, "flat_k: %d families: expected 1 to %d", count, PAPER_MAX_PANELS);
    flat_k_figure *d = calloc(1, sizeof *d);
    if (!d)
        return im_fail(IM_ENOMEM, "flat_k figure: allocation failed");
    for (int j = 0; j < THEORY_POINTS; ++j) {
        d->grid[j] = x_max * j / (THEORY_POINTS - 1);
        d->paper[j] = erf(0.5 * sqrt(M_PI) * IM_THEORY_K_DEFAULT * d->grid[j]);
    }
    for (int i = 0; i < count; ++i)
        flat_k_panel(&families[i], d, i);
    im_plot plot = im_plot_default();
    paper_plot_grid(&plot, d->panels, count);
    int status = paper_plot_write(&plot, file);
    free(d);
    return status;
}
