/* Figure layout with cairo: panels, labels, shared colour bar, scale bar; PNG, PDF, SVG output. */
#include "indentmap/figure.h"
#include "core/args.h"

#include "typeset/fonts.h"
#include "typeset/output.h"
#include "typeset/text.h"
#include "typeset/ticks.h"
#include "indentmap/status.h"

#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_TICKS = 32, MAX_PANELS = 64, MAX_BARS = 2 };

/* The shortest colour bar, in ems: room for three tick labels 1.2 em apart (choose_ticks), so that a
 * two-decade log bar labels every decade; shorter, a bar labels one tick or none. */
#define MIN_BAR_EMS 2.5

im_figure im_figure_default(void)
{
    im_figure figure = {.rows = 1,
                        .columns = 1,
                        .scale_bar = 0.0,
                        .dpi = 300.0,
                        .font_size = 8.0,
                        .png_compression = IM_FIGURE_PNG_COMPRESSION};
    return figure;
}

_Static_assert((int)IM_FIGURE_PNG == (int)TYPESET_PNG && (int)IM_FIGURE_PDF == (int)TYPESET_PDF &&
                   (int)IM_FIGURE_SVG == (int)TYPESET_SVG,
               "im_figure_format is typeset_format");

int im_figure_format_of(const char *path, im_figure_format *format)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(format, "format");
    typeset_format found;
    int status = typeset_format_of(path, &found);
    if (status == IM_OK)
        *format = (im_figure_format)found;
    return status;
}

/* ---- layout, in pixels at the figure's dpi ---- */

/* A colour bar: the force's, then the tension's beside it. */
typedef struct colorbar {
    const im_colormap *colormap;
    const char *label;
    int extend_under, extend_over;
    double x, y, height;     /* left edge, top and length of the bar itself */
    double ticks[MAX_TICKS]; /* the labelled ticks, thinned to fit */
    int tick_count;
    double tick_label_width;
} colorbar;

typedef struct layout {
    double font;                 /* text size in pixels */
    double line;                 /* thin line width (0.6 pt) in pixels */
    double margin, gap;          /* outer margin, gap between panels */
    double title_height;         /* row above each panel for labels and titles (0: none) */
    int cell_width, cell_height; /* largest image */
    int grid_x, grid_y;          /* top left of the first panel's title row */
    double bar_width, tick_length;
    colorbar bars[MAX_BARS];
    int bar_count;
    double scale_height; /* strip below the grid for the scale bar and the note */
    int own_bars;        /* a scale bar under each panel: their scales differ (scales_differ) */
    double row_scale;    /* then a strip for them below every row but the last (the last has scale_height) */
    double note_x;       /* where the note starts */
    int width, height;
} layout;

/* Fonts and a scratch cairo context for measuring text while laying out. */
typedef struct measure {
    cairo_t *cr;
    cairo_font_face_t *regular, *bold;
} measure;

static double text_width(const measure *m, cairo_font_face_t *face, double size, const char *text)
{
    return text ? typeset_rich_text(m->cr, face, size, 0.0, 0.0, text, 0) : 0.0;
}

static int has_panel_text(const im_figure *f)
{
    for (int i = 0; i < f->rows * f->columns; ++i)
        if (f->panels[i].label || f->panels[i].title)
            return 1;
    return 0;
}

/* 1-2-5 length near a fifth of the data width, in the image's units. */
static double automatic_scale_bar(const im_image *image)
{
    double width = image->nx * (image->unit[0] ? image->delta : 1.0);
    double target = width / 5.0, magnitude = pow(10.0, floor(log10(target)));
    double length = magnitude;
    const double multiples[] = {2.0, 5.0};
    for (int i = 0; i < 2; ++i)
        if (multiples[i] * magnitude <= target)
            length = multiples[i] * magnitude;
    return length;
}

/* Where a panel's title starts: centred over the image, but never left of the panel's edge nor
 * over its label (half an em after it). */
