/* FFTW wisdom in the solver's plans: written to the file the options name and reused from it (the
 * same plans), a damaged file told apart and replaced, a file that is not wisdom left alone, and no
 * environment read by the library (the command line resolves IM_FFTW_WISDOM; tests/cli_wisdom.sh). */
#include "support.h"

#include "core/fft_threads.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "solver/plan.h"

#include <fftw3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const int NX = 40, NY = 36;

static im_solver_plan *plan_with(const char *wisdom)
{
    im_solver_options o = im_solver_options_default();
    o.wisdom_path = wisdom;
    im_solver_plan *plan = NULL;
    assert_int_equal(im_solver_plan_create(NX, NY, 1.0, &o, &plan), IM_OK);
    return plan;
}

static char *read_all(const char *path)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    char *text = calloc(1, 1 << 20);
    assert_non_null(text);
    size_t n = fread(text, 1, (1 << 20) - 1, f);
    fclose(f);
    text[n] = '\0';
    return text;
}

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static void forget_wisdom(void)
{
    fft_planner_lock();
    fftw_forget_wisdom();
    fft_planner_unlock();
}

/* FFTW's description of each of the plan's six transforms, concatenated. */
static char *describe(const im_solver_plan *p)
{
    const fftw_plan plans[6] = {p->rows_forward,  p->columns_forward,      p->columns_backward,
                                p->rows_backward, p->precondition_forward, p->precondition_backward};
    size_t size = 1;
    char *parts[6];
    for (int i = 0; i < 6; ++i) {
        parts[i] = fftw_sprint_plan(plans[i]);
        size += strlen(parts[i]) + 1;
    }
    char *all = calloc(1, size);
    assert_non_null(all);
    for (int i = 0; i < 6; ++i) {
        strcat(all, parts[i]);
        strcat(all, "\n");
        free(parts[i]);
    }
    return all;
}

static void library_reads_no_environment(void **state)
{
    (void)state;
    const char *path = test_path("from_environment.wisdom");
    setenv("IM_FFTW_WISDOM", path, 1);
    im_solver_options defaults = im_solver_options_default();
    assert_null(im_solver_wisdom_file(&defaults));
    im_solver_plan *plan = plan_with(NULL);
    assert_int_equal(im_solver_plan_measured(plan), 0);
    assert_int_equal(access(path, F_OK), -1); /* nothing written where the variable points */
    im_solver_plan_free(plan);
    unsetenv("IM_FFTW_WISDOM");
}

/* The first plan measures and writes the file; from the file alone (the process's wisdom forgotten)
 * FFTW can make the same transforms without measuring, and the next plan is the same plan. */
static void wisdom_written_then_reused(void **state)
{
    (void)state;
    const char *path = test_path("reused.wisdom");
    forget_wisdom();
    im_solver_plan *first = plan_with(path);
    assert_int_equal(im_solver_plan_measured(first), 1);
    char *text = read_all(path);
    assert_memory_equal(text, "(fftw-", 6);
    free(text);
    forget_wisdom();
    im_solver_options o = im_solver_options_default();
    o.wisdom_path = path;
    assert_int_equal(im_solver_wisdom_verify(&o), IM_OK); /* imports the file */
    const int length[1] = {first->px}, mx = first->px / 2 + 1;
    fft_planner_lock();
    fftw_plan from_wisdom = fftw_plan_many_dft_r2c(1, length, first->ny, first->rows_in, NULL, 1, first->px,
                                                   first->modes, NULL, 1, mx, FFTW_MEASURE | FFTW_WISDOM_ONLY);
    fft_planner_unlock();
    assert_non_null(from_wisdom); /* NULL: the file did not cover the plan, or FFTW rejected it */
    fft_planner_lock();
    fftw_destroy_plan(from_wisdom);
    fftw_forget_wisdom();
    fft_planner_unlock();
    im_solver_plan *second = plan_with(path);
    char *a = describe(first), *b = describe(second);
    assert_string_equal(a, b);
    free(a);
    free(b);
    im_solver_plan_free(first);
    im_solver_plan_free(second);
}

/* A truncated file is wisdom no more: verify says so (naming it), planning goes on and replaces it. */
static void damaged_wisdom_told_and_replaced(void **state)
{
    (void)state;
    const char *path = test_path("damaged.wisdom");
    im_solver_plan_free(plan_with(path));
    char *whole = read_all(path);
    whole[strlen(whole) / 2] = '\0';
    write_text(path, whole);
    free(whole);
    im_solver_options o = im_solver_options_default();
    o.wisdom_path = path;
    assert_int_equal(im_solver_wisdom_verify(&o), IM_EFORMAT);
    assert_non_null(strstr(im_last_error(), path));
    assert_non_null(strstr(im_last_error(), "FFTW rejects it"));
    im_solver_plan *plan = plan_with(path);
    assert_int_equal(im_solver_plan_measured(plan), 1);
    assert_int_equal(im_solver_wisdom_verify(&o), IM_OK);
    im_solver_plan_free(plan);
}

/* A file that is not wisdom at all is never read nor replaced (it may be someone's data). */
static void foreign_file_left_alone(void **state)
{
    (void)state;
    const char *path = test_path("notes.txt");
    write_text(path, "my notes\n");
    im_solver_options o = im_solver_options_default();
    o.wisdom_path = path;
    assert_int_equal(im_solver_wisdom_verify(&o), IM_EINVAL);
    im_solver_plan *plan = NULL;
    assert_int_equal(im_solver_plan_create(NX, NY, 1.0, &o, &plan), IM_EINVAL);
    assert_null(plan);
    char *text = read_all(path);
    assert_string_equal(text, "my notes\n");
    free(text);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(library_reads_no_environment),
        cmocka_unit_test(wisdom_written_then_reused),
        cmocka_unit_test(damaged_wisdom_told_and_replaced),
        cmocka_unit_test(foreign_file_left_alone),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
