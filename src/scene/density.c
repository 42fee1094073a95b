/* Beyond the paper: the local contact density seen directly (paper/map_figures.c draws it): the
 * maps of every rough family at the panels' load, with their punch axis and smooth contact radius. */
#include "indentmap/status.h"
#include "scene/contents.h"
#include "paper/figures.h"
#include "scene/density.h"
#include "scene/outputs.h"
#include "scene/punch.h"

#include <math.h>

typedef struct density_maps {
    paper_density_map maps[IM_SCENE_MAX_FAMILIES];
    int count;
} density_maps;

static int draw_density(const im_scene *scene, const void *data, const paper_file *file)
{
    const density_maps *d = data;
    return paper_figure_contact_density(scene->alpha_degrees, d->maps, d->count, file);
}

int scene_plot_contact_density(const im_scene *scene, const im_field *const *forces, const double *load_star)
{
    density_maps d = {.count = 0};
    im_indenter punch = scene_punch(scene);
    for (int f = 0; f < scene->family_count; ++f) {
        if (!(scene->slopes[f] > 0.0))
            continue;
        paper_density_map *map = &d.maps[d.count++];
        *map = (paper_density_map){.force = forces[f], .slope = scene->slopes[f], .load_star = load_star[f]};
        map->radius = sqrt(load_star[f] / M_PI) * forces[f]->delta; /* smooth contact radius */
        im_indenter_axis(&punch, forces[f]->nx, forces[f]->ny, forces[f]->delta, &map->axis_x, &map->axis_y);
    }
    return d.count == 0 ? IM_OK : scene_write_png_pdf(scene, "contact_density", draw_density, &d);
}
