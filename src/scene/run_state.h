/* Internal: what a scene run measures and makes, apart from the scene it runs (run.c creates it with
 * the run's copy of the scene, which points to it, and frees it when the run ends). */
#ifndef INDENTMAP_SCENE_RUN_STATE_H
#define INDENTMAP_SCENE_RUN_STATE_H

#include "indentmap/indenter.h"
#include "indentmap/scene.h"

typedef struct scene_run_state {
    /* A scene over files (surfaces.c: scene_measure_files), each file as read and prepared: */
    double file_slopes[IM_SCENE_MAX_FAMILIES];              /* h'rms of the surface as solved, by
                                                               file_slope_definition; their root mean square is
                                                               the copy's slopes[0] */
    int file_slope_definition;                              /* IM_SLOPE_* (surfaces.c: the rule) */
    const char *file_slope_reason;                          /* what chose it (a static text) */
    double file_spacing_differences[IM_SCENE_MAX_FAMILIES]; /* |delta_x - delta_y| / their mean as read
                                                               (formats.h: spacing_difference) */
    int file_resampled[IM_SCENE_MAX_FAMILIES];              /* 1 where it was resampled onto square pixels */
    char file_assumed[IM_SCENE_MAX_FAMILIES][128];          /* what was taken where the file is silent, "" if
                                                               nothing (formats.h: im_surface_read_info.assumed) */
    im_profile *profile;           /* [punch] profile read (owned; the punch borrows it), NULL for other
                                      punches; the copy's profile_file holds its resolved path */
    struct scene_outputs *outputs; /* what the run makes in output_dir (manifest.h), NULL before
                                      scene_outputs_open and after scene_outputs_close */
} scene_run_state;

/* The profile a run's copy of a scene read (run.c), NULL for other punches and outside a run. */
const im_profile *scene_profile(const im_scene *scene);

#endif
