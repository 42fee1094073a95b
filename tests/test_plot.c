/* Plots (cairo): data on the expected pixels of the frame (lines, markers, error bars, NaN gaps,
 * points far outside), the frame where the geometry says, log ticks evenly spaced by decade,
 * automatic limits, the legend, PNG metadata, PDF and SVG, refusals that leave nothing behind,
 * and the paper's Figs. 1-3 against the theory's closed forms and Table 1. Pixel positions are
 * computed here from the limits and the frame (found in the image), not taken from the drawing. */
#include "support.h"

#include "indentmap/io.h"
#include "indentmap/paper.h"
#include "indentmap/plot.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"
#include "plot/clip.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const uint8_t BLUE[3] = {0, 114, 178}, VERMILLION[3] = {213, 94, 0};

typedef struct picture {
    uint8_t *rgb;
    int width, height;
} picture;

static picture read_picture(const char *path)
{
    picture p;
    int channels;
    assert_int_equal(im_png_read(path, &p.rgb, &p.width, &p.height, &channels), IM_OK);
    assert_int_equal(channels, 3);
    return p;
}

static const uint8_t *pixel(const picture *p, double x, double y)
{
    int ix = (int)floor(x), iy = (int)floor(y);
    assert_true(ix >= 0 && ix < p->width && iy >= 0 && iy < p->height);
    return p->rgb + ((size_t)iy * p->width + ix) * 3;
}

static int same_color(const uint8_t *a, const uint8_t b[3], int tolerance)
{
    return abs(a[0] - b[0]) <= tolerance && abs(a[1] - b[1]) <= tolerance && abs(a[2] - b[2]) <= tolerance;
}

static int is_white(const uint8_t *a) { return a[0] == 255 && a[1] == 255 && a[2] == 255; }
static int is_dark(const uint8_t *a) { return a[0] < 110 && a[1] < 110 && a[2] < 110; }

/* Whether a pixel of colour c lies within radius pixels of (x, y). */
static int color_near(const picture *p, double x, double y, const uint8_t c[3], int radius)
{
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx)
            if (same_color(pixel(p, x + dx, y + dy), c, 12))
                return 1;
    return 0;
}

/* Pixel of data (x, y) in a frame with the given limits, computed here. */
static double expected_x(const im_plot_geometry *g, double x, int logarithmic)
{
    double t = logarithmic ? log(x / g->x_lo) / log(g->x_hi / g->x_lo) : (x - g->x_lo) / (g->x_hi - g->x_lo);
    return g->box_x + t * g->box_width;
}

static double expected_y(const im_plot_geometry *g, double y, int logarithmic)
{
    double t = logarithmic ? log(y / g->y_lo) / log(g->y_hi / g->y_lo) : (y - g->y_lo) / (g->y_hi - g->y_lo);
    return g->box_y + (1.0 - t) * g->box_height;
}

static im_plot small_plot(const im_plot_panel *panel)
{
    im_plot plot = im_plot_default();
    plot.panels = panel;
    plot.dpi = 144.0; /* 2 pixels per point */
    return plot;
}

/* Writes the plot as PNG, reads it back and returns its geometry for panel 0. */
static picture draw(const im_plot *plot, const char *name, im_plot_geometry *g)
{
    assert_int_equal(im_plot_geometry_of(plot, 0, g), IM_OK);
    int status = im_plot_write(plot, test_path(name));
    if (status != IM_OK)
        fail_msg("%s", im_last_error());
    picture p = read_picture(test_path(name));
    assert_int_equal(p.width, g->width);
    assert_int_equal(p.height, g->height);
    return p;
}

/* The frame's left edge and top edge found in the image along a row and a column inside it
 * where no tick or data lies: the first dark pixel met going outward from (x, y). */
static void find_frame(const picture *p, double x, double y, double *left, double *top)
{
    int ix = (int)x, iy = (int)y;
    while (ix > 0 && !is_dark(pixel(p, ix, y)))
        --ix;
    while (iy > 0 && !is_dark(pixel(p, x, iy)))
        --iy;
    *left = ix, *top = iy;
}

static void test_frame_and_line_pixels(void **state)
{
    (void)state;
    double x[] = {0.0, 1.0}, y[] = {0.0, 1.0};
    im_plot_series line = {.x = x, .y = y, .n = 2, .line_width = 2.0};
    memcpy(line.color, BLUE, 3);
    im_plot_panel panel = {.x = {IM_PLOT_LINEAR, 0.0, 1.0, "x"},
                           .y = {IM_PLOT_LINEAR, 0.0, 1.0, "y"},
                           .series = &line,
                           .series_count = 1};
    im_plot plot = small_plot(&panel);
    im_plot_geometry g;
    picture p = draw(&plot, "line.png", &g);
    /* The frame is 160 x 120 pt at 2 pixels per point, and drawn where the geometry says. */
    assert_close(g.box_width, 320.0, 0.0);
    assert_close(g.box_height, 240.0, 0.0);
    double left, top;
    find_frame(&p, g.box_x + 0.3 * g.box_width, g.box_y + 0.3 * g.box_height, &left, &top);
    assert_close(left, g.box_x, 1.0);
    assert_close(top, g.box_y, 1.0);
    for (double t = 0.1; t < 0.95; t += 0.1) {
        double px = g.box_x + t * g.box_width, py = g.box_y + (1.0 - t) * g.box_height;
        if (!same_color(pixel(&p, px, py), BLUE, 12))
            fail_msg("t = %g: pixel (%g, %g) is not the line's colour", t, px, py);
        /* 12 pixels off the line (line width 4 pixels): background. */
        assert_true(is_white(pixel(&p, px, py - 12.0)));
    }
    free(p.rgb);
}

