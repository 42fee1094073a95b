/* The C API never crashes on misuse (issue 32; SQLite's rule: a misuse is reported, not undefined).
 *
 * Every public function that takes a handle, a field view, an output pointer or a size is called
 * here with a NULL handle, a NULL output, and (for field views) each view that breaks field.h's
 * invariants: NULL, data NULL, nx = -3, ny = 0, and a 2^20 x 2^20 view whose nx * ny overflows an
 * int. Each call runs in a child process, so a crash is reported as that case's failure (with the
 * signal) instead of ending the test. A case passes when the call returns IM_EINVAL (or, for a
 * function returning void or a value, gives its documented safe result) and im_last_error() names
 * the function and the argument. Functions documented to accept NULL (the *_free family) are
 * called with it too. No case may start computing in the child: OpenMP work begun in the parent
 * (the fixtures) deadlocks in a forked child, so a call that runs on past a missing check hangs
 * and is caught by the alarm.
 *
 * So that a new public function cannot go unchecked, the test reads every header in include/indentmap
 * and fails for a declared function that is neither exercised here nor listed in
 * `no_pointer_arguments` (functions of scalars only). */
#include "support.h"

#include "indentmap/colormap.h"
#include "indentmap/field.h"
#include "indentmap/figure.h"
#include "indentmap/formats.h"
#include "indentmap/indenter.h"
#include "indentmap/io.h"
#include "indentmap/history.h"
#include "indentmap/indent.h"
#include "indentmap/info.h"
#include "indentmap/measure.h"
#include "indentmap/mpi.h"
#include "indentmap/paper.h"
#include "indentmap/plot.h"
#include "indentmap/render.h"
#include "indentmap/scene.h"
#include "indentmap/scene_ranks.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"
#include "indentmap/theory.h"
#include "indentmap/viewer.h"

#include <ctype.h>
#include <dirent.h>
#include <libgen.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

/* ---- the cases ---- */

enum case_kind {
    REPORTED,           /* returns IM_EINVAL naming function and argument */
    REPORTED_AS_BEFORE, /* returns IM_EINVAL with the message it gave before (a size it always checked) */
    SAFE,               /* void or value: the expression is true for the documented safe result, and the
                 message names function and argument */
    ACCEPTED            /* NULL is documented as accepted: the expression is true, nothing else is asked */
};

typedef struct misuse_case {
    const char *function, *argument, *call;
    enum case_kind kind;
    int field_views; /* 1: run once with each invalid field view in BAD */
    int (*run)(void);
} misuse_case;

enum { MAX_CASES = 1024 };
static misuse_case cases[MAX_CASES];
static int case_count;

static void add_case(const char *function, const char *argument, const char *call, enum case_kind kind,
                     int field_views, int (*run)(void))
{
    if (case_count == MAX_CASES) { /* a case dropped would leave its function uncovered without a word */
        fprintf(stderr, "test_api_misuse: more than %d cases: raise MAX_CASES\n", MAX_CASES);
        abort();
    }
    cases[case_count++] = (misuse_case){function, argument, call, kind, field_views, run};
}

