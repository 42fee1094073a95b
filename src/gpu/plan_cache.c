/* VkFFT's compiled kernels kept for the process (see plan_cache.h): a list, newest first. */
#include "gpu/plan_cache.h"

#include <pthread.h>
#include <stdlib.h>
#include <string.h>

typedef struct entry {
    struct entry *older;
    void *key, *binary;
    size_t key_bytes, bytes;
} entry;

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static entry *newest;
static long found_count, kept_count;

static entry *find(const void *key, size_t key_bytes)
{
    for (entry *e = newest; e; e = e->older)
        if (e->key_bytes == key_bytes && memcmp(e->key, key, key_bytes) == 0)
            return e;
    return NULL;
}

void *gpu_plan_cache_copy(const void *key, size_t key_bytes)
{
    pthread_mutex_lock(&lock);
    const entry *e = find(key, key_bytes);
    void *copy = e ? malloc(e->bytes) : NULL;
    if (copy) {
        memcpy(copy, e->binary, e->bytes);
        ++found_count;
    }
    pthread_mutex_unlock(&lock);
    return copy;
}

static void drop(entry *e)
{
    free(e->key);
    free(e->binary);
    free(e);
}

/* Drops the oldest entries until the cache holds at most GPU_PLAN_CACHE_BYTES. */
static void trim(void)
{
    entry **link = &newest;
    size_t kept = 0;
    while (*link && kept + (*link)->bytes <= GPU_PLAN_CACHE_BYTES) {
        kept += (*link)->bytes;
        link = &(*link)->older;
    }
    while (*link) {
        entry *e = *link;
        *link = e->older;
        drop(e);
    }
}

void gpu_plan_cache_keep(const void *key, size_t key_bytes, void *binary, size_t bytes)
{
    entry *e = malloc(sizeof *e);
    void *key_copy = malloc(key_bytes);
    if (!e || !key_copy) { /* not kept: the next plan of this key is compiled again */
        free(e);
        free(key_copy);
        free(binary);
        return;
    }
    memcpy(key_copy, key, key_bytes);
    *e = (entry){.key = key_copy, .binary = binary, .key_bytes = key_bytes, .bytes = bytes};
    pthread_mutex_lock(&lock);
    if (find(key, key_bytes)) { /* another thread kept it meanwhile */
        pthread_mutex_unlock(&lock);
        free(key_copy);
        free(binary);
        free(e);
        return;
    }
    e->older = newest;
    newest = e;
    ++kept_count;
    trim();
    pthread_mutex_unlock(&lock);
}

void gpu_plan_cache_counts(long *found, long *kept)
{
    pthread_mutex_lock(&lock);
    *found = found_count;
    *kept = kept_count;
    pthread_mutex_unlock(&lock);
}
