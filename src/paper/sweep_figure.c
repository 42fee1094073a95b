/* Beyond the paper: Fig. 2 over a sweep, A / A_cone against rho_c for each roughness of the sweep
 * (its cone angles) beside eq. (12) and eq. (6). */
#include "paper/figures.h"

#include "indentmap/plot.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdlib.h>

enum { CURVE_POINTS = 161 };

typedef struct sweep_figure {
    double rho[CURVE_POINTS], variable[CURVE_POINTS], constant[CURVE_POINTS];
    im_plot_series series[2 + PAPER_MAX_SWEEP_GROUPS];
} sweep_figure;

static int check_groups(const paper_sweep_group *groups, int count, const char *source)
{
    if (count < 0 || count > PAPER_MAX_SWEEP_GROUPS)
        return im_fail(IM_EINVAL, "%s: fig2 of a sweep draws at most %d roughnesses (h'rms x H x lambda_s), not %d",
                       source, PAPER_MAX_SWEEP_GROUPS, count);
    for (int k = 0; k < count; ++k) {
        const paper_sweep_group *g = &groups[k];
        if (g->count > 0 && (!g->rho_c || !g->area_ratio))
            return im_fail(IM_EINVAL, "%s: fig2 of a sweep: group %d has %d points without their arrays", source, k,
                           g->count);
        for (int i = 0; i < g->count; ++i)
            if (!(g->rho_c[i] > 0.0) || !isfinite(g->rho_c[i]))
                return im_fail(IM_EINVAL, "%s: fig2 of a sweep: group %d's rho_c = %g: expected a positive number",
                               source, k, g->rho_c[i]);
    }
    return IM_OK;
}

/* [0.1, 100] widened to whole decades around every group's rho_c. */
static void rho_axis(const paper_sweep_group *groups, int count, double *lo, double *hi)
{
    *lo = 0.1, *hi = 100.0;
    for (int k = 0; k < count; ++k)
        for (int i = 0; i < groups[k].count; ++i) {
            *lo = fmin(*lo, pow(10.0, floor(log10(groups[k].rho_c[i]))));
            *hi = fmax(*hi, pow(10.0, ceil(log10(groups[k].rho_c[i]))));
        }
}

static void theory_series(sweep_figure *d)
{
    d->series[0] = (im_plot_series){.x = d->rho,
                                    .y = d->variable,
                                    .n = CURVE_POINTS,
                                    .line_width = 1.2,
                                    .label = "eq. (12), variable γ"};
    d->series[1] = (im_plot_series){.x = d->rho,
                                    .y = d->constant,
                                    .n = CURVE_POINTS,
                                    .line = IM_PLOT_DOTTED,
                                    .line_width = 1.5,
                                    .label = "eq. (6), constant γ"};
    im_plot_palette(6, d->series[0].color); /* black: the theory */
    im_plot_palette(6, d->series[1].color);
}

static void group_series(const paper_sweep_group *groups, int count, sweep_figure *d)
{
    const im_plot_marker markers[] = {IM_PLOT_MARKER_CIRCLE, IM_PLOT_MARKER_SQUARE, IM_PLOT_MARKER_TRIANGLE,
                                      IM_PLOT_MARKER_DIAMOND};
    for (int k = 0; k < count; ++k) {
        d->series[2 + k] = (im_plot_series){.x = groups[k].rho_c,
                                            .y = groups[k].area_ratio,
                                            .sigma = groups[k].sd,
                                            .n = groups[k].count,
                                            .line = IM_PLOT_NO_LINE,
                                            .marker = markers[k % 4],
                                            .marker_size = 4.0,
                                            .label = groups[k].label};
        im_plot_palette(k, d->series[2 + k].color);
    }
}

int paper_figure_sweep(const paper_sweep_group *groups, int count, const char *source, const paper_file *file)
{
    int status = check_groups(groups, count, source);
    if (status != IM_OK)
        return status;
    sweep_figure *d = calloc(1, sizeof *d);
    if (!d)
        return im_fail(IM_ENOMEM, "%s: allocation of the sweep's fig2 failed", source);
    double lo, hi;
    rho_axis(groups, count, &lo, &hi);
    status = paper_area_ratio_curves(lo, hi, CURVE_POINTS, d->rho, d->variable, d->constant);
    theory_series(d);
    group_series(groups, count, d);
    im_plot_panel panel = {.x = {IM_PLOT_LOG, lo, hi, "ρ_{c} = cot α / h′_{rms}"},
                           .y = {IM_PLOT_LINEAR, 0.0, 1.05, "A / A_{cone}"},
                           .series = d->series,
                           .series_count = 2 + count,
                           .legend = IM_PLOT_LEGEND_AUTO};
    im_plot plot = im_plot_default();
    plot.panels = &panel;
    if (status == IM_OK)
        status = paper_plot_write(&plot, file);
    free(d);
    return status;
}
