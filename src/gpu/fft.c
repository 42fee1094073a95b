/* 2-D double-precision R2C / C2R transforms with VkFFT (vulkan.h). The only file that includes
 * VkFFT: its 1.6 MB header compiles here once (15-20 s), without sanitizers (CMakeLists.txt), from
 * the copy cmake/patch_vkfft.cmake makes of Debian's header. */
#include "gpu/vulkan.h"

#include "gpu/plan_cache.h"

#include "indentmap/status.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* VkFFT's own code is not held to the project's warnings. */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wunused-variable"
#pragma GCC diagnostic ignored "-Wunused-but-set-variable"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wformat-truncation"
#pragma GCC diagnostic ignored "-Wformat-overflow"
#pragma GCC diagnostic ignored "-Wstringop-truncation"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wdangling-pointer" /* a local barrier, used only during VkFFTAppend */
#include "vkfft/vkFFT.h"
#pragma GCC diagnostic pop

struct gpu_fft {
    VkFFTApplication app;
    /* VkFFT keeps these pointers (configuration and launches), so they live with the plan. */
    gpu_handles handles;
    VkBuffer real[GPU_MAX_CHUNKS], modes[GPU_MAX_CHUNKS], scratch[GPU_MAX_CHUNKS];
    uint64_t real_bytes[GPU_MAX_CHUNKS], modes_bytes[GPU_MAX_CHUNKS], scratch_bytes[GPU_MAX_CHUNKS];
    uint32_t real_parts, modes_parts, scratch_parts; /* scratch_parts 0: VkFFT allocates its own */
    VkCommandBuffer commands;
    int px, py;
    char labels[2][40]; /* a profile's names of the forward and the inverse transform */
};

VkDeviceSize gpu_fft_modes_bytes(int px, int py) { return (VkDeviceSize)(px / 2 + 1) * py * 2 * sizeof(double); }

int gpu_fft_side_supported(int side)
{
    if (side < 1)
        return 0;
    static const int radices[] = {2, 3, 5, 7, 11, 13};
    for (int k = 0; k < 6; ++k)
        while (side % radices[k] == 0)
            side /= radices[k];
    return side == 1;
}

/* The smallest prime factor of side above 13 (side is not supported). */
static int large_factor(int side)
{
    for (int f = 17; f <= side; f += 2)
        if (side % f == 0)
            return f;
    return side;
}

static int check_sizes(const gpu_context *context, int px, int py, const gpu_buffer *real, const gpu_buffer *modes,
                       const gpu_buffer *scratch)
{
    if (px < 2 || py < 2)
        return im_fail(IM_EINVAL, "GPU FFT %d x %d: expected at least 2 x 2", px, py);
    int sides[2] = {px, py};
    for (int k = 0; k < 2; ++k)
        if (!gpu_fft_side_supported(sides[k]))
            return im_fail(IM_EUNSUPPORTED,
                           "GPU FFT %d x %d: side %d has a prime factor above 13 (%d); VkFFT's exact radices are 2, "
                           "3, "
                           "5, 7, 11 and 13",
                           px, py, sides[k], large_factor(sides[k]));
    /* VkFFT 1.2.26 binds the real buffer, as the inverse's output, with the modes' size as its
     * descriptor range (validation: VUID-VkDescriptorBufferInfo-range-00342), so the real buffer
     * must be as large as the modes buffer; it reads and writes only the first px * py reals. */
    VkDeviceSize modes_bytes = gpu_fft_modes_bytes(px, py);
    const VkDeviceSize scratch_bytes = scratch ? scratch->bytes : modes_bytes;
    if (real->bytes < modes_bytes || modes->bytes < modes_bytes || scratch_bytes < modes_bytes)
        return im_fail(IM_EINVAL,
                       "GPU FFT %d x %d: buffers of %llu (reals), %llu (modes) and %llu (scratch) bytes: expected "
                       "at least %llu each",
                       px, py, (unsigned long long)real->bytes, (unsigned long long)modes->bytes,
                       (unsigned long long)scratch_bytes, (unsigned long long)modes_bytes);
    /* VkFFT's multi-buffer shaders index their blocks by non-uniform indices without marking them so */
    if (modes_bytes > gpu_context_part_bytes(context) && !gpu_context_nonuniform_buffers(context))
        return im_fail(IM_EUNSUPPORTED,
                       "GPU FFT %d x %d: its %.1f MiB buffers exceed one storage buffer, and %s does not index "
                       "arrays of storage buffers non-uniformly natively (VkFFT's multi-buffer mode needs it)",
                       px, py, (double)modes_bytes / 1048576.0, gpu_context_device_name(context));
    return IM_OK;
}

/* An out-of-place R2C plan: reals (row stride px) in the input buffer, px/2 + 1 complex modes per
 * row in the main buffer; the inverse writes back to the input buffer and overwrites the modes.
 * The padded grid's zero block is transformed like any data: VkFFT 1.2.26's spatial zero padding
 * (performZeropadding), tried to skip it as the CPU engine's pruned transforms do, passed every
 * comparison up to 2048^2 transforms but broke the 8192^2 one on an H200 (a 4096^2 cone solve
 * stopped at residual 25.7 after 10000 iterations; docs/benchmarks.md, "GPU engine"). */
