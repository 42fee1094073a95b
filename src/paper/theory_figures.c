/* The paper's figures that need no contact solution: Fig. 1 (local contact density of the cone),
 * Fig. 2 (area ratio against rho_c, eqs. 6 and 12) and Fig. 3 (statistics of a surface). */
#include "indentmap/paper.h"
#include "core/args.h"
#include "paper/figures.h"

#include "indentmap/status.h"
#include "indentmap/theory.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { FIG1_MAX_CURVES = 16, FIG1_POINTS = 801, FIG2_POINTS = 241, FIG3_PSD_BINS = 40 };

/* The output settings of style (or the defaults) with the given grid and panels. */
static im_plot plot_like(const im_plot *style, int rows, int columns, const im_plot_panel *panels)
{
    im_plot plot = style ? *style : im_plot_default();
    plot.rows = rows, plot.columns = columns, plot.panels = panels;
    return plot;
}

/* ---- Fig. 1 ---- */

/* gamma(s) for s = r/a in [0, 1], the points crowded towards the rim, where gamma falls fastest. */
static int density_curve(double beta, double *s, double *gamma)
{
    for (int i = 0; i < FIG1_POINTS; ++i) {
        double u = (double)i / (FIG1_POINTS - 1);
        s[i] = 1.0 - (1.0 - u) * (1.0 - u);
        int status = im_theory_cone_contact_density(beta, s[i], &gamma[i]);
        if (status != IM_OK)
            return status;
    }
    return IM_OK;
}

static int density_label(double slope_rms, double rho, char *text, size_t size)
{
    if (slope_rms == 0.0)
        return snprintf(text, size, "smooth");
    return snprintf(text, size, "%g  (%.2f)", slope_rms, rho);
}

int im_paper_fig1_contact_density(double alpha_deg, const double *slope_rms, int count, const im_plot *style,
                                  const char *path)
{
    ARG_REQUIRE(slope_rms, "slope_rms");
    ARG_REQUIRE(path, "path");
    if (count < 1 || count > FIG1_MAX_CURVES || !slope_rms)
        return im_fail(IM_EINVAL, "Fig. 1: %d roughness values: expected 1 to %d", count, FIG1_MAX_CURVES);
    double *buffer = malloc(sizeof(double) * 2 * FIG1_POINTS * (size_t)count);
    char labels[FIG1_MAX_CURVES][96];
    im_plot_series series[FIG1_MAX_CURVES];
    if (!buffer)
        return im_fail(IM_ENOMEM, "Fig. 1: out of memory");
    int status = IM_OK;
    for (int i = 0; status == IM_OK && i < count; ++i) {
        if (!(slope_rms[i] >= 0.0 && isfinite(slope_rms[i]))) {
            status = im_fail(IM_EINVAL, "Fig. 1: h'rms[%d] = %g: expected a finite value >= 0", i, slope_rms[i]);
            break;
        }
        im_theory_interface rough = im_theory_interface_default(slope_rms[i]);
        double rho = 0.0, beta, *s = buffer + (size_t)2 * FIG1_POINTS * i, *gamma = s + FIG1_POINTS;
        status = im_theory_cone_rho(&rough, alpha_deg, &rho);
        if (status == IM_OK)
            status = im_theory_erf_scale(rho, rough.normalisation, rough.k, &beta);
        if (status == IM_OK)
            status = density_curve(beta, s, gamma);
        density_label(slope_rms[i], rho, labels[i], sizeof labels[i]);
        series[i] = (im_plot_series){.x = s, .y = gamma, .n = FIG1_POINTS, .line_width = 1.2, .label = labels[i]};
        im_plot_family_color(i, count, series[i].color);
    }
    if (status == IM_OK) {
        char title[64];
        snprintf(title, sizeof title, "cone, α = %g°", alpha_deg);
        im_plot_panel panel = {.x = {IM_PLOT_LINEAR, 0.0, 1.0, "r / a"},
                               .y = {IM_PLOT_LINEAR, 0.0, 1.05, "γ(r)"},
                               .series = series,
                               .series_count = count,
                               .title = title,
                               .legend_title = "h′_{rms}  (ρ_{c})"};
        im_plot plot = plot_like(style, 1, 1, &panel);
        status = im_plot_write(&plot, path);
    }
    free(buffer);
    return status;
}

