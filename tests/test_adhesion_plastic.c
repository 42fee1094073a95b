/* Adhesion with a hardness (solver.h, "Adhesion" and "Hardness"): the net pressure lies in [-sigma0, H_p],
 * the surface flattened where it reached H_p and remembering it across steps. Checked against the two limits
 * (a vanishing work gives the capped repulsive answers, a huge hardness the adhesive ones), the law's own
 * conditions on every patch, an elastic adhesive run on the flattened profile (the unloading and its
 * pull-off), and load control against displacement control's states. */
#include "support.h"

#include "indentmap/indenter.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A sphere of radius 64 patches (E* = 1) with w = 0.05 and delta_c = 0.6 (sigma0 = 0.083, Maugis's lambda
 * about 1), and a hardness below the elastic contact's peak pressure (0.11 at approach 2). */
static const double RADIUS = 64, WORK = 0.05, RANGE = 0.6, HARDNESS = 0.06, LARGEST = 2.5;
static const int SIDE = 64;

static im_solver_options sphere_options(double work, double hardness)
{
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-8;
    o.adhesion_work = work;
    o.adhesion_range = work > 0 ? RANGE : 0;
    o.hardness = hardness;
    return o;
}

/* A run of the sphere on `surface` (a flat one when NULL). */
static im_indentation *sphere_run(const im_field *surface, enum im_control control, double largest,
                                  const im_solver_options *o)
{
    im_field *flat = NULL;
    if (!surface) {
        assert_int_equal(im_field_create(SIDE, SIDE, 1.0, &flat), IM_OK);
        surface = flat;
    }
    im_indenter sphere = im_indenter_sphere(RADIUS);
    im_indentation *run = NULL;
    if (im_indentation_create(surface, &sphere, control, largest, o, &run) != IM_OK)
        fail_msg("im_indentation_create: %s", im_last_error());
    im_field_free(flat);
    return run;
}

static im_step_result step(im_indentation *run, double target)
{
    im_step_result r;
    if (im_indentation_step(run, target, &r) != IM_OK)
        fail_msg("step %g: %s", target, im_last_error());
    return r;
}

/* An approach into yielding, and back out past the pull-off. */
static const double HISTORY[] = {-0.5, 0.5, 1.0, 1.5, 2.0, 1.5, 1.0, 0.5, 0.0, -0.3, -0.6, -0.9, -1.2};
enum { HISTORY_STEPS = sizeof HISTORY / sizeof HISTORY[0] };

/* A vanishing work of adhesion gives the capped repulsive answers on a rough surface under a cone, loading and
 * unloading: the same loads to 1e-8, contact, yielded patches and plastic depth. */
static void vanishing_work_gives_the_capped_answers(void **state)
{
    (void)state;
    im_field *surface = test_rough_surface(64, 0.08, 3);
    im_indenter cone = im_indenter_cone(80.0);
    im_solver_options plain = im_solver_options_default(), sticky;
    plain.tol = 1e-10;
    plain.hardness = 0.1;
    sticky = plain;
    sticky.adhesion_work = 1e-16;
    sticky.adhesion_range = 1e-6;
    im_indentation *a = NULL, *b = NULL;
    assert_int_equal(im_indentation_create(surface, &cone, IM_CONTROL_DISPLACEMENT, 4, &plain, &a), IM_OK);
    assert_int_equal(im_indentation_create(surface, &cone, IM_CONTROL_DISPLACEMENT, 4, &sticky, &b), IM_OK);
    const double approaches[] = {1, 2, 3, 4, 3, 2, 1};
    long yielded = 0;
    for (size_t k = 0; k < sizeof approaches / sizeof approaches[0]; ++k) {
        const im_step_result ra = step(a, approaches[k]), rb = step(b, approaches[k]);
        if (!(test_relative_difference(ra.load, rb.load) <= 1e-8 && ra.contact_patches == rb.contact_patches &&
              ra.yielding_patches == rb.yielding_patches &&
              test_relative_difference(ra.plastic_depth, rb.plastic_depth) <= 1e-8))
            fail_msg("w = %g: load %.17g against %.17g, contact %ld against %ld, yielded %ld against %ld, plastic "
                     "depth %.17g against %.17g",
                     approaches[k], rb.load, ra.load, rb.contact_patches, ra.contact_patches, rb.yielding_patches,
                     ra.yielding_patches, rb.plastic_depth, ra.plastic_depth);
        yielded += ra.yielding_patches;
    }
    assert_true(yielded > 0);
    im_indentation_free(a);
    im_indentation_free(b);
    im_field_free(surface);
}

