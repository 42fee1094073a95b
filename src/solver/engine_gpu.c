/* The GPU engine of the Polonsky-Keer iteration (engine.h): the fields live on a Vulkan device for
 * the whole solve, each pass is one compute shader (shaders/compute/), the convolutions are VkFFT
 * transforms in double precision (gpu/fft.c), and every sum is an ordered two-stage reduction
 * (reduce.glsl) whose few values are all that comes back to the host per pass. Passes without a
 * result are only recorded; a pass with one submits what was recorded and waits for it.
 *
 * Fewer waits (docs/solver.md, "Host round trips"): a pass that returns sums also
 * sums what a later pass would, in the same order (the same bits), and keeps it until a pass writes
 * the fields those sums read: update_pressure the summary of p (impose_load's pressure sum, the
 * solve's summary), precondition <g, z> (precondition_centre's result when the mean is 0: no pass),
 * and under displacement control update_pressure records the next gaps pass in its own submission
 * when the step before changed no patch beyond the plain step (then the next gaps are at the same
 * approach, on the p and u it leaves); when this step did change some, those gaps are dropped.
 * winkler_loads sums the local guess at the 7 midpoints of three bisection steps in one pass.
 *
 * The plan made on the CPU (plan.c) gives the kernel's spectrum, the preconditioner's and K(0), so
 * both engines convolve with the same numbers; the GPU keeps its own copies (the host keeps K(0)). In
 * the periodic mode the preconditioner's spectrum is derived on the device from the kernel's
 * (multiply.comp), within an ulp of the CPU's, not to the bit.
 * Coarse cascade levels share their finest plan's device and pipelines, and its work buffers.
 *
 * Device memory (solver_buffers, docs/solver.md): five fields of nx x ny (gap0, p, u, g, t), z and
 * the transform grid `real` (each as large as the modes, as VkFFT binds them), one modes buffer that
 * the kernel's transform and the preconditioner's share, and VkFFT's scratch (its four-step
 * reordering, as large as the modes): z during the kernel's periodic transforms and `real` during
 * the preconditioner's (each idle then: z holds the masked g from gaps to precondition and M g from
 * there to direction only, and `real` holds K t from convolve_direction to update_pressure only,
 * overwritten before it is read again),
 * a buffer of its own on the padded grid. Then the tables: the spectrum, the preconditioner's
 * (derived from the spectrum in the periodic mode, where M is K's inverse: multiply.comp), and K for
 * the direct sums (not in the periodic mode, where a pair costs about as much as 1.1 log2(nx ny)
 * direct sums: direct_limit). A coarse level has only its own tables: its fields are the finest
 * level's, idle while the cascade start solves the coarse levels before the fine solve begins. */
#include "solver/engine.h"

#include "gpu/vulkan.h"
#include "indentmap/status.h"

#include "spirv/clip.h"
#include "spirv/contact_mean.h"
#include "spirv/direction.h"
#include "spirv/gaps.h"
#include "spirv/load_split.h"
#include "spirv/multiply.h"
#include "spirv/pad.h"
#include "spirv/point_loads.h"
#include "spirv/precondition_centre.h"
#include "spirv/precondition_mask.h"
#include "spirv/precondition_restrict.h"
#include "spirv/prolong.h"
#include "spirv/reduce_finish.h"
#include "spirv/scale.h"
#include "spirv/scale_elastic.h"
#include "spirv/step.h"
#include "spirv/summary.h"
#include "spirv/unpad.h"
#include "spirv/update_pressure.h"
#include "spirv/winkler.h"
#include "spirv/winkler_loads.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- push constants: each mirrors its shader's block (std430: the doubles first) ---- */
typedef struct {
    uint32_t nx, ny, px, py;
} push_grid;
typedef struct {
    uint32_t count;
} push_count;
typedef struct {
    double scale; /* invert: the spectrum's product with its inverse (1 / (nx ny)^2) */
    uint32_t count, invert;
} push_multiply;
typedef struct {
    double value;
    uint32_t n;
} push_value;
typedef struct {
    double a, b;
    uint32_t n, flag;
} push_pair;
typedef struct {
    double cap, p_factor, u_factor;
    uint32_t n;
} push_rescaled_mean;
typedef struct {
    double a, b;
    uint32_t nx, ny, px, join;
} push_update; /* a = tau, b = cap */
typedef struct {
    double beta, cap;
    uint32_t nx, ny, px, py, join;
} push_direction;
typedef struct {
    double cap;
    uint32_t nx, ny, px, join;
} push_step;
typedef struct {
    uint32_t n, join;
} push_set;
typedef struct {
    double w[SOLVER_WINKLER_BATCH], k0;
    uint32_t n;
} push_loads;
typedef struct {
    double value;
    uint32_t n, join;
} push_value_set;
typedef struct {
    uint32_t groups, slots, max_slots;
} push_finish;
typedef struct {
    uint32_t nx, ny, count;
} push_point_loads;
typedef struct {
    uint32_t nx, ny, cx; /* cx: the coarse level's row length */
} push_prolong;

enum kernel {
    K_PAD,
    K_UNPAD,
    K_MULTIPLY,
    K_CONTACT_MEAN,
    K_GAPS,
    K_WINKLER,
    K_WINKLER_LOADS,
    K_CLIP,
    K_LOAD_SPLIT,
    K_SCALE_ELASTIC,
    K_SUMMARY,
    K_SCALE,
    K_DIRECTION,
    K_PRECONDITION_MASK,
    K_PRECONDITION_RESTRICT,
    K_PRECONDITION_CENTRE,
    K_STEP,
    K_UPDATE_PRESSURE,
    K_POINT_LOADS,
    K_PROLONG,
    K_REDUCE_FINISH,
    K_COUNT
};