static void test_marker_centre(void **state)
{
    (void)state;
    double x[] = {0.3}, y[] = {0.7};
    im_plot_series point =
        {.x = x, .y = y, .n = 1, .line = IM_PLOT_NO_LINE, .marker = IM_PLOT_MARKER_CIRCLE, .marker_size = 8.0};
    memcpy(point.color, VERMILLION, 3);
    im_plot_panel panel = {.x = {IM_PLOT_LINEAR, 0.0, 2.0, NULL},
                           .y = {IM_PLOT_LINEAR, -1.0, 1.0, NULL},
                           .series = &point,
                           .series_count = 1};
    im_plot plot = small_plot(&panel);
    im_plot_geometry g;
    picture p = draw(&plot, "marker.png", &g);
    double sx = 0.0, sy = 0.0, n = 0.0;
    for (int j = 0; j < p.height; ++j)
        for (int i = 0; i < p.width; ++i)
            if (same_color(pixel(&p, i, j), VERMILLION, 12))
                sx += i + 0.5, sy += j + 0.5, n += 1.0;
    /* An 8 pt circle at 2 pixels per point: about pi 8^2 = 201 pixels. */
    assert_true(n > 150.0 && n < 260.0);
    assert_close(sx / n, g.box_x + 0.15 * g.box_width, 0.5);
    assert_close(sy / n, g.box_y + 0.15 * g.box_height, 0.5);
    free(p.rgb);
}

/* Centres of the dark runs along a row between x0 and x1. */
static int dark_runs(const picture *p, double y, double x0, double x1, double *centres, int capacity)
{
    int count = 0, start = -1;
    for (int x = (int)x0; x <= (int)x1 + 1; ++x) {
        int dark = x <= (int)x1 && is_dark(pixel(p, x, y));
        if (dark && start < 0)
            start = x;
        if (!dark && start >= 0) {
            if (count < capacity)
                centres[count] = 0.5 * (start + x);
            ++count;
            start = -1;
        }
    }
    return count;
}

static void test_log_ticks_by_decade(void **state)
{
    (void)state;
    double x[] = {0.05, 30.0}, y[] = {1.0, 2.0};
    im_plot_series s = {.x = x, .y = y, .n = 2, .line = IM_PLOT_NO_LINE};
    im_plot_panel panel = {.x = {IM_PLOT_LOG, 0.01, 100.0, NULL},
                           .y = {IM_PLOT_LINEAR, 0.0, 3.0, NULL},
                           .series = &s,
                           .series_count = 1};
    im_plot plot = small_plot(&panel);
    im_plot_geometry g;
    picture p = draw(&plot, "log.png", &g);
    /* Major ticks are 3.5 pt (7 px) long, minor ones 2 pt (4 px): a row 5.5 px inside the
     * bottom edge crosses only the majors, at 10^-2 ... 10^2, a quarter of the frame apart. */
    double centres[16];
    int count = dark_runs(&p, g.box_y + g.box_height - 5.5, g.box_x + 2, g.box_x + g.box_width - 2, centres, 16);
    assert_int_equal(count, 3); /* the inner three; the outer two lie on the frame's sides */
    for (int k = 0; k < 3; ++k)
        assert_close(centres[k], g.box_x + (k + 1) * 0.25 * g.box_width, 1.0);
    /* A row 2.5 px inside crosses the minors too: 8 per decade, 4 decades, plus 3 majors. */
    count = dark_runs(&p, g.box_y + g.box_height - 2.5, g.box_x + 2, g.box_x + g.box_width - 2, centres, 16);
    assert_int_equal(count, 4 * 8 + 3);
    free(p.rgb);
}

static void test_automatic_limits(void **state)
{
    (void)state;
    double x[] = {0.03, 1.0, 40.0}, y[] = {0.13, 0.5, 0.87}, sigma[] = {0.0, 0.0, 0.2};
    im_plot_series s = {.x = x, .y = y, .n = 3};
    im_plot_panel panel = {.x = {.scale = IM_PLOT_LOG},
                           .y = {.scale = IM_PLOT_LINEAR},
                           .series = &s,
                           .series_count = 1};
    im_plot plot = small_plot(&panel);
    im_plot_geometry g;
    assert_int_equal(im_plot_geometry_of(&plot, 0, &g), IM_OK);
    assert_close(g.x_lo, 0.02, 1e-15); /* 1-2-5 bounds around 0.03 and 40 */
    assert_close(g.x_hi, 50.0, 1e-12);
    assert_close(g.y_lo, 0.0, 1e-15); /* span 0.74: step 0.2 (about six intervals) */
    assert_close(g.y_hi, 1.0, 1e-12);
    s.sigma = sigma; /* the error bar reaches 1.07: one more step */
    assert_int_equal(im_plot_geometry_of(&plot, 0, &g), IM_OK);
    assert_close(g.y_hi, 1.2, 1e-12);
    double same[] = {5.0, 5.0}; /* a flat series: +-10 % */
    s.y = same, s.n = 2, s.sigma = NULL;
    assert_int_equal(im_plot_geometry_of(&plot, 0, &g), IM_OK);
    assert_true(g.y_lo <= 4.5 && g.y_hi >= 5.5 && g.y_hi - g.y_lo <= 2.0);
}