/* ---- Fig. 2 ---- */

int paper_area_ratio_curves(double rho_lo, double rho_hi, int points, double *rho, double *variable, double *constant)
{
    for (int i = 0; i < points; ++i) {
        rho[i] = rho_lo * pow(rho_hi / rho_lo, (double)i / (points - 1));
        double beta;
        int status = im_theory_erf_scale(rho[i], IM_THEORY_NORMALISATION_PR, IM_THEORY_K_DEFAULT, &beta);
        if (status == IM_OK)
            status = im_theory_cone_area_ratio_variable(beta, &variable[i]);
        if (status == IM_OK)
            status = im_theory_cone_area_ratio_constant(beta, &constant[i]);
        if (status != IM_OK)
            return status;
    }
    return IM_OK;
}

/* [0.1, 100] widened to whole decades around the points' positive finite x. */
static void rho_range(const im_paper_points *points, double *lo, double *hi)
{
    *lo = 0.1, *hi = 100.0;
    for (int i = 0; points && i < points->count; ++i)
        if (points->x[i] > 0.0 && isfinite(points->x[i])) {
            *lo = fmin(*lo, pow(10.0, floor(log10(points->x[i]))));
            *hi = fmax(*hi, pow(10.0, ceil(log10(points->x[i]))));
        }
}

int im_paper_fig2_area_ratio(const im_paper_points *points, const im_plot *style, const char *path)
{
    ARG_REQUIRE(path, "path");
    int has_points = points && points->count > 0;
    if (has_points && (!points->x || !points->y))
        return im_fail(IM_EINVAL, "Fig. 2: %d points without x or y arrays", points->count);
    double lo, hi, curves[3][FIG2_POINTS];
    rho_range(points, &lo, &hi);
    int status = paper_area_ratio_curves(lo, hi, FIG2_POINTS, curves[0], curves[1], curves[2]);
    if (status != IM_OK)
        return status;
    im_plot_series series[3] = {
        {.x = curves[0], .y = curves[1], .n = FIG2_POINTS, .line_width = 1.2, .label = "eq. (12), variable γ"},
        {.x = curves[0],
         .y = curves[2],
         .n = FIG2_POINTS,
         .line = IM_PLOT_DOTTED,
         .line_width = 1.5,
         .label = "eq. (6), constant γ"},
    };
    im_plot_palette(6, series[0].color); /* black: the theory */
    im_plot_palette(6, series[1].color);
    if (has_points) {
        series[2] = (im_plot_series){.x = points->x,
                                     .y = points->y,
                                     .sigma = points->sigma,
                                     .n = points->count,
                                     .line = IM_PLOT_NO_LINE,
                                     .marker = IM_PLOT_MARKER_CIRCLE,
                                     .marker_size = 4.0,
                                     .label = points->label ? points->label : "simulations (mean ± sd)"};
        im_plot_palette(1, series[2].color);
    }
    im_plot_panel panel = {.x = {IM_PLOT_LOG, lo, hi, "ρ_{c} = cot α / h′_{rms}"},
                           .y = {IM_PLOT_LINEAR, 0.0, 1.05, "A / A_{cone}"},
                           .series = series,
                           .series_count = has_points ? 3 : 2,
                           .legend = IM_PLOT_LEGEND_AUTO};
    im_plot plot = plot_like(style, 1, 1, &panel);
    return im_plot_write(&plot, path);
}

/* ---- Fig. 3 ---- */

/* Gaussian density with the histogram's own mean and standard deviation, at its bin centres. */
static void gaussian_of(const im_histogram *h, double *gaussian)
{
    double width = (h->hi - h->lo) / h->bins, mean = 0.0, variance = 0.0;
    for (int i = 0; i < h->bins; ++i)
        mean += h->centre[i] * h->density[i] * width;
    for (int i = 0; i < h->bins; ++i)
        variance += (h->centre[i] - mean) * (h->centre[i] - mean) * h->density[i] * width;
    double sd = sqrt(variance);
    for (int i = 0; i < h->bins; ++i) {
        double z = (h->centre[i] - mean) / sd;
        gaussian[i] = sd > 0.0 ? exp(-0.5 * z * z) / (sd * sqrt(2.0 * M_PI)) : NAN;
    }
}