static VkFFTConfiguration configuration(gpu_fft *fft)
{
    VkFFTConfiguration c = {0};
    c.FFTdim = 2;
    c.size[0] = (uint64_t)fft->px;
    c.size[1] = (uint64_t)fft->py;
    c.doublePrecision = 1;
    c.performR2C = 1;
    c.normalize = 0;
    c.physicalDevice = fft->handles.physical_device;
    c.device = fft->handles.device;
    c.queue = fft->handles.queue;
    c.commandPool = fft->handles.pool;
    c.fence = fft->handles.fence;
    c.isInputFormatted = 1;
    c.inverseReturnToInputBuffer = 1;
    c.inputBufferNum = fft->real_parts;
    c.inputBuffer = fft->real;
    c.inputBufferSize = fft->real_bytes;
    c.inputBufferStride[0] = (uint64_t)fft->px; /* in reals */
    c.inputBufferStride[1] = (uint64_t)fft->px * (uint64_t)fft->py;
    c.bufferNum = fft->modes_parts;
    c.buffer = fft->modes;
    c.bufferSize = fft->modes_bytes;
    c.bufferStride[0] = (uint64_t)(fft->px / 2 + 1); /* in complex numbers */
    c.bufferStride[1] = (uint64_t)(fft->px / 2 + 1) * (uint64_t)fft->py;
    if (fft->scratch_parts) { /* the four-step algorithm's reordering, when an axis takes several uploads */
        c.userTempBuffer = 1;
        c.tempBufferNum = fft->scratch_parts;
        c.tempBuffer = fft->scratch;
        c.tempBufferSize = fft->scratch_bytes;
    }
    return c;
}

/* A buffer as VkFFT takes it: the bytes used in one part when the modes' extent fits one, or
 * (VkFFT's multi-buffer mode) the equal parts that hold that extent, which VkFFT binds as blocks of
 * the smallest one's size. A larger buffer (a coarse cascade level's, which is its finest level's)
 * is handed over only as far as the transform reaches. */
static void hand_over(const gpu_buffer *buffer, uint64_t extent, uint64_t used, VkBuffer *buffers, uint64_t *sizes,
                      uint32_t *count)
{
    *count = extent <= buffer->part_bytes ? 1 : (uint32_t)((extent + buffer->part_bytes - 1) / buffer->part_bytes);
    for (uint32_t k = 0; k < *count; ++k) {
        buffers[k] = buffer->part[k];
        sizes[k] = *count == 1 ? used : buffer->part_bytes;
    }
}

/* Buffers in parts only where VkFFT 1.2.26's multi-buffer mode was seen right. Its kernels that read
 * or write the reals as reals (the R2C axis in one upload) index the blocks of the real buffer by the
 * complex block size, half the reals a block holds: on an H200 a 256^2 transform in 5 parts was
 * wrong (1.3e3 of the largest mode) with cmake/patch_vkfft.cmake's edit (d) and without. When the
 * first axis takes several uploads (GPU_PARTS_FIRST_AXIS and longer in double) VkFFT reads the reals as
 * complex pairs, and with edit (d) a 16384^2 periodic solve (modes in 2 parts) converged on the H200. */
static int check_parts_path(const gpu_fft *fft)
{
    const int in_parts = fft->real_parts > 1 || fft->modes_parts > 1;
    const VkFFTPlan *plans[2] = {fft->app.localFFTPlan, fft->app.localFFTPlan_inverse};
    for (int k = 0; k < 2 && in_parts; ++k)
        if (plans[k] && plans[k]->numAxisUploads[0] < 2)
            return im_fail(IM_EUNSUPPORTED,
                           "GPU FFT %d x %d: its buffers exceed one storage buffer (%u parts) and its first axis "
                           "takes one upload: VkFFT 1.2.26's multi-buffer mode then addresses the reals wrongly "
                           "(docs/solver.md, \"Fields beyond one storage buffer\"); transforms in parts need a "
                           "first axis of several uploads (%d and longer in double)",
                           fft->px, fft->py, fft->modes_parts > fft->real_parts ? fft->modes_parts : fft->real_parts,
                           GPU_PARTS_FIRST_AXIS);
    return IM_OK;
}

/* What VkFFT's kernels depend on (plan_cache.h): the device, whose limits VkFFT sizes its
 * workgroups and shared memory by, and the configuration but for its handles. */
typedef struct plan_key {
    uint32_t vendor, device, driver;
    uint8_t pipeline_cache[VK_UUID_SIZE];
    int px, py;
    uint32_t real_parts, modes_parts, scratch_parts;
    uint64_t real_bytes[GPU_MAX_CHUNKS], modes_bytes[GPU_MAX_CHUNKS], scratch_bytes[GPU_MAX_CHUNKS];
} plan_key;