/* A pixel covered at least a third by BLUE on white (anti-aliased thin lines are never pure). */
static int blueish(const uint8_t *a) { return a[2] - a[0] > 60; }

/* Vertical extent (first to last row) of blueish pixels in the 3 columns around x between rows y0
 * and y1. */
static double column_extent(const picture *p, double x, double y0, double y1)
{
    int first = -1, last = -1;
    for (int y = (int)y0; y <= (int)y1; ++y)
        if (blueish(pixel(p, x - 1, y)) || blueish(pixel(p, x, y)) || blueish(pixel(p, x + 1, y))) {
            if (first < 0)
                first = y;
            last = y;
        }
    return first < 0 ? 0.0 : last - first + 1.0;
}

static void test_error_bars(void **state)
{
    (void)state;
    double x[] = {0.25, 0.75}, y[] = {0.5, 0.4}, sigma[] = {0.2, 0.05};
    im_plot_series s = {.x = x, .y = y, .sigma = sigma, .n = 2, .line = IM_PLOT_NO_LINE};
    memcpy(s.color, BLUE, 3);
    im_plot_panel panel = {.x = {IM_PLOT_LINEAR, 0.0, 1.0, NULL},
                           .y = {IM_PLOT_LINEAR, 0.0, 1.0, NULL},
                           .series = &s,
                           .series_count = 1};
    im_plot plot = small_plot(&panel);
    im_plot_geometry g;
    picture p = draw(&plot, "bars.png", &g);
    for (int i = 0; i < 2; ++i) {
        double column = expected_x(&g, x[i], 0);
        double length = column_extent(&p, column, g.box_y + 2, g.box_y + g.box_height - 2);
        /* 2 sigma in data units, plus the caps' line width (0.6 pt = 1.2 px). */
        assert_close(length, 2.0 * sigma[i] * g.box_height + 1.2, 1.5);
    }
    free(p.rgb);
    /* On a log axis a bar reaching below zero is drawn to the bottom of the frame. */
    double ly[] = {1.0, 1.0}, lsigma[] = {2.0, 0.5};
    s.y = ly, s.sigma = lsigma;
    panel.y = (im_plot_axis){IM_PLOT_LOG, 0.1, 10.0, NULL};
    p = draw(&plot, "logbars.png", &g);
    double column = expected_x(&g, x[0], 0);
    assert_close(column_extent(&p, column, g.box_y + g.box_height - 4, g.box_y + g.box_height - 2), 3.0, 0.0);
    double expected = expected_y(&g, 0.5, 1) - expected_y(&g, 1.5, 1) + 1.2;
    assert_close(column_extent(&p, expected_x(&g, x[1], 0), g.box_y + 2, g.box_y + g.box_height - 2), expected, 1.5);
    free(p.rgb);
}

static void test_nan_gap_and_far_points(void **state)
{
    (void)state;
    double x[11], y[11];
    for (int i = 0; i < 11; ++i)
        x[i] = 0.1 * i, y[i] = 0.1 * i;
    y[5] = NAN;
    double fx[] = {0.5, 1e12}, fy[] = {0.5, -1e12}; /* a segment leaving the frame far away */
    im_plot_series s[2] = {{.x = x, .y = y, .n = 11, .line_width = 2.0},
                           {.x = fx, .y = fy, .n = 2, .line_width = 2.0}};
    memcpy(s[0].color, BLUE, 3);
    memcpy(s[1].color, VERMILLION, 3);
    im_plot_panel panel = {.x = {IM_PLOT_LINEAR, 0.0, 1.0, NULL},
                           .y = {IM_PLOT_LINEAR, 0.0, 1.0, NULL},
                           .series = s,
                           .series_count = 2};
    im_plot plot = small_plot(&panel);
    im_plot_geometry g;
    picture p = draw(&plot, "gap.png", &g);
    assert_true(same_color(pixel(&p, expected_x(&g, 0.25, 0), expected_y(&g, 0.25, 0)), BLUE, 12));
    assert_true(same_color(pixel(&p, expected_x(&g, 0.75, 0), expected_y(&g, 0.75, 0)), BLUE, 12));
    /* Points 4 and 6 are not joined: the gap around x = 0.5 is background. */
    assert_false(color_near(&p, expected_x(&g, 0.47, 0), expected_y(&g, 0.47, 0), BLUE, 2));
    assert_false(color_near(&p, expected_x(&g, 0.53, 0), expected_y(&g, 0.53, 0), BLUE, 2));
    /* The far segment runs from the centre at slope -1 towards the lower right corner. */
    assert_true(same_color(pixel(&p, expected_x(&g, 0.75, 0), expected_y(&g, 0.25, 0)), VERMILLION, 12));
    assert_true(same_color(pixel(&p, expected_x(&g, 0.95, 0), expected_y(&g, 0.05, 0)), VERMILLION, 12));
    free(p.rgb);
}

