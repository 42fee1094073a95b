/* paper/: the paper's figures, built from plain data. A builder takes arrays and numbers (what a
 * scene measured, or what a test makes up) and one path, lays the figure out with plot/ (line
 * plots) or figure/ (contact maps) and writes it: PNG, PDF or SVG by the path's extension,
 * atomically (nothing is left at the path on an error). Builders know nothing of scenes; scene/
 * gathers the data and calls them once per file (NAME.png, NAME.pdf), each a paper_file: its path and
 * what it carries beside the drawing (the run's provenance as PNG text chunks and PDF metadata).
 *
 * Builders are re-entrant: they keep nothing between calls (their working memory is allocated per
 * call), so two threads may build figures at once.
 *
 * Figs. 1, 2 and 3, which need no contact solution, are public (paper.h: im_paper_fig*,
 * theory_figures.c); the figures drawn from solutions are here (history_figures.c: Figs. 5, 6, 7
 * and the sphere's regimes; map_figures.c: Fig. 4's contact panels and the contact density;
 * flat_k_figure.c: eq. (2)'s k measured; sweep_figure.c: Fig. 2 over a sweep's roughnesses;
 * distribution_figure.c: gap and patch-size distributions).
 *
 * Units: lengths (approach, radius, axis) in the surface's units, delta its grid spacing, loads N
 * in those units with E* (the plots divide by E* delta^2). Errors: IM_EINVAL for data that cannot
 * be drawn (the message names `source`, e.g. the scene file), IM_ENOMEM, and im_plot_write's or
 * im_figure_write's errors. */
#ifndef INDENTMAP_PAPER_FIGURES_H
#define INDENTMAP_PAPER_FIGURES_H

#include "indentmap/colormap.h"
#include "indentmap/field.h"
#include "indentmap/io.h"
#include "indentmap/plot.h"
#include "indentmap/render.h"

#include <stdio.h>

/* At most this many panels in a figure, and this many surfaces drawn per panel (the first ones). */
enum { PAPER_MAX_PANELS = 64, PAPER_MAX_SURFACE_LINES = 64 };
/* At most this many texts in a file, the builder's own among them. */
enum { PAPER_MAX_TEXTS = 16 };

/* Where a builder writes, and the texts the file carries (NULL: none). */
typedef struct paper_file {
    const char *path;
    const im_png_text *texts;
    int text_count;
} paper_file;

/* Writes plot to the file, with its texts. */
int paper_plot_write(im_plot *plot, const paper_file *file);
/* The default plot settings with the file's texts: the style of paper.h's figure builders. */
im_plot paper_file_style(const paper_file *file);

/* Columns of a grid of count panels: three when they fill whole rows (Fig. 4's 2 x 3), else two,
 * else a single row. */
int paper_panel_columns(int count);
/* A plot's grid of count panels (plot.h): paper_panel_columns' when it has at most three columns, else
 * rows of three, the last one part empty (a row of five stood 4633 px wide at 300 dpi). */
void paper_plot_grid(im_plot *plot, const im_plot_panel *panels, int count);

/* ---- histories (history_figures.c) ---- */

/* One surface's indentation history: `steps` rows (borrowed arrays). */
typedef struct paper_history {
    int family; /* its family (0-based): the panel it is drawn in */
    int steps;
    const double *approach;   /* w */
    const double *load;       /* N */
    const double *load_star;  /* N* */
    const double *area_ratio; /* A / A_cone (cone), A / A_Hertz (sphere) */
    const long *patches;      /* contact patches n_p (A / delta^2) */
} paper_history;

/* The histories of an ensemble of families (a family: the surfaces of one roughness). */
typedef struct paper_histories {
    const char *source;           /* named in error messages */
    int family_count;             /* 1 to PAPER_MAX_PANELS */
    const double *slopes;         /* per family: h'rms, 0 for a smooth family */
    const char *const *titles;    /* per family: the panel's title */
    const double *eq12;           /* per family: eq. (12)'s A / A_cone, NaN where none (Fig. 5) */
    const paper_history *members; /* every surface, in any order */
    int count;
    double delta, e_star, cot_alpha; /* grid spacing, E*, cot of the cone's half angle */
} paper_histories;

