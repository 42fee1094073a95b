/* One indentation run into its folder (indentmap/indent.h: im_indent_run), as `indentmap indent` and
 * Python make it: the surface read and prepared, the punch, the solver, the folder, then the steps
 * (indent_run.c), run.json (indent_record.c) and what follows the steps (indent_results.c). */
#include "front/indent_run.h"
#include "core/args.h"

#include "indentmap/indent.h"
#include "indentmap/io.h"
#include "indentmap/status.h"

#include <limits.h>
#include <math.h>
#include <omp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

im_indent_options im_indent_options_default(void)
{
    return (im_indent_options){.nx = 512,
                               .ny = 512,
                               .delta = 1,
                               .slope_definition = -1,
                               .punch = im_indenter_cone(80),
                               .control = IM_CONTROL_DISPLACEMENT,
                               .solver = im_solver_options_default(),
                               .out = "output/indent"};
}

void indent_say(const indent_run_state *s, im_log_level level, const char *format, ...)
{
    if (!s->options->log)
        return;
    char line[8192];
    va_list arguments;
    va_start(arguments, format);
    vsnprintf(line, sizeof line, format, arguments);
    va_end(arguments);
    s->options->log(s->options->user, level, line);
}

const char *indent_target_name(enum im_control control)
{
    return control == IM_CONTROL_LOAD ? "load" : control == IM_CONTROL_MEAN_GAP ? "mean_gap" : "approach";
}

static indent_files files_of(const im_indent_options *o)
{
    return (indent_files){o->fields || o->frames, o->solver.hardness, o->distributions, o->target_count};
}

run_folder_rules indent_folder_rules(const im_indent_options *o, const indent_files *files)
{
    return (run_folder_rules){.dir = o->out,
                              .option = "--out",
                              .lock_advice = "give this run another --out",
                              .wisdom_advice = "give another --wisdom (or IM_FFTW_WISDOM) or another --out",
                              .claims = indent_files_claims,
                              .state = files};
}

int indent_run_check(const im_indent_options *o)
{
    const char *const inputs[] = {o->surface_path, o->profile_path};
    const indent_files files = files_of(o);
    const run_folder_rules rules = indent_folder_rules(o, &files);
    return run_folder_check(&rules, inputs, 2, &o->solver);
}

/* ---- warnings ---- */

/* Small-slope (linear) elasticity assumes the surface slopes are small; a steep cone's flank,
 * slope cot(alpha), stretches it. Warn, but still solve: the answer is the model's, not nature's. */
#define STEEP_CONE_DEGREES 60.0

static void warn_if_steep(const indent_run_state *s)
{
    const im_indenter *punch = &s->punch;
    if (punch->kind == IM_PUNCH_CONE && punch->alpha_degrees > 0 && punch->alpha_degrees < STEEP_CONE_DEGREES)
        indent_say(s, IM_LOG_WARNING,
                   "warning: alpha = %g degrees: the cone flank's slope cot(alpha) = %.3g is not small; small-slope "
                   "elasticity is stretched (alpha >= %g advised)",
                   punch->alpha_degrees, 1 / tan(punch->alpha_degrees * M_PI / 180), STEEP_CONE_DEGREES);
}

/* The same for the surface: the half-space's small-slope elasticity and the paper's theory assume
 * slopes well below 1 and, for a cone, below its flank's; a measured part can be far beyond both
 * (finding D17: a machined part with h'rms 1.15 under an 80 degree cone, flank 0.176). */
static void warn_if_rough_beyond_small_slopes(const indent_run_state *s)
{
    const double flank = s->punch.kind == IM_PUNCH_CONE ? 1 / tan(s->punch.alpha_degrees * M_PI / 180) : INFINITY;
    if (s->theory_slope > 1.0)
        indent_say(s, IM_LOG_WARNING,
                   "warning: the surface's h'rms = %.3g: slopes steeper than 45 degrees on average, where "
                   "small-slope elasticity is stretched",
                   s->theory_slope);
    if (s->theory_slope > flank)
        indent_say(s, IM_LOG_WARNING,
                   "warning: the surface's h'rms = %.3g is %.3g times the cone flank's slope cot(alpha) = %.3g: the "
                   "roughness, not the cone, shapes the contact, beyond the paper's theory (h'rms below cot(alpha))",
                   s->theory_slope, s->theory_slope / flank, flank);
}

