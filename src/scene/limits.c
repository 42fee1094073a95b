/* Limits checked before any work: the scene's consistency with its grid, the memory and disk its
 * outputs need against what the machine has, and outputs that would overwrite inputs. The
 * estimates are upper bounds of the largest terms, not exact accounts: each solve's FFT plan and
 * fields, the fields the frames keep, and the files at their uncompressed sizes. */
#include "front/front.h"
#include "front/run_folder.h"
#include "scene/contents.h"
#include "indentmap/field.h"
#include "indentmap/io.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "scene/ensemble.h"
#include "scene/histories.h"
#include "scene/limits.h"
#include "scene/plots.h"
#include "scene/progress.h"
#include "scene/punch.h"
#include "scene/surfaces.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>

enum {
    PLOT_BYTES = 1 << 18, /* a plot's PNG and PDF together, besides any surface image it
                                    embeds (measured at 64 x 64: at most 0.2 MiB) */
    FRAME_TEXT_BYTES = 1 << 15
}; /* a frame's title, colour bar and labels (measured: 0.03 MiB) */
static const double MIB = 1048576.0;

typedef struct grid {
    int nx, ny;
    double delta;
} grid;

/* The scene's grid: [surfaces] n, m, or the surface file's (read here: it is an input anyway, and
 * reading checks it before any work). */
static int scene_grid(const im_scene *scene, grid *out)
{
    *out = (grid){scene->surface.nx, scene->surface.ny, scene->surface.delta};
    if (!scene->surface_file[0])
        return IM_OK;
    im_field *surface = NULL;
    int status = scene_surface(scene, 0, 0, &surface);
    if (status == IM_OK)
        *out = (grid){surface->nx, surface->ny, surface->delta};
    im_field_free(surface);
    return status;
}

static int ensemble_size(const im_scene *scene)
{
    int count = 0;
    for (int f = 0; f < scene->family_count; ++f)
        count += scene->slopes[f] == 0.0 && !scene->surface_file[0] ? 1 : scene->seed_count;
    return count;
}

/* ---- consistency ---- */

/* The smooth contact must stay inside the surface: a disc of radius `radius` (patches) around the centred
 * axis (im_indenter_axis: the centre of patch n / 2), which must stay short of the edge patches' centres,
 * (n - 1) / 2 patches away on the nearer side of the shorter one (64: 31), as the solver judges it before a
 * step (else every solve ends at the surface's edge). `how` says how the radius follows from the value. */
static int check_radius_fits(const im_scene *scene, const grid *g, const char *key, double value, double radius,
                             const char *how)
{
    int room = ((g->nx < g->ny ? g->nx : g->ny) - 1) / 2;
    if (radius >= room)
        return im_fail(IM_EINVAL,
                       "%s: %s = %g: the smooth contact radius %s = %.1f patches reaches the edge of "
                       "the %d x %d surface (expected a radius < %d patches, from the axis to the edge patches' "
                       "centres; use a larger grid or smaller %s)",
                       scene->path, key, value, how, radius, g->nx, g->ny, room,
                       strstr(key, "steps") ? "steps" : "loads");
    return IM_OK;
}

/* N* is defined by the smooth contact area A = N* delta^2, a disc of radius sqrt(N* / pi) patches,
 * whatever the punch. */
static int check_contact_fits(const im_scene *scene, const grid *g, const char *key, double n_star)
{
    return check_radius_fits(scene, g, key, n_star, sqrt(n_star / M_PI), "sqrt(N*/pi)");
}

/* The largest of loads given as loads (with [adhesion]): its smooth (repulsive) contact, a disc of area A(N).
 * Nothing to check when no load presses, or for a 2-D profile (no smooth-contact area: the solver's edge
 * check stops it). */
static int check_load_fits(const im_scene *scene, const grid *g, double largest)
{
    im_indenter punch = scene_punch(scene);
    const double area = largest > 0 ? im_indenter_area_for_load(&punch, scene->modulus, largest) : NAN;
    if (!isfinite(area))
        return IM_OK;
    return check_radius_fits(scene, g, "[loading] steps (largest load)", largest, sqrt(area / M_PI) / g->delta,
                             "sqrt(A(N)/pi)");
}

