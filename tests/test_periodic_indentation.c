/* Periodic contact as an indentation (solver.h, "Periodic mode"; options.periodic in
 * im_indentation_create): a rigid flat on a rough cell is im_flat_contact bit for bit; a cone repeated
 * with a cell much larger than its contact carries the half-space cone's contact; the hardness's
 * memory holds in a periodic cell; mean-gap and displacement control reach load control's states. */
#include "support.h"

#include "indentmap/solver.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static im_indentation *periodic_run_under(const im_field *surface, const im_indenter *punch, enum im_control control,
                                          double largest, double hardness)
{
    im_solver_options o = im_solver_options_default();
    o.periodic = 1;
    o.tol = 1e-10;
    o.hardness = hardness;
    im_indentation *run = NULL;
    if (im_indentation_create(surface, punch, control, largest, &o, &run) != IM_OK)
        fail_msg("periodic indentation: %s", im_last_error());
    return run;
}

static im_indentation *periodic_run(const im_field *surface, const im_indenter *punch, double largest,
                                    double hardness)
{
    return periodic_run_under(surface, punch, IM_CONTROL_LOAD, largest, hardness);
}

static im_step_result step(im_indentation *run, double load)
{
    im_step_result r;
    if (im_indentation_step(run, load, &r) != IM_OK)
        fail_msg("load %g: %s", load, im_last_error());
    return r;
}

/* A flat punch wider than the cell's diagonal is the rigid flat (g0 = max h - h): the same solves as
 * im_flat_contact at the same mean pressures, to the bit; area_ratio is A / A0; no N*. */
static void rigid_flat_is_flat_contact(void **state)
{
    (void)state;
    enum { N = 128 };
    im_field *s = test_rough_surface(N, 0.08, 2);
    im_indenter flat = im_indenter_flat(2.0 * N);
    const double pressures[] = {0.002, 0.01, 0.004}, cell = (double)N * N;
    im_indentation *run = periodic_run(s, &flat, 0.01 * cell, 0);
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-10;
    im_flat_contact *reference = NULL;
    assert_int_equal(im_flat_contact_create(s, &o, &reference), IM_OK);
    for (int k = 0; k < 3; ++k) {
        im_step_result r = step(run, pressures[k] * cell);
        im_flat_result f;
        assert_int_equal(im_flat_contact_solve(reference, pressures[k], &f), IM_OK);
        assert_int_equal(r.contact_patches, f.contact_patches);
        assert_true(r.load == pressures[k] * cell || test_relative_difference(r.load, pressures[k] * cell) < 1e-14);
        assert_true(r.area_ratio == (double)r.contact_patches / cell);
        assert_true(isnan(r.load_star));
        im_field *force = NULL;
        assert_int_equal(im_indentation_fields_full(run, &force, NULL, NULL), IM_OK);
        if (memcmp(force->data, im_flat_contact_pressure(reference), sizeof(double) * N * N) != 0)
            fail_msg("mean pressure %g: the periodic indentation's forces differ from im_flat_contact's",
                     pressures[k]);
        im_field_free(force);
    }
    im_flat_contact_free(reference);
    im_indentation_free(run);
    im_field_free(s);
}

/* An 80 degree cone repeated with a 512^2 cell, its contact about 54 patches across: the contact
 * patches of the half-space's cone at the same load to 1% (measured: equal, 2297). The two kernels
 * differ near a patch (the periodic one is the sampled spectrum 2 / (E* |q|), the half-space's Love's
 * patch integral): a contact 17 patches across (256^2, N = 20) has 3.4% more patches periodic. */
static void repeated_cone_is_the_half_spaces(void **state)
{
    (void)state;
    enum { N = 512 };
    im_field *smooth = NULL;
    assert_int_equal(im_field_create(N, N, 1.0, &smooth), IM_OK);
    im_indenter cone = im_indenter_cone(80);
    const double load = 200.0;
    im_indentation *periodic = periodic_run(smooth, &cone, load, 0);
    im_step_result p = step(periodic, load);
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-10;
    im_indentation *half_space = NULL;
    assert_int_equal(im_indentation_create(smooth, &cone, IM_CONTROL_LOAD, load, &o, &half_space), IM_OK);
    im_step_result h = step(half_space, load);
    print_message("cone at N = %g: n_p %ld periodic, %ld half-space\n", load, p.contact_patches, h.contact_patches);
    if (test_relative_difference((double)p.contact_patches, (double)h.contact_patches) > 0.01)
        fail_msg("n_p %ld periodic, %ld half-space", p.contact_patches, h.contact_patches);
    im_indentation_free(periodic);
    im_indentation_free(half_space);
    im_field_free(smooth);
}