/* A measured surface beyond small slopes, mostly filled, or with heights in a unit its file does not state. */
static void warn_about_surface(const indent_run_state *s, const im_field *surface)
{
    if (s->smooth)
        return;
    warn_if_rough_beyond_small_slopes(s);
    char warning[8192];
    if (surface_fill_warning(s->options->surface_path, s->filled, im_field_count(surface), warning, sizeof warning))
        indent_say(s, IM_LOG_WARNING, "%s", warning);
    if (surface_assumption_warning(s->options->surface_path, &s->read_info, warning, sizeof warning))
        indent_say(s, IM_LOG_WARNING, "%s", warning);
}

/* Said once before the steps: a Dugdale zone shorter than a patch is not resolved. */
static void warn_if_zone_unresolved(const indent_run_state *s, const im_solver_options *solved)
{
    const double patches = im_adhesion_zone_length(solved) / s->surface_delta;
    if (patches < 1)
        indent_say(s, IM_LOG_WARNING,
                   "warning: the adhesive zone's length pi E* D^2 / (8 W) = %.3g patches is below one patch: the "
                   "grid does not resolve it and the pull-off comes out too strong (a sphere: 8%% at 0.33 patches, 5 "
                   "times at 0.03; 0.6%% at 3): use a finer delta, a wider --adhesion-range or --adhesion-zone 1",
                   patches);
}

/* Said once before the steps: with --adhesion-zone, the law solved and the law asked (run.json "adhesion"). */
static void say_adhesion_law(const indent_run_state *s)
{
    const im_solver_options *asked = &s->options->solver;
    im_solver_options solved;
    int widened = 0;
    if (im_adhesion_solved_law(asked, s->surface_delta, &solved, &widened) != IM_OK)
        return; /* (the run solving it checked the options) */
    warn_if_zone_unresolved(s, &solved);
    if (!(asked->adhesion_zone > 0))
        return;
    const double patches = im_adhesion_zone_length(asked) / s->surface_delta;
    if (!widened) {
        indent_say(s, IM_LOG_INFO, "adhesion zone %.4g patches already spans --adhesion-zone %g: the law as given",
                   patches, asked->adhesion_zone);
        return;
    }
    char mu[128] = "";
    if (s->punch.kind == IM_PUNCH_SPHERE)
        snprintf(mu, sizeof mu, ", Tabor mu %.4g (asked %.4g)", im_adhesion_tabor_mu(&solved, s->punch.radius),
                 im_adhesion_tabor_mu(asked, s->punch.radius));
    indent_say(s, IM_LOG_INFO,
               "adhesion zone widened from %.4g to %g patches at the same work: range %.6g (asked %.6g), stress "
               "%.6g (asked %.6g)%s; a smoother law than the one asked (docs/solver.md, \"Across Tabor's mu\")",
               patches, asked->adhesion_zone, solved.adhesion_range, asked->adhesion_range,
               solved.adhesion_work / solved.adhesion_range, asked->adhesion_work / asked->adhesion_range, mu);
}

/* ---- the surface and the punch ---- */

static int load_surface(indent_run_state *s, im_field **surface)
{
    const im_indent_options *o = s->options;
    if (!s->smooth) {
        int status = im_surface_read_with(o->surface_path, &o->read, surface, &s->read_info);
        s->filled = status == IM_OK ? s->read_info.filled : 0;
        const surface_preparation preparation = {{o->crop[0], o->crop[1], o->crop[2], o->crop[3]},
                                                 o->detrend,
                                                 o->align};
        if (status == IM_OK && (status = surface_prepare(&preparation, surface)) != IM_OK)
            im_fail_context(status, "%s", o->surface_path);
        return status;
    }
    int status = im_field_create(o->nx, o->ny, o->delta, surface);
    if (status == IM_OK)
        memcpy((*surface)->unit, o->read.set.lateral, sizeof(*surface)->unit);
    return status;
}