/* A hardness far above every pressure gives the adhesive answers along the history, pull-off included. */
static void huge_hardness_gives_the_adhesive_answers(void **state)
{
    (void)state;
    const im_solver_options elastic = sphere_options(WORK, 0), capped = sphere_options(WORK, 1e6);
    im_indentation *a = sphere_run(NULL, IM_CONTROL_DISPLACEMENT, LARGEST, &elastic);
    im_indentation *b = sphere_run(NULL, IM_CONTROL_DISPLACEMENT, LARGEST, &capped);
    const double unit = M_PI * WORK * RADIUS;
    for (int k = 0; k < HISTORY_STEPS; ++k) {
        const im_step_result ra = step(a, HISTORY[k]), rb = step(b, HISTORY[k]);
        if (!(fabs(ra.load - rb.load) <= 1e-6 * unit && ra.contact_patches == rb.contact_patches &&
              rb.yielding_patches == 0 && rb.plastic_depth == 0))
            fail_msg("w = %g: load %.17g against %.17g, contact %ld against %ld, %ld yielded", HISTORY[k], rb.load,
                     ra.load, rb.contact_patches, ra.contact_patches, rb.yielding_patches);
    }
    im_indentation_free(a);
    im_indentation_free(b);
}

/* The largest and least gap over patch i of the full grid and its four neighbours. */
static void gap_spread(const im_field *gap, int x, int y, double *least, double *largest)
{
    static const int dx[] = {0, 1, -1, 0, 0}, dy[] = {0, 0, 0, 1, -1};
    *least = INFINITY;
    *largest = -INFINITY;
    for (int k = 0; k < 5; ++k) {
        const int nx = x + dx[k], ny = y + dy[k];
        if (nx < 0 || ny < 0 || nx >= gap->nx || ny >= gap->ny)
            continue;
        *least = fmin(*least, gap->data[(size_t)ny * gap->nx + nx]);
        *largest = fmax(*largest, gap->data[(size_t)ny * gap->nx + nx]);
    }
}

/* Whether net pressure p at a patch of gap g (gaps from least to largest around it) obeys the law with the cap:
 * -sigma0 <= p <= H_p; a patch off contact carries no compression; one wholly beyond delta_c nothing, one wholly
 * inside the zone and off contact exactly -sigma0; a patch that carries more than -sigma0 is in contact. */
static int obeys_the_law(double p, double g, double least, double largest, double gap_tol)
{
    const double sigma0 = WORK / RANGE, rounding = 1e-12;
    if (!(p >= -sigma0 * (1 + rounding) && p <= HARDNESS * (1 + rounding)))
        return 0;
    if (least > RANGE)
        return p == 0;
    if (g > gap_tol && largest < RANGE)
        return fabs(p + sigma0) <= rounding * sigma0;
    if (p > -sigma0 * (1 - rounding))
        return fabs(g) <= gap_tol || p <= 0;
    return 1;
}

/* At every step of a history (the targets), every patch obeys the law with the cap (obeys_the_law); the patches
 * at H_p are the step's yielded ones, in contact, the load is the force field's sum, and somewhere both bounds
 * are met. */
