/* Checked path building: a path that does not fit its buffer is an error naming it, never a
 * silently truncated path (which could name another file). */
#include "indentmap/io.h"
#include "indentmap/status.h"

#include <stdio.h>

/* Writes a then b into out; IM_EINVAL naming what was being built when it does not fit. */
static int join_checked(char *out, size_t size, const char *a, const char *separator, const char *b)
{
    int length = snprintf(out, size, "%s%s%s", a, separator, b);
    if (length >= 0 && (size_t)length < size)
        return IM_OK;
    if (size > 0)
        out[0] = '\0'; /* no truncated path is left for a caller to use by mistake */
    return im_fail(IM_EINVAL, "path '%s%s%s' is %d bytes long: expected at most %zu", a, separator, b, length,
                   size > 0 ? size - 1 : 0);
}

int im_path_join(char *out, size_t size, const char *dir, const char *name)
{
    return join_checked(out, size, dir, "/", name);
}

int im_path_suffix(char *out, size_t size, const char *path, const char *suffix)
{
    return join_checked(out, size, path, "", suffix);
}
