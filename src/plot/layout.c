/* Plot checks, limits, ticks and placement, in pixels at the plot's dpi. */
#include "plot/layout.h"

#include "typeset/text.h"
#include "typeset/ticks.h"
#include "indentmap/status.h"

#include <math.h>
#include <string.h>

/* About this many linear tick intervals per axis. */
static const double TICK_TARGET = 6.0;
/* At most this many labelled decades per log axis; the others keep unlabelled ticks. */
enum { MAX_LABELLED_DECADES = 6 };

/* ---- checks ---- */

static int check_plot(const im_plot *p)
{
    if (p->rows < 1 || p->columns < 1 || p->rows * p->columns > PLOT_MAX_PANELS || !p->panels)
        return im_fail(IM_EINVAL, "plot: %d x %d panels: expected 1 to %d panels", p->rows, p->columns,
                       PLOT_MAX_PANELS);
    if (!(p->panel_width > 0.0 && p->panel_width <= 2000.0 && p->panel_height > 0.0 && p->panel_height <= 2000.0))
        return im_fail(IM_EINVAL, "plot: panel %g x %g pt: expected (0, 2000] each", p->panel_width, p->panel_height);
    if (!(p->dpi > 0.0 && p->dpi <= 2400.0))
        return im_fail(IM_EINVAL, "plot: dpi = %g: expected (0, 2400]", p->dpi);
    if (!(p->font_size > 0.0 && p->font_size <= 72.0))
        return im_fail(IM_EINVAL, "plot: font size %g pt: expected (0, 72]", p->font_size);
    if (p->png_compression < 0 || p->png_compression > 9)
        return im_fail(IM_EINVAL, "plot: PNG compression %d: expected 0-9", p->png_compression);
    if (p->text_count < 0 || (p->text_count > 0 && !p->texts))
        return im_fail(IM_EINVAL, "plot: %d texts without an array", p->text_count);
    return IM_OK;
}

static int check_axis(int panel, const char *name, const im_plot_axis *a)
{
    if (a->scale != IM_PLOT_LINEAR && a->scale != IM_PLOT_LOG)
        return im_fail(IM_EINVAL, "plot panel %d: %s axis scale %d: expected linear or log", panel, name, (int)a->scale);
    if (!(a->lo < a->hi))
        return IM_OK; /* automatic */
    if (!isfinite(a->lo) || !isfinite(a->hi))
        return im_fail(IM_ENUMERIC, "plot panel %d: %s limits [%g, %g]: expected finite values", panel, name, a->lo, a->hi);
    if (a->scale == IM_PLOT_LOG && !(a->lo > 0.0))
        return im_fail(IM_EINVAL, "plot panel %d: %s limits [%g, %g] on a log axis: expected lo > 0", panel, name,
                       a->lo, a->hi);
    return IM_OK;
}

/* One array of a series: infinities refused, non-positive values refused where `positive`. */
static int check_values(int panel, int index, const char *what, const double *v, int n, int positive)
{
    for (int i = 0; i < n; ++i) {
        if (isinf(v[i]))
            return im_fail(IM_ENUMERIC, "plot panel %d series %d: %s[%d] = %g: expected a finite value (NaN "
                           "leaves a gap)", panel, index, what, i, v[i]);
        if (positive && v[i] <= 0.0)
            return im_fail(IM_EINVAL, "plot panel %d series %d: %s[%d] = %g on a log axis: expected > 0",
                           panel, index, what, i, v[i]);
    }
    return IM_OK;
}

static int check_style(int panel, int index, const im_plot_series *s)
{
    if ((int)s->line < IM_PLOT_SOLID || s->line > IM_PLOT_NO_LINE)
        return im_fail(IM_EINVAL, "plot panel %d series %d: line style %d unknown", panel, index, (int)s->line);
    if ((int)s->marker < IM_PLOT_MARKER_NONE || s->marker > IM_PLOT_MARKER_DIAMOND)
        return im_fail(IM_EINVAL, "plot panel %d series %d: marker %d unknown", panel, index, (int)s->marker);
    if (!(s->line_width >= 0.0 && s->line_width <= 50.0) || !(s->marker_size >= 0.0 && s->marker_size <= 50.0))
        return im_fail(IM_EINVAL, "plot panel %d series %d: line width %g pt, marker size %g pt: expected "
                       "[0, 50] (0: default)", panel, index, s->line_width, s->marker_size);
    if (!s->band_lo != !s->band_hi)
        return im_fail(IM_EINVAL, "plot panel %d series %d: a band needs both band_lo and band_hi", panel, index);
    return IM_OK;
}

