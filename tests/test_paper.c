/* The paper's figure builders (src/paper/figures.h): re-entrant (two threads building figures at
 * once write the same bytes as one thread alone), and their checks on the data. */
#include "paper/figures.h"

#include "indentmap/status.h"
#include "support.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

enum { FAMILIES = 2, SEEDS = 3, STEPS = 6, MEMBERS = FAMILIES * SEEDS, ROUNDS = 8 };

/* Made-up histories of two families (smooth, rough); `variant` changes every number, so that
 * figures of the two variants differ wherever one's data leaked into the other's. */
typedef struct made_histories {
    double approach[MEMBERS][STEPS], load[MEMBERS][STEPS], load_star[MEMBERS][STEPS], ratio[MEMBERS][STEPS];
    long patches[MEMBERS][STEPS];
    paper_history members[MEMBERS];
    double slopes[FAMILIES], eq12[FAMILIES];
    const char *titles[FAMILIES];
    paper_histories h;
} made_histories;

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
        m->members[i] = (paper_history){family, STEPS, m->approach[i], m->load[i], m->load_star[i], m->ratio[i],
                                        m->patches[i]};
    }
    m->slopes[0] = 0.0, m->slopes[1] = 0.08;
    m->eq12[0] = NAN, m->eq12[1] = 0.9;
    m->titles[0] = "smooth", m->titles[1] = variant ? "variant B" : "variant A";
    m->h = (paper_histories){.source = "test.ini", .family_count = FAMILIES, .slopes = m->slopes,
                             .titles = m->titles, .eq12 = m->eq12, .members = m->members, .count = MEMBERS,
                             .delta = 1.0, .e_star = 1.0, .cot_alpha = 0.176};
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

/* Figs. 7 and 5 of one variant into dir/NAME_v_r.png. */
static int build(const made_histories *m, int variant, int round, const char *dir, char paths[2][512])
{
    snprintf(paths[0], 512, "%s/fig7_%d_%d.png", dir, variant, round);
    snprintf(paths[1], 512, "%s/fig5_%d_%d.png", dir, variant, round);
    int status = paper_figure_area_ratio_against_load(&m->h, paths[0]);
    return status == IM_OK ? paper_figure_against_approach(&m->h, 0, paths[1]) : status;
}

/* Both threads start each round together, so that their builders overlap. */
static pthread_barrier_t round_start;

typedef struct builder_thread {
    const made_histories *data;
    int variant, failures;
    char reference[2][512];
} builder_thread;

static void *build_rounds(void *arg)
{
    builder_thread *t = arg;
    for (int r = 0; r < ROUNDS; ++r) {
        char paths[2][512];
        pthread_barrier_wait(&round_start);
        if (build(t->data, t->variant, r + 1, test_temp_dir(), paths) != IM_OK)
            ++t->failures;
        else
            t->failures += !same_file(paths[0], t->reference[0]) + !same_file(paths[1], t->reference[1]);
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
    assert_false(same_file(threads[0].reference[0], threads[1].reference[0]));
    assert_false(same_file(threads[0].reference[1], threads[1].reference[1]));
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
    const char *path = test_path("fig7_none.png");
    assert_int_equal(paper_figure_area_ratio_against_load(&data.h, path), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "test.ini: fig7 needs a rough family"));
    assert_int_equal(access(path, F_OK), -1);
}

static void test_panel_columns(void **state)
{
    (void)state;
    const int counts[] = {1, 2, 3, 4, 5, 6, 8, 9, 10, 12}, columns[] = {1, 2, 3, 2, 5, 3, 2, 3, 2, 3};
    for (size_t i = 0; i < sizeof counts / sizeof *counts; ++i)
        assert_int_equal(paper_panel_columns(counts[i]), columns[i]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_builders_are_reentrant),
        cmocka_unit_test(test_fig7_needs_a_common_range),
        cmocka_unit_test(test_panel_columns),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
