/* Plots: defaults, colours, layout queries and output through the figure module's writers. */
#include "indentmap/plot.h"
#include "core/args.h"

#include "typeset/fonts.h"
#include "typeset/output.h"
#include "indentmap/colormap.h"
#include "indentmap/figure.h"
#include "indentmap/status.h"
#include "plot/layout.h"

#include <math.h>
#include <stdlib.h>

im_plot im_plot_default(void)
{
    im_plot plot = {.rows = 1,
                    .columns = 1,
                    .panel_width = 160.0,
                    .panel_height = 120.0,
                    .dpi = 300.0,
                    .font_size = 8.0,
                    .png_compression = IM_FIGURE_PNG_COMPRESSION};
    return plot;
}

void im_plot_palette(int i, uint8_t rgb[3])
{
    ARG_REQUIRE_OR(rgb, "rgb", );
    static const uint8_t okabe_ito[IM_PLOT_PALETTE_SIZE][3] = {
        {0, 114, 178},   /* blue */
        {213, 94, 0},    /* vermillion */
        {0, 158, 115},   /* bluish green */
        {230, 159, 0},   /* orange */
        {204, 121, 167}, /* reddish purple */
        {86, 180, 233},  /* sky blue */
        {0, 0, 0},       /* black */
        {240, 228, 66},  /* yellow */
    };
    int k = ((i % IM_PLOT_PALETTE_SIZE) + IM_PLOT_PALETTE_SIZE) % IM_PLOT_PALETTE_SIZE;
    rgb[0] = okabe_ito[k][0], rgb[1] = okabe_ito[k][1], rgb[2] = okabe_ito[k][2];
}

void im_plot_family_color(int i, int count, uint8_t rgb[3])
{
    ARG_REQUIRE_OR(rgb, "rgb", );
    const uint8_t(*table)[3] = im_colormap_table(IM_COLORMAP_VIRIDIS);
    double t = count > 1 ? (double)i / (count - 1) : 0.0;
    int index = (int)lround(0.85 * 255.0 * fmin(fmax(t, 0.0), 1.0));
    rgb[0] = table[index][0], rgb[1] = table[index][1], rgb[2] = table[index][2];
}

/* Lays the plot out on a scratch cairo context with the regular font face. */
static int layout_plot(const im_plot *plot, plot_layout *layout)
{
    cairo_font_face_t *regular, *bold;
    int status = typeset_fonts(&regular, &bold);
    if (status != IM_OK)
        return status;
    cairo_surface_t *scratch = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1);
    cairo_t *measure = cairo_create(scratch);
    cairo_set_font_face(measure, regular);
    status = plot_make_layout(plot, measure, layout);
    cairo_destroy(measure);
    cairo_surface_destroy(scratch);
    return status;
}

int im_plot_geometry_of(const im_plot *plot, int panel, im_plot_geometry *g)
{
    ARG_REQUIRE(plot, "plot");
    ARG_REQUIRE(g, "geometry");
    plot_layout *l = malloc(sizeof *l);
    if (!l)
        return im_fail(IM_ENOMEM, "plot layout: out of memory");
    int status = layout_plot(plot, l);
    if (status == IM_OK && (panel < 0 || panel >= l->panel_count))
        status = im_fail(IM_EINVAL, "plot: panel %d: expected 0 to %d", panel, l->panel_count - 1);
    if (status == IM_OK) {
        const plot_panel_layout *p = &l->panels[panel];
        *g = (im_plot_geometry){l->width,      l->height,   p->box_x,        p->box_y,        p->box_width,
                                p->box_height, p->x.lo,     p->x.hi,         p->y.lo,         p->y.hi,
                                p->legend_x,   p->legend_y, p->legend_width, p->legend_height};
    }
    free(l);
    return status;
}

typedef struct plot_drawing {
    const im_plot *plot;
    const plot_layout *layout;
} plot_drawing;

static int paint_plot(cairo_t *cr, const void *context)
{
    const plot_drawing *d = context;
    return plot_draw(d->plot, d->layout, cr);
}

int im_plot_write(const im_plot *plot, const char *path)
{
    ARG_REQUIRE(plot, "plot");
    ARG_REQUIRE(path, "path");
    typeset_format format;
    int status = typeset_format_of(path, &format);
    if (status != IM_OK)
        return status;
    plot_layout *l = malloc(sizeof *l);
    if (!l)
        return im_fail(IM_ENOMEM, "plot layout: out of memory");
    status = layout_plot(plot, l);
    if (status == IM_OK) {
        typeset_canvas canvas = {l->width,    l->height,        plot->dpi,
                                 plot->texts, plot->text_count, plot->png_compression};
        plot_drawing drawing = {plot, l};
        status = typeset_output(path, format, &canvas, paint_plot, &drawing);
    }
    free(l);
    return status;
}
