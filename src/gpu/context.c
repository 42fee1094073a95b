/* The Vulkan compute layer: instance, device, buffers, pipelines with push descriptors, one
 * command buffer (vulkan.h). The FFT is in fft.c. */
#include "gpu/vulkan.h"

#include "gpu/profile.h"

#include "indentmap/status.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* MAX_DESCRIPTORS: the push descriptors a pipeline may take, the least maxPushDescriptors a device
 * offers (a field binding takes GPU_MAX_CHUNKS of them). */
enum { MAX_DEVICES = 16, MAX_BINDINGS = 16, MAX_DESCRIPTORS = 32 };

static const char VALIDATION_LAYER[] = "VK_LAYER_KHRONOS_validation";

/* Limits in bytes a test may set (read_limits); UINT64_MAX: none. */
typedef struct gpu_limits {
    VkDeviceSize memory, part, buffer;
} gpu_limits;

struct gpu_context {
    VkInstance instance;
    VkDebugUtilsMessengerEXT messenger;
    PFN_vkDestroyDebugUtilsMessengerEXT destroy_messenger;
    VkPhysicalDevice physical;
    VkDevice device;
    uint32_t queue_family;
    VkQueue queue;
    VkCommandPool pool;
    VkCommandBuffer commands;
    VkFence fence;
    PFN_vkCmdPushDescriptorSetKHR push_descriptor_set;
    VkPhysicalDeviceMemoryProperties memory;
    VkDeviceSize max_buffer;
    VkDeviceSize part_bytes, chunk_bytes; /* gpu_context_part_bytes, gpu_context_chunk_bytes */
    VkDeviceSize device_bytes;            /* gpu_context_device_bytes */
    gpu_limits limits;                    /* the environment's (read_limits) */
    int nonuniform_buffers;               /* gpu_context_nonuniform_buffers */
    int software;
    int recording;
    int deferred_status; /* a failure while recording (void functions), returned by gpu_submit_wait */
    char deferred_error[512];
    gpu_buffer upload, download;       /* staging (GPU_HOST_WRITE, GPU_HOST_READ), grown on demand */
    VkDeviceSize local_bytes;          /* gpu_context_local_bytes */
    VkDeviceSize uploaded, downloaded; /* gpu_context_transfers */
    long submissions;                  /* gpu_context_submissions */
    long validation_messages;
    gpu_profile *profile; /* NULL unless INDENTMAP_GPU_PROFILE asks for one */
    char name[VK_MAX_PHYSICAL_DEVICE_NAME_SIZE];
};

const char *gpu_result_name(VkResult result)
{
#define NAME(r)                                                                                                      \
    {                                                                                                                \
        r, #r                                                                                                        \
    }
    static const struct {
        VkResult result;
        const char *name;
    } names[] = {
        NAME(VK_SUCCESS),
        NAME(VK_NOT_READY),
        NAME(VK_TIMEOUT),
        NAME(VK_INCOMPLETE),
        NAME(VK_ERROR_OUT_OF_HOST_MEMORY),
        NAME(VK_ERROR_OUT_OF_DEVICE_MEMORY),
        NAME(VK_ERROR_INITIALIZATION_FAILED),
        NAME(VK_ERROR_DEVICE_LOST),
        NAME(VK_ERROR_MEMORY_MAP_FAILED),
        NAME(VK_ERROR_LAYER_NOT_PRESENT),
        NAME(VK_ERROR_EXTENSION_NOT_PRESENT),
        NAME(VK_ERROR_FEATURE_NOT_PRESENT),
        NAME(VK_ERROR_INCOMPATIBLE_DRIVER),
        NAME(VK_ERROR_TOO_MANY_OBJECTS),
        NAME(VK_ERROR_FORMAT_NOT_SUPPORTED),
        NAME(VK_ERROR_FRAGMENTED_POOL),
        NAME(VK_ERROR_UNKNOWN),
        NAME(VK_ERROR_OUT_OF_POOL_MEMORY),
        NAME(VK_ERROR_INVALID_EXTERNAL_HANDLE),
    };
#undef NAME
    for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i)
        if (names[i].result == result)
            return names[i].name;
    return "unknown VkResult";
}

/* A failed Vulkan call as a status: out of memory is IM_ENOMEM, anything else IM_EUNSUPPORTED
 * (the device or driver cannot do what was asked). */
static int vk_fail(VkResult result, const char *call)
{
    int status = result == VK_ERROR_OUT_OF_HOST_MEMORY || result == VK_ERROR_OUT_OF_DEVICE_MEMORY ? IM_ENOMEM
                                                                                                  : IM_EUNSUPPORTED;
    return im_fail(status, "%s: %s (%d)", call, gpu_result_name(result), (int)result);
}

#define VK_CHECK(call)                                                                                               \
    do {                                                                                                             \
        VkResult r_ = (call);                                                                                        \
        if (r_ != VK_SUCCESS)                                                                                        \
            return vk_fail(r_, #call);                                                                               \
    } while (0)

/* ---- Instance and validation ---- */

static VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                            VkDebugUtilsMessageTypeFlagsEXT types,
                                                            const VkDebugUtilsMessengerCallbackDataEXT *data,
                                                            void *user)
{
    (void)types;
    gpu_context *context = user;
    if (severity &
        (VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT)) {
        context->validation_messages++;
        /* Only with validation on (tests, debugging): the library otherwise never prints. */
        fprintf(stderr, "vulkan validation: %s\n", data && data->pMessage ? data->pMessage : "(no message)");
    }
    return VK_FALSE;
}

static VkDebugUtilsMessengerCreateInfoEXT messenger_info(gpu_context *context)
{
    return (VkDebugUtilsMessengerCreateInfoEXT){.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
                                                .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                                                   VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
                                                .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                                               VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                                               VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
                                                .pfnUserCallback = on_validation_message,
                                                .pUserData = context};
}

