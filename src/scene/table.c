/* The ensemble table (the paper's Table 1): every seed of every family solved at one load, in
 * parallel over surfaces; per family the mean and spread of A/A_cone beside eq. (12). */
#include "indentmap/io.h"
#include "scene/contents.h"
#include "core/summation.h"
#include "indentmap/paper.h"
#include "indentmap/status.h"
#include "scene/ensemble.h"
#include "scene/key.h"
#include "scene/outputs.h"
#include "scene/plots.h"
#include "scene/progress.h"
#include "scene/punch.h"
#include "scene/run_state.h"
#include "scene/surfaces.h"
#include "scene/table.h"

#include <inttypes.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* The paper's Table 1 (alpha = 80 degrees), for the Markdown table beside ours. */
static const struct paper_row {
    double slope, height_rms, rho_c;
    long n_p_ref;
    double area_ratio, sd, eq12;
} PAPER_TABLE1[] = {
    {0.00, NAN, INFINITY, 37164, 1.000, 0.0, 1.000}, {0.01, 0.16, 17.63, 37364, 1.002, 0.009, 0.998},
    {0.02, 0.32, 8.82, 37470, 1.001, 0.017, 0.992},  {0.04, 0.64, 4.41, 37211, 0.985, 0.031, 0.969},
    {0.08, 1.29, 2.20, 35152, 0.909, 0.045, 0.894},  {0.16, 2.57, 1.10, 30031, 0.724, 0.044, 0.719},
};

static const struct paper_row *paper_row_for(double slope)
{
    for (size_t i = 0; i < sizeof PAPER_TABLE1 / sizeof *PAPER_TABLE1; ++i)
        if (fabs(PAPER_TABLE1[i].slope - slope) < 1e-12)
            return &PAPER_TABLE1[i];
    return NULL;
}

static int member_path(const im_scene *scene, const scene_member *m, char *path, size_t size)
{
    char relative[96];
    snprintf(relative, sizeof relative, "table/member_%02d_%llu.csv", m->family, (unsigned long long)m->seed);
    return scene_output_path(scene, relative, path, size);
}

static const char MEMBER_HEADER[] = "family,slope,seed,height_rms,load,load_star,contact_patches,area_ratio,"
                                    "iterations,seconds,approach,key,checksum\n";

/* The header, then one row whose last column is the checksum of the row before it: a kept member
 * with a changed digit is solved again, not read into the table. */
static int write_member(const im_scene *scene, const scene_member *m)
{
    char path[IM_SCENE_PATH], text[640];
    int status = member_path(scene, m, path, sizeof path);
    uint64_t key = scene_result_key(scene, m->family, m->seed, SCENE_RESULT_AT_LOAD_STAR);
    size_t header = sizeof MEMBER_HEADER - 1;
    int length = snprintf(text, sizeof text, "%s%d,%.17g,%llu,%.17g,%.17g,%.17g,%ld,%.17g,%d,%.6f,%.17g,%016" PRIx64,
                          MEMBER_HEADER, m->family, scene_member_slope(scene, m->family, m->seed),
                          (unsigned long long)m->seed, m->height_rms, m->load, m->load_star, m->contact_patches,
                          m->area_ratio, m->iterations, m->seconds, m->load_star_approach, key);
    uint64_t checksum = scene_checksum(text + header, (size_t)length - header);
    length += snprintf(text + length, sizeof text - (size_t)length, ",%016" PRIx64 "\n", checksum);
    return status == IM_OK ? im_write_file_atomic(path, text, (size_t)length) : status;
}

/* A kept member's row (after the header) into m and *key; 0 with why when it is not this version's
 * whole row of this member, or its checksum does not match it (edited). */