static const struct kernel_source {
    const uint32_t *code;
    size_t bytes;
    uint32_t bindings, fields, push_bytes; /* bindings 0 .. fields - 1: chunked fields (chunks.glsl) */
    const char *label;                     /* its name in a GPU profile */
} KERNELS[K_COUNT] = {
#define KERNEL(id, name, bindings, fields, push) [id] = {name, sizeof name, bindings, fields, sizeof(push), #name + 6}
    KERNEL(K_PAD, spirv_pad, 2, 2, push_grid),
    KERNEL(K_UNPAD, spirv_unpad, 2, 2, push_grid),
    KERNEL(K_MULTIPLY, spirv_multiply, 2, 2, push_multiply),
    KERNEL(K_CONTACT_MEAN, spirv_contact_mean, 4, 3, push_rescaled_mean),
    KERNEL(K_GAPS, spirv_gaps, 6, 5, push_pair),
    KERNEL(K_WINKLER, spirv_winkler, 3, 2, push_pair),
    KERNEL(K_WINKLER_LOADS, spirv_winkler_loads, 2, 1, push_loads),
    KERNEL(K_CLIP, spirv_clip, 1, 1, push_value),
    KERNEL(K_LOAD_SPLIT, spirv_load_split, 2, 1, push_pair),
    KERNEL(K_SCALE_ELASTIC, spirv_scale_elastic, 2, 1, push_pair),
    KERNEL(K_SUMMARY, spirv_summary, 2, 1, push_count),
    KERNEL(K_SCALE, spirv_scale, 1, 1, push_value),
    KERNEL(K_DIRECTION, spirv_direction, 5, 5, push_direction),
    KERNEL(K_PRECONDITION_MASK, spirv_precondition_mask, 3, 3, push_set),
    KERNEL(K_PRECONDITION_RESTRICT, spirv_precondition_restrict, 4, 3, push_set),
    KERNEL(K_PRECONDITION_CENTRE, spirv_precondition_centre, 4, 3, push_value_set),
    KERNEL(K_STEP, spirv_step, 5, 4, push_step),
    KERNEL(K_UPDATE_PRESSURE, spirv_update_pressure, 9, 5, push_update),
    KERNEL(K_POINT_LOADS, spirv_point_loads, 4, 2, push_point_loads),
    KERNEL(K_PROLONG, spirv_prolong, 3, 3, push_prolong),
    KERNEL(K_REDUCE_FINISH, spirv_reduce_finish, 2, 0, push_finish),
#undef KERNEL
};

/* A reduction runs at most this many workgroups (reduce_finish.comp folds their partials), and
 * carries at most this many values. */
enum { REDUCE_GROUPS = 1024, REDUCE_SLOTS = 8, GROUP_SIZE = 256, MAX_GROUPS = 65535 };
/* update_pressure's slots: its own two, then the summary's three (summary.comp's order) */
enum { SUMMARY_SLOTS = 3, UPDATE_SLOTS = 2 + SUMMARY_SLOTS };
/* The change list's room (shaders/compute/point_loads.glsl: CHANGE_CAPACITY). */
enum { CHANGE_CAPACITY = 256 };
/* The reductions' partial sums on the device (gpu_device.partials). */
static const VkDeviceSize PARTIAL_BYTES = sizeof(double) * REDUCE_GROUPS * REDUCE_SLOTS;

/* What the plans of one solver (its cascade levels) share: one device, its pipelines, and the
 * buffers of the reductions. */
typedef struct gpu_device {
    gpu_context *context;
    gpu_pipeline kernels[K_COUNT];
    gpu_buffer partials, result; /* result: host-visible */
    gpu_buffer ahead;            /* host-visible: the gaps pass recorded ahead (update_pressure) */
    VkDeviceSize fields_bytes;   /* what the plans' buffers and partials occupy (solver_footprint) */
    int references;
} gpu_device;

struct gpu_solver {
    gpu_device *device;
    gpu_buffer gap0, p, u, g, t, z;   /* nx x ny */
    gpu_buffer real, modes, spectrum; /* the px x py transform grid and its modes */
    gpu_buffer scratch;               /* VkFFT's own work (the padded grid; periodic: none) */
    gpu_buffer inverse_spectrum;      /* the preconditioner's (not periodic) */
    gpu_buffer kernel;                /* nx x ny: K at offset (|dx|, |dy|), for direct sums (not periodic) */
    gpu_buffer change_count, change_index, change_value; /* update_pressure's changes */
    gpu_fft *fft, *precondition_fft;
    uint32_t nx, ny, px, py;
    int periodic;
    int borrowed;           /* its work buffers are its finest level's (not freed here) */
    VkDeviceSize footprint; /* its share of device->fields_bytes */
    /* Sums kept from a pass for a later one (the header's "Fewer waits"); each valid while its flag is
     * set, cleared by any pass that writes what they read (wrote_pressure, wrote_fields). */
    int summary_kept, gz_kept, gaps_kept, step_changed; /* step_changed: the last update's changes */
    double summary[SUMMARY_SLOTS];                      /* sum of p, patches with p > 0, largest p */
    double gz;                                          /* <g, z> on the step's set */
    gap_stats gaps;                                     /* at gaps_w, gaps_cap */
    double gaps_w, gaps_cap;
};

/* ---- the device and its pipelines ---- */

static void device_release(gpu_device *d)
{
    if (!d || --d->references > 0)
        return;
    for (int k = 0; k < K_COUNT; ++k)
        gpu_pipeline_free(d->context, &d->kernels[k]);
    gpu_buffer_free(d->context, &d->partials);
    gpu_buffer_free(d->context, &d->result);
    gpu_buffer_free(d->context, &d->ahead);
    gpu_context_close(d->context);
    free(d);
}

static int device_open(const im_solver_options *o, gpu_device **out)
{
    *out = NULL;
    gpu_device *d = calloc(1, sizeof *d);
    if (!d)
        return im_fail(IM_ENOMEM, "GPU engine");
    d->references = 1;
    enum gpu_preference preference = o->device == IM_DEVICE_AUTO ? GPU_PREFER_HARDWARE : GPU_ANY;
    int status = gpu_context_open(preference, o->gpu_validation, &d->context);
    for (int k = 0; k < K_COUNT && status == IM_OK; ++k)
        status = gpu_pipeline_create(d->context, KERNELS[k].code, KERNELS[k].bytes, KERNELS[k].bindings,
                                     KERNELS[k].fields, KERNELS[k].push_bytes, &d->kernels[k]);
    for (int k = 0; k < K_COUNT && status == IM_OK; ++k)
        d->kernels[k].label = KERNELS[k].label;
    if (status == IM_OK) {
        status = gpu_buffer_create(d->context, PARTIAL_BYTES, GPU_DEVICE_LOCAL, &d->partials);
        d->fields_bytes = gpu_context_buffer_footprint(d->context, PARTIAL_BYTES);
    }
    if (status == IM_OK)
        status = gpu_buffer_create(d->context, sizeof(double) * REDUCE_SLOTS, GPU_HOST_READ, &d->result);
    if (status == IM_OK)
        status = gpu_buffer_create(d->context, sizeof(double) * REDUCE_SLOTS, GPU_HOST_READ, &d->ahead);
    if (status != IM_OK) {
        device_release(d);
        return status;
    }
    *out = d;
    return IM_OK;
}