static int layer_installed(const char *name)
{
    uint32_t count = 0;
    if (vkEnumerateInstanceLayerProperties(&count, NULL) != VK_SUCCESS || count == 0)
        return 0;
    VkLayerProperties *layers = calloc(count, sizeof *layers);
    int found = 0;
    if (layers && vkEnumerateInstanceLayerProperties(&count, layers) == VK_SUCCESS)
        for (uint32_t i = 0; i < count && !found; ++i)
            found = strcmp(layers[i].layerName, name) == 0;
    free(layers);
    return found;
}

static int create_instance(gpu_context *context, int validation)
{
    if (validation && !layer_installed(VALIDATION_LAYER))
        return im_fail(IM_EUNSUPPORTED, "Vulkan validation: %s is not installed (Debian: vulkan-validationlayers)",
                       VALIDATION_LAYER);
    VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
                             .pApplicationName = "indentmap",
                             .pEngineName = "indentmap",
                             .apiVersion = VK_API_VERSION_1_1};
    /* Synchronization validation checks the barriers between dispatches and copies too. */
    VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkDebugUtilsMessengerCreateInfoEXT messenger = messenger_info(context);
    VkValidationFeaturesEXT features = {.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
                                        .pNext = &messenger, /* reports instance creation itself */
                                        .enabledValidationFeatureCount = 1,
                                        .pEnabledValidationFeatures = enables};
    const char *layers[] = {VALIDATION_LAYER};
    const char *extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
    VkInstanceCreateInfo info = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, .pApplicationInfo = &app};
    if (validation) {
        info.pNext = &features;
        info.enabledLayerCount = 1;
        info.ppEnabledLayerNames = layers;
        info.enabledExtensionCount = 1;
        info.ppEnabledExtensionNames = extensions;
    }
    VK_CHECK(vkCreateInstance(&info, NULL, &context->instance));
    if (!validation)
        return IM_OK;
    PFN_vkCreateDebugUtilsMessengerEXT create = (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(
        context->instance, "vkCreateDebugUtilsMessengerEXT");
    context->destroy_messenger = (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(
        context->instance, "vkDestroyDebugUtilsMessengerEXT");
    if (!create || !context->destroy_messenger)
        return im_fail(IM_EUNSUPPORTED, "Vulkan validation: vkCreateDebugUtilsMessengerEXT is not available");
    VK_CHECK(create(context->instance, &messenger, NULL, &context->messenger));
    return IM_OK;
}

/* ---- Choosing the device ---- */

static const char *type_name(VkPhysicalDeviceType type)
{
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
    }
}

/* Higher is preferred; 0: a CPU implementation, -1: "other" (neither GPU nor CPU). */
static int type_rank(VkPhysicalDeviceType type)
{
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 0;
    default: return -1;
    }
}

static int compute_queue_family(VkPhysicalDevice device, uint32_t *family)
{
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, NULL);
    VkQueueFamilyProperties families[32];
    if (count > 32)
        count = 32;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families);
    for (uint32_t i = 0; i < count; ++i) {
        if (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) {
            *family = i;
            return 1;
        }
    }
    return 0;
}

static int has_device_extension(VkPhysicalDevice device, const char *name)
{
    uint32_t count = 0;
    if (vkEnumerateDeviceExtensionProperties(device, NULL, &count, NULL) != VK_SUCCESS)
        return 0;
    VkExtensionProperties *extensions = calloc(count ? count : 1, sizeof *extensions);
    int found = 0;
    if (extensions && vkEnumerateDeviceExtensionProperties(device, NULL, &count, extensions) == VK_SUCCESS)
        for (uint32_t i = 0; i < count && !found; ++i)
            found = strcmp(extensions[i].extensionName, name) == 0;
    free(extensions);
    return found;
}

/* Why a device cannot serve (NULL when it can). */
static const char *unsuitable(VkPhysicalDevice device, uint32_t *family)
{
    VkPhysicalDeviceProperties properties;
    VkPhysicalDeviceFeatures features;
    vkGetPhysicalDeviceProperties(device, &properties);
    vkGetPhysicalDeviceFeatures(device, &features);
    if (properties.apiVersion < VK_API_VERSION_1_1)
        return "Vulkan 1.0 only";
    if (!features.shaderFloat64)
        return "no shaderFloat64";
    if (!compute_queue_family(device, family))
        return "no compute queue";
    if (!has_device_extension(device, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME))
        return "no " VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME;
    return NULL;
}

/* Adds "NAME (TYPE)" or "NAME (TYPE: WHY)" to the list of devices found. */
static void note_device(char *found, size_t size, const VkPhysicalDeviceProperties *properties, const char *why)
{
    size_t used = strlen(found);
    if (used < size)
        snprintf(found + used, size - used, "%s%s (%s%s%s)", used ? "; " : "", properties->deviceName,
                 type_name(properties->deviceType), why ? ": " : "", why ? why : "");
}

/* The best suitable device by type (discrete first); with GPU_PREFER_HARDWARE, a GPU only. The
 * refusal names every device found and why it was passed over. */
static int choose_device(gpu_context *context, enum gpu_preference preference)
{
    VkPhysicalDevice devices[MAX_DEVICES];
    uint32_t count = MAX_DEVICES;
    VkResult result = vkEnumeratePhysicalDevices(context->instance, &count, devices);
    if (result != VK_SUCCESS && result != VK_INCOMPLETE)
        return vk_fail(result, "vkEnumeratePhysicalDevices");
    if (count == 0)
        return im_fail(IM_EUNSUPPORTED, "no Vulkan device (vkEnumeratePhysicalDevices found none)");
    int best = -1, best_rank = -2;
    char found[1024] = "";
    for (uint32_t i = 0; i < count; ++i) {
        VkPhysicalDeviceProperties properties;
        vkGetPhysicalDeviceProperties(devices[i], &properties);
        uint32_t family = 0;
        const char *why = unsuitable(devices[i], &family);
        int rank = type_rank(properties.deviceType);
        if (!why && preference == GPU_PREFER_HARDWARE && rank < 1)
            why = "not a GPU";
        note_device(found, sizeof found, &properties, why);
        if (!why && rank > best_rank) {
            best = (int)i;
            best_rank = rank;
            context->queue_family = family;
        }
    }
    if (best < 0)
        return im_fail(IM_EUNSUPPORTED, "no Vulkan %s with shaderFloat64, a compute queue and %s; found: %s",
                       preference == GPU_PREFER_HARDWARE ? "GPU" : "device", VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME,
                       found);
    context->physical = devices[best];
    return IM_OK;
}