/* Every history (any punch, load or displacement control) must reach its last step: refused here,
 * before any work, when even the smooth contact of that step leaves the surface. */
static int check_histories_fit(const im_scene *scene, const grid *g)
{
    if (!scene_wants_histories(scene) || scene->step_count < 1 || scene->periodic) /* the cell is all contact */
        return IM_OK;
    double last = scene->steps[0]; /* the largest step (a history with a hardness may go down) */
    for (int i = 1; i < scene->step_count; ++i)
        last = fmax(last, scene->steps[i]);
    if (scene_steps_are_loads(scene))
        return check_load_fits(scene, g, last);
    if (scene->control == IM_CONTROL_LOAD)
        return check_contact_fits(scene, g, "[loading] steps (largest)", last);
    im_indenter punch = scene_punch(scene);
    return check_radius_fits(scene, g, "[loading] steps (largest approach)", last,
                             im_indenter_contact_radius(&punch, last) / g->delta, "a(w) of the punch");
}

static int check_consistency(const im_scene *scene, const grid *g)
{
    int status = IM_OK;
    if (scene->load_star > 0.0 && (scene->contact_panels || scene->frames || scene->table || scene->distributions))
        status = check_contact_fits(scene, g, "[loading] load_star", scene->load_star);
    if (status == IM_OK)
        status = check_histories_fit(scene, g);
    const int room = ((g->nx < g->ny ? g->nx : g->ny) - 1) / 2; /* as in check_radius_fits */
    if (status == IM_OK && scene->punch == IM_PUNCH_FLAT && scene->radius >= room)
        status = im_fail(IM_EINVAL,
                         "%s: [punch] radius = %g: a flat punch as wide as the %d x %d surface "
                         "(radius in patches; expected < %d, from the axis to the edge patches' centres)",
                         scene->path, scene->radius, g->nx, g->ny, room);
    return status;
}

/* ---- memory ---- */

/* Whether a history's steps are solved on boxes of the window (solver.h: im_indentation_step; under
 * displacement control on a cropped half-space without adhesion, on the CPU engine). */
static int steps_in_boxes(const im_scene *scene, const im_solver_memory *plan)
{
    const im_solver_options o = scene_solver_options(scene);
    return scene_wants_histories(scene) && scene->step_count > 0 && scene->control == IM_CONTROL_DISPLACEMENT &&
           !scene_steps_are_loads(scene) && o.crop && !o.periodic && !(o.adhesion_work > 0) && !plan->gpu;
}

/* One solve: its plan on the solves' window w (solves_window: the whole grid where it is not known) on
 * the engine the scene's device takes (the host's share: the CPU plan, or a GPU plan's tables, staging and
 * cascade arrays) and its fields (surface, undeformed gap, pressure, displacement, and the copies a step
 * hands out). A history stepping in boxes holds beside the window's plan a box's solver plan and the box
 * within reach's displacement plan, each up to the window's (their sizes follow the steps), with their
 * gap, pressure and displacement arrays: at 512^2, steps 30 and 52 of a cone (its window the whole grid) took
 * 102 MiB beside the program against the 75 MiB counted without them. */
static double solve_bytes(const im_scene *scene, const grid *g, const grid *w, const im_solver_memory *plan)
{
    const double boxes = steps_in_boxes(scene, plan) ? 2.0 * plan->host_bytes + 6.0 * 8.0 * w->nx * w->ny : 0.0;
    return plan->host_bytes + boxes + 8.0 * 8.0 * g->nx * g->ny;
}

/* Whether the scene draws or measures a state's displacement on the whole grid (frames, distributions:
 * im_indentation_fields_full), which a run plans once beside its solver's (a periodic cell's solve covers
 * the cell already). */
static int draws_whole_grid(const im_scene *scene)
{
    return (scene->frames || scene->distributions) && !scene->periodic;
}

/* That whole-grid convolution's plan (im_displacement_plan_create's: a convolution's, on the engine the
 * scene's device takes); all zero where the scene has none. A 1024^2 frame history on a file (its window
 * known and small) held 163-168 MiB beyond a tiny frame history against the 142.8 MiB counted without it;
 * a solver plan's 140 B a patch was counted for it until the convolution's own (64-80 B) was made. */
