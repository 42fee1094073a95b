/* Internal: the Vulkan compute layer under the GPU solver engine (src/gpu/).
 *
 * Entry points:
 *   gpu_context_open / gpu_context_close      one instance, one device with shaderFloat64, one queue
 *   gpu_devices_describe                      the Vulkan devices this machine has (indentmap info)
 *   gpu_buffer_create / _free / _upload / _download
 *   gpu_pipeline_create / _free               a compute pipeline from embedded SPIR-V
 *   gpu_begin / gpu_dispatch / gpu_barrier / gpu_submit_wait   recording and running work
 *   gpu_fft_create / _forward / _inverse / _free               VkFFT R2C / C2R in double (fft.c)
 *
 * Threads: a context and everything made from it belong to one thread at a time. Errors: every
 * function returning int returns IM_OK or an IM_E* status with the reason in im_last_error(). */
#ifndef INDENTMAP_GPU_VULKAN_H
#define INDENTMAP_GPU_VULKAN_H

#include <stddef.h>
#include <stdint.h>
#include <vulkan/vulkan.h>

typedef struct gpu_context gpu_context;

/* A buffer as the shaders see it is an array of GPU_MAX_CHUNKS chunks of the context's chunk size
 * (gpu_context_chunk_bytes; shaders/compute/chunks.glsl), since no storage buffer binding may
 * exceed maxStorageBufferRange. In memory it is one Vulkan buffer, or, beyond the largest power of
 * two within that range (gpu_context_part_bytes), several parts of that size each (the last one
 * too, as VkFFT's multi-buffer mode needs equal blocks); each chunk lies within one part. */
enum { GPU_MAX_CHUNKS = 5 };
typedef struct gpu_buffer {
    VkBuffer part[GPU_MAX_CHUNKS];
    VkDeviceMemory memory[GPU_MAX_CHUNKS];
    uint32_t parts;
    VkDeviceSize bytes;      /* what was asked for */
    VkDeviceSize part_bytes; /* each part's size: bytes when there is one */
    void *mapped; /* host-visible buffers (one part): their persistent mapping (coherent); NULL otherwise */
    VkDeviceSize local_bytes; /* the device-local memory it holds (gpu_context_local_bytes) */
} gpu_buffer;

typedef struct gpu_pipeline {
    VkPipeline pipeline;
    VkPipelineLayout layout;
    VkDescriptorSetLayout set_layout;
    uint32_t bindings;   /* storage buffers at bindings 0 .. bindings - 1 of set 0 */
    uint32_t fields;     /* bindings 0 .. fields - 1 are fields: arrays of GPU_MAX_CHUNKS chunks */
    uint32_t push_bytes; /* push-constant block size */
    const char *label;   /* the pass's name in a profile (profile.h); set by its maker */
} gpu_pipeline;

/* Which device a context takes. */
enum gpu_preference {
    GPU_PREFER_HARDWARE, /* a discrete, then an integrated or virtual GPU; IM_EUNSUPPORTED if only a CPU device */
    GPU_ANY              /* as above, else a CPU implementation (lavapipe): tests */
};

/* Opens the device (it must offer shaderFloat64 and a compute queue). validation = 1 enables
 * VK_LAYER_KHRONOS_validation with synchronization validation and counts what it reports
 * (gpu_context_validation_messages); IM_EUNSUPPORTED when the layer is not installed. */
int gpu_context_open(enum gpu_preference preference, int validation, gpu_context **out);
void gpu_context_close(gpu_context *context);
const char *gpu_context_device_name(const gpu_context *context);
int gpu_context_is_software(const gpu_context *context);         /* a CPU implementation (lavapipe) */
VkDeviceSize gpu_context_max_buffer(const gpu_context *context); /* maxStorageBufferRange */
/* A buffer's parts: the largest power of two within maxStorageBufferRange, at most 2 GiB, or within
 * the environment's INDENTMAP_GPU_MAX_PART (bytes; a test setting for VkFFT's multi-buffer mode on
 * small grids) when that is smaller. */
VkDeviceSize gpu_context_part_bytes(const gpu_context *context);
/* The chunks the shaders index: the part size, or the largest power of two within the environment's
 * INDENTMAP_GPU_MAX_BUFFER (bytes; a test setting that splits small fields) when that is smaller.
 * A device-local buffer holds at most GPU_MAX_CHUNKS of them. */
