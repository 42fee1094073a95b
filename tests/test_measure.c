/* What an indentation experiment measures: the contact stiffness against Love's and Hertz's
 * closed forms, Sneddon's modulus of a simulated smooth cone against the true E*, contact patches
 * and gaps of hand-made fields. */
#include "support.h"

#include "indentmap/indenter.h"
#include "indentmap/measure.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <math.h>
#include <stdlib.h>

/* The three-point derivative is exact on Love's N = 2 E* w^2 / (pi cot alpha), unequal steps too,
 * and second order on Hertz's w^(3/2). */
static void stiffness_of_closed_forms(void **state)
{
    (void)state;
    const double w[] = {0.5, 0.8, 1.6, 2.0, 3.5}, cot = tan(10.0 * M_PI / 180.0);
    double love[5], hertz[5], s[5];
    for (int i = 0; i < 5; ++i) {
        love[i] = 2.0 * w[i] * w[i] / (M_PI * cot);
        hertz[i] = 4.0 / 3.0 * sqrt(100.0) * pow(w[i], 1.5);
    }
    assert_int_equal(im_measure_stiffness(w, love, 5, s), IM_OK);
    for (int i = 0; i < 5; ++i)
        assert_true(test_relative_difference(s[i], 4.0 * w[i] / (M_PI * cot)) < 1e-12);
    const double fine[] = {1.0, 1.01, 1.02};
    for (int i = 0; i < 3; ++i)
        hertz[i] = 4.0 / 3.0 * sqrt(100.0) * pow(fine[i], 1.5);
    assert_int_equal(im_measure_stiffness(fine, hertz, 3, s), IM_OK);
    /* Sneddon's S = 2 E* a with a = sqrt(R w) */
    assert_true(test_relative_difference(s[1], 2.0 * sqrt(100.0 * 1.01)) < 1e-5);
    assert_int_equal(im_measure_stiffness(w, love, 2, s), IM_OK);
    assert_true(s[0] == s[1] && test_relative_difference(s[0], (love[1] - love[0]) / 0.3) < 1e-14);
    /* unloading: the same curve walked back gives the same stiffness */
    double w_back[5], love_back[5];
    for (int i = 0; i < 5; ++i) {
        w_back[i] = w[4 - i];
        love_back[i] = 2.0 * w_back[i] * w_back[i] / (M_PI * cot);
    }
    assert_int_equal(im_measure_stiffness(w_back, love_back, 5, s), IM_OK);
    for (int i = 0; i < 5; ++i)
        assert_true(test_relative_difference(s[i], 4.0 * w_back[i] / (M_PI * cot)) < 1e-12);
    double turn[] = {1.0, 2.0, 1.5};
    assert_int_equal(im_measure_stiffness(turn, love, 3, s), IM_EINVAL);
    assert_int_equal(im_measure_stiffness(w, love, 1, s), IM_EINVAL);
}

/* A simulated smooth cone: the modulus Sneddon's relation infers from dN/dw and the smooth area is
 * the true E* within the grid's error (2%), however E* is scaled. */
static void sneddon_modulus_of_a_smooth_cone(void **state)
{
    (void)state;
    im_field *surface = NULL;
    assert_int_equal(im_field_create(128, 128, 1.0, &surface), IM_OK);
    im_indenter punch = im_indenter_cone(80.0);
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-8; /* the bars below were set at tol 1e-8 (not the default, 1e-6) */
    o.e_star = 3.0;
    im_indentation *run = NULL;
    assert_int_equal(im_indentation_create(surface, &punch, IM_CONTROL_DISPLACEMENT, 6.0, &o, &run), IM_OK);
    double w[5], n[5], s[5];
    for (int i = 0; i < 5; ++i) {
        im_step_result r;
        w[i] = 4.0 + 0.5 * i;
        assert_int_equal(im_indentation_step(run, w[i], &r), IM_OK);
        n[i] = r.load;
    }
    assert_int_equal(im_measure_stiffness(w, n, 5, s), IM_OK);
    double area = im_indenter_area_for_load(&punch, 3.0, n[2]);
    double e_eff = im_measure_sneddon_modulus(s[2], area);
    if (test_relative_difference(e_eff, 3.0) > 0.02)
        fail_msg("Sneddon's E* = %g, true 3", e_eff);
    assert_true(isnan(im_measure_sneddon_modulus(1.0, 0.0)));
    im_indentation_free(run);
    im_field_free(surface);
}