static double title_left(double font, double x, double image_width, double label_width, double title_width)
{
    double after_label = x + (label_width > 0.0 ? label_width + 0.5 * font : 0.0);
    return fmax(x + 0.5 * (image_width - title_width), after_label);
}

/* Width of a panel's column: its image, or its label and title row when wider. */
static double panel_width(const im_figure_panel *p, const measure *m, double font)
{
    double label = text_width(m, m->bold, font, p->label), title = text_width(m, m->regular, font, p->title);
    double row = p->title ? title_left(font, 0.0, p->image->width, label, title) + title : label;
    return fmax(p->image->width, ceil(row));
}

static double tick_position(const colorbar *b, double v)
{
    const im_colormap *c = b->colormap;
    double t = c->logarithmic ? log(v / c->lo) / log(c->hi / c->lo) : (v - c->lo) / (c->hi - c->lo);
    return b->y + (1.0 - t) * b->height;
}

int im_figure_ticks(const im_colormap *colormap, double *ticks, int capacity)
{
    ARG_REQUIRE_OR(colormap, "colormap", 0);
    ARG_REQUIRE_OR(ticks, "ticks", 0);
    return typeset_colour_bar_ticks(colormap->lo, colormap->hi, colormap->logarithmic, ticks, capacity);
}

/* The ticks to label: every k-th of im_figure_ticks, with the smallest k that puts labels at least
 * 1.2 em apart along the bar. */
static void choose_ticks(colorbar *b, double font)
{
    double all[MAX_TICKS];
    int count = im_figure_ticks(b->colormap, all, MAX_TICKS), stride = 1;
    for (; stride < count; ++stride) {
        int fits = 1;
        for (int i = stride; i < count && fits; i += stride)
            fits = tick_position(b, all[i - stride]) - tick_position(b, all[i]) >= 1.2 * font;
        if (fits)
            break;
    }
    b->tick_count = 0;
    for (int i = 0; i < count; i += stride)
        b->ticks[b->tick_count++] = all[i];
}

static void measure_colorbar(const measure *m, double font, colorbar *b)
{
    choose_ticks(b, font);
    b->tick_label_width = 0.0;
    for (int i = 0; i < b->tick_count; ++i) {
        char text[64];
        typeset_tick_label(b->colormap->logarithmic, b->ticks, b->tick_count, i, text, sizeof text);
        b->tick_label_width = fmax(b->tick_label_width, text_width(m, m->regular, font, text));
    }
}

/* Pixels per unit length of an image (per patch where it has no unit). */
static double pixels_per_length(const im_image *image)
{
    return image->pixels_per_patch / (image->unit[0] ? image->delta : 1.0);
}

/* Whether the panels have different scales (spacing, pixels per patch or unit): then each panel has a bar of
 * its own, as one bar gives only the bottom-left panel's scale. */
static int scales_differ(const im_figure *f)
{
    const im_image *first = f->panels[0].image;
    for (int i = 1; i < f->rows * f->columns; ++i) {
        const im_image *image = f->panels[i].image;
        if (strcmp(image->unit, first->unit) != 0 || pixels_per_length(image) != pixels_per_length(first))
            return 1;
    }
    return 0;
}

/* The scale bar's text (its length in the image's units) and its length in pixels, for the panel image. */
static void scale_bar(const im_figure *f, const im_image *image, char *text, size_t size, double *pixels)
{
    double length = f->scale_bar > 0.0 ? f->scale_bar : automatic_scale_bar(image);
    *pixels = (image->unit[0] ? length / image->delta : length) * image->pixels_per_patch;
    typeset_length_label(length, image->unit, text, size);
}

/* Moves the grid and the bars placed so far down (and grows the page) so that the last bar's
 * rotated label, centred on the bar, stays inside the margins. */