/* ---- recording passes ---- */

static struct gpu_solver *solver_of(const pk_run *r) { return r->plan->gpu; }
static gpu_context *context_of(const struct gpu_solver *s) { return s->device->context; }
static uint32_t patches(const struct gpu_solver *s) { return s->nx * s->ny; }

static uint32_t groups_for(uint32_t count)
{
    uint32_t groups = (count + GROUP_SIZE - 1) / GROUP_SIZE;
    return groups < 1 ? 1 : (groups > MAX_GROUPS ? MAX_GROUPS : groups);
}

static uint32_t reduce_groups(uint32_t count)
{
    uint32_t groups = groups_for(count);
    return groups > REDUCE_GROUPS ? REDUCE_GROUPS : groups;
}

/* Records a pass over count elements (a grid-stride loop in the shader). */
static void record(struct gpu_solver *s, enum kernel k, const gpu_buffer *const *buffers, const void *push,
                   uint32_t count)
{
    gpu_begin(context_of(s));
    gpu_dispatch(context_of(s), &s->device->kernels[k], buffers, push, groups_for(count));
}

/* Records a reducing pass over count elements and its finish, which leaves its slots' values in the
 * host-visible buffer into; a failure to begin recording as gpu_begin's. */
static int record_reduction(struct gpu_solver *s, enum kernel k, const gpu_buffer *const *buffers, const void *push,
                            uint32_t count, uint32_t slots, uint32_t max_slots, const gpu_buffer *into)
{
    gpu_context *c = context_of(s);
    const push_finish finish = {.groups = reduce_groups(count), .slots = slots, .max_slots = max_slots};
    const gpu_buffer *folded[2] = {&s->device->partials, into};
    int status = gpu_begin(c);
    if (status == IM_OK) {
        gpu_dispatch(c, &s->device->kernels[k], buffers, push, finish.groups);
        gpu_dispatch(c, &s->device->kernels[K_REDUCE_FINISH], folded, &finish, 1);
    }
    return status;
}

/* Reads slots values of a host-visible result buffer into out after a submission of status (NaN
 * after a failure, which r->status keeps). */
static void read_result(pk_run *r, int status, const gpu_buffer *from, uint32_t slots, double *out)
{
    if (status != IM_OK && r->status == IM_OK)
        r->status = status;
    for (uint32_t j = 0; j < slots; ++j)
        out[j] = status == IM_OK ? ((const double *)from->mapped)[j] : NAN;
}

/* Records a reducing pass, runs everything recorded, and reads its slots' values into out. */
static void reduce(pk_run *r, enum kernel k, const gpu_buffer *const *buffers, const void *push, uint32_t count,
                   uint32_t slots, uint32_t max_slots, double *out)
{
    struct gpu_solver *s = solver_of(r);
    int status = record_reduction(s, k, buffers, push, count, slots, max_slots, &s->device->result);
    read_result(r, status == IM_OK ? gpu_submit_wait(context_of(s)) : status, &s->device->result, slots, out);
}

/* What a pass that writes p (and perhaps u, g, z, gap0) leaves of the kept sums: none. */
static void wrote_pressure(struct gpu_solver *s) { s->summary_kept = s->gz_kept = s->gaps_kept = 0; }

/* What a pass that writes u, g or z but not p leaves of them: the summary of p. */
static void wrote_fields(struct gpu_solver *s) { s->gz_kept = s->gaps_kept = 0; }

/* Runs what is recorded (passes without a result), keeping a failure in r->status. */
static void flush(pk_run *r)
{
    int status = gpu_submit_wait(context_of(solver_of(r)));
    if (status != IM_OK && r->status == IM_OK)
        r->status = status;
}

/* K x of the transform grid `real` (filled by the caller), left there: R2C, times the spectrum, C2R. */
static void convolve_real(struct gpu_solver *s)
{
    const gpu_buffer *multiply[2] = {&s->modes, &s->spectrum};
    const push_multiply modes = {.count = s->py * (s->px / 2 + 1)};
    gpu_fft_forward(context_of(s), s->fft);
    record(s, K_MULTIPLY, multiply, &modes, modes.count);
    gpu_fft_inverse(context_of(s), s->fft);
}

/* u = K p on the device */
static void record_convolution(struct gpu_solver *s)
{
    const push_grid grid = {.nx = s->nx, .ny = s->ny, .px = s->px, .py = s->py};
    const gpu_buffer *pad[2] = {&s->p, &s->real}, *unpad[2] = {&s->real, &s->u};
    record(s, K_PAD, pad, &grid, s->px * s->py);
    convolve_real(s);
    record(s, K_UNPAD, unpad, &grid, patches(s));
}

/* ---- the engine's passes ---- */

/* p = the coarse level's answer, which its solve left at the start of p (a coarse level's fields are
 * these buffers), prolonged into g and copied to p (unpad over the same grid). */
static void record_prolongation(struct gpu_solver *s, const im_solver_plan *coarse)
{
    const push_prolong prolong = {.nx = s->nx, .ny = s->ny, .cx = (uint32_t)coarse->nx};
    const push_grid copy = {.nx = s->nx, .ny = s->ny, .px = s->nx, .py = s->ny};
    const gpu_buffer *to_g[3] = {&s->gap0, &s->p, &s->g}, *to_p[2] = {&s->g, &s->p};
    record(s, K_PROLONG, to_g, &prolong, patches(s));
    record(s, K_UNPAD, to_p, &copy, patches(s));
}

/* gap0 up, and p up or, from a cascade's coarse level, prolonged on the device (pk_run.start_prolonged). */
static int gpu_engine_begin(pk_run *r)
{
    struct gpu_solver *s = solver_of(r);
    const VkDeviceSize bytes = sizeof(double) * patches(s);
    const int prolong = r->start_prolonged;
    r->start_prolonged = 0; /* a later begin (a search's next trial) starts from the p it returned */
    wrote_pressure(s);
    s->step_changed = 1; /* no gaps ahead of the first step */
    int status = gpu_buffer_upload(context_of(s), &s->gap0, 0, r->gap0, bytes);
    if (status == IM_OK && !prolong)
        status = gpu_buffer_upload(context_of(s), &s->p, 0, r->p, bytes);
    if (status == IM_OK) /* t is read (times beta = 0) before it is first written, and the coarse levels' */
        status = gpu_begin(context_of(s)); /* solves, which share it, may leave anything there */
    if (status == IM_OK && prolong)
        record_prolongation(s, r->plan->coarse);
    if (status == IM_OK)
        gpu_zero(context_of(s), &s->t);
    return status == IM_OK ? IM_OK : im_fail_context(status, "GPU solve %u x %u", s->nx, s->ny);
}