/* The sum of the device-local heaps of a device. */
static VkDeviceSize device_local_bytes(VkPhysicalDevice device)
{
    VkPhysicalDeviceMemoryProperties memory;
    vkGetPhysicalDeviceMemoryProperties(device, &memory);
    VkDeviceSize bytes = 0;
    for (uint32_t i = 0; i < memory.memoryHeapCount; ++i)
        if (memory.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
            bytes += memory.memoryHeaps[i].size;
    return bytes;
}

/* The largest power of two not above limit, nor above 2 GiB (so a chunk's doubles fit a 32-bit
 * index with room to spare). */
static VkDeviceSize power_of_two_within(VkDeviceSize limit)
{
    VkDeviceSize bytes = (VkDeviceSize)1 << 31;
    while (bytes > limit)
        bytes >>= 1;
    return bytes;
}

/* Lowers *limit to the whole number of bytes in environment variable `name`, when it is set (empty:
 * not set); IM_EINVAL naming the variable and its text for anything else, a unit suffix included. */
static int lower_to_environment(const char *name, VkDeviceSize *limit)
{
    enum { SMALLEST = 4096 };
    const char *text = getenv(name);
    if (!text || !*text)
        return IM_OK;
    char *end;
    errno = 0;
    const unsigned long long asked = strtoull(text, &end, 10);
    if (errno || *end || text[0] == '-' || asked < SMALLEST)
        return im_fail(IM_EINVAL, "%s=%s: expected a whole number of bytes (digits only, no unit), at least %d", name,
                       text, SMALLEST);
    if (asked < *limit)
        *limit = asked;
    return IM_OK;
}

/* The test settings of the environment, read when a context opens, before any device, so that bad text
 * fails wherever it is set (not only where a device opens): INDENTMAP_GPU_MAX_MEMORY lowers the device
 * memory the engine may fill (a run too large for the device on any machine); INDENTMAP_GPU_MAX_BUFFER
 * splits small fields into shader chunks while VkFFT keeps one buffer (any device, lavapipe included);
 * INDENTMAP_GPU_MAX_PART splits buffers into parts, so that VkFFT's multi-buffer mode runs on small
 * grids (devices that index buffer arrays non-uniformly natively: NVIDIA's, not lavapipe). The one
 * place they are read. */
static int read_limits(gpu_limits *limits)
{
    *limits = (gpu_limits){UINT64_MAX, UINT64_MAX, UINT64_MAX};
    int status = lower_to_environment("INDENTMAP_GPU_MAX_MEMORY", &limits->memory);
    if (status == IM_OK)
        status = lower_to_environment("INDENTMAP_GPU_MAX_PART", &limits->part);
    if (status == IM_OK)
        status = lower_to_environment("INDENTMAP_GPU_MAX_BUFFER", &limits->buffer);
    return status;
}

static VkDeviceSize smaller(VkDeviceSize a, VkDeviceSize b) { return a < b ? a : b; }

/* The device memory the engine may fill, the part size and the chunk size, within the settings. */
static void choose_limits(gpu_context *context)
{
    context->device_bytes = smaller(device_local_bytes(context->physical), context->limits.memory);
    context->part_bytes = power_of_two_within(smaller(context->max_buffer, context->limits.part));
    context->chunk_bytes = power_of_two_within(smaller(context->part_bytes, context->limits.buffer));
}

/* shaderStorageBufferArrayNonUniformIndexingNative (VK_EXT_descriptor_indexing's property). */
static int nonuniform_buffers(VkPhysicalDevice device)
{
    if (!has_device_extension(device, VK_EXT_DESCRIPTOR_INDEXING_EXTENSION_NAME))
        return 0;
    VkPhysicalDeviceDescriptorIndexingPropertiesEXT indexing = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DESCRIPTOR_INDEXING_PROPERTIES_EXT};
    VkPhysicalDeviceProperties2 properties = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2,
                                              .pNext = &indexing};
    vkGetPhysicalDeviceProperties2(device, &properties);
    return indexing.shaderStorageBufferArrayNonUniformIndexingNative == VK_TRUE;
}

static int create_device(gpu_context *context)
{
    VkPhysicalDeviceProperties properties;
    VkPhysicalDeviceFeatures supported;
    vkGetPhysicalDeviceProperties(context->physical, &properties);
    vkGetPhysicalDeviceFeatures(context->physical, &supported);
    vkGetPhysicalDeviceMemoryProperties(context->physical, &context->memory);
    snprintf(context->name, sizeof context->name, "%s", properties.deviceName);
    context->software = properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    context->max_buffer = properties.limits.maxStorageBufferRange;
    choose_limits(context);
    context->nonuniform_buffers = nonuniform_buffers(context->physical);

    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                     .queueFamilyIndex = context->queue_family,
                                     .queueCount = 1,
                                     .pQueuePriorities = &priority};
    /* 64-bit integers too where offered: VkFFT indexes large grids with them. */
    VkPhysicalDeviceFeatures features = {.shaderFloat64 = VK_TRUE, .shaderInt64 = supported.shaderInt64};
    const char *extensions[] = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    VkDeviceCreateInfo info = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
                               .queueCreateInfoCount = 1,
                               .pQueueCreateInfos = &queue,
                               .enabledExtensionCount = 1,
                               .ppEnabledExtensionNames = extensions,
                               .pEnabledFeatures = &features};
    VK_CHECK(vkCreateDevice(context->physical, &info, NULL, &context->device));
    vkGetDeviceQueue(context->device, context->queue_family, 0, &context->queue);
    context->push_descriptor_set = (PFN_vkCmdPushDescriptorSetKHR)vkGetDeviceProcAddr(context->device,
                                                                                      "vkCmdPushDescriptorSetKHR");
    if (!context->push_descriptor_set)
        return im_fail(IM_EUNSUPPORTED, "vkGetDeviceProcAddr(vkCmdPushDescriptorSetKHR): not available");
    return IM_OK;
}

