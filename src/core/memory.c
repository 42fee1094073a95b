/* The memory probe: what the machine, the address-space limit and the caller's cap leave for the
 * next allocation, checked before every large one (field.h: im_memory_check). */
#include "core/memory.h"
#include "core/args.h"

#include "indentmap/field.h"
#include "indentmap/status.h"

#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <sys/resource.h>
#include <unistd.h>

/* The caller's cap in bytes (im_memory_set_limit), 0 for none. */
static _Atomic size_t memory_limit;

void im_memory_set_limit(size_t bytes) { atomic_store(&memory_limit, bytes); }

size_t im_memory_limit(void) { return atomic_load(&memory_limit); }

size_t memory_meminfo_available(void)
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

static size_t smaller_known(size_t available, size_t bound)
{
    return available == 0 || bound < available ? bound : available;
}

size_t memory_virtual_size(void)
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
    size_t used = memory_virtual_size();
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
    size_t available = memory_meminfo_available();
    struct rlimit limit;
    if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
        available = smaller_known(available, address_space_left((size_t)limit.rlim_cur));
    size_t cap = im_memory_limit();
    if (cap > 0)
        available = smaller_known(available, cap);
    return available;
}

int im_memory_check(double bytes, const char *what)
{
    ARG_REQUIRE(what, "what");
    /* Beyond SIZE_MAX no allocation can succeed, whatever the machine reports (or fails to). */
    if (!(bytes <= (double)SIZE_MAX))
        return im_fail(IM_ENOMEM, "%s needs about %.1f MiB, more than this machine can address (%.1f MiB)", what,
                       bytes / 1048576.0, (double)SIZE_MAX / 1048576.0);
    size_t available = im_memory_available();
    if (available != 0 && bytes > (double)available)
        return im_fail(IM_ENOMEM, "%s needs about %.1f MiB but only %.1f MiB are available", what, bytes / 1048576.0,
                       (double)available / 1048576.0);
    return IM_OK;
}
