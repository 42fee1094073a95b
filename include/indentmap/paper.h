/* indentmap/paper.h: the paper's figures that need no contact solution, drawn from its theory.
 *
 * Entry points:
 *   im_paper_fig1_contact_density  Fig. 1: the cone's local contact density gamma(r/a)
 *   im_paper_fig2_area_ratio       Fig. 2: A/A_cone against rho_c, eqs. (6) and (12), with points
 *   im_paper_fig3_surface          Fig. 3: a surface's slope, height, curvature and PSD statistics
 *
 * Each takes the output settings (dpi, font size, frame size, texts, compression) from style
 * (NULL: im_plot_default(); its rows, columns and panels are ignored) and writes path as
 * im_plot_write does (plot.h): PNG, PDF or SVG by the extension, atomically, nothing left at the
 * path on an error. The theory is the paper's: the PR normalisation with k = 2. The figures drawn
 * from contact solutions (Figs. 4-7) are a scene's (scene.h, [output] plots).
 *
 * NULL: path and the arrays a figure needs give IM_EINVAL naming the argument (status.h); style
 * may be NULL, and so may Fig. 2's points. Errors: IM_EINVAL for arguments out of range (each
 * entry says which), then im_plot_write's (IM_EINVAL, IM_ENUMERIC, IM_EUNSUPPORTED without the
 * fonts, IM_EIO, IM_ENOMEM). Threads: re-entrant; two threads may draw figures at once (to
 * different paths).
 */
#ifndef INDENTMAP_PAPER_H
#define INDENTMAP_PAPER_H

#include "indentmap/field.h"
#include "indentmap/plot.h"
#include "indentmap/surface.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Fig. 1: the local contact density gamma(r/a) = erf(sqrt(pi)/2 rho_c acosh(a/r)) (eqs. 10-11) on
 * 0 <= r/a <= 1 for a cone of semi-opening alpha_deg (0 < alpha < 90; the paper: 80) and each of
 * count roughnesses slope_rms[i] >= 0 (the paper: 0.01, 0.02, 0.04, 0.08, 0.16; 0 is the smooth
 * surface, gamma = 1), coloured as a viridis family, with h'rms and rho_c (eq. 7) in the legend.
 * IM_EINVAL for count outside [1, 16], a negative or non-finite slope, alpha_deg outside (0, 90). */
int im_paper_fig1_contact_density(double alpha_deg, const double *slope_rms, int count, const im_plot *style,
                                  const char *path);

/* Measured points with error bars for Fig. 2, e.g. the ensemble means +- standard deviations of
 * A/A_cone at each rho_c. sigma may be NULL (no bars). */
typedef struct im_paper_points {
    const double *x, *y, *sigma;
    int count;         /* 0: no points */
    const char *label; /* legend entry; NULL: "simulations (mean ± sd)" */
} im_paper_points;

/* Fig. 2: A/A_cone against rho_c on a log axis from 0.1 to 100 (widened to whole decades around
 * the points): eq. (12) (variable density, solid) and eq. (6) (constant density, dotted), with
 * the points (NULL or count 0: none), which follow plot.h's data rules (rho_c > 0). IM_EINVAL for
 * points with count > 0 but no x or y array. */
int im_paper_fig2_area_ratio(const im_paper_points *points, const im_plot *style, const char *path);

/* Fig. 3, a 2 x 2 figure of a surface: the distributions of (a) slope (both forward-difference
 * components), (b) height h - mean and (c) mean curvature (im_surface_histogram, `bins` bins,
 * 10 to 10000), each with the Gaussian of the same mean and standard deviation dashed, and (d)
 * the isotropic PSD C_iso(q) (im_surface_psd, log-log) with the power law q^(-2(1+H)) of
 * params->hurst drawn dashed beside it over params' band 2 pi / lambda_r <= q <= 2 pi / lambda_s
 * (a factor 4 above the spectrum's geometric mean there). Lengths are normalised by the grid
 * spacing delta: h / delta, curvature x delta, q delta, C / delta^4. params: those the surface was
 * generated with (only hurst, lambda_s and lambda_r are read). IM_EINVAL for an invalid surface
 * view, a NULL params, bins outside [10, 10000], or not 0 < hurst < 1 and 0 < lambda_s < lambda_r. */
int im_paper_fig3_surface(const im_field *surface, const im_surface_params *params, int bins, const im_plot *style,
                          const char *path);

#ifdef __cplusplus
}
#endif

#endif
