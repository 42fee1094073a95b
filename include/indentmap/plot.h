/* indentmap/plot.h: publication line and scatter plots drawn with cairo (the paper's Figs. 1-3
 * built on them are in paper.h).
 *
 * Entry points:
 *   im_plot_default, im_plot_write        a grid of panels of series, written as PNG, PDF or SVG
 *   im_plot_geometry_of                   where a panel lands in the picture
 *   im_plot_palette, im_plot_family_color the series' colours
 *
 * A plot is a grid of axes panels (rows x columns, e.g. Fig. 5's 2 x 3). Each panel has a linear
 * or logarithmic x and y axis with nice ticks (1-2-5 steps, or decades: im_figure_ticks), tick
 * labels, axis labels, an optional bold panel label "(a)" and a title above it, a frame with
 * inward ticks on all four sides (labels left and bottom, minor ticks at 2..9 x each decade of a
 * log axis), and the series drawn inside the frame (clipped to it): lines (solid, dashed,
 * dotted), markers, symmetric error bars y +- sigma, shaded bands, and a legend of the labelled
 * series.
 *
 * Text is UTF-8 with the figure module's _{subscript} and ^{superscript} markup, e.g. "ρ_{c}" or
 * "C^{iso}(q) / δ^{4}", in DejaVu Sans loaded with FreeType (no fontconfig).
 *
 * Sizes: the axes boxes have the size panel_width x panel_height points; text, line widths and
 * marker sizes are in points; the layout is made in pixels at dpi (PNG: 300 by default, with a
 * pHYs chunk and the texts as tEXt chunks); PDF and SVG use the same layout at 72 / dpi points per
 * pixel (PDF: the texts as keywords). The format comes from the path's extension (.png, .pdf,
 * .svg). Every file is written atomically: on any error nothing is left at the path.
 *
 * Data rules (checked before anything is drawn or written):
 *   - a series needs n >= 1 points and x, y arrays: IM_EINVAL otherwise;
 *   - NaN in x or y: the point is skipped and the line is broken there (a gap); its error bar and
 *     band are skipped too; a NaN sigma or band end skips that bar or that band point only; a
 *     finite point whose pixel position overflows a double (|value| near 1e308 against the
 *     limits) is a gap as well. Segments leaving the frame, however far, are clipped exactly;
 *   - +-Inf anywhere: IM_ENUMERIC naming the panel, series, array and index;
 *   - x or y <= 0 on a logarithmic axis: IM_EINVAL naming them (the value has no place on it);
 *     the lower end y - sigma of an error bar, or a band end, <= 0 on a log y axis is drawn to
 *     the bottom of the frame;
 *   - negative sigma: IM_EINVAL;
 *   - automatic limits need at least one finite point on the panel: IM_EINVAL otherwise.
 *
 * Misuse (status.h): IM_EINVAL for a NULL plot, path, output or series array and for an invalid
 * field view; im_plot_palette and im_plot_family_color do nothing for a NULL rgb.
 * Threads: thread-safe; two threads may write plots at once (to different paths). The fonts are
 * loaded once per process, under a lock.
 */
#ifndef INDENTMAP_PLOT_H
#define INDENTMAP_PLOT_H

#include "indentmap/io.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum im_plot_scale { IM_PLOT_LINEAR = 0, IM_PLOT_LOG = 1 } im_plot_scale;

typedef enum im_plot_line_style {
    IM_PLOT_SOLID = 0,
    IM_PLOT_DASHED, /* 3.5 pt on, 2 pt off (times the line width above 1 pt) */
    IM_PLOT_DOTTED, /* round dots 1.6 pt apart (times the line width above 1 pt) */
    IM_PLOT_NO_LINE /* markers, error bars and bands only */
} im_plot_line_style;

typedef enum im_plot_marker {
    IM_PLOT_MARKER_NONE = 0,
    IM_PLOT_MARKER_CIRCLE,
    IM_PLOT_MARKER_SQUARE,
    IM_PLOT_MARKER_TRIANGLE,
    IM_PLOT_MARKER_DIAMOND
} im_plot_marker;

typedef struct im_plot_series {
    const double *x, *y;             /* n points, in data units; required */
    int n;                           /* >= 1 */
    const double *sigma;             /* NULL, or n half-lengths: error bars from y - sigma to y + sigma */
    const double *band_lo, *band_hi; /* NULL, or n each: a band shaded between them (both needed) */
    im_plot_line_style line;
    double line_width; /* points; 0: 1 pt */
    im_plot_marker marker;
    double marker_size; /* points across; 0: 4 pt */
    uint8_t color[3];   /* line, markers and bars; the band at 25 % opacity */
    const char *label;  /* legend entry; NULL: not in the legend */
} im_plot_series;