static void history_obeys_the_capped_law(im_indentation *run, const double *targets, double tol)
{
    long capped_steps = 0, pulled_steps = 0;
    double worst_gap = 0;
    for (int k = 0; k < HISTORY_STEPS; ++k) {
        const im_step_result r = step(run, targets[k]);
        im_field *force = NULL, *gap = NULL;
        assert_int_equal(im_indentation_fields(run, &force, &gap, NULL), IM_OK);
        const double gap_tol = 10 * tol * fmax(fabs(r.approach), RANGE);
        long at_cap = 0, at_tension = 0;
        double sum = 0;
        for (int y = 0; y < SIDE; ++y)
            for (int x = 0; x < SIDE; ++x) {
                const size_t i = (size_t)y * SIDE + x;
                const double p = force->data[i], g = gap->data[i];
                double least, largest;
                gap_spread(gap, x, y, &least, &largest);
                if (!obeys_the_law(p, g, least, largest, gap_tol))
                    fail_msg("step to %g, patch (%d, %d): p = %.17g at g = %.17g (neighbours %g to %g)", targets[k],
                             x, y, p, g, least, largest);
                at_cap += p >= HARDNESS * (1 - 1e-12);
                at_tension += p == -WORK / RANGE;
                worst_gap = p > 0 ? fmax(worst_gap, fabs(g)) : worst_gap;
                sum += p;
            }
        assert_int_equal(at_cap, r.yielding_patches);
        assert_close(sum, r.load, 1e-10 * M_PI * WORK * RADIUS);
        capped_steps += at_cap > 0;
        pulled_steps += at_tension > 0;
        im_field_free(force);
        im_field_free(gap);
    }
    print_message("largest |gap| under compression %.3g\n", worst_gap);
    assert_true(capped_steps >= 2 && pulled_steps >= 8);
}

static void every_patch_obeys_the_capped_law(void **state)
{
    (void)state;
    const im_solver_options o = sphere_options(WORK, HARDNESS);
    im_indentation *run = sphere_run(NULL, IM_CONTROL_DISPLACEMENT, LARGEST, &o);
    history_obeys_the_capped_law(run, HISTORY, o.tol);
    im_indentation_free(run);
}

/* After yielding, the unloading and the pull-off are an elastic adhesive contact's on the flattened profile:
 * the same sphere, no hardness, on a surface lowered by the plastic depth (its first touch shifted by the
 * residual approach), approached to the largest approach and retracted along the same steps gives the same
 * loads. No patch yields on the way back (the plastic depth stays), and the flattened contact pulls off harder
 * than the unflattened one. */
static void unloading_keeps_the_flattening(void **state)
{
    (void)state;
    const im_solver_options yielding = sphere_options(WORK, HARDNESS), elastic = sphere_options(WORK, 0);
    im_indentation *capped = sphere_run(NULL, IM_CONTROL_DISPLACEMENT, LARGEST, &yielding);
    im_indentation *unflattened = sphere_run(NULL, IM_CONTROL_DISPLACEMENT, LARGEST, &elastic);
    int top = 0;
    while (HISTORY[top + 1] > HISTORY[top])
        step(capped, HISTORY[top++]);
    const im_step_result deepest = step(capped, HISTORY[top]);
    im_field *plastic = NULL;
    assert_int_equal(im_indentation_plastic(capped, &plastic), IM_OK);
    for (size_t i = 0; i < im_field_count(plastic); ++i)
        plastic->data[i] = -plastic->data[i];
    im_indentation *flattened = sphere_run(plastic, IM_CONTROL_DISPLACEMENT, LARGEST, &elastic);
    const double shift = deepest.residual_approach;
    assert_true(deepest.plastic_depth > 0.05 && shift > 0);
    step(flattened, HISTORY[top] - shift);
    const double unit = M_PI * WORK * RADIUS;
    double least_capped = 0, least_flattened = 0, least_unflattened = 0;
    for (int k = 0; k < HISTORY_STEPS; ++k) {
        const double w = HISTORY[k];
        least_unflattened = fmin(least_unflattened, step(unflattened, w).load);
        if (k <= top)
            continue;
        const im_step_result a = step(capped, w), b = step(flattened, w - shift);
        if (!(fabs(a.load - b.load) <= 1e-6 * unit && a.contact_patches == b.contact_patches &&
              a.plastic_depth == deepest.plastic_depth))
            fail_msg("w = %g: load %.17g against the flattened profile's %.17g, contact %ld against %ld, plastic "
                     "depth %.17g (was %.17g)",
                     w, a.load, b.load, a.contact_patches, b.contact_patches, a.plastic_depth, deepest.plastic_depth);
        least_capped = fmin(least_capped, a.load);
        least_flattened = fmin(least_flattened, b.load);
    }
    print_message("pull-off %.6f (flattened profile %.6f, unflattened sphere %.6f) pi w R; residual depth %.4f\n",
                  -least_capped / unit, -least_flattened / unit, -least_unflattened / unit, deepest.plastic_depth);
    assert_true(least_capped < least_unflattened - 0.01 * unit);
    im_field_free(plastic);
    im_indentation_free(capped);
    im_indentation_free(flattened);
    im_indentation_free(unflattened);
}