static int full_grid_memory(const im_scene *scene, const grid *g, const im_solver_memory *plan,
                            im_solver_memory *full)
{
    *full = (im_solver_memory){.host_bytes = 0.0};
    if (!draws_whole_grid(scene))
        return IM_OK;
    im_solver_options o = scene_solver_options(scene);
    o.device = plan->gpu ? IM_DEVICE_GPU : IM_DEVICE_CPU; /* where the run's own plans went */
    int status = im_displacement_memory_needed(g->nx, g->ny, &o, full);
    return status == IM_OK ? IM_OK : im_fail_context(status, "%s: the whole grid's displacement", scene->path);
}

/* The host memory; *at_once: the most solves at once (the members, or the panels, one per thread). */
static double memory_needed(const im_scene *scene, const grid *g, const grid *w, const im_solver_memory *plan,
                            const im_solver_memory *full, int *at_once)
{
    double field = 8.0 * g->nx * g->ny, needed = 0.0, solve = solve_bytes(scene, g, w, plan);
    int members = ensemble_size(scene), threads = omp_get_max_threads();
    *at_once = 0;
    if (scene->table || scene->step_count > 0) {
        *at_once = members < threads ? members : threads;
        needed = *at_once * solve + members * (5.0 * 8.0 * scene->step_count + sizeof(scene_member));
    }
    double frame_pixels = (double)scene->frame_scale * scene->frame_scale * g->nx * g->ny;
    if (scene->frames) /* force and deformed heights of every step, the contact and height images, all
                        * rendered before their figures are written, and the contact figures (counted as
                        * twice the image) kept for the GIF */
        needed = fmax(needed, solve + full->host_bytes + scene->frame_count * (2.0 * field + 16.0 * frame_pixels));
    if (scene->distributions) /* one state at a time: its force and gap on the whole grid */
        needed = fmax(needed, solve + full->host_bytes + 2.0 * field);
    if (scene->frames3d) /* the 3-D frames' figures kept for the GIF (RGBA, twice the view) */
        needed += scene->frame_count * 8.0 * scene->frame3d_width * scene->frame3d_height;
    if (scene->contact_panels) { /* every family's force and panel image (2 pixels a patch when small); the
                                  * panels are solved side by side, one per thread */
        int panels_at_once = scene->family_count < threads ? scene->family_count : threads;
        needed = fmax(needed, panels_at_once * solve + scene->family_count * (field + 16.0 * g->nx * g->ny));
        *at_once = panels_at_once > *at_once ? panels_at_once : *at_once;
    }
    if (*at_once == 0 && scene->frames)
        *at_once = 1;
    return needed;
}

/* Address space that holds no data but counts against an address-space limit (ulimit -v), as
 * measured with VmPeak on Debian 12 (glibc 2.36, Mesa 22.3 llvmpipe): each worker thread beyond
 * the first reserves its stack and two 64 MiB malloc arenas (136 MiB measured, 512 x 512 solve);
 * the renderer maps Mesa and LLVM (337 MiB measured with no render threads) and each llvmpipe
 * thread (LP_NUM_THREADS, else one per processor) 115 MiB more. Without this, fig4 passed the
 * check under ulimit -v 350000 and failed mid-run. */
static const double ARENA_BYTES = 64.0 * 1048576.0, RENDERER_BYTES = 360.0 * 1048576.0;

