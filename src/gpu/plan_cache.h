/* Internal: VkFFT's compiled kernels kept for the life of the process (fft.c).
 *
 * VkFFT compiles every kernel of a plan with glslang when the plan is made (0.06-0.9 s a plan on
 * lavapipe's host, most of a small solve's time; a test program or an ensemble makes many plans of
 * the same sizes). VkFFT can save a plan's SPIR-V (saveApplicationToString) and make a plan from it
 * again without glslang (loadApplicationFromString): this cache keeps those binaries, keyed by
 * everything the kernels depend on (fft.c's plan_key: the device and the configuration), oldest
 * dropped first beyond GPU_PLAN_CACHE_BYTES. Threads: every function locks the cache. */
#ifndef INDENTMAP_GPU_PLAN_CACHE_H
#define INDENTMAP_GPU_PLAN_CACHE_H

#include <stddef.h>

enum { GPU_PLAN_CACHE_BYTES = 32 << 20 };

/* A copy (malloc'd, the caller frees it) of the binary kept under key; NULL when none is kept (or
 * the copy's memory could not be had: the plan is then compiled). */
void *gpu_plan_cache_copy(const void *key, size_t key_bytes);
/* Keeps binary (malloc'd; the cache takes it over and frees it when dropped) under key. */
void gpu_plan_cache_keep(const void *key, size_t key_bytes, void *binary, size_t bytes);
/* Since the process started: plans found in the cache, binaries kept. */
void gpu_plan_cache_counts(long *found, long *kept);

#endif
