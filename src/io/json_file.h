/* Internal: the one writer and reader of the JSON records (json_file.c): run.json of `indent` and of
 * scenes (src/front/record.c), a surface's sidecar (surface/sidecar.c) and a field's (npy_sidecar.c),
 * read also by the program (cli/) and the run page (viewer/page.c).
 *
 * Unsigned 64-bit integers (seeds): jansson's integers are signed 64-bit, so a value of 2^63 or more has
 * no integer of its own. json_unsigned makes one that json_text and json_file_write write as its decimal
 * (in memory a string, the marker UNSIGNED_MARKER before the digits); json_text_load and json_file_load
 * read an integer beyond the signed range the same way (a marked string of its digits, whatever its size
 * or sign); json_unsigned_value reads either back, and a negative integer as its two's complement, as
 * earlier builds wrote a seed of 2^63 or more. */
#ifndef INDENTMAP_IO_JSON_FILE_H
#define INDENTMAP_IO_JSON_FILE_H

#include <jansson.h>
#include <stdint.h>

/* Writes root to path atomically: 2-space indentation, reals with 17 significant digits (they read
 * back exactly), unsigned integers as their decimal, a final newline. IM_ENOMEM when it cannot be
 * formatted, else im_write_file_atomic's status. root is not taken. */
int json_file_write(const char *path, const json_t *root);

/* json_dumps(root, flags) with json_unsigned's values written as their decimal; NULL when it cannot be
 * formatted. free() it. */
char *json_text(const json_t *root, size_t flags);

/* value as a JSON value: an integer up to INT64_MAX, else the marked string json_text writes as digits. */
json_t *json_unsigned(uint64_t value);

/* The unsigned integer value holds into *out: an integer >= 0, a negative integer's two's complement (an
 * older file's seed of 2^63 or more), or a marked decimal up to 2^64 - 1. -1 (out unchanged) for any
 * other value: another type, an integer below -2^63 or above 2^64 - 1. */
int json_unsigned_value(const json_t *value, uint64_t *out);

/* json_loads and json_load_file (the same flags and error) that read an integer beyond jansson's signed
 * range as json_unsigned's marked string of its digits instead of failing. */
json_t *json_text_load(const char *text, size_t flags, json_error_t *error);
json_t *json_file_load(const char *path, size_t flags, json_error_t *error);

#endif
