/* Periodic contact as an indentation (solver.h, "Periodic mode"; options.periodic in
 * im_indentation_create): a rigid flat on a rough cell is im_flat_contact bit for bit; a cone repeated
 * with a cell much larger than its contact carries the half-space cone's contact; the hardness's
 * memory holds in a periodic cell; displacement control is refused. */
#include "support.h"

#include "indentmap/solver.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static im_indentation *periodic_run(const im_field *surface, const im_indenter *punch, double largest,
                                    double hardness)
{
    im_solver_options o = im_solver_options_default();
    o.periodic = 1;
    o.tol = 1e-10;
    o.hardness = hardness;
    im_indentation *run = NULL;
    if (im_indentation_create(surface, punch, IM_CONTROL_LOAD, largest, &o, &run) != IM_OK)
        fail_msg("periodic indentation: %s", im_last_error());
    return run;
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
    assert_true(again.plastic_work == top.plastic_work || test_relative_difference(again.plastic_work,
                                                                                   top.plastic_work) < 1e-9);
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

static void displacement_control_is_refused(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(32, 0.08, 1);
    im_indenter flat = im_indenter_flat(64);
    im_solver_options o = im_solver_options_default();
    o.periodic = 1;
    im_indentation *run = NULL;
    assert_int_equal(im_indentation_create(s, &flat, IM_CONTROL_DISPLACEMENT, 1.0, &o, &run), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "expected load control"));
    assert_null(run);
    im_field_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(rigid_flat_is_flat_contact),
        cmocka_unit_test(repeated_cone_is_the_half_spaces),
        cmocka_unit_test(periodic_memory),
        cmocka_unit_test(capped_spike_is_not_an_answer),
        cmocka_unit_test(displacement_control_is_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