/* A 5 x 4 field with two patches, counted by hand:
 *   1 1 0 0 0
 *   0 1 0 1 0
 *   0 0 0 1 0
 *   0 0 0 0 0
 * patch A: 3 cells, 8 open edges; patch B: 2 cells, 6 open edges. */
static void contact_patches_by_hand(void **state)
{
    (void)state;
    im_field *f = NULL;
    assert_int_equal(im_field_create(5, 4, 0.5, &f), IM_OK);
    const int on[] = {0, 1, 6, 8, 13};
    for (int i = 0; i < 5; ++i)
        f->data[on[i]] = 1.0 + i;
    im_contact_patches p;
    long *sizes = NULL;
    assert_int_equal(im_measure_contact_patches(f, &p, &sizes), IM_OK);
    assert_int_equal(p.patches, 2);
    assert_int_equal(p.cells, 5);
    assert_int_equal(p.largest, 3);
    assert_int_equal(sizes[0], 3);
    assert_int_equal(sizes[1], 2);
    assert_true(p.perimeter == 14 * 0.5);
    assert_true(p.mean_area == 2.5 * 0.25);
    free(sizes);
    /* joining them through (2, 1) makes one patch of 6 cells; the new cell's two open edges replace
     * the two it closes, so the perimeter stays 14 */
    f->data[7] = 1.0;
    assert_int_equal(im_measure_contact_patches(f, &p, NULL), IM_OK);
    assert_int_equal(p.patches, 1);
    assert_int_equal(p.largest, 6);
    assert_true(p.perimeter == 14 * 0.5);
    long counts[4];
    /* as a gap field: -1 and thirteen zeros in the first bin, 1.0 in the third; 2, 3, 4, 5 and
     * +INFINITY not counted */
    f->data[0] = -1.0;
    f->data[19] = INFINITY;
    assert_int_equal(im_measure_gap_histogram(f, 2.0, 4, counts), IM_OK);
    assert_int_equal(counts[0], 14);
    assert_int_equal(counts[1], 0);
    assert_int_equal(counts[2], 1);
    assert_int_equal(counts[3], 0);
    assert_int_equal(im_measure_gap_histogram(f, 0.0, 4, counts), IM_EINVAL);
    im_field_free(f);
}

/* Planted discs on a 64 x 48 grid (delta 0.5): digital discs (cells within r of a centre cell) of
 * radius 1, 2, 3.5 and 6, far apart, and a 5 x 3 rectangle against the left border. A digital disc
 * is convex along rows and columns, so its perimeter is that of its bounding box: 2 (2 floor(r) + 1)
 * x 2 edges; its cells are sum over rows of 2 floor(sqrt(r^2 - dy^2)) + 1. Patches come in order of
 * their first cell (row by row). */
static int in_disc(int dx, int dy, double r) { return dx * dx + dy * dy <= r * r; }

static long disc_cells(double r)
{
    long cells = 0;
    for (int dy = -(int)r; dy <= (int)r; ++dy)
        cells += 2 * (long)floor(sqrt(r * r - dy * dy)) + 1;
    return cells;
}

