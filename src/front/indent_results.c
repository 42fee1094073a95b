/* What an indentation run writes after its steps (indent_run.h: indent_run_results), of the steps done,
 * also after a failure: the frames, the indentation or adhesion analysis, the history figure and a
 * periodic cell's k fit. A failure here is said but leaves the run's status alone (the history is the
 * result), but for the frames'. */
#include "front/indent_run.h"
#include "core/error_keep.h"

#include "indentmap/io.h"
#include "indentmap/status.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>

/* --periodic under a rigid flat without a hardness: k of eq. (2) fitted to the steps done (front.h:
 * periodic_fit_k, with the surface's h'rms of the slope definition), said and recorded in run.json
 * with its range. */
static void write_k_fit(const indent_run_state *s, const im_theory_interface *rough, const im_history_row *rows,
                        int done, json_t *record)
{
    periodic_k_fit k;
    if (periodic_fit_k(rows, done, s->cell_area, rough->slope_rms, rough->e_star, &k) != IM_OK) {
        indent_say(s, IM_LOG_WARNING, "%s", im_last_error());
        return;
    }
    const char *definition = slope_definition_name(s->slope_definition);
    char line[1024];
    periodic_k_fit_describe(&k, rough->slope_rms, definition, line, sizeof line);
    indent_say(s, IM_LOG_INFO, "%s", line);
    json_object_set_new(record, "k_fit", periodic_k_fit_record(&k, rough->slope_rms, definition));
}

/* The smooth punch's adhesive theory (front.h: a sphere's Maugis-Dugdale, a flat punch's Kendall) beside the
 * measured pull-off in run.json's "adhesion" block ("theory": null for the other punches, a rough surface or
 * a hardness) and adhesion_theory.csv beside the history. */
static void write_adhesion_theory(const indent_run_state *s, const im_history_row *rows, int done, json_t *law)
{
    const im_solver_options *solver = &s->options->solver;
    const im_theory_adhesion theory = {solver->e_star, solver->adhesion_work, solver->adhesion_range};
    const char *model = NULL;
    im_theory_adhesive_point pull_off;
    /* (a periodic cell's flat is not a punch on a half-space, and the theories are the Maugis-Dugdale law's, on an
     * elastic body: no hardness) */
    const int smooth_punch = s->smooth && !solver->periodic && solver->adhesion_law == IM_ADHESION_MAUGIS_DUGDALE &&
                             !(solver->hardness > 0);
    int status = smooth_punch ? adhesion_theory_pull_off(&s->punch, &theory, &model, &pull_off) : IM_OK;
    if (status == IM_OK && model)
        status = adhesion_theory_write(s->options->out, &s->punch, &theory, rows, done);
    if (status != IM_OK) {
        indent_say(s, IM_LOG_WARNING, "adhesion theory: %s", im_last_error());
        model = NULL;
    }
    if (!model) {
        json_object_set_new(law, "theory", json_null());
        return;
    }
    json_object_set_new(law, "theory",
                        json_pack("{s:s, s:f, s:f, s:f, s:s}", "model", model, "pull_off_force", -pull_off.load,
                                  "pull_off_approach", pull_off.approach, "contact_radius", pull_off.contact_radius,
                                  "file", "adhesion_theory.csv"));
    indent_say(s, IM_LOG_INFO, "adhesion theory (%s): pull-off force %.6g at w = %.6g; %s/adhesion_theory.csv", model,
               -pull_off.load, pull_off.approach, s->options->out);
}

/* With adhesion: the pull-off, the jumps and the lost work (front.h), said and in run.json's "adhesion"
 * block beside the law, and force_distance.{png,pdf}. */
static void write_adhesion(const indent_run_state *s, const im_history_row *rows, int done, json_t *record)
{
    im_adhesion_summary summary;
    json_t *law = json_object_get(record, "adhesion");
    if (run_record_adhesion_summary(law, s->options->out, rows, done, s->options->control, s->length_unit,
                                    s->force_unit, &s->figure_texts, &summary) != IM_OK)
        indent_say(s, IM_LOG_WARNING, "adhesion summary: %s", im_last_error());
    if (isnan(summary.work_done))
        return;
    char line[8192];
    analysis_describe_adhesion(&summary, rows, done, s->options->control, s->options->out, line, sizeof line);
    indent_say(s, IM_LOG_INFO, "%s", line);
    write_adhesion_theory(s, rows, done, law);
}

static void say_note(void *user, const char *note)
{
    indent_say(user, IM_LOG_INFO, "indentation analysis: %s", note);
}

