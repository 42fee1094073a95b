/* Bounded reading: the open checks and the line reader every reader of the program shares (io.h). */
#include "indentmap/field.h"
#include "core/args.h"
#include "indentmap/io.h"
#include "indentmap/status.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* What a file that is neither regular nor a pipe is, for the message. */
static const char *kind_of(mode_t mode)
{
    if (S_ISDIR(mode))
        return "a directory";
    if (S_ISCHR(mode))
        return "a character device";
    if (S_ISBLK(mode))
        return "a block device";
    if (S_ISSOCK(mode))
        return "a socket";
    return S_ISFIFO(mode) ? "a pipe" : "not a regular file";
}

/* Waits, polling the stop flag, until a pipe has data or its writer has come and gone: a named pipe
 * no program writes to would otherwise hold the open (and the program) beyond SIGINT/SIGTERM. */
static int wait_for_pipe(int fd, const char *path)
{
    struct pollfd pipe_end = {.fd = fd, .events = POLLIN};
    for (;;) {
        int ready = poll(&pipe_end, 1, 100);
        if (ready > 0)
            return IM_OK;
        if (ready < 0 && errno != EINTR)
            return im_fail(IM_EIO, "%s: cannot wait for the pipe: %s", path, strerror(errno));
        if (im_stop_requested())
            return im_fail(IM_EINTERRUPTED,
                           "%s is a pipe no program has written to: waiting for one interrupted by "
                           "signal %d",
                           path, im_stop_requested());
    }
}

/* Opened without blocking (a FIFO with no writer, a terminal), its kind checked before anything is
 * read; then blocking again for the reads. */
static int open_checked(const char *path, enum im_read_source source, int *fd, struct stat *info)
{
    *fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (*fd < 0)
        return im_fail(IM_EIO, "%s: cannot open: %s", path, strerror(errno));
    int status = IM_OK;
    if (fstat(*fd, info) != 0)
        status = im_fail(IM_EIO, "%s: cannot examine: %s", path, strerror(errno));
    else if (!S_ISREG(info->st_mode) && !(source == IM_READ_OR_PIPE && S_ISFIFO(info->st_mode)))
        status = im_fail(IM_EINVAL, "%s is %s: expected a regular file%s", path, kind_of(info->st_mode),
                         source == IM_READ_OR_PIPE ? " or a pipe" : "");
    else if (S_ISFIFO(info->st_mode))
        status = wait_for_pipe(*fd, path);
    if (status == IM_OK && fcntl(*fd, F_SETFL, fcntl(*fd, F_GETFL) & ~O_NONBLOCK) != 0)
        status = im_fail(IM_EIO, "%s: cannot set blocking reads: %s", path, strerror(errno));
    if (status != IM_OK)
        close(*fd);
    return status;
}

int im_read_open(const char *path, const char *mode, enum im_read_source source, FILE **stream, long long *size)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(mode, "mode");
    ARG_REQUIRE(stream, "stream");
    *stream = NULL;
    int fd;
    struct stat info;
    int status = open_checked(path, source, &fd, &info);
    if (status != IM_OK)
        return status;
    FILE *opened = fdopen(fd, mode);
    if (!opened) {
        int error = errno;
        close(fd);
        return im_fail(IM_EIO, "%s: cannot open: %s", path, strerror(error));
    }
    if (size)
        *size = S_ISREG(info.st_mode) ? (long long)info.st_size : -1;
    *stream = opened;
    return IM_OK;
}

/* Grows line->text to hold at least `needed` bytes, within the memory check. */
static int grow_line(im_text_line *line, const char *path, size_t needed)
{
    size_t capacity = line->capacity ? line->capacity : 256;
    while (capacity < needed)
        capacity *= 2;
    char what[4200];
    snprintf(what, sizeof what, "%s:%ld: a line of %zu bytes", path, line->number, needed);
    int status = im_memory_check((double)capacity, what);
    if (status != IM_OK)
        return status;
    char *grown = realloc(line->text, capacity);
    if (!grown)
        return im_fail(IM_ENOMEM, "%s: allocation of %zu bytes failed", what, capacity);
    line->text = grown;
    line->capacity = capacity;
    return IM_OK;
}