/* Each case is one line; it registers itself before main. */
#define CASE_AT2(line, kind, views, function, argument, expr)                                                        \
    static int misuse_##line(void) { return (int)(expr); }                                                           \
    __attribute__((constructor)) static void register_##line(void)                                                   \
    {                                                                                                                \
        add_case(#function, argument, #expr, kind, views, misuse_##line);                                            \
    }
#define CASE_AT(line, kind, views, function, argument, expr) CASE_AT2(line, kind, views, function, argument, expr)
/* A call that must return IM_EINVAL naming function and argument. */
#define REPORT(function, argument, expr) CASE_AT(__LINE__, REPORTED, 0, function, argument, expr)
#define REPORT_AS_BEFORE(function, expr) CASE_AT(__LINE__, REPORTED_AS_BEFORE, 0, function, "", expr)
/* The same, once for every invalid field view BAD. */
#define REPORT_VIEW(function, argument, expr) CASE_AT(__LINE__, REPORTED, 1, function, argument, expr)
/* A void or value call: expr is true when the result is the documented safe one. */
#define SAFE_RESULT(function, argument, expr)                                                                        \
    CASE_AT(__LINE__, SAFE, 0, function, argument, (expr) ? IM_EINVAL : IM_OK)
#define SAFE_VIEW(function, argument, expr) CASE_AT(__LINE__, SAFE, 1, function, argument, (expr) ? IM_EINVAL : IM_OK)
#define ACCEPT(function, expr) CASE_AT(__LINE__, ACCEPTED, 0, function, "", (expr) ? IM_EINVAL : IM_OK)

/* ---- fixtures, made once before the children fork ---- */

static double values[64], out_values[64], big_values[4096];
static im_unloading_branch branch; /* measured nothing: no note */
static im_field good = {8, 8, 1.0, "", values, ""};
static im_field bad_views[5];
static const char *bad_view_names[5] = {"NULL", "data NULL", "nx = -3", "ny = 0",
                                        "nx = ny = 2^20 (nx * ny overflows)"};
static const im_field *BAD; /* the invalid view of the case running */
static im_solver_plan *plan;
static im_solver_plan *convolution_plan; /* im_displacement_plan_create's: it convolves, never solves */
static im_indentation *run;
static im_flat_contact *flat;
static im_profile *profile;
static im_psd *psd;
static im_solver_options options;
static im_indenter cone, punch;
static im_theory_interface rough;
static im_theory_adhesion adhesion_law = {1.0, 0.1, 0.5};
static im_theory_adhesive_point adhesive_point;
static im_colormap colormap;
static im_colormap_range forces_range, unknown_range; /* unknown_range: values not an im_colormap_values */
static im_contact_style contact_style;
static im_height_style height_style;
static im_view3d_style view_style;
static im_plot plot;
static im_plot_panel plot_panel;
static im_figure figure;
static im_surface_params params;
static im_scene *scene; /* misuse.ini loaded: a scene file's */
static im_scene *scene_out;
static im_scene_run_options scene_options;                                  /* a run's defaults */
static im_indent_options indent_no_out, indent_no_targets, indent_no_steps; /* each lacking what it names */
static long contact[64];
static im_adhesion_summary adhesion;
static im_taper taper = {IM_TAPER_HANN, 1.0};
static int dummy_context; /* a non-NULL context that no function may touch before its checks */
#define CONTEXT ((im_render_context *)(void *)&dummy_context)
static const double r3[] = {0.0, 1.0, 2.0}, z3[] = {0.0, 1.0, 2.0};

/* outputs */
static im_field *field_out;
static im_profile *profile_out;
static im_psd *psd_out;
static int count_out;
static im_history_row history_row_out;
static char big_text[2048];
static im_histogram *histogram_out;
static im_solver_plan *plan_out;
static im_solver_memory memory_out;
static im_indentation *run_out;
static im_window window_out;
static im_flat_contact *flat_out;
static im_surface_stats stats;
static im_contact_patches patches;
static im_patch *patch_list;
static im_flat_result flat_result;
static im_step_result step_result;
static im_theory_k_fit k_fit;
static im_theory_step theory_step;
static im_image image, image_out;
static im_gif_options gif_options;
static im_plot_geometry geometry;
static im_atomic_file atomic;
static im_folder_lock lock;
static im_text_line line;
static double d, x, y;
static int i1, i2, i3;
static long l1, counts[64];
static char text[256];
static uint8_t rgb[3], pixels[4 * 64 * 64];
static uint8_t *pixels_out;
static FILE *stream;
static enum im_punch_kind kind;
static enum im_file_kind file_kind;
static im_colormap_id map_id;
static im_render_backend backend;
static im_figure_format figure_format;
static const double *r_out, *z_out;
static const im_field *field_samples;
static char *text_out;
static const char *path_text = "misuse.npy"; /* set to a path in the test's folder */

static void make_fixtures(void)
{
    indent_no_out = indent_no_targets = indent_no_steps = im_indent_options_default();
    indent_no_out.out = NULL;
    indent_no_out.targets = indent_no_steps.targets = values;
    indent_no_out.target_count = indent_no_targets.target_count = 1;
    for (int i = 0; i < 64; ++i)
        values[i] = 0.01 * (double)((i * 37) % 11);
    bad_views[0] = good; /* placeholder: case 0 passes NULL */
    bad_views[1] = good;
    bad_views[1].data = NULL;
    bad_views[2] = good;
    bad_views[2].nx = -3;
    bad_views[3] = good;
    bad_views[3].ny = 0;
    bad_views[4] = good;
    bad_views[4].nx = bad_views[4].ny = 1 << 20;
    bad_views[4].data = big_values;
    options = im_solver_options_default();
    cone = im_indenter_cone(80.0);
    rough = im_theory_interface_default(0.1);
    colormap = im_colormap_make(IM_COLORMAP_VIRIDIS, 0.0, 1.0);
    forces_range = im_colormap_range_empty(IM_COLORMAP_FORCES);
    unknown_range = im_colormap_range_empty((im_colormap_values)7);
    contact_style = im_contact_style_default(&good);
    height_style = im_height_style_default(&good);
    view_style = im_view3d_style_default(&good);
    plot = im_plot_default();
    plot_panel = (im_plot_panel){0};
    plot.panels = &plot_panel;
    figure = im_figure_default();
    gif_options = im_gif_options_default();
    params = im_surface_params_default();
    const char *scene_path = test_path("misuse.ini");
    test_write_bytes(scene_path, "[output]\ntable = yes\n", 21);
    assert_int_equal(im_scene_load(scene_path, &scene), IM_OK);
    assert_int_equal(im_solver_plan_create(8, 8, 1.0, &options, &plan), IM_OK);
    assert_int_equal(im_displacement_plan_create(8, 8, 1.0, &options, &convolution_plan), IM_OK);
    assert_int_equal(im_indentation_create(&good, &cone, IM_CONTROL_DISPLACEMENT, 0.5, &options, &run), IM_OK);
    assert_int_equal(im_flat_contact_create(&good, NULL, &flat), IM_OK);
    assert_int_equal(im_profile_axisymmetric(r3, z3, 3, &profile), IM_OK);
    assert_int_equal(im_surface_psd(&good, 4, &psd), IM_OK);
    path_text = strdup(test_path("misuse.npy"));
}

/* ---- status.h (the format through a variable: a literal NULL is refused by the compiler) ---- */
static const char *no_format;
REPORT(im_fail, "fmt", im_fail(IM_EIO, no_format))
REPORT(im_fail_context, "fmt", im_fail_context(IM_EIO, no_format))

/* ---- field.h ---- */
REPORT(im_field_create, "out", im_field_create(4, 4, 1.0, NULL))
REPORT_VIEW(im_field_clone, "src", im_field_clone(BAD, &field_out))
REPORT(im_field_clone, "out", im_field_clone(&good, NULL))
ACCEPT(im_field_free, (im_field_free(NULL), 1))
REPORT_VIEW(im_field_check_finite, "heights", im_field_check_finite(BAD, "heights"))
REPORT_VIEW(im_field_check_view, "field", im_field_check_view(BAD, NULL))
ACCEPT(im_field_count, im_field_count(NULL) == 0 && im_field_count(&bad_views[2]) == 0)
REPORT(im_memory_check, "what", im_memory_check(8.0, NULL))

/* ---- colormap.h ---- */
REPORT(im_colormap_from_name, "name", im_colormap_from_name(NULL, &map_id))
REPORT(im_colormap_from_name, "map", im_colormap_from_name("viridis", NULL))
REPORT(im_colormap_check, "colormap", im_colormap_check(NULL))
SAFE_RESULT(im_colormap_index, "colormap", im_colormap_index(NULL, 0.5) == -2)
SAFE_RESULT(im_colormap_rgb, "colormap", (im_colormap_rgb(NULL, 0.5, rgb), 1))
SAFE_RESULT(im_colormap_rgb, "rgb", (im_colormap_rgb(&colormap, 0.5, NULL), 1))
SAFE_RESULT(im_colormap_field_image, "colormap", (im_colormap_field_image(NULL, &good, pixels), 1))
SAFE_VIEW(im_colormap_field_image, "field", (im_colormap_field_image(&colormap, BAD, pixels), 1))
SAFE_RESULT(im_colormap_field_image, "rgb", (im_colormap_field_image(&colormap, &good, NULL), 1))
REPORT(im_colormap_range_add, "range", im_colormap_range_add(NULL, &good))
REPORT_VIEW(im_colormap_range_add, "field", im_colormap_range_add(&forces_range, BAD))
REPORT(im_colormap_range_clipped, "range",
       im_colormap_range_clipped(IM_COLORMAP_HEIGHTS, (im_field *const[]){&good}, 1, 1.0, NULL))
REPORT(im_colormap_range_clipped, "fields",
       im_colormap_range_clipped(IM_COLORMAP_HEIGHTS, NULL, 1, 1.0, &forces_range))
REPORT(im_colormap_range_clipped, "percent",
       im_colormap_range_clipped(IM_COLORMAP_HEIGHTS, (im_field *const[]){&good}, 1, 50.0, &forces_range))
REPORT_VIEW(im_colormap_range_clipped, "fields",
            im_colormap_range_clipped(IM_COLORMAP_FORCES, (im_field *const[]){(im_field *)BAD}, 1, 1.0,
                                      &forces_range))
REPORT(im_colormap_outlier_note, "fields", im_colormap_outlier_note(NULL, 1, big_text, sizeof big_text, &count_out))
REPORT(im_colormap_outlier_note, "text",
       im_colormap_outlier_note((im_field *const[]){&good}, 1, NULL, sizeof big_text, &count_out))
REPORT(im_colormap_outlier_note, "size",
       im_colormap_outlier_note((im_field *const[]){&good}, 1, big_text, 0, &count_out))
REPORT(im_colormap_outlier_note, "farthest",
       im_colormap_outlier_note((im_field *const[]){&good}, 1, big_text, sizeof big_text, NULL))
SAFE_RESULT(im_colormap_range_norm, "range", isnan(im_colormap_range_norm(NULL, IM_COLORMAP_MAGMA, NAN, NAN, 1).hi))
SAFE_RESULT(im_colormap_range_norm, "values",
            isnan(im_colormap_range_norm(&unknown_range, IM_COLORMAP_MAGMA, NAN, NAN, 1).lo))

/* ---- figure.h ---- */
REPORT(im_figure_format_of, "path", im_figure_format_of(NULL, &figure_format))
REPORT(im_figure_format_of, "format", im_figure_format_of("a.png", NULL))
REPORT(im_figure_write, "figure", im_figure_write(NULL, path_text))
REPORT(im_figure_write, "path", im_figure_write(&figure, NULL))
SAFE_RESULT(im_figure_ticks, "colormap", im_figure_ticks(NULL, out_values, 8) == 0)
SAFE_RESULT(im_figure_ticks, "ticks", im_figure_ticks(&colormap, NULL, 8) == 0)
/* ---- indent.h ---- */
REPORT(im_indent_run, "options", im_indent_run(NULL))
REPORT(im_indent_run, "options->out", im_indent_run(&indent_no_out))
REPORT(im_indent_run, "options->targets", im_indent_run(&indent_no_targets))
REPORT(im_indent_run, "options->target_count", im_indent_run(&indent_no_steps))
/* ---- info.h ---- */
REPORT(im_info_text, "text", im_info_text(IM_RENDER_AUTO, NULL))
REPORT(im_formats_text, "text", im_formats_text(NULL))
REPORT(im_figure_colorbar_label, "quantity", im_figure_colorbar_label(NULL, "N", text, sizeof text))
REPORT(im_figure_colorbar_label, "unit", im_figure_colorbar_label("force", NULL, text, sizeof text))
REPORT(im_figure_colorbar_label, "text", im_figure_colorbar_label("force", "N", NULL, sizeof text))
REPORT(im_figure_colorbar_label, "size", im_figure_colorbar_label("force", "N", text, 8))
REPORT(im_figure_colorbar_label, "quantity 'pressure'", im_figure_colorbar_label("pressure", "", text, sizeof text))
REPORT(im_frame_path, "buffer", im_frame_path(NULL, 64, "d", "p", 0))
REPORT(im_frame_path, "directory", im_frame_path(text, sizeof text, NULL, "p", 0))
REPORT(im_frame_path, "prefix", im_frame_path(text, sizeof text, "d", NULL, 0))
REPORT(im_animation_gif, "frames", im_animation_gif(NULL, 2, 0.1, path_text))
REPORT(im_animation_gif, "path", im_animation_gif(&image, 1, 0.1, NULL))
REPORT(im_animation_gif_with, "frames", im_animation_gif_with(NULL, 2, &gif_options, path_text))
REPORT(im_animation_gif_with, "options", im_animation_gif_with(&image, 1, NULL, path_text))
REPORT(im_animation_gif_with, "path", im_animation_gif_with(&image, 1, &gif_options, NULL))
REPORT(im_figure_write_frame, "figure", im_figure_write_frame(NULL, path_text, &image_out))
REPORT(im_figure_write_frame, "path", im_figure_write_frame(&figure, NULL, &image_out))
REPORT(im_figure_write_frame, "frame", im_figure_write_frame(&figure, path_text, NULL))
REPORT(im_animation_mp4, "directory", im_animation_mp4(NULL, "p", 2, 10.0, path_text))
REPORT(im_animation_mp4, "prefix", im_animation_mp4("d", NULL, 2, 10.0, path_text))
REPORT(im_animation_mp4, "path", im_animation_mp4("d", "p", 2, 10.0, NULL))

/* ---- indenter.h ---- */
ACCEPT(im_indenter_from_profile, (punch = im_indenter_from_profile(NULL), im_indenter_check(&punch) == IM_EINVAL))
REPORT(im_profile_axisymmetric, "r", im_profile_axisymmetric(NULL, z3, 3, &profile_out))
REPORT(im_profile_axisymmetric, "z", im_profile_axisymmetric(r3, NULL, 3, &profile_out))
REPORT(im_profile_axisymmetric, "out", im_profile_axisymmetric(r3, z3, 3, NULL))
REPORT_VIEW(im_profile_field, "heights", im_profile_field(BAD, &profile_out))
REPORT(im_profile_field, "out", im_profile_field(&good, NULL))
ACCEPT(im_profile_free, (im_profile_free(NULL), 1))
SAFE_RESULT(im_profile_kind, "profile", (int)im_profile_kind(NULL) == -1)
SAFE_RESULT(im_profile_extent, "profile", isnan(im_profile_extent(NULL)))
SAFE_RESULT(im_profile_samples, "profile",
            (r_out = z3, im_profile_samples(NULL, &r_out, &z_out, &i1, &field_samples), r_out == NULL && i1 == 0))
SAFE_RESULT(im_profile_samples, "r", (im_profile_samples(profile, NULL, NULL, NULL, NULL), 1))
REPORT(im_profile_read, "path", im_profile_read(NULL, 1.0, &profile_out))
REPORT(im_profile_read, "out", im_profile_read(path_text, 1.0, NULL))
REPORT(im_punch_parse, "name", im_punch_parse(NULL, &kind))
REPORT(im_punch_parse, "kind", im_punch_parse("cone", NULL))
REPORT(im_indenter_check, "punch", im_indenter_check(NULL))
SAFE_RESULT(im_indenter_profile, "punch", isnan(im_indenter_profile(NULL, 1.0)))
SAFE_RESULT(im_indenter_height, "punch", isnan(im_indenter_height(NULL, 1.0, 1.0)))
SAFE_RESULT(im_indenter_axis, "punch", (x = 0.0, im_indenter_axis(NULL, 8, 8, 1.0, &x, &y), isnan(x) && isnan(y)))
SAFE_RESULT(im_indenter_axis, "x", (im_indenter_axis(&cone, 8, 8, 1.0, NULL, NULL), 1))
SAFE_RESULT(im_indenter_load, "punch", isnan(im_indenter_load(NULL, 1.0, 1.0)))
SAFE_RESULT(im_indenter_contact_radius, "punch", isnan(im_indenter_contact_radius(NULL, 1.0)))
SAFE_RESULT(im_indenter_pressure, "punch", isnan(im_indenter_pressure(NULL, 1.0, 1.0, 0.5)))
SAFE_RESULT(im_indenter_approach_for_load, "punch", isnan(im_indenter_approach_for_load(NULL, 1.0, 1.0)))
SAFE_RESULT(im_indenter_area_for_load, "punch", isnan(im_indenter_area_for_load(NULL, 1.0, 1.0)))
/* A punch im_indenter_check refuses, or a modulus that is not finite and positive: NaN and the message, not a
 * number of the wrong sign (a 95-degree cone's Love load was -29.1 at w = 2, with no message). */
SAFE_RESULT(im_indenter_load, "alpha",
            isnan(im_indenter_load(&(im_indenter){.kind = IM_PUNCH_CONE, .alpha_degrees = 95}, 1.0, 2.0)))
SAFE_RESULT(im_indenter_load, "E*", isnan(im_indenter_load(&cone, -1.0, 2.0)))
SAFE_RESULT(im_indenter_contact_radius, "sphere radius = -1",
            isnan(im_indenter_contact_radius(&(im_indenter){.kind = IM_PUNCH_SPHERE, .radius = -1}, 1.0)))
SAFE_RESULT(im_indenter_pressure, "radius",
            isnan(im_indenter_pressure(&(im_indenter){.kind = IM_PUNCH_FLAT, .radius = NAN}, 1.0, 1.0, 0.5)))
SAFE_RESULT(im_indenter_pressure, "E*", isnan(im_indenter_pressure(&cone, NAN, 1.0, 0.5)))
SAFE_RESULT(im_indenter_approach_for_load, "E*", isnan(im_indenter_approach_for_load(&cone, 0.0, 1.0)))
SAFE_RESULT(im_indenter_area_for_load, "alpha",
            isnan(im_indenter_area_for_load(&(im_indenter){.kind = IM_PUNCH_CONE, .alpha_degrees = 0}, 1.0, 1.0)))

/* ---- io.h ---- */
REPORT(im_output_protect, "path", im_output_protect(NULL))
REPORT(im_output_check, "path", im_output_check(NULL))
REPORT(im_path_absolute, "path", im_path_absolute(NULL, text, sizeof text))
REPORT(im_path_absolute, "out", im_path_absolute("a", NULL, 64))
REPORT(im_path_join, "out", im_path_join(NULL, 64, "d", "n"))
REPORT(im_path_join, "dir", im_path_join(text, sizeof text, NULL, "n"))
REPORT(im_path_join, "name", im_path_join(text, sizeof text, "d", NULL))
REPORT(im_path_suffix, "out", im_path_suffix(NULL, 64, "p", ".json"))
REPORT(im_path_suffix, "path", im_path_suffix(text, sizeof text, NULL, ".json"))
REPORT(im_path_suffix, "suffix", im_path_suffix(text, sizeof text, "p", NULL))
SAFE_RESULT(im_file_kind_of_bytes, "bytes", im_file_kind_of_bytes(NULL, 16) == IM_KIND_NONE)
REPORT(im_file_kind_of, "path", im_file_kind_of(NULL, &file_kind))
REPORT(im_file_kind_of, "kind", im_file_kind_of(path_text, NULL))
REPORT(im_atomic_open, "file", im_atomic_open(NULL, path_text))
REPORT(im_atomic_open, "path", im_atomic_open(&atomic, NULL))
REPORT(im_atomic_open_suffixed, "file", im_atomic_open_suffixed(NULL, path_text, ".x"))
REPORT(im_atomic_open_suffixed, "path", im_atomic_open_suffixed(&atomic, NULL, ".x"))
REPORT(im_atomic_commit, "file", im_atomic_commit(NULL))
ACCEPT(im_atomic_abort, (im_atomic_abort(NULL), 1))
SAFE_RESULT(im_atomic_is_temporary_name, "name", im_atomic_is_temporary_name(NULL) == 0)
REPORT(im_write_file_atomic, "path", im_write_file_atomic(NULL, "x", 1))
REPORT(im_write_file_atomic, "data", im_write_file_atomic(path_text, NULL, 1))
REPORT(im_make_directories, "path", im_make_directories(NULL))
SAFE_RESULT(im_path_utf8, "path", (text[0] = 'x', im_path_utf8(NULL, text, sizeof text) == 0 && text[0] == '\0'))
SAFE_RESULT(im_path_utf8, "out", im_path_utf8("a", NULL, 64) == 0)
REPORT(im_folder_lock_acquire, "folder", im_folder_lock_acquire(NULL, "advice", &lock))
REPORT(im_folder_lock_acquire, "lock", im_folder_lock_acquire(test_temp_dir(), "advice", NULL))
ACCEPT(im_folder_lock_release, (im_folder_lock_release(NULL), 1))
REPORT(im_folder_lock_probe, "folder", im_folder_lock_probe(NULL, "advice"))
REPORT(im_folder_lock_probe, "advice", im_folder_lock_probe(test_temp_dir(), NULL))
SAFE_RESULT(im_folder_remove_temporaries, "folder", im_folder_remove_temporaries(NULL, 0) == 0)
SAFE_RESULT(im_pair_writers_lock, "path", im_pair_writers_lock(NULL) == -1)
ACCEPT(im_pair_writers_unlock, (im_pair_writers_unlock(-1), 1))
REPORT(im_read_open, "path", im_read_open(NULL, "r", IM_READ_REGULAR, &stream, NULL))
REPORT(im_read_open, "mode", im_read_open(path_text, NULL, IM_READ_REGULAR, &stream, NULL))
REPORT(im_read_open, "stream", im_read_open(path_text, "r", IM_READ_REGULAR, NULL, NULL))
REPORT(im_read_line, "stream", im_read_line(NULL, "p", 100, &line, &i1))
REPORT(im_read_line, "line", im_read_line(stdin, "p", 100, NULL, &i1))
REPORT(im_read_line, "end", im_read_line(stdin, "p", 100, &line, NULL))
REPORT(im_read_text_file, "path", im_read_text_file(NULL, 100, &text_out, NULL))
REPORT(im_read_text_file, "text", im_read_text_file(path_text, 100, NULL, NULL))
REPORT_VIEW(im_npy_write, "field", im_npy_write(path_text, BAD, IM_NPY_FLOAT64))
REPORT(im_npy_write, "path", im_npy_write(NULL, &good, IM_NPY_FLOAT64))
REPORT_VIEW(im_field_sidecar_write, "field", im_field_sidecar_write(path_text, BAD, "heights"))
REPORT(im_field_sidecar_write, "path", im_field_sidecar_write(NULL, &good, "heights"))
REPORT(im_npy_read, "path", im_npy_read(NULL, &field_out))
REPORT(im_npy_read, "out", im_npy_read(path_text, NULL))
REPORT_VIEW(im_text_write, "field", im_text_write(path_text, BAD))
REPORT(im_text_write, "path", im_text_write(NULL, &good))
REPORT(im_text_read, "path", im_text_read(NULL, &field_out))
REPORT(im_text_read, "out", im_text_read(path_text, NULL))
REPORT_VIEW(im_gsf_write, "field", im_gsf_write(path_text, BAD))
REPORT(im_gsf_write, "path", im_gsf_write(NULL, &good))
REPORT(im_gsf_read, "path", im_gsf_read(NULL, &field_out))
REPORT(im_gsf_read, "out", im_gsf_read(path_text, NULL))
REPORT_VIEW(im_sdf_write, "field", im_sdf_write(path_text, BAD))
REPORT(im_sdf_write, "path", im_sdf_write(NULL, &good))
REPORT(im_sdf_read, "path", im_sdf_read(NULL, &field_out))
REPORT(im_sdf_read, "out", im_sdf_read(path_text, NULL))
REPORT_VIEW(im_netcdf_write, "field", im_netcdf_write(path_text, BAD))
REPORT(im_netcdf_write, "path", im_netcdf_write(NULL, &good))
REPORT(im_netcdf_read, "path", im_netcdf_read(NULL, &field_out))
REPORT(im_netcdf_read, "out", im_netcdf_read(path_text, NULL))
REPORT_VIEW(im_x3p_write, "field", im_x3p_write(path_text, BAD))
REPORT(im_x3p_write, "path", im_x3p_write(NULL, &good))
REPORT(im_x3p_read, "path", im_x3p_read(NULL, &field_out))
REPORT(im_x3p_read, "out", im_x3p_read(path_text, NULL))
SAFE_RESULT(im_length_unit_metres, "name", im_length_unit_metres(NULL, NULL) == 0.0)
REPORT(im_surface_read_with, "path", im_surface_read_with(NULL, NULL, &field_out, NULL))
REPORT(im_surface_read_with, "out", im_surface_read_with(path_text, NULL, NULL, NULL))
REPORT(im_surface_read_with, "npy_order",
       im_surface_read_with(path_text, &(im_surface_read_options){.npy_order = (enum im_npy_order)7}, &field_out,
                            NULL))
REPORT(im_surface_read, "path", im_surface_read(NULL, &field_out))
REPORT(im_surface_read, "out", im_surface_read(path_text, NULL))
REPORT_VIEW(im_surface_write, "field", im_surface_write(path_text, BAD))
REPORT(im_surface_write, "path", im_surface_write(NULL, &good))
REPORT_VIEW(im_surface_write_with_sidecar, "surface", im_surface_write_with_sidecar(path_text, BAD, NULL, NULL, NULL))
REPORT(im_surface_write_with_sidecar, "path", im_surface_write_with_sidecar(NULL, &good, NULL, "s", NULL))
REPORT(im_png_write, "path", im_png_write(NULL, pixels, 4, 4, 3, 12, NULL))
REPORT(im_png_write, "pixels", im_png_write(path_text, NULL, 4, 4, 3, 12, NULL))
REPORT_AS_BEFORE(im_png_write, im_png_write(path_text, pixels, -3, 4, 3, 12, NULL))
REPORT(im_png_read, "path", im_png_read(NULL, &pixels_out, &i1, &i2, &i3))
REPORT(im_png_read, "pixels", im_png_read(path_text, NULL, &i1, &i2, &i3))
REPORT(im_png_read, "width", im_png_read(path_text, &pixels_out, NULL, &i2, &i3))
REPORT(im_png_read, "height", im_png_read(path_text, &pixels_out, &i1, NULL, &i3))
REPORT(im_png_read, "channels", im_png_read(path_text, &pixels_out, &i1, &i2, NULL))

/* ---- measure.h ---- */
REPORT(im_measure_stiffness, "approach", im_measure_stiffness(NULL, values, 3, out_values))
REPORT(im_measure_stiffness, "load", im_measure_stiffness(values, NULL, 3, out_values))
REPORT(im_measure_stiffness, "stiffness", im_measure_stiffness(values, values, 3, NULL))
REPORT(im_history_measure, "punch", im_history_measure(NULL, NULL, NULL, 1e-6, &history_row_out, 0))
REPORT(im_history_measure, "rows", im_history_measure(&cone, NULL, NULL, 1e-6, NULL, 0))
REPORT(im_history_measure, "tol", im_history_measure(&cone, NULL, NULL, NAN, &history_row_out, 0))
REPORT(im_history_measure, "tol", im_history_measure(&cone, NULL, NULL, -1e-6, &history_row_out, 0))
SAFE_RESULT(im_history_format, "row", im_history_format(NULL, big_text, sizeof big_text) == -1)
SAFE_RESULT(im_history_format, "line", im_history_format(&history_row_out, NULL, 0) == -1)
REPORT(im_history_write_analysis, "dir",
       im_history_write_analysis(NULL, &cone, &history_row_out, 1, 1, 1, "", "", &count_out))
REPORT(im_history_write_analysis, "punch",
       im_history_write_analysis(".", NULL, &history_row_out, 1, 1, 1, "", "", &count_out))
REPORT(im_history_write_analysis, "rows", im_history_write_analysis(".", &cone, NULL, 1, 1, 1, "", "", &count_out))
REPORT(im_history_write_analysis, "length_unit",
       im_history_write_analysis(".", &cone, &history_row_out, 1, 1, 1, NULL, "", &count_out))
REPORT(im_history_write_analysis, "force_unit",
       im_history_write_analysis(".", &cone, &history_row_out, 1, 1, 1, "", NULL, &count_out))
REPORT(im_history_write_analysis, "branches",
       im_history_write_analysis(".", &cone, &history_row_out, 1, 1, 1, "", "", NULL))
REPORT(im_history_write_analysis, "count",
       im_history_write_analysis(".", &cone, &history_row_out, -3, 1, 1, "", "", &count_out))
REPORT(im_history_units_json, "length_unit", im_history_units_json(NULL, "", 0, big_text, sizeof big_text))
REPORT(im_history_units_json, "e_star_unit", im_history_units_json("m", NULL, 0, big_text, sizeof big_text))
REPORT(im_history_units_json, "text", im_history_units_json("m", "Pa", 0, NULL, sizeof big_text))
REPORT(im_history_units_json, "size", im_history_units_json("m", "Pa", 0, big_text, 8))
REPORT(im_history_row_values, "row", im_history_row_values(NULL, big_values))
REPORT(im_history_row_values, "values", im_history_row_values(&history_row_out, NULL))
REPORT(im_history_row_from_values, "values", im_history_row_from_values(NULL, &history_row_out))
REPORT(im_history_row_from_values, "row", im_history_row_from_values(big_values, NULL))
SAFE_RESULT(im_history_parse, "text", im_history_parse(NULL, 1, &history_row_out, 1, &count_out, big_text, 64) == 0)
SAFE_RESULT(im_history_parse, "rows", im_history_parse("x", 1, NULL, 1, &count_out, big_text, 64) == 0)
SAFE_RESULT(im_history_parse, "count", im_history_parse("x", 1, &history_row_out, 1, NULL, big_text, 64) == 0)
SAFE_RESULT(im_history_parse, "why", im_history_parse("x", 1, &history_row_out, 1, &count_out, NULL, 64) == 0)
REPORT(im_measure_unloading, "punch", im_measure_unloading(NULL, values, values, NULL, 3, NULL, 0, &count_out))
REPORT(im_measure_unloading, "approach", im_measure_unloading(&cone, NULL, values, NULL, 3, NULL, 0, &count_out))
REPORT(im_measure_unloading, "load", im_measure_unloading(&cone, values, NULL, NULL, 3, NULL, 0, &count_out))
REPORT(im_measure_unloading, "found", im_measure_unloading(&cone, values, values, NULL, 3, NULL, 0, NULL))
REPORT(im_measure_unloading, "branches", im_measure_unloading(&cone, values, values, NULL, 3, NULL, 2, &count_out))
REPORT(im_measure_unloading_note, "branch", im_measure_unloading_note(NULL, big_text, sizeof big_text))
REPORT(im_measure_unloading_note, "text", im_measure_unloading_note(&branch, NULL, sizeof big_text))
REPORT(im_measure_unloading_note, "size", im_measure_unloading_note(&branch, big_text, 0))
SAFE_RESULT(im_measure_epsilon, "punch", isnan(im_measure_epsilon(NULL)))
SAFE_RESULT(im_measure_projected_area, "punch", isnan(im_measure_projected_area(NULL, 1.0)))
REPORT_VIEW(im_measure_contact_patches, "force", im_measure_contact_patches(BAD, &patches, NULL))
REPORT(im_measure_contact_patches, "out", im_measure_contact_patches(&good, NULL, NULL))
REPORT_VIEW(im_measure_gap_histogram, "gap", im_measure_gap_histogram(BAD, 1.0, 4, counts))
REPORT(im_measure_gap_histogram, "counts", im_measure_gap_histogram(&good, 1.0, 4, NULL))
REPORT_VIEW(im_measure_patch_list, "force", im_measure_patch_list(BAD, &patch_list, &l1))
REPORT(im_measure_patch_list, "patches", im_measure_patch_list(&good, NULL, &l1))
REPORT(im_measure_patch_list, "count", im_measure_patch_list(&good, &patch_list, NULL))
REPORT(im_measure_patch_histogram, "list", im_measure_patch_histogram(NULL, 2, counts, counts, counts))
REPORT_VIEW(im_measure_gap_distribution, "gap", im_measure_gap_distribution(BAD, &good, 1.0, 4, counts, &d, &l1))
REPORT_VIEW(im_measure_gap_distribution, "force", im_measure_gap_distribution(&good, BAD, 1.0, 4, counts, &d, &l1))
REPORT(im_measure_gap_distribution, "counts", im_measure_gap_distribution(&good, &good, 1.0, 4, NULL, &d, &l1))
REPORT(im_measure_gap_distribution, "bin_width", im_measure_gap_distribution(&good, &good, 1.0, 4, counts, NULL, &l1))
REPORT(im_measure_gap_distribution, "infinite", im_measure_gap_distribution(&good, &good, 1.0, 4, counts, &d, NULL))
REPORT_VIEW(im_measure_write_distributions, "force", im_measure_write_distributions(BAD, &good, 1.0, 4, path_text))
REPORT_VIEW(im_measure_write_distributions, "gap", im_measure_write_distributions(&good, BAD, 1.0, 4, path_text))
REPORT(im_measure_write_distributions, "prefix", im_measure_write_distributions(&good, &good, 1.0, 4, NULL))

/* ---- plot.h ---- */
REPORT(im_plot_write, "plot", im_plot_write(NULL, path_text))
REPORT(im_plot_write, "path", im_plot_write(&plot, NULL))
REPORT(im_plot_geometry_of, "plot", im_plot_geometry_of(NULL, 0, &geometry))
REPORT(im_plot_geometry_of, "geometry", im_plot_geometry_of(&plot, 0, NULL))
SAFE_RESULT(im_plot_palette, "rgb", (im_plot_palette(0, NULL), 1))
SAFE_RESULT(im_plot_family_color, "rgb", (im_plot_family_color(0, 2, NULL), 1))

/* ---- paper.h ---- */
REPORT(im_paper_fig1_contact_density, "slope_rms", im_paper_fig1_contact_density(80.0, NULL, 2, NULL, path_text))
REPORT(im_paper_fig1_contact_density, "path", im_paper_fig1_contact_density(80.0, values, 2, NULL, NULL))
REPORT(im_paper_fig2_area_ratio, "path", im_paper_fig2_area_ratio(NULL, NULL, NULL))
REPORT_VIEW(im_paper_fig3_surface, "surface", im_paper_fig3_surface(BAD, &params, 20, NULL, path_text))
REPORT(im_paper_fig3_surface, "params", im_paper_fig3_surface(&good, NULL, 20, NULL, path_text))
REPORT(im_paper_fig3_surface, "path", im_paper_fig3_surface(&good, &params, 20, NULL, NULL))

/* ---- render.h (CONTEXT is never touched: the checks come first) ---- */
REPORT(im_render_backend_from_name, "name", im_render_backend_from_name(NULL, &backend))
REPORT(im_render_backend_from_name, "backend", im_render_backend_from_name("auto", NULL))
REPORT(im_render_open, "out", im_render_open(IM_RENDER_AUTO, NULL))
SAFE_RESULT(im_render_context_missing, "message", im_render_context_missing(IM_EUNSUPPORTED, NULL) == 0)
ACCEPT(im_render_close, (im_render_close(NULL), 1))
SAFE_RESULT(im_render_backend_name, "context", im_render_backend_name(NULL) == NULL)
SAFE_RESULT(im_render_display_name, "context", im_render_display_name(NULL) == NULL)
SAFE_RESULT(im_render_gl_renderer, "context", im_render_gl_renderer(NULL) == NULL)
SAFE_RESULT(im_render_gl_version, "context", im_render_gl_version(NULL) == NULL)
ACCEPT(im_image_release, (im_image_release(NULL), 1))
SAFE_VIEW(im_contact_style_default, "force", im_contact_style_default(BAD).colormap.hi == 1.0)
SAFE_VIEW(im_contact_largest_tension, "force", im_contact_largest_tension(BAD) == 0.0)
REPORT(im_render_contact_map, "context", im_render_contact_map(NULL, &good, &contact_style, &image))
REPORT_VIEW(im_render_contact_map, "force", im_render_contact_map(CONTEXT, BAD, &contact_style, &image))
REPORT(im_render_contact_map, "style", im_render_contact_map(CONTEXT, &good, NULL, &image))
REPORT(im_render_contact_map, "image", im_render_contact_map(CONTEXT, &good, &contact_style, NULL))
SAFE_VIEW(im_height_style_default, "height", im_height_style_default(BAD).colormap.hi == 1.0)
SAFE_RESULT(im_height_outline_width, "style", im_height_outline_width(NULL) == 0)
REPORT(im_render_height_map, "context", im_render_height_map(NULL, &good, &height_style, &image))
REPORT_VIEW(im_render_height_map, "height", im_render_height_map(CONTEXT, BAD, &height_style, &image))
REPORT_VIEW(im_render_height_map, "contact",
            (height_style.contact = BAD ? BAD : &bad_views[1],
             im_render_height_map(CONTEXT, &good, &height_style, &image)))
REPORT(im_render_height_map, "style", im_render_height_map(CONTEXT, &good, NULL, &image))
REPORT(im_render_height_map, "image", im_render_height_map(CONTEXT, &good, &height_style, NULL))
SAFE_RESULT(im_view3d_style_default, "force", im_view3d_style_default(&bad_views[2]).width == 1920)
REPORT(im_render_view3d, "context", im_render_view3d(NULL, &good, &good, &cone, &view_style, &image))
REPORT_VIEW(im_render_view3d, "height", im_render_view3d(CONTEXT, BAD, &good, &cone, &view_style, &image))
REPORT(im_render_view3d, "force", im_render_view3d(CONTEXT, &good, &bad_views[2], &cone, &view_style, &image))
REPORT(im_render_view3d, "style", im_render_view3d(CONTEXT, &good, &good, &cone, NULL, &image))
REPORT(im_render_view3d, "image", im_render_view3d(CONTEXT, &good, &good, &cone, &view_style, NULL))
SAFE_RESULT(im_view3d_exaggeration_text, "text", (im_view3d_exaggeration_text(1.0, NULL, 64), 1))
REPORT_VIEW(im_view3d_fit_distance, "height", im_view3d_fit_distance(BAD, &cone, &view_style, &values[0]))
REPORT(im_view3d_fit_distance, "style", im_view3d_fit_distance(&good, &cone, NULL, &values[0]))
REPORT(im_view3d_fit_distance, "distance", im_view3d_fit_distance(&good, &cone, &view_style, NULL))

/* ---- scene.h ---- */
SAFE_RESULT(im_scene_plot_parse, "name", im_scene_plot_parse(NULL) == 0)
REPORT(im_scene_load, "path", im_scene_load(NULL, &scene_out))
REPORT(im_scene_load, "scene", im_scene_load(path_text, NULL))
REPORT(im_scene_load_record, "record", im_scene_load_record(NULL, &scene_out))
REPORT(im_scene_load_record, "scene", im_scene_load_record(path_text, NULL))
ACCEPT(im_scene_free, (im_scene_free(NULL), 1))
SAFE_RESULT(im_scene_path, "scene", strcmp(im_scene_path(NULL), "") == 0)
SAFE_RESULT(im_scene_name, "scene", strcmp(im_scene_name(NULL), "") == 0)
SAFE_RESULT(im_scene_output_dir, "scene", strcmp(im_scene_output_dir(NULL), "") == 0)
REPORT(im_scene_set_output_dir, "scene", im_scene_set_output_dir(NULL, "out"))
REPORT(im_scene_set_output_dir, "dir", im_scene_set_output_dir(scene, NULL))
SAFE_RESULT(im_scene_set_wisdom_path, "scene", (im_scene_set_wisdom_path(NULL, "w"), 1))
SAFE_RESULT(im_scene_recorded_plans, "scene", im_scene_recorded_plans(NULL) == -1)
SAFE_RESULT(im_scene_asks_for_output, "scene", im_scene_asks_for_output(NULL) == 0)
SAFE_RESULT(im_scene_renders, "scene", im_scene_renders(NULL) == 0)
REPORT(im_scene_run, "scene", im_scene_run(NULL, NULL))
REPORT(im_scene_run, "options", im_scene_run(scene, NULL))
REPORT(im_scene_check, "report", im_scene_check(scene, &scene_options, 1, NULL))
REPORT(im_scene_check, "scene", im_scene_check(NULL, &scene_options, 1, &text_out))
REPORT(im_scene_check, "options", im_scene_check(scene, NULL, 1, &text_out))
REPORT(im_scene_check, "ranks", im_scene_check(scene, &scene_options, 0, &text_out))
REPORT(im_scene_file_path, "scene", im_scene_file_path(NULL, 0, text, sizeof text))
REPORT(im_scene_file_path, "out", im_scene_file_path(scene, 0, NULL, 64))
SAFE_RESULT(im_scene_resolve_path, "scene",
            (text[0] = 'x', im_scene_resolve_path(NULL, "a", text, sizeof text), text[0] == '\0'))
SAFE_RESULT(im_scene_resolve_path, "relative",
            (text[0] = 'x', im_scene_resolve_path(scene, NULL, text, sizeof text), text[0] == '\0'))
SAFE_RESULT(im_scene_resolve_path, "out", (im_scene_resolve_path(scene, "a", NULL, 64), 1))
SAFE_RESULT(im_scene_suggest_key, "word", im_scene_suggest_key(NULL, NULL) == NULL)

/* ---- solver.h ---- */
REPORT(im_device_parse, "word", im_device_parse(NULL, &i1))
REPORT(im_device_parse, "device", im_device_parse("cpu", NULL))
REPORT(im_solver_options_check, "options", im_solver_options_check(NULL))
ACCEPT(im_solver_wisdom_file, im_solver_wisdom_file(NULL) == NULL) /* NULL options: no wisdom */
REPORT(im_solver_wisdom_check, "options", im_solver_wisdom_check(NULL))
REPORT(im_solver_wisdom_verify, "options", im_solver_wisdom_verify(NULL))
REPORT(im_quality_tolerance, "name", im_quality_tolerance(NULL, &d))
REPORT(im_quality_tolerance, "tol", im_quality_tolerance("draft", NULL))
REPORT(im_solver_plan_create, "out", im_solver_plan_create(8, 8, 1.0, &options, NULL))
REPORT(im_solver_plan_create, "nx", im_solver_plan_create(-3, 8, 1.0, &options, &plan_out))
ACCEPT(im_solver_plan_free, (im_solver_plan_free(NULL), 1))
SAFE_RESULT(im_solver_plan_bytes, "nx", isnan(im_solver_plan_bytes(-3, 8)))
REPORT(im_solver_memory_needed, "out", im_solver_memory_needed(8, 8, &options, NULL))
REPORT(im_solver_memory_needed, "nx", im_solver_memory_needed(-3, 8, &options, &memory_out))
REPORT(im_solver_plan_memory, "plan", im_solver_plan_memory(NULL, &memory_out))
REPORT(im_solver_plan_memory, "out", im_solver_plan_memory(NULL, NULL))
SAFE_RESULT(im_solver_plan_seconds, "plan", isnan(im_solver_plan_seconds(NULL)))
REPORT(im_measure_adhesion, "approach", im_measure_adhesion(NULL, values, contact, 2, 0, &adhesion))
REPORT(im_measure_adhesion, "load", im_measure_adhesion(values, NULL, contact, 2, 0, &adhesion))
REPORT(im_measure_adhesion, "contact", im_measure_adhesion(values, values, NULL, 2, 0, &adhesion))
REPORT(im_measure_adhesion, "out", im_measure_adhesion(values, values, contact, 2, 0, NULL))
SAFE_RESULT(im_adhesion_zone_length, "options", isnan(im_adhesion_zone_length(NULL)))
SAFE_RESULT(im_adhesion_maugis_lambda, "options", isnan(im_adhesion_maugis_lambda(NULL, 1.0)))
SAFE_RESULT(im_adhesion_tabor_mu, "options", isnan(im_adhesion_tabor_mu(NULL, 1.0)))
REPORT(im_adhesion_solved_law, "options", im_adhesion_solved_law(NULL, 1.0, &options, NULL))
REPORT(im_adhesion_solved_law, "solved", im_adhesion_solved_law(&options, 1.0, NULL, NULL))
REPORT(im_adhesion_law_parse, "word", im_adhesion_law_parse(NULL, &i1))
REPORT(im_adhesion_law_parse, "law", im_adhesion_law_parse("exponential", NULL))
SAFE_RESULT(im_solver_plan_device, "plan", im_solver_plan_device(NULL) == NULL)
SAFE_RESULT(im_solver_plan_measured, "plan", im_solver_plan_measured(NULL) == 0)
SAFE_RESULT(im_solver_convolve, "plan", (im_solver_convolve(NULL, values, out_values), 1))
SAFE_RESULT(im_solver_convolve, "pressure", (im_solver_convolve(plan, NULL, out_values), 1))
SAFE_RESULT(im_solver_convolve, "displacement", (im_solver_convolve(plan, values, NULL), 1))
REPORT_VIEW(im_displacement_full, "force", im_displacement_full(BAD, &options, &field_out))
REPORT(im_displacement_full, "displacement", im_displacement_full(&good, &options, NULL))
REPORT(im_displacement_plan_create, "plan", im_displacement_plan_create(8, 8, 1.0, &options, NULL))
REPORT(im_displacement_plan_create, "nx", im_displacement_plan_create(-3, 8, 1.0, &options, &plan_out))
REPORT(im_displacement_memory_needed, "out", im_displacement_memory_needed(8, 8, &options, NULL))
REPORT(im_displacement_memory_needed, "nx", im_displacement_memory_needed(-3, 8, &options, &memory_out))
REPORT(im_displacement_full_with, "plan", im_displacement_full_with(NULL, &good, &field_out))
REPORT_VIEW(im_displacement_full_with, "force", im_displacement_full_with(plan, BAD, &field_out))
REPORT(im_displacement_full_with, "displacement", im_displacement_full_with(plan, &good, NULL))
REPORT(im_solver_solve, "plan",
       im_solver_solve(NULL, values, IM_CONTROL_DISPLACEMENT, 0.1, out_values, big_values, NULL))
REPORT(im_solver_solve, "plan",
       im_solver_solve(convolution_plan, values, IM_CONTROL_DISPLACEMENT, 0.1, out_values, big_values, NULL))
REPORT(im_solver_solve, "gap0",
       im_solver_solve(plan, NULL, IM_CONTROL_DISPLACEMENT, 0.1, out_values, big_values, NULL))
REPORT(im_solver_solve, "pressure",
       im_solver_solve(plan, values, IM_CONTROL_DISPLACEMENT, 0.1, NULL, big_values, NULL))
REPORT(im_solver_solve, "displacement",
       im_solver_solve(plan, values, IM_CONTROL_DISPLACEMENT, 0.1, out_values, NULL, NULL))
REPORT_VIEW(im_flat_contact_create, "surface", im_flat_contact_create(BAD, NULL, &flat_out))
REPORT(im_flat_contact_create, "out", im_flat_contact_create(&good, NULL, NULL))
ACCEPT(im_flat_contact_free, (im_flat_contact_free(NULL), 1))
REPORT(im_flat_contact_solve, "run", im_flat_contact_solve(NULL, 0.1, &flat_result))
REPORT(im_flat_contact_solve, "out", im_flat_contact_solve(flat, 0.1, NULL))
REPORT(im_flat_contact_solve_gap, "run", im_flat_contact_solve_gap(NULL, 0.1, &flat_result))
REPORT(im_flat_contact_solve_gap, "out", im_flat_contact_solve_gap(flat, 0.1, NULL))
SAFE_RESULT(im_flat_contact_pressure, "run", im_flat_contact_pressure(NULL) == NULL)
REPORT_VIEW(im_indentation_create, "surface",
            im_indentation_create(BAD, &cone, IM_CONTROL_DISPLACEMENT, 0.5, &options, &run_out))
REPORT(im_indentation_create, "punch",
       im_indentation_create(&good, NULL, IM_CONTROL_DISPLACEMENT, 0.5, &options, &run_out))
REPORT(im_indentation_create, "out",
       im_indentation_create(&good, &cone, IM_CONTROL_DISPLACEMENT, 0.5, &options, NULL))
REPORT_VIEW(im_indentation_window_for, "surface",
            im_indentation_window_for(BAD, &cone, IM_CONTROL_DISPLACEMENT, 0.5, &options, &window_out))
REPORT(im_indentation_window_for, "punch",
       im_indentation_window_for(&good, NULL, IM_CONTROL_DISPLACEMENT, 0.5, &options, &window_out))
REPORT(im_indentation_window_for, "out",
       im_indentation_window_for(&good, &cone, IM_CONTROL_DISPLACEMENT, 0.5, &options, NULL))
ACCEPT(im_indentation_free, (im_indentation_free(NULL), 1))
REPORT(im_indentation_step, "run", im_indentation_step(NULL, 0.1, &step_result))
REPORT(im_indentation_step, "out", im_indentation_step(run, 0.1, NULL))
SAFE_RESULT(im_indentation_window, "run", im_indentation_window(NULL).nx == 0)
SAFE_RESULT(im_indentation_plan, "run", im_indentation_plan(NULL) == NULL)
REPORT(im_indentation_fields, "run", im_indentation_fields(NULL, &field_out, NULL, NULL))
REPORT(im_indentation_fields_full, "run", im_indentation_fields_full(NULL, &field_out, NULL, NULL))
REPORT(im_indentation_plastic, "run", im_indentation_plastic(NULL, &field_out))
REPORT(im_indentation_plastic, "plastic", im_indentation_plastic(run, NULL))

/* ---- surface.h ---- */
REPORT(im_surface_params_check, "params", im_surface_params_check(NULL))
REPORT(im_surface_generate, "params", im_surface_generate(NULL, &field_out))
REPORT(im_surface_generate, "out", im_surface_generate(&params, NULL))
SAFE_RESULT(im_surface_generate_bytes, "nx", isnan(im_surface_generate_bytes(-3, 8)))
REPORT_VIEW(im_surface_slope_rms, "surface", im_surface_slope_rms(BAD, IM_SLOPE_SPECTRAL, &d))
REPORT(im_surface_slope_rms, "slope_rms", im_surface_slope_rms(&good, IM_SLOPE_SPECTRAL, NULL))
REPORT_VIEW(im_surface_statistics, "surface", im_surface_statistics(BAD, &stats))
REPORT(im_surface_statistics, "stats", im_surface_statistics(&good, NULL))
REPORT_VIEW(im_surface_check_height_range, "surface", im_surface_check_height_range(BAD, "s"))
ACCEPT(im_surface_check_height_range, im_surface_check_height_range(&good, NULL) == IM_OK)
REPORT_VIEW(im_surface_psd, "surface", im_surface_psd(BAD, 4, &psd_out))
REPORT(im_surface_psd, "out", im_surface_psd(&good, 4, NULL))
ACCEPT(im_psd_free, (im_psd_free(NULL), 1))
REPORT(im_psd_fit_exponent, "psd", im_psd_fit_exponent(NULL, 0.1, 1.0, &d))
REPORT(im_psd_fit_exponent, "exponent", im_psd_fit_exponent(psd, 0.1, 1.0, NULL))
REPORT_VIEW(im_surface_histogram, "surface", im_surface_histogram(BAD, IM_HIST_HEIGHT, 8, &histogram_out))
REPORT(im_surface_histogram, "out", im_surface_histogram(&good, IM_HIST_HEIGHT, 8, NULL))
ACCEPT(im_histogram_free, (im_histogram_free(NULL), 1))
REPORT(im_surface_sidecar_write, "path", im_surface_sidecar_write(NULL, &good, NULL, "s", NULL))
REPORT_VIEW(im_surface_sidecar_write, "surface", im_surface_sidecar_write(path_text, BAD, NULL, "s", NULL))
REPORT(im_surface_generator_record, "params", im_surface_generator_record(NULL, &text_out))
REPORT(im_surface_generator_record, "text", im_surface_generator_record(&params, NULL))
REPORT(im_surface_generator_parse, "text", im_surface_generator_parse(NULL, &params))
REPORT(im_surface_generator_parse, "params", im_surface_generator_parse("{}", NULL))
SAFE_RESULT(im_surface_expected_height_rms, "params", isnan(im_surface_expected_height_rms(NULL, 0.1)))
SAFE_RESULT(im_surface_height_rms_eq15, "params", isnan(im_surface_height_rms_eq15(NULL, 0.1)))
REPORT_VIEW(im_surface_crop, "surface", im_surface_crop(BAD, 0, 0, 2, 2, &field_out))
REPORT(im_surface_crop, "out", im_surface_crop(&good, 0, 0, 2, 2, NULL))
REPORT_VIEW(im_surface_fill_missing, "surface", im_surface_fill_missing((im_field *)BAD, &l1))
REPORT(im_surface_fill_missing, "filled", im_surface_fill_missing(&good, NULL))
REPORT_VIEW(im_surface_resample_square, "field", im_surface_resample_square(BAD, 1.0, 2.0, &field_out))
REPORT(im_surface_resample_square, "out", im_surface_resample_square(&good, 1.0, 2.0, NULL))
REPORT_VIEW(im_surface_detrend, "surface", im_surface_detrend((im_field *)BAD, IM_DETREND_PLANE))
REPORT_VIEW(im_surface_align_rows, "surface", im_surface_align_rows((im_field *)BAD, IM_ALIGN_MEDIAN))
REPORT_VIEW(im_surface_tapered, "surface", im_surface_tapered(BAD, &taper, &field_out))
REPORT(im_surface_tapered, "out", im_surface_tapered(&good, &taper, NULL))
REPORT_VIEW(im_surface_statistics_tapered, "surface", im_surface_statistics_tapered(BAD, &taper, &stats))
REPORT(im_surface_statistics_tapered, "stats", im_surface_statistics_tapered(&good, &taper, NULL))

/* ---- theory.h ---- */
REPORT(im_theory_p_rough, "rough", im_theory_p_rough(NULL, &d))
REPORT(im_theory_p_rough, "p_rough", im_theory_p_rough(&rough, NULL))
REPORT(im_theory_normalising_pressure, "rough", im_theory_normalising_pressure(NULL, &d))
REPORT(im_theory_normalising_pressure, "p_n", im_theory_normalising_pressure(&rough, NULL))
REPORT(im_theory_flat_area_ratio, "rough", im_theory_flat_area_ratio(NULL, 0.1, &d))
REPORT(im_theory_flat_area_ratio, "ratio", im_theory_flat_area_ratio(&rough, 0.1, NULL))
REPORT(im_theory_hertz_area, "area", im_theory_hertz_area(1.0, 1.0, 1.0, NULL))
REPORT(im_theory_sphere_area, "rough", im_theory_sphere_area(NULL, 1.0, 1.0, &d))
REPORT(im_theory_sphere_area, "area", im_theory_sphere_area(&rough, 1.0, 1.0, NULL))
REPORT(im_theory_sphere_crossover_load, "rough", im_theory_sphere_crossover_load(NULL, 1.0, &d))
REPORT(im_theory_sphere_crossover_load, "load", im_theory_sphere_crossover_load(&rough, 1.0, NULL))
REPORT(im_theory_cone_mean_pressure, "p_mean", im_theory_cone_mean_pressure(80.0, 1.0, NULL))
REPORT(im_theory_cone_area, "area", im_theory_cone_area(1.0, 80.0, 1.0, NULL))
REPORT(im_theory_cone_rho, "rough", im_theory_cone_rho(NULL, 80.0, &d))
REPORT(im_theory_cone_rho, "rho_c", im_theory_cone_rho(&rough, 80.0, NULL))
REPORT(im_theory_erf_scale, "beta", im_theory_erf_scale(1.0, IM_THEORY_NORMALISATION_PR, 2.0, NULL))
REPORT(im_theory_cone_area_small_rho, "rough", im_theory_cone_area_small_rho(NULL, 1.0, &d))
REPORT(im_theory_cone_area_small_rho, "area", im_theory_cone_area_small_rho(&rough, 1.0, NULL))
REPORT(im_theory_cone_area_ratio_constant, "ratio", im_theory_cone_area_ratio_constant(1.0, NULL))
REPORT(im_theory_cone_area_ratio_variable, "ratio", im_theory_cone_area_ratio_variable(1.0, NULL))
REPORT(im_theory_cone_area_ratio_greenwood, "ratio", im_theory_cone_area_ratio_greenwood(1.0, NULL))
REPORT(im_theory_cone_pressure, "p_over_mean", im_theory_cone_pressure(0.5, NULL))
REPORT(im_theory_cone_contact_density, "gamma", im_theory_cone_contact_density(1.0, 0.5, NULL))
REPORT(im_theory_punch_pressure, "p_over_mean", im_theory_punch_pressure(IM_PUNCH_CONE, 0.5, NULL))
REPORT(im_theory_punch_contact_density, "gamma", im_theory_punch_contact_density(IM_PUNCH_CONE, 1.0, 0.5, NULL))
REPORT(im_theory_punch_area_ratio, "ratio", im_theory_punch_area_ratio(IM_PUNCH_CONE, 1.0, NULL))
REPORT(im_theory_maugis_lambda, "law", im_theory_maugis_lambda(NULL, 10.0, &d))
REPORT(im_theory_maugis_lambda, "lambda", im_theory_maugis_lambda(&adhesion_law, 10.0, NULL))
REPORT(im_theory_md_sphere, "law", im_theory_md_sphere(NULL, 10.0, 1.0, &adhesive_point))
REPORT(im_theory_md_sphere, "out", im_theory_md_sphere(&adhesion_law, 10.0, 1.0, NULL))
REPORT(im_theory_md_sphere_pull_off, "law", im_theory_md_sphere_pull_off(NULL, 10.0, &adhesive_point))
REPORT(im_theory_md_sphere_pull_off, "out", im_theory_md_sphere_pull_off(&adhesion_law, 10.0, NULL))
REPORT(im_theory_md_sphere_separation, "law", im_theory_md_sphere_separation(NULL, 10.0, &adhesive_point))
REPORT(im_theory_md_sphere_separation, "out", im_theory_md_sphere_separation(&adhesion_law, 10.0, NULL))
REPORT(im_theory_md_sphere_load_at_approach, "law", im_theory_md_sphere_load_at_approach(NULL, 10.0, 1.0, &d))
REPORT(im_theory_md_sphere_load_at_approach, "load",
       im_theory_md_sphere_load_at_approach(&adhesion_law, 10.0, 1.0, NULL))
REPORT(im_theory_kendall_pull_off, "law", im_theory_kendall_pull_off(NULL, 10.0, &adhesive_point))
REPORT(im_theory_kendall_pull_off, "out", im_theory_kendall_pull_off(&adhesion_law, 10.0, NULL))
REPORT(im_theory_kendall_load_at_approach, "law", im_theory_kendall_load_at_approach(NULL, 10.0, 1.0, &d))
REPORT(im_theory_kendall_load_at_approach, "load", im_theory_kendall_load_at_approach(&adhesion_law, 10.0, 1.0, NULL))
REPORT(im_theory_jkr_cone, "law", im_theory_jkr_cone(NULL, 80.0, 1.0, &adhesive_point))
REPORT(im_theory_jkr_cone, "out", im_theory_jkr_cone(&adhesion_law, 80.0, 1.0, NULL))
REPORT(im_theory_jkr_cone_pull_off, "law", im_theory_jkr_cone_pull_off(NULL, 80.0, &adhesive_point))
REPORT(im_theory_jkr_cone_pull_off, "out", im_theory_jkr_cone_pull_off(&adhesion_law, 80.0, NULL))
REPORT(im_theory_punch_mean_pressure, "p_mean", im_theory_punch_mean_pressure(IM_PUNCH_CONE, 80.0, 1.0, 1.0, NULL))
REPORT(im_theory_fit_k, "pressure_ratio", im_theory_fit_k(NULL, values, 2, &k_fit))
REPORT(im_theory_fit_k, "area_fraction", im_theory_fit_k(values, NULL, 2, &k_fit))
REPORT(im_theory_fit_k, "out", im_theory_fit_k(values, values, 2, NULL))
REPORT(im_theory_step_columns, "punch", im_theory_step_columns(NULL, &rough, 1.0, 1.0, &theory_step))
REPORT(im_theory_step_columns, "rough", im_theory_step_columns(&cone, NULL, 1.0, 1.0, &theory_step))
REPORT(im_theory_step_columns, "out", im_theory_step_columns(&cone, &rough, 1.0, 1.0, NULL))

/* ---- viewer.h ---- */
REPORT(im_viewer_write, "dir", im_viewer_write(NULL, "title"))
REPORT(im_viewer_write, "title", im_viewer_write(test_temp_dir(), NULL))
REPORT(im_viewer_write_with, "dir", im_viewer_write_with(NULL, "title", &(im_viewer_options){0}))
REPORT(im_viewer_write_with, "title", im_viewer_write_with(test_temp_dir(), NULL, &(im_viewer_options){0}))
REPORT(im_viewer_write_with, "options", im_viewer_write_with(test_temp_dir(), "title", NULL))

/* ---- mpi.h (the checks come before any MPI call: MPI is not initialised here) ---- */
#if IM_HAVE_MPI
static int mpi_rows[2];
REPORT(im_mpi_solver_create, "out", im_mpi_solver_create(MPI_COMM_WORLD, 8, 8, 1.0, &options, NULL))
ACCEPT(im_mpi_solver_free, (im_mpi_solver_free(NULL), 1))
SAFE_RESULT(im_mpi_solver_rows, "solver",
            (mpi_rows[1] = 7, im_mpi_solver_rows(NULL, &mpi_rows[0], &mpi_rows[1]), mpi_rows[1] == 0))
SAFE_RESULT(im_mpi_solver_bytes, "nx", isnan(im_mpi_solver_bytes(-3, 8, 2)))
SAFE_RESULT(im_mpi_convolve, "solver", (im_mpi_convolve(NULL, values, out_values), 1))
REPORT(im_mpi_solver_solve, "solver",
       im_mpi_solver_solve(NULL, values, IM_CONTROL_DISPLACEMENT, 0.1, out_values, big_values, NULL))
static im_mpi_flat_contact *mpi_flat_out;
REPORT(im_mpi_flat_contact_create, "out", im_mpi_flat_contact_create(NULL, values, NULL))
REPORT(im_mpi_flat_contact_create, "solver", im_mpi_flat_contact_create(NULL, values, &mpi_flat_out))
ACCEPT(im_mpi_flat_contact_free, (im_mpi_flat_contact_free(NULL), 1))
REPORT(im_mpi_flat_contact_solve, "run", im_mpi_flat_contact_solve(NULL, 0.1, &flat_result))
REPORT(im_mpi_flat_contact_solve_gap, "run", im_mpi_flat_contact_solve_gap(NULL, 0.1, &flat_result))
SAFE_RESULT(im_mpi_flat_contact_pressure, "run", im_mpi_flat_contact_pressure(NULL) == NULL)
REPORT(im_mpi_flat_contact_gap, "run", im_mpi_flat_contact_gap(NULL, out_values))
REPORT(im_mpi_flat_contact_step, "run", im_mpi_flat_contact_step(NULL, IM_CONTROL_LOAD, 0.1, &step_result))
REPORT(im_mpi_flat_contact_adhesion, "run", im_mpi_flat_contact_adhesion(NULL, &options))
static im_mpi_indentation *mpi_indentation_out;
REPORT(im_mpi_indentation_create, "out",
       im_mpi_indentation_create(NULL, values, &cone, IM_CONTROL_DISPLACEMENT, 1, &options, NULL))
REPORT(im_mpi_indentation_create, "solver",
       im_mpi_indentation_create(NULL, values, &cone, IM_CONTROL_LOAD, 1, NULL, &mpi_indentation_out))
ACCEPT(im_mpi_indentation_free, (im_mpi_indentation_free(NULL), 1))
REPORT(im_mpi_indentation_step, "run", im_mpi_indentation_step(NULL, 0.1, &step_result))
SAFE_RESULT(im_mpi_indentation_pressure, "run", im_mpi_indentation_pressure(NULL) == NULL)
REPORT(im_mpi_indentation_gap, "run", im_mpi_indentation_gap(NULL, out_values))
REPORT(im_mpi_undeformed_gap, "solver", im_mpi_undeformed_gap(NULL, values, &cone, out_values))
REPORT(im_mpi_check_edge, "solver", im_mpi_check_edge(NULL, values))
REPORT(im_mpi_gather_map, "solver", im_mpi_gather_map(NULL, values, 1, &field_out))
REPORT(im_mpi_surface_generate, "params", im_mpi_surface_generate(MPI_COMM_WORLD, NULL, 0, 1, out_values))
REPORT(im_mpi_surface_generate, "heights", im_mpi_surface_generate(MPI_COMM_WORLD, &params, 0, 1, NULL))
REPORT(im_mpi_npy_shape, "path", im_mpi_npy_shape(MPI_COMM_WORLD, NULL, &i1, &i2))
REPORT(im_mpi_npy_shape, "nx", im_mpi_npy_shape(MPI_COMM_WORLD, path_text, NULL, &i2))
REPORT(im_mpi_npy_shape, "ny", im_mpi_npy_shape(MPI_COMM_WORLD, path_text, &i1, NULL))
REPORT(im_mpi_npy_read_rows, "path", im_mpi_npy_read_rows(MPI_COMM_WORLD, NULL, 0, 1, out_values))
REPORT(im_mpi_npy_read_rows, "data", im_mpi_npy_read_rows(MPI_COMM_WORLD, path_text, 0, 1, NULL))
REPORT(im_mpi_npy_write_rows, "path", im_mpi_npy_write_rows(MPI_COMM_WORLD, NULL, 8, 8, 0, 1, values))
REPORT(im_mpi_npy_write_rows, "data", im_mpi_npy_write_rows(MPI_COMM_WORLD, path_text, 8, 8, 0, 1, NULL))
REPORT(im_scene_run_ranks, "scene", im_scene_run_ranks(MPI_COMM_WORLD, NULL, NULL))
REPORT(im_scene_run_ranks, "options", im_scene_run_ranks(MPI_COMM_WORLD, scene, NULL))
REPORT(im_scene_check_ranks, "report", im_scene_check_ranks(MPI_COMM_WORLD, scene, &scene_options, NULL))
REPORT(im_scene_check_ranks, "scene", im_scene_check_ranks(MPI_COMM_WORLD, NULL, &scene_options, &text_out))
REPORT(im_scene_check_ranks, "options", im_scene_check_ranks(MPI_COMM_WORLD, scene, NULL, &text_out))
#endif

/* ---- sizes and enumerations out of range (the checks most functions always had) ---- */
REPORT_AS_BEFORE(im_field_create, im_field_create(-3, 4, 1.0, &field_out))
REPORT_AS_BEFORE(im_surface_psd, im_surface_psd(&good, -3, &psd_out))
REPORT_AS_BEFORE(im_surface_histogram, im_surface_histogram(&good, IM_HIST_HEIGHT, 0, &histogram_out))
REPORT_AS_BEFORE(im_surface_histogram, im_surface_histogram(&good, (enum im_histogram_quantity)99, 8, &histogram_out))
REPORT_AS_BEFORE(im_surface_slope_rms, im_surface_slope_rms(&good, (enum im_slope_definition)99, &d))
REPORT_AS_BEFORE(im_surface_detrend, im_surface_detrend(&good, (enum im_detrend)99))
REPORT_AS_BEFORE(im_surface_align_rows, im_surface_align_rows(&good, (enum im_row_alignment)99))
REPORT_AS_BEFORE(im_surface_crop, im_surface_crop(&good, -3, 0, 2, 2, &field_out))
REPORT_AS_BEFORE(im_surface_crop, im_surface_crop(&good, 0, 0, 1 << 30, 2, &field_out))
REPORT_AS_BEFORE(im_surface_resample_square, im_surface_resample_square(&good, 1.0, NAN, &field_out))
REPORT_AS_BEFORE(im_measure_stiffness, im_measure_stiffness(values, values, -3, out_values))
REPORT_AS_BEFORE(im_measure_gap_histogram, im_measure_gap_histogram(&good, 1.0, 0, counts))
REPORT_AS_BEFORE(im_measure_gap_distribution, im_measure_gap_distribution(&good, &good, 1.0, -3, counts, &d, &l1))
REPORT_AS_BEFORE(im_measure_patch_histogram, im_measure_patch_histogram(patch_list, -3, counts, counts, counts))
REPORT_AS_BEFORE(im_profile_axisymmetric, im_profile_axisymmetric(r3, z3, -3, &profile_out))
REPORT_AS_BEFORE(im_theory_fit_k, im_theory_fit_k(values, values, -3, &k_fit))
REPORT_AS_BEFORE(im_theory_punch_pressure, im_theory_punch_pressure((enum im_punch_kind)99, 0.5, &d))
REPORT_AS_BEFORE(im_animation_gif, im_animation_gif(&image, -3, 0.1, path_text))
REPORT_AS_BEFORE(im_frame_path, im_frame_path(text, 0, "d", "p", 0))
REPORT_AS_BEFORE(im_frame_path, im_frame_path(text, sizeof text, "d", "p", -3))
REPORT_AS_BEFORE(im_path_join, im_path_join(text, 0, "d", "n"))
REPORT_AS_BEFORE(im_path_suffix, im_path_suffix(text, 0, "p", ".json"))
REPORT_AS_BEFORE(im_path_absolute, im_path_absolute("a", text, 0))
REPORT_AS_BEFORE(im_scene_file_path, im_scene_file_path(scene, -3, text, sizeof text))
REPORT_AS_BEFORE(im_plot_geometry_of, im_plot_geometry_of(&plot, -3, &geometry))
REPORT_AS_BEFORE(im_paper_fig1_contact_density, im_paper_fig1_contact_density(80.0, values, -3, NULL, path_text))
REPORT_AS_BEFORE(im_paper_fig3_surface, im_paper_fig3_surface(&good, &params, -3, NULL, path_text))
REPORT_AS_BEFORE(im_png_write, im_png_write(path_text, pixels, 4, 4, 5, 20, NULL))
REPORT_AS_BEFORE(im_png_write, im_png_write(path_text, pixels, 4, 4, 3, 2, NULL))
REPORT_AS_BEFORE(im_solver_solve,
                 im_solver_solve(plan, values, (enum im_control)99, 0.1, out_values, big_values, NULL))
REPORT_AS_BEFORE(im_indentation_create,
                 im_indentation_create(&good, &cone, (enum im_control)99, 0.5, &options, &run_out))
ACCEPT(im_figure_ticks, im_figure_ticks(&colormap, out_values, -3) == 0)
ACCEPT(im_path_utf8, im_path_utf8("a", text, 0) == 0)
ACCEPT(im_view3d_exaggeration_text, (im_view3d_exaggeration_text(1.0, text, 0), 1))
ACCEPT(im_scene_resolve_path, (im_scene_resolve_path(scene, "a", text, 0), 1))
ACCEPT(im_colormap_name, strcmp(im_colormap_name((im_colormap_id)99), "unknown") == 0)
ACCEPT(im_colormap_table, im_colormap_table((im_colormap_id)99) == im_colormap_table(IM_COLORMAP_VIRIDIS))
ACCEPT(im_colormap_make, im_colormap_make((im_colormap_id)99, 0.0, 1.0).hi == 1.0)
ACCEPT(im_punch_name, strcmp(im_punch_name((enum im_punch_kind)99), "unknown") == 0)
ACCEPT(im_adhesion_law_name, im_adhesion_law_name(-1) == NULL && im_adhesion_law_name(99) == NULL)
ACCEPT(im_file_kind_name, strcmp(im_file_kind_name((enum im_file_kind)99), "unknown") == 0)
ACCEPT(im_strstatus, im_strstatus(99) != NULL && im_strstatus(-1) != NULL)
ACCEPT(im_scene_plot_name, im_scene_plot_name((enum im_scene_plot)(1u << 30)) == NULL)

/* ---- pointers inside the structures passed ---- */
static im_plot plot_of(const im_plot_panel *panels)
{
    im_plot p = im_plot_default();
    p.panels = panels;
    return p;
}
static im_plot_series series_xy(const double *xs, const double *ys)
{
    return (im_plot_series){.x = xs, .y = ys, .n = 3};
}
static im_plot_panel panel_of(const im_plot_series *series)
{
    return (im_plot_panel){.series = series, .series_count = 1};
}
static im_plot_series series;
static im_paper_points points;
REPORT_AS_BEFORE(im_plot_write, (plot = plot_of(NULL), im_plot_write(&plot, path_text)))
REPORT_AS_BEFORE(im_plot_write, (series = series_xy(NULL, values), plot_panel = panel_of(&series),
                                 plot = plot_of(&plot_panel), im_plot_write(&plot, path_text)))
REPORT_AS_BEFORE(im_plot_write, (series = series_xy(values, NULL), plot_panel = panel_of(&series),
                                 plot = plot_of(&plot_panel), im_plot_write(&plot, path_text)))
REPORT_AS_BEFORE(im_plot_write, (plot_panel = (im_plot_panel){.series = NULL, .series_count = 2},
                                 plot = plot_of(&plot_panel), im_plot_write(&plot, path_text)))
REPORT_AS_BEFORE(im_plot_write, (plot = plot_of(&plot_panel), plot.texts = NULL, plot.text_count = 3,
                                 im_plot_write(&plot, path_text)))
REPORT_AS_BEFORE(im_paper_fig2_area_ratio, (points = (im_paper_points){.x = NULL, .y = values, .count = 3},
                                            im_paper_fig2_area_ratio(&points, NULL, path_text)))
REPORT_AS_BEFORE(im_figure_write,
                 (figure = im_figure_default(), figure.panels = NULL, im_figure_write(&figure, path_text)))
REPORT_AS_BEFORE(im_figure_write, (figure = im_figure_default(), figure.panels = &(im_figure_panel){.image = NULL},
                                   im_figure_write(&figure, path_text)))
REPORT_AS_BEFORE(im_figure_write, (figure = im_figure_default(), figure.panels = &(im_figure_panel){.image = &image},
                                   figure.texts = NULL, figure.text_count = 2, im_figure_write(&figure, path_text)))
REPORT(im_png_write, "texts",
       im_png_write(path_text, pixels, 4, 4, 3, 12, &(im_png_options){.texts = NULL, .text_count = 2}))
REPORT(im_png_write, "texts",
       im_png_write(path_text, pixels, 4, 4, 3, 12,
                    &(im_png_options){.texts = &(im_png_text){"k", NULL}, .text_count = 1}))
REPORT_AS_BEFORE(im_indentation_create,
                 (punch = im_indenter_cone(80.0), punch.kind = IM_PUNCH_PROFILE, punch.profile = NULL,
                  im_indentation_create(&good, &punch, IM_CONTROL_DISPLACEMENT, 0.5, &options, &run_out)))
REPORT_AS_BEFORE(im_animation_gif, (image = (im_image){.width = 4, .height = 4, .rgba = NULL},
                                    im_animation_gif(&image, 1, 0.1, path_text)))

/* Public functions of scalars only (or of a pointer they document as accepting NULL, such as
 * im_set_stop_flag's): nothing to misuse here. A new function belongs either here or in a case
 * above. */
static const char *const no_pointer_arguments[] = {
    "im_colormap_make",
    "im_colormap_name",
    "im_colormap_table",
    "im_colormap_range_empty",
    "im_contact_tension_norm",
    "im_memory_available",
    "im_memory_set_limit",
    "im_memory_limit",
    "im_address_space_available",
    "im_figure_default",
    "im_gif_options_default",
    "im_gwyddion_reader",
    "im_ffmpeg_available",
    "im_indenter_cone",
    "im_indenter_sphere",
    "im_indenter_flat",
    "im_punch_name",
    "im_output_protect_reset",
    "im_file_kind_name",
    "im_atomic_remove_temporaries",
    "im_measure_sneddon_modulus",
    "im_history_columns",
    "im_history_integer_columns",
    "im_mpi_init",
    "im_mpi_cleanup",
    "im_plot_default",
    "im_scene_plot_name",
    "im_solver_options_default",
    "im_indent_options_default",
    "im_quality_default_tolerance",
    "im_influence_square",
    "im_strstatus",
    "im_last_error",
    "im_set_stop_flag",
    "im_stop_requested",
    "im_surface_params_default",
    "im_theory_interface_default",
    "im_theory_wavy1d_area_fraction",
    "im_theory_wavy2d_light_area_fraction",
    "im_theory_wavy2d_near_full_area_fraction",
    "im_theory_moment",
    "im_theory_height_rms_moments",
    "im_theory_height_rms_eq15",
};

/* ---- running the cases ---- */

typedef struct outcome {
    int signal; /* the signal that ended the child, 0 if none */
    int status; /* the call's return value */
    char message[400];
} outcome;

static outcome run_isolated(const misuse_case *c, int view)
{
    outcome result = {0};
    int pipe_fd[2];
    assert_int_equal(pipe(pipe_fd), 0);
    fflush(NULL);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        close(pipe_fd[0]);
        const int fatal[] = {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT}; /* not cmocka's handlers */
        for (size_t i = 0; i < sizeof fatal / sizeof *fatal; ++i)
            signal(fatal[i], SIG_DFL);
        alarm(20); /* a call that hangs is a failure too (SIGALRM) */
        BAD = view == 0 ? NULL : &bad_views[view];
        im_fail(IM_OK, "%s", "");
        outcome child = {0};
        child.status = c->run();
        snprintf(child.message, sizeof child.message, "%s", im_last_error());
        ssize_t written = write(pipe_fd[1], &child, sizeof child);
        _exit(written == (ssize_t)sizeof child ? 0 : 3);
    }
    close(pipe_fd[1]);
    ssize_t got = read(pipe_fd[0], &result, sizeof result);
    close(pipe_fd[0]);
    int wstatus = 0;
    waitpid(pid, &wstatus, 0);
    if (WIFSIGNALED(wstatus))
        result.signal = WTERMSIG(wstatus);
    else if (got != (ssize_t)sizeof result || WEXITSTATUS(wstatus) != 0)
        result.signal = -1; /* exited without reporting (exit() or abort inside the call) */
    return result;
}

