/* Internal: the contact density beside gamma(r/a) (density.c). */
#ifndef INDENTMAP_SCENE_DENSITY_H
#define INDENTMAP_SCENE_DENSITY_H

#include "indentmap/field.h"
#include "indentmap/scene.h"

/* Beyond the paper: ring-averaged contact fraction of each rough family's map beside gamma(r/a)
 * (contact_density.png/pdf); forces and load_star per family, as the panels solved them. */
int scene_plot_contact_density(const im_scene *scene, const im_field *const *forces, const double *load_star);

#endif