/* The profile, read now that the surface's spacing (a 2-D profile's) and length unit are known. */
static int load_profile(indent_run_state *s, const im_field *surface)
{
    if (!s->options->profile_path)
        return IM_OK;
    int status = im_profile_read(s->options->profile_path, surface->delta, &s->profile);
    if (status != IM_OK)
        return im_fail_context(status, "--profile");
    const im_indenter given = s->punch;
    s->punch = im_indenter_from_profile(s->profile);
    s->punch.centred = given.centred;
    s->punch.x0 = given.x0;
    s->punch.y0 = given.y0;
    return im_indenter_check(&s->punch);
}

/* A periodic cell: the rigid flat when no punch was given (a flat punch wider than the cell's diagonal
 * covers every nearest image), loads from mean pressures, and a warning when the surface is not
 * periodic (the solver joins its edges, as ContactMechanics warns). */
static void prepare_periodic(indent_run_state *s, const im_field *surface)
{
    const im_indent_options *o = s->options;
    if (!o->solver.periodic)
        return;
    s->cell_area = periodic_cell_area(surface);
    if (!o->punch_given)
        s->punch = periodic_rigid_flat(surface);
    for (int i = 0; o->pressures && i < o->target_count; ++i)
        s->targets[i] *= s->cell_area;
    char warning[8192];
    if (periodic_warning(surface, s->smooth ? "the surface" : o->surface_path, warning, sizeof warning))
        indent_say(s, IM_LOG_WARNING, "%s", warning);
}

/* A punch placed off its centre must have its axis on the surface (before: "the surface is too small"). */
static int check_axis_inside(const indent_run_state *s, const im_field *surface)
{
    const im_indenter *p = &s->options->punch;
    double width = surface->nx * surface->delta, height = surface->ny * surface->delta;
    if (p->centred || (p->x0 >= 0 && p->x0 <= width && p->y0 >= 0 && p->y0 <= height))
        return IM_OK;
    return im_fail(IM_EINVAL,
                   "--x %g --y %g: the punch's axis lies outside the %d x %d surface (expected 0 <= x <= "
                   "%g and 0 <= y <= %g)",
                   p->x0, p->y0, surface->nx, surface->ny, width, height);
}

/* The h'rms definition when none is given, into s with what chose it: spectral for a cell solved as
 * periodic and a flat surface, a generated surface's own (its sidecar's: the definition of its target, so
 * that a generated surface gives a generated family's numbers, as scenes' files do, scene/surfaces.c), and
 * forward differences for a measured one. */
static void default_slope_definition(indent_run_state *s)
{
    const im_indent_options *o = s->options;
    const int generated = s->smooth ? IM_SLOPE_SPECTRAL : surface_sidecar_slope_definition(o->surface_path);
    if (o->solver.periodic) {
        s->slope_definition = IM_SLOPE_SPECTRAL;
        s->slope_reason = "default: a periodic cell";
    } else if (generated >= 0) {
        s->slope_definition = generated;
        s->slope_reason = generated == IM_SLOPE_SPECTRAL ? "default: a generated surface (its target's definition)"
                                                         : "default: a generated surface of forward-difference h'rms "
                                                           "(its target's definition)";
    } else {
        s->slope_definition = IM_SLOPE_FINITE_DIFFERENCE;
        s->slope_reason = "default: a measured surface";
    }
}

/* The theory columns' interface: the surface's h'rms (the options' definition, else the default's), the
 * solver's E*, k = 2 and the PR normalisation. */
static int measured_interface(indent_run_state *s, const im_field *surface, im_theory_interface *rough)
{
    const im_indent_options *o = s->options;
    s->slope_definition = o->slope_definition;
    if (s->slope_definition < 0)
        default_slope_definition(s);
    else
        s->slope_reason = "--slope-definition";
    double slope;
    int status = im_surface_slope_rms(surface, (enum im_slope_definition)s->slope_definition, &slope);
    if (status == IM_OK) {
        *rough = im_theory_interface_default(slope);
        rough->e_star = o->solver.e_star;
        s->theory_slope = slope;
    }
    return status;
}