static int create_commands(gpu_context *context)
{
    VkCommandPoolCreateInfo pool = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                    .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                    .queueFamilyIndex = context->queue_family};
    VK_CHECK(vkCreateCommandPool(context->device, &pool, NULL, &context->pool));
    VkCommandBufferAllocateInfo allocate = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                            .commandPool = context->pool,
                                            .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                            .commandBufferCount = 1};
    VK_CHECK(vkAllocateCommandBuffers(context->device, &allocate, &context->commands));
    VkFenceCreateInfo fence = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_CHECK(vkCreateFence(context->device, &fence, NULL, &context->fence));
    return IM_OK;
}

int gpu_context_open(enum gpu_preference preference, int validation, gpu_context **out)
{
    *out = NULL;
    gpu_context *context = calloc(1, sizeof *context);
    if (!context)
        return im_fail(IM_ENOMEM, "GPU context: out of memory");
    int status = read_limits(&context->limits);
    if (status == IM_OK)
        status = create_instance(context, validation);
    if (status == IM_OK)
        status = choose_device(context, preference);
    if (status == IM_OK)
        status = create_device(context);
    if (status == IM_OK)
        status = create_commands(context);
    if (status == IM_OK)
        context->profile = gpu_profile_open(context->device, context->physical, context->queue_family);
    if (status != IM_OK) {
        gpu_context_close(context);
        return status;
    }
    *out = context;
    return IM_OK;
}

void gpu_context_close(gpu_context *context)
{
    if (!context)
        return;
    if (context->device) {
        vkDeviceWaitIdle(context->device);
        gpu_profile_close(context->profile, context->name, stderr);
        gpu_buffer_free(context, &context->upload);
        gpu_buffer_free(context, &context->download);
        vkDestroyFence(context->device, context->fence, NULL);
        vkDestroyCommandPool(context->device, context->pool, NULL); /* frees the command buffer */
        vkDestroyDevice(context->device, NULL);
    }
    if (context->messenger)
        context->destroy_messenger(context->instance, context->messenger, NULL);
    if (context->instance)
        vkDestroyInstance(context->instance, NULL);
    free(context);
}

const char *gpu_context_device_name(const gpu_context *context) { return context->name; }
int gpu_context_is_software(const gpu_context *context) { return context->software; }
VkDeviceSize gpu_context_max_buffer(const gpu_context *context) { return context->max_buffer; }
VkDeviceSize gpu_context_part_bytes(const gpu_context *context) { return context->part_bytes; }
VkDeviceSize gpu_context_chunk_bytes(const gpu_context *context) { return context->chunk_bytes; }
int gpu_context_nonuniform_buffers(const gpu_context *context) { return context->nonuniform_buffers; }

/* How many pieces of `size` hold `bytes`. */
static uint32_t pieces(VkDeviceSize bytes, VkDeviceSize size) { return (uint32_t)((bytes + size - 1) / size); }

VkDeviceSize gpu_context_buffer_footprint(const gpu_context *context, VkDeviceSize bytes)
{
    return bytes <= context->part_bytes ? bytes : pieces(bytes, context->part_bytes) * context->part_bytes;
}
VkDeviceSize gpu_context_local_bytes(const gpu_context *context) { return context->local_bytes; }
long gpu_context_validation_messages(const gpu_context *context) { return context->validation_messages; }

long gpu_context_submissions(const gpu_context *context) { return context->submissions; }

void gpu_context_transfers(const gpu_context *context, VkDeviceSize *uploaded, VkDeviceSize *downloaded)
{
    *uploaded = context->uploaded;
    *downloaded = context->downloaded;
}

gpu_handles gpu_context_handles(gpu_context *context)
{
    return (gpu_handles){.physical_device = &context->physical,
                         .device = &context->device,
                         .queue = &context->queue,
                         .pool = &context->pool,
                         .fence = &context->fence};
}

/* ---- Describing the devices (indentmap info) ---- */

VkDeviceSize gpu_context_device_bytes(const gpu_context *context) { return context->device_bytes; }

static int describe_device(VkPhysicalDevice device, char *line, size_t size)
{
    VkPhysicalDeviceProperties properties;
    VkPhysicalDeviceFeatures features;
    vkGetPhysicalDeviceProperties(device, &properties);
    vkGetPhysicalDeviceFeatures(device, &features);
    return snprintf(line, size, "%s, %s, Vulkan %u.%u, float64 %s, %llu MiB device-local\n", properties.deviceName,
                    type_name(properties.deviceType), VK_API_VERSION_MAJOR(properties.apiVersion),
                    VK_API_VERSION_MINOR(properties.apiVersion), features.shaderFloat64 ? "yes" : "no",
                    (unsigned long long)(device_local_bytes(device) >> 20));
}

static int describe_all(VkInstance instance, char *text, size_t size)
{
    VkPhysicalDevice devices[MAX_DEVICES];
    uint32_t count = MAX_DEVICES;
    VkResult result = vkEnumeratePhysicalDevices(instance, &count, devices);
    if (result != VK_SUCCESS && result != VK_INCOMPLETE)
        return vk_fail(result, "vkEnumeratePhysicalDevices");
    if (count == 0)
        return im_fail(IM_EUNSUPPORTED, "no Vulkan device (vkEnumeratePhysicalDevices found none)");
    size_t used = 0;
    for (uint32_t i = 0; i < count; ++i) {
        int n = describe_device(devices[i], text + used, size - used);
        if (n < 0 || (size_t)n >= size - used)
            return im_fail(IM_EINVAL, "Vulkan devices: %zu bytes of text are too few for %u devices", size, count);
        used += (size_t)n;
    }
    return IM_OK;
}

