/* Drawing a laid-out plot with cairo, in pixel coordinates. */
#include "plot/layout.h"

#include "plot/clip.h"
#include "typeset/fonts.h"
#include "typeset/text.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* Line widths and lengths in points. */
static const double FRAME_WIDTH = 0.6, MAJOR_TICK = 3.5, MINOR_TICK = 2.0;
static const double DEFAULT_LINE = 1.0, DEFAULT_MARKER = 4.0, ERROR_BAR_WIDTH = 0.6, BAND_OPACITY = 0.25;

static void set_color(cairo_t *cr, const uint8_t rgb[3])
{
    cairo_set_source_rgb(cr, rgb[0] / 255.0, rgb[1] / 255.0, rgb[2] / 255.0);
}

static double line_width(const im_plot_series *s) { return s->line_width > 0.0 ? s->line_width : DEFAULT_LINE; }
static double marker_size(const im_plot_series *s) { return s->marker_size > 0.0 ? s->marker_size : DEFAULT_MARKER; }

void plot_set_line_style(cairo_t *cr, const im_plot_series *s, double points)
{
    double w = line_width(s), scale = fmax(1.0, w) * points;
    cairo_set_line_width(cr, w * points);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    if (s->line == IM_PLOT_DASHED) {
        const double dashes[] = {3.5 * scale, 2.0 * scale};
        cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
        cairo_set_dash(cr, dashes, 2, 0.0);
    } else if (s->line == IM_PLOT_DOTTED) {
        const double dashes[] = {0.0, 1.6 * scale}; /* zero-length dashes with round caps are dots */
        cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
        cairo_set_dash(cr, dashes, 2, 0.0);
    } else {
        cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
        cairo_set_dash(cr, NULL, 0, 0.0);
    }
}

void plot_draw_marker(cairo_t *cr, const im_plot_series *s, double points, double x, double y)
{
    double r = 0.5 * marker_size(s) * points;
    switch (s->marker) {
    case IM_PLOT_MARKER_CIRCLE:
        cairo_new_sub_path(cr);
        cairo_arc(cr, x, y, r, 0.0, 2.0 * M_PI);
        break;
    case IM_PLOT_MARKER_SQUARE:
        cairo_rectangle(cr, x - 0.89 * r, y - 0.89 * r, 1.78 * r, 1.78 * r); /* the circle's area */
        break;
    case IM_PLOT_MARKER_TRIANGLE:
        cairo_move_to(cr, x, y - 1.2 * r);
        cairo_line_to(cr, x + 1.04 * r, y + 0.6 * r);
        cairo_line_to(cr, x - 1.04 * r, y + 0.6 * r);
        cairo_close_path(cr);
        break;
    case IM_PLOT_MARKER_DIAMOND:
        cairo_move_to(cr, x, y - 1.25 * r);
        cairo_line_to(cr, x + 1.25 * r, y);
        cairo_line_to(cr, x, y + 1.25 * r);
        cairo_line_to(cr, x - 1.25 * r, y);
        cairo_close_path(cr);
        break;
    case IM_PLOT_MARKER_NONE: return;
    }
    set_color(cr, s->color);
    cairo_fill(cr);
}

/* ---- series ---- */

typedef struct frame {
    const plot_panel_layout *p;
    double left, top, right, bottom; /* the frame widened by a margin, for clipping in doubles */
} frame;

static double px(const frame *f, double x) { return plot_axis_pixel(&f->p->x, x, f->p->box_x, f->p->box_width); }
static double py(const frame *f, double y)
{
    return plot_axis_pixel(&f->p->y, y, f->p->box_y + f->p->box_height, -f->p->box_height);
}

/* Liang-Barsky: clips the segment a-b to the widened frame; 0 when it lies outside. Done in
 * doubles so that points far outside never reach cairo's fixed-point coordinates. */
