/* UTF-16 text decoded to UTF-8 in memory, then read through a stream over the decoded bytes. */
#define _GNU_SOURCE /* fopencookie */
#include "formats/utf16_text.h"

#include "indentmap/field.h"
#include "indentmap/status.h"

#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>

typedef struct decoded_text {
    char *bytes;
    size_t length, at;
} decoded_text;

static ssize_t read_decoded(void *cookie, char *buffer, size_t size)
{
    decoded_text *text = cookie;
    size_t left = text->length - text->at, given = size < left ? size : left;
    memcpy(buffer, text->bytes + text->at, given);
    text->at += given;
    return (ssize_t)given;
}

static int close_decoded(void *cookie)
{
    decoded_text *text = cookie;
    free(text->bytes);
    free(text);
    return 0;
}

enum byte_order { NOT_UTF16, LITTLE_ENDIAN_16, BIG_ENDIAN_16 };

/* The byte order a regular file's byte-order mark states; the stream is rewound. */
static enum byte_order byte_order_mark(FILE *stream, long long *size)
{
    struct stat about;
    if (fstat(fileno(stream), &about) != 0 || !S_ISREG(about.st_mode))
        return NOT_UTF16;
    *size = (long long)about.st_size;
    int first = fgetc(stream), second = fgetc(stream);
    rewind(stream);
    return first == 0xff && second == 0xfe   ? LITTLE_ENDIAN_16
           : first == 0xfe && second == 0xff ? BIG_ENDIAN_16
                                             : NOT_UTF16;
}

static unsigned long code_unit(const unsigned char *at, enum byte_order order)
{
    return order == BIG_ENDIAN_16 ? (unsigned long)at[0] << 8 | at[1] : (unsigned long)at[1] << 8 | at[0];
}

/* Writes code point code as UTF-8 at out; returns the bytes written (1 to 4). */
static size_t put_utf8(unsigned long code, char *out)
{
    if (code < 0x80) {
        out[0] = (char)code;
        return 1;
    }
    size_t length = code < 0x800 ? 2 : code < 0x10000 ? 3 : 4;
    static const unsigned char LEAD[5] = {0, 0, 0xc0, 0xe0, 0xf0};
    for (size_t k = length - 1; k > 0; --k, code >>= 6)
        out[k] = (char)(0x80 | (code & 0x3f));
    out[0] = (char)(LEAD[length] | code);
    return length;
}

/* The code point at in[*k] (a surrogate pair taken whole: *k then moves past its first unit), or 0
 * after saying what is wrong there. */
static unsigned long next_code_point(const char *path, const unsigned char *in, size_t length, size_t *k,
                                     enum byte_order order)
{
    unsigned long unit = code_unit(in + *k, order);
    if (unit == 0) {
        im_fail(IM_EFORMAT, "%s: UTF-16 text: a NUL character (U+0000) at byte %zu: expected text", path, *k);
        return 0;
    }
    if (unit >= 0xdc00 && unit <= 0xdfff) {
        im_fail(IM_EFORMAT,
                "%s: UTF-16 text: a lone low surrogate 0x%04lX at byte %zu: expected it after a high "
                "surrogate (D800-DBFF)",
                path, unit, *k);
        return 0;
    }
    if (unit < 0xd800 || unit > 0xdbff)
        return unit;
    unsigned long low = *k + 3 < length ? code_unit(in + *k + 2, order) : 0;
    if (low < 0xdc00 || low > 0xdfff) {
        im_fail(IM_EFORMAT,
                "%s: UTF-16 text: a lone high surrogate 0x%04lX at byte %zu: expected a low surrogate "
                "(DC00-DFFF) after it",
                path, unit, *k);
        return 0;
    }
    *k += 2;
    return 0x10000 + ((unit - 0xd800) << 10) + (low - 0xdc00);
}

/* The UTF-8 spelling of length bytes of UTF-16 (the mark first) into text. */
static int decode(const char *path, const unsigned char *in, size_t length, enum byte_order order, decoded_text *text)
{
    if (length % 2)
        return im_fail(IM_EFORMAT, "%s: UTF-16 text of %zu bytes, an odd number: it ends inside a character", path,
                       length);
    text->bytes = malloc(length / 2 * 3 + 1); /* a unit gives at most 3 bytes, a pair of them 4 */
    if (!text->bytes)
        return im_fail(IM_ENOMEM, "%s: allocation of %zu bytes for its UTF-8 text failed", path, length / 2 * 3 + 1);
    for (size_t k = 2; k < length; k += 2) {
        unsigned long code = next_code_point(path, in, length, &k, order);
        if (!code)
            return IM_EFORMAT;
        text->length += put_utf8(code, text->bytes + text->length);
    }
    return IM_OK;
}

/* The whole file behind stream, decoded into text. */
static int read_and_decode(FILE *stream, const char *path, long long size, enum byte_order order, decoded_text *text)
{
    char what[4200];
    snprintf(what, sizeof what, "%s: UTF-16 text of %lld bytes and its UTF-8", path, size);
    int status = im_memory_check(2.5 * (double)size, what);
    if (status != IM_OK)
        return status;
    unsigned char *in = malloc(size > 0 ? (size_t)size : 1);
    if (!in)
        return im_fail(IM_ENOMEM, "%s: allocation of %lld bytes to read it failed", path, size);
    size_t got = fread(in, 1, (size_t)size, stream);
    status = got == (size_t)size ? decode(path, in, got, order, text)
                                 : im_fail(IM_EIO, "%s: read %zu of its %lld bytes", path, got, size);
    free(in);
    return status;
}

int formats_utf16_decode_if_marked(FILE **stream, const char *path, const char **encoding)
{
    long long size = 0;
    enum byte_order order = byte_order_mark(*stream, &size);
    *encoding = order == LITTLE_ENDIAN_16 ? "UTF-16LE" : order == BIG_ENDIAN_16 ? "UTF-16BE" : NULL;
    if (order == NOT_UTF16)
        return IM_OK;
    decoded_text *text = calloc(1, sizeof *text);
    int status = text ? read_and_decode(*stream, path, size, order, text)
                      : im_fail(IM_ENOMEM, "%s: allocation failed", path);
    fclose(*stream);
    *stream = status == IM_OK
                  ? fopencookie(text, "r", (cookie_io_functions_t){.read = read_decoded, .close = close_decoded})
                  : NULL;
    if (status == IM_OK && !*stream)
        status = im_fail(IM_ENOMEM, "%s: cannot open a stream over its decoded text", path);
    if (!*stream && text)
        close_decoded(text);
    return status;
}
