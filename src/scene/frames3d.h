/* Internal: the frames' history in 3-D (frames3d.c). */
#ifndef INDENTMAP_SCENE_FRAMES3D_H
#define INDENTMAP_SCENE_FRAMES3D_H

#include "indentmap/colormap.h"
#include "indentmap/field.h"
#include "indentmap/render.h"
#include "indentmap/scene.h"

/* The framed history's steps, for the 3-D frames (frames3d.c). */
typedef struct scene_frames3d_input {
    int count;
    im_field *const *deformed, *const *force; /* per step: h - u and the force per patch */
    const double *load_star;
    const im_colormap *norm;       /* the contact frames' force norm (frames_clip's cut included) */
    int extend_under, extend_over; /* some step's forces lie below / above it: the colour bar's triangles */
    const im_colormap *tension;    /* and their tension norm; NULL: no step has tension */
} scene_frames3d_input;

/* With frames3d = yes: IM_EINVAL naming the punch's key when a camera that frames the punch over the scene's
 * grid (its surface flat: the relief only adds to it) is beyond the 3-D view's (render.h: im_view3d_fit_distance),
 * a needle of a cone; checked before solving (S12). IM_OK otherwise. */
int scene_check_frames3d(const im_scene *scene);

/* frames3d = yes: frames/view3d_NNNN.png, one annotated 3-D view per step (one norm, exaggeration and
 * camera for all), and view3d.gif / view3d.mp4 of those frames as `animation` asks. */
int scene_write_frames3d(const im_scene *scene, const im_scene_run_options *options, im_render_context *context,
                         const scene_frames3d_input *in);

#endif
