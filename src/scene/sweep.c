/* Sweeps: a scene whose [punch] alpha, [surfaces] hurst or lambda_s is a list runs every
 * combination as a sweep point, a scene of its own (one alpha, hurst and lambda_s; all slopes x
 * seeds) in its own folder. The table's families of every point are gathered into sweep.csv and,
 * with plots = fig2, drawn against rho_c beside eq. (12) in the scene's own fig2. */
#include "indentmap/status.h"
#include "scene/contents.h"
#include "core/summation.h"
#include "paper/figures.h"
#include "scene/labels.h"
#include "scene/limits.h"
#include "scene/outputs.h"
#include "scene/plots.h"
#include "scene/progress.h"
#include "scene/punch.h"
#include "scene/surfaces.h"
#include "scene/sweep.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int list_count(int count) { return count > 1 ? count : 1; }

int scene_sweep_count(const im_scene *scene)
{
    return list_count(scene->alpha_count) * list_count(scene->hurst_count) * list_count(scene->lambda_s_count);
}

/* Point index of the sweep: alpha varies slowest, lambda_s fastest (the order of sweep.csv). */
static void sweep_values(const im_scene *scene, int index, double *alpha, double *hurst, double *lambda_s)
{
    int n_lambda = list_count(scene->lambda_s_count), n_hurst = list_count(scene->hurst_count);
    int i_lambda = index % n_lambda, i_hurst = index / n_lambda % n_hurst, i_alpha = index / n_lambda / n_hurst;
    *alpha = scene->alpha_count > 1 ? scene->alphas[i_alpha] : scene->alpha_degrees;
    *hurst = scene->hurst_count > 1 ? scene->hursts[i_hurst] : scene->surface.hurst;
    *lambda_s = scene->lambda_s_count > 1 ? scene->lambda_ss[i_lambda] : scene->surface.lambda_s;
}

int scene_sweep_point(const im_scene *scene, int index, im_scene *point)
{
    *point = *scene;
    sweep_values(scene, index, &point->alpha_degrees, &point->surface.hurst, &point->surface.lambda_s);
    point->alphas[0] = point->alpha_degrees;
    point->hursts[0] = point->surface.hurst;
    point->lambda_ss[0] = point->surface.lambda_s;
    point->alpha_count = point->hurst_count = point->lambda_s_count = 1;
    int length = snprintf(point->output_dir, sizeof point->output_dir, "%s/alpha_%g_hurst_%g_lambda_s_%g",
                          scene->output_dir, point->alpha_degrees, point->surface.hurst, point->surface.lambda_s);
    if (length < 0 || (size_t)length >= sizeof point->output_dir)
        return im_fail(IM_EINVAL, "%s: the sweep point's folder under %s is too long", scene->path,
                       scene->output_dir);
    return IM_OK;
}

/* One family of one sweep point, as the table measured it. */
typedef struct sweep_row {
    double alpha, hurst, lambda_s, slope, rho_c, area_ratio, sd, eq12;
    int count;
} sweep_row;

/* The mean and sample standard deviation of A/A_cone over the family's members. */
static sweep_row sweep_summary(const im_scene *point, const scene_member *members, int count, int family)
{
    sweep_row row = {point->alpha_degrees,
                     point->surface.hurst,
                     point->surface.lambda_s,
                     point->slopes[family],
                     NAN,
                     NAN,
                     NAN,
                     NAN,
                     0};
    double sum = 0.0, sum_squares = 0.0;
    for (int i = 0; i < count; ++i) {
        if (members[i].family != family)
            continue;
        ++row.count;
        sum += members[i].area_ratio;
        sum_squares += members[i].area_ratio * members[i].area_ratio;
    }
    if (row.count > 0)
        row.area_ratio = sum / row.count;
    row.sd = row.slope == 0.0 ? 0.0 : sample_sd(sum, sum_squares, row.count); /* smooth: one surface, exact */
    row.eq12 = scene_eq12(point, row.slope, &row.rho_c);
    return row;
}