/* NULL when the case passed, else why not (a static buffer). */
static const char *judge(const misuse_case *c, const outcome *o)
{
    static char why[600];
    if (o->signal > 0)
        snprintf(why, sizeof why, "crashed (signal %d, %s)", o->signal, strsignal(o->signal));
    else if (o->signal < 0)
        snprintf(why, sizeof why, "ended the process without returning");
    else if (o->status != IM_EINVAL)
        snprintf(why, sizeof why, "%s (status %d), message '%s'",
                 c->kind != SAFE ? "did not return IM_EINVAL" : "did not give the safe result", o->status,
                 o->message);
    else if (c->kind == REPORTED_AS_BEFORE && !o->message[0])
        snprintf(why, sizeof why, "no message");
    else if (c->kind != ACCEPTED && c->kind != REPORTED_AS_BEFORE &&
             (!strstr(o->message, c->function) || (c->argument[0] && !strstr(o->message, c->argument))))
        snprintf(why, sizeof why, "message '%s' does not name %s and '%s'", o->message, c->function, c->argument);
    else
        return NULL;
    return why;
}

static void every_misuse_is_reported(void **state)
{
    (void)state;
    make_fixtures();
    int failures = 0, runs = 0;
    for (int i = 0; i < case_count; ++i) {
        const misuse_case *c = &cases[i];
        int views = c->field_views ? 5 : 1;
        for (int v = 0; v < views; ++v) {
            outcome o = run_isolated(c, v);
            const char *why = judge(c, &o);
            ++runs;
            if (why) {
                ++failures;
                printf("FAIL %s%s%s: %s\n     %s\n", c->function, c->field_views ? " with a view " : "",
                       c->field_views ? bad_view_names[v] : "", why, c->call);
            }
        }
    }
    printf("%d misuse calls of %d cases, %d failed\n", runs, case_count, failures);
    im_indentation_free(run);
    im_solver_plan_free(plan);
    im_solver_plan_free(convolution_plan);
    im_flat_contact_free(flat);
    im_profile_free(profile);
    im_psd_free(psd);
    free((void *)path_text);
    if (failures)
        fail_msg("%d of %d misuse calls crashed or were not reported (listed above)", failures, runs);
}