/* The unit of the distributions' gaps: the surface's h_rms, its delta when it is flat. */
static int set_gap_scale(indent_run_state *s, const im_field *surface)
{
    im_surface_stats stats;
    int status = im_surface_statistics(surface, &stats);
    if (status == IM_OK)
        s->gap_scale = stats.height_rms > 0.0 ? stats.height_rms : surface->delta;
    return status;
}

/* The surface read and prepared, the punch placed on it, what the run derives from both. */
static int prepare_surface(indent_run_state *s, im_field **surface, im_theory_interface *rough)
{
    int status = s->punch.kind == IM_PUNCH_PROFILE ? IM_OK /* checked once read, after the surface */
                                                   : im_indenter_check(&s->punch);
    if (status == IM_OK) {
        warn_if_steep(s);
        status = load_surface(s, surface);
    }
    if (status == IM_OK)
        status = load_profile(s, *surface);
    if (status == IM_OK) {
        prepare_periodic(s, *surface);
        status = check_axis_inside(s, *surface);
    }
    if (status == IM_OK) {
        s->surface_delta = (*surface)->delta;
        memcpy(s->length_unit, (*surface)->unit, sizeof s->length_unit);
        step_force_unit(s->options->e_star_unit ? s->options->e_star_unit : "", (*surface)->unit, s->force_unit,
                        sizeof s->force_unit);
        status = measured_interface(s, *surface, rough);
    }
    if (status == IM_OK)
        warn_about_surface(s, *surface);
    return status == IM_OK ? set_gap_scale(s, *surface) : status;
}

/* ---- the steps ---- */

/* Once per run, after the steps, one line naming every step whose contact the grid does not resolve: a few
 * patches (a smooth cone at 1 patch carries 2.4x Love's load, at 9 patches 1.05x; issue 32), or a smooth
 * punch's contact radius at the step's load, sqrt(A_smooth(N) / pi), of under RESOLVED_RADIUS patches
 * (the contact's own where it is larger: adhesion),
 * where the load is resolved but the area is not: a smooth cone's A/A_cone on a 64^2 grid, w = 0.2..6, is
 * 1.42 at 21 patches (radius 2.6), 1.11 at 89, 1.058 at 293 (radius 9.7), within 1.037 from 333 on
 * (redteam4). Nothing else would say so (S13: said of the first such step only). A long list ends in
 * "and N more". */
enum { RESOLVED_PATCHES = 10, RESOLVED_RADIUS = 10 };

/* The contact radius in patches: of the smooth punch's area at the load, or of the contact's own area where
 * it is larger (adhesion holds more than A_smooth(N), and all of it where N <= 0: A_smooth 0 or NaN). NaN
 * on a periodic cell, whose contact has no radius. */
static double contact_radius_patches(const indent_run_state *s, const im_history_row *row)
{
    if (s->options->solver.periodic)
        return NAN;
    const double d2 = s->surface_delta * s->surface_delta;
    return sqrt(fmax(row->theory.area_smooth, (double)row->result.contact_patches * d2) / M_PI) / s->surface_delta;
}

static int unresolved(const indent_run_state *s, const im_history_row *row)
{
    const long n = row->result.contact_patches;
    return n > 0 && (n < RESOLVED_PATCHES || contact_radius_patches(s, row) < RESOLVED_RADIUS);
}

/* Appends "K (N patches)" to the list, with the radius where the patches alone would not say why. */
static void note_unresolved(const indent_run_state *s, const im_history_row *row, int k, int named, char *list,
                            size_t size)
{
    const long n = row->result.contact_patches;
    char radius[40] = "";
    if (n >= RESOLVED_PATCHES)
        snprintf(radius, sizeof radius, ", radius %.1f", contact_radius_patches(s, row));
    const size_t used = strlen(list);
    snprintf(list + used, size - used, "%s%d (%ld patch%s%s)", named ? ", " : "", k + 1, n, n == 1 ? "" : "es",
             radius);
}