static int member_is_whole(const char *text, scene_member *m, uint64_t *key, char *why, size_t why_size)
{
    size_t header = sizeof MEMBER_HEADER - 1;
    const char *row = strncmp(text, MEMBER_HEADER, header) == 0 ? text + header : NULL, *last = NULL;
    double slope;
    unsigned long long seed;
    uint64_t checksum = 0;
    int family, used = 0;
    if (row)
        last = strrchr(row, ',');
    if (!last || sscanf(last, ",%" SCNx64 "%n", &checksum, &used) != 1 || strcmp(last + used, "\n") != 0 ||
        sscanf(row, "%d,%lf,%llu,%lf,%lf,%lf,%ld,%lf,%d,%lf,%lf,%" SCNx64, &family, &slope, &seed, &m->height_rms,
               &m->load, &m->load_star, &m->contact_patches, &m->area_ratio, &m->iterations, &m->seconds,
               &m->load_star_approach, key) != 12) {
        snprintf(why, why_size,
                 "expected the header line \"%.40s...\" and one row ending in a key and a checksum; "
                 "or an older version wrote it",
                 MEMBER_HEADER);
        return 0;
    }
    if (family != m->family || seed != m->seed) {
        snprintf(why, why_size, "it holds family %d, seed %llu, where its name says %d, %llu", family, seed,
                 m->family, (unsigned long long)m->seed);
        return 0;
    }
    if (scene_checksum(row, (size_t)(last - row)) != checksum) {
        snprintf(why, why_size, "its row does not match its checksum: edited");
        return 0;
    }
    return 1;
}

int scene_table_member_kept(const im_scene *scene, const im_scene_run_options *options, scene_member *m)
{
    char path[IM_SCENE_PATH], why[160];
    if (member_path(scene, m, path, sizeof path) != IM_OK || access(path, F_OK) != 0)
        return 0;
    char *text = NULL;
    if (im_read_text_file(path, 4096, &text, NULL) != IM_OK)
        return scene_kept_damaged(options, path, im_last_error());
    uint64_t key = 0;
    int whole = member_is_whole(text, m, &key, why, sizeof why);
    free(text);
    if (!whole)
        return scene_kept_damaged(options, path, why);
    return scene_key_matches(options, path, key,
                             scene_result_key(scene, m->family, m->seed, SCENE_RESULT_AT_LOAD_STAR));
}

/* Solves one member at load_star: load control, warm-started by a step at a quarter of it. */
static int solve_member(const im_scene *scene, const im_scene_run_options *run_options, scene_member *m)
{
    im_field *surface = NULL;
    int status = scene_surface(scene, m->family, m->seed, &surface);
    im_surface_stats stats;
    if (status == IM_OK)
        status = im_surface_statistics(surface, &stats);
    im_indentation *run = NULL;
    im_step_result step = {0};
    if (status == IM_OK) {
        m->height_rms = stats.height_rms;
        double n = scene_load_for_load_star(scene, surface->delta);
        im_indenter punch = scene_punch(scene);
        im_solver_options options = scene_solver_options(scene);
        options.wisdom_path = NULL; /* two steps on a window of its own size: measuring its plans would not pay
                                      * (docs/solver.md, "FFTW wisdom") */
        status = im_indentation_create(surface, &punch, IM_CONTROL_LOAD, n, &options, &run);
        if (status == IM_OK)
            status = im_indentation_step(run, 0.25 * n, &step);
        int warm_up_iterations = step.iterations;
        if (status == IM_OK && scene_stop_signal(run_options))
            status = IM_EINTERRUPTED; /* abandoned: the caller reports the interruption */
        if (status == IM_OK)
            status = im_indentation_step(run, n, &step);
        if (status == IM_OK && scene_keeps_force(scene, m))
            status = im_indentation_fields(run, &m->force, NULL, NULL);
        m->iterations = warm_up_iterations + step.iterations;
    }
    im_indentation_free(run);
    im_field_free(surface);
    m->load = step.load;
    m->load_star = step.load_star;
    m->load_star_approach = step.approach;
    m->contact_patches = step.contact_patches;
    m->area_ratio = step.area_ratio;
    return status;
}

int scene_table_member(const im_scene *scene, const im_scene_run_options *options, scene_member *m)
{
    if (options->resume && scene_table_member_kept(scene, options, m)) {
        m->origin = SCENE_READ_BACK;
        return IM_OK;
    }
    double start = omp_get_wtime();
    int status = solve_member(scene, options, m);
    m->seconds = omp_get_wtime() - start;
    return status == IM_OK ? write_member(scene, m) : status;
}

typedef struct family_summary {
    double slope, rho_c, height_rms, area_ratio, sd, eq12, relative_error, n_p_mean, n_p_sd;
    long n_p_ref;
    int count;
} family_summary;

