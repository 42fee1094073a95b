/* Internal: the one writer of the JSON records (json_file.c): run.json of `indent` and of scenes
 * (src/front/record.c), a surface's sidecar (surface/sidecar.c) and a field's (npy_sidecar.c). */
#ifndef INDENTMAP_IO_JSON_FILE_H
#define INDENTMAP_IO_JSON_FILE_H

#include <jansson.h>

/* Writes root to path atomically: 2-space indentation, reals with 17 significant digits (they read
 * back exactly), a final newline. IM_ENOMEM when it cannot be formatted, else im_write_file_atomic's
 * status. root is not taken. */
int json_file_write(const char *path, const json_t *root);

#endif
