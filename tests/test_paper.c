/* The paper's figure builders (src/paper/figures.h): re-entrant (two threads building figures at
 * once write the same bytes as one thread alone), and their checks on the data. */
#include "paper/figures.h"

#include "indentmap/status.h"
#include "support.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

enum { FAMILIES = 2, SEEDS = 3, STEPS = 6, MEMBERS = FAMILIES * SEEDS, ROUNDS = 8, FIGURES = 4 };
enum { ANGLES = 4, BINS = 12 };

/* A sweep's made-up groups: each family's A / A_cone at ANGLES values of rho_c. */
typedef struct made_sweep {
    double rho_c[FAMILIES][ANGLES], ratio[FAMILIES][ANGLES], sd[FAMILIES][ANGLES];
    paper_sweep_group groups[FAMILIES];
} made_sweep;

/* Made-up distributions of the two families (the second rough). */
typedef struct made_distributions {
    double gap[FAMILIES][BINS], density[FAMILIES][BINS], area[FAMILIES][BINS], patches[FAMILIES][BINS];
    paper_distribution_family families[FAMILIES];
} made_distributions;

/* Made-up histories of two families (smooth, rough); `variant` changes every number, so that
 * figures of the two variants differ wherever one's data leaked into the other's. */
typedef struct made_histories {
    double approach[MEMBERS][STEPS], load[MEMBERS][STEPS], load_star[MEMBERS][STEPS], ratio[MEMBERS][STEPS];
    long patches[MEMBERS][STEPS];
    paper_history members[MEMBERS];
    double slopes[FAMILIES], eq12[FAMILIES];
    const char *titles[FAMILIES];
    paper_histories h;
    made_sweep sweep;
    made_distributions distributions;
} made_histories;

static void make_sweep(int variant, const char *const *labels, made_sweep *m)
{
    for (int f = 0; f < FAMILIES; ++f) {
        for (int i = 0; i < ANGLES; ++i) {
            m->rho_c[f][i] = (0.5 + i) * (1.0 + f) * (1.0 + 0.3 * variant);
            m->ratio[f][i] = 0.3 + 0.15 * i + 0.02 * f;
            m->sd[f][i] = 0.01 * (1 + i);
        }
        m->groups[f] = (paper_sweep_group){labels[f], ANGLES, m->rho_c[f], m->ratio[f], m->sd[f]};
    }
}

static void make_distributions(int variant, const char *const *labels, made_distributions *m)
{
    for (int f = 0; f < FAMILIES; ++f) {
        for (int b = 0; b < BINS; ++b) {
            m->gap[f][b] = (b + 0.5) * 0.2;
            m->density[f][b] = exp(-(1.0 + variant) * m->gap[f][b]);
            m->area[f][b] = (double)(1L << b);
            m->patches[f][b] = b < 7 ? (double)(64 >> b) + variant : NAN; /* NaN: empty bins */
        }
        m->families[f] = (paper_distribution_family){labels[f],     f == 1, BINS,       m->gap[f],
                                                     m->density[f], BINS,   m->area[f], m->patches[f]};
    }
}

static void make_histories(int variant, made_histories *m)
{
    for (int i = 0; i < MEMBERS; ++i) {
        int family = i / SEEDS, seed = i % SEEDS;
        for (int k = 0; k < STEPS; ++k) {
            double w = (k + 1) * (1.0 + 0.5 * variant);
            m->approach[i][k] = w;
            m->load_star[i][k] = 100.0 * (k + 1) + 10.0 * seed;
            m->load[i][k] = 0.01 * w * w;
            m->ratio[i][k] = 1.0 - 0.05 * family * (1.0 + variant) - 0.01 * seed + 0.002 * k;
            m->patches[i][k] = (long)(40 * w * w) + seed;
        }
        m->members[i] = (paper_history){family,          STEPS,       m->approach[i], m->load[i],
                                        m->load_star[i], m->ratio[i], m->patches[i]};
    }
    m->slopes[0] = 0.0, m->slopes[1] = 0.08;
    m->eq12[0] = NAN, m->eq12[1] = 0.9;
    m->titles[0] = "smooth", m->titles[1] = variant ? "variant B" : "variant A";
    m->h = (paper_histories){.source = "test.ini",
                             .family_count = FAMILIES,
                             .slopes = m->slopes,
                             .titles = m->titles,
                             .eq12 = m->eq12,
                             .members = m->members,
                             .count = MEMBERS,
                             .delta = 1.0,
                             .e_star = 1.0,
                             .cot_alpha = 0.176};
    make_sweep(variant, m->titles, &m->sweep);
    make_distributions(variant, m->titles, &m->distributions);
}