/* A rough cell under a rigid flat at a hardness: loading flows, unloading does not, and the mean
 * pressure the cell carried is kept in its plastic depth; reloading retraces unloading. */
static void periodic_memory(void **state)
{
    (void)state;
    enum { N = 64 };
    im_field *s = test_rough_surface(N, 0.08, 4);
    im_indenter flat = im_indenter_flat(2.0 * N);
    const double cell = (double)N * N, hardness = 0.1;
    im_indentation *run = periodic_run(s, &flat, 0.02 * cell, hardness);
    step(run, 0.01 * cell);
    im_step_result top = step(run, 0.02 * cell);
    assert_true(top.plastic_work > 0 && top.yielding_patches > 0);
    im_step_result down = step(run, 0.01 * cell);
    assert_true(down.plastic_work == top.plastic_work && down.yielding_patches == 0);
    im_step_result again = step(run, 0.02 * cell);
    assert_true(again.plastic_work == top.plastic_work ||
                test_relative_difference(again.plastic_work, top.plastic_work) < 1e-9);
    if (test_relative_difference(again.approach, top.approach) > 1e-8)
        fail_msg("reload to the top: w = %.12g, loading gave %.12g", again.approach, top.approach);
    im_indentation_free(run);
    im_field_free(s);
}

/* One spike on a flat cell, a rigid flat, a cap: the local start puts the whole load on the spike, which
 * the cap clips to H_p, and no patch is left elastic. The load control must not accept the capped
 * spike's load as the answer (it did, once it kept its approach: N = 0.1 for a load of 0.5); with no
 * patch that can join or unload it says so. */
static void capped_spike_is_not_an_answer(void **state)
{
    (void)state;
    enum { N = 32 };
    im_field *s = NULL;
    assert_int_equal(im_field_create(N, N, 1.0, &s), IM_OK);
    s->data[(N / 2) * N + N / 2] = 1.0;
    im_indenter flat = im_indenter_flat(2.0 * N);
    im_indentation *run = periodic_run(s, &flat, 0.5, 0.1);
    im_step_result r;
    int status = im_indentation_step(run, 0.5, &r);
    if (status == IM_OK && test_relative_difference(r.load, 0.5) > 1e-6)
        fail_msg("load control answered N = %.9g for the load 0.5", r.load);
    if (status != IM_OK)
        assert_non_null(strstr(im_last_error(), "every patch in contact is at the hardness cap"));
    im_indentation_free(run);
    im_field_free(s);
}

/* A rigid flat on the cell (a flat punch wider than its diagonal) under mean-gap control. */
static im_indentation *mean_gap_run(const im_field *surface, double largest, double hardness)
{
    im_indenter flat = im_indenter_flat(2.0 * surface->nx);
    return periodic_run_under(surface, &flat, IM_CONTROL_MEAN_GAP, largest, hardness);
}

/* Mean-gap control and load control describe one state: a rough cell pressed to the mean gaps that
 * load control reports carries those loads on the same patches; the mean gap reported is the one
 * imposed, and an approach imposed (displacement control) is the same state again. */
static void mean_gap_is_load_control(void **state)
{
    (void)state;
    enum { N = 128 };
    im_field *s = test_rough_surface(N, 0.08, 2);
    im_indenter flat = im_indenter_flat(2.0 * N);
    const double pressures[] = {0.002, 0.01, 0.004}, cell = (double)N * N;
    im_indentation *by_load = periodic_run(s, &flat, 0.01 * cell, 0), *by_gap = mean_gap_run(s, 10.0, 0),
                   *by_approach = periodic_run_under(s, &flat, IM_CONTROL_DISPLACEMENT, 10.0, 0);
    for (int k = 0; k < 3; ++k) {
        im_step_result l = step(by_load, pressures[k] * cell), g = step(by_gap, l.mean_gap),
                       w = step(by_approach, l.approach);
        if (test_relative_difference(g.load, l.load) > 1e-8 || test_relative_difference(w.load, l.load) > 1e-8)
            fail_msg("p_m %g: load %.17g under load control, %.17g at its mean gap, %.17g at its approach",
                     pressures[k], l.load, g.load, w.load);
        assert_int_equal(g.contact_patches, l.contact_patches);
        assert_int_equal(w.contact_patches, l.contact_patches);
        if (fabs(g.mean_gap - l.mean_gap) > 1e-9 * l.mean_gap)
            fail_msg("mean gap %.17g imposed, %.17g reported", l.mean_gap, g.mean_gap);
    }
    im_indentation_free(by_load);
    im_indentation_free(by_gap);
    im_indentation_free(by_approach);
    im_field_free(s);
}