/* p and u back to the caller, except from a cascade's coarse level whose finer level prolongs p here. */
static int gpu_engine_finish(pk_run *r)
{
    struct gpu_solver *s = solver_of(r);
    const VkDeviceSize bytes = sizeof(double) * patches(s);
    flush(r);
    if (r->keep_answer)
        return IM_OK;
    int status = gpu_buffer_download(context_of(s), &s->p, 0, r->p, bytes);
    if (status == IM_OK)
        status = gpu_buffer_download(context_of(s), &s->u, 0, r->u, bytes);
    return status == IM_OK ? IM_OK : im_fail_context(status, "GPU solve %u x %u", s->nx, s->ny);
}

static void gpu_engine_convolve_pressure(pk_run *r)
{
    wrote_fields(solver_of(r));
    record_convolution(solver_of(r));
}

static void gpu_engine_convolve_direction(pk_run *r) { convolve_real(solver_of(r)); }

static double gpu_engine_contact_mean(pk_run *r, double p_factor, double u_factor, double cap, long *count)
{
    struct gpu_solver *s = solver_of(r);
    const gpu_buffer *b[4] = {&s->p, &s->u, &s->gap0, &s->device->partials};
    const push_rescaled_mean push = {.cap = cap, .p_factor = p_factor, .u_factor = u_factor, .n = patches(s)};
    double v[2];
    wrote_pressure(s);
    reduce(r, K_CONTACT_MEAN, b, &push, push.n, 2, 0, v);
    *count = (long)v[1];
    return v[1] > 0 ? v[0] / v[1] : 0;
}

enum { GAPS_SLOTS = 5 };

/* Records the gaps pass at approach w, its sums into the host-visible buffer into. */
static int record_gaps(pk_run *r, double w, double cap, const gpu_buffer *into)
{
    struct gpu_solver *s = solver_of(r);
    const gpu_buffer *b[6] = {&s->p, &s->u, &s->gap0, &s->g, &s->z, &s->device->partials};
    const push_pair push = {.a = w, .b = cap, .n = patches(s), .flag = r->plan->options.precondition != 0};
    return record_reduction(s, K_GAPS, b, &push, push.n, GAPS_SLOTS, 1u << 3, into);
}

static gap_stats gap_stats_of(const double v[GAPS_SLOTS])
{
    return (gap_stats){.sum_squares = v[0],
                       .contact = (long)v[1],
                       .moving_squares = v[2],
                       .penetration = v[3],
                       .penetration_squares = v[4]};
}

static gap_stats gpu_engine_gaps(pk_run *r, double w, double cap)
{
    struct gpu_solver *s = solver_of(r);
    if (s->gaps_kept && s->gaps_w == w && s->gaps_cap == cap) { /* recorded ahead by update_pressure */
        s->gaps_kept = 0;
        return s->gaps;
    }
    wrote_fields(s);
    double v[GAPS_SLOTS];
    const int status = record_gaps(r, w, cap, &s->device->result);
    read_result(r, status == IM_OK ? gpu_submit_wait(context_of(s)) : status, &s->device->result, GAPS_SLOTS, v);
    return gap_stats_of(v);
}

static double gpu_engine_winkler(pk_run *r, double w, double k0, int store)
{
    struct gpu_solver *s = solver_of(r);
    const gpu_buffer *b[3] = {&s->gap0, &s->p, &s->device->partials};
    const push_pair push = {.a = w, .b = k0, .n = patches(s), .flag = store != 0};
    double sum;
    wrote_pressure(s);
    reduce(r, K_WINKLER, b, &push, push.n, 1, 0, &sum);
    return sum * r->plan->delta * r->plan->delta;
}

static void gpu_engine_winkler_loads(pk_run *r, const double *w, int count, double k0, double *loads)
{
    struct gpu_solver *s = solver_of(r);
    const gpu_buffer *b[2] = {&s->gap0, &s->device->partials};
    push_loads push = {.k0 = k0, .n = patches(s)}; /* the slots past count sum at w = 0: nothing */
    memcpy(push.w, w, sizeof(double) * (size_t)count);
    double v[SOLVER_WINKLER_BATCH];
    reduce(r, K_WINKLER_LOADS, b, &push, push.n, SOLVER_WINKLER_BATCH, 0, v);
    for (int k = 0; k < count; ++k)
        loads[k] = v[k] * r->plan->delta * r->plan->delta;
}

static void gpu_engine_clip(pk_run *r, double cap)
{
    struct gpu_solver *s = solver_of(r);
    const gpu_buffer *b[1] = {&s->p};
    const push_value push = {.value = cap, .n = patches(s)};
    wrote_pressure(s);
    record(s, K_CLIP, b, &push, push.n);
}

static void gpu_engine_summary(pk_run *r, double *sum, long *contact, double *peak)
{
    struct gpu_solver *s = solver_of(r);
    const gpu_buffer *b[2] = {&s->p, &s->device->partials};
    const push_count push = {.count = patches(s)};
    double v[SUMMARY_SLOTS];
    if (s->summary_kept) /* summed by update_pressure, in this pass's order */
        memcpy(v, s->summary, sizeof v);
    else
        reduce(r, K_SUMMARY, b, &push, push.count, SUMMARY_SLOTS, 1u << 2, v);
    *sum = v[0];
    *contact = (long)v[1];
    *peak = v[2];
}

static int gpu_engine_any_positive(pk_run *r)
{
    double sum, peak;
    long contact;
    gpu_engine_summary(r, &sum, &contact, &peak);
    return contact > 0;
}

static void gpu_engine_load_split(pk_run *r, double cap, double *elastic, double *capped)
{
    struct gpu_solver *s = solver_of(r);
    const gpu_buffer *b[2] = {&s->p, &s->device->partials};
    const push_pair push = {.a = cap, .b = r->plan->delta * r->plan->delta, .n = patches(s)};
    double v[2];
    reduce(r, K_LOAD_SPLIT, b, &push, push.n, 2, 0, v);
    *elastic = v[0];
    *capped = v[1];
}