int gpu_devices_describe(char *text, size_t size)
{
    if (!text || size == 0)
        return im_fail(IM_EINVAL, "Vulkan devices: no room for the text");
    text[0] = '\0';
    VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
                             .pApplicationName = "indentmap",
                             .apiVersion = VK_API_VERSION_1_1};
    VkInstanceCreateInfo info = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, .pApplicationInfo = &app};
    VkInstance instance;
    VkResult result = vkCreateInstance(&info, NULL, &instance);
    if (result == VK_ERROR_INCOMPATIBLE_DRIVER)
        return im_fail(IM_EUNSUPPORTED, "no Vulkan driver (vkCreateInstance: VK_ERROR_INCOMPATIBLE_DRIVER)");
    if (result != VK_SUCCESS)
        return vk_fail(result, "vkCreateInstance");
    int status = describe_all(instance, text, size);
    vkDestroyInstance(instance, NULL);
    return status;
}

/* ---- Buffers ---- */

static int memory_type(const gpu_context *context, uint32_t allowed, VkMemoryPropertyFlags wanted, uint32_t *type)
{
    for (uint32_t i = 0; i < context->memory.memoryTypeCount; ++i) {
        if ((allowed & (1u << i)) && (context->memory.memoryTypes[i].propertyFlags & wanted) == wanted) {
            *type = i;
            return 1;
        }
    }
    return 0;
}

/* The memory type for a use: GPU_HOST_READ takes a cached type first and settles for any coherent one. */
static int memory_type_for(const gpu_context *context, uint32_t allowed, enum gpu_memory memory, uint32_t *type)
{
    const VkMemoryPropertyFlags mapped = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    if (memory == GPU_DEVICE_LOCAL)
        return memory_type(context, allowed, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, type);
    if (memory == GPU_HOST_READ && memory_type(context, allowed, mapped | VK_MEMORY_PROPERTY_HOST_CACHED_BIT, type))
        return 1;
    return memory_type(context, allowed, mapped, type);
}

static int allocate_part(gpu_context *context, gpu_buffer *buffer, uint32_t k, enum gpu_memory memory)
{
    VkBufferCreateInfo info = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                               .size = buffer->part_bytes,
                               .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               .sharingMode = VK_SHARING_MODE_EXCLUSIVE};
    VK_CHECK(vkCreateBuffer(context->device, &info, NULL, &buffer->part[k]));
    VkMemoryRequirements needs;
    vkGetBufferMemoryRequirements(context->device, buffer->part[k], &needs);
    uint32_t type;
    const int host_visible = memory != GPU_DEVICE_LOCAL;
    if (!memory_type_for(context, needs.memoryTypeBits, memory, &type))
        return im_fail(IM_EUNSUPPORTED, "GPU buffer: no %s memory type on %s",
                       host_visible ? "host-visible coherent" : "device-local", context->name);
    VkMemoryAllocateInfo allocate = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                                     .allocationSize = needs.size,
                                     .memoryTypeIndex = type};
    VK_CHECK(vkAllocateMemory(context->device, &allocate, NULL, &buffer->memory[k]));
    if (!host_visible) {
        buffer->local_bytes += info.size;
        context->local_bytes += info.size;
    }
    VK_CHECK(vkBindBufferMemory(context->device, buffer->part[k], buffer->memory[k], 0));
    if (host_visible)
        VK_CHECK(vkMapMemory(context->device, buffer->memory[k], 0, VK_WHOLE_SIZE, 0, &buffer->mapped));
    return IM_OK;
}

/* Host-visible buffers are mapped whole, so they stay within one part (the staging copies go part
 * by part); device-local ones take up to GPU_MAX_CHUNKS chunks. */
static int check_buffer_size(const gpu_context *context, VkDeviceSize bytes, enum gpu_memory memory)
{
    if (bytes == 0)
        return im_fail(IM_EINVAL, "GPU buffer of 0 bytes: expected at least 1");
    const int local = memory == GPU_DEVICE_LOCAL;
    const VkDeviceSize piece = local ? context->chunk_bytes : context->part_bytes;
    const uint32_t most = local ? GPU_MAX_CHUNKS : 1;
    if (bytes > most * piece)
        return im_fail(IM_ENOMEM,
                       "GPU buffer of %.1f MiB: more than %u %s of %.1f MiB (%s's maxStorageBufferRange is %.1f MiB)",
                       bytes / 1048576.0, most, local ? "chunks" : "part", piece / 1048576.0, context->name,
                       context->max_buffer / 1048576.0);
    return IM_OK;
}

int gpu_buffer_create(gpu_context *context, VkDeviceSize bytes, enum gpu_memory memory, gpu_buffer *out)
{
    *out = (gpu_buffer){0};
    int status = check_buffer_size(context, bytes, memory);
    if (status != IM_OK)
        return status;
    out->bytes = bytes;
    out->parts = pieces(bytes, context->part_bytes);
    out->part_bytes = out->parts == 1 ? bytes : context->part_bytes;
    for (uint32_t k = 0; k < out->parts && status == IM_OK; ++k)
        status = allocate_part(context, out, k, memory);
    if (status != IM_OK)
        gpu_buffer_free(context, out);
    return status;
}

void gpu_buffer_free(gpu_context *context, gpu_buffer *buffer)
{
    if (!context || !buffer)
        return;
    if (buffer->mapped)
        vkUnmapMemory(context->device, buffer->memory[0]);
    for (uint32_t k = 0; k < buffer->parts; ++k) {
        vkDestroyBuffer(context->device, buffer->part[k], NULL);
        vkFreeMemory(context->device, buffer->memory[k], NULL);
    }
    context->local_bytes -= buffer->local_bytes;
    *buffer = (gpu_buffer){0};
}

static int check_range(const gpu_buffer *buffer, VkDeviceSize offset, VkDeviceSize bytes, const char *what)
{
    if (offset > buffer->bytes || bytes > buffer->bytes - offset)
        return im_fail(IM_EINVAL, "GPU buffer %s of %llu bytes at offset %llu: the buffer holds %llu", what,
                       (unsigned long long)bytes, (unsigned long long)offset, (unsigned long long)buffer->bytes);
    return IM_OK;
}