static char *read_all(const char *path, size_t *size)
{
    FILE *stream = fopen(path, "rb");
    assert_non_null(stream);
    fseek(stream, 0, SEEK_END);
    *size = (size_t)ftell(stream);
    rewind(stream);
    char *bytes = malloc(*size + 1);
    assert_non_null(bytes);
    assert_int_equal(fread(bytes, 1, *size, stream), *size);
    fclose(stream);
    return bytes;
}

static int same_file(const char *a, const char *b)
{
    size_t size_a, size_b;
    char *x = read_all(a, &size_a), *y = read_all(b, &size_b);
    int same = size_a == size_b && memcmp(x, y, size_a) == 0;
    free(x);
    free(y);
    return same;
}

/* Figs. 7 and 5, the sweep's fig2 and the distributions of one variant into dir/NAME_v_r.png. */
static int build(const made_histories *m, int variant, int round, const char *dir, char paths[FIGURES][512])
{
    const char *names[FIGURES] = {"fig7", "fig5", "sweep", "distributions"};
    for (int i = 0; i < FIGURES; ++i)
        snprintf(paths[i], 512, "%s/%s_%d_%d.png", dir, names[i], variant, round);
    int status = paper_figure_area_ratio_against_load(&m->h, &(paper_file){.path = paths[0]});
    if (status == IM_OK)
        status = paper_figure_against_approach(&m->h, 0, &(paper_file){.path = paths[1]});
    if (status == IM_OK)
        status = paper_figure_sweep(m->sweep.groups, FAMILIES, "test.ini", &(paper_file){.path = paths[2]});
    return status == IM_OK ? paper_figure_distributions(m->distributions.families, FAMILIES, "test.ini",
                                                        &(paper_file){.path = paths[3]})
                           : status;
}

/* Both threads start each round together, so that their builders overlap. */
static pthread_barrier_t round_start;

typedef struct builder_thread {
    const made_histories *data;
    int variant, failures;
    char reference[FIGURES][512];
} builder_thread;

static void *build_rounds(void *arg)
{
    builder_thread *t = arg;
    for (int r = 0; r < ROUNDS; ++r) {
        char paths[FIGURES][512];
        pthread_barrier_wait(&round_start);
        if (build(t->data, t->variant, r + 1, test_temp_dir(), paths) != IM_OK)
            ++t->failures;
        else
            for (int i = 0; i < FIGURES; ++i)
                t->failures += !same_file(paths[i], t->reference[i]);
    }
    return NULL;
}

/* A builder that kept its data in static buffers would draw one thread's numbers in the other's
 * figure: each file must equal the one the same data gave on one thread alone. */
static void test_builders_are_reentrant(void **state)
{
    (void)state;
    static made_histories data[2];
    builder_thread threads[2];
    for (int v = 0; v < 2; ++v) {
        make_histories(v, &data[v]);
        threads[v] = (builder_thread){.data = &data[v], .variant = v};
        assert_int_equal(build(&data[v], v, 0, test_temp_dir(), threads[v].reference), IM_OK);
    }
    for (int i = 0; i < FIGURES; ++i)
        assert_false(same_file(threads[0].reference[i], threads[1].reference[i]));
    pthread_t ids[2];
    assert_int_equal(pthread_barrier_init(&round_start, NULL, 2), 0);
    for (int v = 0; v < 2; ++v)
        assert_int_equal(pthread_create(&ids[v], NULL, build_rounds, &threads[v]), 0);
    for (int v = 0; v < 2; ++v)
        assert_int_equal(pthread_join(ids[v], NULL), 0);
    pthread_barrier_destroy(&round_start);
    assert_int_equal(threads[0].failures, 0);
    assert_int_equal(threads[1].failures, 0);
}