static int gpu_engine_scale_elastic(pk_run *r, double scale, double cap)
{
    struct gpu_solver *s = solver_of(r);
    const gpu_buffer *b[2] = {&s->p, &s->device->partials};
    const push_pair push = {.a = scale, .b = cap, .n = patches(s)};
    double clipped;
    wrote_pressure(s);
    reduce(r, K_SCALE_ELASTIC, b, &push, push.n, 1, 1, &clipped);
    return clipped > 0;
}

static double gpu_engine_pressure_sum(pk_run *r)
{
    double sum, peak;
    long contact;
    gpu_engine_summary(r, &sum, &contact, &peak);
    return sum;
}

static void gpu_engine_scale(pk_run *r, double p_factor, double u_factor)
{
    struct gpu_solver *s = solver_of(r);
    const gpu_buffer *p[1] = {&s->p}, *u[1] = {&s->u};
    const push_value scale_p = {.value = p_factor, .n = patches(s)}, scale_u = {.value = u_factor, .n = patches(s)};
    wrote_pressure(s);
    if (p_factor != 1)
        record(s, K_SCALE, p, &scale_p, scale_p.n);
    if (u_factor != 1)
        record(s, K_SCALE, u, &scale_u, scale_u.n);
}

static void gpu_engine_direction(pk_run *r, int preconditioned, double beta, double cap)
{
    struct gpu_solver *s = solver_of(r);
    const gpu_buffer *b[5] = {&s->p, &s->g, preconditioned ? &s->z : &s->g, &s->t, &s->real};
    const push_direction push =
        {.beta = beta, .cap = cap, .nx = s->nx, .ny = s->ny, .px = s->px, .py = s->py, .join = r->join};
    record(s, K_DIRECTION, b, &push, s->px * s->py);
}

static double gpu_engine_precondition(pk_run *r, long *count)
{
    struct gpu_solver *s = solver_of(r);
    const push_set set = {.n = patches(s), .join = r->join};
    const double n = (double)patches(s);
    const push_multiply modes = {.scale = 1 / (n * n), .count = s->ny * (s->nx / 2 + 1), .invert = s->periodic};
    const gpu_buffer *mask[3] = {&s->p, &s->g, &s->z};
    const gpu_buffer *multiply[2] = {&s->modes, s->periodic ? &s->spectrum : &s->inverse_spectrum};
    const gpu_buffer *restrict_to_set[4] = {&s->p, &s->g, &s->z, &s->device->partials};
    wrote_fields(s);
    if (r->join != SOLVER_JOIN_NONE) /* without a join the gaps pass left this mask */
        record(s, K_PRECONDITION_MASK, mask, &set, set.n);
    gpu_fft_forward(context_of(s), s->precondition_fft);
    record(s, K_MULTIPLY, multiply, &modes, modes.count);
    gpu_fft_inverse(context_of(s), s->precondition_fft);
    double v[3];
    reduce(r, K_PRECONDITION_RESTRICT, restrict_to_set, &set, set.n, 3, 0, v);
    s->gz = v[2];
    s->gz_kept = r->status == IM_OK;
    *count = (long)v[1];
    return v[0];
}

static double gpu_engine_precondition_centre(pk_run *r, double mean)
{
    struct gpu_solver *s = solver_of(r);
    const gpu_buffer *b[4] = {&s->p, &s->g, &s->z, &s->device->partials};
    const push_value_set push = {.value = mean, .n = patches(s), .join = r->join};
    double gz = s->gz;
    if (s->gz_kept && mean == 0) { /* z - 0 is z: precondition summed <g, z> in this pass's order */
        s->gz_kept = 0;
        return gz;
    }
    wrote_fields(s);
    reduce(r, K_PRECONDITION_CENTRE, b, &push, push.n, 1, 0, &gz);
    return gz;
}

static step_terms gpu_engine_step(pk_run *r, double cap)
{
    struct gpu_solver *s = solver_of(r);
    const gpu_buffer *b[5] = {&s->p, &s->g, &s->t, &s->real, &s->device->partials};
    const push_step push = {.cap = cap, .nx = s->nx, .ny = s->ny, .px = s->px, .join = r->join};
    double v[5];
    reduce(r, K_STEP, b, &push, patches(s), 5, 0, v);
    return (step_terms){.gt = v[0], .kt_t = v[1], .kt_sum = v[2], .t_sum = v[3], .count = (long)v[4]};
}

static long gpu_engine_update_pressure(pk_run *r, double tau, double cap, int *joined)
{
    struct gpu_solver *s = solver_of(r);
    const gpu_buffer *b[9] = {
        &s->p,           &s->u, &s->g, &s->t, &s->real, &s->device->partials, &s->change_count, &s->change_index,
        &s->change_value};
    const push_update push = {.a = tau, .b = cap, .nx = s->nx, .ny = s->ny, .px = s->px, .join = r->join};
    /* the next gaps, when this step is likely to leave p and u to them as it does (the last changed none) */
    const int ahead = r->control == IM_CONTROL_DISPLACEMENT && !s->step_changed;
    double v[UPDATE_SLOTS], gaps[GAPS_SLOTS];
    wrote_pressure(s);
    gpu_zero(context_of(s), &s->change_count);
    int status = record_reduction(s, K_UPDATE_PRESSURE, b, &push, patches(s), UPDATE_SLOTS, 1u << 1 | 1u << 4,
                                  &s->device->result);
    if (status == IM_OK && ahead)
        status = record_gaps(r, r->target, cap, &s->device->ahead);
    if (status == IM_OK)
        status = gpu_submit_wait(context_of(s));
    read_result(r, status, &s->device->result, UPDATE_SLOTS, v);
    s->step_changed = v[0] != 0;
    s->summary_kept = status == IM_OK;
    memcpy(s->summary, v + 2, sizeof s->summary);
    s->gaps_kept = status == IM_OK && ahead && !s->step_changed; /* else u moves before the next gaps */
    if (s->gaps_kept) {
        read_result(r, status, &s->device->ahead, GAPS_SLOTS, gaps);
        s->gaps = gap_stats_of(gaps);
        s->gaps_w = r->target;
        s->gaps_cap = cap;
    }
    *joined = v[1] > 0;
    return (long)v[0];
}

/* u += K (the step's changes), summed on the device; pk.c calls it for at most the plan's direct
 * limit, within the list's room, and recomputes u by FFT beyond (the exact convolution, also here
 * should the list have overflowed). The sum runs on a fixed number of workgroups: each sorts the list. */
