#include "indentmap/io.h"
#include "core/args.h"

#include "indentmap/status.h"

#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int check_image(const char *path, int width, int height, int channels)
{
    if (width < 1 || height < 1 || width > 1 << 15 || height > 1 << 15)
        return im_fail(IM_EINVAL, "%s: image %d x %d: expected each side in [1, 32768]", path, width, height);
    if (channels != 3 && channels != 4)
        return im_fail(IM_EINVAL, "%s: %d channels: expected 3 (RGB) or 4 (RGBA)", path, channels);
    return IM_OK;
}

/* tEXt holds Latin-1 only; UTF-8 beyond ASCII goes into an uncompressed iTXt chunk. */
static int is_ascii(const char *text)
{
    for (const unsigned char *p = (const unsigned char *)text; *p; ++p)
        if (*p > 0x7e || (*p < 0x20 && *p != '\n'))
            return 0;
    return 1;
}

static void set_metadata(png_structp png, png_infop info, const im_png_options *options)
{
    if (!options)
        return;
    if (options->text_count > 0) {
        png_textp texts = calloc((size_t)options->text_count, sizeof *texts);
        for (int i = 0; texts && i < options->text_count; ++i) {
            texts[i].key = (png_charp)options->texts[i].key;
            texts[i].text = (png_charp)options->texts[i].value;
            texts[i].compression = is_ascii(texts[i].text) ? PNG_TEXT_COMPRESSION_NONE : PNG_ITXT_COMPRESSION_NONE;
            texts[i].lang = (png_charp) "";
            texts[i].lang_key = (png_charp) "";
        }
        if (texts)
            png_set_text(png, info, texts, options->text_count);
        free(texts); /* png_set_text copies the strings */
    }
    if (options->dots_per_metre > 0.0) {
        png_uint_32 dpm = (png_uint_32)(options->dots_per_metre + 0.5);
        png_set_pHYs(png, info, dpm, dpm, PNG_RESOLUTION_METER);
    }
}

/* What made libpng give up: its message, and errno at that moment (a failed write's reason). */
typedef struct png_failure {
    char message[128];
    int saved_errno;
} png_failure;

/* libpng's default handler prints "libpng error: Write Error" with no file and no reason; this one
 * keeps both for the caller's message. */
static void on_png_error(png_structp png, png_const_charp message)
{
    png_failure *failure = png_get_error_ptr(png);
    failure->saved_errno = errno;
    snprintf(failure->message, sizeof failure->message, "%s", message);
    png_longjmp(png, 1);
}

static void on_png_warning(png_structp png, png_const_charp message)
{
    (void)png;
    (void)message; /* nothing libpng warns about when writing what we give it */
}

/* Encodes into an open stream; libpng reports errors through longjmp. */
static int encode(FILE *stream, const uint8_t *pixels, int width, int height, int channels, size_t stride,
                  const im_png_options *options, png_failure *failure)
{
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, failure, on_png_error, on_png_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!info) {
        png_destroy_write_struct(&png, NULL);
        snprintf(failure->message, sizeof failure->message, "libpng allocation failed");
        return IM_ENOMEM;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return IM_EIO;
    }
    png_init_io(png, stream);
    png_set_compression_level(png, options ? options->compression : 6);
    png_set_IHDR(png, info, (png_uint_32)width, (png_uint_32)height, 8,
                 channels == 4 ? PNG_COLOR_TYPE_RGBA : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    set_metadata(png, info, options);
    png_write_info(png, info);
    for (int row = 0; row < height; ++row)
        png_write_row(png, (png_const_bytep)(pixels + (size_t)row * stride));
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    return IM_OK;
}

/* The text chunks' array and strings, when there are texts. */
static int check_texts(const im_png_options *options)
{
    if (!options || options->text_count <= 0)
        return IM_OK;
    if (!options->texts)
        return im_fail(IM_EINVAL, "im_png_write: options->texts is NULL: expected text_count = %d texts",
                       options->text_count);
    for (int i = 0; i < options->text_count; ++i)
        if (!options->texts[i].key || !options->texts[i].value)
            return im_fail(IM_EINVAL, "im_png_write: options->texts[%d] has a NULL key or value: expected text", i);
    return IM_OK;
}

int im_png_write(const char *path, const uint8_t *pixels, int width, int height, int channels, size_t stride,
                 const im_png_options *options)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(pixels, "pixels");
    int status = check_image(path, width, height, channels);
    if (status != IM_OK)
        return status;
    if (stride < (size_t)width * (size_t)channels)
        return im_fail(IM_EINVAL, "im_png_write: stride = %zu: expected at least width x channels = %d x %d", stride,
                       width, channels);
    status = check_texts(options);
    if (status != IM_OK)
        return status;
    im_atomic_file file;
    status = im_atomic_open(&file, path);
    if (status != IM_OK)
        return status;
    png_failure failure = {"", 0};
    status = encode(file.stream, pixels, width, height, channels, stride, options, &failure);
    if (status != IM_OK) {
        im_atomic_abort(&file);
        if (failure.saved_errno && strstr(failure.message, "Write Error"))
            return im_fail(status, "%s: write failed: %s", path, strerror(failure.saved_errno));
        return im_fail(status, "%s: PNG encoding failed: %s", path, failure.message);
    }
    return im_atomic_commit(&file);
}

static int decode(FILE *stream, const char *path, uint8_t **pixels, int *width, int *height, int *channels)
{
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    uint8_t *volatile buffer = NULL;
    if (!info) {
        png_destroy_read_struct(&png, NULL, NULL);
        return im_fail(IM_ENOMEM, "%s: libpng allocation failed", path);
    }
    if (setjmp(png_jmpbuf(png))) {
        free(buffer);
        png_destroy_read_struct(&png, &info, NULL);
        return im_fail(IM_EFORMAT, "%s: not a readable PNG", path);
    }
    png_init_io(png, stream);
    png_read_info(png, info);
    png_set_expand(png);
    png_set_strip_16(png);
    png_set_gray_to_rgb(png);
    png_read_update_info(png, info);
    int w = (int)png_get_image_width(png, info), h = (int)png_get_image_height(png, info);
    int c = png_get_channels(png, info);
    buffer = malloc((size_t)w * (size_t)h * (size_t)c);
    if (!buffer)
        png_error(png, "out of memory");
    for (int row = 0; row < h; ++row)
        png_read_row(png, buffer + (size_t)row * (size_t)w * (size_t)c, NULL);
    png_read_end(png, NULL);
    png_destroy_read_struct(&png, &info, NULL);
    *pixels = buffer;
    *width = w;
    *height = h;
    *channels = c;
    return IM_OK;
}

int im_png_read(const char *path, uint8_t **pixels, int *width, int *height, int *channels)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(pixels, "pixels");
    ARG_REQUIRE(width, "width");
    ARG_REQUIRE(height, "height");
    ARG_REQUIRE(channels, "channels");
    *pixels = NULL;
    FILE *stream = fopen(path, "rb");
    if (!stream)
        return im_fail(IM_EIO, "%s: cannot open: %s", path, strerror(errno));
    int status = decode(stream, path, pixels, width, height, channels);
    fclose(stream);
    return status;
}