static void fit_colorbar_label(const measure *m, layout *l, double *bottom)
{
    const colorbar *b = &l->bars[l->bar_count - 1];
    double half = 0.5 * text_width(m, m->regular, l->font, b->label);
    double centre = b->y + 0.5 * b->height, shift = ceil(fmax(0.0, l->margin - (centre - half)));
    l->grid_y += (int)shift;
    for (int i = 0; i < l->bar_count; ++i)
        l->bars[i].y += shift;
    *bottom = fmax(*bottom, centre + shift + half);
}

/* The right edge of the last column's widest image: a title wider than its image widens the cells, but
 * the colour bars belong beside the images. */
static double images_right(const im_figure *f, const layout *l)
{
    int widest = 0;
    for (int row = 0; row < f->rows; ++row) {
        const im_image *image = f->panels[row * f->columns + f->columns - 1].image;
        widest = widest > image->width ? widest : image->width;
    }
    return l->grid_x + (f->columns - 1) * (l->cell_width + l->gap) + widest;
}

/* Places a colour bar along the panels' height (less its extension triangles) right of `left`, or of
 * `cells_right` (the cells' edge, which titles wider than their images push out) when its rotated
 * label, longer than the bar, would reach up into the title row; the right edge of its labels.
 * Beside panels too low for it (a 16 x 1024 scan) the bar keeps MIN_BAR_EMS and runs on below them,
 * right of `under_end`, where the scale bar's text and the note under the panels end. */
static double place_colorbar(const measure *m, layout *l, colorbar bar, double left, double cells_right,
                             double under_end, double grid_height, double *bottom)
{
    colorbar *b = &l->bars[l->bar_count++];
    *b = bar;
    /* Extension triangles for values beyond the norm sit inside the panels' height. */
    double triangle = round(1.2 * l->bar_width);
    b->y = l->grid_y + l->title_height + (b->extend_over ? triangle : 0.0);
    b->height = grid_height - l->title_height - (b->extend_over + b->extend_under) * triangle;
    int lengthened = b->height < round(MIN_BAR_EMS * l->font);
    if (lengthened) {
        b->height = round(MIN_BAR_EMS * l->font);
        left = fmax(left, under_end);
    }
    if (text_width(m, m->regular, l->font, b->label) > b->height)
        left = fmax(left, cells_right);
    b->x = round(left + 1.2 * l->font);
    measure_colorbar(m, l->font, b);
    if (b->label)
        fit_colorbar_label(m, l, bottom);
    /* the under triangle, or the lowest tick label's lower half */
    if (lengthened)
        *bottom = fmax(*bottom, b->y + b->height + fmax(b->extend_under ? triangle : 0.0, 0.6 * l->font));
    return b->x + l->bar_width + l->tick_length + 0.3 * l->font + b->tick_label_width +
           (b->label ? 1.6 * l->font : 0.0);
}

/* The panels' grid: its rows, their titles, the gaps and the scale bars' strips between them. */
static double grid_height_of(const im_figure *f, const layout *l)
{
    return f->rows * (l->title_height + l->cell_height) + (f->rows - 1) * (l->gap + l->row_scale);
}

