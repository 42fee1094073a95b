/* The JSON sidecar PATH.json of a .npy file: the units the .npy format cannot state. */
#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "core/args.h"

#include "indentmap/status.h"
#include "io/json_file.h"
#include "formats/readers.h"

#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int im_field_sidecar_write(const char *path, const im_field *field, const char *quantity)
{
    ARG_REQUIRE(path, "path");
    ARG_VIEW(field, "field");
    char sidecar[4096];
    int status = im_path_suffix(sidecar, sizeof sidecar, path, ".json");
    if (status != IM_OK)
        return status;
    json_t *root = json_pack("{s:s, s:s, s:s, s:i, s:i, s:f, s:s, s:s}", "program", "indentmap", "version",
                             IM_VERSION, "quantity", quantity, "nx", field->nx, "ny", field->ny, "delta",
                             field->delta, "unit", field->unit, "value_unit", field->value_unit);
    status = json_file_write(sidecar, root);
    json_decref(root);
    return status;
}

/* A string member of at most size - 1 bytes, or absent; -1 for another type or a longer string. */
static int copy_string(json_t *root, const char *key, char *out, size_t size)
{
    json_t *value = json_object_get(root, key);
    if (!value)
        return 0;
    if (!json_is_string(value) || json_string_length(value) >= size)
        return -1;
    memcpy(out, json_string_value(value), json_string_length(value) + 1);
    return 0;
}

/* "order": "yx" (rows are y) or "xy" (the first index is x); absent (""): left as it is. -1 otherwise. */
static int parse_order(const char *order, enum im_npy_order *out)
{
    if (order[0])
        *out = strcmp(order, "xy") == 0 ? IM_NPY_ORDER_XY : strcmp(order, "yx") == 0 ? IM_NPY_ORDER_YX : 0;
    return *out == IM_NPY_ORDER_SIDECAR ? -1 : 0;
}

int npy_sidecar_read(const char *path, surface_stated *stated, char *value_unit, size_t size)
{
    char sidecar[4096];
    int joined = im_path_suffix(sidecar, sizeof sidecar, path, ".json");
    if (joined != IM_OK)
        return joined;
    struct stat info;
    if (stat(sidecar, &info) != 0)
        return IM_OK; /* none: the .npy states no units */
    if (!S_ISREG(info.st_mode) || info.st_size > (1 << 20))
        return im_fail(IM_EFORMAT, "%s: the sidecar stating the units of %s is not a regular file of at most 1 MiB",
                       sidecar, path);
    json_error_t error;
    json_t *root = json_file_load(sidecar, 0, &error);
    if (!json_is_object(root)) {
        json_decref(root);
        return im_fail(IM_EFORMAT,
                       "%s:%d: the sidecar stating the units of %s is not a JSON object (%s); fix or "
                       "remove it",
                       sidecar, error.line, path, error.text);
    }
    json_t *delta = json_object_get(root, "delta");
    int bad = delta && !(json_is_number(delta) && json_number_value(delta) > 0.0);
    if (!bad && delta)
        stated->units.delta_x = stated->units.delta_y = json_number_value(delta);
    char order[4] = "";
    bad = bad || copy_string(root, "unit", stated->units.lateral, sizeof stated->units.lateral) != 0 ||
          copy_string(root, "value_unit", value_unit, size) != 0 ||
          copy_string(root, "order", order, sizeof order) != 0 || parse_order(order, &stated->npy_order) != 0;
    json_decref(root);
    if (bad)
        return im_fail(IM_EFORMAT,
                       "%s: expected \"delta\" a number > 0, \"unit\" and \"value_unit\" short strings, "
                       "\"order\" \"yx\" or \"xy\"",
                       sidecar);
    stated->spacing_keys = "the sidecar's delta";
    stated->lateral_key = "the sidecar's unit";
    return IM_OK;
}
