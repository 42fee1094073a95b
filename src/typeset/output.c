/* A cairo drawing written as PNG, PDF or SVG, atomically. */
#include "typeset/output.h"

#include "indentmap/io.h"
#include "indentmap/status.h"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static int check_canvas(const typeset_canvas *c)
{
    if (c->width < 1 || c->height < 1 || c->width > 32768 || c->height > 32768)
        return im_fail(IM_EINVAL,
                       "figure %d x %d pixels: expected 1 to 32768 per side; lower the dpi "
                       "or the sizes",
                       c->width, c->height);
    return IM_OK;
}

/* Paints the canvas into an RGBA image (alpha 255), the pixels a PNG of it holds. */
static int raster(const typeset_canvas *c, typeset_painter paint, const void *context, im_image *image)
{
    cairo_surface_t *surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, c->width, c->height);
    cairo_t *cr = cairo_create(surface);
    int status = paint(cr, context);
    if (status == IM_OK && cairo_status(cr) != CAIRO_STATUS_SUCCESS)
        status = im_fail(IM_ENOMEM, "figure: cairo: %s", cairo_status_to_string(cairo_status(cr)));
    cairo_destroy(cr);
    *image = (im_image){.width = c->width, .height = c->height};
    image->rgba = status == IM_OK ? malloc((size_t)c->width * c->height * 4) : NULL;
    if (status == IM_OK && !image->rgba)
        status = im_fail(IM_ENOMEM, "figure %d x %d: out of memory", c->width, c->height);
    if (status == IM_OK) {
        cairo_surface_flush(surface);
        const unsigned char *data = cairo_image_surface_get_data(surface);
        int stride = cairo_image_surface_get_stride(surface);
        for (int row = 0; row < c->height; ++row)
            for (int x = 0; x < c->width; ++x) {
                uint32_t p = ((const uint32_t *)(data + (size_t)row * stride))[x];
                uint8_t *out = image->rgba + ((size_t)row * c->width + x) * 4;
                out[0] = (uint8_t)(p >> 16), out[1] = (uint8_t)(p >> 8), out[2] = (uint8_t)p, out[3] = 255;
            }
    }
    cairo_surface_destroy(surface);
    return status;
}

/* The image as an RGB PNG with the canvas's texts and resolution. */
static int write_image_png(const char *path, const typeset_canvas *c, const im_image *image)
{
    size_t pixels = (size_t)image->width * image->height;
    uint8_t *rgb = malloc(pixels * 3);
    if (!rgb)
        return im_fail(IM_ENOMEM, "figure %d x %d: out of memory", image->width, image->height);
    for (size_t i = 0; i < pixels; ++i)
        memcpy(rgb + 3 * i, image->rgba + 4 * i, 3);
    im_png_options options = {c->texts, c->text_count, c->dpi / 0.0254, c->png_compression};
    int status = im_png_write(path, rgb, image->width, image->height, 3, (size_t)image->width * 3, &options);
    free(rgb);
    return status;
}

int typeset_output_frame(const char *path, const typeset_canvas *canvas, typeset_painter paint, const void *context,
                         im_image *frame)
{
    int status = check_canvas(canvas);
    im_image image = {0};
    if (status == IM_OK)
        status = raster(canvas, paint, context, &image);
    if (status == IM_OK)
        status = write_image_png(path, canvas, &image);
    if (status == IM_OK && frame)
        *frame = image;
    else
        im_image_release(&image);
    return status;
}

/* Where cairo writes a vector figure, and errno of the first write that failed: cairo's own status says
 * only "error while writing to output stream", not why (a full disk). */
typedef struct vector_stream {
    FILE *stream;
    int error;
} vector_stream;

static cairo_status_t write_stream(void *closure, const unsigned char *data, unsigned int length)
{
    vector_stream *out = closure;
    if (fwrite(data, 1, length, out->stream) == length)
        return CAIRO_STATUS_SUCCESS;
    if (!out->error)
        out->error = errno ? errno : EIO;
    return CAIRO_STATUS_WRITE_ERROR;
}

/* text as UTF-8, the text of PDF metadata (a path that is not UTF-8 is escaped, io.h: im_path_utf8);
 * NULL when out of memory. The caller frees it. */
static char *utf8_copy(const char *text)
{
    size_t size = 4 * strlen(text) + 1;
    char *copy = malloc(size);
    if (copy)
        im_path_utf8(text, copy, size);
    return copy;
}