/* Fig. 7 of data refused for want of a common range of N*, nothing written to NAME. */
static void assert_no_fig7(const made_histories *data, const char *name)
{
    const char *path = test_path(name);
    assert_int_equal(paper_figure_area_ratio_against_load(&data->h, &(paper_file){.path = path}), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "test.ini: fig7 needs a rough family"));
    assert_int_equal(access(path, F_OK), -1);
}

/* Fig. 7 draws the N* range all of a family's surfaces reached: surfaces whose ranges do not
 * overlap share none, and nothing is written. */
static void test_fig7_needs_a_common_range(void **state)
{
    (void)state;
    static made_histories data;
    make_histories(0, &data);
    for (int i = 0; i < MEMBERS; ++i)
        for (int k = 0; k < STEPS; ++k)
            data.load_star[i][k] += 1000.0 * i;
    assert_no_fig7(&data, "fig7_none.png");
}

/* Histories of one step each are no range of N* (the range's ends were 0 and inf: "x[1] = inf"). */
static void test_fig7_needs_two_steps(void **state)
{
    (void)state;
    static made_histories data;
    make_histories(0, &data);
    for (int i = 0; i < MEMBERS; ++i)
        data.members[i].steps = 1;
    assert_no_fig7(&data, "fig7_one_step.png");
}

/* fig7.csv holds what Fig. 7 plots: made_histories' rough family has A / A_cone = 0.948 + 2e-5 N*
 * - 0.0102 s for seed s = 0, 1, 2 on N* from 120 (the last first point) to 600 (the first last),
 * so the mean is 0.9378 + 2e-5 N* and the sample sd 0.0102 at every N*; the smooth family is not
 * in it. */
/* fig7.csv of histories written to the test folder's file name, opened for reading. */
static FILE *fig7_statistics(const paper_histories *h, const char *name)
{
    const char *path = test_path(name);
    FILE *out = fopen(path, "w");
    assert_non_null(out);
    assert_int_equal(paper_write_area_ratio_statistics(h, out), IM_OK);
    fclose(out);
    FILE *in = fopen(path, "r");
    assert_non_null(in);
    return in;
}

static void test_fig7_statistics(void **state)
{
    (void)state;
    static made_histories data;
    make_histories(0, &data);
    FILE *in = fig7_statistics(&data.h, "fig7.csv");
    char header[128];
    assert_non_null(fgets(header, sizeof header, in));
    assert_string_equal(header, "slope,n_star,area_ratio_mean,area_ratio_sd,surfaces,area_ratio_eq12\n");
    double slope, n_star, mean, sd, eq12, first = NAN, last = NAN;
    int surfaces, rows = 0;
    while (fscanf(in, "%lf,%lf,%lf,%lf,%d,%lf\n", &slope, &n_star, &mean, &sd, &surfaces, &eq12) == 6) {
        assert_close(slope, 0.08, 0.0);
        assert_close(mean, 0.9378 + 2e-5 * n_star, 1e-12);
        assert_close(sd, 0.0102, 1e-12);
        assert_int_equal(surfaces, SEEDS);
        assert_close(eq12, 0.9, 0.0);
        first = rows++ == 0 ? n_star : first;
        last = n_star;
    }
    fclose(in);
    assert_int_equal(rows, 40);
    assert_close(first, 120.0, 1e-12);
    assert_close(last, 600.0, 1e-12);
}

/* One surface of a family has no spread to estimate: fig7.csv's sd is nan (it was 0, a claim that
 * the mean is exact). */