static void make_layout(const im_figure *f, const measure *m, layout *l)
{
    memset(l, 0, sizeof *l);
    double k = f->dpi / 72.0;
    l->font = f->font_size * k;
    l->line = 0.6 * k;
    l->margin = round(0.8 * l->font);
    l->gap = round(1.0 * l->font);
    l->title_height = has_panel_text(f) ? round(1.5 * l->font) : 0.0;
    for (int i = 0; i < f->rows * f->columns; ++i) {
        l->cell_width = (int)fmax(l->cell_width, panel_width(&f->panels[i], m, l->font));
        l->cell_height = l->cell_height > f->panels[i].image->height ? l->cell_height : f->panels[i].image->height;
    }
    l->grid_x = (int)l->margin;
    l->grid_y = (int)l->margin;
    double grid_width = f->columns * l->cell_width + (f->columns - 1) * l->gap;
    l->scale_height = f->scale_bar >= 0.0 || f->note ? round(2.4 * l->font) : 0.0;
    l->own_bars = f->scale_bar >= 0.0 && scales_differ(f);
    l->row_scale = l->own_bars ? l->scale_height : 0.0;
    double grid_height = grid_height_of(f, l);
    double right = l->grid_x + grid_width, bottom = 0.0, scale_end = l->grid_x;
    if (f->scale_bar >= 0.0) {
        char text[64];
        double pixels;
        scale_bar(f, f->panels[(f->rows - 1) * f->columns].image, text, sizeof text, &pixels);
        /* the bar starts at the bottom-left panel's data, data_x into its cell */
        double start = f->panels[(f->rows - 1) * f->columns].image->data_x;
        scale_end = l->grid_x + start + fmax(pixels, text_width(m, m->regular, l->font, text));
        right = fmax(right, scale_end);
    }
    if (f->note) {
        /* Right-aligned with the grid, never over the scale bar's text: the figure widens instead. */
        double width = text_width(m, m->regular, l->font, f->note);
        l->note_x = fmax(l->grid_x + grid_width - width, f->scale_bar >= 0.0 ? scale_end + l->font : l->grid_x);
        right = fmax(right, l->note_x + width);
    }
    l->bar_width = round(1.1 * l->font);
    l->tick_length = round(0.4 * l->font);
    double cells_right = l->grid_x + grid_width, bars_end = images_right(f, l), under_end = right;
    if (f->colormap)
        bars_end = place_colorbar(m, l,
                                  (colorbar){.colormap = f->colormap,
                                             .label = f->colorbar_label,
                                             .extend_under = f->extend_under,
                                             .extend_over = f->extend_over},
                                  bars_end, cells_right, under_end, grid_height, &bottom);
    if (f->tension_colormap)
        bars_end = place_colorbar(m, l, (colorbar){.colormap = f->tension_colormap, .label = f->tension_label},
                                  bars_end, cells_right, under_end, grid_height, &bottom);
    if (l->bar_count)
        right = fmax(right, bars_end);
    l->width = (int)ceil(right + l->margin);
    l->height = (int)ceil(fmax(l->grid_y + grid_height + l->scale_height, bottom) + l->margin);
}

/* ---- drawing ---- */

/* A cairo surface holding an RGBA image (opaque) or a table. Caller destroys it. */
static cairo_surface_t *image_surface(const uint8_t *rgba, int width, int height, size_t stride_bytes, int channels)
{
    cairo_surface_t *surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
    if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS)
        return surface;
    cairo_surface_flush(surface);
    unsigned char *data = cairo_image_surface_get_data(surface);
    int stride = cairo_image_surface_get_stride(surface);
    for (int row = 0; row < height; ++row) {
        uint32_t *out = (uint32_t *)(data + (size_t)row * stride);
        const uint8_t *in = rgba + (size_t)row * stride_bytes;
        for (int x = 0; x < width; ++x)
            out[x] = (uint32_t)in[channels * x] << 16 | (uint32_t)in[channels * x + 1] << 8 | in[channels * x + 2];
    }
    cairo_surface_mark_dirty(surface);
    return surface;
}

static int paint_surface(cairo_t *cr, cairo_surface_t *surface, double x, double y, double scale_x, double scale_y)
{
    if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS) {
        cairo_surface_destroy(surface);
        return im_fail(IM_ENOMEM, "figure: image surface: %s", cairo_status_to_string(cairo_surface_status(surface)));
    }
    cairo_save(cr);
    cairo_translate(cr, x, y);
    cairo_scale(cr, scale_x, scale_y);
    cairo_set_source_surface(cr, surface, 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
    cairo_paint(cr);
    cairo_restore(cr);
    cairo_surface_destroy(surface);
    return IM_OK;
}