/* ---- every declared function is covered ---- */

static int covered(const char *name)
{
    for (int i = 0; i < case_count; ++i)
        if (strcmp(cases[i].function, name) == 0)
            return 1;
    for (size_t i = 0; i < sizeof no_pointer_arguments / sizeof *no_pointer_arguments; ++i)
        if (strcmp(no_pointer_arguments[i], name) == 0)
            return 1;
    return 0;
}

/* The header's text without comments and preprocessor lines. */
static char *declarations_of(const char *path)
{
    FILE *file = fopen(path, "r");
    assert_non_null(file);
    char *text_in = calloc(1, 1 << 20), *out = calloc(1, 1 << 20);
    size_t n = fread(text_in, 1, (1 << 20) - 1, file);
    fclose(file);
    size_t o = 0;
    for (size_t i = 0; i < n; ++i) {
        if (text_in[i] == '/' && text_in[i + 1] == '*') {
            char *end = strstr(text_in + i + 2, "*/");
            i = end ? (size_t)(end - text_in) + 1 : n;
        } else if (text_in[i] == '#' && (i == 0 || text_in[i - 1] == '\n')) {
            while (i < n && text_in[i] != '\n')
                i += text_in[i] == '\\' ? 2 : 1;
        } else {
            out[o++] = text_in[i];
        }
    }
    free(text_in);
    return out;
}