VkDeviceSize gpu_context_chunk_bytes(const gpu_context *context);
/* Whether the device indexes arrays of storage buffers by non-uniform indices natively, which
 * VkFFT's multi-buffer mode (transforms of buffers in several parts) relies on. */
int gpu_context_nonuniform_buffers(const gpu_context *context);
/* The device-local memory the engine may fill: the device's heaps' sum, or less where the environment's
 * INDENTMAP_GPU_MAX_MEMORY (a whole number of bytes, no unit; a test setting: a run too large for the
 * device on any machine) says so; and what a buffer of `bytes` occupies there (whole parts). Like
 * INDENTMAP_GPU_MAX_PART and INDENTMAP_GPU_MAX_BUFFER it is read when the context opens, which fails
 * with IM_EINVAL naming the variable and its text when that is not a whole number of bytes >= 4096. */
VkDeviceSize gpu_context_device_bytes(const gpu_context *context);
VkDeviceSize gpu_context_buffer_footprint(const gpu_context *context, VkDeviceSize bytes);
/* The device-local memory the context's buffers hold now (their parts' sizes; VkFFT's own small
 * allocations, its twiddle tables, are not among them). */
VkDeviceSize gpu_context_local_bytes(const gpu_context *context);
long gpu_context_validation_messages(const gpu_context *context); /* warnings and errors so far */
/* The bytes gpu_buffer_upload and gpu_buffer_download have copied to and from the device so far. */
void gpu_context_transfers(const gpu_context *context, VkDeviceSize *uploaded, VkDeviceSize *downloaded);
/* The submissions gpu_submit_wait has made and waited for so far (each one fence wait of the host;
 * VkFFT's own, while it plans, are not among them). */
long gpu_context_submissions(const gpu_context *context);

/* Writes one line per Vulkan device ("name, type, Vulkan x.y, float64 yes|no, N MiB") into text;
 * IM_EUNSUPPORTED (with the reason) when there is no Vulkan loader or no device. */
int gpu_devices_describe(char *text, size_t size);

/* Where a buffer's memory lives. */
enum gpu_memory {
    GPU_DEVICE_LOCAL, /* the device's own memory: the fields */
    GPU_HOST_WRITE,   /* host-visible and coherent, mapped: what the host writes (uploads) */
    GPU_HOST_READ     /* the same, and cached on the host where the device offers it: what the host reads
                       * (results, downloads), since the host reads uncached mapped memory far slower */
};
int gpu_buffer_create(gpu_context *context, VkDeviceSize bytes, enum gpu_memory memory, gpu_buffer *out);
void gpu_buffer_free(gpu_context *context, gpu_buffer *buffer);
/* Synchronous copies through a staging buffer (direct for host-visible buffers); offset in bytes.
 * The staging buffers grow to the largest copy; gpu_context_reserve_staging sizes them at once. */
int gpu_context_reserve_staging(gpu_context *context, VkDeviceSize bytes);
int gpu_buffer_upload(gpu_context *context, gpu_buffer *buffer, VkDeviceSize offset, const void *data,
                      VkDeviceSize bytes);
int gpu_buffer_download(gpu_context *context, const gpu_buffer *buffer, VkDeviceSize offset, void *data,
                        VkDeviceSize bytes);

/* bindings 0 .. fields - 1 are chunked fields (chunks.glsl), the rest single small buffers; the
 * shader's CHUNK_DOUBLES (specialization constant 0) is set to the context's chunk size. */
int gpu_pipeline_create(gpu_context *context, const uint32_t *spirv, size_t spirv_bytes, uint32_t bindings,
                        uint32_t fields, uint32_t push_bytes, gpu_pipeline *out);
void gpu_pipeline_free(gpu_context *context, gpu_pipeline *pipeline);

/* Starts recording into the context's command buffer (idempotent while recording). */
int gpu_begin(gpu_context *context);
/* Records one dispatch of groups x 1 x 1 workgroups, buffers[k] at binding k (push descriptors),
 * push: pipeline->push_bytes of constants. Followed by a compute-to-compute memory barrier. */
void gpu_dispatch(gpu_context *context, const gpu_pipeline *pipeline, const gpu_buffer *const *buffers,
                  const void *push, uint32_t groups);