static void panel_origin(const im_figure *f, const layout *l, int index, int *x, int *y)
{
    int row = index / f->columns, column = index % f->columns;
    *x = l->grid_x + (int)(column * (l->cell_width + l->gap));
    *y = l->grid_y + (int)(row * (l->title_height + l->cell_height + l->row_scale + l->gap) + l->title_height);
}

static int draw_panels(const im_figure *f, const layout *l, cairo_t *cr, cairo_font_face_t *regular,
                       cairo_font_face_t *bold)
{
    for (int i = 0; i < f->rows * f->columns; ++i) {
        const im_figure_panel *p = &f->panels[i];
        int x, y;
        panel_origin(f, l, i, &x, &y);
        int status = paint_surface(
            cr, image_surface(p->image->rgba, p->image->width, p->image->height, (size_t)p->image->width * 4, 4), x,
            y, 1.0, 1.0);
        if (status != IM_OK)
            return status;
        cairo_set_source_rgb(cr, 0, 0, 0);
        double baseline = y - 0.45 * l->font;
        double label_width = p->label ? typeset_rich_text(cr, bold, l->font, 0, 0, p->label, 0) : 0.0;
        if (p->label)
            typeset_show_text(cr, bold, l->font, x, baseline, 0.0, p->label);
        if (p->title) {
            double width = typeset_rich_text(cr, regular, l->font, 0, 0, p->title, 0);
            typeset_show_text(cr, regular, l->font, title_left(l->font, x, p->image->width, label_width, width),
                              baseline, 0.0, p->title);
        }
    }
    return IM_OK;
}

/* Under the panel `index`, whose scale it gives: a bar of the given length and its value, in δ or the unit; the
 * text centred under the bar, or starting at the panel's edge when the bar is shorter. It hangs from that
 * panel's image, not its cell: under a panel smaller than the others it sat a cell's height below it (S13). */
static void draw_scale_bar(const im_figure *f, const layout *l, int index, cairo_t *cr, cairo_font_face_t *regular)
{
    int x, y;
    const im_image *image = f->panels[index].image;
    panel_origin(f, l, index, &x, &y);
    char text[64];
    double pixels;
    scale_bar(f, image, text, sizeof text, &pixels);
    double top = y + image->height + 0.5 * l->font, left = x + image->data_x;
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_rectangle(cr, left, top, pixels, round(0.3 * l->font));
    cairo_fill(cr);
    double width = typeset_rich_text(cr, regular, l->font, 0, 0, text, 0);
    typeset_show_text(cr, regular, l->font, fmax(x, left + 0.5 * (pixels - width)),
                      top + 0.3 * l->font + 1.1 * l->font, 0.0, text);
}

/* The note under the grid, on the line of a scale bar under the bottom row's full cell height. */
static void draw_note(const im_figure *f, const layout *l, cairo_t *cr, cairo_font_face_t *regular)
{
    double top = l->grid_y + grid_height_of(f, l) + 0.5 * l->font;
    cairo_set_source_rgb(cr, 0, 0, 0);
    typeset_show_text(cr, regular, l->font, l->note_x, top + 0.3 * l->font + 1.1 * l->font, 0.0, f->note);
}

/* Unlabelled ticks at 2..9 times each decade of a logarithmic bar, half as long. */
static void draw_minor_ticks(const colorbar *b, const layout *l, cairo_t *cr)
{
    const im_colormap *c = b->colormap;
    double right = b->x + l->bar_width;
    for (double decade = pow(10.0, floor(log10(c->lo))); decade <= c->hi; decade *= 10.0)
        for (int m = 2; m <= 9; ++m) {
            double v = m * decade;
            if (v < c->lo || v > c->hi)
                continue;
            double y = tick_position(b, v);
            cairo_move_to(cr, right, y);
            cairo_line_to(cr, right + 0.5 * l->tick_length, y);
            cairo_stroke(cr);
        }
}