/* What the grid's resolution costs, as measured for the run's punch: the flat punch's face is its own set of
 * patches (64^2, w = 1: A/A_punch and N/N_Boussinesq 1.59 and 1.18 at radius 1, 1.026 and 0.991 at 3, 1.009
 * and 0.995 at 10); the cone's numbers stand for the other punches, named as the cone's. */
static void resolution_cost(const indent_run_state *s, char *text, size_t size)
{
    const int flat = s->punch.kind == IM_PUNCH_FLAT && !s->options->solver.periodic; /* a cell's flat has no face */
    if (flat) {
        snprintf(text, size,
                 "a smooth flat punch's face of radius 1 patch covers 5 patches, its area A/A_punch 1.59 and its "
                 "load 1.18x Boussinesq's; of radius 3, 1.026 and 0.99x; of radius 10, 1.009 and 0.995x");
        return;
    }
    snprintf(text, size,
             "%sa smooth cone carries 2.4x Love's load at 1 patch, 1.05x at 9; its area A/A_cone is off by up to "
             "42%% where the contact radius spans under %d patches, 4%% beyond",
             s->punch.kind == IM_PUNCH_CONE ? "" : "as measured for a cone: ", RESOLVED_RADIUS);
}

static void warn_if_unresolved(const indent_run_state *s, const im_history_row *rows, int done)
{
    char steps[640] = "";
    int named = 0, unnamed = 0;
    for (int k = 0; k < done; ++k) {
        if (!unresolved(s, &rows[k]))
            continue;
        if (strlen(steps) + 64 > sizeof steps) {
            ++unnamed;
            continue;
        }
        note_unresolved(s, &rows[k], k, named, steps, sizeof steps);
        ++named;
    }
    char more[48] = "";
    if (unnamed)
        snprintf(more, sizeof more, " and %d more", unnamed);
    if (!named)
        return;
    char cost[320];
    resolution_cost(s, cost, sizeof cost);
    indent_say(s, IM_LOG_WARNING,
               "warning: step%s %s%s: the contact covers too few patches for the grid to resolve it (%s): use a "
               "finer delta or a larger approach or load",
               named + unnamed == 1 ? "" : "s", steps, more, cost);
}

/* What the step line's area ratio divides by: the cell (periodic), or the smooth punch's area at the
 * load (the history's area_ratio, indenter.h). */
static const char *area_ratio_name(const indent_run_state *s)
{
    if (s->options->solver.periodic)
        return "A/A0";
    switch (s->punch.kind) {
    case IM_PUNCH_CONE: return "A/A_cone";
    case IM_PUNCH_SPHERE: return "A/A_Hertz";
    case IM_PUNCH_FLAT: return "A/A_punch";
    default: return "A/A_smooth";
    }
}

/* The step just solved (indent_run.h's stepped): a warning for a contact too small, its line, the progress. */
static void report_step(const im_history_row *rows, int i, const void *state)
{
    const indent_run_state *s = state;
    const im_step_result *r = &rows[i].result;
    char gap[48] = "";
    if (s->options->solver.periodic)
        snprintf(gap, sizeof gap, "  mean gap = %.6g", r->mean_gap);
    indent_say(s, IM_LOG_INFO,
               "step %d: w = %.6g%s  N = %.6g  n_p = %ld  %s = %.4f  iterations %d  residual %.2e  %.3f s", i + 1,
               r->approach, gap, r->load, r->contact_patches, area_ratio_name(s), r->area_ratio, r->iterations,
               r->residual, r->seconds);
    if (s->options->progress)
        s->options->progress(s->options->user, "steps", i + 1, s->options->target_count);
}

/* The signal that asked to stop, or 0 (indent_run.h's stop). */
static int stop_signal(const void *state)
{
    const indent_run_state *s = state;
    return s->options->stop ? (int)*s->options->stop : 0;
}

/* The steps (indent_run.h: indent_run_steps), then what follows them of those done, also after a
 * failure; run.json finished. */