static int check_series(int panel, int index, const im_plot_series *s, const im_plot_panel *p)
{
    if (s->n < 1 || !s->x || !s->y)
        return im_fail(IM_EINVAL, "plot panel %d series %d%s%s: no points (n = %d): expected n >= 1 and x, y "
                       "arrays", panel, index, s->label ? " " : "", s->label ? s->label : "", s->n);
    int status = check_style(panel, index, s);
    if (status == IM_OK)
        status = check_values(panel, index, "x", s->x, s->n, p->x.scale == IM_PLOT_LOG);
    if (status == IM_OK)
        status = check_values(panel, index, "y", s->y, s->n, p->y.scale == IM_PLOT_LOG);
    if (status == IM_OK && s->sigma)
        status = check_values(panel, index, "sigma", s->sigma, s->n, 0);
    for (int i = 0; status == IM_OK && s->sigma && i < s->n; ++i)
        if (s->sigma[i] < 0.0)
            return im_fail(IM_EINVAL, "plot panel %d series %d: sigma[%d] = %g: expected >= 0", panel, index, i,
                           s->sigma[i]);
    if (status == IM_OK && s->band_lo)
        status = check_values(panel, index, "band_lo", s->band_lo, s->n, 0);
    if (status == IM_OK && s->band_hi)
        status = check_values(panel, index, "band_hi", s->band_hi, s->n, 0);
    return status;
}

static int check_panel(int index, const im_plot_panel *p)
{
    int status = check_axis(index, "x", &p->x);
    if (status == IM_OK)
        status = check_axis(index, "y", &p->y);
    if (status == IM_OK && (p->series_count < 0 || (p->series_count > 0 && !p->series)))
        return im_fail(IM_EINVAL, "plot panel %d: %d series without an array", index, p->series_count);
    if (status == IM_OK && ((int)p->legend < IM_PLOT_LEGEND_AUTO || p->legend > IM_PLOT_LEGEND_HIDDEN))
        return im_fail(IM_EINVAL, "plot panel %d: legend position %d unknown", index, (int)p->legend);
    for (int s = 0; status == IM_OK && s < p->series_count; ++s)
        status = check_series(index, s + 1, &p->series[s], p);
    return status;
}

/* ---- limits and ticks ---- */

typedef struct range {
    double lo, hi;
} range;

static void include(range *r, double v, im_plot_scale scale)
{
    if (isnan(v) || (scale == IM_PLOT_LOG && !(v > 0.0)))
        return;
    r->lo = fmin(r->lo, v);
    r->hi = fmax(r->hi, v);
}

/* The data's range on both axes: points with finite x and y, their error bars and bands. */
static void data_ranges(const im_plot_panel *p, range *x, range *y)
{
    *x = *y = (range){INFINITY, -INFINITY};
    for (int s = 0; s < p->series_count; ++s) {
        const im_plot_series *series = &p->series[s];
        for (int i = 0; i < series->n; ++i) {
            if (isnan(series->x[i]) || isnan(series->y[i]))
                continue;
            include(x, series->x[i], p->x.scale);
            include(y, series->y[i], p->y.scale);
            if (series->sigma) {
                include(y, series->y[i] - series->sigma[i], p->y.scale);
                include(y, series->y[i] + series->sigma[i], p->y.scale);
            }
            if (series->band_lo) {
                include(y, series->band_lo[i], p->y.scale);
                include(y, series->band_hi[i], p->y.scale);
            }
        }
    }
}

static int tick_values(plot_axis_layout *a)
{
    return figure_ticks_between(a->lo, a->hi, a->scale == IM_PLOT_LOG, TICK_TARGET, a->ticks, PLOT_MAX_TICKS);
}

/* The largest (down) or smallest (up) of 1, 2, 5 x 10^k at or beyond v > 0. */
static double nice_log_bound(double v, int up)
{
    static const double multiples[] = {1.0, 2.0, 5.0, 10.0};
    double decade = pow(10.0, floor(log10(v))), bound = up ? 10.0 * decade : decade;
    for (int i = 0; i < 4; ++i) {
        double m = multiples[i] * decade;
        if (up && m >= v * (1 - 1e-9) && m < bound)
            bound = m;
        if (!up && m <= v * (1 + 1e-9))
            bound = m;
    }
    return bound;
}