/* Rescales a histogram of a quantity with dimension length^power to units of delta^power. */
static void normalise_histogram(im_histogram *h, double delta, int power)
{
    double unit = pow(delta, power);
    for (int i = 0; i < h->bins; ++i) {
        h->centre[i] /= unit;
        h->density[i] *= unit;
    }
    h->lo /= unit, h->hi /= unit;
}

/* The PSD in units of delta (q delta, C / delta^4), packed to the bins that hold modes with C
 * above zero to rounding (none above q_s): returns how many remain at the front of q and c. */
static int normalise_psd(im_psd *psd, double delta)
{
    double largest = 0.0;
    for (int i = 0; i < psd->bins; ++i)
        if (psd->counts[i] && psd->c[i] > largest)
            largest = psd->c[i];
    int kept = 0;
    for (int i = 0; i < psd->bins; ++i)
        if (psd->counts[i] && psd->c[i] > 1e-10 * largest) {
            psd->q[kept] = psd->q[i] * delta;
            psd->c[kept++] = psd->c[i] / pow(delta, 4);
        }
    return kept;
}

/* The power law q^exponent over [q_lo, q_hi], a factor 4 above the spectrum's geometric mean
 * there (in C q^-exponent), so that it runs beside the data. IM_EINVAL without data in the band. */
static int power_law(const im_psd *psd, int count, double exponent, double q_lo, double q_hi, double q[2],
                     double c[2])
{
    double sum = 0.0;
    int n = 0;
    for (int i = 0; i < count; ++i)
        if (psd->q[i] >= q_lo && psd->q[i] <= q_hi)
            sum += log(psd->c[i]) - exponent * log(psd->q[i]), ++n;
    if (n == 0)
        return im_fail(IM_EINVAL, "Fig. 3: no PSD bins in the power-law band q delta in [%g, %g]", q_lo, q_hi);
    double prefactor = 4.0 * exp(sum / n);
    q[0] = q_lo, q[1] = q_hi;
    c[0] = prefactor * pow(q_lo, exponent), c[1] = prefactor * pow(q_hi, exponent);
    return IM_OK;
}

typedef struct surface_figure {
    im_histogram *hist[3];
    double *gaussian[3];
    im_psd *psd;
    int psd_count; /* bins kept by normalise_psd */
    double law_q[2], law_c[2];
    char law_label[64];
    im_plot_series series[8];
    im_plot_panel panels[4];
} surface_figure;

static int compute_statistics(const im_field *surface, const im_surface_params *params, int bins, surface_figure *f)
{
    static const enum im_histogram_quantity quantities[3] = {IM_HIST_SLOPE, IM_HIST_HEIGHT, IM_HIST_CURVATURE};
    static const int powers[3] = {0, 1, -1}; /* dimension of each quantity: length^power */
    int status = IM_OK;
    for (int k = 0; status == IM_OK && k < 3; ++k) {
        status = im_surface_histogram(surface, quantities[k], bins, &f->hist[k]);
        f->gaussian[k] = status == IM_OK ? malloc(sizeof(double) * (size_t)bins) : NULL;
        if (status == IM_OK && !f->gaussian[k])
            status = im_fail(IM_ENOMEM, "Fig. 3: out of memory");
        if (status == IM_OK) {
            normalise_histogram(f->hist[k], surface->delta, powers[k]);
            gaussian_of(f->hist[k], f->gaussian[k]);
        }
    }
    if (status == IM_OK)
        status = im_surface_psd(surface, FIG3_PSD_BINS, &f->psd);
    if (status != IM_OK)
        return status;
    f->psd_count = normalise_psd(f->psd, surface->delta);
    double exponent = -2.0 * (1.0 + params->hurst);
    snprintf(f->law_label, sizeof f->law_label, "∝ q^{−%.2g}  (H = %g)", -exponent, params->hurst);
    return power_law(f->psd, f->psd_count, exponent, 2.0 * M_PI / params->lambda_r, 2.0 * M_PI / params->lambda_s,
                     f->law_q, f->law_c);
}