static double thread_stack_bytes(void)
{
    struct rlimit limit;
    if (getrlimit(RLIMIT_STACK, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY)
        return 8.0 * 1048576.0; /* glibc's default when the limit is unlimited */
    return (double)limit.rlim_cur;
}

static int render_threads(void)
{
    /* not a setting of the library: Mesa's llvmpipe reads it in this process, and so sizes its threads */
    const char *text = getenv("LP_NUM_THREADS");
    return text && text[0] ? atoi(text) : omp_get_num_procs();
}

static double address_space_overhead(const im_scene *scene)
{
    double overhead = (omp_get_max_threads() - 1) * (2.0 * ARENA_BYTES + thread_stack_bytes());
    if (scene->contact_panels || scene->frames)
        overhead += RENDERER_BYTES + render_threads() * 2.0 * ARENA_BYTES;
    return overhead;
}

/* ---- the solves' window ---- */

/* *largest, or the window of a solve of surface at the largest target (im_indentation_window_for) when
 * it has more patches. An error is left to the solve (the whole grid is then counted). */
static int keep_larger_window(const im_field *surface, const im_indenter *punch, enum im_control control,
                              double target, const im_solver_options *options, im_window *largest)
{
    im_window w;
    int status = im_indentation_window_for(surface, punch, control, target, options, &w);
    if (status == IM_OK && (double)w.nx * w.ny > (double)largest->nx * largest->ny)
        *largest = w;
    return status;
}

/* The largest window of the solves of a member on surface: its history's at the largest step, and the
 * load_star stages' (table, frames, panels, distributions) at load_star. */
static int member_window(const im_scene *scene, const im_field *surface, im_window *largest)
{
    const im_solver_options options = scene_solver_options(scene);
    int status = IM_OK;
    if (scene_wants_histories(scene) && scene->step_count > 0) {
        const im_indenter punch = scene_member_punch(scene, surface);
        status = keep_larger_window(surface, &punch, scene->control, scene_largest_step(scene, surface), &options,
                                    largest);
    }
    const int at_load_star = scene->load_star > 0.0 &&
                             (scene->contact_panels || scene->frames || scene->table || scene->distributions);
    if (status == IM_OK && at_load_star) {
        const im_indenter punch = scene_punch(scene);
        status = keep_larger_window(surface, &punch, IM_CONTROL_LOAD, scene_load_for_load_star(scene, surface->delta),
                                    &options, largest);
    }
    return status;
}

/* Whether every member's heights are known before any work: surface files (read again here), or smooth
 * families. A synthesized family's are not, and its window's bound holds its height range. */
static int heights_known(const im_scene *scene)
{
    for (int f = 0; f < scene->family_count && !scene->surface_file[0]; ++f)
        if (scene->slopes[f] != 0.0)
            return 0;
    return 1;
}

/* The grid a solve of the scene is planned on: the largest window of its members' solves where their
 * heights are known before any work, else (a synthesized family, a periodic cell, which has no window, or
 * a window the solve would refuse) the whole grid, an upper bound. */
static grid solves_window(const im_scene *scene, const grid *g)
{
    if (scene->periodic || !heights_known(scene))
        return *g;
    const int files = scene->surface_file[0] ? scene->file_count : 0, members = files ? files : scene->family_count;
    im_window largest = {0, 0, 0, 0};
    int status = IM_OK;
    for (int k = 0; k < members && status == IM_OK; ++k) {
        im_field *surface = NULL;
        status = scene_surface(scene, files ? 0 : k, files ? (uint64_t)k : scene->seeds[0], &surface);
        if (status == IM_OK)
            status = member_window(scene, surface, &largest);
        im_field_free(surface);
    }
    return status == IM_OK && largest.nx > 0 ? (grid){largest.nx, largest.ny, g->delta} : *g;
}

/* Whether the solves take less than the whole grid. */
static int is_window(const grid *g, const grid *w) { return w->nx != g->nx || w->ny != g->ny; }

/* "a 60 x 54 window of the 256 x 256 grid", or "a 256 x 256 grid" when the solves take all of it. */
static void describe_solve(const grid *g, const grid *w, char *text, size_t size)
{
    if (!is_window(g, w))
        snprintf(text, size, "a %d x %d grid", g->nx, g->ny);
    else
        snprintf(text, size, "a %d x %d window of the %d x %d grid", w->nx, w->ny, g->nx, g->ny);
}

/* The device memory of the solves at once, each on its own context of the one GPU, and of a run that
 * draws the whole grid: its solve's plan beside the whole grid's convolution. */
static int check_device_memory(const im_scene *scene, const grid *g, const grid *w, const im_solver_memory *plan,
                               const im_solver_memory *full, int at_once)
{
    const double drawing = full->gpu ? plan->device_bytes + full->device_bytes : 0.0;
    if (!plan->gpu || fmax(at_once * plan->device_bytes, drawing) <= plan->device_memory)
        return IM_OK;
    char solve[96];
    describe_solve(g, w, solve, sizeof solve);
    if (drawing > at_once * plan->device_bytes)
        return im_fail(IM_ENOMEM,
                       "%s: this scene's frames or distributions hold a solve's %.3g GiB of device memory on %s (for "
                       "%s) beside %.3g GiB for the whole %d x %d grid's displacement, but %s has %.3g GiB; use "
                       "device = cpu or a smaller grid",
                       scene->path, plan->device_bytes / (1024 * MIB), plan->device, solve,
                       full->device_bytes / (1024 * MIB), g->nx, g->ny, plan->device,
                       plan->device_memory / (1024 * MIB));
    return im_fail(IM_ENOMEM,
                   "%s: this scene solves %d surfaces at once on %s, %.3g GiB of device memory each for %s (%.3g "
                   "GiB), but %s has %.3g GiB; use fewer threads (OMP_NUM_THREADS), device = cpu, or a smaller grid",
                   scene->path, at_once, plan->device, plan->device_bytes / (1024 * MIB), solve,
                   at_once * plan->device_bytes / (1024 * MIB), plan->device, plan->device_memory / (1024 * MIB));
}

/* The memory a solve on w needs on the engine the scene's device takes (a GPU is opened only when asked
 * for, and only for scenes that solve); device = auto falling back to the CPU says why. */
static int plan_memory(const im_scene *scene, const im_scene_run_options *options, const grid *g, const grid *w,
                       im_solver_memory *plan)
{
    im_solver_options solver = scene_solver_options(scene);
    int solves = scene->table || scene->step_count > 0 || scene->frames || scene->contact_panels;
    if (!solves)
        solver.device = IM_DEVICE_CPU;
    int status = im_solver_memory_needed(w->nx, w->ny, &solver, plan);
    char solve[96];
    describe_solve(g, w, solve, sizeof solve);
    if (status == IM_ENOMEM) /* the device's memory: the others name what they refuse */
        return im_fail_context(status, "%s: [solver] device = gpu%s%s", scene->path,
                               is_window(g, w) ? ", solves on " : "", is_window(g, w) ? solve : "");
    if (status != IM_OK)
        return im_fail_context(status, "%s", scene->path);
    if (plan->note[0])
        scene_warn(options, "%s: %s", scene->path, plan->note);
    return IM_OK;
}

/* The estimate check_memory judges and what it is judged against, kept in *limits. */
static void keep_memory(const im_scene *scene, scene_limits *limits, const grid *w, const im_solver_memory *plan,
                        double solve, double needed, int at_once)
{
    limits->window_nx = w->nx;
    limits->window_ny = w->ny;
    limits->gpu = plan->gpu;
    limits->solve_bytes = solve;
    limits->memory_needed = needed;
    limits->at_once = at_once;
    limits->memory_available = (double)im_memory_available();
    limits->address_space = (double)im_address_space_available();
    limits->address_reserved = address_space_overhead(scene);
}

static int check_memory(const im_scene *scene, const im_scene_run_options *options, const grid *g,
                        scene_limits *limits)
{
    im_solver_memory plan, full;
    const grid w = solves_window(scene, g);
    int at_once, status = plan_memory(scene, options, g, &w, &plan);
    if (status == IM_OK)
        status = full_grid_memory(scene, g, &plan, &full);
    if (status != IM_OK)
        return status;
    double needed = memory_needed(scene, g, &w, &plan, &full, &at_once);
    keep_memory(scene, limits, &w, &plan, solve_bytes(scene, g, &w, &plan), needed, at_once);
    if ((status = check_device_memory(scene, g, &w, &plan, &full, at_once)) != IM_OK)
        return status;
    const double available = limits->memory_available;
    if (available != 0 && needed > available)
        return im_fail(IM_ENOMEM,
                       "%s: this scene needs about %.1f MiB of memory (%d surfaces solved at once, "
                       "%.1f MiB each for the solver plan (%s engine) and fields of a %d x %d grid, plus what the "
                       "frames, panels and the whole grid's displacement keep) but only %.1f MiB are available; use "
                       "a smaller grid or fewer "
                       "threads (OMP_NUM_THREADS)",
                       scene->path, needed / MIB, at_once, limits->solve_bytes / MIB, plan.gpu ? "GPU" : "CPU", g->nx,
                       g->ny, available / MIB);
    const double address_space = limits->address_space, reserved = limits->address_reserved;
    if (address_space != 0 && needed + reserved > address_space)
        return im_fail(IM_ENOMEM,
                       "%s: this scene needs about %.1f MiB of address space (%.1f MiB of data, %.1f MiB "
                       "reserved by %d threads%s) but the address-space limit (ulimit -v) leaves %.1f MiB; raise the "
                       "limit, or use fewer threads (OMP_NUM_THREADS%s)",
                       scene->path, (needed + reserved) / MIB, needed / MIB, reserved / MIB, omp_get_max_threads(),
                       scene->contact_panels || scene->frames ? " and the renderer" : "", address_space / MIB,
                       scene->contact_panels || scene->frames ? ", LP_NUM_THREADS" : "");
    return IM_OK;
}

/* ---- disk ---- */

typedef struct disk_estimate {
    double total, largest;
    const char *largest_name;
} disk_estimate;

static void add_files(disk_estimate *d, double count, double bytes, const char *name)
{
    d->total += count * bytes;
    if (count > 0 && bytes > d->largest) {
        d->largest = bytes;
        d->largest_name = name;
    }
}

/* The figures [output] plots names. */
static int plot_count(const im_scene *scene) { return __builtin_popcount(scene->plots); }

/* Files with their images at their uncompressed sizes, an upper bound (PNG and GIF compress: a
 * height map's frame to 0.86 of it, contact maps ten times more); the margins, colour bar and labels
 * of a figure or frame as measured. A second copy of each image for the margins made the estimate
 * 12x the outputs (16.4 MiB for 1.3 MiB: tests/cli_full_disk.sh), refusing runs that fit. */
static disk_estimate disk_needed(const im_scene *scene, const grid *g)
{
    double cells = (double)g->nx * g->ny, members = ensemble_size(scene);
    disk_estimate d = {0.0, 0.0, ""};
    if (scene->contact_panels && scene->periodic) { /* every step's fields and contact map (periodic.h) */
        int scale = fields_frames_pixels_per_patch(g->nx, g->ny);
        double steps = (double)scene->family_count * scene->step_count;
        add_files(&d, steps * step_field_count(scene->hardness), 8.0 * cells + 1024.0,
                  "panels/family_FF/force_NNNN.npy");
        add_files(&d, steps, 3.0 * scale * scale * cells + FRAME_TEXT_BYTES, "panels/family_FF/contact_NNNN.png");
    } else if (scene->contact_panels) {
        add_files(&d, scene->family_count, 8.0 * cells + 128.0, "panels/force_FF.npy");
        add_files(&d, 2.0, scene->family_count * 3.0 * 4.0 * cells + PLOT_BYTES, "contact_panels.png");
    }
    double frame_cells = cells * scene->frame_scale * scene->frame_scale,
           view = (double)scene->frame3d_width * scene->frame3d_height;
    if (scene->frames) { /* the GIF: one byte a pixel of the figures */
        add_files(&d, 2.0 * scene->frame_count, 3.0 * frame_cells + FRAME_TEXT_BYTES, "frames/contact_NNNN.png");
        add_files(&d, 1.0, scene->frame_count * frame_cells + 1024.0, "contact.gif");
    }
    if (scene->frames3d) { /* figures of the views and the GIF of them */
        add_files(&d, scene->frame_count, 3.0 * view, "frames/view3d_NNNN.png");
        add_files(&d, 1.0, scene->frame_count * view + 1024.0, "view3d.gif");
    }
    if (scene->table)
        add_files(&d, members, 512.0, "table/member_FF_SEED.csv");
    add_files(&d, members, 256.0 + 128.0 * scene->step_count, "histories/member_FF_SEED.csv");
    add_files(&d, plot_count(scene), PLOT_BYTES + 3.0 * cells, "a plot");
    return d;
}

static int check_disk(const im_scene *scene, const grid *g, int space_check, scene_limits *limits)
{
    disk_estimate d = disk_needed(scene, g);
    limits->disk_total = d.total;
    limits->disk_largest = d.largest;
    limits->disk_largest_name = d.largest_name;
    limits->disk_free = -1.0;
    struct rlimit limit;
    if (getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY && d.largest > (double)limit.rlim_cur)
        return im_fail(IM_EIO, "%s: %s would be about %.1f MiB but the file-size limit (ulimit -f) is %.1f MiB",
                       scene->path, d.largest_name, d.largest / MIB, (double)limit.rlim_cur / MIB);
    char *folder = limits->disk_folder;
    double free_bytes = run_folder_free_disk(scene->output_dir, folder, sizeof limits->disk_folder);
    if (free_bytes == -1.0)
        return IM_OK;       /* cannot tell: the writes will report it */
    if (free_bytes == -2.0) /* proc, sysfs: "0.0 MiB free" would read as a full disk */
        return im_fail(IM_EIO,
                       "%s: the output folder %s is on a file system that stores no files (%s has no "
                       "blocks, like /proc or /sys); give an output folder on a disk",
                       scene->path, scene->output_dir, folder);
    limits->disk_free = free_bytes;
    if (d.total > free_bytes && space_check)
        return im_fail(IM_EIO,
                       "%s: the outputs need about %.1f MiB of disk (the largest, %s, %.1f MiB) but %s has "
                       "only %.1f MiB free; this is an upper bound: IM_NO_SPACE_CHECK=1 runs anyway (a full disk "
                       "then stops the run, keeping what it finished)",
                       scene->path, d.total / MIB, d.largest_name, d.largest / MIB, folder, free_bytes / MIB);
    return IM_OK;
}

/* ---- outputs never overwrite inputs ---- */

/* The absolute, symlink-free form of path, which need not exist yet (its missing tail is kept as
 * written). */
static int absolute_path(const char *path, char *out)
{
    char existing[PATH_MAX], resolved[PATH_MAX];
    size_t n = run_folder_existing_prefix(path);
    run_folder_existing_ancestor(path, existing, sizeof existing);
    if (!realpath(existing, resolved))
        return im_fail(IM_EIO, "%s: cannot resolve: %s", existing, strerror(errno));
    const char *tail = path + n;
    while (*tail == '/')
        ++tail;
    int length = snprintf(out, PATH_MAX, "%s%s%s", resolved, *tail && strcmp(resolved, "/") ? "/" : "", tail);
    return length < PATH_MAX ? IM_OK : im_fail(IM_EINVAL, "%s: path too long", path);
}

static int check_not_inside(const im_scene *scene, const char *output, const char *input, const char *what)
{
    char resolved[PATH_MAX];
    if (!realpath(input, resolved))
        return IM_OK; /* the reader reports a missing input */
    size_t n = strlen(output);
    if (strcmp(resolved, output) == 0 || (strncmp(resolved, output, n) == 0 && resolved[n] == '/'))
        return im_fail(IM_EINVAL,
                       "%s: [scene] output = %s would hold the %s %s, and could overwrite it; "
                       "give another output folder",
                       scene->path, scene->output_dir, what, input);
    return IM_OK;
}

static int check_outputs_apart(const im_scene *scene)
{
    char output[PATH_MAX];
    int status = absolute_path(scene->output_dir, output);
    if (status == IM_OK)
        status = check_not_inside(scene, output, scene->path, "scene file");
    for (int i = 0; status == IM_OK && i < scene->file_count; ++i) {
        char surface[IM_SCENE_PATH];
        status = im_scene_file_path(scene, i, surface, sizeof surface);
        if (status == IM_OK)
            status = check_not_inside(scene, output, surface, "surface file");
    }
    return status;
}

int scene_check_limits(const im_scene *scene, const im_scene_run_options *options, scene_limits *limits)
{
    grid g;
    *limits = (scene_limits){.disk_free = -1.0};
    int status = check_outputs_apart(scene);
    if (status == IM_OK)
        status = scene_grid(scene, &g);
    if (status == IM_OK) {
        limits->nx = limits->window_nx = g.nx;
        limits->ny = limits->window_ny = g.ny;
        status = check_consistency(scene, &g);
    }
    if (status == IM_OK)
        status = check_memory(scene, options, &g, limits);
    if (status == IM_OK)
        status = check_disk(scene, &g, !options->no_space_check, limits);
    return status;
}