static void test_band(void **state)
{
    (void)state;
    double x[] = {0.0, 0.25, 0.5, 0.75, 1.0}, y[] = {0.5, 0.5, 0.5, 0.5, 0.5};
    double lo[] = {0.2, 0.2, NAN, 0.2, 0.2}, hi[] = {0.4, 0.4, 0.4, 0.4, 0.4};
    im_plot_series s = {.x = x, .y = y, .n = 5, .band_lo = lo, .band_hi = hi, .line = IM_PLOT_NO_LINE};
    memcpy(s.color, BLUE, 3);
    im_plot_panel panel = {.x = {IM_PLOT_LINEAR, 0.0, 1.0, NULL},
                           .y = {IM_PLOT_LINEAR, 0.0, 1.0, NULL},
                           .series = &s,
                           .series_count = 1};
    im_plot plot = small_plot(&panel);
    im_plot_geometry g;
    picture p = draw(&plot, "band.png", &g);
    /* 25 % blue over white, between 0.2 and 0.4 where band_lo is a number on both sides. */
    const uint8_t tint[3] = {191, 220, 236};
    assert_true(same_color(pixel(&p, expected_x(&g, 0.1, 0), expected_y(&g, 0.3, 0)), tint, 3));
    assert_true(same_color(pixel(&p, expected_x(&g, 0.9, 0), expected_y(&g, 0.21, 0)), tint, 3));
    assert_true(is_white(pixel(&p, expected_x(&g, 0.1, 0), expected_y(&g, 0.45, 0))));
    assert_true(is_white(pixel(&p, expected_x(&g, 0.1, 0), expected_y(&g, 0.15, 0))));
    assert_true(is_white(pixel(&p, expected_x(&g, 0.5, 0), expected_y(&g, 0.3, 0)))); /* the NaN gap */
    free(p.rgb);
    /* An upper end far above the frame: the edge towards it is nearly vertical at x = 0.75, so
     * the band fills the frame above 0.2 on its right; pulling the vertex in would tilt it. */
    hi[4] = 1e9;
    p = draw(&plot, "farband.png", &g);
    assert_true(same_color(pixel(&p, expected_x(&g, 0.875, 0), expected_y(&g, 0.95, 0)), tint, 3));
    assert_true(is_white(pixel(&p, expected_x(&g, 0.7, 0), expected_y(&g, 0.95, 0))));
    free(p.rgb);
}

static double shoelace(const double *xy, int n)
{
    double twice = 0.0;
    for (int i = 0; i < n; ++i) {
        int j = (i + 1) % n;
        twice += xy[2 * i] * xy[2 * j + 1] - xy[2 * j] * xy[2 * i + 1];
    }
    return 0.5 * fabs(twice);
}

static void test_polygon_clipping(void **state)
{
    (void)state;
    plot_rect unit = {0.0, 0.0, 1.0, 1.0};
    /* x + y <= 1.2 in the unit square: 1 - 0.8^2 / 2. */
    double triangle[] = {0.0, 0.0, 1.2, 0.0, 0.0, 1.2}, *out;
    int n = plot_clip_polygon(triangle, 3, unit, &out);
    assert_int_equal(n, 5);
    assert_close(shoelace(out, n), 0.68, 1e-12);
    free(out);
    /* A far vertex: the triangle (0, 0.5), (1e12, 0.5), (0, 1e12) covers the square's top half. */
    double far[] = {0.0, 0.5, 1e12, 0.5, 0.0, 1e12};
    n = plot_clip_polygon(far, 3, unit, &out);
    assert_close(shoelace(out, n), 0.5, 1e-9);
    free(out);
    double outside[] = {2.0, 2.0, 3.0, 2.0, 3.0, 3.0};
    assert_int_equal(plot_clip_polygon(outside, 3, unit, &out), 0);
    assert_null(out);
}

static int count_color(const picture *p, double x, double y, double w, double h, const uint8_t c[3], int dark)
{
    int n = 0;
    for (int j = (int)y; j < (int)(y + h); ++j)
        for (int i = (int)x; i < (int)(x + w); ++i)
            n += dark ? is_dark(pixel(p, i, j)) : same_color(pixel(p, i, j), c, 12);
    return n;
}

static void test_legend(void **state)
{
    (void)state;
    double x[] = {0.0, 0.2}, y[] = {0.0, 0.2};
    im_plot_series s[3] = {{.x = x, .y = y, .n = 2, .label = "first"},
                           {.x = x, .y = y, .n = 2, .line = IM_PLOT_DASHED, .label = "second"},
                           {.x = x, .y = y, .n = 2, .marker = IM_PLOT_MARKER_SQUARE, .line = IM_PLOT_NO_LINE}};
    memcpy(s[0].color, BLUE, 3);
    memcpy(s[1].color, VERMILLION, 3);
    im_plot_panel panel = {.x = {IM_PLOT_LINEAR, 0.0, 1.0, NULL},
                           .y = {IM_PLOT_LINEAR, 0.0, 1.0, NULL},
                           .series = s,
                           .series_count = 3};
    im_plot plot = small_plot(&panel);
    im_plot_geometry g;
    picture p = draw(&plot, "legend.png", &g);
    /* The data sit in the lower left, so the legend goes to the upper right, inside the frame. */
    assert_true(g.legend_width > 0.0 && g.legend_height > 0.0);
    assert_true(g.legend_x > g.box_x + 0.5 * g.box_width && g.legend_y < g.box_y + 0.5 * g.box_height);
    assert_true(g.legend_x + g.legend_width < g.box_x + g.box_width);
    assert_true(count_color(&p, g.legend_x, g.legend_y, g.legend_width, g.legend_height, BLUE, 0) > 20);
    assert_true(count_color(&p, g.legend_x, g.legend_y, g.legend_width, g.legend_height, VERMILLION, 0) > 10);
    assert_true(count_color(&p, g.legend_x, g.legend_y, g.legend_width, g.legend_height, NULL, 1) > 100); /* text */
    double two_rows = g.legend_height;
    free(p.rgb);
    /* A third label adds a row; a title another. */
    s[2].label = "third";
    assert_int_equal(im_plot_geometry_of(&plot, 0, &g), IM_OK);
    double row = g.legend_height - two_rows;
    assert_true(row > 0.0);
    panel.legend_title = "series";
    assert_int_equal(im_plot_geometry_of(&plot, 0, &g), IM_OK);
    assert_close(g.legend_height, two_rows + 2.0 * row, 0.0);
    /* Hidden: no legend, the corner stays white. */
    panel.legend = IM_PLOT_LEGEND_HIDDEN;
    im_plot_geometry shown = g;
    p = draw(&plot, "nolegend.png", &g);
    assert_close(g.legend_width, 0.0, 0.0);
    assert_int_equal(count_color(&p, shown.legend_x + 2, shown.legend_y + 2, shown.legend_width - 4,
                                 shown.legend_height - 4, NULL, 1),
                     0);
    free(p.rgb);
}

