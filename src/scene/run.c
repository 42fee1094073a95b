#include "indentmap/scene.h"

#include "indentmap/io.h"
#include "indentmap/plot.h"
#include "indentmap/status.h"
#include "indentmap/viewer.h"
#include "indentmap/theory.h"
#include "scene/scene_internal.h"

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

im_indenter scene_punch(const im_scene *scene)
{
    switch (scene->punch) {
    case IM_PUNCH_SPHERE: return im_indenter_sphere(scene->radius);
    case IM_PUNCH_FLAT: return im_indenter_flat(scene->radius);
    default: return im_indenter_cone(scene->alpha_degrees);
    }
}

double scene_load_for_load_star(const im_scene *scene, double delta)
{
    return scene_load_for_n_star(scene, scene->load_star, delta);
}

double scene_load_for_n_star(const im_scene *scene, double n_star, double delta)
{
    /* A(N) increases with N for every punch: bisect A(N) = n_star delta^2 in log N. */
    im_indenter punch = scene_punch(scene);
    double area = n_star * delta * delta, lo = 1e-300, hi = 1.0;
    while (im_indenter_area_for_load(&punch, scene->modulus, hi) < area && hi < 1e300)
        hi *= 2.0;
    for (int i = 0; i < 200 && hi / lo > 1.0 + 1e-15; ++i) {
        double mid = sqrt(lo * hi);
        if (im_indenter_area_for_load(&punch, scene->modulus, mid) < area)
            lo = mid;
        else
            hi = mid;
    }
    return hi;
}

/* File i of the scene, read and prepared as it is solved. */
static int file_surface(const im_scene *scene, int i, im_field **out)
{
    char path[IM_SCENE_PATH];
    int status = im_scene_file_path(scene, i, path, sizeof path);
    im_surface_read_options read = {.fill = scene->fill};
    if (status == IM_OK)
        status = im_surface_read_with(path, &read, out, NULL);
    if (status == IM_OK && (status = im_surface_detrend(*out, (enum im_detrend)scene->detrend)) != IM_OK) {
        im_field_free(*out);
        *out = NULL;
    }
    return status;
}

/* An ensemble of files shares one grid and spacing (the panels, limits and sums assume it). */
static int check_same_grid(const im_scene *scene, const im_field *first, const im_field *other, int i)
{
    if (other->nx == first->nx && other->ny == first->ny && other->delta == first->delta &&
        strcmp(other->unit, first->unit) == 0)
        return IM_OK;
    char a[IM_SCENE_PATH], b[IM_SCENE_PATH];
    im_scene_file_path(scene, 0, a, sizeof a);
    im_scene_file_path(scene, i, b, sizeof b);
    return im_fail(IM_EFORMAT, "%s: file: %s is %d x %d with delta %g %s but %s is %d x %d with delta %g %s: the "
                   "files of an ensemble share one grid", scene->path, b, other->nx, other->ny, other->delta,
                   other->unit, a, first->nx, first->ny, first->delta, first->unit);
}

int im_scene_measure_files(im_scene *scene)
{
    im_field *first = NULL;
    double sum_squares = 0.0;
    int status = IM_OK;
    for (int i = 0; i < scene->file_count && status == IM_OK; ++i) {
        im_field *surface = NULL;
        status = file_surface(scene, i, &surface);
        if (status == IM_OK && first)
            status = check_same_grid(scene, first, surface, i);
        if (status == IM_OK)
            status = im_surface_slope_rms(surface, IM_SLOPE_FINITE_DIFFERENCE, &scene->file_slopes[i]);
        sum_squares += status == IM_OK ? scene->file_slopes[i] * scene->file_slopes[i] : 0.0;
        if (!first)
            first = surface;
        else
            im_field_free(surface);
    }
    if (status == IM_OK && first) { /* the grid the scene's records and checks describe */
        scene->surface.nx = first->nx;
        scene->surface.ny = first->ny;
        scene->surface.delta = first->delta;
        memcpy(scene->file_unit, first->unit, sizeof scene->file_unit);
        scene->slopes[0] = sqrt(sum_squares / scene->file_count);
    }
    im_field_free(first);
    return status;
}

