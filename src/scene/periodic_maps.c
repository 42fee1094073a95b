/* A periodic scene's contact panels and distributions: every step of each family's first surface, its
 * fields and distributions written as `indent --periodic --fields --distributions` writes them and its
 * contact maps drawn as `indent --frames` draws them (front.h, "the files of one solved step"). A cell
 * has no load_star to draw them at, nor a smooth contact circle. */
#include "scene/periodic.h"
#include "scene/contents.h"

#include "front/front.h"
#include "indentmap/figure.h"
#include "indentmap/io.h"
#include "indentmap/status.h"
#include "indentmap/version.h"
#include "paper/figures.h"
#include "scene/manifest.h"
#include "scene/outputs.h"
#include "scene/provenance.h"
#include "scene/punch.h"
#include "scene/surfaces.h"

#include <stdio.h>
#include <stdlib.h>

int scene_periodic_writes_steps(const im_scene *scene, const scene_member *m)
{
    return scene->periodic && (scene->contact_panels || scene->distributions) && m->seed == scene->seeds[0];
}

/* OUTPUT/panels/family_FF, made. */
static int panel_folder(const im_scene *scene, int family, char *folder, size_t size)
{
    char relative[64];
    snprintf(relative, sizeof relative, "panels/family_%02d", family);
    int status = scene_output_path(scene, relative, folder, size);
    return status == IM_OK ? im_make_directories(folder) : status;
}

/* Notes the step's files under OUTPUT/relative (outputs.h), so that a damaged one is removed before it is
 * written again: the writers' kind guard would refuse to replace it. */
static int note_files(const im_scene *scene, const char *relative, const char *const *suffixes, int count)
{
    int status = IM_OK;
    for (int i = 0; i < count && status == IM_OK; ++i) {
        char name[128], path[IM_SCENE_PATH];
        snprintf(name, sizeof name, "%s%s", relative, suffixes[i]);
        status = scene_output_path(scene, name, path, sizeof path);
    }
    return status;
}

static int step_fields(const im_scene *scene, const scene_member *m, im_indentation *run, int step,
                       const im_field *surface)
{
    char folder[IM_SCENE_PATH], force_unit[64];
    int status = panel_folder(scene, m->family, folder, sizeof folder);
    for (int i = 0; i < step_field_count(scene->hardness) && status == IM_OK; ++i) {
        char relative[96];
        const char *const suffixes[] = {".npy", ".npy.json"};
        snprintf(relative, sizeof relative, "panels/family_%02d/%s%04d", m->family, STEP_FIELD_PREFIXES[i], step);
        status = note_files(scene, relative, suffixes, 2);
    }
    step_force_unit("", surface->unit, force_unit, sizeof force_unit);
    const step_units units = {scene->hardness, surface->unit, force_unit};
    return status == IM_OK ? step_fields_write(folder, run, step, &units) : status;
}

static int step_distributions(const im_scene *scene, const scene_member *m, im_indentation *run, int step,
                              const im_field *surface)
{
    char relative[64], prefix[IM_SCENE_PATH];
    const char *const suffixes[] = {"_gaps.csv", "_patches.csv", "_patch_list.csv"};
    snprintf(relative, sizeof relative, "distributions/family_%02d_%04d", m->family, step);
    int status = scene_output_path(scene, "distributions", prefix, sizeof prefix);
    if (status == IM_OK)
        status = im_make_directories(prefix);
    if (status == IM_OK)
        status = note_files(scene, relative, suffixes, 3);
    if (status == IM_OK)
        status = scene_output_path(scene, relative, prefix, sizeof prefix);
    /* the gaps in the surface's h_rms, delta for a smooth one, as indent --distributions */
    const double gap_scale = m->height_rms > 0.0 ? m->height_rms : surface->delta;
    return status == IM_OK ? step_distributions_write(prefix, run, gap_scale) : status;
}

int scene_periodic_step_files(const im_scene *scene, const scene_member *m, im_indentation *run, int step,
                              const im_field *surface)
{
    int status = scene->contact_panels ? step_fields(scene, m, run, step, surface) : IM_OK;
    if (status == IM_OK && scene->distributions)
        status = step_distributions(scene, m, run, step, surface);
    return status == IM_OK ? IM_OK : im_fail_context(status, "family %d, step %d", m->family, step);
}

void scene_periodic_keep_rows(const im_scene *scene, scene_reuse *reuse, scene_member *members, int count)
{
    for (int i = 0; i < count && scene->contact_panels; ++i) {
        scene_member *m = &members[i];
        if (!scene_periodic_writes_steps(scene, m) || reuse->rows[m->family])
            continue;
        reuse->rows[m->family] = m->history;
        reuse->row_count[m->family] = m->steps;
        m->history = NULL;
    }
}

/* Family's contact maps, panels/family_FF/contact_MMMM.png, from its fields; its surface once more for
 * the punch and the units (the history was solved on another thread). */
static int draw_family(const im_scene *scene, const scene_reuse *reuse, im_render_context *context, int family)
{
    char folder[IM_SCENE_PATH], force_unit[64];
    im_field *surface = NULL;
    int status = panel_folder(scene, family, folder, sizeof folder);
    for (int step = 1; step <= reuse->row_count[family] && status == IM_OK; ++step) {
        char path[IM_SCENE_PATH];
        status = im_frame_path(path, sizeof path, folder, "contact", step - 1);
        if (status == IM_OK)
            scene_outputs_note(scene, path);
    }
    if (status == IM_OK)
        status = scene_surface(scene, family, scene->seeds[0], &surface);
    if (status != IM_OK)
        return status;
    step_force_unit("", surface->unit, force_unit, sizeof force_unit);
    const im_indenter punch = scene_member_punch(scene, surface);
    run_figure_texts texts;
    status = scene_figure_texts(scene, NULL, 0, &texts);
    const fields_frames frames = {folder, folder,     reuse->rows[family], reuse->row_count[family],
                                  &punch, force_unit, texts.texts,         texts.count};
    if (status == IM_OK)
        status = fields_frames_write(context, &frames);
    run_figure_texts_free(&texts);
    im_field_free(surface);
    return status;
}

int scene_periodic_draw_panels(const im_scene *scene, const scene_reuse *reuse, im_render_context *context)
{
    int status = IM_OK;
    for (int f = 0; f < scene->family_count && status == IM_OK; ++f)
        status = reuse->rows[f] ? draw_family(scene, reuse, context, f) : IM_OK;
    return status;
}
