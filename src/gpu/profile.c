/* The GPU profile (profile.h): timestamp queries around the recorded passes, summed per label. */
#include "gpu/profile.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_MARKS = 2048, MAX_LABELS = 96 };

typedef struct label_total {
    char label[48]; /* a copy: an FFT's label goes with its plan, before the report */
    long passes;
    double seconds;
} label_total;

struct gpu_profile {
    VkDevice device;
    VkQueryPool pool;
    double seconds_per_tick;
    uint64_t valid_mask;
    const char *labels[MAX_MARKS]; /* labels[k]: the pass that ends at mark k (mark 0: the start) */
    uint32_t marks;
    uint64_t ticks[MAX_MARKS];
    long untimed; /* passes past MAX_MARKS in one submission */
    label_total totals[MAX_LABELS];
    int label_count;
    label_total host[4]; /* host work, not part of the device's span */
    int host_count;
    long submissions;
    double host_seconds, device_seconds;
};

static int profiling_asked(void)
{
    const char *value = getenv("INDENTMAP_GPU_PROFILE");
    return value && *value && strcmp(value, "0") != 0;
}

gpu_profile *gpu_profile_open(VkDevice device, VkPhysicalDevice physical, uint32_t queue_family)
{
    if (!profiling_asked())
        return NULL;
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(physical, &properties);
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, NULL);
    VkQueueFamilyProperties families[32];
    count = count > 32 ? 32 : count;
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, families);
    const uint32_t bits = queue_family < count ? families[queue_family].timestampValidBits : 0;
    if (bits == 0) {
        fprintf(stderr, "indentmap: GPU profile: the queue writes no timestamps; not profiling\n");
        return NULL;
    }
    gpu_profile *p = calloc(1, sizeof *p);
    VkQueryPoolCreateInfo info = {.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
                                  .queryType = VK_QUERY_TYPE_TIMESTAMP,
                                  .queryCount = MAX_MARKS};
    if (!p || vkCreateQueryPool(device, &info, NULL, &p->pool) != VK_SUCCESS) {
        free(p);
        return NULL;
    }
    p->device = device;
    p->seconds_per_tick = properties.limits.timestampPeriod * 1e-9;
    p->valid_mask = bits >= 64 ? UINT64_MAX : ((uint64_t)1 << bits) - 1;
    return p;
}

void gpu_profile_begin(gpu_profile *p, VkCommandBuffer commands)
{
    if (!p)
        return;
    vkCmdResetQueryPool(commands, p->pool, 0, MAX_MARKS);
    vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, p->pool, 0);
    p->labels[0] = NULL;
    p->marks = 1;
}

void gpu_profile_mark(gpu_profile *p, VkCommandBuffer commands, const char *label)
{
    if (!p || p->marks == 0)
        return;
    if (p->marks == MAX_MARKS) {
        ++p->untimed;
        return;
    }
    vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, p->pool, p->marks);
    p->labels[p->marks++] = label;
}

static label_total *total_of(gpu_profile *p, const char *label)
{
    for (int k = 0; k < p->label_count; ++k)
        if (strcmp(p->totals[k].label, label) == 0)
            return &p->totals[k];
    if (p->label_count == MAX_LABELS)
        return NULL;
    p->totals[p->label_count] = (label_total){.passes = 0};
    snprintf(p->totals[p->label_count].label, sizeof p->totals[p->label_count].label, "%s", label);
    return &p->totals[p->label_count++];
}

void gpu_profile_collect(gpu_profile *p, double host_seconds)
{
    if (!p || p->marks == 0)
        return;
    const uint64_t *ticks = p->ticks;
    const uint32_t marks = p->marks;
    p->marks = 0;
    ++p->submissions;
    p->host_seconds += host_seconds;
    if (marks < 2 || vkGetQueryPoolResults(p->device, p->pool, 0, marks, sizeof p->ticks, p->ticks, sizeof *ticks,
                                           VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT) != VK_SUCCESS)
        return;
    for (uint32_t k = 1; k < marks; ++k) {
        const double seconds = (double)((ticks[k] - ticks[k - 1]) & p->valid_mask) * p->seconds_per_tick;
        label_total *t = total_of(p, p->labels[k]);
        if (t) {
            ++t->passes;
            t->seconds += seconds;
        }
    }
    p->device_seconds += (double)((ticks[marks - 1] - ticks[0]) & p->valid_mask) * p->seconds_per_tick;
}

void gpu_profile_host(gpu_profile *p, const char *label, double seconds)
{
    if (!p)
        return;
    int k = 0;
    while (k < p->host_count && strcmp(p->host[k].label, label) != 0)
        ++k;
    if (k == p->host_count) {
        if (k == (int)(sizeof p->host / sizeof *p->host))
            return;
        snprintf(p->host[k].label, sizeof p->host[k].label, "%s", label);
        ++p->host_count;
    }
    ++p->host[k].passes;
    p->host[k].seconds += seconds;
}

static int by_time(const void *a, const void *b)
{
    const double x = ((const label_total *)a)->seconds, y = ((const label_total *)b)->seconds;
    return (x < y) - (x > y);
}

void gpu_profile_close(gpu_profile *p, const char *device_name, FILE *report)
{
    if (!p)
        return;
    qsort(p->totals, (size_t)p->label_count, sizeof *p->totals, by_time);
    fprintf(report,
            "GPU profile (%s): %ld submissions waited for %.4f s on the host; the device's marks span "
            "%.4f s (the rest, %.4f s, is submission and wait latency)%s\n",
            device_name, p->submissions, p->host_seconds, p->device_seconds, p->host_seconds - p->device_seconds,
            p->untimed ? " (some passes untimed: too many in one submission)" : "");
    fprintf(report, "  %-34s %9s %11s %7s %10s\n", "pass", "passes", "device ms", "share", "mean us");
    for (int k = 0; k < p->label_count; ++k) {
        const label_total *t = &p->totals[k];
        fprintf(report, "  %-34s %9ld %11.3f %6.1f%% %10.2f\n", t->label, t->passes, t->seconds * 1e3,
                p->device_seconds > 0 ? 100 * t->seconds / p->device_seconds : 0, t->seconds / t->passes * 1e6);
    }
    for (int k = 0; k < p->host_count; ++k)
        fprintf(report, "  host: %-28s %9ld %11.3f ms\n", p->host[k].label, p->host[k].passes,
                p->host[k].seconds * 1e3);
    vkDestroyQueryPool(p->device, p->pool, NULL);
    free(p);
}
