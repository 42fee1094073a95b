/* Internal: the paper's line figures that [output] plots asks for (plots.c). */
#ifndef INDENTMAP_SCENE_PLOTS_H
#define INDENTMAP_SCENE_PLOTS_H

#include "indentmap/scene.h"

/* Plots: whether [output] plots names one of the figures in the bits of plot; IM_EINVAL when a
 * plot lacks what it draws (density: contact_panels, sphere: a sphere, fig2: the table; sphere, fig7 and
 * flat_k: a rough family), before any work. */
int scene_wants_plot(const im_scene *scene, enum im_scene_plot plot);
int scene_check_plots(const im_scene *scene);
/* How many families are rough (h'rms > 0): those fig1, sphere, fig2's groups and contact_density draw. */
int scene_rough_family_count(const im_scene *scene);
/* Whether a plot needs the ensemble's histories (fig5, fig6, fig7, sphere). */
int scene_wants_histories(const im_scene *scene);

/* fig1 (gamma(r/a) of the scene's roughnesses) and fig3 (the framed family's surface), which need
 * no solution. */
int scene_run_theory_plots(const im_scene *scene, const im_scene_run_options *options);

/* fig2: A/A_cone against rho_c from theory, with the ensemble's points. */
struct im_paper_points;
int scene_plot_area_ratio(const im_scene *scene, const struct im_paper_points *points);

#endif