/* Widens the data range to whole tick steps (linear) or to 1-2-5 multiples of decades (log). */
static void widen(plot_axis_layout *a, range r)
{
    if (a->scale == IM_PLOT_LOG) {
        a->lo = nice_log_bound(r.lo, 0);
        a->hi = nice_log_bound(r.hi, 1);
        if (!(a->hi > a->lo))
            a->hi = nice_log_bound(a->lo * 1.5, 1);
        return;
    }
    if (!(r.hi > r.lo)) {
        double pad = r.lo != 0.0 ? 0.1 * fabs(r.lo) : 1.0;
        r.lo -= pad, r.hi += pad;
    }
    a->lo = r.lo, a->hi = r.hi;
    int count = tick_values(a);
    double step = count >= 2 ? a->ticks[1] - a->ticks[0] : r.hi - r.lo;
    a->lo = step * floor(r.lo / step + 1e-9);
    a->hi = step * ceil(r.hi / step - 1e-9);
}

static int resolve_axis(int panel, const char *name, const im_plot_axis *axis, range data, plot_axis_layout *a)
{
    a->scale = axis->scale;
    if (axis->lo < axis->hi) {
        a->lo = axis->lo, a->hi = axis->hi;
    } else {
        if (!(data.hi >= data.lo))
            return im_fail(IM_EINVAL, "plot panel %d: no finite data to set the %s limits: give them", panel, name);
        widen(a, data);
        if (!isfinite(a->lo) || !isfinite(a->hi) || !(a->hi > a->lo))
            return im_fail(IM_ENUMERIC, "plot panel %d: %s data from %g to %g: automatic limits overflow; give "
                           "them", panel, name, data.lo, data.hi);
    }
    a->tick_count = tick_values(a);
    int decades = a->scale == IM_PLOT_LOG && a->tick_count >= 2 && a->ticks[1] / a->ticks[0] > 9.99;
    a->label_every = decades ? (a->tick_count + MAX_LABELLED_DECADES - 1) / MAX_LABELLED_DECADES : 1;
    return IM_OK;
}

double plot_axis_pixel(const plot_axis_layout *a, double v, double start, double length)
{
    double t;
    if (a->scale == IM_PLOT_LOG)
        t = v > 0.0 ? log(v / a->lo) / log(a->hi / a->lo) : -INFINITY;
    else
        t = (v - a->lo) / (a->hi - a->lo);
    return start + t * length;
}

/* ---- placement ---- */

double plot_legend_row_height(const plot_layout *l) { return round(1.35 * l->font); }
double plot_legend_sample_length(const plot_layout *l) { return round(2.2 * l->font); }
double plot_legend_padding(const plot_layout *l) { return round(0.45 * l->font); }

static double text_width(cairo_t *cr, const plot_layout *l, const char *text)
{
    return figure_rich_text(cr, cairo_get_font_face(cr), l->font, 0.0, 0.0, text, 0);
}

/* Widest labelled tick of an axis, and half the width of its last label. */
static void tick_label_widths(cairo_t *cr, const plot_layout *l, const plot_axis_layout *a, double *widest,
                              double *last_half)
{
    *widest = *last_half = 0.0;
    for (int i = 0; i < a->tick_count; ++i) {
        if (i % a->label_every)
            continue;
        char text[64];
        figure_tick_label(a->scale == IM_PLOT_LOG, a->ticks, a->tick_count, i, text, sizeof text);
        double w = text_width(cr, l, text);
        *widest = fmax(*widest, w);
        *last_half = 0.5 * w;
    }
}

/* Number of sampled data positions (points and 8 along each segment) inside a rectangle. */
static int covered(const im_plot_panel *p, const plot_panel_layout *pl, double x0, double y0, double w, double h)
{
    int count = 0;
    for (int s = 0; s < p->series_count; ++s) {
        const im_plot_series *series = &p->series[s];
        double px_prev = NAN, py_prev = NAN;
        for (int i = 0; i < series->n; ++i) {
            double px = plot_axis_pixel(&pl->x, series->x[i], pl->box_x, pl->box_width);
            double py = plot_axis_pixel(&pl->y, series->y[i], pl->box_y + pl->box_height, -pl->box_height);
            int steps = series->line != IM_PLOT_NO_LINE && isfinite(px_prev + py_prev) ? 8 : 1;
            for (int k = 1; k <= steps && isfinite(px + py); ++k) {
                double f = (double)k / steps;
                double qx = steps > 1 ? px_prev + f * (px - px_prev) : px;
                double qy = steps > 1 ? py_prev + f * (py - py_prev) : py;
                count += qx >= x0 && qx <= x0 + w && qy >= y0 && qy <= y0 + h;
            }
            px_prev = px, py_prev = py;
        }
    }
    return count;
}