static int run_steps(indent_run_state *s, const im_theory_interface *rough, im_indentation *run,
                     history_file *history, im_render_context *context, const run_folder *folder, json_t *record)
{
    const im_indent_options *o = s->options;
    im_history_row *rows = calloc((size_t)o->target_count, sizeof *rows);
    if (!rows)
        return im_fail(IM_ENOMEM, "history of %d steps", o->target_count);
    const indent_run_plan plan = {.dir = o->out,
                                  .punch = &s->punch,
                                  .rough = o->solver.periodic ? NULL : rough,
                                  .targets = s->targets,
                                  .count = o->target_count,
                                  .tol = o->solver.tol,
                                  .target_name = indent_target_name(o->control),
                                  .files = s->files,
                                  .units = {o->solver.hardness, s->length_unit, s->force_unit},
                                  .gap_scale = s->gap_scale,
                                  .stop = stop_signal,
                                  .stepped = report_step,
                                  .state = s};
    int done = 0;
    int status = indent_run_steps(&plan, run, history, rows, &done);
    warn_if_unresolved(s, rows, done);
    indent_run_results(s, rough, rows, done, context, record, &status);
    free(rows);
    return run_folder_record(folder, record, done, status);
}

/* ---- the folder ---- */

/* Makes and locks the folder (a stale lock taken over is a warning), then removes what an earlier run
 * left there that this one would not replace (indent_run.h: indent_files_clear). */
static int prepare_folder(const indent_run_state *s, run_folder *folder)
{
    const run_folder_rules rules = indent_folder_rules(s->options, &s->files);
    int status = run_folder_open(&rules, 0, folder); /* the folder may be any: not its subfolders */
    if (status != IM_OK)
        return status;
    if (folder->lock.stale_pid > 0)
        indent_say(s, IM_LOG_WARNING, "taking over the stale lock %s of pid %ld, which no longer runs",
                   folder->lock.path, folder->lock.stale_pid);
    return indent_files_clear(s->options->out);
}

/* The record, with its inputs, and the figures' texts; the history started. A failure here is said in
 * run.json (no step solved: the record says why, not an earlier run's). */
static int start_record(indent_run_state *s, const im_field *surface, const im_indentation *run,
                        const run_folder *folder, history_file *history, json_t **record)
{
    const im_indent_options *o = s->options;
    im_window w = im_indentation_window(run);
    indent_say(s, IM_LOG_INFO, "surface %d x %d, window [%d, %d) x [%d, %d) (%d x %d), %d threads, device %s",
               surface->nx, surface->ny, w.x0, w.x0 + w.nx, w.y0, w.y0 + w.ny, w.nx, w.ny, omp_get_max_threads(),
               im_solver_plan_device(im_indentation_plan(run)));
    *record = indent_run_record(s, surface, run);
    int status = *record ? indent_run_record_inputs(o, *record) : im_fail(IM_ENOMEM, "run record");
    const im_png_text command = {"Command", o->command};
    if (status == IM_OK)
        status = run_figure_texts_make(&command, o->command ? 1 : 0, json_object_get(*record, "inputs"),
                                       &s->figure_texts);
    if (status == IM_OK)
        status = history_start(o->out, history);
    if (status == IM_OK)
        status = run_record_start(o->out, *record);
    if (*record && status != IM_OK)
        run_folder_record(folder, *record, 0, status);
    return status;
}

/* out/index.html over what the run left, even after a failure; the run's own error, if any, stays the
 * one reported. */
static int write_viewer_page(const indent_run_state *s, const run_folder *folder, int status)
{
    char title[1024];
    snprintf(title, sizeof title, "indentmap indent: %s", s->smooth ? "smooth surface" : s->options->surface_path);
    return run_folder_page(folder, title, s->options->page_embed, status);
}

/* device = auto on the CPU because the GPU's memory would not hold the plan: said, with the numbers of
 * the plan as made (its window and options, not the run's: solver.h, im_solver_plan_memory). */
static void note_auto_on_cpu(const indent_run_state *s, const im_indentation *run)
{
    const im_solver_plan *plan = im_indentation_plan(run);
    im_solver_memory m;
    if (s->options->solver.device == IM_DEVICE_AUTO && strcmp(im_solver_plan_device(plan), "cpu") == 0 &&
        im_solver_plan_memory(plan, &m) == IM_OK && m.note[0])
        indent_say(s, IM_LOG_WARNING, "%s", m.note);
}