static int clip_segment(const frame *f, double *ax, double *ay, double *bx, double *by)
{
    double t0 = 0.0, t1 = 1.0, dx = *bx - *ax, dy = *by - *ay;
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {*ax - f->left, f->right - *ax, *ay - f->top, f->bottom - *ay};
    for (int i = 0; i < 4; ++i) {
        if (p[i] == 0.0) {
            if (q[i] < 0.0)
                return 0;
            continue;
        }
        double t = q[i] / p[i];
        if (p[i] < 0.0)
            t0 = fmax(t0, t);
        else
            t1 = fmin(t1, t);
        if (t0 > t1)
            return 0;
    }
    double x0 = *ax + t0 * dx, y0 = *ay + t0 * dy;
    *bx = *ax + t1 * dx, *by = *ay + t1 * dy;
    *ax = x0, *ay = y0;
    return 1;
}

/* The line through the finite points; NaN breaks it. */
static void draw_line(cairo_t *cr, const im_plot_series *s, const frame *f, double points)
{
    double last_x = NAN, last_y = NAN; /* previous finite point, pixels */
    double pen_x = NAN, pen_y = NAN;   /* where the current path ends */
    for (int i = 0; i < s->n; ++i) {
        double x = px(f, s->x[i]), y = py(f, s->y[i]);
        if (!isfinite(x) || !isfinite(y)) {
            last_x = last_y = NAN;
            continue;
        }
        double ax = last_x, ay = last_y, bx = x, by = y;
        last_x = x, last_y = y;
        if (isnan(ax) && i + 1 < s->n && isfinite(s->x[i + 1]) && isfinite(s->y[i + 1]))
            continue; /* the first point of a run: drawn with the next segment */
        if (isnan(ax))
            ax = bx, ay = by; /* an isolated point: a dot of zero length */
        if (!clip_segment(f, &ax, &ay, &bx, &by))
            continue;
        if (ax != pen_x || ay != pen_y)
            cairo_move_to(cr, ax, ay);
        cairo_line_to(cr, bx, by);
        pen_x = bx, pen_y = by;
    }
    plot_set_line_style(cr, s, points);
    set_color(cr, s->color);
    cairo_stroke(cr);
}

/* A vertical pixel position kept within reach of cairo: beyond the widened frame it is clamped,
 * which is exact for vertical error bars (+Inf, a value <= 0 on a log axis, goes to the bottom). */
static double clamp_y(const frame *f, double y) { return fmin(fmax(y, f->top), f->bottom); }

static int band_point(const im_plot_series *s, int i)
{
    return !isnan(s->x[i]) && !isnan(s->y[i]) && !isnan(s->band_lo[i]) && !isnan(s->band_hi[i]);
}

/* A band vertex in pixels; an infinite position (a value <= 0 on a log axis, or one that
 * overflows) is put just beyond the widened frame on its side, so that clipping stays finite. */
static void band_vertex(const frame *f, double x, double y, double *out)
{
    out[0] = px(f, x), out[1] = py(f, y);
    if (isinf(out[0]))
        out[0] = out[0] > 0 ? f->right + 1.0 : f->left - 1.0;
    if (isinf(out[1]))
        out[1] = out[1] > 0 ? f->bottom + 1.0 : f->top - 1.0;
}

/* The polygon between band_lo and band_hi over the run start..end, clipped to the widened frame
 * in doubles, added to the path. */
static int band_polygon(cairo_t *cr, const im_plot_series *s, const frame *f, int start, int end, double *xy)
{
    int n = 0;
    for (int i = start; i <= end; ++i, ++n)
        band_vertex(f, s->x[i], s->band_hi[i], xy + 2 * n);
    for (int i = end; i >= start; --i, ++n)
        band_vertex(f, s->x[i], s->band_lo[i], xy + 2 * n);
    double *clipped;
    n = plot_clip_polygon(xy, n, (plot_rect){f->left, f->top, f->right, f->bottom}, &clipped);
    if (n < 0)
        return im_fail(IM_ENOMEM, "plot band of %d points: out of memory", end - start + 1);
    for (int i = 0; i < n; ++i)
        cairo_line_to(cr, clipped[2 * i], clipped[2 * i + 1]);
    cairo_close_path(cr);
    cairo_new_sub_path(cr);
    free(clipped);
    return IM_OK;
}