/* Fig. 5 (load = 0: A / delta^2) or Fig. 6 (load = 1: N / (E* delta^2)) against w, a panel per
 * family: every surface thin, the smooth cone's closed form (Love) thick, and for Fig. 5 eq. (12)
 * dashed on rough families. */
int paper_figure_against_approach(const paper_histories *h, int load, const paper_file *file);

/* Fig. 7: A / A_cone against N* for each rough family: the mean over its surfaces (solid) and
 * +- one standard deviation (dotted), on the N* range every surface reached. IM_EINVAL when no
 * rough family's surfaces share a range. */
int paper_figure_area_ratio_against_load(const paper_histories *h, const paper_file *file);
/* The numbers Fig. 7 plots, as CSV on out: a header, then per rough family and N* point the slope,
 * N*, the mean and standard deviation of A / A_cone, the surfaces averaged and eq. (12)'s ratio
 * (nan where the family has none). Same errors as the figure, and nothing written on any. */
int paper_write_area_ratio_statistics(const paper_histories *h, FILE *out);

/* A contact of fewer patches than this is below the grid's resolution: its area is counted in
 * whole patches (one patch more or less is 10 % or more of it), so the sphere's figure starts each
 * surface at its first step of at least this many contact patches. */
enum { PAPER_MIN_PATCHES = 10 };
/* The first step of m with at least PAPER_MIN_PATCHES contact patches; m->steps when none has. */
int paper_first_resolved_step(const paper_history *m);

/* A rough family of the sphere's figure: its crossover load and the theory curves beside it. */
typedef struct paper_sphere_family {
    int family;            /* index into the histories' families */
    double crossover_load; /* N_c of eq. (3) */
    int theory_points;
    const double *theory_x;                       /* N / N_c */
    const double *theory_constant, *theory_gamma; /* A / A_Hertz: eq. (3), the gamma integral */
} paper_sphere_family;

/* Pastewka and Robbins' regimes: A / A_Hertz against N / N_c on log axes, a panel per rough
 * family (count >= 1): every surface thin from its first resolved step (below), eq. (3) thick and
 * the gamma integral dashed in a second colour on top of it (the two nearly coincide). */
int paper_figure_sphere_regimes(const paper_histories *h, const paper_sphere_family *families, int count,
                                const paper_file *file);

/* ---- contact maps (map_figures.c) ---- */

/* The key of the text chunk (PNG) and metadata entry (PDF) holding a scene's contents as parsed
 * (im_scene.contents), beside its "Software" and "Source" (the path). */
#define PAPER_SCENE_CONTENTS "Scene contents"

/* Fig. 4: the rendered contact maps of count families (1 to PAPER_MAX_PANELS) in a grid, labelled
 * (a), (b), ... and titled, with one colour bar of the shared norm (extended below it when
 * extend_under) and the load N* stated under the panels. The file carries its texts and the load
 * ("Load": "N* = ..."); `source` is named in error messages. */
typedef struct paper_contact_panels {
    int count;
    const im_image *images;    /* count maps (borrowed) */
    const char *const *titles; /* count titles */
    const im_colormap *norm;
    const im_colormap *tension;    /* the tension's norm and bar; NULL: none (no map has tension) */
    int extend_under, extend_over; /* forces below / above norm: the colour bar's triangles */
    const char *norm_text;         /* the PNG's "Norm" text (render's and the frames'), NULL: none */
    const char *source;
    double load_star;
} paper_contact_panels;
int paper_figure_contact_panels(const paper_contact_panels *in, const paper_file *file);