static int ensure_staging(gpu_context *context, gpu_buffer *staging, enum gpu_memory memory, VkDeviceSize bytes)
{
    if (staging->bytes >= bytes)
        return IM_OK;
    gpu_buffer_free(context, staging);
    return gpu_buffer_create(context, bytes, memory, staging);
}

/* The staging buffers hold at most one part: larger copies go part by part. */
int gpu_context_reserve_staging(gpu_context *context, VkDeviceSize bytes)
{
    bytes = bytes < context->part_bytes ? bytes : context->part_bytes;
    int status = ensure_staging(context, &context->upload, GPU_HOST_WRITE, bytes);
    return status == IM_OK ? ensure_staging(context, &context->download, GPU_HOST_READ, bytes) : status;
}

static double seconds_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* memcpy by all threads for large copies: one thread's copy into or out of mapped memory is a
 * fraction of what the host's memory can carry. */
static void copy_threaded(void *to, const void *from, size_t bytes)
{
    enum { CHUNK = 1 << 22 };
    const long chunks = (long)((bytes + CHUNK - 1) / CHUNK);
#pragma omp parallel for schedule(static) if (chunks > 1)
    for (long k = 0; k < chunks; ++k) {
        const size_t start = (size_t)k * CHUNK, length = bytes - start < CHUNK ? bytes - start : CHUNK;
        memcpy((char *)to + start, (const char *)from + start, length);
    }
}

/* One copy between a buffer and the staging buffer, run to completion. */
static int copy_and_wait(gpu_context *context, VkBuffer from, VkDeviceSize from_offset, VkBuffer to,
                         VkDeviceSize to_offset, VkDeviceSize bytes)
{
    int status = gpu_begin(context);
    if (status != IM_OK)
        return status;
    VkBufferCopy region = {.srcOffset = from_offset, .dstOffset = to_offset, .size = bytes};
    vkCmdCopyBuffer(context->commands, from, to, 1, &region);
    gpu_mark(context, "copy to or from the host");
    return gpu_submit_wait(context);
}

static int transfer_allowed(const gpu_context *context, const char *what)
{
    if (context->recording)
        return im_fail(IM_EINVAL, "GPU buffer %s while commands are being recorded: submit them first", what);
    return IM_OK;
}

/* The part of a copy at `offset` of a buffer that one staging copy takes: within one part of the
 * buffer and within the staging size (a part of the context). */
typedef struct {
    uint32_t part;
    VkDeviceSize offset, bytes; /* in that part */
} copy_piece;

static copy_piece piece_at(const gpu_context *context, const gpu_buffer *buffer, VkDeviceSize offset,
                           VkDeviceSize left)
{
    copy_piece piece = {.part = (uint32_t)(offset / buffer->part_bytes), .offset = offset % buffer->part_bytes};
    const VkDeviceSize room = buffer->part_bytes - piece.offset;
    piece.bytes = left < room ? left : room;
    if (piece.bytes > context->part_bytes)
        piece.bytes = context->part_bytes;
    return piece;
}

static int upload_piece(gpu_context *context, gpu_buffer *buffer, copy_piece piece, const void *data)
{
    int status = ensure_staging(context, &context->upload, GPU_HOST_WRITE, piece.bytes);
    if (status != IM_OK)
        return status;
    const double start = seconds_now();
    copy_threaded(context->upload.mapped, data, piece.bytes);
    gpu_profile_host(context->profile, "copy into staging", seconds_now() - start);
    return copy_and_wait(context, context->upload.part[0], 0, buffer->part[piece.part], piece.offset, piece.bytes);
}

static int download_piece(gpu_context *context, const gpu_buffer *buffer, copy_piece piece, void *data)
{
    int status = ensure_staging(context, &context->download, GPU_HOST_READ, piece.bytes);
    if (status == IM_OK)
        status = copy_and_wait(context, buffer->part[piece.part], piece.offset, context->download.part[0], 0,
                               piece.bytes);
    if (status == IM_OK) {
        const double start = seconds_now();
        copy_threaded(data, context->download.mapped, piece.bytes);
        gpu_profile_host(context->profile, "copy out of staging", seconds_now() - start);
    }
    return status;
}

int gpu_buffer_upload(gpu_context *context, gpu_buffer *buffer, VkDeviceSize offset, const void *data,
                      VkDeviceSize bytes)
{
    int status = check_range(buffer, offset, bytes, "upload");
    if (status == IM_OK)
        status = transfer_allowed(context, "upload");
    if (status != IM_OK || bytes == 0)
        return status;
    context->uploaded += bytes;
    if (buffer->mapped) {
        memcpy((char *)buffer->mapped + offset, data, bytes);
        return IM_OK;
    }
    for (VkDeviceSize done = 0; done < bytes && status == IM_OK;) {
        const copy_piece piece = piece_at(context, buffer, offset + done, bytes - done);
        status = upload_piece(context, buffer, piece, (const char *)data + done);
        done += piece.bytes;
    }
    return status;
}

int gpu_buffer_download(gpu_context *context, const gpu_buffer *buffer, VkDeviceSize offset, void *data,
                        VkDeviceSize bytes)
{
    int status = check_range(buffer, offset, bytes, "download");
    if (status == IM_OK)
        status = transfer_allowed(context, "download");
    if (status != IM_OK || bytes == 0)
        return status;
    context->downloaded += bytes;
    if (buffer->mapped) {
        memcpy(data, (const char *)buffer->mapped + offset, bytes);
        return IM_OK;
    }
    for (VkDeviceSize done = 0; done < bytes && status == IM_OK;) {
        const copy_piece piece = piece_at(context, buffer, offset + done, bytes - done);
        status = download_piece(context, buffer, piece, (char *)data + done);
        done += piece.bytes;
    }
    return status;
}

/* ---- Pipelines ---- */

