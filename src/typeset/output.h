/* Writing a cairo drawing as PNG (tEXt chunks, pHYs), PDF (keywords, creator) or SVG, atomically.
 * Shared by the figure module and the plot module. */
#ifndef INDENTMAP_TYPESET_OUTPUT_H
#define INDENTMAP_TYPESET_OUTPUT_H

#include "indentmap/figure.h"

#include <cairo.h>

/* The page: its size in pixels at dpi, and what goes into the file besides the drawing. */
typedef struct im_figure_canvas {
    int width, height;              /* pixels, 1 to 32768 each */
    double dpi;                     /* PNG pHYs; PDF and SVG are scaled to 72 / dpi points per pixel */
    const im_png_text *texts;       /* PNG tEXt chunks, PDF keywords; may be NULL */
    int text_count;
    int png_compression;            /* zlib level 0-9 */
} im_figure_canvas;

/* Paints the whole canvas in pixel coordinates (the origin at the top left); returns a status. */
typedef int (*im_figure_painter)(cairo_t *cr, const void *context);

/* Draws with paint and writes path in format. The painter's failure is returned as it is and
 * nothing is left behind; IM_EIO when the file cannot be written, IM_ENOMEM. */
int figure_output(const char *path, im_figure_format format, const im_figure_canvas *canvas,
                     im_figure_painter paint, const void *context);

/* As figure_output for a PNG, and when frame is not NULL the PNG's pixels (RGBA, alpha 255) in
 * *frame (im_image_release; only the size and the pixels are set). */
int figure_output_frame(const char *path, const im_figure_canvas *canvas, im_figure_painter paint,
                        const void *context, im_image *frame);

#endif
