/* Plot checks, limits, ticks and placement, in pixels at the plot's dpi. */
#include "plot/clip.h"
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
    if (p->panel_count != 0 &&
        (p->panel_count <= (p->rows - 1) * p->columns || p->panel_count > p->rows * p->columns))
        return im_fail(IM_EINVAL, "plot: %d panels in %d x %d cells: expected %d to %d (0: every cell)",
                       p->panel_count, p->rows, p->columns, (p->rows - 1) * p->columns + 1, p->rows * p->columns);
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
        return im_fail(IM_EINVAL, "plot panel %d: %s axis scale %d: expected linear or log", panel, name,
                       (int)a->scale);
    if (!(a->lo < a->hi))
        return IM_OK; /* automatic */
    if (!isfinite(a->lo) || !isfinite(a->hi))
        return im_fail(IM_ENUMERIC, "plot panel %d: %s limits [%g, %g]: expected finite values", panel, name, a->lo,
                       a->hi);
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
            return im_fail(IM_ENUMERIC,
                           "plot panel %d series %d: %s[%d] = %g: expected a finite value (NaN "
                           "leaves a gap)",
                           panel, index, what, i, v[i]);
        if (positive && v[i] <= 0.0)
            return im_fail(IM_EINVAL, "plot panel %d series %d: %s[%d] = %g on a log axis: expected > 0", panel,
                           index, what, i, v[i]);
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
        return im_fail(IM_EINVAL,
                       "plot panel %d series %d: line width %g pt, marker size %g pt: expected "
                       "[0, 50] (0: default)",
                       panel, index, s->line_width, s->marker_size);
    if (!s->band_lo != !s->band_hi)
        return im_fail(IM_EINVAL, "plot panel %d series %d: a band needs both band_lo and band_hi", panel, index);
    return IM_OK;
}

static int check_series(int panel, int index, const im_plot_series *s, const im_plot_panel *p)
{
    if (s->n < 1 || !s->x || !s->y)
        return im_fail(IM_EINVAL,
                       "plot panel %d series %d%s%s: no points (n = %d): expected n >= 1 and x, y "
                       "arrays",
                       panel, index, s->label ? " " : "", s->label ? s->label : "", s->n);
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
    if (status == IM_OK && ((int)p->legend < IM_PLOT_LEGEND_AUTO || p->legend > IM_PLOT_LEGEND_OUTSIDE_RIGHT))
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
    return typeset_ticks_between(a->lo, a->hi, a->scale == IM_PLOT_LOG, TICK_TARGET, a->ticks, PLOT_MAX_TICKS);
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
            return im_fail(IM_ENUMERIC,
                           "plot panel %d: %s data from %g to %g: automatic limits overflow; give "
                           "them",
                           panel, name, data.lo, data.hi);
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
    return typeset_rich_text(cr, cairo_get_font_face(cr), l->font, 0.0, 0.0, text, 0);
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
        typeset_tick_label(a->scale == IM_PLOT_LOG, a->ticks, a->tick_count, i, text, sizeof text);
        double w = text_width(cr, l, text);
        *widest = fmax(*widest, w);
        *last_half = 0.5 * w;
    }
}

/* Whether the segment from (ax, ay) to (bx, by) meets the rectangle r (Liang-Barsky); a point
 * when both ends are equal. Non-finite ends (gaps, log axes' zeros) meet nothing. */
static int segment_meets(plot_rect r, double ax, double ay, double bx, double by)
{
    if (!isfinite(ax + ay + bx + by))
        return 0;
    double t0 = 0.0, t1 = 1.0, dx = bx - ax, dy = by - ay;
    const double p[4] = {-dx, dx, -dy, dy}, q[4] = {ax - r.left, r.right - ax, ay - r.top, r.bottom - ay};
    for (int i = 0; i < 4; ++i) {
        if (p[i] == 0.0) {
            if (q[i] < 0.0)
                return 0;
        } else if (p[i] < 0.0) {
            t0 = fmax(t0, q[i] / p[i]);
        } else {
            t1 = fmin(t1, q[i] / p[i]);
        }
    }
    return t0 <= t1;
}

/* Whether series s draws anything (line, marker, error bar, band edge) inside r. */
static int series_meets(const im_plot_series *s, const plot_panel_layout *pl, plot_rect r)
{
    double bottom = pl->box_y + pl->box_height;
    for (int i = 0; i < s->n; ++i) {
        double x = plot_axis_pixel(&pl->x, s->x[i], pl->box_x, pl->box_width);
        double y = plot_axis_pixel(&pl->y, s->y[i], bottom, -pl->box_height);
        double x0 = i > 0 ? plot_axis_pixel(&pl->x, s->x[i - 1], pl->box_x, pl->box_width) : x;
        double y0 = i > 0 ? plot_axis_pixel(&pl->y, s->y[i - 1], bottom, -pl->box_height) : y;
        if (segment_meets(r, x, y, x, y) || (s->line != IM_PLOT_NO_LINE && segment_meets(r, x0, y0, x, y)))
            return 1;
        if (s->sigma && isfinite(s->sigma[i]) &&
            segment_meets(r, x, plot_axis_pixel(&pl->y, s->y[i] - s->sigma[i], bottom, -pl->box_height), x,
                          plot_axis_pixel(&pl->y, s->y[i] + s->sigma[i], bottom, -pl->box_height)))
            return 1;
        for (int edge = 0; edge < 2 && s->band_lo && s->band_hi; ++edge) {
            const double *band = edge ? s->band_hi : s->band_lo;
            if (segment_meets(r, x, plot_axis_pixel(&pl->y, band[i], bottom, -pl->box_height), x,
                              plot_axis_pixel(&pl->y, band[i > 0 ? i - 1 : 0], bottom, -pl->box_height)))
                return 1;
        }
    }
    return 0;
}