typedef struct im_plot_axis {
    im_plot_scale scale;
    double lo, hi;     /* fixed limits when lo < hi; otherwise automatic: the data's range
                                   widened to whole tick steps (linear) or to the nearest 1, 2 or
                                   5 x 10^k (log) */
    const char *label; /* NULL: none */
} im_plot_axis;

typedef enum im_plot_legend {
    IM_PLOT_LEGEND_AUTO = 0, /* the first corner of the frame (in the order below) whose legend box,
                                   grown by half a font size all round, touches no line, marker or
                                   error bar; outside on the right when every corner would */
    IM_PLOT_LEGEND_UPPER_RIGHT,
    IM_PLOT_LEGEND_UPPER_LEFT,
    IM_PLOT_LEGEND_LOWER_RIGHT,
    IM_PLOT_LEGEND_LOWER_LEFT,
    IM_PLOT_LEGEND_HIDDEN,       /* no legend even when series have labels */
    IM_PLOT_LEGEND_OUTSIDE_RIGHT /* right of the frame, top-aligned with it; the figure widens */
} im_plot_legend;

typedef struct im_plot_panel {
    im_plot_axis x, y;
    const im_plot_series *series; /* series_count >= 0 series, drawn in this order */
    int series_count;
    const char *label;        /* "(a)", bold, above the frame's left edge; NULL: none */
    const char *title;        /* above the frame, centred; NULL: none */
    im_plot_legend legend;    /* drawn when at least one series has a label */
    const char *legend_title; /* a first legend row naming what the labels give; NULL: none */
} im_plot_panel;

typedef struct im_plot {
    int rows, columns;                /* >= 1 each, at most 64 panels */
    const im_plot_panel *panels;      /* panel_count panels, row by row from the top */
    int panel_count;                  /* 0: rows * columns; else more than (rows - 1) * columns and at most
                                   rows * columns: the last row's other cells stay empty */
    double panel_width, panel_height; /* size of each axes frame in points, (0, 2000] */
    double dpi;                       /* (0, 2400] */
    double font_size;                 /* points, (0, 72] */
    const im_png_text *texts;         /* PNG tEXt chunks, PDF keywords; may be NULL */
    int text_count;
    int png_compression; /* zlib level 0-9 */
} im_plot;

/* One panel (panels must still be set), 160 x 120 pt frames, 300 dpi, 8 pt text, PNG compression
 * IM_FIGURE_PNG_COMPRESSION. */
im_plot im_plot_default(void);

/* Checks, lays out and writes the plot. IM_EINVAL for a bad specification or bad data (see the
 * data rules above; the message names the panel and series, counted from 1), IM_ENUMERIC for
 * infinities, IM_EUNSUPPORTED when the fonts cannot be loaded, IM_EIO when the file cannot be
 * written (nothing is left behind), IM_ENOMEM. */
int im_plot_write(const im_plot *plot, const char *path);

/* Where a panel lands in the PNG that im_plot_write makes, in pixels from the top left corner. */
typedef struct im_plot_geometry {
    int width, height;                                      /* the whole image */
    double box_x, box_y, box_width, box_height;             /* the frame: data x = lo at box_x, hi at
                                                 box_x + box_width; y = lo at box_y + box_height */
    double x_lo, x_hi, y_lo, y_hi;                          /* the limits in force (automatic ones resolved) */
    double legend_x, legend_y, legend_width, legend_height; /* all 0 when there is no legend */
} im_plot_geometry;

/* The geometry of panel (0-based, row by row). Same errors as im_plot_write, less the file's. */
int im_plot_geometry_of(const im_plot *plot, int panel, im_plot_geometry *geometry);

/* ---- colours ---- */

/* Okabe and Ito's colour-blind-safe qualitative palette, in the order used for series:
 * blue, vermillion, bluish green, orange, reddish purple, sky blue, black, yellow; i wraps. */
#define IM_PLOT_PALETTE_SIZE 8
void im_plot_palette(int i, uint8_t rgb[3]);

/* Member i of a family of count curves (e.g. increasing roughness) from the viridis table, from
 * its dark end to 85 % of the way (the last 15 %, pale yellow, reads badly on white). */
void im_plot_family_color(int i, int count, uint8_t rgb[3]);

#ifdef __cplusplus
}
#endif

#endif