/* The option that asks for the whole grid's fields, as the command line names it. */
static const char *whole_grid_option(const im_indent_options *o)
{
    return o->frames ? "--frames" : o->fields ? "--fields" : "--distributions";
}

/* Fields and distributions convolve each step's force over the whole grid (im_indentation_fields_full)
 * on a plan made at the first step: checked here, before any step, so that a run whose window fits but
 * whose whole grid does not is refused at once instead of after its first solve (at 4096^2 and beyond,
 * minutes). Counted: the convolution's plan where the solver's plan is not that of the whole grid (as
 * solver/indentation.c decides) and the force, gap, displacement and plastic fields written. */
static int check_whole_grid_memory(const indent_run_state *s, const im_field *surface, const im_indentation *run)
{
    const im_indent_options *o = s->options;
    if (!(s->files.fields || s->files.distributions) || o->solver.periodic) /* a cell's solve covers it */
        return IM_OK;
    const im_solver_plan *plan = im_indentation_plan(run);
    const im_window w = im_indentation_window(run);
    const int on_cpu = strcmp(im_solver_plan_device(plan), "cpu") == 0;
    im_solver_memory full = {.host_bytes = 0.0};
    if (!(w.nx == surface->nx && w.ny == surface->ny && on_cpu && !im_solver_plan_measured(plan))) {
        im_solver_options options = o->solver;
        if (on_cpu) /* where the run's own plan went; on a GPU, as asked (auto may take the CPU for the grid) */
            options.device = IM_DEVICE_CPU;
        int status = im_displacement_memory_needed(surface->nx, surface->ny, &options, &full);
        if (status != IM_OK)
            return im_fail_context(status, "%s: the whole %d x %d grid's displacement", whole_grid_option(o),
                                   surface->nx, surface->ny);
    }
    const double field = 8.0 * surface->nx * surface->ny,
                 fields = s->files.fields && o->solver.hardness > 0 ? 4.0 : 3.0;
    const double needed = full.host_bytes + fields * field;
    const size_t available = im_memory_available();
    if (available == 0 || needed <= (double)available)
        return IM_OK;
    return im_fail(IM_ENOMEM,
                   "%s on the %d x %d surface: the whole grid's displacement needs about %.1f MiB (its "
                   "convolution's plan %.1f MiB and %.0f fields of %.1f MiB) but only %.1f MiB are available; "
                   "refused before any step was solved: leave out %s (history.csv holds every step's "
                   "measures) or use a smaller grid (--crop)",
                   whole_grid_option(o), surface->nx, surface->ny, needed / 1048576.0, full.host_bytes / 1048576.0,
                   fields, field / 1048576.0, (double)available / 1048576.0, whole_grid_option(o));
}

/* The step files (fields and frames) of every step against the free disk, before any step, as a scene's
 * outputs are (src/scene/limits.c): at 4096^2 the fields are 384 MiB a step, and a disk that fills stops
 * the run at that step, hours in. An upper bound: the fields at their size with a sidecar, a frame
 * uncompressed (its PNG is about ten times smaller); the room the earlier run's step files leave when
 * they are removed counts as free. The distributions' CSVs are not counted (a row per patch). */