static void planted_discs_are_measured_exactly(void **state)
{
    (void)state;
    enum { NX = 64, NY = 48 };
    const double radius[] = {1.0, 2.0, 3.5, 6.0};
    const int cx[] = {10, 30, 50, 30}, cy[] = {8, 6, 12, 30}; /* first cells' rows: 7, 4, 9, 24 */
    im_field *f = NULL;
    assert_int_equal(im_field_create(NX, NY, 0.5, &f), IM_OK);
    for (int k = 0; k < 4; ++k)
        for (int iy = 0; iy < NY; ++iy)
            for (int ix = 0; ix < NX; ++ix)
                if (in_disc(ix - cx[k], iy - cy[k], radius[k]))
                    f->data[iy * NX + ix] = 1.0;
    for (int iy = 40; iy < 43; ++iy) /* 5 x 3 rectangle at the left border, rows 40-42 */
        for (int ix = 0; ix < 5; ++ix)
            f->data[iy * NX + ix] = 2.0;
    im_patch *list = NULL;
    long count = 0;
    assert_int_equal(im_measure_patch_list(f, &list, &count), IM_OK);
    assert_int_equal(count, 5);
    const int order[] = {1, 0, 2, 3}; /* by first row: disc 2 (row 4), disc 1 (row 7), 3.5 (row 9), 6 */
    for (int k = 0; k < 4; ++k) {
        double r = radius[order[k]];
        assert_int_equal(list[k].cells, disc_cells(r));
        assert_int_equal(list[k].edges, 8 * (long)floor(r) + 4);
    }
    assert_int_equal(list[4].cells, 15);
    assert_int_equal(list[4].edges, 16); /* the border edges count */
    assert_int_equal(disc_cells(1.0), 5);
    assert_int_equal(disc_cells(2.0), 13);
    /* the histogram: 5 cells (bin 2), 13 and 15 (bin 3), 37 (bin 5), 113 (bin 6) */
    long patches[IM_PATCH_BINS], cells[IM_PATCH_BINS], edges[IM_PATCH_BINS];
    /* no contact: no list (im_measure_patch_list's NULL), an empty histogram (a step at load 0 failed here) */
    assert_int_equal(im_measure_patch_histogram(NULL, 0, patches, cells, edges), IM_OK);
    assert_int_equal(patches[0] + cells[IM_PATCH_BINS - 1] + edges[2], 0);
    assert_int_equal(im_measure_patch_histogram(list, count, patches, cells, edges), IM_OK);
    assert_int_equal(disc_cells(3.5), 37);
    assert_int_equal(disc_cells(6.0), 113);
    const long expected_patches[] = {0, 0, 1, 2, 0, 1, 1, 0};
    for (int b = 0; b < 8; ++b)
        assert_int_equal(patches[b], expected_patches[b]);
    assert_int_equal(cells[3], 13 + 15);
    assert_int_equal(edges[3], 8 * 2 + 4 + 16);
    /* the statistics agree with the list */
    im_contact_patches p;
    assert_int_equal(im_measure_contact_patches(f, &p, NULL), IM_OK);
    assert_int_equal(p.patches, 5);
    assert_int_equal(p.cells, 5 + 13 + 37 + 113 + 15);
    assert_true(p.perimeter == 0.5 * (12 + 20 + 28 + 52 + 16));
    free(list);
    im_field_free(f);
}

/* A rough cone indentation's fields: the patch histogram's counts add up to the patch count and
 * its cells to the contact's; the gap distribution's counts to the cells outside contact, and its
 * density integrates to the non-contact fraction. A flat punch's never-touched cells (gap +Inf)
 * are counted apart. */