static void gpu_engine_add_point_loads(pk_run *r, long changes)
{
    struct gpu_solver *s = solver_of(r);
    if (changes > CHANGE_CAPACITY) {
        gpu_engine_convolve_pressure(r);
        return;
    }
    wrote_fields(s);
    const gpu_buffer *b[4] = {&s->u, &s->kernel, &s->change_index, &s->change_value};
    const push_point_loads push = {.nx = s->nx, .ny = s->ny, .count = (uint32_t)changes};
    gpu_begin(context_of(s));
    gpu_dispatch(context_of(s), &s->device->kernels[K_POINT_LOADS], b, &push, reduce_groups(patches(s)));
}

/* displacement = K pressure through the device; NaN everywhere when the device fails, so that a
 * failure is never read as a displacement. */
static int gpu_engine_convolve_arrays(im_solver_plan *plan, const double *pressure, double *displacement)
{
    struct gpu_solver *s = plan->gpu;
    const VkDeviceSize bytes = sizeof(double) * patches(s);
    wrote_pressure(s);
    int status = gpu_buffer_upload(context_of(s), &s->p, 0, pressure, bytes);
    if (status == IM_OK)
        status = gpu_begin(context_of(s));
    if (status == IM_OK) {
        record_convolution(s);
        status = gpu_submit_wait(context_of(s));
    }
    if (status == IM_OK)
        status = gpu_buffer_download(context_of(s), &s->u, 0, displacement, bytes);
    if (status != IM_OK)
        for (uint32_t i = 0; i < patches(s); ++i)
            displacement[i] = NAN;
    return status;
}

/* ---- making and freeing a plan's device state ---- */

enum { MAX_SOLVER_BUFFERS = 16 };

/* A buffer of a plan's device state: where it is, its size, and whether it is a work field (which a
 * coarse level borrows from its finest level) rather than a table of its own. */
typedef struct {
    gpu_buffer *buffer;
    VkDeviceSize bytes;
    int field;
} solver_buffer;

/* The buffers of a plan's device state (the header's list), in a fixed order. */
static size_t solver_buffers(struct gpu_solver *s, int precondition, solver_buffer *list)
{
    const VkDeviceSize d = sizeof(double), n = (VkDeviceSize)s->nx * s->ny;
    const VkDeviceSize modes = (VkDeviceSize)s->py * (s->px / 2 + 1), small = (VkDeviceSize)s->ny * (s->nx / 2 + 1);
    /* the transforms' real buffers hold as many bytes as their modes (gpu/vulkan.h: VkFFT binds them
     * so), and so does VkFFT's scratch; z is the kernel's periodic transforms' scratch */
    const VkDeviceSize transform = gpu_fft_modes_bytes((int)s->px, (int)s->py);
    const solver_buffer all[] = {{&s->gap0, d * n, 1},
                                 {&s->p, d * n, 1},
                                 {&s->u, d * n, 1},
                                 {&s->g, d * n, 1},
                                 {&s->t, d * n, 1},
                                 {&s->z, gpu_fft_modes_bytes((int)s->nx, (int)s->ny), 1},
                                 {&s->real, transform, 1},
                                 {&s->modes, transform, 1},
                                 {&s->scratch, s->periodic ? 0 : transform, 1},
                                 {&s->spectrum, d * modes, 0},
                                 {&s->kernel, s->periodic ? 0 : d * n, 0},
                                 {&s->change_count, 16, 0},
                                 {&s->change_index, sizeof(uint32_t) * CHANGE_CAPACITY, 0},
                                 {&s->change_value, d * CHANGE_CAPACITY, 0},
                                 {&s->inverse_spectrum, precondition && !s->periodic ? d * small : 0, 0}};
    size_t count = 0;
    for (size_t k = 0; k < sizeof all / sizeof *all; ++k)
        if (all[k].bytes > 0)
            list[count++] = all[k];
    return count;
}

/* The device memory a plan's own buffers occupy (whole parts; a coarse level's fields are its finest
 * level's). VkFFT's scratch is among them; its small twiddle tables are not. */
static VkDeviceSize solver_footprint(const gpu_context *c, struct gpu_solver *s, int precondition)
{
    solver_buffer list[MAX_SOLVER_BUFFERS];
    VkDeviceSize total = 0;
    const size_t count = solver_buffers(s, precondition, list);
    for (size_t k = 0; k < count; ++k)
        if (!(s->borrowed && list[k].field))
            total += gpu_context_buffer_footprint(c, list[k].bytes);
    return total;
}

/* What check_memory will have counted once a plan of nx x ny and its cascade levels are made: the
 * reductions' partials, then each level's solver_footprint, from buffer lists of levels not yet made. */
static VkDeviceSize plan_footprint(const gpu_context *c, int nx, int ny, const im_solver_options *o)
{
    VkDeviceSize total = gpu_context_buffer_footprint(c, PARTIAL_BYTES);
    const int pad = o->periodic ? 1 : 2;
    for (int borrowed = 0, more = 1; more; borrowed = 1) {
        struct gpu_solver level = {.nx = (uint32_t)nx,
                                   .ny = (uint32_t)ny,
                                   .px = (uint32_t)(pad * nx),
                                   .py = (uint32_t)(pad * ny),
                                   .periodic = o->periodic,
                                   .borrowed = borrowed};
        total += solver_footprint(c, &level, o->precondition);
        more = o->cascade && solver_cascade_sides(nx, ny, o->periodic, &nx, &ny);
    }
    return total;
}

static void gpu_engine_free(im_solver_plan *plan)
{
    struct gpu_solver *s = plan->gpu;
    if (!s)
        return;
    gpu_context *c = context_of(s);
    gpu_fft_free(s->fft);
    gpu_fft_free(s->precondition_fft);
    solver_buffer list[MAX_SOLVER_BUFFERS];
    const size_t count = solver_buffers(s, plan->options.precondition, list);
    for (size_t k = 0; k < count; ++k)
        if (!(s->borrowed && list[k].field))
            gpu_buffer_free(c, list[k].buffer);
    s->device->fields_bytes -= s->footprint;
    device_release(s->device);
    free(s);
    plan->gpu = NULL;
}