static int write_sweep_csv(const im_scene *scene, const sweep_row *rows, int count)
{
    im_atomic_file file;
    int status = scene_open_output(scene, "sweep.csv", &file);
    if (status != IM_OK)
        return status;
    fprintf(file.stream, "alpha,hurst,lambda_s,slope,rho_c,surfaces,area_ratio_mean,area_ratio_sd,area_ratio_eq12\n");
    for (int i = 0; i < count; ++i)
        fprintf(file.stream, "%.10g,%.10g,%.10g,%.10g,%.10g,%d,%.10g,%.10g,%.10g\n", rows[i].alpha, rows[i].hurst,
                rows[i].lambda_s, rows[i].slope, rows[i].rho_c, rows[i].count, rows[i].area_ratio, rows[i].sd,
                rows[i].eq12);
    return im_atomic_commit(&file);
}

enum { MAX_GROUPS = PAPER_MAX_SWEEP_GROUPS };

/* The points of a sweep, grouped by roughness (h'rms, H, lambda_s): along a group only alpha varies. */
typedef struct sweep_groups {
    int count;
    char labels[MAX_GROUPS][96];
    double x[MAX_GROUPS][IM_SCENE_MAX_SWEEP_POINTS], y[MAX_GROUPS][IM_SCENE_MAX_SWEEP_POINTS],
        sigma[MAX_GROUPS][IM_SCENE_MAX_SWEEP_POINTS];
    paper_sweep_group groups[MAX_GROUPS]; /* the builder's view of the arrays above */
} sweep_groups;

static int same_roughness(const sweep_row *a, const sweep_row *b)
{
    return a->slope == b->slope && a->hurst == b->hurst && a->lambda_s == b->lambda_s;
}

/* The group label: h'rms, and H and lambda_s when the scene sweeps them. */
static void group_label(const im_scene *scene, const sweep_row *row, char *label, size_t size)
{
    int written = snprintf(label, size, "h′_{rms} = %g, mean ± sd", row->slope);
    if (scene->hurst_count > 1 && written > 0 && (size_t)written < size)
        written += snprintf(label + written, size - (size_t)written, ", H = %g", row->hurst);
    if (scene->lambda_s_count > 1 && written > 0 && (size_t)written < size)
        snprintf(label + written, size - (size_t)written, ", λ_{s} = %g", row->lambda_s);
}

static int too_many_groups(const im_scene *scene)
{
    return im_fail(IM_EINVAL, "%s: fig2 of a sweep draws at most %d roughnesses (h'rms x H x lambda_s)", scene->path,
                   MAX_GROUPS);
}

int scene_sweep_check_fig2(const im_scene *scene)
{
    if (scene_sweep_count(scene) == 1 || !scene->table || !scene_wants_plot(scene, IM_SCENE_PLOT_FIG2))
        return IM_OK;
    int roughnesses = scene_rough_family_count(scene) * list_count(scene->hurst_count) *
                      list_count(scene->lambda_s_count);
    return roughnesses > MAX_GROUPS ? too_many_groups(scene) : IM_OK;
}

/* Rough rows with a finite rho_c, grouped (at most MAX_GROUPS groups; IM_EINVAL beyond). */
static int group_rows(const im_scene *scene, const sweep_row *rows, int count, sweep_groups *g)
{
    const sweep_row *first[MAX_GROUPS];
    for (int i = 0; i < count; ++i) {
        if (!(rows[i].slope > 0.0) || !isfinite(rows[i].rho_c) || !(rows[i].rho_c > 0.0))
            continue;
        int k = 0;
        while (k < g->count && !same_roughness(first[k], &rows[i]))
            ++k;
        if (k == MAX_GROUPS)
            return too_many_groups(scene);
        paper_sweep_group *group = &g->groups[k];
        if (k == g->count) {
            first[g->count++] = &rows[i];
            group_label(scene, &rows[i], g->labels[k], sizeof g->labels[k]);
            *group = (paper_sweep_group){.label = g->labels[k],
                                         .rho_c = g->x[k],
                                         .area_ratio = g->y[k],
                                         .sd = g->sigma[k]};
        }
        if (group->count == IM_SCENE_MAX_SWEEP_POINTS) /* parse.c refuses repeated values, so this is a bug */
            return im_fail(IM_EINVAL, "%s: fig2 of a sweep: more than %d points of one roughness", scene->path,
                           IM_SCENE_MAX_SWEEP_POINTS);
        g->x[k][group->count] = rows[i].rho_c;
        g->y[k][group->count] = rows[i].area_ratio;
        g->sigma[k][group->count++] = rows[i].sd;
    }
    return IM_OK;
}