/* A triangle beyond one end of the bar (direction -1 up, +1 down) in the under or over colour. */
static void draw_extension(const colorbar *b, const layout *l, cairo_t *cr, double base_y, double direction,
                           const uint8_t rgb[3])
{
    double triangle = round(1.2 * l->bar_width);
    cairo_move_to(cr, b->x, base_y);
    cairo_line_to(cr, b->x + 0.5 * l->bar_width, base_y + direction * triangle);
    cairo_line_to(cr, b->x + l->bar_width, base_y);
    cairo_close_path(cr);
    cairo_set_source_rgb(cr, rgb[0] / 255.0, rgb[1] / 255.0, rgb[2] / 255.0);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, l->line);
    cairo_stroke(cr);
}

static int draw_colorbar(const colorbar *b, const layout *l, cairo_t *cr, cairo_font_face_t *regular)
{
    /* The table as a 1 x 256 image, top row = last entry, stretched without interpolation. */
    const im_colormap *c = b->colormap;
    const uint8_t(*table)[3] = im_colormap_table(c->map);
    uint8_t column[256][3];
    for (int i = 0; i < 256; ++i)
        memcpy(column[i], table[255 - i], 3);
    int status = paint_surface(cr, image_surface(&column[0][0], 1, 256, 3, 3), b->x, b->y, l->bar_width,
                               b->height / 256.0);
    if (status != IM_OK)
        return status;
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, l->line);
    cairo_rectangle(cr, b->x, b->y, l->bar_width, b->height);
    cairo_stroke(cr);
    if (b->extend_over)
        draw_extension(b, l, cr, b->y, -1.0, c->over);
    if (b->extend_under)
        draw_extension(b, l, cr, b->y + b->height, 1.0, c->under);
    double right = b->x + l->bar_width;
    for (int i = 0; i < b->tick_count; ++i) {
        double y = tick_position(b, b->ticks[i]);
        cairo_move_to(cr, right, y);
        cairo_line_to(cr, right + l->tick_length, y);
        cairo_stroke(cr);
        char text[64];
        typeset_tick_label(c->logarithmic, b->ticks, b->tick_count, i, text, sizeof text);
        typeset_show_text(cr, regular, l->font, right + l->tick_length + 0.3 * l->font, y + 0.36 * l->font, 0.0,
                          text);
    }
    if (c->logarithmic)
        draw_minor_ticks(b, l, cr);
    if (b->label) {
        cairo_save(cr);
        cairo_translate(cr, right + l->tick_length + 0.3 * l->font + b->tick_label_width + 1.2 * l->font,
                        b->y + 0.5 * b->height);
        cairo_rotate(cr, -M_PI / 2.0);
        typeset_show_text(cr, regular, l->font, 0.0, 0.0, 0.5, b->label);
        cairo_restore(cr);
    }
    return IM_OK;
}

static int draw_figure(const im_figure *f, const layout *l, cairo_t *cr)
{
    cairo_font_face_t *regular, *bold;
    int status = typeset_fonts(&regular, &bold);
    if (status != IM_OK)
        return status;
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    status = draw_panels(f, l, cr, regular, bold);
    if (status == IM_OK && f->scale_bar >= 0.0) /* under the bottom-left panel; under each where scales differ */
        for (int i = 0; i < f->rows * f->columns; ++i)
            if (l->own_bars || i == (f->rows - 1) * f->columns)
                draw_scale_bar(f, l, i, cr, regular);
    if (status == IM_OK && f->note)
        draw_note(f, l, cr, regular);
    for (int i = 0; i < l->bar_count && status == IM_OK; ++i)
        status = draw_colorbar(&l->bars[i], l, cr, regular);
    return status;
}

typedef struct figure_drawing {
    const im_figure *figure;
    const layout *layout;
} figure_drawing;

static int paint_figure(cairo_t *cr, const void *context)
{
    const figure_drawing *d = context;
    return draw_figure(d->figure, d->layout, cr);
}