/* Data y of the pixel row py on a linear y axis of the geometry g. */
static double data_y(const im_plot_geometry *g, double py)
{
    return g->y_lo + (g->y_hi - g->y_lo) * (g->box_y + g->box_height - py) / g->box_height;
}

/* IM_PLOT_LEGEND_AUTO: a corner whose box a line passes within a few pixels of, with no vertex
 * near it, is not taken (the older rule counted sampled points inside the box only); when every
 * corner is touched the legend goes outside on the right and the figure widens by it. */
static void test_legend_keeps_clear_of_lines(void **state)
{
    (void)state;
    double x[] = {0.0, 1.0}, y[] = {0.0, 0.0};
    im_plot_series s = {.x = x, .y = y, .n = 2, .label = "a line"};
    im_plot_panel panel = {.x = {IM_PLOT_LINEAR, 0.0, 1.0, NULL},
                           .y = {IM_PLOT_LINEAR, 0.0, 1.0, NULL},
                           .series = &s,
                           .series_count = 1};
    im_plot plot = small_plot(&panel);
    im_plot_geometry free_corner, g;
    assert_int_equal(im_plot_geometry_of(&plot, 0, &free_corner), IM_OK);
    assert_true(free_corner.legend_x > free_corner.box_x + 0.5 * free_corner.box_width); /* upper right */
    /* A horizontal line 2 pixels below the upper-right legend, its vertices at the frame's sides. */
    y[0] = y[1] = data_y(&free_corner, free_corner.legend_y + free_corner.legend_height + 2.0);
    assert_int_equal(im_plot_geometry_of(&plot, 0, &g), IM_OK);
    assert_true(g.legend_y > g.box_y + 0.5 * g.box_height); /* a lower corner */
    /* Lines along the top and the bottom rows of legends: no corner is clear. */
    double xs[] = {0.0, 1.0, NAN, 0.0, 1.0};
    double ys[] = {y[0], y[0], NAN, 0.0, 0.0};
    ys[3] = ys[4] = data_y(&free_corner, free_corner.box_y + free_corner.box_height - free_corner.legend_height -
                                             2.0 - (free_corner.legend_y - free_corner.box_y));
    s = (im_plot_series){.x = xs, .y = ys, .n = 5, .label = "two lines"};
    assert_int_equal(im_plot_geometry_of(&plot, 0, &g), IM_OK);
    assert_true(g.legend_x >= g.box_x + g.box_width);
    assert_close(g.legend_y, g.box_y, 0.0);
    assert_true(g.width >= free_corner.width + (int)g.legend_width);
    /* Stated, it goes outside as well; a stated corner stays where it is told. */
    panel.legend = IM_PLOT_LEGEND_UPPER_RIGHT;
    assert_int_equal(im_plot_geometry_of(&plot, 0, &g), IM_OK);
    assert_close(g.legend_x + g.legend_width, free_corner.legend_x + free_corner.legend_width, 0.0);
    assert_int_equal(g.width, free_corner.width);
    panel.legend = IM_PLOT_LEGEND_OUTSIDE_RIGHT;
    s.n = 2;
    assert_int_equal(im_plot_geometry_of(&plot, 0, &g), IM_OK);
    assert_true(g.legend_x >= g.box_x + g.box_width);
    panel.legend = (im_plot_legend)(IM_PLOT_LEGEND_OUTSIDE_RIGHT + 1);
    assert_int_equal(im_plot_geometry_of(&plot, 0, &g), IM_EINVAL);
}

static uint8_t *slurp(const char *path, size_t *size)
{
    FILE *stream = fopen(path, "rb");
    assert_non_null(stream);
    fseek(stream, 0, SEEK_END);
    *size = (size_t)ftell(stream);
    rewind(stream);
    uint8_t *data = malloc(*size + 1);
    assert_int_equal(fread(data, 1, *size, stream), *size);
    data[*size] = 0;
    fclose(stream);
    return data;
}

static int contains(const uint8_t *data, size_t size, const char *text, size_t length)
{
    for (size_t at = 0; at + length <= size; ++at)
        if (memcmp(data + at, text, length) == 0)
            return 1;
    return 0;
}