/* Under load control the yielding, adhesive sphere holds the loads displacement control found, at its approaches
 * and with its contact and plastic depth, loading and unloading into tension. */
static void load_control_holds_the_displacement_states(void **state)
{
    (void)state;
    const im_solver_options o = sphere_options(WORK, HARDNESS);
    im_indentation *by_approach = sphere_run(NULL, IM_CONTROL_DISPLACEMENT, LARGEST, &o);
    const double approaches[] = {1.5, 2.0, 1.5, 1.0, 0.5, 0.0};
    enum { COUNT = sizeof approaches / sizeof approaches[0] };
    im_step_result expected[COUNT];
    double largest = 0;
    for (int k = 0; k < COUNT; ++k) {
        expected[k] = step(by_approach, approaches[k]);
        largest = fmax(largest, fabs(expected[k].load));
    }
    assert_true(expected[0].load > 0 && expected[COUNT - 1].load < 0); /* from no contact, a load walks forward */
    im_indentation *by_load = sphere_run(NULL, IM_CONTROL_LOAD, largest, &o);
    double worst = 0;
    for (int k = 0; k < COUNT; ++k) {
        const im_step_result r = step(by_load, expected[k].load);
        /* the search ends within tol of the load or of the approach (of delta_c near 0), each solve exact to tol */
        const int held = fabs(r.load - expected[k].load) <= 2e-8 * largest ||
                         fabs(r.approach - approaches[k]) <= 5e-8 * fmax(fabs(approaches[k]), RANGE);
        if (!(held && r.contact_patches == expected[k].contact_patches &&
              test_relative_difference(r.plastic_depth, expected[k].plastic_depth) <= 1e-6))
            fail_msg("load %.17g: approach %.17g (expected %g), contact %ld (%ld), plastic depth %.17g (%.17g)",
                     expected[k].load, r.approach, approaches[k], r.contact_patches, expected[k].contact_patches,
                     r.plastic_depth, expected[k].plastic_depth);
        worst = fmax(worst, fabs(r.approach - approaches[k]));
    }
    print_message("load control: approaches within %.2g of displacement control's\n", worst);
    im_indentation_free(by_approach);
    im_indentation_free(by_load);
}

/* ---- a periodic cell under mean-gap control ---- */

/* The undeformed mean gap of a periodic run (mean g0: at a mean gap of 100 the flat is clear, at the approach
 * mean g0 - 100). */
static double undeformed_mean_gap(const im_field *surface, const im_indenter *punch)
{
    im_solver_options o = im_solver_options_default();
    o.periodic = 1;
    im_indentation *run = NULL;
    assert_int_equal(im_indentation_create(surface, punch, IM_CONTROL_MEAN_GAP, 100, &o, &run), IM_OK);
    const double mean_gap0 = step(run, 100).approach + 100;
    im_indentation_free(run);
    return mean_gap0;
}

/* The sphere repeated with a SIDE^2 cell (its contact at the deepest approach about 20 patches across) under
 * mean-gap control, or load control up to largest_load, and the mean gaps of HISTORY's approaches before any
 * yielding (mean g0 - w). */