int scene_surface(const im_scene *scene, int family, uint64_t seed, im_field **out)
{
    if (scene->surface_file[0])
        return file_surface(scene, (int)seed, out);
    if (scene->slopes[family] == 0.0)
        return im_field_create(scene->surface.nx, scene->surface.ny, scene->surface.delta, out);
    im_surface_params params = scene->surface;
    params.target = IM_TARGET_SLOPE;
    params.slope_rms = scene->slopes[family];
    params.seed = seed;
    return im_surface_generate(&params, out);
}

double scene_member_slope(const im_scene *scene, int family, uint64_t seed)
{
    return scene->file_count > 0 ? scene->file_slopes[seed] : scene->slopes[family];
}

im_solver_options scene_solver_options(const im_scene *scene)
{
    im_solver_options options = im_solver_options_default();
    options.e_star = scene->modulus;
    options.tol = scene->tol;
    options.hardness = scene->hardness;
    options.wisdom_path = scene->wisdom_path;
    return options;
}

void scene_family_title(const im_scene *scene, int family, char *buffer, size_t size)
{
    if (scene->file_count > 1)
        snprintf(buffer, size, "%d files, h′_{rms} = %.3g", scene->file_count, scene->slopes[family]);
    else if (scene->surface_file[0])
        snprintf(buffer, size, "%s, h′_{rms} = %.3g", scene->surface_file, scene->slopes[family]);
    else if (scene->slopes[family] == 0.0)
        snprintf(buffer, size, "smooth");
    else
        snprintf(buffer, size, "h′_{rms} = %g", scene->slopes[family]);
}

int scene_panel_columns(int count)
{
    return count > 3 && count % 3 == 0 ? 3 : count > 3 && count % 2 == 0 ? 2 : count;
}

im_colormap scene_force_norm(const im_scene *scene, double largest)
{
    double hi = largest > 0.0 ? largest : 1.0;
    im_colormap norm = im_colormap_make((im_colormap_id)scene->colormap, scene->log_norm ? 0.01 * hi : 0.0, hi);
    norm.logarithmic = scene->log_norm;
    return norm;
}

double scene_eq12(const im_scene *scene, double slope, double *rho_c)
{
    im_theory_interface rough = im_theory_interface_default(slope);
    double rho = NAN, beta, ratio;
    int ok = scene->punch == IM_PUNCH_CONE && im_theory_cone_rho(&rough, scene->alpha_degrees, &rho) == IM_OK &&
             im_theory_erf_scale(rho, rough.normalisation, rough.k, &beta) == IM_OK &&
             im_theory_cone_area_ratio_variable(beta, &ratio) == IM_OK;
    if (rho_c)
        *rho_c = rho;
    return ok ? ratio : NAN;
}

int scene_write_png_pdf(const im_scene *scene, const char *name,
                        int (*draw)(const im_scene *, const void *, const char *), const void *data)
{
    int status = IM_OK;
    const char *extensions[] = {"png", "pdf"};
    for (int i = 0; i < 2 && status == IM_OK; ++i) {
        char relative[128], path[IM_SCENE_PATH];
        snprintf(relative, sizeof relative, "%s.%s", name, extensions[i]);
        status = scene_output_path(scene, relative, path, sizeof path);
        if (status == IM_OK)
            status = draw(scene, data, path);
    }
    return status;
}

int scene_draw_plot(const im_scene *scene, const void *plot, const char *path)
{
    (void)scene;
    return im_plot_write(plot, path);
}

int scene_output_path(const im_scene *scene, const char *relative, char *buffer, size_t size)
{
    int length = snprintf(buffer, size, "%s/%s", scene->output_dir, relative);
    if (length < 0 || (size_t)length >= size)
        return im_fail(IM_EINVAL, "output path %s/%s is too long", scene->output_dir, relative);
    return IM_OK;
}

int scene_stop_signal(const im_scene_run_options *options)
{
    return options->stop ? (int)*options->stop : 0;
}