static void test_png_pdf_svg(void **state)
{
    (void)state;
    double x[] = {1.0, 2.0, 3.0}, y[] = {1.0, 4.0, 9.0};
    im_plot_series s = {.x = x, .y = y, .n = 3, .marker = IM_PLOT_MARKER_TRIANGLE, .label = "squares"};
    im_plot_panel panels[2] = {
        {.x = {.label = "n"},
         .y = {.label = "n^{2}"},
         .series = &s,
         .series_count = 1,
         .label = "(a)",
         .title = "linear"},
        {.x = {.scale = IM_PLOT_LOG}, .y = {.scale = IM_PLOT_LOG}, .series = &s, .series_count = 1, .label = "(b)"}};
    im_png_text texts[] = {{"Figure", "test plot"}};
    im_plot plot = im_plot_default();
    plot.rows = 1, plot.columns = 2, plot.panels = panels, plot.texts = texts, plot.text_count = 1;
    assert_int_equal(im_plot_write(&plot, test_path("meta.png")), IM_OK);
    size_t size;
    uint8_t *data = slurp(test_path("meta.png"), &size);
    assert_true(contains(data, size, "tEXtFigure\0test plot", 20));
    assert_true(contains(data, size, "pHYs\0\0\x2e\x23\0\0\x2e\x23\x01", 13)); /* 11811 per metre, twice */
    free(data);
    /* Two panels side by side: the second frame lies right of the first, at the same height. */
    im_plot_geometry a, b;
    assert_int_equal(im_plot_geometry_of(&plot, 0, &a), IM_OK);
    assert_int_equal(im_plot_geometry_of(&plot, 1, &b), IM_OK);
    assert_true(b.box_x > a.box_x + a.box_width && b.box_y == a.box_y);
    assert_int_equal(im_plot_geometry_of(&plot, 2, &b), IM_EINVAL);
    assert_int_equal(im_plot_write(&plot, test_path("meta.pdf")), IM_OK);
    data = slurp(test_path("meta.pdf"), &size);
    assert_memory_equal(data, "%PDF-", 5);
    assert_true(contains(data, size, "%%EOF", 5));
    assert_true(contains(data, size, "Figure=test plot", 16));
    /* The trailer's startxref gives the byte offset of the cross-reference table. */
    const char *startxref = NULL;
    for (size_t at = 0; at + 9 <= size; ++at)
        if (memcmp(data + at, "startxref", 9) == 0)
            startxref = (const char *)data + at + 9;
    assert_non_null(startxref);
    long offset = strtol(startxref, NULL, 10);
    assert_true(offset > 0 && (size_t)offset + 4 < size);
    assert_memory_equal(data + offset, "xref", 4);
    free(data);
    assert_int_equal(im_plot_write(&plot, test_path("meta.svg")), IM_OK);
    data = slurp(test_path("meta.svg"), &size);
    const char *text = (const char *)data;
    assert_non_null(strstr(text, "<?xml"));
    assert_non_null(strstr(text, "<svg"));
    const char *end = strstr(text, "</svg>");
    assert_non_null(end);
    for (end += 6; *end == '\n'; ++end)
        ;
    assert_int_equal(*end, '\0');              /* complete: nothing after the closing tag */
    assert_non_null(strstr(text, "width=\"")); /* 72 / 300 points per pixel */
    free(data);
}

static int directory_entries(const char *path)
{
    DIR *dir = opendir(path);
    int count = 0;
    for (struct dirent *e; dir && (e = readdir(dir)) != NULL;)
        count += e->d_name[0] != '.';
    if (dir)
        closedir(dir);
    return count;
}

/* Refused with status and a message containing text; nothing written. */
static void refused(const im_plot *plot, int status, const char *text)
{
    int before = directory_entries(test_temp_dir());
    int got = im_plot_write(plot, test_path("refused.png"));
    if (got != status || !strstr(im_last_error(), text))
        fail_msg("status %d, expected %d; message \"%s\", expected to contain \"%s\"", got, status, im_last_error(),
                 text);
    assert_int_equal(directory_entries(test_temp_dir()), before);
}

/* Five panels in rows of three: the last row's third cell stays empty, the grid as six panels'. */
static void test_partial_last_row(void **state)
{
    (void)state;
    double x[] = {1.0, 2.0}, y[] = {1.0, 2.0};
    im_plot_series s = {.x = x, .y = y, .n = 2};
    im_plot_panel panels[6];
    for (int i = 0; i < 6; ++i)
        panels[i] = (im_plot_panel){.series = &s, .series_count = 1, .label = "(a)"};
    im_plot plot = small_plot(panels);
    plot.rows = 2, plot.columns = 3;
    im_plot_geometry six[6], five[5];
    for (int i = 0; i < 6; ++i)
        assert_int_equal(im_plot_geometry_of(&plot, i, &six[i]), IM_OK);
    plot.panel_count = 5;
    for (int i = 0; i < 5; ++i) {
        assert_int_equal(im_plot_geometry_of(&plot, i, &five[i]), IM_OK);
        assert_memory_equal(&five[i], &six[i], sizeof five[i]);
    }
    assert_int_equal(im_plot_geometry_of(&plot, 5, &five[0]), IM_EINVAL);
    assert_true(five[3].box_x == five[0].box_x && five[3].box_y > five[0].box_y + five[0].box_height);
    assert_int_equal(im_plot_write(&plot, test_path("five.png")), IM_OK);
    plot.panel_count = 3;
    refused(&plot, IM_EINVAL, "plot: 3 panels in 2 x 3 cells: expected 4 to 6 (0: every cell)");
    plot.panel_count = 7;
    refused(&plot, IM_EINVAL, "plot: 7 panels in 2 x 3 cells");
}