static im_indentation *cell_sphere_run(const im_solver_options *elastic, double hardness, enum im_control control,
                                       double largest_load, double *mean_gaps)
{
    im_field *flat = NULL;
    assert_int_equal(im_field_create(SIDE, SIDE, 1.0, &flat), IM_OK);
    const im_indenter sphere = im_indenter_sphere(RADIUS);
    const double mean_gap0 = undeformed_mean_gap(flat, &sphere);
    for (int k = 0; k < HISTORY_STEPS; ++k)
        mean_gaps[k] = mean_gap0 - HISTORY[k];
    im_solver_options o = *elastic;
    o.periodic = 1;
    o.hardness = hardness;
    im_indentation *run = NULL;
    const double largest = control == IM_CONTROL_MEAN_GAP ? mean_gap0 + LARGEST : largest_load;
    if (im_indentation_create(flat, &sphere, control, largest, &o, &run) != IM_OK)
        fail_msg("im_indentation_create: %s", im_last_error());
    im_field_free(flat);
    return run;
}

/* On the cell too a vanishing work gives the capped repulsive answers, on a rough cell under the rigid flat:
 * mean gaps falling into yielding and rising again, the same loads to 1e-8, contact, yielded patches and plastic
 * depth. */
static void cell_vanishing_work_gives_the_capped_answers(void **state)
{
    (void)state;
    im_field *surface = test_rough_surface(SIDE, 0.08, 3);
    const im_indenter flat = im_indenter_flat(4.0 * SIDE);
    const double mean_gap0 = undeformed_mean_gap(surface, &flat), parts[] = {0.5, 0.3, 0.2, 0.3, 0.5};
    im_solver_options plain = im_solver_options_default(), sticky;
    plain.tol = 1e-10;
    plain.periodic = 1;
    plain.hardness = 0.05;
    sticky = plain;
    sticky.adhesion_work = 1e-16;
    sticky.adhesion_range = 1e-6;
    im_indentation *a = NULL, *b = NULL;
    assert_int_equal(im_indentation_create(surface, &flat, IM_CONTROL_MEAN_GAP, mean_gap0, &plain, &a), IM_OK);
    assert_int_equal(im_indentation_create(surface, &flat, IM_CONTROL_MEAN_GAP, mean_gap0, &sticky, &b), IM_OK);
    long yielded = 0;
    for (size_t k = 0; k < sizeof parts / sizeof parts[0]; ++k) {
        const double gap = parts[k] * mean_gap0;
        const im_step_result ra = step(a, gap), rb = step(b, gap);
        if (!(test_relative_difference(ra.load, rb.load) <= 1e-8 && ra.contact_patches == rb.contact_patches &&
              ra.yielding_patches == rb.yielding_patches &&
              test_relative_difference(ra.plastic_depth, rb.plastic_depth) <= 1e-8 &&
              fabs(rb.mean_gap - gap) <= 1e-8 * gap))
            fail_msg("mean gap %g: load %.17g against %.17g, contact %ld against %ld, yielded %ld against %ld, "
                     "plastic depth %.17g against %.17g, mean gap %.17g",
                     gap, rb.load, ra.load, rb.contact_patches, ra.contact_patches, rb.yielding_patches,
                     ra.yielding_patches, rb.plastic_depth, ra.plastic_depth, rb.mean_gap);
        yielded += ra.yielding_patches;
    }
    assert_true(yielded > 0);
    im_indentation_free(a);
    im_indentation_free(b);
    im_field_free(surface);
}

/* On the cell a hardness far above every pressure gives the adhesive answers along the history. */
static void cell_huge_hardness_gives_the_adhesive_answers(void **state)
{
    (void)state;
    const im_solver_options o = sphere_options(WORK, 0);
    double gaps[HISTORY_STEPS];
    im_indentation *a = cell_sphere_run(&o, 0, IM_CONTROL_MEAN_GAP, 0, gaps);
    im_indentation *b = cell_sphere_run(&o, 1e6, IM_CONTROL_MEAN_GAP, 0, gaps);
    const double unit = M_PI * WORK * RADIUS;
    for (int k = 0; k < HISTORY_STEPS; ++k) {
        const im_step_result ra = step(a, gaps[k]), rb = step(b, gaps[k]);
        if (!(fabs(ra.load - rb.load) <= 1e-6 * unit && ra.contact_patches == rb.contact_patches &&
              rb.yielding_patches == 0 && rb.plastic_depth == 0))
            fail_msg("mean gap %g: load %.17g against %.17g, contact %ld against %ld, %ld yielded", gaps[k], rb.load,
                     ra.load, rb.contact_patches, ra.contact_patches, rb.yielding_patches);
    }
    im_indentation_free(a);
    im_indentation_free(b);
}

