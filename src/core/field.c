#include "indentmap/field.h"

#include "core/args.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int im_field_create(int nx, int ny, double delta, im_field **out)
{
    ARG_REQUIRE(out, "out");
    *out = NULL;
    if (nx < 1 || ny < 1 || nx > IM_FIELD_MAX_SIDE || ny > IM_FIELD_MAX_SIDE)
        return im_fail(IM_EINVAL, "grid %d x %d: expected each side in [1, %d]", nx, ny, IM_FIELD_MAX_SIDE);
    if (!(delta > 0.0) || !isfinite(delta))
        return im_fail(IM_EINVAL, "grid spacing delta = %g: expected a finite value > 0", delta);
    char what[64];
    snprintf(what, sizeof what, "field %d x %d", nx, ny);
    double bytes = (double)nx * (double)ny * sizeof(double);
    int status = im_memory_check(bytes, what);
    if (status != IM_OK)
        return status;
    im_field *field = calloc(1, sizeof *field);
    double *data = calloc((size_t)nx * (size_t)ny, sizeof *data);
    if (!field || !data) {
        free(field);
        free(data);
        return im_fail(IM_ENOMEM, "%s: allocation of %.0f bytes failed", what, bytes);
    }
    field->nx = nx;
    field->ny = ny;
    field->delta = delta;
    field->data = data;
    *out = field;
    return IM_OK;
}

int im_field_clone(const im_field *src, im_field **out)
{
    ARG_VIEW(src, "src");
    ARG_REQUIRE(out, "out");
    int status = im_field_create(src->nx, src->ny, src->delta, out);
    if (status != IM_OK)
        return status;
    memcpy((*out)->unit, src->unit, sizeof src->unit);
    memcpy((*out)->value_unit, src->value_unit, sizeof src->value_unit);
    memcpy((*out)->data, src->data, im_field_count(src) * sizeof *src->data);
    return IM_OK;
}

void im_field_free(im_field *field)
{
    if (!field)
        return;
    free(field->data);
    free(field);
}

int im_field_check_finite(const im_field *field, const char *what)
{
    char context[160];
    snprintf(context, sizeof context, "im_field_check_finite: %s", what ? what : "field");
    int status = im_field_check_view(field, context);
    if (status != IM_OK)
        return status;
    size_t count = im_field_count(field);
    for (size_t i = 0; i < count; ++i) {
        if (!isfinite(field->data[i]))
            return im_fail(IM_ENUMERIC, "%s: value %g at (x=%zu, y=%zu): expected finite numbers", what,
                           field->data[i], i % (size_t)field->nx, i / (size_t)field->nx);
    }
    return IM_OK;
}

int im_field_check_view(const im_field *field, const char *what)
{
    if (!what)
        what = "im_field_check_view: field";
    if (!field)
        return im_fail(IM_EINVAL, "%s is NULL: expected a field", what);
    if (field->nx < 1 || field->ny < 1 || field->nx > IM_FIELD_MAX_SIDE || field->ny > IM_FIELD_MAX_SIDE)
        return im_fail(IM_EINVAL, "%s is %d x %d: expected each side in [1, %d]", what, field->nx, field->ny,
                       IM_FIELD_MAX_SIDE);
    if (!field->data)
        return im_fail(IM_EINVAL, "%s data is NULL: expected %d x %d values", what, field->nx, field->ny);
    return IM_OK;
}

int arg_null(const char *function, const char *argument)
{
    return im_fail(IM_EINVAL, "%s: %s is NULL: expected a pointer", function, argument);
}

int arg_sides(const char *function, int nx, int ny)
{
    if (nx < 1 || ny < 1 || nx > IM_FIELD_MAX_SIDE || ny > IM_FIELD_MAX_SIDE)
        return im_fail(IM_EINVAL, "%s: nx x ny = %d x %d: expected each side in [1, %d]", function, nx, ny,
                       IM_FIELD_MAX_SIDE);
    return IM_OK;
}

int arg_view(const char *function, const char *argument, const im_field *field)
{
    char what[160];
    snprintf(what, sizeof what, "%s: %s", function, argument);
    return im_field_check_view(field, what);
}
