#include "indentmap/field.h"

#include "indentmap/status.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

int im_field_create(int nx, int ny, double delta, im_field **out)
{
    *out = NULL;
    if (nx < 1 || ny < 1 || nx > IM_FIELD_MAX_SIDE || ny > IM_FIELD_MAX_SIDE)
        return im_fail(IM_EINVAL, "grid %d x %d: expected each side in [1, %d]", nx, ny,
                       IM_FIELD_MAX_SIDE);
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
    size_t count = im_field_count(field);
    for (size_t i = 0; i < count; ++i) {
        if (!isfinite(field->data[i]))
            return im_fail(IM_ENUMERIC, "%s: value %g at (x=%zu, y=%zu): expected finite numbers",
                           what, field->data[i], i % (size_t)field->nx, i / (size_t)field->nx);
    }
    return IM_OK;
}

/* MemAvailable from /proc/meminfo in bytes; 0 if it cannot be read. */
static size_t meminfo_available(void)
{
    size_t available = 0;
    FILE *meminfo = fopen("/proc/meminfo", "r");
    if (!meminfo)
        return 0;
    char line[256];
    unsigned long long kib;
    while (fgets(line, sizeof line, meminfo)) {
        if (sscanf(line, "MemAvailable: %llu kB", &kib) == 1) {
            available = (size_t)kib * 1024u;
            break;
        }
    }
    fclose(meminfo);
    return available;
}

/* The cap set by IM_MEMORY_LIMIT_MIB in bytes: 0 when unset, -1 when it is not a number > 0. */
static double environment_limit(void)
{
    const char *text = getenv("IM_MEMORY_LIMIT_MIB");
    if (!text || !text[0])
        return 0.0;
    char *end;
    double mib = strtod(text, &end);
    if (end == text || *end != '\0' || !(mib > 0.0) || !isfinite(mib))
        return -1.0;
    return fmin(mib * 1048576.0, 0x1p63); /* far beyond any machine; converts to size_t exactly */
}

static size_t smaller_known(size_t available, size_t bound)
{
    return available == 0 || bound < available ? bound : available;
}

/* This process's virtual size in bytes (/proc/self/statm); 0 if it cannot be read. */
static size_t virtual_size(void)
{
    FILE *statm = fopen("/proc/self/statm", "r");
    unsigned long long pages = 0;
    int read = statm && fscanf(statm, "%llu", &pages) == 1;
    if (statm)
        fclose(statm);
    long page = sysconf(_SC_PAGESIZE);
    return read && page > 0 ? (size_t)pages * (size_t)page : 0;
}

/* What an address-space limit (ulimit -v) leaves: the limit less what this process already maps,
 * fields, plans and thread stacks included. */
static size_t address_space_left(size_t limit)
{
    size_t used = virtual_size();
    return used < limit ? limit - used : 1; /* 1, not 0: 0 would read as "unknown" */
}

size_t im_address_space_available(void)
{
    struct rlimit limit;
    if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY)
        return 0;
    return address_space_left((size_t)limit.rlim_cur);
}

size_t im_memory_available(void)
{
    size_t available = meminfo_available();
    struct rlimit limit;
    if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
        available = smaller_known(available, address_space_left((size_t)limit.rlim_cur));
    double cap = environment_limit();
    if (cap > 0.0)
        available = smaller_known(available, (size_t)cap);
    return available;
}

int im_memory_check(double bytes, const char *what)
{
    if (environment_limit() < 0.0)
        return im_fail(IM_EINVAL, "%s: IM_MEMORY_LIMIT_MIB = '%s': expected a number of MiB > 0", what,
                       getenv("IM_MEMORY_LIMIT_MIB"));
    /* Beyond SIZE_MAX no allocation can succeed, whatever the machine reports (or fails to). */
    if (!(bytes <= (double)SIZE_MAX))
        return im_fail(IM_ENOMEM, "%s needs about %.1f MiB, more than this machine can address (%.1f MiB)",
                       what, bytes / 1048576.0, (double)SIZE_MAX / 1048576.0);
    size_t available = im_memory_available();
    if (available != 0 && bytes > (double)available)
        return im_fail(IM_ENOMEM, "%s needs about %.1f MiB but only %.1f MiB are available",
                       what, bytes / 1048576.0, (double)available / 1048576.0);
    return IM_OK;
}
