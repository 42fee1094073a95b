/* gzip-compressed text, decompressed as it is read. */
#define _GNU_SOURCE /* fopencookie */
#include "formats/gzip_stream.h"

#include "indentmap/status.h"

#include <errno.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

static ssize_t read_decompressed(void *cookie, char *buffer, size_t size)
{
    int got = gzread((gzFile)cookie, buffer, size > (1u << 30) ? 1u << 30 : (unsigned)size);
    if (got < 0)
        errno = EIO; /* a damaged stream: the reader's next line fails with the error */
    return got;
}

static int close_decompressed(void *cookie) { return gzclose_r((gzFile)cookie) == Z_OK ? 0 : EOF; }

/* 1 when the regular file behind stream starts with 1f 8b; the stream is rewound. */
static int starts_gzip(FILE *stream)
{
    struct stat about;
    if (fstat(fileno(stream), &about) != 0 || !S_ISREG(about.st_mode))
        return 0;
    int first = fgetc(stream), second = fgetc(stream);
    rewind(stream);
    return first == 0x1f && second == 0x8b;
}

int formats_gunzip_if_compressed(FILE **stream, const char *path, int *compressed)
{
    *compressed = starts_gzip(*stream);
    if (!*compressed)
        return IM_OK;
    int fd = dup(fileno(*stream));
    fclose(*stream);
    *stream = NULL;
    gzFile gz = fd >= 0 ? gzdopen(fd, "rb") : NULL;
    if (!gz) {
        if (fd >= 0)
            close(fd);
        return im_fail(IM_ENOMEM, "%s: cannot start decompressing (gzip)", path);
    }
    *stream = fopencookie(gz, "r", (cookie_io_functions_t){.read = read_decompressed, .close = close_decompressed});
    if (*stream)
        return IM_OK;
    gzclose_r(gz);
    return im_fail(IM_ENOMEM, "%s: cannot open a stream over the decompressed text", path);
}