/* The local contact density seen directly: the contact fraction of each map averaged over rings
 * of width 0.05 a around the punch axis, out to 1.3 a, beside gamma(r/a) of eq. (10) for a cone. */
typedef struct paper_density_map {
    const im_field *force; /* force per patch; contact where > 0 */
    double axis_x, axis_y; /* the punch axis from the grid's corner */
    double radius;         /* a, the smooth contact radius */
    double slope;          /* h'rms (> 0), for gamma and the title */
    double load_star;      /* N* of the map, stated in its title */
} paper_density_map;
int paper_figure_contact_density(double alpha_degrees, const paper_density_map *maps, int count,
                                 const paper_file *file);

/* ---- eq. (2)'s k (flat_k_figure.c) ---- */

/* One rough family pressed flat: A / A0 against x = p_m / (h'rms E*) and the fitted k. */
typedef struct paper_flat_family {
    double slope; /* h'rms */
    int points;
    const double *x, *area; /* the surfaces' points */
    double k, k_error;      /* fitted k of A / A0 = erf(sqrt(pi) / 2 k x) and its error */
} paper_flat_family;

/* A panel per family: the points, erf with the fitted k and erf with k = 2, over x in [0, x_max]. */
int paper_figure_flat_k(const paper_flat_family *families, int count, double x_max, const paper_file *file);

/* ---- Fig. 2 over a sweep (sweep_figure.c) ---- */

/* At most this many roughness groups in a sweep's Fig. 2. */
enum { PAPER_MAX_SWEEP_GROUPS = 8 };

/* The points of one roughness (h'rms, H, lambda_s) of a sweep: along a group only alpha varies.
 * Borrowed arrays of count points: rho_c = cot alpha / h'rms (> 0, finite), the mean A / A_cone
 * and its standard deviation (NULL: no bars; NaN or 0: no bar at that point). */
typedef struct paper_sweep_group {
    const char *label; /* legend entry */
    int count;
    const double *rho_c, *area_ratio, *sd;
} paper_sweep_group;

/* The theory of Fig. 2 on `points` log-spaced rho_c from lo to hi (PR normalisation, k = 2):
 * eq. (12) (variable density) into variable and eq. (6) (constant density) into constant.
 * theory.h's errors. (Shared with the public Fig. 2, theory_figures.c.) */
int paper_area_ratio_curves(double lo, double hi, int points, double *rho, double *variable, double *constant);

/* A / A_cone against rho_c on a log axis from 0.1 to 100, widened to whole decades around the
 * points: eq. (12) solid and eq. (6) dotted in black, and each group (0 to PAPER_MAX_SWEEP_GROUPS)
 * as markers with error bars of its own colour and shape. IM_EINVAL (naming `source`) for too
 * many groups, a group without arrays or a rho_c that is not positive and finite. */
int paper_figure_sweep(const paper_sweep_group *groups, int count, const char *source, const paper_file *file);

/* ---- gap and contact-patch size distributions (distribution_figure.c) ---- */

/* One family's distributions at one load (borrowed arrays; NaN where a bin is empty, a gap in
 * the line). Gaps g in the surface's h_rms, density per cell of the whole grid and unit gap;
 * patch areas in delta^2 (one per octave: the smallest area of the octave), patches counted. */
typedef struct paper_distribution_family {
    const char *label; /* legend entry */
    int rough;         /* non-zero: drawn in (a) too (a smooth surface has no h_rms) */
    int gap_bins;
    const double *gap, *gap_density;
    int patch_bins;
    const double *patch_area, *patch_count;
} paper_distribution_family;

/* (a) the gap density against g / h_rms of the rough families (log y), (b) patches per octave of
 * area of every family (log-log), one colour per family (viridis order); (b) alone when no family
 * is rough. IM_EINVAL (naming `source`) for count outside 1 to PAPER_MAX_PANELS or a family
 * without its arrays. */
int paper_figure_distributions(const paper_distribution_family *families, int count, const char *source,
                               const paper_file *file);

#endif