static int create_layouts(gpu_context *context, gpu_pipeline *pipeline)
{
    VkDescriptorSetLayoutBinding bindings[MAX_BINDINGS];
    for (uint32_t k = 0; k < pipeline->bindings; ++k)
        bindings[k] = (VkDescriptorSetLayoutBinding){.binding = k,
                                                     .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                                     .descriptorCount = k < pipeline->fields ? GPU_MAX_CHUNKS : 1,
                                                     .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT};
    VkDescriptorSetLayoutCreateInfo set = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                           .flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR,
                                           .bindingCount = pipeline->bindings,
                                           .pBindings = bindings};
    VK_CHECK(vkCreateDescriptorSetLayout(context->device, &set, NULL, &pipeline->set_layout));
    VkPushConstantRange range = {.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT,
                                 .offset = 0,
                                 .size = pipeline->push_bytes};
    VkPipelineLayoutCreateInfo layout = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                         .setLayoutCount = 1,
                                         .pSetLayouts = &pipeline->set_layout,
                                         .pushConstantRangeCount = pipeline->push_bytes ? 1 : 0,
                                         .pPushConstantRanges = &range};
    VK_CHECK(vkCreatePipelineLayout(context->device, &layout, NULL, &pipeline->layout));
    return IM_OK;
}

static int create_compute_pipeline(gpu_context *context, const uint32_t *spirv, size_t spirv_bytes,
                                   gpu_pipeline *pipeline)
{
    VkShaderModuleCreateInfo module_info = {.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
                                            .codeSize = spirv_bytes,
                                            .pCode = spirv};
    VkShaderModule module;
    VK_CHECK(vkCreateShaderModule(context->device, &module_info, NULL, &module));
    const uint32_t chunk_doubles = (uint32_t)(context->chunk_bytes / sizeof(double));
    const VkSpecializationMapEntry entry = {.constantID = 0, .offset = 0, .size = sizeof chunk_doubles};
    const VkSpecializationInfo specialization = {.mapEntryCount = 1,
                                                 .pMapEntries = &entry,
                                                 .dataSize = sizeof chunk_doubles,
                                                 .pData = &chunk_doubles};
    VkComputePipelineCreateInfo info = {.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
                                        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                                                  .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                                                  .module = module,
                                                  .pName = "main",
                                                  .pSpecializationInfo = &specialization},
                                        .layout = pipeline->layout};
    VkResult result = vkCreateComputePipelines(context->device, VK_NULL_HANDLE, 1, &info, NULL, &pipeline->pipeline);
    vkDestroyShaderModule(context->device, module, NULL); /* the pipeline keeps what it needs */
    return result == VK_SUCCESS ? IM_OK : vk_fail(result, "vkCreateComputePipelines");
}

int gpu_pipeline_create(gpu_context *context, const uint32_t *spirv, size_t spirv_bytes, uint32_t bindings,
                        uint32_t fields, uint32_t push_bytes, gpu_pipeline *out)
{
    *out = (gpu_pipeline){.bindings = bindings, .fields = fields, .push_bytes = push_bytes};
    if (bindings == 0 || bindings > MAX_BINDINGS)
        return im_fail(IM_EINVAL, "GPU pipeline: %u buffers: expected 1..%d", bindings, MAX_BINDINGS);
    if (fields > bindings || fields * GPU_MAX_CHUNKS + (bindings - fields) > MAX_DESCRIPTORS)
        return im_fail(IM_EINVAL,
                       "GPU pipeline: %u fields of %u chunks among %u buffers: expected at most %d "
                       "descriptors in all",
                       fields, GPU_MAX_CHUNKS, bindings, MAX_DESCRIPTORS);
    if (push_bytes % 4 != 0 || push_bytes > 128)
        return im_fail(IM_EINVAL, "GPU pipeline: %u bytes of push constants: expected a multiple of 4 up to 128",
                       push_bytes);
    if (!spirv || spirv_bytes == 0 || spirv_bytes % 4 != 0)
        return im_fail(IM_EINVAL, "GPU pipeline: SPIR-V of %zu bytes: expected a non-empty multiple of 4",
                       spirv_bytes);
    int status = create_layouts(context, out);
    if (status == IM_OK)
        status = create_compute_pipeline(context, spirv, spirv_bytes, out);
    if (status != IM_OK)
        gpu_pipeline_free(context, out);
    return status;
}

void gpu_pipeline_free(gpu_context *context, gpu_pipeline *pipeline)
{
    if (!context || !pipeline)
        return;
    vkDestroyPipeline(context->device, pipeline->pipeline, NULL);
    vkDestroyPipelineLayout(context->device, pipeline->layout, NULL);
    vkDestroyDescriptorSetLayout(context->device, pipeline->set_layout, NULL);
    *pipeline = (gpu_pipeline){0};
}

/* ---- Recording and running ---- */

int gpu_begin(gpu_context *context)
{
    if (context->recording)
        return IM_OK;
    VkCommandBufferBeginInfo info = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                     .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    VK_CHECK(vkBeginCommandBuffer(context->commands, &info));
    context->recording = 1;
    gpu_profile_begin(context->profile, context->commands);
    return IM_OK;
}

void gpu_defer_failure(gpu_context *context, int status)
{
    if (context->deferred_status != IM_OK || status == IM_OK)
        return;
    context->deferred_status = status;
    snprintf(context->deferred_error, sizeof context->deferred_error, "%s", im_last_error());
}

/* Whether to record: gpu_dispatch and gpu_barrier return nothing, so a failure to begin is kept
 * for gpu_submit_wait, and nothing is recorded after a failure. */
static int recording(gpu_context *context)
{
    if (context->deferred_status != IM_OK)
        return 0;
    gpu_defer_failure(context, gpu_begin(context));
    return context->deferred_status == IM_OK;
}

VkCommandBuffer gpu_command_buffer(gpu_context *context)
{
    return recording(context) ? context->commands : VK_NULL_HANDLE;
}

void gpu_barrier(gpu_context *context)
{
    if (!recording(context))
        return;
    const VkPipelineStageFlags stages = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
    VkMemoryBarrier barrier = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                               .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                               .dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                                                VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT};
    vkCmdPipelineBarrier(context->commands, stages, stages, 0, 1, &barrier, 0, NULL, 0, NULL);
}