static void layout_surface_figure(surface_figure *f, int bins)
{
    static const char *const labels[3] = {"(a)", "(b)", "(c)"};
    static const char *const quantities[3] = {"slope ∂h/∂x, ∂h/∂y", "height (h − h̄) / δ", "curvature κ δ"};
    for (int k = 0; k < 3; ++k) {
        im_plot_series *s = &f->series[2 * k];
        /* The Gaussian, thin and dashed in a second colour, on top of the broad histogram line:
         * where they agree both stay visible. */
        s[0] = (im_plot_series){.x = f->hist[k]->centre,
                                .y = f->hist[k]->density,
                                .n = bins,
                                .line_width = 1.8,
                                .label = "surface"};
        s[1] = (im_plot_series){.x = f->hist[k]->centre,
                                .y = f->gaussian[k],
                                .n = bins,
                                .line = IM_PLOT_DASHED,
                                .line_width = 0.9,
                                .label = "Gaussian"};
        im_plot_palette(0, s[0].color);
        im_plot_palette(1, s[1].color);
        f->panels[k] = (im_plot_panel){.x = {IM_PLOT_LINEAR, f->hist[k]->lo, f->hist[k]->hi, quantities[k]},
                                       .y = {.label = "probability density"},
                                       .series = s,
                                       .series_count = 2,
                                       .label = labels[k],
                                       .legend = k == 0 ? IM_PLOT_LEGEND_UPPER_RIGHT : IM_PLOT_LEGEND_HIDDEN};
    }
    im_plot_series *s = &f->series[6];
    s[0] = (im_plot_series){.x = f->psd->q,
                            .y = f->psd->c,
                            .n = f->psd_count,
                            .line_width = 0.8,
                            .marker = IM_PLOT_MARKER_CIRCLE,
                            .marker_size = 3.0,
                            .label = "C^{iso}(q)"};
    s[1] = (im_plot_series){.x = f->law_q, .y = f->law_c, .n = 2, .line = IM_PLOT_DASHED, .label = f->law_label};
    im_plot_palette(0, s[0].color);
    im_plot_palette(6, s[1].color);
    f->panels[3] = (im_plot_panel){.x = {IM_PLOT_LOG, 0, 0, "wave number q δ"},
                                   .y = {IM_PLOT_LOG, 0, 0, "C^{iso}(q) / δ^{4}"},
                                   .series = s,
                                   .series_count = 2,
                                   .label = "(d)",
                                   .legend = IM_PLOT_LEGEND_LOWER_LEFT};
}

int im_paper_fig3_surface(const im_field *surface, const im_surface_params *params, int bins, const im_plot *style,
                          const char *path)
{
    ARG_VIEW(surface, "surface");
    ARG_REQUIRE(params, "params");
    ARG_REQUIRE(path, "path");
    if (!surface || !params)
        return im_fail(IM_EINVAL, "Fig. 3: a surface and its parameters are required");
    if (bins < 10 || bins > 10000)
        return im_fail(IM_EINVAL, "Fig. 3: %d bins: expected 10 to 10000", bins);
    if (!(params->hurst > 0.0 && params->hurst < 1.0) ||
        !(params->lambda_s > 0.0 && params->lambda_r > params->lambda_s))
        return im_fail(IM_EINVAL,
                       "Fig. 3: H = %g, lambda_s = %g, lambda_r = %g: expected 0 < H < 1 and "
                       "0 < lambda_s < lambda_r",
                       params->hurst, params->lambda_s, params->lambda_r);
    surface_figure *f = calloc(1, sizeof *f);
    if (!f)
        return im_fail(IM_ENOMEM, "Fig. 3: out of memory");
    int status = compute_statistics(surface, params, bins, f);
    if (status == IM_OK) {
        layout_surface_figure(f, bins);
        im_plot plot = plot_like(style, 2, 2, f->panels);
        status = im_plot_write(&plot, path);
    }
    for (int k = 0; k < 3; ++k) {
        im_histogram_free(f->hist[k]);
        free(f->gaussian[k]);
    }
    im_psd_free(f->psd);
    free(f);
    return status;
}