/* Records filling the whole buffer with zero bits (0.0 in doubles), then a barrier. */
void gpu_zero(gpu_context *context, gpu_buffer *buffer);
/* A compute (and transfer) write -> compute (and transfer) read/write barrier. */
void gpu_barrier(gpu_context *context);
/* Marks the end of a pass recorded other than by gpu_dispatch (an FFT) for a profile (profile.h);
 * nothing when the context does not profile. */
void gpu_mark(gpu_context *context, const char *label);
/* Ends, submits, waits on the fence, and leaves the command buffer ready for gpu_begin. */
int gpu_submit_wait(gpu_context *context);
/* The command buffer being recorded (fft.c), begun if it was not; VK_NULL_HANDLE when beginning
 * failed (gpu_submit_wait reports it). */
VkCommandBuffer gpu_command_buffer(gpu_context *context);
/* Keeps a failure met while recording (status, with im_last_error() as it is now) for
 * gpu_submit_wait to return; the first one is kept and nothing more is recorded until then. */
void gpu_defer_failure(gpu_context *context, int status);

/* The handles VkFFT takes by pointer (fft.c): they stay valid as long as the context. VkFFT submits
 * its own set-up work (tables it uploads) on this queue with this pool and fence, so plans are
 * made between recordings. */
typedef struct gpu_handles {
    VkPhysicalDevice *physical_device;
    VkDevice *device;
    VkQueue *queue;
    VkCommandPool *pool;
    VkFence *fence;
} gpu_handles;
gpu_handles gpu_context_handles(gpu_context *context);
/* "VK_ERROR_DEVICE_LOST" for a VkResult ("unknown VkResult" for codes it does not list). */
const char *gpu_result_name(VkResult result);

/* ---- FFT (fft.c, the only file that includes vkFFT.h) ----
 * A 2-D double-precision R2C transform of px x py reals (row-major, row stride px) in `real` into
 * py x (px/2 + 1) complex modes in `modes`, and the C2R transform back into `real`; unnormalised
 * (forward then inverse multiplies by px * py), as FFTW's. The inverse overwrites the modes (as
 * FFTW's c2r destroys its input). Both buffers must hold gpu_fft_modes_bytes(px, py): VkFFT binds
 * the real buffer with the modes' size, though it touches only the first px * py reals. Sides must
 * factor into 2, 3, 5, 7, 11 and 13 (VkFFT's exact radices): others are refused with
 * IM_EUNSUPPORTED naming the side. Buffers larger than that are used from their start (a coarse
 * cascade level's transforms run in its finest level's buffers). scratch: VkFFT's work buffer for
 * the four-step algorithm (an axis longer than the device's shared memory holds takes several
 * uploads, and VkFFT reorders through it), at least gpu_fft_modes_bytes too, whose contents the
 * transforms destroy; NULL lets VkFFT allocate its own, as one buffer, when it needs one. */
VkDeviceSize gpu_fft_modes_bytes(int px, int py); /* (px/2 + 1) * py complex doubles */
/* Buffers in parts (VkFFT's multi-buffer mode) are transformed only when the transform's first axis
 * takes several of VkFFT's uploads: its one-upload R2C kernels address the reals of a buffer in parts
 * wrongly (fft.c, check_parts_path, which asks the plan). A first axis of this many reals or more takes
 * several in double (its 8192 complex values, 128 KiB, exceed a workgroup's shared memory on the devices
 * seen); the estimate (engine_gpu.c, check_estimated_transforms) judges by this length before any plan,
 * refusing in parts whatever is shorter. */
enum { GPU_PARTS_FIRST_AXIS = 16384 };
typedef struct gpu_fft gpu_fft;
int gpu_fft_create(gpu_context *context, int px, int py, gpu_buffer *real, gpu_buffer *modes, gpu_buffer *scratch,
                   gpu_fft **out);
void gpu_fft_forward(gpu_context *context, gpu_fft *fft); /* records into the current command buffer */
void gpu_fft_inverse(gpu_context *context, gpu_fft *fft);
void gpu_fft_free(gpu_fft *fft);
int gpu_fft_side_supported(int side); /* 1 when side factors into 2, 3, 5, 7, 11, 13 */

#endif