/* Whether a legend at (x, y) of the panel's legend size, grown by `clearance` all round, would
 * touch anything the panel draws. */
static int legend_touches_data(const im_plot_panel *p, const plot_panel_layout *pl, double x, double y,
                               double clearance)
{
    plot_rect r = {x - clearance, y - clearance, x + pl->legend_width + clearance, y + pl->legend_height + clearance};
    for (int s = 0; s < p->series_count; ++s)
        if (series_meets(&p->series[s], pl, r))
            return 1;
    return 0;
}

/* The legend's size from its entries (0 x 0: no legend). */
static void size_legend(cairo_t *cr, const im_plot_panel *p, const plot_layout *l, plot_panel_layout *pl)
{
    int entries = p->legend_title ? 1 : 0;
    double text = p->legend_title ? text_width(cr, l, p->legend_title) - plot_legend_sample_length(l) - 0.5 * l->font
                                  : 0.0;
    for (int s = 0; s < p->series_count; ++s)
        if (p->series[s].label) {
            ++entries;
            text = fmax(text, text_width(cr, l, p->series[s].label));
        }
    pl->legend_width = pl->legend_height = 0.0;
    if (entries == (p->legend_title ? 1 : 0) || p->legend == IM_PLOT_LEGEND_HIDDEN)
        return;
    double pad = plot_legend_padding(l);
    pl->legend_width = ceil(2 * pad + plot_legend_sample_length(l) + 0.5 * l->font + text);
    pl->legend_height = 2 * pad + entries * plot_legend_row_height(l);
}

/* Places a sized legend: at its stated corner or outside, or for IM_PLOT_LEGEND_AUTO at the first
 * corner that touches no data, else outside. The frame must be placed. Returns whether it went
 * outside. */
static int place_legend(const im_plot_panel *p, const plot_layout *l, plot_panel_layout *pl)
{
    if (pl->legend_width <= 0.0)
        return 0;
    double inset = round(0.5 * l->font);
    double left = pl->box_x + inset, right = pl->box_x + pl->box_width - inset - pl->legend_width;
    double top = pl->box_y + inset, bottom = pl->box_y + pl->box_height - inset - pl->legend_height;
    /* Corners in the order of im_plot_legend (upper right first); the fifth place is outside. */
    const double place_x[5] = {right, left, right, left, pl->box_x + pl->box_width + 2 * inset};
    const double place_y[5] = {top, top, bottom, bottom, pl->box_y};
    int chosen = p->legend == IM_PLOT_LEGEND_OUTSIDE_RIGHT ? 4 : (int)p->legend - 1;
    if (p->legend == IM_PLOT_LEGEND_AUTO)
        for (chosen = 0; chosen < 4 && legend_touches_data(p, pl, place_x[chosen], place_y[chosen], inset);)
            ++chosen;
    pl->legend_x = place_x[chosen];
    pl->legend_y = place_y[chosen];
    return chosen == 4;
}

/* The room right of the frames that legends placed outside need: `inner` for a panel of any column
 * but the last (it pushes the next column over), `last` for one of the last column (it widens the
 * figure only); none for the last panel of a row left part empty when the empty cells' frames hold it.
 * A frame at the origin is enough to choose, since only the frame's size matters. */
static void outside_legend_room(cairo_t *cr, const im_plot *plot, plot_layout *l, double box_w, double box_h,
                                double *inner, double *last)
{
    *inner = *last = 0.0;
    for (int i = 0; i < l->panel_count; ++i) {
        plot_panel_layout *pl = &l->panels[i];
        pl->box_x = pl->box_y = 0.0, pl->box_width = box_w, pl->box_height = box_h;
        size_legend(cr, &plot->panels[i], l, pl);
        int empty_cells = i == l->panel_count - 1 ? plot->rows * plot->columns - l->panel_count : 0;
        if (!place_legend(&plot->panels[i], l, pl) || pl->legend_width + round(0.5 * l->font) <= empty_cells * box_w)
            continue;
        double *room = i % plot->columns == plot->columns - 1 ? last : inner;
        *room = fmax(*room, pl->legend_width + 2 * round(0.5 * l->font));
    }
}

static int has_heading(const im_plot *plot, int panel_count)
{
    for (int i = 0; i < panel_count; ++i)
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
    l->panel_count = plot->panel_count ? plot->panel_count : plot->rows * plot->columns;
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
    double top = has_heading(plot, l->panel_count) ? round(1.5 * f) : round(0.6 * f);
    double box_w = round(plot->panel_width * l->points), box_h = round(plot->panel_height * l->points);
    double inner_room, last_room;
    outside_legend_room(cr, plot, l, box_w, box_h, &inner_room, &last_room);
    double right = ceil(fmax(0.6 * f, x_overhang) + inner_room);
    double cell_w = left + box_w + right, cell_h = top + box_h + bottom;
    l->width = (int)(2 * margin + plot->columns * cell_w + ceil(fmax(0.0, last_room - inner_room)));
    l->height = (int)(2 * margin + plot->rows * cell_h);
    for (int i = 0; i < l->panel_count; ++i) {
        plot_panel_layout *pl = &l->panels[i];
        pl->box_x = margin + (i % plot->columns) * cell_w + left;
        pl->box_y = margin + (double)(i / plot->columns) * cell_h + top;
        pl->box_width = box_w, pl->box_height = box_h;
        place_legend(&plot->panels[i], l, pl);
    }
    if (l->width > 32768 || l->height > 32768)
        return im_fail(IM_EINVAL,
                       "plot %d x %d pixels: expected at most 32768 per side; lower the dpi or the "
                       "panel size",
                       l->width, l->height);
    return IM_OK;
}