int scene_interrupted(const im_scene_run_options *options, const char *where)
{
    return im_fail(IM_EINTERRUPTED, "interrupted by signal %d (%s) %s; finished results are kept: "
                   "run again with --resume to continue", scene_stop_signal(options),
                   strsignal(scene_stop_signal(options)), where);
}

void scene_progress(const im_scene_run_options *options, const char *fmt, ...)
{
    if (options->quiet)
        return;
    va_list args;
    va_start(args, fmt);
    fputs("indentmap: ", stderr);
    vfprintf(stderr, fmt, args);
    fputc('\n', stderr);
    va_end(args);
}

int scene_lock_acquire(const im_scene *scene, scene_lock *lock)
{
    return im_folder_lock_acquire(scene->output_dir, "give this scene another [scene] output", lock);
}

void scene_lock_release(scene_lock *lock)
{
    im_folder_lock_release(lock);
}

static int check_runnable(const im_scene *scene)
{
    if ((scene->contact_panels || scene->frames || scene->table) && !(scene->load_star > 0.0))
        return im_fail(IM_EINVAL, "%s: contact panels, frames and tables need [loading] load_star > 0",
                       scene->path);
    if (scene->frames3d && !scene->frames)
        return im_fail(IM_EINVAL, "%s: [output] frames3d draws the frames' history in 3-D: set frames = yes too",
                       scene->path);
    if (scene->table && scene->punch != IM_PUNCH_CONE)
        return im_fail(IM_EINVAL, "%s: [output] table compares with eq. (12), which is for a cone", scene->path);
    im_indenter punch = scene_punch(scene);
    int status = im_indenter_check(&punch);
    return status == IM_OK ? scene_check_plots(scene) : status;
}

/* Between stages: IM_EINTERRUPTED once a signal has asked to stop. */
static int check_stop(const im_scene_run_options *options, const char *next_stage)
{
    char where[96];
    snprintf(where, sizeof where, "before %s", next_stage);
    return scene_stop_signal(options) ? scene_interrupted(options, where) : IM_OK;
}

/* Frames and panels, which need an OpenGL context. */
static int run_rendered_stages(const im_scene *scene, const im_scene_run_options *options, const scene_reuse *reuse)
{
    int status = check_stop(options, "the frames and panels");
    if (status != IM_OK)
        return status;
    im_render_context *context = NULL;
    status = im_render_open((im_render_backend)options->backend, &context);
    if (status != IM_OK)
        return status;
    scene_progress(options, "rendering with %s (%s)", im_render_backend_name(context),
                   im_render_gl_renderer(context));
    im_field *framed_force = NULL;
    if (scene->frames)
        status = scene_run_frames(scene, options, context, &framed_force);
    if (status == IM_OK && scene->contact_panels)
        status = scene_run_panels(scene, options, context, reuse, framed_force);
    im_field_free(framed_force);
    im_render_close(context);
    return status;
}

/* The stages in order; what one solves at load_star, a later one reuses (nothing solved twice). */
static int run_stages(const im_scene *scene, const im_scene_run_options *options)
{
    scene_reuse reuse = {0};
    int status = scene_run_theory_plots(scene, options);
    if (status == IM_OK && scene->table && (status = check_stop(options, "the table")) == IM_OK)
        status = scene_run_table(scene, options, &reuse);
    if (status == IM_OK && scene_wants_plot(scene, "flat_k") && (status = check_stop(options, "the flat contacts")) == IM_OK)
        status = scene_run_flat_k(scene, options, &reuse);
    if (status == IM_OK && scene_wants_histories(scene) && (status = check_stop(options, "the histories")) == IM_OK)
        status = scene_run_histories(scene, options, &reuse);
    if (status == IM_OK && (scene->contact_panels || scene->frames))
        status = run_rendered_stages(scene, options, &reuse);
    scene_reuse_free(&reuse);
    return status;
}

/* The scene file and its surface files become inputs no write may replace (io.h: the output
 * guard), and the FFTW wisdom file (scene->wisdom_path) may be neither one of them, nor in the output
 * folder, nor anything but wisdom. */