static void every_public_function_is_covered(void **state)
{
    (void)state;
    /* the source tree: $IM_SOURCE_DIR (ctest sets it), else the folder above this file's */
    const char *source = getenv("IM_SOURCE_DIR");
    char folder[4096];
    if (source)
        snprintf(folder, sizeof folder, "%s/include/indentmap", source);
    else {
        char here[4096];
        snprintf(here, sizeof here, "%s", __FILE__);
        snprintf(folder, sizeof folder, "%s/../include/indentmap", dirname(here));
    }
    DIR *dir = opendir(folder);
    assert_non_null(dir);
    int missing = 0, functions = 0;
    for (struct dirent *entry; (entry = readdir(dir));) {
        size_t length = strlen(entry->d_name);
        if (length < 3 || strcmp(entry->d_name + length - 2, ".h") != 0)
            continue;
        char path[8192];
        snprintf(path, sizeof path, "%s/%s", folder, entry->d_name);
        char *text_h = declarations_of(path);
        /* a function: im_NAME followed by '(' (types, macros and enumerators are not) */
        for (char *p = text_h; (p = strstr(p, "im_"));) {
            char *start = p;
            if (start > text_h && (isalnum((unsigned char)start[-1]) || start[-1] == '_')) {
                ++p;
                continue;
            }
            while (isalnum((unsigned char)*p) || *p == '_')
                ++p;
            char name[128];
            snprintf(name, sizeof name, "%.*s", (int)(p - start), start);
            char *q = p;
            while (*q == ' ' || *q == '\n')
                ++q;
            if (*q != '(')
                continue;
            ++functions;
            if (!covered(name)) {
                ++missing;
                printf("%s (%s): neither called with misuse in test_api_misuse.c nor listed in "
                       "no_pointer_arguments\n",
                       name, entry->d_name);
            }
        }
        free(text_h);
    }
    closedir(dir);
    printf("%d public function names checked\n", functions);
    assert_true(functions > 200);
    if (missing)
        fail_msg("%d public functions are not covered", missing);
}

/* Where NULL options are documented as the defaults, they give the defaults' result bit for bit.
 * (Run here, not in a child: a forked child must not start OpenMP work its parent began.) */
static void null_options_are_the_defaults(void **state)
{
    (void)state;
    for (int i = 0; i < 64; ++i)
        values[i] = (i % 9 == 4) ? 0.25 : 0.0;
    im_solver_options defaults = im_solver_options_default();
    im_field *u_null = NULL, *u_default = NULL;
    assert_int_equal(im_displacement_full(&good, NULL, &u_null), IM_OK);
    assert_int_equal(im_displacement_full(&good, &defaults, &u_default), IM_OK);
    assert_memory_equal(u_null->data, u_default->data, sizeof values);
    assert_null(im_solver_wisdom_file(NULL));
    im_field_free(u_null);
    im_field_free(u_default);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(null_options_are_the_defaults),
        cmocka_unit_test(every_public_function_is_covered),
        cmocka_unit_test(every_misuse_is_reported),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