/* indentation.csv over the steps done (front.h), said and in run.json, with why a branch's S is NaN. */
static void write_analysis(const indent_run_state *s, const im_history_row *rows, int done, json_t *record)
{
    const im_indent_options *o = s->options;
    int branches = 0;
    if (o->solver.adhesion_work > 0) { /* Oliver-Pharr's analysis is of repulsive contact */
        json_object_set_new(record, "indentation", json_null());
        write_adhesion(s, rows, done, record);
        return;
    }
    if (o->solver.periodic) { /* Oliver-Pharr's areas are a punch's on a half-space */
        json_object_set_new(record, "indentation", json_null());
        return;
    }
    int status = analysis_write(o->out, &s->punch, rows, done, s->surface_delta, o->solver.e_star, s->length_unit,
                                s->force_unit, &s->figure_texts, &branches);
    if (status != IM_OK) {
        indent_say(s, IM_LOG_WARNING, "indentation analysis: %s", im_last_error());
        return;
    }
    json_object_set_new(record, "indentation", branches > 0 ? json_string("indentation.csv") : json_null());
    if (branches > 0)
        indent_say(s, IM_LOG_INFO,
                   "indentation analysis of %d unloading branch%s: %s/indentation.csv, load_displacement.png and "
                   ".pdf",
                   branches, branches == 1 ? "" : "es", o->out);
    if (branches > 0 && analysis_notes(&s->punch, rows, done, say_note, (void *)s) != IM_OK)
        indent_say(s, IM_LOG_WARNING, "indentation analysis: %s", im_last_error());
}

history_figure indent_history_figure(const im_solver_options *solver, int punch_given, double cell_area,
                                     const im_theory_interface *rough)
{
    const int elastic = !(solver->hardness > 0) && !(solver->adhesion_work > 0);
    /* an adhesive cell's net load goes through 0: its force against the approach, as an adhesive punch's */
    const int area_plot = solver->periodic && !(solver->adhesion_work > 0);
    return (history_figure){.cell_area = area_plot ? cell_area : 0.0,
                            .flat_theory = solver->periodic && !punch_given && elastic ? rough : NULL,
                            .theory = elastic};
}

/* out/history.{png,pdf} (front.h: history_figure_write), with the theory where the run is elastic and
 * repulsive. */
static void write_history_figure(const indent_run_state *s, const im_theory_interface *rough,
                                 const im_history_row *rows, int done)
{
    const im_indent_options *o = s->options;
    history_figure figure = indent_history_figure(&o->solver, o->punch_given, s->cell_area, rough);
    figure.rows = rows;
    figure.count = done;
    figure.punch = &s->punch;
    figure.length_unit = s->length_unit;
    figure.force_unit = s->force_unit;
    figure.pressure_unit = o->e_star_unit ? o->e_star_unit : "";
    figure.texts = &s->figure_texts;
    if (history_figure_write(o->out, &figure) != IM_OK)
        indent_say(s, IM_LOG_WARNING, "history figure: %s", im_last_error());
}

/* out/frames/contact_NNNN.png of the steps done (front.h: fields_frames_write): a failure is the run's
 * error (kept in *kept) when it had none, else said. */
static void draw_frames(const indent_run_state *s, const im_history_row *rows, int done, im_render_context *context,
                        int *status, kept_error *kept)
{
    char folder[PATH_MAX];
    const fields_frames frames = {
        s->options->out, folder, rows, done, &s->punch, s->force_unit, s->figure_texts.texts, s->figure_texts.count};
    int drawn = im_path_join(folder, sizeof folder, s->options->out, "frames");
    if (drawn == IM_OK)
        drawn = fields_frames_write(context, &frames);
    if (drawn != IM_OK)
        im_fail_context(drawn, "--frames");
    if (drawn != IM_OK && *status == IM_OK) {
        *status = drawn;
        error_keep(kept);
    } else if (drawn != IM_OK) {
        indent_say(s, IM_LOG_WARNING, "%s", im_last_error());
    }
}

void indent_run_results(indent_run_state *s, const im_theory_interface *rough, const im_history_row *rows, int done,
                        im_render_context *context, json_t *record, int *status)
{
    const im_solver_options *solver = &s->options->solver;
    kept_error kept;
    error_keep(&kept);
    if (s->options->frames) /* of the steps done, also when a later step failed */
        draw_frames(s, rows, done, context, status, &kept);
    write_analysis(s, rows, done, record);
    write_history_figure(s, rough, rows, done);
    /* eq. (2) is an elastic, repulsive law for a rigid flat: no fit with a cap, adhesion or a repeated punch;
     * none when no step was solved (it said "no step with a positive load" above the failure of step 1) */
    if (solver->periodic && !s->options->punch_given && !(solver->hardness > 0) && !(solver->adhesion_work > 0) &&
        done > 0)
        write_k_fit(s, rough, rows, done, record);
    if (*status != IM_OK) /* what the analysis or the fit said is not the run's error */
        error_restore(&kept, *status);
}
