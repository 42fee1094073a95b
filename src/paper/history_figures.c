/* The paper's figures drawn from indentation histories: Fig. 5 (A / delta^2 against w), Fig. 6
 * (N against w), Fig. 7 (A / A_cone against N*, mean and +- one standard deviation) and the
 * sphere's regimes (A / A_Hertz against N / N_c). */
#include "paper/figures.h"
#include "core/summation.h"

#include "indentmap/plot.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

enum { THEORY_POINTS = 101, COMMON_POINTS = 40, SERIES_PER_PANEL = PAPER_MAX_SURFACE_LINES + 3 };

/* A grid of panels and their series, allocated per figure. */
typedef struct panel_grid {
    im_plot_panel panels[PAPER_MAX_PANELS];
    im_plot_series series[PAPER_MAX_PANELS][SERIES_PER_PANEL];
} panel_grid;

int paper_panel_columns(int count)
{
    return count > 3 && count % 3 == 0 ? 3 : count > 3 && count % 2 == 0 ? 2 : count;
}

void paper_plot_grid(im_plot *plot, const im_plot_panel *panels, int count)
{
    int columns = paper_panel_columns(count);
    plot->columns = columns <= 3 ? columns : 3;
    plot->rows = (count + plot->columns - 1) / plot->columns;
    plot->panels = panels;
    plot->panel_count = count;
}

im_plot paper_file_style(const paper_file *file)
{
    im_plot style = im_plot_default();
    style.texts = file->texts;
    style.text_count = file->text_count;
    return style;
}

int paper_plot_write(im_plot *plot, const paper_file *file)
{
    plot->texts = file->texts;
    plot->text_count = file->text_count;
    return im_plot_write(plot, file->path);
}

static int write_grid(const im_plot_panel *panels, int count, const paper_file *file)
{
    im_plot plot = im_plot_default();
    paper_plot_grid(&plot, panels, count);
    return paper_plot_write(&plot, file);
}

static int check_families(const paper_histories *h, const char *figure)
{
    if (h->family_count < 1 || h->family_count > PAPER_MAX_PANELS)
        return im_fail(IM_EINVAL, "%s: %s: %d families: expected 1 to %d", h->source, figure, h->family_count,
                       PAPER_MAX_PANELS);
    return IM_OK;
}

/* The most steps of any member: the rows of a buffer of scaled values per member. */
static int most_steps(const paper_histories *h)
{
    int steps = 0;
    for (int i = 0; i < h->count; ++i)
        steps = h->members[i].steps > steps ? h->members[i].steps : steps;
    return steps;
}

static double largest_approach(const paper_histories *h)
{
    double w = 0.0;
    for (int i = 0; i < h->count; ++i)
        for (int k = 0; k < h->members[i].steps; ++k)
            w = fmax(w, h->members[i].approach[k]);
    return w > 0.0 ? w : 1.0;
}

/* A smooth cone's closed forms against w (Love): A / delta^2 = pi a^2 / delta^2, a = 2 w / (pi cot alpha),
 * or N / (E* delta^2) = 2 w^2 / (pi delta^2 cot alpha). */
static void fill_theory(const paper_histories *h, double w_max, int load, double *theory_w, double *theory_smooth)
{
    double c = h->cot_alpha, delta = h->delta;
    for (int i = 0; i < THEORY_POINTS; ++i) {
        double w = w_max * i / (THEORY_POINTS - 1), a = 2.0 * w / (M_PI * c);
        theory_w[i] = w;
        theory_smooth[i] = load ? 2.0 * w * w / (M_PI * c * delta * delta) : M_PI * a * a / (delta * delta);
    }
}

static im_plot_series thin_line(const double *x, const double *y, int n, int family, int families)
{
    im_plot_series s = {.x = x, .y = y, .n = n, .line = IM_PLOT_SOLID, .line_width = 0.5};
    im_plot_family_color(family, families, s.color);
    return s;
}

typedef struct approach_figure {
    panel_grid grid;
    double theory_w[THEORY_POINTS], theory_smooth[THEORY_POINTS];
    double theory_eq12[PAPER_MAX_PANELS][THEORY_POINTS];
} approach_figure;

/* Family f's panel of Fig. 5 or 6: its surfaces (y scaled into `scaled`, a row per member), the
 * smooth theory and eq. (12). */
