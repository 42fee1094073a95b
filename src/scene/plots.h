/* Internal: the paper's line figures that [output] plots asks for (plots.c). */
#ifndef INDENTMAP_SCENE_PLOTS_H
#define INDENTMAP_SCENE_PLOTS_H

#include "indentmap/scene.h"

/* Plots: whether [output] plots names a figure; IM_EINVAL naming an unknown one. */
int scene_wants_plot(const im_scene *scene, const char *name);
int scene_check_plots(const im_scene *scene);
/* Whether a plot needs the ensemble's histories (fig5, fig6, fig7, sphere). */
int scene_wants_histories(const im_scene *scene);

/* fig1 (gamma(r/a) of the scene's roughnesses) and fig3 (the framed family's surface), which need
 * no solution. */
int scene_run_theory_plots(const im_scene *scene, const im_scene_run_options *options);

/* fig2: A/A_cone against rho_c from theory, with the ensemble's points. */
struct im_plot_points;
int scene_plot_area_ratio(const im_scene *scene, const struct im_plot_points *points);

#endif