/* On the cell, at every step of the history's mean gaps, every patch obeys the law with the cap. */
static void cell_every_patch_obeys_the_capped_law(void **state)
{
    (void)state;
    const im_solver_options o = sphere_options(WORK, 0);
    double gaps[HISTORY_STEPS];
    im_indentation *run = cell_sphere_run(&o, HARDNESS, IM_CONTROL_MEAN_GAP, 0, gaps);
    history_obeys_the_capped_law(run, gaps, o.tol);
    im_indentation_free(run);
}

/* Under load control the yielding, adhesive cell holds the loads mean-gap control found (HISTORY's approaches
 * 1.5, 2, 1.5, 1: loading into yielding and unloading) at its mean gaps, with its contact and plastic depth.
 * Further out the states part with the path: at approach 0.5 (load -34.73) mean-gap control's one step from 1
 * leaves 325 patches in contact, the walk's steps of delta_c / 8 meet that load at 0.64 with 393. */
static void cell_load_control_holds_the_mean_gap_states(void **state)
{
    (void)state;
    const im_solver_options o = sphere_options(WORK, 0);
    enum { FIRST = 3, COUNT = 4 };
    double gaps[HISTORY_STEPS];
    im_indentation *by_gap = cell_sphere_run(&o, HARDNESS, IM_CONTROL_MEAN_GAP, 0, gaps);
    im_step_result expected[COUNT];
    double largest = 0;
    for (int k = 0; k < COUNT; ++k) {
        expected[k] = step(by_gap, gaps[FIRST + k]);
        largest = fmax(largest, fabs(expected[k].load));
    }
    assert_true(expected[1].yielding_patches > 0 && expected[COUNT - 1].yielding_patches == 0);
    im_indentation *by_load = cell_sphere_run(&o, HARDNESS, IM_CONTROL_LOAD, largest, gaps);
    double worst = 0;
    for (int k = 0; k < COUNT; ++k) {
        const im_step_result r = step(by_load, expected[k].load);
        /* as on the half-space: within tol of the load or of the approach (of delta_c near 0) */
        const int held = fabs(r.load - expected[k].load) <= 2e-8 * largest ||
                         fabs(r.mean_gap - expected[k].mean_gap) <= 5e-8 * fmax(fabs(r.approach), RANGE);
        if (!(held && r.contact_patches == expected[k].contact_patches &&
              test_relative_difference(r.plastic_depth, expected[k].plastic_depth) <= 1e-6))
            fail_msg("load %.17g: mean gap %.17g (expected %.17g), contact %ld (%ld), plastic depth %.17g (%.17g)",
                     expected[k].load, r.mean_gap, expected[k].mean_gap, r.contact_patches,
                     expected[k].contact_patches, r.plastic_depth, expected[k].plastic_depth);
        worst = fmax(worst, fabs(r.mean_gap - expected[k].mean_gap));
    }
    print_message("load control on the cell: mean gaps within %.2g of mean-gap control's\n", worst);
    im_indentation_free(by_gap);
    im_indentation_free(by_load);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(vanishing_work_gives_the_capped_answers),
        cmocka_unit_test(huge_hardness_gives_the_adhesive_answers),
        cmocka_unit_test(every_patch_obeys_the_capped_law),
        cmocka_unit_test(unloading_keeps_the_flattening),
        cmocka_unit_test(load_control_holds_the_displacement_states),
        cmocka_unit_test(cell_vanishing_work_gives_the_capped_answers),
        cmocka_unit_test(cell_huge_hardness_gives_the_adhesive_answers),
        cmocka_unit_test(cell_every_patch_obeys_the_capped_law),
        cmocka_unit_test(cell_load_control_holds_the_mean_gap_states),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
