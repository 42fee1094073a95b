/* Internal: the surfaces of a scene, generated or read from its files (surfaces.c). */
#ifndef INDENTMAP_SCENE_SURFACES_H
#define INDENTMAP_SCENE_SURFACES_H

#include "indentmap/field.h"
#include "indentmap/scene.h"

#include <stdint.h>

/* The surface of one family and seed: flat for slope 0, the file when the scene names one, else
 * generated. */
int scene_surface(const im_scene *scene, int family, uint64_t seed, im_field **out);

/* Reads every surface file of the run's copy of a scene (prepared as it will be solved), checks that
 * they share one grid and spacing (IM_EFORMAT naming the files otherwise), and sets the copy's grid,
 * file_unit and slopes[0] (the files' root mean square h'rms: spectral when the scene is periodic or
 * every file is a generated surface of spectral h'rms by its sidecar, else forward differences; state says
 * which and why) and state's measurements of each file (run_state.h). IM_OK at once for a scene without files. */
int scene_measure_files(im_scene *scene, struct scene_run_state *state);

/* The h'rms of one member: its file's measured one in a scene over files (a run's copy), else its
 * family's. */
double scene_member_slope(const im_scene *scene, int family, uint64_t seed);

#endif