/* ---- validation and output ---- */

static int check_figure(const im_figure *f)
{
    if (f->rows < 1 || f->columns < 1 || f->rows * f->columns > MAX_PANELS || !f->panels)
        return im_fail(IM_EINVAL, "figure: %d x %d panels: expected 1 to %d panels", f->rows, f->columns, MAX_PANELS);
    for (int i = 0; i < f->rows * f->columns; ++i)
        if (!f->panels[i].image || !f->panels[i].image->rgba || f->panels[i].image->width < 1)
            return im_fail(IM_EINVAL, "figure: panel %d has no image", i + 1);
    if (!(f->dpi > 0.0 && f->dpi <= 2400.0))
        return im_fail(IM_EINVAL, "figure: dpi = %g: expected (0, 2400]", f->dpi);
    if (!(f->font_size > 0.0 && f->font_size <= 72.0))
        return im_fail(IM_EINVAL, "figure: font size %g pt: expected (0, 72]", f->font_size);
    if (!isfinite(f->scale_bar))
        return im_fail(IM_EINVAL, "figure: scale bar %g: expected a finite length", f->scale_bar);
    if (f->png_compression < 0 || f->png_compression > 9)
        return im_fail(IM_EINVAL, "figure: PNG compression %d: expected 0-9", f->png_compression);
    int status = f->colormap ? im_colormap_check(f->colormap) : IM_OK;
    if (status == IM_OK && f->tension_colormap && (status = im_colormap_check(f->tension_colormap)) != IM_OK)
        return im_fail_context(status, "figure: tension colour bar");
    return status;
}

/* Checks the figure and lays it out. */
static int prepare(const im_figure *f, layout *l)
{
    int status = check_figure(f);
    cairo_font_face_t *regular, *bold;
    if (status == IM_OK)
        status = typeset_fonts(&regular, &bold);
    if (status != IM_OK)
        return status;
    cairo_surface_t *scratch = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1);
    measure m = {cairo_create(scratch), regular, bold};
    make_layout(f, &m, l);
    cairo_destroy(m.cr);
    cairo_surface_destroy(scratch);
    if (l->width > 32768 || l->height > 32768)
        return im_fail(IM_EINVAL,
                       "figure %d x %d pixels: expected at most 32768 per side; lower the dpi "
                       "or the pixels per patch",
                       l->width, l->height);
    return IM_OK;
}

/* Writes the figure as path in format; a PNG's pixels also in *frame when frame is not NULL. */
static int output(const im_figure *f, const char *path, typeset_format format, im_image *frame)
{
    layout l;
    int status = prepare(f, &l);
    if (status != IM_OK)
        return status;
    typeset_canvas canvas = {l.width, l.height, f->dpi, f->texts, f->text_count, f->png_compression};
    figure_drawing drawing = {f, &l};
    return format == TYPESET_PNG ? typeset_output_frame(path, &canvas, paint_figure, &drawing, frame)
                                 : typeset_output(path, format, &canvas, paint_figure, &drawing);
}

int im_figure_write(const im_figure *f, const char *path)
{
    ARG_REQUIRE(f, "figure");
    ARG_REQUIRE(path, "path");
    typeset_format format = TYPESET_PNG;
    int status = typeset_format_of(path, &format);
    return status == IM_OK ? output(f, path, format, NULL) : status;
}

int im_figure_write_frame(const im_figure *f, const char *path, im_image *frame)
{
    ARG_REQUIRE(f, "figure");
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(frame, "frame");
    *frame = (im_image){0};
    typeset_format format = TYPESET_PNG;
    int status = typeset_format_of(path, &format);
    if (status == IM_OK && format != TYPESET_PNG)
        status = im_fail(IM_EINVAL, "%s: a frame is a PNG: expected a path ending in .png", path);
    return status == IM_OK ? output(f, path, format, frame) : status;
}