/* Polygons between band_lo and band_hi over each run of points where all are numbers. */
static int draw_band(cairo_t *cr, const im_plot_series *s, const frame *f)
{
    double *xy = malloc(4 * sizeof(double) * (size_t)s->n);
    if (!xy)
        return im_fail(IM_ENOMEM, "plot band of %d points: out of memory", s->n);
    int status = IM_OK;
    for (int start = 0; status == IM_OK && start < s->n;) {
        if (!band_point(s, start)) {
            ++start;
            continue;
        }
        int end = start;
        while (end + 1 < s->n && band_point(s, end + 1))
            ++end;
        status = band_polygon(cr, s, f, start, end, xy);
        start = end + 1;
    }
    free(xy);
    cairo_set_source_rgba(cr, s->color[0] / 255.0, s->color[1] / 255.0, s->color[2] / 255.0, BAND_OPACITY);
    cairo_fill(cr);
    return status;
}

static void draw_error_bars(cairo_t *cr, const im_plot_series *s, const frame *f, double points)
{
    double cap = 0.5 * (s->marker != IM_PLOT_MARKER_NONE ? marker_size(s) : 3.0) * points;
    for (int i = 0; i < s->n; ++i) {
        double x = px(f, s->x[i]);
        if (isnan(s->sigma[i]) || !isfinite(x) || !isfinite(py(f, s->y[i])) || x < f->left || x > f->right)
            continue;
        double lo = clamp_y(f, py(f, s->y[i] - s->sigma[i])), hi = clamp_y(f, py(f, s->y[i] + s->sigma[i]));
        cairo_move_to(cr, x, lo);
        cairo_line_to(cr, x, hi);
        const double ends[2] = {lo, hi};
        for (int e = 0; e < 2; ++e)
            if (ends[e] > f->top && ends[e] < f->bottom) { /* no cap where the bar was cut */
                cairo_move_to(cr, x - cap, ends[e]);
                cairo_line_to(cr, x + cap, ends[e]);
            }
    }
    cairo_set_dash(cr, NULL, 0, 0.0);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
    cairo_set_line_width(cr, ERROR_BAR_WIDTH * points);
    set_color(cr, s->color);
    cairo_stroke(cr);
}

static void draw_markers(cairo_t *cr, const im_plot_series *s, const frame *f, double points)
{
    for (int i = 0; i < s->n; ++i) {
        double x = px(f, s->x[i]), y = py(f, s->y[i]);
        if (isfinite(x) && isfinite(y) && x >= f->left && x <= f->right && y >= f->top && y <= f->bottom)
            plot_draw_marker(cr, s, points, x, y);
    }
}

static int draw_series(cairo_t *cr, const im_plot_panel *p, const plot_panel_layout *pl, double points)
{
    double margin = 20.0 * points;
    frame f = {pl, pl->box_x - margin, pl->box_y - margin, pl->box_x + pl->box_width + margin,
               pl->box_y + pl->box_height + margin};
    cairo_save(cr);
    cairo_rectangle(cr, pl->box_x, pl->box_y, pl->box_width, pl->box_height);
    cairo_clip(cr);
    int status = IM_OK;
    for (int i = 0; status == IM_OK && i < p->series_count; ++i)
        if (p->series[i].band_lo)
            status = draw_band(cr, &p->series[i], &f);
    for (int i = 0; i < p->series_count; ++i) {
        const im_plot_series *s = &p->series[i];
        if (s->sigma)
            draw_error_bars(cr, s, &f, points);
        if (s->line != IM_PLOT_NO_LINE)
            draw_line(cr, s, &f, points);
        draw_markers(cr, s, &f, points);
    }
    cairo_restore(cr);
    return status;
}

/* ---- frame, ticks, labels ---- */

