/* Checked path building: a path that does not fit its buffer is an error naming it, never a
 * silently truncated path (which could name another file). */
#include "indentmap/io.h"
#include "core/args.h"
#include "indentmap/status.h"

#include <stdio.h>
#include <string.h>

enum { SHOWN = 60 }; /* characters of a long path's head and tail in a message */

/* The last SHOWN characters of a, separator and b joined, into tail (SHOWN + 1 bytes). */
static void joined_tail(const char *a, const char *separator, const char *b, char *tail)
{
    const char *parts[3] = {a, separator, b};
    size_t filled = 0;
    tail[SHOWN] = '\0';
    for (int i = 2; i >= 0 && filled < SHOWN; --i) {
        size_t length = strlen(parts[i]), take = length < SHOWN - filled ? length : SHOWN - filled;
        memcpy(tail + SHOWN - filled - take, parts[i] + length - take, take);
        filled += take;
    }
    memmove(tail, tail + SHOWN - filled, filled + 1);
}

/* Writes a, separator and b into out; IM_EINVAL when they do not fit, naming the path by its head
 * and its tail (a long path would fill the message and hide what was wrong). */
static int join_checked(char *out, size_t size, const char *a, const char *separator, const char *b)
{
    int length = snprintf(out, size, "%s%s%s", a, separator, b);
    if (length >= 0 && (size_t)length < size)
        return IM_OK;
    if (size > 0)
        out[0] = '\0'; /* no truncated path is left for a caller to use by mistake */
    char tail[SHOWN + 1];
    joined_tail(a, separator, b, tail);
    return im_fail(IM_EINVAL, "path too long: %d bytes where at most %zu fit: '%.*s...%s'", length,
                   size > 0 ? size - 1 : 0, (int)SHOWN, a, tail);
}

int im_path_join(char *out, size_t size, const char *dir, const char *name)
{
    ARG_REQUIRE(out, "out");
    ARG_REQUIRE(dir, "dir");
    ARG_REQUIRE(name, "name");
    return join_checked(out, size, dir, "/", name);
}

int im_path_suffix(char *out, size_t size, const char *path, const char *suffix)
{
    ARG_REQUIRE(out, "out");
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(suffix, "suffix");
    return join_checked(out, size, path, "", suffix);
}