const solver_engine solver_engine_gpu = {
    .name = "gpu",
    .keeps_answers = 1,
    .begin = gpu_engine_begin,
    .finish = gpu_engine_finish,
    .convolve_pressure = gpu_engine_convolve_pressure,
    .convolve_direction = gpu_engine_convolve_direction,
    .contact_mean = gpu_engine_contact_mean,
    .gaps = gpu_engine_gaps,
    .winkler = gpu_engine_winkler,
    .winkler_loads = gpu_engine_winkler_loads,
    .clip = gpu_engine_clip,
    .any_positive = gpu_engine_any_positive,
    .load_split = gpu_engine_load_split,
    .scale_elastic = gpu_engine_scale_elastic,
    .pressure_sum = gpu_engine_pressure_sum,
    .scale = gpu_engine_scale,
    .direction = gpu_engine_direction,
    .precondition = gpu_engine_precondition,
    .precondition_centre = gpu_engine_precondition_centre,
    .step = gpu_engine_step,
    .update_pressure = gpu_engine_update_pressure,
    .add_point_loads = gpu_engine_add_point_loads,
    .summary = gpu_engine_summary,
    .convolve_arrays = gpu_engine_convolve_arrays,
    .free = gpu_engine_free,
};

/* What VkFFT and the shaders' 32-bit indices can take; IM_EUNSUPPORTED naming what cannot. */
/* A solver grid nx x ny whose transforms are px x py (nx x ny periodic, 2 nx x 2 ny padded) on context c. */
static int check_transform_grid(gpu_context *c, int nx, int ny, int px, int py)
{
    const int sides[2] = {nx, ny};
    for (int k = 0; k < 2; ++k)
        if (!gpu_fft_side_supported(sides[k]))
            return im_fail(IM_EUNSUPPORTED,
                           "GPU engine: solver grid %d x %d (transforms %d x %d): side %d has a prime factor above "
                           "13, which VkFFT does not transform exactly; use device = cpu, or a grid whose sides "
                           "factor into 2, 3, 5, 7, 11 and 13",
                           nx, ny, px, py, sides[k]);
    const double largest = (double)gpu_fft_modes_bytes(px, py);
    const double most = (double)GPU_MAX_CHUNKS * (double)gpu_context_chunk_bytes(c);
    if ((double)px * py >= 4294967296.0 || largest > most)
        return im_fail(IM_EUNSUPPORTED,
                       "GPU engine: solver grid %d x %d needs a %.0f MiB buffer; %s takes at most %.0f MiB per "
                       "buffer (%d chunks of %.0f MiB; use device = cpu, or a smaller grid)",
                       nx, ny, largest / 1048576.0, gpu_context_device_name(c), most / 1048576.0, GPU_MAX_CHUNKS,
                       (double)gpu_context_chunk_bytes(c) / 1048576.0);
    return IM_OK;
}

static int check_grid(const im_solver_plan *plan, const gpu_device *d)
{
    return check_transform_grid(d->context, plan->nx, plan->ny, plan->px, plan->py);
}

/* What the plan's transforms would meet when made (gpu_fft_create's refusal of buffers in parts
 * whose first axis takes one of VkFFT's uploads, known only once VkFFT plans it): judged before any
 * plan by the first axis' length (vulkan.h: GPU_PARTS_FIRST_AXIS), so that a grid the GPU may refuse
 * is estimated on the CPU (the larger plan). */
static int check_estimated_transforms(gpu_context *c, int nx, int ny, const im_solver_options *o)
{
    const int px = o->periodic ? nx : 2 * nx, py = o->periodic ? ny : 2 * ny;
    int status = check_transform_grid(c, nx, ny, px, py);
    if (status == IM_OK && gpu_fft_modes_bytes(px, py) > gpu_context_part_bytes(c) && px < GPU_PARTS_FIRST_AXIS)
        status = im_fail(IM_EUNSUPPORTED,
                         "GPU engine: solver grid %d x %d: its buffers exceed one storage buffer and its first "
                         "axis (%d) is shorter than VkFFT's several uploads need (%d)",
                         nx, ny, px, GPU_PARTS_FIRST_AXIS);
    return status;
}

static int zero_fields(struct gpu_solver *s)
{
    gpu_context *c = context_of(s);
    gpu_buffer *fields[] = {&s->p, &s->u, &s->g, &s->t, &s->z, &s->real};
    int status = gpu_begin(c);
    for (size_t k = 0; k < sizeof fields / sizeof *fields && status == IM_OK; ++k)
        gpu_zero(c, fields[k]);
    return status == IM_OK ? gpu_submit_wait(c) : status;
}

/* How many changes a step adds by direct summation rather than a new u = K p: a sum costs about one
 * read of the nx x ny kernel per change, an FFT pair about 1.1 px py log2(px py) / (nx ny) of them
 * (on an H200 a periodic 8192^2 pair with its pad, multiply and unpad took 3.4 ms, the padded pair of
 * a 4096^2 grid 3.2 ms, against 0.11 ms and 0.028 ms to read their kernels at 4.8 TB/s). */
static long direct_limit(const struct gpu_solver *s)
{
    const double transform = (double)s->px * s->py, ratio = transform / ((double)s->nx * s->ny);
    const long limit = (long)(1.1 * ratio * log2(transform));
    return limit < CHANGE_CAPACITY ? limit : CHANGE_CAPACITY;
}

static int upload_tables(const im_solver_plan *plan, struct gpu_solver *s)
{
    gpu_context *c = context_of(s);
    const VkDeviceSize d = sizeof(double), n = (VkDeviceSize)s->nx * s->ny;
    const VkDeviceSize modes = (VkDeviceSize)s->py * (s->px / 2 + 1), small = (VkDeviceSize)s->ny * (s->nx / 2 + 1);
    int status = gpu_buffer_upload(c, &s->spectrum, 0, plan->spectrum, d * modes);
    if (status == IM_OK && !s->periodic)
        status = gpu_buffer_upload(c, &s->kernel, 0, plan->kernel, d * n);
    if (status == IM_OK && plan->options.precondition && !s->periodic)
        status = gpu_buffer_upload(c, &s->inverse_spectrum, 0, plan->inverse_spectrum, d * small);
    return status;
}

/* A coarse level's work fields: its finest level's buffers (handles copied; the list's order is
 * the same on every level, and a coarser level needs no more of each than a finer one). */
static void borrow_fields(struct gpu_solver *s, struct gpu_solver *finer, int precondition)
{
    solver_buffer mine[MAX_SOLVER_BUFFERS], theirs[MAX_SOLVER_BUFFERS];
    const size_t count = solver_buffers(s, precondition, mine);
    solver_buffers(finer, precondition, theirs);
    for (size_t k = 0; k < count && mine[k].field; ++k)
        *mine[k].buffer = *theirs[k].buffer;
}