static void approach_panel(const paper_histories *h, int load, int f, double *scaled, int row, approach_figure *d)
{
    double delta = h->delta, e_star = h->e_star;
    im_plot_series *series = d->grid.series[f];
    int n = 0;
    for (int i = 0; i < h->count; ++i) {
        const paper_history *m = &h->members[i];
        double *y = scaled + (size_t)i * row;
        if (m->family != f || m->steps == 0 || n >= PAPER_MAX_SURFACE_LINES)
            continue;
        for (int k = 0; k < m->steps; ++k)
            y[k] = load ? m->load[k] / (e_star * delta * delta) : (double)m->patches[k];
        series[n] = thin_line(m->approach, y, m->steps, f, h->family_count);
        series[n].label = n == 0 ? "surfaces" : NULL;
        ++n;
    }
    im_plot_series smooth = {.x = d->theory_w,
                             .y = d->theory_smooth,
                             .n = THEORY_POINTS,
                             .line = IM_PLOT_SOLID,
                             .line_width = 2.0,
                             .label = "smooth (Love)"};
    series[n++] = smooth;
    if (!load && h->slopes[f] > 0.0) {
        double ratio = h->eq12[f];
        for (int i = 0; i < THEORY_POINTS; ++i)
            d->theory_eq12[f][i] = ratio * d->theory_smooth[i];
        im_plot_series eq12 = {.x = d->theory_w,
                               .y = d->theory_eq12[f],
                               .n = THEORY_POINTS,
                               .line = IM_PLOT_DASHED,
                               .line_width = 1.0,
                               .label = "eq. (12)"};
        im_plot_palette(1, eq12.color);
        series[n++] = eq12;
    }
    d->grid.panels[f] =
        (im_plot_panel){.x = {IM_PLOT_LINEAR, 0, 0, "approach w / δ"},
                        .y = {IM_PLOT_LINEAR, 0, 0, load ? "load N / (E* δ²)" : "contact area A / δ²"},
                        .series = series,
                        .series_count = n,
                        .title = h->titles[f],
                        .legend = f == h->family_count - 1 ? IM_PLOT_LEGEND_UPPER_LEFT : IM_PLOT_LEGEND_HIDDEN};
}