static void test_bad_input_refused(void **state)
{
    (void)state;
    double x[] = {1.0, 2.0}, y[] = {1.0, 2.0}, bad[2] = {1.0, 0.0}, sigma[] = {0.1, -0.1};
    im_plot_series s = {.x = x, .y = y, .n = 0};
    im_plot_panel panel = {.series = &s, .series_count = 1};
    im_plot plot = im_plot_default();
    plot.panels = &panel;
    refused(&plot, IM_EINVAL, "series 1: no points");
    s.n = 2, s.y = NULL;
    refused(&plot, IM_EINVAL, "no points");
    s.y = y, bad[1] = INFINITY, s.x = bad;
    refused(&plot, IM_ENUMERIC, "x[1] = inf");
    bad[1] = 0.0;
    panel.x.scale = IM_PLOT_LOG;
    refused(&plot, IM_EINVAL, "x[1] = 0 on a log axis");
    s.x = x, s.sigma = sigma;
    refused(&plot, IM_EINVAL, "sigma[1]");
    s.sigma = NULL;
    panel.x = (im_plot_axis){IM_PLOT_LOG, -1.0, 10.0, NULL};
    refused(&plot, IM_EINVAL, "log axis");
    panel.x = (im_plot_axis){IM_PLOT_LINEAR, 0.0, 0.0, NULL};
    double nan2[] = {NAN, NAN};
    s.y = nan2;
    refused(&plot, IM_EINVAL, "no finite data");
    s.y = y;
    double huge[] = {-1e308, 1e308};
    s.x = huge;
    refused(&plot, IM_ENUMERIC, "overflow");
    s.x = x;
    plot.dpi = 0.0;
    refused(&plot, IM_EINVAL, "dpi");
    plot = im_plot_default();
    plot.panels = &panel;
    plot.rows = 0;
    refused(&plot, IM_EINVAL, "panels");
    plot.rows = 1;
    assert_int_equal(im_plot_write(&plot, test_path("plot.gif")), IM_EINVAL);
    /* Unwritable: IM_EIO; an existing file under a failed write is kept whole. */
    int before = directory_entries(test_temp_dir());
    assert_int_equal(im_plot_write(&plot, test_path("no/such/dir/plot.png")), IM_EIO);
    assert_int_equal(im_plot_write(&plot, test_path("no/such/dir/plot.svg")), IM_EIO);
    assert_int_equal(directory_entries(test_temp_dir()), before);
    test_write_bytes(test_path("keep.png"), "old", 3);
    s.n = 0;
    assert_int_equal(im_plot_write(&plot, test_path("keep.png")), IM_EINVAL);
    size_t size;
    uint8_t *data = slurp(test_path("keep.png"), &size);
    assert_int_equal(size, 3);
    free(data);
}

static void test_palette(void **state)
{
    (void)state;
    uint8_t a[3], b[3];
    im_plot_palette(0, a);
    assert_memory_equal(a, BLUE, 3);
    im_plot_palette(IM_PLOT_PALETTE_SIZE + 1, b);
    assert_memory_equal(b, VERMILLION, 3);
    im_plot_palette(-1, b); /* wraps backwards to yellow */
    assert_int_equal(b[0], 240);
    im_plot_family_color(0, 5, a);
    assert_int_equal(a[0], 68); /* viridis' first entry (68, 1, 84) */
    assert_int_equal(a[2], 84);
    im_plot_family_color(4, 5, b);
    assert_true(b[1] > 180); /* a light green, not the pale yellow end */
}

/* ---- the paper's figures ---- */

/* Geometry of a one-panel figure with the same axes, labels and title as the paper figure. */
static im_plot_geometry figure_geometry(im_plot_axis x, im_plot_axis y, const char *title)
{
    double px[] = {1.0}, py[] = {1.0};
    im_plot_series s = {.x = px, .y = py, .n = 1};
    im_plot_panel panel = {.x = x, .y = y, .series = &s, .series_count = 1, .title = title};
    im_plot plot = im_plot_default();
    plot.panels = &panel;
    im_plot_geometry g;
    assert_int_equal(im_plot_geometry_of(&plot, 0, &g), IM_OK);
    return g;
}

static void test_figure_contact_density(void **state)
{
    (void)state;
    double slope[] = {0.16};
    const char *path = test_path("fig1.png");
    assert_int_equal(im_paper_fig1_contact_density(80.0, slope, 1, NULL, path), IM_OK);
    picture p = read_picture(path);
    im_plot_geometry g = figure_geometry((im_plot_axis){IM_PLOT_LINEAR, 0.0, 1.0, "r / a"},
                                         (im_plot_axis){IM_PLOT_LINEAR, 0.0, 1.05, "γ(r)"}, "t");
    assert_int_equal(p.width, g.width);
    /* gamma = erf(sqrt(pi)/2 rho_c acosh(a/r)), rho_c = cot(80°) / 0.16 (eq. 7), in viridis' first colour. */
    const uint8_t first[3] = {68, 1, 84};
    double rho = 1.0 / tan(80.0 * M_PI / 180.0) / 0.16;
    for (double s = 0.3; s < 0.96; s += 0.15) {
        double gamma = erf(sqrt(M_PI) / 2.0 * rho * acosh(1.0 / s));
        if (!color_near(&p, expected_x(&g, s, 0), expected_y(&g, gamma, 0), first, 1))
            fail_msg("r/a = %g: no curve at gamma = %g", s, gamma);
    }
    free(p.rgb);
    double bad[] = {0.08, -0.01};
    assert_int_equal(im_paper_fig1_contact_density(80.0, bad, 2, NULL, path), IM_EINVAL);
    assert_int_equal(im_paper_fig1_contact_density(95.0, slope, 1, NULL, path), IM_EINVAL);
    assert_int_equal(im_paper_fig1_contact_density(80.0, slope, 0, NULL, path), IM_EINVAL);
}