static void place_legend(cairo_t *cr, const im_plot_panel *p, const plot_layout *l, plot_panel_layout *pl)
{
    int entries = p->legend_title ? 1 : 0;
    double text = p->legend_title ? text_width(cr, l, p->legend_title) - plot_legend_sample_length(l) - 0.5 * l->font : 0.0;
    for (int s = 0; s < p->series_count; ++s)
        if (p->series[s].label) {
            ++entries;
            text = fmax(text, text_width(cr, l, p->series[s].label));
        }
    if (entries == (p->legend_title ? 1 : 0) || p->legend == IM_PLOT_LEGEND_HIDDEN)
        return;
    double pad = plot_legend_padding(l), inset = round(0.5 * l->font);
    pl->legend_width = ceil(2 * pad + plot_legend_sample_length(l) + 0.5 * l->font + text);
    pl->legend_height = 2 * pad + entries * plot_legend_row_height(l);
    double left = pl->box_x + inset, right = pl->box_x + pl->box_width - inset - pl->legend_width;
    double top = pl->box_y + inset, bottom = pl->box_y + pl->box_height - inset - pl->legend_height;
    /* Corners in the order of im_plot_legend (upper right first). */
    const double corner_x[4] = {right, left, right, left}, corner_y[4] = {top, top, bottom, bottom};
    int best = p->legend == IM_PLOT_LEGEND_AUTO ? 0 : (int)p->legend - 1;
    if (p->legend == IM_PLOT_LEGEND_AUTO) {
        int fewest = covered(p, pl, corner_x[0], corner_y[0], pl->legend_width, pl->legend_height);
        for (int c = 1; c < 4 && fewest > 0; ++c) {
            int n = covered(p, pl, corner_x[c], corner_y[c], pl->legend_width, pl->legend_height);
            if (n < fewest)
                fewest = n, best = c;
        }
    }
    pl->legend_x = corner_x[best];
    pl->legend_y = corner_y[best];
}

static int has_heading(const im_plot *plot)
{
    for (int i = 0; i < plot->rows * plot->columns; ++i)
        if (plot->panels[i].label || plot->panels[i].title)
            return 1;
    return 0;
}

int plot_make_layout(const im_plot *plot, cairo_t *cr, plot_layout *l)
{
    int status = check_plot(plot);
    if (status != IM_OK)
        return status;
    memset(l, 0, sizeof *l);
    l->points = plot->dpi / 72.0;
    l->font = plot->font_size * l->points;
    l->panel_count = plot->rows * plot->columns;
    double y_labels = 0.0, x_overhang = 0.0;
    int any_x_label = 0, any_y_label = 0;
    for (int i = 0; i < l->panel_count; ++i) {
        const im_plot_panel *p = &plot->panels[i];
        plot_panel_layout *pl = &l->panels[i];
        range x, y;
        status = check_panel(i + 1, p);
        if (status == IM_OK) {
            data_ranges(p, &x, &y);
            status = resolve_axis(i + 1, "x", &p->x, x, &pl->x);
        }
        if (status == IM_OK)
            status = resolve_axis(i + 1, "y", &p->y, y, &pl->y);
        if (status != IM_OK)
            return status;
        double widest, half;
        tick_label_widths(cr, l, &pl->y, &widest, &half);
        y_labels = fmax(y_labels, widest);
        tick_label_widths(cr, l, &pl->x, &widest, &half);
        x_overhang = fmax(x_overhang, half);
        any_x_label |= p->x.label != NULL;
        any_y_label |= p->y.label != NULL;
    }
    double f = l->font, margin = round(0.4 * f);
    double left = ceil(0.4 * f + y_labels + (any_y_label ? 1.5 * f : 0.0));
    double bottom = ceil(1.4 * f + (any_x_label ? 1.7 * f : 0.0));
    double top = has_heading(plot) ? round(1.5 * f) : round(0.6 * f);
    double right = ceil(fmax(0.6 * f, x_overhang));
    double box_w = round(plot->panel_width * l->points), box_h = round(plot->panel_height * l->points);
    double cell_w = left + box_w + right, cell_h = top + box_h + bottom;
    l->width = (int)(2 * margin + plot->columns * cell_w);
    l->height = (int)(2 * margin + plot->rows * cell_h);
    for (int i = 0; i < l->panel_count; ++i) {
        plot_panel_layout *pl = &l->panels[i];
        pl->box_x = margin + (i % plot->columns) * cell_w + left;
        pl->box_y = margin + (double)(i / plot->columns) * cell_h + top;
        pl->box_width = box_w, pl->box_height = box_h;
        place_legend(cr, &plot->panels[i], l, pl);
    }
    if (l->width > 32768 || l->height > 32768)
        return im_fail(IM_EINVAL, "plot %d x %d pixels: expected at most 32768 per side; lower the dpi or the "
                       "panel size", l->width, l->height);
    return IM_OK;
}