static int draw_sweep(const im_scene *scene, const void *data, const paper_file *file)
{
    const sweep_groups *g = data;
    return paper_figure_sweep(g->groups, g->count, scene->path, file);
}

/* Fig. 2 over the whole sweep (paper/sweep_figure.c): each roughness's points (its angles) as a
 * series of its own against rho_c, beside eq. (12) and eq. (6). */
static int plot_sweep(const im_scene *scene, const sweep_row *rows, int count)
{
    sweep_groups *g = calloc(1, sizeof *g);
    if (!g)
        return im_fail(IM_ENOMEM, "%s: allocation of the sweep's plot failed", scene->path);
    int status = group_rows(scene, rows, count, g);
    if (status == IM_OK)
        status = scene_write_png_pdf(scene, "fig2", draw_sweep, g);
    free(g);
    return status;
}

/* Runs sweep point index with run_stages, appending its table's families to rows. */
static int run_point(const im_scene *scene, const im_scene_run_options *options, int index,
                     scene_stage_runner run_stages, sweep_row *rows, int *row_count)
{
    im_scene *point = malloc(sizeof *point);
    if (!point)
        return im_fail(IM_ENOMEM, "%s: allocation of a sweep point failed", scene->path);
    int status = scene_sweep_point(scene, index, point);
    if (status == IM_OK) {
        scene_progress(options, "sweep point %d of %d: alpha = %g, hurst = %g, lambda_s = %g (%s)", index + 1,
                       scene_sweep_count(scene), point->alpha_degrees, point->surface.hurst, point->surface.lambda_s,
                       point->output_dir);
    }
    if (status == IM_OK)
        status = im_make_directories(point->output_dir);
    scene_reuse reuse = {0};
    if (status == IM_OK)
        status = run_stages(point, options, &reuse);
    for (int f = 0; status == IM_OK && reuse.table && f < point->family_count; ++f)
        rows[(*row_count)++] = sweep_summary(point, reuse.table, reuse.table_count, f);
    scene_reuse_free(&reuse);
    free(point);
    return status;
}

int scene_sweep_check_points(const im_scene *scene, const im_scene_run_options *options, scene_limits *each)
{
    im_scene *point = malloc(sizeof *point);
    if (!point)
        return im_fail(IM_ENOMEM, "%s: allocation of a sweep point failed", scene->path);
    int status = IM_OK;
    for (int i = 0; i < scene_sweep_count(scene) && status == IM_OK; ++i) {
        status = scene_sweep_point(scene, i, point);
        scene_limits limits;
        if (status == IM_OK)
            status = scene_check_limits(point, options, each ? &each[i] : &limits);
    }
    free(point);
    return status;
}

int scene_run_sweep(const im_scene *scene, const im_scene_run_options *options, scene_stage_runner run_stages)
{
    int count = scene_sweep_count(scene), row_count = 0;
    sweep_row *rows = calloc((size_t)count * IM_SCENE_MAX_FAMILIES, sizeof *rows);
    if (!rows)
        return im_fail(IM_ENOMEM, "%s: allocation of the sweep's rows failed", scene->path);
    int status = scene_sweep_check_points(scene, options, NULL);
    for (int i = 0; i < count && status == IM_OK; ++i) {
        if (scene_stop_signal(options))
            status = scene_interrupted(options, "between sweep points");
        else
            status = run_point(scene, options, i, run_stages, rows, &row_count);
    }
    if (status == IM_OK && scene->table)
        status = write_sweep_csv(scene, rows, row_count);
    if (status == IM_OK && scene->table && scene_wants_plot(scene, IM_SCENE_PLOT_FIG2))
        status = plot_sweep(scene, rows, row_count);
    free(rows);
    return status;
}