int paper_figure_against_approach(const paper_histories *h, int load, const paper_file *file)
{
    int status = check_families(h, load ? "fig6" : "fig5");
    if (status != IM_OK)
        return status;
    int row = most_steps(h);
    approach_figure *d = calloc(1, sizeof *d);
    double *scaled = malloc(sizeof *scaled * ((size_t)h->count * (size_t)row + 1));
    if (!d || !scaled) {
        free(d);
        free(scaled);
        return im_fail(IM_ENOMEM, "fig5/fig6: allocation failed");
    }
    fill_theory(h, largest_approach(h), load, d->theory_w, d->theory_smooth);
    for (int f = 0; f < h->family_count; ++f)
        approach_panel(h, load, f, scaled, row, d);
    status = write_grid(d->grid.panels, h->family_count, file);
    free(scaled);
    free(d);
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

typedef struct load_figure {
    panel_grid grid;
    int panels; /* rough families drawn */
    int family[PAPER_MAX_PANELS];
    double x[PAPER_MAX_PANELS][COMMON_POINTS], mean[PAPER_MAX_PANELS][COMMON_POINTS];
    double sd[PAPER_MAX_PANELS][COMMON_POINTS], lo[PAPER_MAX_PANELS][COMMON_POINTS];
    double hi[PAPER_MAX_PANELS][COMMON_POINTS];
    int surfaces[PAPER_MAX_PANELS][COMMON_POINTS];
    double eq12_x[PAPER_MAX_PANELS][2], eq12_y[PAPER_MAX_PANELS][2];
} load_figure;

/* The N* range every surface of family f with two steps or more reached: 0 when they share none
 * (or none has two steps: one step is no range). */
static int common_range(const paper_histories *h, int f, double *start, double *end)
{
    *start = 0.0, *end = INFINITY;
    int ranges = 0;
    for (int i = 0; i < h->count; ++i)
        if (h->members[i].family == f && h->members[i].steps > 1) {
            *start = fmax(*start, h->members[i].load_star[0]);
            *end = fmin(*end, h->members[i].load_star[h->members[i].steps - 1]);
            ++ranges;
        }
    return ranges > 0 && *end > *start;
}

/* Mean and standard deviation of family f's A / A_cone at COMMON_POINTS N* on [start, end]. */
static void mean_and_spread(const paper_histories *h, int f, double start, double end, load_figure *d, int panel)
{
    for (int k = 0; k < COMMON_POINTS; ++k) {
        /* The ends exactly: start + (end - start) may round past the surface that reached only end. */
        double x = k == COMMON_POINTS - 1 ? end : start + (end - start) * k / (COMMON_POINTS - 1);
        double sum = 0, sum_sq = 0;
        int n = 0;
        for (int i = 0; i < h->count; ++i) {
            const paper_history *m = &h->members[i];
            double y = m->family == f ? interpolate(m->load_star, m->area_ratio, m->steps, x) : NAN;
            if (isnan(y))
                continue;
            sum += y;
            sum_sq += y * y;
            ++n;
        }
        double mu = sum / n, sd = sample_sd(sum, sum_sq, n);
        d->x[panel][k] = x;
        d->mean[panel][k] = mu;
        d->sd[panel][k] = sd;
        d->lo[panel][k] = mu - sd;
        d->hi[panel][k] = mu + sd;
        d->surfaces[panel][k] = n;
    }
}

/* The statistics of every rough family whose surfaces share a range of N*: the number of panels. */
static int gather_statistics(const paper_histories *h, load_figure *d)
{
    int panels = 0;
    for (int f = 0; f < h->family_count; ++f) {
        double start, end;
        if (!(h->slopes[f] > 0.0) || !common_range(h, f, &start, &end))
            continue;
        d->family[panels] = f;
        mean_and_spread(h, f, start, end, d, panels++);
    }
    return panels;
}

/* Family f's panel: the mean, +- one sd and, where the family has one, eq. (12)'s ratio (a
 * constant in N*) over the same range. */
static void load_panel(const paper_histories *h, load_figure *d, int panel)
{
    int f = d->family[panel], n = 3;
    im_plot_series *series = d->grid.series[panel];
    series[0] = (im_plot_series){.x = d->x[panel], .y = d->mean[panel], .n = COMMON_POINTS, .label = "mean"};
    series[1] = (im_plot_series){.x = d->x[panel],
                                 .y = d->lo[panel],
                                 .n = COMMON_POINTS,
                                 .line = IM_PLOT_DOTTED,
                                 .label = "± 1 sd"};
    series[2] = (im_plot_series){.x = d->x[panel], .y = d->hi[panel], .n = COMMON_POINTS, .line = IM_PLOT_DOTTED};
    if (isfinite(h->eq12[f])) {
        d->eq12_x[panel][0] = d->x[panel][0], d->eq12_x[panel][1] = d->x[panel][COMMON_POINTS - 1];
        d->eq12_y[panel][0] = d->eq12_y[panel][1] = h->eq12[f];
        series[n] = (im_plot_series){.x = d->eq12_x[panel],
                                     .y = d->eq12_y[panel],
                                     .n = 2,
                                     .line = IM_PLOT_DASHED,
                                     .label = "eq. (12)"};
        im_plot_palette(1, series[n++].color);
    }
    d->grid.panels[panel] = (im_plot_panel){.x = {IM_PLOT_LINEAR, 0, 0, "N* = 2N / (δ² E* cot α)"},
                                            .y = {IM_PLOT_LINEAR, 0, 0, "A / A_{cone}"},
                                            .series = series,
                                            .series_count = n,
                                            .title = h->titles[f],
                                            .legend = panel == d->panels - 1 ? IM_PLOT_LEGEND_AUTO
                                                                             : IM_PLOT_LEGEND_HIDDEN};
}

/* Fig. 7's statistics of h into a new *d (the caller frees it): IM_EINVAL when no rough family's
 * surfaces share a range of N*, or check_families' errors, IM_ENOMEM. */
static int load_statistics(const paper_histories *h, load_figure **d)
{
    int status = check_families(h, "fig7");
    *d = status == IM_OK ? calloc(1, sizeof **d) : NULL;
    if (status == IM_OK && !*d)
        status = im_fail(IM_ENOMEM, "fig7: allocation failed");
    if (status == IM_OK && ((*d)->panels = gather_statistics(h, *d)) == 0)
        status = im_fail(IM_EINVAL, "%s: fig7 needs a rough family whose surfaces share a range of N*", h->source);
    return status;
}

int paper_figure_area_ratio_against_load(const paper_histories *h, const paper_file *file)
{
    load_figure *d;
    int status = load_statistics(h, &d);
    for (int p = 0; status == IM_OK && p < d->panels; ++p)
        load_panel(h, d, p);
    if (status == IM_OK)
        status = write_grid(d->grid.panels, d->panels, file);
    free(d);
    return status;
}

int paper_write_area_ratio_statistics(const paper_histories *h, FILE *out)
{
    load_figure *d;
    int status = load_statistics(h, &d);
    if (status == IM_OK)
        fprintf(out, "slope,n_star,area_ratio_mean,area_ratio_sd,surfaces,area_ratio_eq12\n");
    for (int p = 0; status == IM_OK && p < d->panels; ++p)
        for (int k = 0; k < COMMON_POINTS; ++k)
            fprintf(out, "%.17g,%.17g,%.17g,%.17g,%d,%.17g\n", h->slopes[d->family[p]], d->x[p][k], d->mean[p][k],
                    d->sd[p][k], d->surfaces[p][k], h->eq12[d->family[p]]);
    free(d);
    return status;
}

int paper_first_resolved_step(const paper_history *m)
{
    int k = 0;
    while (k < m->steps && m->patches[k] < PAPER_MIN_PATCHES)
        ++k;
    return k;
}

/* The sphere's panel of one rough family: its surfaces (x = N / N_c, into `scaled`) and the
 * theory. */
static void sphere_panel(const paper_histories *h, const paper_sphere_family *s, double *scaled, int row,
                         panel_grid *grid, int panel)
{
    im_plot_series *series = grid->series[panel];
    int n = 0, f = s->family;
    for (int i = 0; i < h->count; ++i) {
        const paper_history *m = &h->members[i];
        double *x = scaled + (size_t)i * row;
        int first = m->family == f ? paper_first_resolved_step(m) : m->steps;
        if (first == m->steps || n >= PAPER_MAX_SURFACE_LINES)
            continue;
        for (int k = first; k < m->steps; ++k)
            x[k] = m->load[k] / s->crossover_load;
        series[n] = thin_line(x + first, m->area_ratio + first, m->steps - first, f, h->family_count);
        series[n].label = n == 0 ? "surfaces (n_{p} ≥ 10)" : NULL;
        ++n;
    }
    im_plot_series eq3 = {.x = s->theory_x,
                          .y = s->theory_constant,
                          .n = s->theory_points,
                          .line = IM_PLOT_SOLID,
                          .line_width = 2.0,
                          .label = "eq. (3)"};
    series[n++] = eq3;
    im_plot_series gamma = {.x = s->theory_x,
                            .y = s->theory_gamma,
                            .n = s->theory_points,
                            .line = IM_PLOT_DASHED,
                            .line_width = 1.2,
                            .label = "γ integral"};
    im_plot_palette(1, gamma.color); /* vermillion over eq. (3)'s black: both stay visible */
    series[n++] = gamma;
    grid->panels[panel] = (im_plot_panel){.x = {IM_PLOT_LOG, 0, 0, "N / N_{c}"},
                                          .y = {IM_PLOT_LOG, 0, 0, "A / A_{Hertz}"},
                                          .series = series,
                                          .series_count = n,
                                          .title = h->titles[f],
                                          .legend = IM_PLOT_LEGEND_LOWER_RIGHT};
}

int paper_figure_sphere_regimes(const paper_histories *h, const paper_sphere_family *families, int count,
                                const paper_file *file)
{
    int status = check_families(h, "sphere");
    if (status == IM_OK && (count < 1 || count > PAPER_MAX_PANELS))
        status = im_fail(IM_EINVAL, "%s: sphere: %d rough families: expected 1 to %d", h->source, count,
                         PAPER_MAX_PANELS);
    if (status != IM_OK)
        return status;
    int row = most_steps(h);
    panel_grid *grid = calloc(1, sizeof *grid);
    double *scaled = malloc(sizeof *scaled * ((size_t)h->count * (size_t)row + 1));
    if (grid && scaled) {
        for (int p = 0; p < count; ++p)
            sphere_panel(h, &families[p], scaled, row, grid, p);
        status = write_grid(grid->panels, count, file);
    } else {
        status = im_fail(IM_ENOMEM, "sphere figure: allocation failed");
    }
    free(scaled);
    free(grid);
    return status;
}
