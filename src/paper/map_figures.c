/* Figures of contact maps: Fig. 4's panels of every family at one load, and (beyond the paper) the
 * local contact density seen directly, the contact fraction of a map averaged over rings around
 * the punch axis beside gamma(r/a) of eq. (10). */
#include "paper/figures.h"

#include "indentmap/figure.h"
#include "indentmap/plot.h"
#include "indentmap/status.h"
#include "indentmap/theory.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

int paper_figure_contact_panels(const paper_contact_panels *in, const paper_file *file)
{
    if (in->count < 1 || in->count > PAPER_MAX_PANELS)
        return im_fail(IM_EINVAL, "%s: contact panels: %d maps: expected 1 to %d", in->source, in->count,
                       PAPER_MAX_PANELS);
    im_figure_panel panels[PAPER_MAX_PANELS];
    char labels[PAPER_MAX_PANELS][8];
    int columns = paper_panel_columns(in->count);
    for (int i = 0; i < in->count; ++i) {
        snprintf(labels[i], sizeof labels[i], "(%c)", 'a' + i % 26);
        panels[i] = (im_figure_panel){&in->images[i], labels[i], in->titles[i]};
    }
    char load_text[64];
    snprintf(load_text, sizeof load_text, "N* = %g", in->load_star);
    if (file->text_count + 1 >= PAPER_MAX_TEXTS)
        return im_fail(IM_EINVAL, "%s: contact panels: %d texts: expected fewer than %d", in->source,
                       file->text_count, PAPER_MAX_TEXTS - 1);
    im_png_text texts[PAPER_MAX_TEXTS];
    int count = 0;
    for (; count < file->text_count; ++count)
        texts[count] = file->texts[count];
    texts[count++] = (im_png_text){"Load", load_text};
    if (in->norm_text)
        texts[count++] = (im_png_text){"Norm", in->norm_text};
    im_figure figure = im_figure_default();
    figure.rows = in->count / columns;
    figure.columns = columns;
    figure.panels = panels;
    figure.colormap = in->norm;
    figure.colorbar_label = "local force f / (E* δ²)";
    figure.extend_under = in->extend_under;
    figure.extend_over = in->extend_over;
    figure.tension_colormap = in->tension;
    figure.tension_label = "tensile force −f / (E* δ²)";
    figure.texts = texts;
    figure.text_count = count;
    figure.note = load_text;
    return im_figure_write(&figure, file->path);
}

enum { RINGS = 26, DENSITY_THEORY_POINTS = 261 }; /* rings of width 0.05 a out to 1.3 a */
static const double RING_WIDTH = 0.05;

/* Contact fraction per ring of width RING_WIDTH a around the punch axis (NaN for an empty ring). */
static void ring_fractions(const paper_density_map *map, double *r_over_a, double *fraction)
{
    const im_field *force = map->force;
    double x0 = map->axis_x, y0 = map->axis_y, a = map->radius, contact[RINGS] = {0}, total[RINGS] = {0};
    for (int iy = 0; iy < force->ny; ++iy)
        for (int ix = 0; ix < force->nx; ++ix) {
            double r = hypot((ix + 0.5) * force->delta - x0, (iy + 0.5) * force->delta - y0) / a;
            int ring = (int)(r / RING_WIDTH);
            if (ring >= RINGS)
                continue;
            total[ring] += 1.0;
            contact[ring] += force->data[(size_t)iy * force->nx + ix] > 0.0;
        }
    for (int i = 0; i < RINGS; ++i) {
        r_over_a[i] = (i + 0.5) * RING_WIDTH;
        fraction[i] = total[i] > 0.0 ? contact[i] / total[i] : NAN;
    }
}

/* gamma(r/a) of eq. (10) on a fine grid, 0 beyond r = a. */
static int theory_density(double alpha_degrees, double slope, double *r_over_a, double *gamma, int count)
{
    im_theory_interface rough = im_theory_interface_default(slope);
    double rho, beta;
    int status = im_theory_cone_rho(&rough, alpha_degrees, &rho);
    if (status == IM_OK)
        status = im_theory_erf_scale(rho, rough.normalisation, rough.k, &beta);
    for (int i = 0; i < count && status == IM_OK; ++i) {
        r_over_a[i] = 1.3 * i / (count - 1);
        gamma[i] = 0.0;
        if (r_over_a[i] < 1.0)
            status = im_theory_cone_contact_density(beta, fmax(r_over_a[i], 1e-9), &gamma[i]);
    }
    return status;
}

typedef struct density_figure {
    double rings[PAPER_MAX_PANELS][RINGS], fractions[PAPER_MAX_PANELS][RINGS];
    double theory_r[PAPER_MAX_PANELS][DENSITY_THEORY_POINTS], theory_gamma[PAPER_MAX_PANELS][DENSITY_THEORY_POINTS];
    im_plot_series series[PAPER_MAX_PANELS][2];
    im_plot_panel panels[PAPER_MAX_PANELS];
    char titles[PAPER_MAX_PANELS][64];
} density_figure;

static int density_panel(double alpha_degrees, const paper_density_map *map, density_figure *d, int i, int count)
{
    ring_fractions(map, d->rings[i], d->fractions[i]);
    int status = theory_density(alpha_degrees, map->slope, d->theory_r[i], d->theory_gamma[i], DENSITY_THEORY_POINTS);
    im_plot_series measured = {.x = d->rings[i],
                               .y = d->fractions[i],
                               .n = RINGS,
                               .line = IM_PLOT_NO_LINE,
                               .marker = IM_PLOT_MARKER_CIRCLE,
                               .label = "simulated (ring average)"};
    im_plot_series theory = {.x = d->theory_r[i],
                             .y = d->theory_gamma[i],
                             .n = DENSITY_THEORY_POINTS,
                             .line = IM_PLOT_SOLID,
                             .label = "γ(r) eq. (10)"};
    im_plot_palette(0, measured.color);
    im_plot_palette(6, theory.color);
    d->series[i][0] = theory;
    d->series[i][1] = measured;
    snprintf(d->titles[i], sizeof d->titles[i], "h′_{rms} = %g, N* = %g", map->slope, map->load_star);
    d->panels[i] = (im_plot_panel){.x = {IM_PLOT_LINEAR, 0.0, 1.3, "r / a"},
                                   .y = {IM_PLOT_LINEAR, 0.0, 1.05, "contact density"},
                                   .series = d->series[i],
                                   .series_count = 2,
                                   .title = d->titles[i],
                                   .legend = i == count - 1 ? IM_PLOT_LEGEND_AUTO : IM_PLOT_LEGEND_HIDDEN};
    return status;
}

int paper_figure_contact_density(double alpha_degrees, const paper_density_map *maps, int count,
                                 const paper_file *file)
{
    if (count < 1 || count > PAPER_MAX_PANELS)
        return im_fail(IM_EINVAL, "contact density: %d maps: expected 1 to %d", count, PAPER_MAX_PANELS);
    density_figure *d = calloc(1, sizeof *d);
    if (!d)
        return im_fail(IM_ENOMEM, "contact density: allocation failed");
    int status = IM_OK;
    for (int i = 0; i < count && status == IM_OK; ++i)
        status = density_panel(alpha_degrees, &maps[i], d, i, count);
    if (status == IM_OK) {
        im_plot plot = im_plot_default();
        paper_plot_grid(&plot, d->panels, count);
        status = paper_plot_write(&plot, file);
    }
    free(d);
    return status;
}