static void test_fig7_one_surface_has_no_sd(void **state)
{
    (void)state;
    static made_histories data;
    make_histories(0, &data);
    data.h.count = SEEDS + 1; /* the smooth family's surfaces and the rough family's first only */
    FILE *in = fig7_statistics(&data.h, "fig7_one.csv");
    char line[256], sd[16];
    assert_non_null(fgets(line, sizeof line, in));
    int surfaces, rows = 0;
    double slope, n_star, mean;
    while (fgets(line, sizeof line, in)) {
        assert_int_equal(sscanf(line, "%lf,%lf,%lf,%15[^,],%d", &slope, &n_star, &mean, sd, &surfaces), 5);
        assert_string_equal(sd, "nan");
        assert_int_equal(surfaces, 1);
        assert_close(mean, 0.948 + 2e-5 * n_star, 1e-12); /* seed 0's ratio (0.0102 above the three's mean) */
        ++rows;
    }
    fclose(in);
    assert_int_equal(rows, 40);
}

/* The sphere's figure starts a surface at its first step of PAPER_MIN_PATCHES contact patches. */
static void test_first_resolved_step(void **state)
{
    (void)state;
    long few[] = {1, 1, 5, 9, 10, 30}, none[] = {1, 2, 3, 4, 5, 9};
    paper_history m = {.steps = 6, .patches = few};
    assert_int_equal(paper_first_resolved_step(&m), 4);
    m.patches = none;
    assert_int_equal(paper_first_resolved_step(&m), 6);
    m.steps = 0;
    assert_int_equal(paper_first_resolved_step(&m), 0);
}

/* Draws made_histories' sweep with `groups` groups into name; returns the builder's status. */
static int sweep_into(const made_sweep *m, int groups, const char *name)
{
    return paper_figure_sweep(m->groups, groups, "sweep.ini", &(paper_file){.path = test_path(name)});
}

/* The sweep's fig2 draws what it is given: its groups' points (a figure without them differs), on
 * an axis widened to a far point (the figure changes), and refuses what it cannot draw, naming
 * the source and writing nothing. */
static void test_sweep_figure(void **state)
{
    (void)state;
    static made_histories data;
    make_histories(0, &data);
    assert_int_equal(sweep_into(&data.sweep, FAMILIES, "sweep_two.png"), IM_OK);
    assert_int_equal(sweep_into(&data.sweep, 0, "sweep_theory.png"), IM_OK);
    assert_false(same_file(test_path("sweep_two.png"), test_path("sweep_theory.png")));
    data.sweep.rho_c[1][ANGLES - 1] = 5000.0; /* beyond 100: the axis widens to 10^4 */
    assert_int_equal(sweep_into(&data.sweep, FAMILIES, "sweep_wide.png"), IM_OK);
    assert_false(same_file(test_path("sweep_two.png"), test_path("sweep_wide.png")));

    data.sweep.rho_c[1][0] = 0.0;
    assert_int_equal(sweep_into(&data.sweep, FAMILIES, "sweep_zero.png"), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "sweep.ini: fig2 of a sweep: group 1's rho_c = 0"));
    assert_int_equal(access(test_path("sweep_zero.png"), F_OK), -1);
    data.sweep.rho_c[1][0] = 1.0;
    paper_sweep_group many[PAPER_MAX_SWEEP_GROUPS + 1];
    for (int k = 0; k <= PAPER_MAX_SWEEP_GROUPS; ++k)
        many[k] = data.sweep.groups[k % FAMILIES];
    assert_int_equal(paper_figure_sweep(many, PAPER_MAX_SWEEP_GROUPS + 1, "sweep.ini",
                                        &(paper_file){.path = test_path("sweep_many.png")}),
                     IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "sweep.ini: fig2 of a sweep draws at most 8 roughnesses"));
    assert_int_equal(access(test_path("sweep_many.png"), F_OK), -1);
    data.sweep.groups[0].area_ratio = NULL;
    assert_int_equal(sweep_into(&data.sweep, FAMILIES, "sweep_null.png"), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "sweep.ini: fig2 of a sweep: group 0 has 4 points without"));
}

/* The distributions figure: (a) only with a rough family (a figure of the smooth one alone
 * differs from both families'), and refusals that name the source and write nothing. */