/* A tick of the given length inward from both sides of the frame, at pixel position v. */
static void tick_pair(cairo_t *cr, const plot_panel_layout *pl, int vertical_axis, double v, double length)
{
    if (vertical_axis) {
        cairo_move_to(cr, pl->box_x, v);
        cairo_rel_line_to(cr, length, 0.0);
        cairo_move_to(cr, pl->box_x + pl->box_width, v);
        cairo_rel_line_to(cr, -length, 0.0);
    } else {
        cairo_move_to(cr, v, pl->box_y + pl->box_height);
        cairo_rel_line_to(cr, 0.0, -length);
        cairo_move_to(cr, v, pl->box_y);
        cairo_rel_line_to(cr, 0.0, length);
    }
}

/* Minor ticks at 2..9 times each decade of a log axis. */
static void minor_ticks(cairo_t *cr, const plot_panel_layout *pl, const plot_axis_layout *a, int vertical_axis,
                        double length)
{
    for (double decade = pow(10.0, floor(log10(a->lo))); decade <= a->hi; decade *= 10.0)
        for (int m = 2; m <= 9; ++m) {
            double v = m * decade;
            if (v < a->lo * (1 - 1e-9) || v > a->hi * (1 + 1e-9))
                continue;
            double position = vertical_axis ? plot_axis_pixel(a, v, pl->box_y + pl->box_height, -pl->box_height)
                                            : plot_axis_pixel(a, v, pl->box_x, pl->box_width);
            tick_pair(cr, pl, vertical_axis, position, length);
        }
}

static void draw_axis(cairo_t *cr, cairo_font_face_t *face, const plot_layout *l, const plot_panel_layout *pl,
                      const plot_axis_layout *a, int vertical_axis)
{
    double f = l->font;
    for (int i = 0; i < a->tick_count; ++i) {
        double position = vertical_axis ? plot_axis_pixel(a, a->ticks[i], pl->box_y + pl->box_height, -pl->box_height)
                                        : plot_axis_pixel(a, a->ticks[i], pl->box_x, pl->box_width);
        tick_pair(cr, pl, vertical_axis, position, MAJOR_TICK * l->points);
        if (i % a->label_every)
            continue;
        char text[64];
        typeset_tick_label(a->scale == IM_PLOT_LOG, a->ticks, a->tick_count, i, text, sizeof text);
        if (vertical_axis)
            typeset_show_text(cr, face, f, pl->box_x - 0.35 * f, position + 0.36 * f, 1.0, text);
        else
            typeset_show_text(cr, face, f, position, pl->box_y + pl->box_height + 1.15 * f, 0.5, text);
    }
    if (a->scale == IM_PLOT_LOG)
        minor_ticks(cr, pl, a, vertical_axis, MINOR_TICK * l->points);
    cairo_stroke(cr);
}

static void draw_axis_labels(cairo_t *cr, cairo_font_face_t *face, const plot_layout *l, const im_plot_panel *p,
                             const plot_panel_layout *pl, double y_label_left)
{
    double f = l->font;
    if (p->x.label)
        typeset_show_text(cr, face, f, pl->box_x + 0.5 * pl->box_width, pl->box_y + pl->box_height + 2.55 * f, 0.5,
                          p->x.label);
    if (p->y.label) {
        cairo_save(cr);
        cairo_translate(cr, y_label_left + 0.8 * f, pl->box_y + 0.5 * pl->box_height);
        cairo_rotate(cr, -M_PI / 2.0);
        typeset_show_text(cr, face, f, 0.0, 0.0, 0.5, p->y.label);
        cairo_restore(cr);
    }
}

