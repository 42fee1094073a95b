/* A periodic scene's results beyond its histories: the non-periodic-input warning and k of eq. (2) per
 * member, each computed by the helpers `indent --periodic` calls (front.h). */
#include "scene/periodic.h"
#include "scene/contents.h"

#include "front/front.h"
#include "indentmap/io.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"
#include "scene/outputs.h"
#include "scene/progress.h"
#include "scene/surfaces.h"

#include <math.h>
#include <stdio.h>

int scene_periodic_fits_k(const im_scene *scene)
{
    /* as indent --periodic: eq. (2) is the elastic, repulsive flat's */
    return scene->periodic == IM_SCENE_PERIODIC_FLAT && !(scene->hardness > 0) && !(scene->adhesion_work > 0);
}

void scene_warn_if_not_periodic(const im_scene *scene, const im_scene_run_options *options, int family, uint64_t seed,
                                const im_field *surface)
{
    double edge, inner;
    if (!periodic_edge_mismatch(surface, &edge, &inner))
        return;
    char file[IM_SCENE_PATH] = "";
    if (scene->file_count > 0)
        im_scene_file_path(scene, (int)seed, file, sizeof file);
    scene_warn(options,
               "%s%sthe surface of family %d, seed %llu is not periodic: the steps across its edges have "
               "rms %.3g, %.3g times those inside it (%.3g); [punch] periodic joins its edges as if they met. Use "
               "periodic surfaces (generated ones are) or leave periodic out (the half-space)",
               file, file[0] ? ": " : "", family, (unsigned long long)seed, edge, edge / inner, inner);
}

/* One member's row of k_fit.csv. */
static int write_k_row(const im_scene *scene, const scene_member *m, const im_field *surface, FILE *stream)
{
    double slope;
    int status = im_surface_slope_rms(surface, IM_SLOPE_SPECTRAL, &slope);
    periodic_k_fit k;
    if (status == IM_OK)
        status = periodic_fit_k(m->history, m->steps, periodic_cell_area(surface), slope, scene->modulus, &k);
    if (status != IM_OK)
        return im_fail_context(status, "k of eq. (2) for family %d, seed %llu", m->family,
                               (unsigned long long)m->seed);
    fprintf(stream, "%d,%.17g,%llu,%.17g,", m->family, scene->slopes[m->family], (unsigned long long)m->seed, slope);
    periodic_k_fit_write_row(stream, &k);
    return IM_OK;
}

/* The member's surface once more (generated again or read; its history may have been read back), for
 * the warning and its k. */
static int member_results(const im_scene *scene, const im_scene_run_options *options, const scene_member *m,
                          FILE *k_rows)
{
    im_field *surface = NULL;
    int status = scene_surface(scene, m->family, m->seed, &surface);
    if (status == IM_OK)
        scene_warn_if_not_periodic(scene, options, m->family, m->seed, surface);
    if (status == IM_OK && k_rows && scene->slopes[m->family] > 0) /* a smooth cell has no k */
        status = write_k_row(scene, m, surface, k_rows);
    im_field_free(surface);
    return status;
}

int scene_periodic_results(const im_scene *scene, const im_scene_run_options *options, const scene_member *members,
                           int count)
{
    im_atomic_file file;
    const int fits = scene_periodic_fits_k(scene);
    int status = fits ? scene_open_output(scene, "k_fit.csv", &file) : IM_OK;
    if (status != IM_OK)
        return status;
    FILE *k_rows = fits ? file.stream : NULL;
    if (k_rows)
        fprintf(k_rows, "family,slope,seed,slope_rms,%s\n", PERIODIC_K_COLUMNS);
    int rough = 0;
    for (int i = 0; i < count && status == IM_OK; ++i) {
        status = member_results(scene, options, &members[i], k_rows);
        rough += scene->slopes[members[i].family] > 0;
    }
    if (!fits)
        return status;
    if (status != IM_OK) {
        im_atomic_abort(&file);
        return status;
    }
    status = im_atomic_commit(&file);
    if (status == IM_OK)
        scene_progress(options, "periodic: k of eq. (2) of %d rough surfaces in k_fit.csv", rough);
    return status;
}