static int check_step_files_disk(const indent_run_state *s, const im_field *surface)
{
    const im_indent_options *o = s->options;
    const double cells = (double)surface->nx * surface->ny, fields = step_field_count(o->solver.hardness);
    const int scale = fields_frames_pixels_per_patch(surface->nx, surface->ny);
    const double field_files = s->files.fields ? fields * (8.0 * cells + 128.0 + 1024.0) : 0.0;
    const double frame = o->frames ? 3.0 * scale * scale * cells + 32768.0 : 0.0;
    char folder[PATH_MAX];
    const double needed = o->target_count * (field_files + frame),
                 free_bytes = needed > 0.0 ? run_folder_free_disk(o->out, folder, sizeof folder) : -1.0;
    if (o->no_space_check || needed == 0.0 || free_bytes == -1.0)
        return IM_OK;
    if (free_bytes == -2.0)
        return im_fail(IM_EIO,
                       "--out %s: %s is on a file system that stores no files (no blocks, like /proc or /sys)",
                       o->out, folder);
    const double earlier = indent_files_earlier_bytes(o->out);
    if (needed <= free_bytes + earlier)
        return IM_OK;
    char earlier_text[96] = "";
    if (earlier > 0.0)
        snprintf(earlier_text, sizeof earlier_text, " (with %.1f MiB of an earlier run's step files there)",
                 earlier / 1048576.0);
    return im_fail(IM_EIO,
                   "%s: the %d steps' files of the %d x %d surface need about %.1f MiB of disk (%.2f MiB a step) "
                   "but %s has only %.1f MiB free%s; refused before any step was solved: this is an upper bound: "
                   "IM_NO_SPACE_CHECK=1 runs anyway (a full disk then stops the run, keeping the steps it finished)",
                   whole_grid_option(o), o->target_count, surface->nx, surface->ny, needed / 1048576.0,
                   (field_files + frame) / 1048576.0, o->out, (free_bytes + earlier) / 1048576.0, earlier_text);
}

/* The solver on the prepared surface, the folder and the record, the steps, the page. */
static int run_on(indent_run_state *s, const im_field *surface, const im_theory_interface *rough)
{
    const im_indent_options *o = s->options;
    im_render_context *context = NULL; /* frames: opened before any step is solved */
    im_indentation *run = NULL;
    json_t *record = NULL;
    int status = o->frames ? im_render_open((im_render_backend)o->backend, &context) : IM_OK;
    if (status == IM_OK)
        status = im_indentation_create(surface, &s->punch, o->control, steps_largest(s->targets, o->target_count),
                                       &o->solver, &run);
    if (status == IM_OK)
        note_auto_on_cpu(s, run);
    if (status == IM_OK)
        status = check_whole_grid_memory(s, surface, run);
    if (status == IM_OK)
        status = check_step_files_disk(s, surface);
    if (status == IM_OK && o->solver.adhesion_work > 0)
        say_adhesion_law(s);
    run_folder folder = {.lock = {.fd = -1}};
    history_file history = {.fd = -1};
    if (status == IM_OK)
        status = prepare_folder(s, &folder);
    if (status == IM_OK)
        status = start_record(s, surface, run, &folder, &history, &record);
    if (status == IM_OK)
        status = run_steps(s, rough, run, &history, context, &folder, record);
    history_close(&history);
    if (record)
        status = write_viewer_page(s, &folder, status);
    run_folder_close(&folder);
    im_render_close(context);
    json_decref(record);
    im_indentation_free(run);
    return status;
}

int im_indent_run(const im_indent_options *options)
{
    ARG_REQUIRE(options, "options");
    ARG_REQUIRE(options->out, "options->out");
    ARG_REQUIRE(options->targets, "options->targets");
    if (options->target_count < 1 || options->target_count > IM_HISTORY_MAX_STEPS)
        return im_fail(IM_EINVAL, "im_indent_run: options->target_count %d: expected 1 to %d", options->target_count,
                       IM_HISTORY_MAX_STEPS);
    int status = indent_run_check(options);
    if (status != IM_OK)
        return status;
    indent_run_state s = {.options = options,
                          .smooth = options->surface_path == NULL,
                          .files = files_of(options),
                          .punch = options->punch};
    s.targets = malloc(sizeof(double) * (size_t)options->target_count);
    if (!s.targets)
        return im_fail(IM_ENOMEM, "%d targets", options->target_count);
    memcpy(s.targets, options->targets, sizeof(double) * (size_t)options->target_count);
    im_field *surface = NULL;
    im_theory_interface rough;
    status = prepare_surface(&s, &surface, &rough);
    if (status == IM_OK)
        status = run_on(&s, surface, &rough);
    im_profile_free(s.profile); /* after the run that borrowed it */
    im_field_free(surface);
    free(s.targets);
    run_figure_texts_free(&s.figure_texts);
    return status;
}