/* The texts of several lines (a scene's contents, the inputs' checksums) as the document's Subject,
 * "key:\nvalue", blank-line separated (cairo before 1.18 writes no other entries of the information
 * dictionary). */
static void set_pdf_subject(const typeset_canvas *c, cairo_surface_t *surface)
{
    size_t size = 1, used = 0;
    for (int i = 0; i < c->text_count; ++i)
        size += strlen(c->texts[i].key) + strlen(c->texts[i].value) + 4;
    char *subject = malloc(size), *text = NULL;
    if (!subject)
        return; /* metadata only: the figure itself is written */
    subject[0] = '\0';
    for (int i = 0; i < c->text_count; ++i)
        if (strchr(c->texts[i].value, '\n'))
            used += (size_t)snprintf(subject + used, size - used, "%s%s:\n%s", used ? "\n\n" : "", c->texts[i].key,
                                     c->texts[i].value);
    if (used > 0 && (text = utf8_copy(subject)) != NULL)
        cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_SUBJECT, text);
    free(text);
    free(subject);
}

/* The texts as PDF metadata: one-line ones as keywords ("key=value; ..."), those of several lines as
 * the Subject. */
static void set_pdf_metadata(const typeset_canvas *c, cairo_surface_t *surface)
{
    char keywords[2048] = "";
    size_t used = 0;
    for (int i = 0; i < c->text_count && used < sizeof keywords; ++i)
        if (!strchr(c->texts[i].value, '\n'))
            used += (size_t)snprintf(keywords + used, sizeof keywords - used, "%s%s=%s", used ? "; " : "",
                                     c->texts[i].key, c->texts[i].value);
    set_pdf_subject(c, surface);
    char *text = utf8_copy(keywords);
    cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_KEYWORDS, text ? text : "");
    free(text);
    cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATOR, "indentmap " IM_VERSION);
}

static int write_vector(const char *path, typeset_format format, const typeset_canvas *c, typeset_painter paint,
                        const void *context)
{
    im_atomic_file file;
    int status = im_atomic_open(&file, path);
    if (status != IM_OK)
        return status;
    double points = 72.0 / c->dpi;
    vector_stream out = {file.stream, 0};
    cairo_surface_t *surface =
        format == TYPESET_PDF
            ? cairo_pdf_surface_create_for_stream(write_stream, &out, c->width * points, c->height * points)
            : cairo_svg_surface_create_for_stream(write_stream, &out, c->width * points, c->height * points);
    if (format == TYPESET_PDF)
        set_pdf_metadata(c, surface);
    cairo_t *cr = cairo_create(surface);
    cairo_scale(cr, points, points);
    status = paint(cr, context);
    if (status == IM_OK && cairo_status(cr) != CAIRO_STATUS_SUCCESS)
        status = im_fail(IM_ENOMEM, "figure: cairo: %s", cairo_status_to_string(cairo_status(cr)));
    cairo_destroy(cr);
    cairo_surface_finish(surface);
    cairo_status_t written = cairo_surface_status(surface);
    cairo_surface_destroy(surface);
    if (status == IM_OK && out.error)
        status = im_fail(IM_EIO, "%s: write failed: %s", path, strerror(out.error));
    else if (status == IM_OK && written != CAIRO_STATUS_SUCCESS)
        status = im_fail(IM_EIO, "%s: %s", path, cairo_status_to_string(written));
    if (status != IM_OK) {
        im_atomic_abort(&file);
        return status;
    }
    return im_atomic_commit(&file);
}

int typeset_format_of(const char *path, typeset_format *format)
{
    const char *dot = strrchr(path, '.');
    if (dot && strcasecmp(dot, ".png") == 0)
        *format = TYPESET_PNG;
    else if (dot && strcasecmp(dot, ".pdf") == 0)
        *format = TYPESET_PDF;
    else if (dot && strcasecmp(dot, ".svg") == 0)
        *format = TYPESET_SVG;
    else
        return im_fail(IM_EINVAL, "%s: unknown figure format: expected .png, .pdf or .svg", path);
    return IM_OK;
}

int typeset_output(const char *path, typeset_format format, const typeset_canvas *canvas, typeset_painter paint,
                   const void *context)
{
    if (format == TYPESET_PNG)
        return typeset_output_frame(path, canvas, paint, context, NULL);
    int status = check_canvas(canvas);
    return status == IM_OK ? write_vector(path, format, canvas, paint, context) : status;
}
