/* The JSON records' one writer (json_file.h). */
#include "io/json_file.h"

#include "indentmap/io.h"
#include "indentmap/status.h"

#include <stdlib.h>
#include <string.h>

int json_file_write(const char *path, const json_t *root)
{
    char *text = root ? json_dumps(root, JSON_INDENT(2) | JSON_REAL_PRECISION(17)) : NULL;
    if (!text)
        return im_fail(IM_ENOMEM, "%s: cannot build the JSON record", path);
    size_t length = strlen(text);
    text[length] = '\n'; /* json_dumps leaves room: its terminator becomes the newline */
    int status = im_write_file_atomic(path, text, length + 1);
    free(text);
    return status;
}
