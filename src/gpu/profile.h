/* Internal: where a GPU solve's device time goes (INDENTMAP_GPU_PROFILE=1; docs/solver.md).
 *
 * A context that profiles writes a timestamp at the start of each recording and one after each
 * recorded pass (a dispatch, an FFT, a copy), each pass followed by its barrier, so the time
 * between two marks is that pass's, waiting for the one before included. After each submission
 * the times are added up per label (the pass's name), and the submission's host wall time beside
 * the device's span gives what the round trips cost. The totals go to stderr when the context
 * closes. Not a test aid: a measurement for bench_gpu and for users who want to see the split. */
#ifndef INDENTMAP_GPU_PROFILE_H
#define INDENTMAP_GPU_PROFILE_H

#include <stdio.h>
#include <vulkan/vulkan.h>

typedef struct gpu_profile gpu_profile;

/* A profile when INDENTMAP_GPU_PROFILE is set to a non-zero value and the queue family writes
 * timestamps; NULL otherwise (and after a failure: profiling is never fatal). */
gpu_profile *gpu_profile_open(VkDevice device, VkPhysicalDevice physical, uint32_t queue_family);
/* At the start of a recording: resets the marks and writes the first timestamp. */
void gpu_profile_begin(gpu_profile *profile, VkCommandBuffer commands);
/* After a pass and its barrier: its end, under label (a string that lives until the submission's
 * gpu_profile_collect). */
void gpu_profile_mark(gpu_profile *profile, VkCommandBuffer commands, const char *label);
/* After the submission's fence: adds the marks' times to their labels; host_seconds is the wall
 * time from submitting to the fence. */
void gpu_profile_collect(gpu_profile *profile, double host_seconds);
/* Host work beside the device's (a copy into or out of staging memory): seconds under label. */
void gpu_profile_host(gpu_profile *profile, const char *label, double seconds);
/* Writes the totals (per label: passes, device ms, share) to report and frees the profile. */
void gpu_profile_close(gpu_profile *profile, const char *device_name, FILE *report);

#endif