static void test_figure_area_ratio(void **state)
{
    (void)state;
    /* Table 1: rho_c, the simulations' A/A_cone and sd, and eq. (12)'s values. */
    double rho[] = {17.63, 8.82, 4.41, 2.20, 1.10}, mean[] = {1.002, 1.001, 0.985, 0.909, 0.724};
    double sd[] = {0.009, 0.017, 0.031, 0.045, 0.044}, eq12[] = {0.998, 0.992, 0.969, 0.894, 0.719};
    im_paper_points points = {rho, mean, sd, 5, NULL};
    const char *path = test_path("fig2.png");
    assert_int_equal(im_paper_fig2_area_ratio(&points, NULL, path), IM_OK);
    picture p = read_picture(path);
    im_plot_geometry g = figure_geometry((im_plot_axis){IM_PLOT_LOG, 0.1, 100.0, "ρ_{c} = cot α / h′_{rms}"},
                                         (im_plot_axis){IM_PLOT_LINEAR, 0.0, 1.05, "A / A_{cone}"}, NULL);
    for (int i = 0; i < 5; ++i) { /* markers at the means, caps at mean + sd */
        assert_true(same_color(pixel(&p, expected_x(&g, rho[i], 1), expected_y(&g, mean[i], 0)), VERMILLION, 12));
        assert_true(color_near(&p, expected_x(&g, rho[i], 1), expected_y(&g, mean[i] + sd[i], 0), VERMILLION, 1));
    }
    free(p.rgb);
    /* Without points the curves are bare: eq. (12) through Table 1's values (where eq. (6) is at
     * least 0.03 away), eq. (6), dotted, through erf(sqrt(pi)/2 rho_c), within a dot's spacing. */
    assert_int_equal(im_paper_fig2_area_ratio(NULL, NULL, path), IM_OK);
    p = read_picture(path);
    const uint8_t black[3] = {0, 0, 0};
    for (int i = 2; i < 5; ++i)
        if (!color_near(&p, expected_x(&g, rho[i], 1), expected_y(&g, eq12[i], 0), black, 1))
            fail_msg("rho_c = %g: eq. (12) not at %g", rho[i], eq12[i]);
    for (double r = 0.6; r < 3.0; r *= 1.5) {
        double constant = erf(sqrt(M_PI) / 2.0 * r);
        if (!color_near(&p, expected_x(&g, r, 1), expected_y(&g, constant, 0), black, 6))
            fail_msg("rho_c = %g: eq. (6) not at %g", r, constant);
    }
    free(p.rgb);
    rho[0] = 0.0;
    assert_int_equal(im_paper_fig2_area_ratio(&points, NULL, path), IM_EINVAL);
}

static void test_figure_surface(void **state)
{
    (void)state;
    im_surface_params params = im_surface_params_default();
    params.nx = params.ny = 128, params.lambda_r = 128.0, params.slope_rms = 0.16;
    im_field *surface;
    assert_int_equal(im_surface_generate(&params, &surface), IM_OK);
    const char *path = test_path("fig3.png");
    assert_int_equal(im_paper_fig3_surface(surface, &params, 40, NULL, path), IM_OK);
    picture p = read_picture(path);
    assert_true(p.width > 2 * 667 && p.height > 2 * 500); /* 2 x 2 frames of 160 x 120 pt at 300 dpi */
    free(p.rgb);
    assert_int_equal(im_paper_fig3_surface(surface, &params, 40, NULL, test_path("fig3.pdf")), IM_OK);
    assert_int_equal(im_paper_fig3_surface(surface, &params, 5, NULL, path), IM_EINVAL);
    params.hurst = 1.5;
    assert_int_equal(im_paper_fig3_surface(surface, &params, 40, NULL, path), IM_EINVAL);
    im_field_free(surface);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_frame_and_line_pixels),
        cmocka_unit_test(test_marker_centre),
        cmocka_unit_test(test_log_ticks_by_decade),
        cmocka_unit_test(test_automatic_limits),
        cmocka_unit_test(test_error_bars),
        cmocka_unit_test(test_nan_gap_and_far_points),
        cmocka_unit_test(test_polygon_clipping),
        cmocka_unit_test(test_band),
        cmocka_unit_test(test_legend),
        cmocka_unit_test(test_legend_keeps_clear_of_lines),
        cmocka_unit_test(test_png_pdf_svg),
        cmocka_unit_test(test_bad_input_refused),
        cmocka_unit_test(test_partial_last_row),
        cmocka_unit_test(test_palette),
        cmocka_unit_test(test_figure_contact_density),
        cmocka_unit_test(test_figure_area_ratio),
        cmocka_unit_test(test_figure_surface),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
