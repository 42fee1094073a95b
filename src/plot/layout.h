/* The plot module's layout: resolved limits, ticks and pixel boxes of every panel (layout.c), and
 * the drawing of a laid-out plot (draw.c). */
#ifndef INDENTMAP_PLOT_LAYOUT_H
#define INDENTMAP_PLOT_LAYOUT_H

#include "indentmap/plot.h"

#include <cairo.h>

enum { PLOT_MAX_PANELS = 64, PLOT_MAX_TICKS = 40 };

typedef struct plot_axis_layout {
    im_plot_scale scale;
    double lo, hi; /* limits in force */
    double ticks[PLOT_MAX_TICKS];
    int tick_count;
    int label_every; /* label one tick in label_every (crowded decades) */
} plot_axis_layout;

typedef struct plot_panel_layout {
    plot_axis_layout x, y;
    double box_x, box_y, box_width, box_height;             /* the frame, pixels */
    double legend_x, legend_y, legend_width, legend_height; /* 0 size: none */
} plot_panel_layout;

typedef struct plot_layout {
    double font;   /* text size, pixels */
    double points; /* pixels per point */
    int width, height;
    int panel_count;
    plot_panel_layout panels[PLOT_MAX_PANELS];
} plot_layout;

/* Checks the plot and its data (the rules in plot.h), resolves limits and ticks and places
 * everything; measure has the regular font face set. */
int plot_make_layout(const im_plot *plot, cairo_t *measure, plot_layout *layout);

/* Pixel of a data value along an axis whose lo lands at `start` and hi at start + length (for y,
 * pass the bottom of the frame and a negative length). Values <= 0 on a log axis map to -Inf
 * times the direction, so that callers clip them. */
double plot_axis_pixel(const plot_axis_layout *axis, double value, double start, double length);

/* Dimensions of a legend entry row and its line sample, pixels. */
double plot_legend_row_height(const plot_layout *layout);
double plot_legend_sample_length(const plot_layout *layout);
double plot_legend_padding(const plot_layout *layout);

/* Draws the whole plot (white background, panels, series, legends) in pixel coordinates. */
int plot_draw(const im_plot *plot, const plot_layout *layout, cairo_t *cr);

/* Sets the line width and dash of a series' line style on cr (pixels per point given). */
void plot_set_line_style(cairo_t *cr, const im_plot_series *series, double points);
/* Draws a series' marker centred at (x, y). */
void plot_draw_marker(cairo_t *cr, const im_plot_series *series, double points, double x, double y);

#endif