static int protect_inputs(const im_scene *scene)
{
    int status = im_output_protect(scene->path);
    char surface[IM_SCENE_PATH];
    for (int i = 0; i < scene->file_count && status == IM_OK; ++i) {
        status = im_scene_file_path(scene, i, surface, sizeof surface);
        if (status == IM_OK)
            status = im_output_protect(surface);
    }
    im_solver_options solver = scene_solver_options(scene);
    if (status == IM_OK)
        status = im_solver_wisdom_check(&solver);
    const char *wisdom = im_solver_wisdom_file(&solver);
    char folder[PATH_MAX], file[PATH_MAX];
    int resolved = wisdom && im_path_absolute(scene->output_dir, folder, sizeof folder) == IM_OK &&
                   im_path_absolute(wisdom, file, sizeof file) == IM_OK;
    size_t length = resolved ? strlen(folder) : 0;
    if (status == IM_OK && resolved && strncmp(file, folder, length) == 0 && file[length] == '/')
        status = im_fail(IM_EINVAL, "the FFTW wisdom file %s lies in the output folder %s, where this run writes: "
                         "keep it elsewhere", wisdom, scene->output_dir);
    return status;
}

/* Temporary files a killed run left in the (locked) output folder. */
static void remove_stale_temporaries(const im_scene *scene, const im_scene_run_options *options)
{
    int removed = im_folder_remove_temporaries(scene->output_dir, 1); /* table/, histories/, ... */
    if (removed > 0)
        scene_progress(options, "removed %d temporary file%s an interrupted run left in %s", removed,
                       removed == 1 ? "" : "s", scene->output_dir);
}

/* OUTPUT/index.html over what the run left (viewer.h), even after a failure or an interruption;
 * the run's own error, if any, stays the one returned. */
static int write_viewer_page(const im_scene *scene, int status)
{
    char message[1024], title[IM_SCENE_PATH + 96];
    snprintf(message, sizeof message, "%s", im_last_error());
    snprintf(title, sizeof title, "indentmap run: %s (%s)", scene->name, scene->path);
    int written = im_viewer_write(scene->output_dir, title);
    if (status == IM_OK)
        return written;
    im_fail(status, "%s", message);
    return status;
}

static int run_measured(const im_scene *scene, const im_scene_run_options *options);

/* Surface files are measured first (their h'rms is the theory's), on a copy: the caller's scene
 * stays as parsed. */
int im_scene_run(const im_scene *scene, const im_scene_run_options *options)
{
    im_scene *measured = malloc(sizeof *measured);
    if (!measured)
        return im_fail(IM_ENOMEM, "%s: allocation of the scene failed", scene->path);
    *measured = *scene;
    int status = im_scene_measure_files(measured);
    if (status == IM_OK && measured->file_count > 0)
        scene_progress(options, "surface files: h'rms = %.6g (forward differences of the surfaces as solved%s)",
                       measured->slopes[0], measured->file_count > 1 ? ", root mean square over the files" : "");
    if (status == IM_OK)
        status = run_measured(measured, options);
    free(measured);
    return status;
}

static int run_measured(const im_scene *scene, const im_scene_run_options *options)
{
    int status = check_runnable(scene);
    if (status == IM_OK)
        status = protect_inputs(scene);
    if (status == IM_OK)
        status = scene_check_limits(scene);
    if (status == IM_OK)
        status = im_make_directories(scene->output_dir);
    scene_lock lock = {.fd = -1};
    if (status == IM_OK)
        status = scene_lock_acquire(scene, &lock);
    if (status == IM_OK)
        remove_stale_temporaries(scene, options);
    if (status == IM_OK)
        status = scene_write_record(scene);
    const scene_ranks_run *ranks = scene_get_ranks_run(); /* an MPI run: the ranks solve the members first */
    if (status == IM_OK) {
        if (ranks)
            status = ranks->solve_members(scene, options, ranks->data);
        if (status == IM_OK)
            status = run_stages(scene, options);
        status = write_viewer_page(scene, status);
    }
    scene_lock_release(&lock);
    return status;
}
