/* Beyond the paper: eq. (2)'s k measured instead of assumed. Every rough surface of the scene,
 * pressed flat under a sweep of mean pressures in the periodic half-space (solver.h, "Periodic
 * mode"); A/A0 against x = p_m / (h'rms E*) per family (h'rms the spectral one of each surface as
 * solved, generated or read: the periodic cell's, whatever the input path), the fitted k of A/A0 = erf(sqrt(pi)/2 k x)
 * with its error, and eq. (12) for the scene's cone with that k beside k = 2 and (with a table) the
 * simulated A/A_cone on the same surfaces. Writes flat/flat_contact.csv, flat_k.csv and
 * flat_k.png/pdf. Not resumable: the stage solves every time it is asked for. */
#include "indentmap/io.h"
#include "scene/contents.h"
#include "indentmap/status.h"
#include "indentmap/theory.h"
#include "paper/figures.h"
#include "scene/ensemble.h"
#include "scene/flat_k.h"
#include "scene/outputs.h"
#include "scene/periodic.h"
#include "scene/progress.h"
#include "scene/punch.h"
#include "scene/surfaces.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The sweep x = p_m / (h'rms E*) = FLAT_STEP, 2 FLAT_STEP, ..., FLAT_POINTS FLAT_STEP: A/A0 from
 * about 5% to 70% with k = 2, across the linear regime the paper quotes ("up to ~50%"). */
enum { FLAT_POINTS = 16 };
static const double FLAT_STEP = 0.025;

typedef struct flat_family {
    int family, surfaces, points;
    double slope, slope_squares; /* the surfaces' root mean square spectral h'rms; the sum of their squares */
    double x[IM_SCENE_MAX_FAMILIES * FLAT_POINTS], area[IM_SCENE_MAX_FAMILIES * FLAT_POINTS];
    im_theory_k_fit fit;
    double seed_k_mean, seed_k_sem;                     /* k fitted on each surface alone: mean, standard error */
    double rho_c_k, eq12_k, rho_c_2, eq12_2, simulated; /* the cone with the measured k and k = 2 */
} flat_family;

/* One surface's sweep, appended to the family's points and to flat_contact.csv; a surface that is not
 * periodic (a measured scan) warned about, since the flat contact is solved on the periodic cell. */
static int solve_surface(const im_scene *scene, const im_scene_run_options *run_options, int family, uint64_t seed,
                         flat_family *out, FILE *rows, double *seed_k)
{
    im_field *surface = NULL;
    im_flat_contact *run = NULL;
    im_solver_options options = scene_solver_options(scene);
    double slope = NAN;
    int status = scene_surface(scene, family, seed, &surface);
    if (status == IM_OK) {
        scene_warn_if_not_periodic(scene, run_options, family, seed, surface);
        status = im_surface_slope_rms(surface, IM_SLOPE_SPECTRAL, &slope);
    }
    if (status == IM_OK)
        status = im_flat_contact_create(surface, &options, &run);
    double *x = out->x + out->points, *area = out->area + out->points;
    for (int i = 0; i < FLAT_POINTS && status == IM_OK; ++i) {
        im_flat_result r;
        x[i] = FLAT_STEP * (i + 1);
        status = im_flat_contact_solve(run, x[i] * slope * scene->modulus, &r);
        area[i] = r.area_fraction;
        if (status == IM_OK)
            fprintf(rows, "%d,%.17g,%llu,%.17g,%.17g,%.17g,%ld,%d,%.3e\n", family, slope, (unsigned long long)seed,
                    x[i], r.mean_pressure, r.area_fraction, r.contact_patches, r.iterations, r.residual);
    }
    im_theory_k_fit fit;
    if (status == IM_OK)
        status = im_theory_fit_k(x, area, FLAT_POINTS, &fit);
    if (status == IM_OK) {
        *seed_k = fit.k;
        out->slope_squares += slope * slope;
        out->points += FLAT_POINTS;
        ++out->surfaces;
    }
    im_flat_contact_free(run);
    im_field_free(surface);
    return status == IM_OK
               ? IM_OK
               : im_fail_context(status, "flat contact of family %d, seed %llu", family, (unsigned long long)seed);
}

/* Eq. (12) for the scene's cone on surfaces of h'rms slope with eq. (2)'s k (NaN for other punches). */
static double eq12_with_k(const im_scene *scene, double slope, double k, double *rho_c)
{
    im_theory_interface rough = im_theory_interface_default(slope);
    rough.k = k;
    double beta, ratio;
    *rho_c = NAN;
    int ok = scene->punch == IM_PUNCH_CONE && im_theory_cone_rho(&rough, scene->alpha_degrees, rho_c) == IM_OK &&
             im_theory_erf_scale(*rho_c, rough.normalisation, k, &beta) == IM_OK &&
             im_theory_cone_area_ratio_variable(beta, &ratio) == IM_OK;
    return ok ? ratio : NAN;
}

/* The table's mean A/A_cone over the family's surfaces, NaN without a table. */
static double simulated_area_ratio(const scene_reuse *reuse, int family)
{
    double sum = 0.0;
    int count = 0;
    for (int i = 0; i < reuse->table_count; ++i)
        if (reuse->table[i].family == family && reuse->table[i].status == IM_OK) {
            sum += reuse->table[i].area_ratio;
            ++count;
        }
    return count ? sum / count : NAN;
}