/* With a hardness the yielded patches' overlap is plastic flattening, not gap: the approach is searched
 * until the mean of max(g, 0) is the one imposed. Load control at the loads it found reaches the same
 * states (the mean gaps again); unloading is elastic, reloading retraces it. */
static void mean_gap_with_memory(void **state)
{
    (void)state;
    enum { N = 64 };
    im_field *s = test_rough_surface(N, 0.08, 4);
    im_indenter flat = im_indenter_flat(2.0 * N);
    const double cell = (double)N * N, hardness = 0.05, gaps[] = {0.4, 0.2, 0.4, 0.2};
    im_indentation *by_gap = mean_gap_run(s, 1.0, hardness), *by_load = periodic_run(s, &flat, 0.5 * cell, hardness);
    im_step_result g[4];
    for (int k = 0; k < 4; ++k) {
        g[k] = step(by_gap, gaps[k]);
        if (fabs(g[k].mean_gap - gaps[k]) > 1e-10 * gaps[k])
            fail_msg("step %d: mean gap %.17g imposed, %.17g reached", k + 1, gaps[k], g[k].mean_gap);
    }
    assert_true(g[0].yielding_patches > 0 && g[1].plastic_work > g[0].plastic_work);
    assert_true(g[2].plastic_work == g[1].plastic_work && g[2].yielding_patches == 0);
    if (test_relative_difference(g[3].load, g[1].load) > 1e-8)
        fail_msg("reload to the smaller gap: N = %.12g, loading gave %.12g", g[3].load, g[1].load);
    for (int k = 0; k < 2; ++k) {
        im_step_result l = step(by_load, g[k].load);
        if (fabs(l.mean_gap - gaps[k]) > 1e-7 * gaps[k])
            fail_msg("load %.12g: mean gap %.12g under load control, %.12g imposed", g[k].load, l.mean_gap, gaps[k]);
    }
    im_indentation_free(by_gap);
    im_indentation_free(by_load);
    im_field_free(s);
}

/* A mean gap above the undeformed cell's: the flat does not reach the surface. */
static void mean_gap_clear_of_the_surface(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(32, 0.08, 1);
    im_indentation *run = mean_gap_run(s, 100.0, 0);
    im_step_result r = step(run, 100.0);
    assert_true(r.load == 0 && r.contact_patches == 0 && r.approach < 0);
    assert_true(fabs(r.mean_gap - 100.0) < 1e-12 * 100.0);
    im_indentation_free(run);
    im_field_free(s);
}

static void mean_gap_refusals(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(32, 0.08, 1);
    im_indenter flat = im_indenter_flat(64), cone = im_indenter_cone(80.0);
    im_solver_options o = im_solver_options_default();
    im_indentation *run = NULL;
    assert_int_equal(im_indentation_create(s, &cone, IM_CONTROL_MEAN_GAP, 1.0, &o, &run), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "expected a periodic cell"));
    assert_null(run);
    o.periodic = 1;
    o.adhesion_work = 0.01;
    o.adhesion_range = 0.1;
    /* adhesion on a cell holds its mean gap or its load (test_adhesion, test_adhesion_cell), not an approach */
    assert_int_equal(im_indentation_create(s, &flat, IM_CONTROL_DISPLACEMENT, 1.0, &o, &run), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "expected mean-gap or load control on a periodic cell"));
    assert_non_null(strstr(im_last_error(), "adhesion under approach control"));
    run = mean_gap_run(s, 1.0, 0);
    im_step_result r;
    assert_int_equal(im_indentation_step(run, 0.0, &r), IM_EINVAL);
    assert_int_equal(im_indentation_step(run, 1.5, &r), IM_EINVAL);
    im_indentation_free(run);
    /* the half-space has no mean gap */
    o = im_solver_options_default();
    assert_int_equal(im_indentation_create(s, &cone, IM_CONTROL_DISPLACEMENT, 1.0, &o, &run), IM_OK);
    r = step(run, 0.5);
    assert_true(isnan(r.mean_gap));
    im_indentation_free(run);
    im_field_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(rigid_flat_is_flat_contact),
        cmocka_unit_test(repeated_cone_is_the_half_spaces),
        cmocka_unit_test(periodic_memory),
        cmocka_unit_test(capped_spike_is_not_an_answer),
        cmocka_unit_test(mean_gap_is_load_control),
        cmocka_unit_test(mean_gap_with_memory),
        cmocka_unit_test(mean_gap_clear_of_the_surface),
        cmocka_unit_test(mean_gap_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