static family_summary summarise(const im_scene *scene, const scene_member *members, int count, int family)
{
    family_summary s = {.slope = scene->slopes[family], .n_p_ref = -1};
    /* members keep h_rms in the surfaces' length unit; the table states it in delta (run.json's units),
     * which differ for files with a unit (all files of a scene share one delta) */
    const double delta = scene->surface.delta;
    double sum = 0.0, sum_sq = 0.0, height = 0.0, patches = 0.0, patches_sq = 0.0;
    for (int i = 0; i < count; ++i) {
        const scene_member *m = &members[i];
        if (m->family != family)
            continue;
        ++s.count;
        sum += m->area_ratio;
        sum_sq += m->area_ratio * m->area_ratio;
        height += m->height_rms / delta;
        patches += (double)m->contact_patches;
        patches_sq += (double)m->contact_patches * (double)m->contact_patches;
        if (s.n_p_ref < 0 || m->contact_patches < s.n_p_ref)
            s.n_p_ref = m->contact_patches;
    }
    s.area_ratio = sum / s.count;
    /* the smooth family is the same surface for every seed, solved once: its spread is exactly 0 */
    const int smooth = s.slope == 0.0;
    s.sd = smooth ? 0.0 : sample_sd(sum, sum_sq, s.count);
    s.height_rms = height / s.count;
    s.n_p_mean = patches / s.count;
    s.n_p_sd = smooth ? 0.0 : sample_sd(patches, patches_sq, s.count);
    s.eq12 = scene_eq12(scene, s.slope, &s.rho_c);
    s.relative_error = fabs(s.area_ratio - s.eq12) / s.area_ratio;
    return s;
}

static int write_table_csv(const im_scene *scene, const family_summary *rows)
{
    im_atomic_file file;
    int status = scene_open_output(scene, "table1.csv", &file);
    if (status != IM_OK)
        return status;
    fprintf(file.stream, "slope,surfaces,height_rms_mean,rho_c,n_p_ref,n_p_mean,area_ratio_mean,area_ratio_sd,"
                         "area_ratio_eq12,relative_error,n_p_sd\n");
    for (int f = 0; f < scene->family_count; ++f) {
        const family_summary *r = &rows[f];
        fprintf(file.stream, "%.6g,%d,%.6g,%.6g,%ld,%.1f,%.6f,%.6f,%.6f,%.6f,%.1f\n", r->slope, r->count,
                r->height_rms, r->rho_c, r->n_p_ref, r->n_p_mean, r->area_ratio, r->sd, r->eq12, r->relative_error,
                r->n_p_sd);
    }
    return im_atomic_commit(&file);
}

/* Whether a (sweep-made) value is the paper's: a range's steps round (hurst = 0.2:0.9:8 gives 0.7999999999999998). */
static int is_papers(double value, double papers) { return fabs(value - papers) <= 1e-9 * papers; }

/* The paper's Table 1 is of elastic 80° cones on generated surfaces of H = 0.8 and lambda_s = 4 delta:
 * beside another angle, spectrum, a surface file or a hardness its values would be those of other contacts
 * (a sweep's alpha = 70 point beside the paper's 0.724 at h'rms 0.16, where eq. (12) gives 0.900). */
static int papers_setting(const im_scene *scene)
{
    return scene->file_count == 0 && scene->punch == IM_PUNCH_CONE && is_papers(scene->alpha_degrees, 80.0) &&
           is_papers(scene->surface.hurst, 0.8) && is_papers(scene->surface.lambda_s, 4.0) && !(scene->hardness > 0);
}

static void markdown_row(FILE *out, const im_scene *scene, const family_summary *r)
{
    const struct paper_row *p = papers_setting(scene) ? paper_row_for(r->slope) : NULL;
    char paper[64] = "–", spread[32] = ""; /* no ± for one surface: it has no spread (sample_sd) */
    if (p)
        snprintf(paper, sizeof paper, "%.3f ± %.3f (%ld)", p->area_ratio, p->sd, p->n_p_ref);
    if (!isnan(r->sd))
        snprintf(spread, sizeof spread, " ± %.3f", r->sd);
    if (r->slope == 0.0)
        fprintf(out, "| 0.00 | – | – | %ld | %.3f | %.3f | – | %s |\n", r->n_p_ref, r->area_ratio, r->eq12, paper);
    else
        fprintf(out, "| %.2f | %.2f | %.2f | %ld | %.3f%s | %.3f | %.1f%% | %s |\n", r->slope, r->height_rms,
                r->rho_c, r->n_p_ref, r->area_ratio, spread, r->eq12, 100.0 * r->relative_error, paper);
}

