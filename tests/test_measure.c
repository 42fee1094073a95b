/* What an indentation experiment measures: the contact stiffness against Love's and Hertz's
 * closed forms, Sneddon's modulus of a simulated smooth cone against the true E*, contact patches
 * and gaps of hand-made fields. */
#include "support.h"

#include "indentmap/indenter.h"
#include "indentmap/measure.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"

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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(stiffness_of_closed_forms),
        cmocka_unit_test(sneddon_modulus_of_a_smooth_cone),
        cmocka_unit_test(contact_patches_by_hand),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