static plan_key key_of(const gpu_fft *fft)
{
    plan_key key;
    memset(&key, 0, sizeof key); /* padding too: keys compare as bytes */
    VkPhysicalDeviceProperties device;
    vkGetPhysicalDeviceProperties(*fft->handles.physical_device, &device);
    key.vendor = device.vendorID;
    key.device = device.deviceID;
    key.driver = device.driverVersion;
    memcpy(key.pipeline_cache, device.pipelineCacheUUID, VK_UUID_SIZE);
    key.px = fft->px;
    key.py = fft->py;
    key.real_parts = fft->real_parts;
    key.modes_parts = fft->modes_parts;
    key.scratch_parts = fft->scratch_parts;
    memcpy(key.real_bytes, fft->real_bytes, sizeof key.real_bytes);
    memcpy(key.modes_bytes, fft->modes_bytes, sizeof key.modes_bytes);
    memcpy(key.scratch_bytes, fft->scratch_bytes, sizeof key.scratch_bytes);
    return key;
}

/* initializeVkFFT from the kernels a plan of the same key compiled before, or compiling them
 * with glslang and keeping them for the next one. */
static VkFFTResult initialize(gpu_fft *fft)
{
    const plan_key key = key_of(fft);
    void *binary = gpu_plan_cache_copy(&key, sizeof key);
    VkFFTConfiguration c = configuration(fft);
    c.loadApplicationFromString = binary != NULL;
    c.loadApplicationString = binary;
    c.saveApplicationToString = binary == NULL;
    VkFFTResult result = initializeVkFFT(&fft->app, c);
    free(binary); /* VkFFT copied each kernel out of it */
    if (result == VKFFT_SUCCESS && c.saveApplicationToString) {
        /* the cache takes VkFFT's copy over (deleteVkFFT frees only what it still points to) */
        gpu_plan_cache_keep(&key, sizeof key, fft->app.saveApplicationString, fft->app.applicationStringSize);
        fft->app.saveApplicationString = NULL;
    }
    return result;
}

int gpu_fft_create(gpu_context *context, int px, int py, gpu_buffer *real, gpu_buffer *modes, gpu_buffer *scratch,
                   gpu_fft **out)
{
    *out = NULL;
    int status = check_sizes(context, px, py, real, modes, scratch);
    if (status != IM_OK)
        return status;
    gpu_fft *fft = calloc(1, sizeof *fft);
    if (!fft)
        return im_fail(IM_ENOMEM, "GPU FFT %d x %d: out of memory", px, py);
    fft->handles = gpu_context_handles(context);
    const uint64_t extent = gpu_fft_modes_bytes(px, py);
    hand_over(real, extent, (uint64_t)px * py * sizeof(double), fft->real, fft->real_bytes, &fft->real_parts);
    hand_over(modes, extent, extent, fft->modes, fft->modes_bytes, &fft->modes_parts);
    if (scratch)
        hand_over(scratch, extent, extent, fft->scratch, fft->scratch_bytes, &fft->scratch_parts);
    fft->px = px;
    fft->py = py;
    snprintf(fft->labels[0], sizeof fft->labels[0], "FFT R2C %d x %d", px, py);
    snprintf(fft->labels[1], sizeof fft->labels[1], "FFT C2R %d x %d", px, py);
    /* VkFFT starts glslang (glslang_initialize_process, reference counted in glslang 12) for the
     * plan's shaders and stops it again before returning. */
    VkFFTResult result = initialize(fft);
    status = result == VKFFT_SUCCESS
                 ? check_parts_path(fft)
                 : im_fail(IM_EUNSUPPORTED, "GPU FFT %d x %d: initializeVkFFT: VkFFT error %d", px, py, (int)result);
    if (status != IM_OK) {
        deleteVkFFT(&fft->app);
        free(fft);
        return status;
    }
    *out = fft;
    return IM_OK;
}

/* VkFFT records its dispatches (with its own shader-write -> shader-read barriers between them);
 * the closing barrier orders them before whatever the caller records next. */
static void append(gpu_context *context, gpu_fft *fft, int direction)
{
    fft->commands = gpu_command_buffer(context);
    if (fft->commands == VK_NULL_HANDLE)
        return; /* gpu_submit_wait reports why */
    VkFFTLaunchParams launch = {0};
    launch.commandBuffer = &fft->commands;
    VkFFTResult result = VkFFTAppend(&fft->app, direction, &launch);
    if (result != VKFFT_SUCCESS) {
        gpu_defer_failure(context, im_fail(IM_EUNSUPPORTED, "GPU FFT %d x %d: VkFFTAppend (%s): VkFFT error %d",
                                           fft->px, fft->py, direction < 0 ? "forward" : "inverse", (int)result));
        return;
    }
    gpu_barrier(context);
    gpu_mark(context, fft->labels[direction < 0 ? 0 : 1]);
}

void gpu_fft_forward(gpu_context *context, gpu_fft *fft) { append(context, fft, -1); }
void gpu_fft_inverse(gpu_context *context, gpu_fft *fft) { append(context, fft, 1); }

void gpu_fft_free(gpu_fft *fft)
{
    if (!fft)
        return;
    deleteVkFFT(&fft->app);
    free(fft);
}