static int solve_family(const im_scene *scene, const im_scene_run_options *options, const scene_reuse *reuse,
                        int family, flat_family *out, FILE *rows)
{
    double seed_k[IM_SCENE_MAX_FAMILIES];
    *out = (flat_family){.family = family};
    int status = IM_OK;
    for (int s = 0; s < scene->seed_count && status == IM_OK; ++s) {
        if (scene_stop_signal(options))
            return scene_interrupted(options, "during the flat contacts");
        status = solve_surface(scene, options, family, scene->seeds[s], out, rows, &seed_k[s]);
    }
    if (status == IM_OK)
        status = im_theory_fit_k(out->x, out->area, out->points, &out->fit);
    if (status != IM_OK)
        return status;
    double sum = 0.0, squares = 0.0;
    for (int s = 0; s < out->surfaces; ++s)
        sum += seed_k[s];
    out->seed_k_mean = sum / out->surfaces;
    for (int s = 0; s < out->surfaces; ++s)
        squares += (seed_k[s] - out->seed_k_mean) * (seed_k[s] - out->seed_k_mean);
    out->seed_k_sem = out->surfaces > 1 ? sqrt(squares / (out->surfaces - 1) / out->surfaces) : NAN;
    const double slope = out->slope = sqrt(out->slope_squares / out->surfaces);
    out->eq12_k = eq12_with_k(scene, slope, out->fit.k, &out->rho_c_k);
    out->eq12_2 = eq12_with_k(scene, slope, IM_THEORY_K_DEFAULT, &out->rho_c_2);
    out->simulated = simulated_area_ratio(reuse, family);
    scene_progress(options,
                   "flat contact, h'rms = %g: k = %.4f ± %.4f (surfaces: %.4f ± %.4f), linear to 50%%: "
                   "%.4f; eq. (12) %.4f (k = 2: %.4f)",
                   slope, out->fit.k, out->fit.k_error, out->seed_k_mean, out->seed_k_sem, out->fit.k_linear,
                   out->eq12_k, out->eq12_2);
    return IM_OK;
}

static int write_k_table(const im_scene *scene, const flat_family *families, int count)
{
    im_atomic_file file;
    int status = scene_open_output(scene, "flat_k.csv", &file);
    if (status != IM_OK)
        return status;
    fprintf(file.stream, "slope,surfaces,points,k,k_error,k_surfaces_mean,k_surfaces_sem,k_linear_to_half,"
                         "rms_residual,rho_c,area_ratio_eq12,rho_c_k2,area_ratio_eq12_k2,area_ratio_simulated\n");
    for (int i = 0; i < count; ++i) {
        const flat_family *f = &families[i];
        fprintf(file.stream, "%.17g,%d,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                f->slope, f->surfaces, f->points, f->fit.k, f->fit.k_error, f->seed_k_mean, f->seed_k_sem,
                f->fit.k_linear, f->fit.rms_residual, f->rho_c_k, f->eq12_k, f->rho_c_2, f->eq12_2, f->simulated);
    }
    return im_atomic_commit(&file);
}

typedef struct flat_k_plot {
    paper_flat_family families[IM_SCENE_MAX_FAMILIES];
    int count;
} flat_k_plot;

static int draw_k(const im_scene *scene, const void *data, const paper_file *file)
{
    (void)scene;
    const flat_k_plot *plot = data;
    return paper_figure_flat_k(plot->families, plot->count, FLAT_STEP * FLAT_POINTS, file);
}

/* A/A0 against x per family (paper/flat_k_figure.c): the surfaces' points, erf with the fitted k,
 * erf with k = 2. */
static int plot_k(const im_scene *scene, const flat_family *families, int count)
{
    flat_k_plot plot = {.count = count};
    for (int i = 0; i < count; ++i) {
        const flat_family *f = &families[i];
        plot.families[i] = (paper_flat_family){f->slope, f->points, f->x, f->area, f->fit.k, f->fit.k_error};
    }
    return scene_write_png_pdf(scene, "flat_k", draw_k, &plot);
}

/* The flat contacts of every rough family into families: flat/flat_contact.csv, flat_k.csv and the
 * figure. */
static int write_flat_k(const im_scene *scene, const im_scene_run_options *options, const scene_reuse *reuse,
                        flat_family *families)
{
    char path[IM_SCENE_PATH];
    im_atomic_file rows;
    int status = scene_output_path(scene, "flat", path, sizeof path);
    if (status == IM_OK)
        status = im_make_directories(path);
    if (status == IM_OK)
        status = scene_open_output(scene, "flat/flat_contact.csv", &rows);
    if (status != IM_OK)
        return status;
    fprintf(rows.stream, "family,slope,seed,pressure_ratio,mean_pressure,area_fraction,contact_patches,iterations,"
                         "residual\n");
    int count = 0;
    for (int f = 0; f < scene->family_count && status == IM_OK; ++f)
        if (scene->slopes[f] > 0.0)
            status = solve_family(scene, options, reuse, f, &families[count++], rows.stream);
    if (status != IM_OK) {
        im_atomic_abort(&rows);
        return status;
    }
    status = im_atomic_commit(&rows);
    if (status == IM_OK && count == 0)
        status = im_fail(IM_EINVAL, "%s: plots = flat_k measures k on rough surfaces: give a slope > 0", scene->path);
    if (status == IM_OK)
        status = write_k_table(scene, families, count);
    if (status == IM_OK)
        status = plot_k(scene, families, count);
    return status;
}

int scene_run_flat_k(const im_scene *scene, const im_scene_run_options *options, const scene_reuse *reuse)
{
    flat_family *families = calloc(IM_SCENE_MAX_FAMILIES, sizeof *families);
    if (!families)
        return im_fail(IM_ENOMEM, "flat contacts: allocation failed");
    int status = write_flat_k(scene, options, reuse, families);
    free(families);
    return status;
}
