/* Units end to end (issue 13): an indentation solved in SI units, on a surface whose file gives it in
 * µm (converted on reading, --length-unit m), equals the dimensionless run (lengths in delta, E* = 1)
 * times its scales: loads by E* delta^2, forces per patch by E* delta^2, gaps and displacements by
 * delta, contact areas by delta^2; the contact patches are the same. */
#include "support.h"

#include "indentmap/indenter.h"
#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

enum { SIDE = 48, STEPS = 3 };
static const double PIXEL_UM = 0.2, E_STAR_PA = 7.5e10;

/* A Gwyddion text export of a rough surface: Width in µm, heights in nm. */
static void write_export(const char *path, const im_field *surface)
{
    FILE *text = fopen(path, "w");
    assert_non_null(text);
    fprintf(text, "# Width: %.17g \u00b5m\n# Height: %.17g \u00b5m\n# Value units: nm\n", SIDE * PIXEL_UM,
            SIDE * PIXEL_UM);
    for (int i = 0; i < SIDE * SIDE; ++i)
        fprintf(text, "%.17g%c", surface->data[i] * PIXEL_UM * 1e3, i % SIDE == SIDE - 1 ? '\n' : ' ');
    fclose(text);
}

typedef struct run_output {
    im_step_result steps[STEPS];
    im_field *force, *gap, *displacement;
} run_output;

static void indent(const im_field *surface, double e_star, const double *approaches, run_output *out)
{
    im_indenter cone = im_indenter_cone(80.0);
    im_solver_options options = im_solver_options_default();
    options.tol = 1e-8; /* the bars below were set at tol 1e-8 (not the default, 1e-6) */
    options.e_star = e_star;
    options.tol = 1e-13;
    im_indentation *run = NULL;
    assert_int_equal(
        im_indentation_create(surface, &cone, IM_CONTROL_DISPLACEMENT, approaches[STEPS - 1], &options, &run), IM_OK);
    for (int i = 0; i < STEPS; ++i)
        if (im_indentation_step(run, approaches[i], &out->steps[i]) != IM_OK)
            fail_msg("step %d: %s", i, im_last_error());
    assert_int_equal(im_indentation_fields(run, &out->force, &out->gap, &out->displacement), IM_OK);
    im_indentation_free(run);
}

static void assert_scaled(const im_field *si, const im_field *dimensionless, double scale, const char *what)
{
    double largest = 0.0;
    for (int i = 0; i < SIDE * SIDE; ++i)
        largest = fmax(largest, fabs(dimensionless->data[i] * scale));
    for (int i = 0; i < SIDE * SIDE; ++i)
        if (!(fabs(si->data[i] - dimensionless->data[i] * scale) <= 1e-12 * largest))
            fail_msg("%s at %d: SI %.17g, dimensionless x scale %.17g", what, i, si->data[i],
                     dimensionless->data[i] * scale);
}

static void si_run_is_the_dimensionless_run_scaled(void **state)
{
    (void)state;
    im_surface_params params = im_surface_params_default();
    params.nx = params.ny = SIDE;
    params.lambda_r = SIDE;
    params.slope_rms = 0.1;
    im_field *dimensionless = NULL, *si = NULL;
    assert_int_equal(im_surface_generate(&params, &dimensionless), IM_OK);
    write_export(test_path("export.txt"), dimensionless);
    im_surface_read_options read = {.express_in = "m"};
    assert_int_equal(im_surface_read_with(test_path("export.txt"), &read, &si, NULL), IM_OK);
    const double delta = PIXEL_UM * 1e-6;
    assert_close(si->delta, delta, 1e-15 * delta);
    assert_string_equal(si->unit, "m");
    /* nm heights and µm spacing, both converted to m: h / delta is the generated surface again */
    for (int i = 0; i < SIDE * SIDE; ++i) {
        assert_close(si->data[i] / delta, dimensionless->data[i], 1e-13);
        dimensionless->data[i] = si->data[i] / delta; /* the same heights, to the last bit */
    }
    const double approaches[STEPS] = {0.5, 1.5, 3.0};
    double approaches_si[STEPS];
    for (int i = 0; i < STEPS; ++i)
        approaches_si[i] = approaches[i] * delta;
    run_output a = {0}, b = {0};
    indent(si, E_STAR_PA, approaches_si, &a);
    indent(dimensionless, 1.0, approaches, &b);
    const double force_scale = E_STAR_PA * delta * delta;
    for (int i = 0; i < STEPS; ++i) {
        assert_int_equal(a.steps[i].contact_patches, b.steps[i].contact_patches);
        assert_true(b.steps[i].contact_patches > 0);
        assert_close(a.steps[i].load / force_scale, b.steps[i].load, 1e-12 * b.steps[i].load);
        assert_close(a.steps[i].load_star, b.steps[i].load_star, 1e-12 * b.steps[i].load_star);
        assert_close(a.steps[i].area_ratio, b.steps[i].area_ratio, 1e-12 * b.steps[i].area_ratio);
        assert_close(a.steps[i].mean_pressure / E_STAR_PA, b.steps[i].mean_pressure,
                     1e-12 * b.steps[i].mean_pressure);
    }
    assert_scaled(a.force, b.force, force_scale, "force");
    assert_scaled(a.displacement, b.displacement, delta, "displacement");
    assert_scaled(a.gap, b.gap, delta, "gap");
    im_field *fields[] = {a.force, a.gap, a.displacement, b.force, b.gap, b.displacement};
    for (int i = 0; i < 6; ++i)
        im_field_free(fields[i]);
    im_field_free(si);
    im_field_free(dimensionless);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(si_run_is_the_dimensionless_run_scaled),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