static int write_table_markdown(const im_scene *scene, const family_summary *rows)
{
    im_atomic_file file;
    int status = scene_open_output(scene, "table1.md", &file);
    if (status != IM_OK)
        return status;
    fprintf(file.stream,
            "A/A_cone at N* = %g (alpha = %g°, %d x %d, %d surface%s per h'rms, quality %s, tol %g), %s.\n\n",
            scene->load_star, scene->alpha_degrees, scene->surface.nx, scene->surface.ny, scene->seed_count,
            scene->seed_count == 1 ? "" : "s", scene->quality, scene->tol,
            papers_setting(scene)
                ? "beside the paper's Table 1 (Icarus mean ± sd, and its n_p,ref)"
                : "without the paper's Table 1 beside it (its cones are elastic, of 80°, on generated "
                  "surfaces of H = 0.8 and lambda_s = 4)");
    if (scene->file_count > 0)
        fprintf(file.stream,
                "The surface%s the %d file%s of `file`; h'rms is measured by %s of each surface as solved "
                "(root mean square over the files), and eq. (12) is taken at it.\n\n",
                scene->file_count == 1 ? " is" : "s are", scene->file_count, scene->file_count == 1 ? "" : "s",
                scene->run->file_slope_definition == IM_SLOPE_SPECTRAL ? "the spectrum" : "forward differences");
    fprintf(file.stream, "| h'rms | mean h_rms/δ | ρ_c | n_p,ref | A/A_cone indentmap | A/A_cone eq. (12) | "
                         "relative error | paper (Icarus) |\n|---|---|---|---|---|---|---|---|\n");
    for (int f = 0; f < scene->family_count; ++f)
        markdown_row(file.stream, scene, &rows[f]);
    return im_atomic_commit(&file);
}

/* Fig. 2: the rough families' means and standard deviations against rho_c. */
static int plot_area_ratio(const im_scene *scene, const family_summary *rows)
{
    double x[IM_SCENE_MAX_FAMILIES], y[IM_SCENE_MAX_FAMILIES], sigma[IM_SCENE_MAX_FAMILIES];
    int count = 0;
    for (int f = 0; f < scene->family_count; ++f) {
        if (!(rows[f].slope > 0.0))
            continue;
        x[count] = rows[f].rho_c;
        y[count] = rows[f].area_ratio;
        sigma[count++] = rows[f].sd;
    }
    im_paper_points points = {x, y, sigma, count, NULL};
    return scene_plot_area_ratio(scene, &points);
}

int scene_run_table(const im_scene *scene, const im_scene_run_options *options, scene_reuse *reuse)
{
    scene_member *members = NULL;
    int count = 0;
    int status = scene_ensemble_prepare(scene, "table", &members, &count);
    if (status == IM_OK) {
        scene_progress(options, "table: %d surface%s of %d famil%s at N* = %g", count, count == 1 ? "" : "s",
                       scene->family_count, scene->family_count == 1 ? "y" : "ies", scene->load_star);
        status = scene_ensemble_run(scene, options, "table", members, count, scene_table_member, reuse->ranks);
    }
    if (status == IM_OK)
        scene_report_origins(options, "table", members, count);
    family_summary rows[IM_SCENE_MAX_FAMILIES];
    for (int f = 0; status == IM_OK && f < scene->family_count; ++f)
        rows[f] = summarise(scene, members, count, f);
    if (status == IM_OK)
        status = write_table_csv(scene, rows);
    if (status == IM_OK)
        status = write_table_markdown(scene, rows);
    if (status == IM_OK && scene_wants_plot(scene, IM_SCENE_PLOT_FIG2))
        status = plot_area_ratio(scene, rows);
    scene_reuse_take_forces(reuse, members, count, SCENE_RESULT_AT_LOAD_STAR);
    reuse->table = members;
    reuse->table_count = count;
    return status;
}
