/* Beyond the paper: the local contact density seen directly. The contact fraction of a simulated
 * map averaged over rings of radius r around the punch axis, beside the theory's gamma(r/a) of
 * eq. (10), for every rough family at the panels' load. */
#include "indentmap/plot.h"
#include "indentmap/status.h"
#include "indentmap/theory.h"
#include "scene/scene_internal.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

enum { RINGS = 26 };               /* rings of width 0.05 a out to 1.3 a */
static const double RING_WIDTH = 0.05;

/* Contact fraction per ring of width RING_WIDTH a around the punch axis (NaN for an empty ring). */
static void ring_fractions(const im_field *force, const im_indenter *punch, double a, double *r_over_a,
                           double *fraction)
{
    double x0, y0, contact[RINGS] = {0}, total[RINGS] = {0};
    im_indenter_axis(punch, force->nx, force->ny, force->delta, &x0, &y0);
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
static int theory_density(const im_scene *scene, double slope, double *r_over_a, double *gamma, int count)
{
    im_theory_interface rough = im_theory_interface_default(slope);
    double rho, beta;
    int status = im_theory_cone_rho(&rough, scene->alpha_degrees, &rho);
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

int scene_plot_contact_density(const im_scene *scene, const im_field *const *forces, const double *load_star)
{
    enum { THEORY_POINTS = 261 };
    static double rings[IM_SCENE_MAX_FAMILIES][RINGS], fractions[IM_SCENE_MAX_FAMILIES][RINGS];
    static double theory_r[IM_SCENE_MAX_FAMILIES][THEORY_POINTS], theory_gamma[IM_SCENE_MAX_FAMILIES][THEORY_POINTS];
    im_plot_series series[IM_SCENE_MAX_FAMILIES][2];
    im_plot_panel panels[IM_SCENE_MAX_FAMILIES];
    char titles[IM_SCENE_MAX_FAMILIES][64];
    im_indenter punch = scene_punch(scene);
    int count = 0, status = IM_OK;
    for (int f = 0; f < scene->family_count && status == IM_OK; ++f) {
        if (!(scene->slopes[f] > 0.0))
            continue;
        double a = sqrt(load_star[f] / M_PI) * forces[f]->delta; /* smooth contact radius */
        ring_fractions(forces[f], &punch, a, rings[count], fractions[count]);
        status = theory_density(scene, scene->slopes[f], theory_r[count], theory_gamma[count], THEORY_POINTS);
        im_plot_series measured = {.x = rings[count], .y = fractions[count], .n = RINGS, .line = IM_PLOT_NO_LINE,
                                   .marker = IM_PLOT_MARKER_CIRCLE, .label = "simulated (ring average)"};
        im_plot_series theory = {.x = theory_r[count], .y = theory_gamma[count], .n = THEORY_POINTS,
                                 .line = IM_PLOT_SOLID, .label = "γ(r) eq. (10)"};
        im_plot_palette(0, measured.color);
        im_plot_palette(6, theory.color);
        series[count][0] = theory;
        series[count][1] = measured;
        snprintf(titles[count], sizeof titles[count], "h′_{rms} = %g", scene->slopes[f]);
        panels[count] = (im_plot_panel){.x = {IM_PLOT_LINEAR, 0.0, 1.3, "r / a"},
                                        .y = {IM_PLOT_LINEAR, 0.0, 1.05, "contact density"},
                                        .series = series[count], .series_count = 2, .title = titles[count],
                                        .legend = count == 0 ? IM_PLOT_LEGEND_LOWER_LEFT : IM_PLOT_LEGEND_HIDDEN};
        ++count;
    }
    if (status != IM_OK || count == 0)
        return status;
    im_plot plot = im_plot_default();
    plot.columns = scene_panel_columns(count);
    plot.rows = count / plot.columns;
    plot.panels = panels;
    return scene_write_png_pdf(scene, "contact_density", scene_draw_plot, &plot);
}
