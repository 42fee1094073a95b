#include "formats/payload.h"

#include "indentmap/field.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdio.h>
#include <sys/stat.h>

static int check_payload_size(FILE *stream, const char *path, uint64_t expected, const char *claim)
{
    struct stat info;
    long position = ftell(stream);
    if (position < 0 || fstat(fileno(stream), &info) != 0 || !S_ISREG(info.st_mode))
        return IM_OK;
    uint64_t present = info.st_size > position ? (uint64_t)(info.st_size - position) : 0;
    if (present < expected)
        return im_fail(IM_EFORMAT,
                       "%s: truncated data: the header (%s) needs %llu bytes after it, "
                       "the file has %llu",
                       path, claim, (unsigned long long)expected, (unsigned long long)present);
    if (present > expected)
        return im_fail(IM_EFORMAT,
                       "%s: more data than the header (%s) holds: %llu bytes after it, "
                       "%llu expected",
                       path, claim, (unsigned long long)present, (unsigned long long)expected);
    return IM_OK;
}

int formats_check_grid(FILE *stream, const char *path, long nx, long ny, unsigned item_size, const char *claim)
{
    char what[4200];
    snprintf(what, sizeof what, "%s: field %ld x %ld", path, nx, ny);
    int status = im_memory_check((double)nx * (double)ny * sizeof(double), what);
    if (status != IM_OK)
        return status;
    if (nx > IM_FIELD_MAX_SIDE || ny > IM_FIELD_MAX_SIDE)
        return im_fail(IM_EFORMAT, "%s: %s: expected each side in [1, %d]", path, claim, IM_FIELD_MAX_SIDE);
    return check_payload_size(stream, path, (uint64_t)nx * (uint64_t)ny * item_size, claim);
}

int formats_check_finite(const im_field *field, const char *path)
{
    if (im_field_check_finite(field, path) == IM_OK)
        return IM_OK;
    char message[4400];
    snprintf(message, sizeof message, "%s", im_last_error());
    return im_fail(IM_EFORMAT, "%s (NaN and Inf are not heights)", message);
}

int formats_check_heights_or_missing_writable(const im_field *field, const char *path)
{
    int status = im_field_check_view(field, path);
    if (status != IM_OK)
        return status;
    size_t count = im_field_count(field);
    for (size_t i = 0; i < count; ++i)
        if (isinf(field->data[i]))
            return im_fail(IM_EINVAL,
                           "%s: value %g at (x=%zu, y=%zu); not written: expected finite heights or NaN "
                           "(a missing point)",
                           path, field->data[i], i % (size_t)field->nx, i / (size_t)field->nx);
    return IM_OK;
}