enum { STOP_POLL_BYTES = 1 << 16 }; /* how often a long line polls for a stop request */

/* The bytes of one line up to its newline (not kept) or the end of the file. */
static int read_line_bytes(FILE *stream, const char *path, size_t max_length, im_text_line *line, int *got_any)
{
    int c;
    while ((c = getc_unlocked(stream)) != EOF) {
        *got_any = 1;
        if (c == '\n')
            return IM_OK;
        if (c == '\0')
            return im_fail(IM_EFORMAT, "%s:%ld: a NUL byte at column %zu: expected a text file", path, line->number,
                           line->length + 1);
        if (line->length >= max_length)
            return im_fail(IM_EFORMAT,
                           "%s:%ld: line longer than %zu bytes: expected a text file with lines "
                           "of at most that length",
                           path, line->number, max_length);
        if (line->length + 2 > line->capacity) {
            int status = grow_line(line, path, line->length + 2);
            if (status != IM_OK)
                return status;
        }
        line->text[line->length++] = (char)c;
        if (line->length % STOP_POLL_BYTES == 0 && im_stop_requested())
            return im_fail(IM_EINTERRUPTED, "%s:%ld: reading interrupted by signal %d", path, line->number,
                           im_stop_requested());
    }
    if (ferror(stream))
        return im_fail(IM_EIO, "%s:%ld: cannot read: %s", path, line->number, strerror(errno));
    return IM_OK;
}

int im_read_line(FILE *stream, const char *path, size_t max_length, im_text_line *line, int *end)
{
    ARG_REQUIRE(stream, "stream");
    ARG_REQUIRE(line, "line");
    ARG_REQUIRE(end, "end");
    *end = 0;
    if (im_stop_requested())
        return im_fail(IM_EINTERRUPTED, "%s:%ld: reading interrupted by signal %d", path, line->number + 1,
                       im_stop_requested());
    if (!line->text) {
        int status = grow_line(line, path, 256);
        if (status != IM_OK)
            return status;
    }
    ++line->number;
    line->length = 0;
    int got_any = 0;
    flockfile(stream);
    int status = read_line_bytes(stream, path, max_length, line, &got_any);
    funlockfile(stream);
    line->text[line->length] = '\0';
    if (status == IM_OK && !got_any) {
        --line->number;
        *end = 1;
    }
    return status;
}

int im_read_text_file(const char *path, size_t max_bytes, char **text, size_t *size)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(text, "text");
    *text = NULL;
    FILE *stream;
    long long length;
    int status = im_read_open(path, "rb", IM_READ_REGULAR, &stream, &length);
    if (status != IM_OK)
        return status;
    if ((unsigned long long)length > max_bytes) {
        fclose(stream);
        return im_fail(IM_EINVAL, "%s: %lld bytes, more than the %zu such a file may hold", path, length, max_bytes);
    }
    char what[4200];
    snprintf(what, sizeof what, "%s (%lld bytes)", path, length);
    status = im_memory_check((double)length + 1.0, what);
    char *buffer = status == IM_OK ? malloc((size_t)length + 1) : NULL;
    if (status == IM_OK && !buffer)
        status = im_fail(IM_ENOMEM, "%s: allocation failed", what);
    size_t got = buffer ? fread(buffer, 1, (size_t)length, stream) : 0;
    if (status == IM_OK && (got != (size_t)length || ferror(stream)))
        status = im_fail(IM_EIO, "%s: cannot read: %s", path, ferror(stream) ? strerror(errno) : "it shrank");
    fclose(stream);
    if (status == IM_OK && memchr(buffer, '\0', got))
        status = im_fail(IM_EFORMAT, "%s: a NUL byte at offset %zu: expected a text file", path,
                         (size_t)((char *)memchr(buffer, '\0', got) - buffer));
    if (status != IM_OK) {
        free(buffer);
        return status;
    }
    buffer[got] = '\0';
    *text = buffer;
    if (size)
        *size = got;
    return IM_OK;
}