static int make_buffers(im_solver_plan *plan, struct gpu_solver *s)
{
    gpu_context *c = context_of(s);
    solver_buffer list[MAX_SOLVER_BUFFERS];
    const size_t count = solver_buffers(s, plan->options.precondition, list);
    int status = IM_OK;
    for (size_t k = 0; k < count && status == IM_OK; ++k)
        if (!(s->borrowed && list[k].field))
            status = gpu_buffer_create(c, list[k].bytes, GPU_DEVICE_LOCAL, list[k].buffer);
    if (status == IM_OK)
        status = upload_tables(plan, s);
    if (status == IM_OK)
        status = zero_fields(s); /* t is read (times beta = 0) before it is first written */
    /* VkFFT's scratch: its own on the padded grid; periodic, z for the kernel's transform and the
     * transform grid for the preconditioner's (the header says why each is idle then) */
    if (status == IM_OK)
        status = gpu_fft_create(c, (int)s->px, (int)s->py, &s->real, &s->modes, s->periodic ? &s->z : &s->scratch,
                                &s->fft);
    if (status == IM_OK && plan->options.precondition)
        status = gpu_fft_create(c, (int)s->nx, (int)s->ny, &s->z, &s->modes, s->periodic ? &s->real : &s->scratch,
                                &s->precondition_fft);
    return status;
}

/* Refuses, before allocating, a plan whose buffers with those of its finer levels exceed the
 * device's memory: IM_ENOMEM, as im_solver_memory_needed's estimate and a failed device allocation
 * (device = auto then solves on the CPU). */
static int check_memory(const im_solver_plan *plan, struct gpu_solver *s)
{
    gpu_device *d = s->device;
    const VkDeviceSize needed = solver_footprint(d->context, s, plan->options.precondition);
    const VkDeviceSize available = gpu_context_device_bytes(d->context);
    if (d->fields_bytes + needed <= available) {
        d->fields_bytes += s->footprint = needed;
        return IM_OK;
    }
    return im_fail(IM_ENOMEM,
                   "GPU engine: solver grid %d x %d needs %.2f GiB of device memory for its fields (%.2f GiB with "
                   "its finer cascade levels), and %s has %.2f GiB (use device = cpu, or a smaller grid)",
                   plan->nx, plan->ny, (double)needed / 1073741824.0,
                   (double)(d->fields_bytes + needed) / 1073741824.0, gpu_context_device_name(d->context),
                   (double)available / 1073741824.0);
}

int solver_engine_gpu_attach(im_solver_plan *plan, const im_solver_plan *finer)
{
    gpu_device *device = NULL;
    int status = IM_OK;
    if (finer) {
        device = finer->gpu->device;
        ++device->references;
    } else if ((status = device_open(&plan->options, &device)) != IM_OK)
        return status;
    else /* the top plan's fields are the largest a solve copies: no staging grows level by level */
        status = gpu_context_reserve_staging(device->context, sizeof(double) * (VkDeviceSize)plan->nx * plan->ny);
    if (status != IM_OK) {
        device_release(device);
        return status;
    }
    if ((status = check_grid(plan, device)) != IM_OK) {
        device_release(device);
        return status;
    }
    struct gpu_solver *s = calloc(1, sizeof *s);
    if (!s) {
        device_release(device);
        return im_fail(IM_ENOMEM, "GPU engine %d x %d", plan->nx, plan->ny);
    }
    *s = (struct gpu_solver){.device = device,
                             .nx = (uint32_t)plan->nx,
                             .ny = (uint32_t)plan->ny,
                             .px = (uint32_t)plan->px,
                             .py = (uint32_t)plan->py,
                             .periodic = plan->options.periodic,
                             .borrowed = finer != NULL};
    plan->gpu = s;
    if (finer)
        borrow_fields(s, finer->gpu, plan->options.precondition);
    status = check_memory(plan, s);
    if (status == IM_OK)
        status = make_buffers(plan, s);
    if (status != IM_OK) { /* the plan stays whole on the CPU engine */
        status = im_fail_context(status, "GPU engine %d x %d on %s", plan->nx, plan->ny,
                                 gpu_context_device_name(device->context));
        gpu_engine_free(plan);
        return status;
    }
    plan->engine = &solver_engine_gpu;
    plan->direct_limit = s->periodic ? 0 : direct_limit(s);
    return IM_OK;
}

int solver_engine_gpu_estimate(int nx, int ny, const im_solver_options *o, solver_gpu_estimate *out)
{
    gpu_context *c = NULL;
    int status = gpu_context_open(o->device == IM_DEVICE_AUTO ? GPU_PREFER_HARDWARE : GPU_ANY, 0, &c);
    if (status == IM_OK)
        status = check_estimated_transforms(c, nx, ny, o);
    if (status != IM_OK) {
        gpu_context_close(c);
        return status;
    }
    /* gpu_context_reserve_staging: an upload and a download buffer of the top plan's field, a part at most */
    const double field = sizeof(double) * (double)nx * ny, part = (double)gpu_context_part_bytes(c);
    *out = (solver_gpu_estimate){.device_bytes = (double)plan_footprint(c, nx, ny, o),
                                 .device_memory = (double)gpu_context_device_bytes(c),
                                 .staging_bytes = 2 * fmin(field, part),
                                 .software = gpu_context_is_software(c)};
    snprintf(out->device, sizeof out->device, "%s", gpu_context_device_name(c));
    gpu_context_close(c);
    return IM_OK;
}

const char *solver_engine_gpu_device(const im_solver_plan *plan)
{
    return plan->gpu ? gpu_context_device_name(plan->gpu->device->context) : NULL;
}

void solver_engine_gpu_memory(const im_solver_plan *plan, double *counted, double *held)
{
    const gpu_device *d = plan->gpu ? plan->gpu->device : NULL;
    *counted = d ? (double)d->fields_bytes : -1;
    *held = d ? (double)gpu_context_local_bytes(d->context) : -1;
}

void solver_engine_gpu_transfers(const im_solver_plan *plan, double *uploaded, double *downloaded)
{
    VkDeviceSize up = 0, down = 0;
    if (plan->gpu)
        gpu_context_transfers(plan->gpu->device->context, &up, &down);
    *uploaded = plan->gpu ? (double)up : -1;
    *downloaded = plan->gpu ? (double)down : -1;
}

long solver_engine_gpu_submissions(const im_solver_plan *plan)
{
    return plan->gpu ? gpu_context_submissions(plan->gpu->device->context) : -1;
}

long solver_engine_gpu_validation_messages(const im_solver_plan *plan)
{
    return plan->gpu ? gpu_context_validation_messages(plan->gpu->device->context) : -1;
}
