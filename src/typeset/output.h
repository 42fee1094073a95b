/* Writing a cairo drawing as PNG (tEXt chunks, pHYs), PDF (keywords, creator) or SVG, atomically.
 * Shared by the figure module and the plot module. */
#ifndef INDENTMAP_TYPESET_OUTPUT_H
#define INDENTMAP_TYPESET_OUTPUT_H

#include "indentmap/io.h"
#include "indentmap/render.h"

#include <cairo.h>

/* The file formats (im_figure_format, figure.h, is this enumeration). */
typedef enum typeset_format { TYPESET_PNG, TYPESET_PDF, TYPESET_SVG } typeset_format;
/* The format from path's extension (.png, .pdf, .svg, any case); IM_EINVAL naming them otherwise. */
int typeset_format_of(const char *path, typeset_format *format);

/* The page: its size in pixels at dpi, and what goes into the file besides the drawing. */
typedef struct typeset_canvas {
    int width, height;        /* pixels, 1 to 32768 each */
    double dpi;               /* PNG pHYs; PDF and SVG are scaled to 72 / dpi points per pixel */
    const im_png_text *texts; /* PNG tEXt chunks, PDF keywords; may be NULL */
    int text_count;
    int png_compression; /* zlib level 0-9 */
} typeset_canvas;

/* Paints the whole canvas in pixel coordinates (the origin at the top left); returns a status. */
typedef int (*typeset_painter)(cairo_t *cr, const void *context);

/* Draws with paint and writes path in format. The painter's failure is returned as it is and
 * nothing is left behind; IM_EIO when the file cannot be written, IM_ENOMEM. */
int typeset_output(const char *path, typeset_format format, const typeset_canvas *canvas, typeset_painter paint,
                   const void *context);

/* As typeset_output for a PNG, and when frame is not NULL the PNG's pixels (RGBA, alpha 255) in
 * *frame (im_image_release; only the size and the pixels are set). */
int typeset_output_frame(const char *path, const typeset_canvas *canvas, typeset_painter paint, const void *context,
                         im_image *frame);

#endif