static void distributions_add_up(void **state)
{
    (void)state;
    im_surface_params params = im_surface_params_default();
    params.nx = params.ny = 64;
    params.lambda_r = 64;
    params.lambda_0 = 64;
    params.seed = 3;
    params.target = IM_TARGET_SLOPE;
    params.slope_rms = 0.16;
    im_field *surface = NULL;
    assert_int_equal(im_surface_generate(&params, &surface), IM_OK);
    for (int shape = 0; shape < 2; ++shape) {
        im_indenter punch = shape == 0 ? im_indenter_cone(80.0) : im_indenter_flat(12.0);
        im_solver_options o = im_solver_options_default();
        im_indentation *run = NULL;
        assert_int_equal(im_indentation_create(surface, &punch, IM_CONTROL_LOAD, 100.0, &o, &run), IM_OK);
        im_step_result r;
        assert_int_equal(im_indentation_step(run, shape == 0 ? 60.0 : 20.0, &r), IM_OK);
        im_field *force = NULL, *gap = NULL;
        assert_int_equal(im_indentation_fields_full(run, &force, &gap, NULL), IM_OK);
        im_patch *list = NULL;
        long count = 0, patches[IM_PATCH_BINS], cells[IM_PATCH_BINS], edges[IM_PATCH_BINS];
        assert_int_equal(im_measure_patch_list(force, &list, &count), IM_OK);
        assert_int_equal(im_measure_patch_histogram(list, count, patches, cells, edges), IM_OK);
        im_contact_patches stats;
        assert_int_equal(im_measure_contact_patches(force, &stats, NULL), IM_OK);
        long patch_sum = 0, cell_sum = 0;
        for (int b = 0; b < IM_PATCH_BINS; ++b) {
            patch_sum += patches[b];
            cell_sum += cells[b];
        }
        if (count < 5)
            fail_msg("punch %d: %ld patches: expected several", shape, count);
        assert_int_equal(patch_sum, stats.patches);
        assert_int_equal(cell_sum, r.contact_patches);
        enum { BINS = 30 };
        long counts[BINS], infinite = 0;
        double width = 0.0, integral = 0.0, total = (double)im_field_count(gap);
        assert_int_equal(im_measure_gap_distribution(gap, force, 0.7, BINS, counts, &width, &infinite), IM_OK);
        long free_cells = infinite;
        for (int b = 0; b < BINS; ++b) {
            free_cells += counts[b];
            integral += counts[b] / (total * width) * width;
        }
        assert_int_equal(free_cells, (long)total - r.contact_patches);
        assert_true(shape == 0 ? infinite == 0 : infinite > 0);
        if (fabs(integral - (total - r.contact_patches - infinite) / total) > 1e-12)
            fail_msg("gap density integrates to %.15g", integral);
        free(list);
        im_field_free(force);
        im_field_free(gap);
        im_indentation_free(run);
    }
    im_field_free(surface);
}

/* A gap field made by hand: 0, 1, ..., 9 outside contact (scale 2: bins of width 4.5 / bins), the
 * contact's cells not counted whatever their gap, NaN outside contact refused. */
static void gap_distribution_by_hand(void **state)
{
    (void)state;
    im_field *gap = NULL, *force = NULL;
    assert_int_equal(im_field_create(4, 3, 1.0, &gap), IM_OK);
    assert_int_equal(im_field_create(4, 3, 1.0, &force), IM_OK);
    for (int i = 0; i < 10; ++i)
        gap->data[i] = i;
    gap->data[10] = gap->data[11] = 0.5;
    force->data[10] = force->data[11] = 1.0;
    long counts[3], infinite = -1;
    double width = 0.0;
    assert_int_equal(im_measure_gap_distribution(gap, force, 2.0, 3, counts, &width, &infinite), IM_OK);
    assert_true(width == 1.5);
    assert_int_equal(counts[0], 3); /* g / 2 in [0, 1.5): 0, 1, 2 */
    assert_int_equal(counts[1], 3); /* 3, 4, 5 */
    assert_int_equal(counts[2], 4); /* 6, 7, 8 and the largest, 9 */
    assert_int_equal(infinite, 0);
    gap->data[3] = NAN;
    assert_int_equal(im_measure_gap_distribution(gap, force, 2.0, 3, counts, &width, &infinite), IM_EINVAL);
    assert_int_equal(im_measure_gap_distribution(gap, force, 0.0, 3, counts, &width, &infinite), IM_EINVAL);
    im_field_free(gap);
    im_field_free(force);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(stiffness_of_closed_forms), cmocka_unit_test(sneddon_modulus_of_a_smooth_cone),
        cmocka_unit_test(contact_patches_by_hand),   cmocka_unit_test(planted_discs_are_measured_exactly),
        cmocka_unit_test(distributions_add_up),      cmocka_unit_test(gap_distribution_by_hand),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