static void draw_legend(cairo_t *cr, cairo_font_face_t *face, const plot_layout *l, const im_plot_panel *p,
                        const plot_panel_layout *pl)
{
    if (pl->legend_width <= 0.0)
        return;
    cairo_rectangle(cr, pl->legend_x, pl->legend_y, pl->legend_width, pl->legend_height);
    cairo_set_source_rgba(cr, 1, 1, 1, 0.9);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.7, 0.7, 0.7);
    cairo_set_line_width(cr, 0.5 * l->points);
    cairo_set_dash(cr, NULL, 0, 0.0);
    cairo_stroke(cr);
    double pad = plot_legend_padding(l), row = plot_legend_row_height(l), sample = plot_legend_sample_length(l);
    double y = pl->legend_y + pad + 0.5 * row, x = pl->legend_x + pad;
    if (p->legend_title) {
        cairo_set_source_rgb(cr, 0, 0, 0);
        typeset_show_text(cr, face, l->font, x, y + 0.36 * l->font, 0.0, p->legend_title);
        y += row;
    }
    for (int i = 0; i < p->series_count; ++i) {
        const im_plot_series *s = &p->series[i];
        if (!s->label)
            continue;
        if (s->band_lo) {
            cairo_rectangle(cr, x, y - 0.3 * row, sample, 0.6 * row);
            cairo_set_source_rgba(cr, s->color[0] / 255.0, s->color[1] / 255.0, s->color[2] / 255.0, BAND_OPACITY);
            cairo_fill(cr);
        }
        if (s->sigma) {
            cairo_move_to(cr, x + 0.5 * sample, y - 0.35 * row);
            cairo_line_to(cr, x + 0.5 * sample, y + 0.35 * row);
            cairo_set_dash(cr, NULL, 0, 0.0);
            cairo_set_line_width(cr, ERROR_BAR_WIDTH * l->points);
            set_color(cr, s->color);
            cairo_stroke(cr);
        }
        if (s->line != IM_PLOT_NO_LINE) {
            cairo_move_to(cr, x, y);
            cairo_line_to(cr, x + sample, y);
            plot_set_line_style(cr, s, l->points);
            set_color(cr, s->color);
            cairo_stroke(cr);
        }
        plot_draw_marker(cr, s, l->points, x + 0.5 * sample, y);
        cairo_set_source_rgb(cr, 0, 0, 0);
        typeset_show_text(cr, face, l->font, x + sample + 0.5 * l->font, y + 0.36 * l->font, 0.0, s->label);
        y += row;
    }
}

static int draw_panel(cairo_t *cr, cairo_font_face_t *regular, cairo_font_face_t *bold, const plot_layout *l,
                      const im_plot_panel *p, const plot_panel_layout *pl, double y_label_left)
{
    int status = draw_series(cr, p, pl, l->points);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_dash(cr, NULL, 0, 0.0);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
    cairo_set_line_width(cr, FRAME_WIDTH * l->points);
    cairo_rectangle(cr, pl->box_x, pl->box_y, pl->box_width, pl->box_height);
    cairo_stroke(cr);
    draw_axis(cr, regular, l, pl, &pl->x, 0);
    draw_axis(cr, regular, l, pl, &pl->y, 1);
    draw_axis_labels(cr, regular, l, p, pl, y_label_left);
    double baseline = pl->box_y - 0.45 * l->font;
    if (p->label)
        typeset_show_text(cr, bold, l->font, pl->box_x, baseline, 0.0, p->label);
    if (p->title)
        typeset_show_text(cr, regular, l->font, pl->box_x + 0.5 * pl->box_width, baseline, 0.5, p->title);
    draw_legend(cr, regular, l, p, pl);
    return status;
}

int plot_draw(const im_plot *plot, const plot_layout *l, cairo_t *cr)
{
    cairo_font_face_t *regular, *bold;
    int status = typeset_fonts(&regular, &bold);
    if (status != IM_OK)
        return status;
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    /* The y labels of a column share a left edge: the cell's left edge plus the outer margin. */
    double first_box = l->panels[0].box_x;
    for (int i = 0; status == IM_OK && i < l->panel_count; ++i) {
        const plot_panel_layout *pl = &l->panels[i];
        double cell_left = pl->box_x - first_box + round(0.4 * l->font);
        status = draw_panel(cr, regular, bold, l, &plot->panels[i], pl, cell_left);
    }
    return status;
}