static void test_distribution_figure(void **state)
{
    (void)state;
    static made_histories data;
    make_histories(0, &data);
    paper_distribution_family *families = data.distributions.families;
    const char *both = test_path("distributions_both.png"), *smooth = test_path("distributions_smooth.png");
    assert_int_equal(paper_figure_distributions(families, FAMILIES, "d.ini", &(paper_file){.path = both}), IM_OK);
    assert_int_equal(paper_figure_distributions(families, 1, "d.ini", &(paper_file){.path = smooth}), IM_OK);
    assert_false(same_file(both, smooth));

    const char *none = test_path("distributions_none.png");
    assert_int_equal(paper_figure_distributions(families, 0, "d.ini", &(paper_file){.path = none}), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "d.ini: distributions of 0 families: expected 1 to 64"));
    families[1].gap_density = NULL;
    assert_int_equal(paper_figure_distributions(families, FAMILIES, "d.ini", &(paper_file){.path = none}), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "d.ini: distributions: family 1's bins come without their arrays"));
    assert_int_equal(access(none, F_OK), -1);
}

static void test_panel_columns(void **state)
{
    (void)state;
    const int counts[] = {1, 2, 3, 4, 5, 6, 8, 9, 10, 12}, columns[] = {1, 2, 3, 2, 5, 3, 2, 3, 2, 3};
    for (size_t i = 0; i < sizeof counts / sizeof *counts; ++i)
        assert_int_equal(paper_panel_columns(counts[i]), columns[i]);
}

/* PNG width and height from its IHDR. */
static void png_size(const char *path, int *width, int *height)
{
    unsigned char header[24];
    FILE *file = fopen(path, "rb");
    assert_non_null(file);
    assert_int_equal(fread(header, 1, sizeof header, file), sizeof header);
    fclose(file);
    *width = header[16] << 24 | header[17] << 16 | header[18] << 8 | header[19];
    *height = header[20] << 24 | header[21] << 16 | header[22] << 8 | header[23];
}

/* The contact density of count maps (a disc of contact on 32^2 patches each) as PNG: its size. */
static void density_figure_size(int count, int *width, int *height)
{
    im_field *force;
    assert_int_equal(im_field_create(32, 32, 1.0, &force), IM_OK);
    for (int i = 0; i < 32 * 32; ++i)
        force->data[i] = hypot(i % 32 + 0.5 - 16, i / 32 + 0.5 - 16) < 10 ? 1.0 : 0.0;
    paper_density_map maps[6];
    for (int i = 0; i < count; ++i)
        maps[i] = (paper_density_map){force, 16, 16, 10, 0.01 * (i + 1), 314};
    const char *path = test_path("density.png");
    assert_int_equal(paper_figure_contact_density(80.0, maps, count, &(paper_file){.path = path}), IM_OK);
    png_size(path, width, height);
    im_field_free(force);
}

/* Five maps lie in rows of three, as six do (one row of five stood 4633 px wide at 300 dpi): the
 * figure is no wider than three maps' (the legend, outside their last frame, sits in the sixth cell),
 * as high as six maps'. */
static void test_density_rows_of_three(void **state)
{
    (void)state;
    int width3, height3, width5, height5, width6, height6;
    density_figure_size(3, &width3, &height3);
    density_figure_size(5, &width5, &height5);
    density_figure_size(6, &width6, &height6);
    assert_true(width5 <= width3 && width6 == width3);
    assert_int_equal(height5, height6);
    assert_true(height5 > 3 * height3 / 2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_builders_are_reentrant),
        cmocka_unit_test(test_fig7_needs_a_common_range),
        cmocka_unit_test(test_fig7_needs_two_steps),
        cmocka_unit_test(test_fig7_statistics),
        cmocka_unit_test(test_fig7_one_surface_has_no_sd),
        cmocka_unit_test(test_first_resolved_step),
        cmocka_unit_test(test_sweep_figure),
        cmocka_unit_test(test_distribution_figure),
        cmocka_unit_test(test_panel_columns),
        cmocka_unit_test(test_density_rows_of_three),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