void gpu_zero(gpu_context *context, gpu_buffer *buffer)
{
    if (!recording(context))
        return;
    for (uint32_t k = 0; k < buffer->parts; ++k)
        vkCmdFillBuffer(context->commands, buffer->part[k], 0, VK_WHOLE_SIZE, 0);
    gpu_barrier(context);
    gpu_mark(context, "zero");
}

void gpu_mark(gpu_context *context, const char *label)
{
    if (recording(context))
        gpu_profile_mark(context->profile, context->commands, label);
}

/* A field binding's descriptors: chunk j is the part holding bytes j C .. (j + 1) C (C, a power of
 * two, divides the part size), the last chunk repeated up to GPU_MAX_CHUNKS (the shader never reads
 * past a field's end, but every element of a bound array must be valid). */
static uint32_t describe_binding(const gpu_context *context, const gpu_buffer *buffer, int field,
                                 VkDescriptorBufferInfo *infos)
{
    if (!field) {
        infos[0] = (VkDescriptorBufferInfo){.buffer = buffer->part[0], .offset = 0, .range = VK_WHOLE_SIZE};
        return 1;
    }
    const VkDeviceSize chunk = context->chunk_bytes, last = (buffer->bytes - 1) / chunk;
    for (uint32_t j = 0; j < GPU_MAX_CHUNKS; ++j) {
        const VkDeviceSize start = (j < last ? j : last) * chunk, in_part = start % buffer->part_bytes;
        const VkDeviceSize rest = buffer->part_bytes - in_part;
        infos[j] = (VkDescriptorBufferInfo){.buffer = buffer->part[start / buffer->part_bytes],
                                            .offset = in_part,
                                            .range = rest <= chunk ? VK_WHOLE_SIZE : chunk};
    }
    return GPU_MAX_CHUNKS;
}

void gpu_dispatch(gpu_context *context, const gpu_pipeline *pipeline, const gpu_buffer *const *buffers,
                  const void *push, uint32_t groups)
{
    if (!recording(context))
        return;
    VkDescriptorBufferInfo infos[MAX_DESCRIPTORS];
    VkWriteDescriptorSet writes[MAX_BINDINGS];
    uint32_t used = 0;
    for (uint32_t k = 0; k < pipeline->bindings; ++k) {
        if (k >= pipeline->fields && buffers[k]->bytes > context->chunk_bytes) {
            gpu_defer_failure(context,
                              im_fail(IM_EINVAL, "GPU dispatch (%s): binding %u takes one chunk, given %llu bytes",
                                      pipeline->label ? pipeline->label : "dispatch", k,
                                      (unsigned long long)buffers[k]->bytes));
            return;
        }
        const uint32_t count = describe_binding(context, buffers[k], k < pipeline->fields, infos + used);
        writes[k] = (VkWriteDescriptorSet){.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                                           .dstBinding = k,
                                           .descriptorCount = count,
                                           .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                           .pBufferInfo = infos + used};
        used += count;
    }
    vkCmdBindPipeline(context->commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline->pipeline);
    context->push_descriptor_set(context->commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline->layout, 0,
                                 pipeline->bindings, writes);
    if (pipeline->push_bytes)
        vkCmdPushConstants(context->commands, pipeline->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, pipeline->push_bytes,
                           push);
    vkCmdDispatch(context->commands, groups, 1, 1);
    gpu_barrier(context);
    gpu_mark(context, pipeline->label ? pipeline->label : "dispatch");
}

/* After a failed submission the command buffer is reset, so the next gpu_begin starts afresh. */
/* The device's writes made visible to the host before the fence: the reductions' results are read
 * through a mapped buffer right after the wait. */
static void host_read_barrier(gpu_context *context)
{
    VkMemoryBarrier barrier = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                               .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                               .dstAccessMask = VK_ACCESS_HOST_READ_BIT};
    vkCmdPipelineBarrier(context->commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0, NULL, 0, NULL);
}

/* A blocking wait returned about 100 us after the device's work ended on an H200 (the profile's
 * submissions waited 0.17 s more than the device's span over 1699 submissions), and a solve waits
 * about five times an iteration; polling the fence first returns within microseconds. The poll
 * stops after FENCE_POLL_SECONDS from the submission, so long work is waited for by blocking. */
static const double FENCE_POLL_SECONDS = 2e-3;

static VkResult wait_for_fence(gpu_context *context, double submitted)
{
    VkResult result = VK_NOT_READY;
    /* a CPU device (lavapipe) works on the host's cores: polling would take one from it */
    while (!context->software && (result = vkGetFenceStatus(context->device, context->fence)) == VK_NOT_READY &&
           seconds_now() - submitted < FENCE_POLL_SECONDS)
        continue;
    return result == VK_NOT_READY ? vkWaitForFences(context->device, 1, &context->fence, VK_TRUE, UINT64_MAX)
                                  : result;
}

static int end_submit_wait(gpu_context *context)
{
    host_read_barrier(context);
    VK_CHECK(vkEndCommandBuffer(context->commands));
    VkSubmitInfo submit = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
                           .commandBufferCount = 1,
                           .pCommandBuffers = &context->commands};
    const double start = seconds_now();
    VK_CHECK(vkQueueSubmit(context->queue, 1, &submit, context->fence));
    ++context->submissions;
    VK_CHECK(wait_for_fence(context, start));
    const double waited = seconds_now() - start;
    VK_CHECK(vkResetFences(context->device, 1, &context->fence));
    gpu_profile_collect(context->profile, waited);
    return IM_OK;
}

int gpu_submit_wait(gpu_context *context)
{
    int status = context->deferred_status;
    context->deferred_status = IM_OK;
    if (status != IM_OK)
        im_fail(status, "%s", context->deferred_error);
    else if (context->recording)
        status = end_submit_wait(context);
    if (context->recording)
        vkResetCommandBuffer(context->commands, 0);
    context->recording = 0;
    return status;
}
