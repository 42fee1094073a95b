/* The output folder of a run (src/front/run_folder.h), which scenes and `indent` share: inputs
 * written over, the wisdom rule, the lock, a killed run's temporary files, and the run's error kept
 * in run.json and through index.html; then the names `indent` writes there (src/front/indent_run.h). */
#include "support.h"

#include "front/indent_run.h"
#include "front/run_folder.h"
#include "indentmap/io.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"

#include <jansson.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

/* A run that writes history.csv and run.json into its folder, as `indent` claims its names. */
static int claims_history(const char *name, const void *state)
{
    (void)state;
    return strcmp(name, "history.csv") == 0 || strcmp(name, "run.json") == 0;
}

/* A fresh folder test_temp_dir()/name. */
static const char *fresh_folder(const char *name)
{
    const char *dir = test_path(name);
    assert_int_equal(mkdir(dir, 0755), 0);
    return dir;
}

static run_folder_rules claiming_rules(const char *dir)
{
    return (run_folder_rules){.dir = dir,
                              .option = "--out",
                              .lock_advice = "give another --out",
                              .wisdom_advice = "move it",
                              .claims = claims_history};
}

static void claimed_inputs_refused(void **state)
{
    (void)state;
    const char *dir = fresh_folder("claimed");
    char input[4096], sidecar_of[4096], sidecar[4096], apart[4096];
    snprintf(input, sizeof input, "%s/history.csv", dir);
    snprintf(sidecar_of, sizeof sidecar_of, "%s/run", dir); /* its sidecar is run.json */
    snprintf(sidecar, sizeof sidecar, "%s/run.json", dir);
    snprintf(apart, sizeof apart, "%s/surface.npy", dir);
    test_write_bytes(input, "x", 1);
    test_write_bytes(sidecar_of, "x", 1);
    test_write_bytes(sidecar, "{}", 2);
    test_write_bytes(apart, "x", 1);
    const run_folder_rules rules = claiming_rules(dir);
    const im_solver_options solver = im_solver_options_default();
    const char *unclaimed[] = {apart, NULL};
    assert_int_equal(run_folder_check(&rules, unclaimed, 2, &solver), IM_OK);
    char expected[8192];
    const char *claimed[] = {apart, input};
    assert_int_equal(run_folder_check(&rules, claimed, 2, &solver), IM_EINVAL);
    snprintf(expected, sizeof expected, "--out %s would write %s/history.csv over the input file %s", dir, dir,
             input);
    assert_non_null(strstr(im_last_error(), expected));
    const char *by_sidecar[] = {sidecar_of};
    assert_int_equal(run_folder_check(&rules, by_sidecar, 1, &solver), IM_EINVAL);
    snprintf(expected, sizeof expected, "would write %s/run.json over the input file %s.json", dir, sidecar_of);
    assert_non_null(strstr(im_last_error(), expected));
    const run_folder_rules anything = {.dir = dir, .wisdom_advice = "move it"}; /* a scene: no claims to check */
    assert_int_equal(run_folder_check(&anything, claimed, 2, &solver), IM_OK);
}

/* run_folder_check's status for a wisdom file dir/name under rules. */
static int wisdom_status(const run_folder_rules *rules, const char *name)
{
    char wisdom[4096];
    snprintf(wisdom, sizeof wisdom, "%s/%s", rules->dir, name);
    im_solver_options solver = im_solver_options_default();
    solver.wisdom_path = wisdom;
    return run_folder_check(rules, NULL, 0, &solver);
}

static void wisdom_rule(void **state)
{
    (void)state;
    const char *dir = fresh_folder("wisdom");
    const run_folder_rules claiming = claiming_rules(dir);
    assert_int_equal(wisdom_status(&claiming, "fftw.wisdom"), IM_OK); /* a file the run does not write */
    assert_int_equal(wisdom_status(&claiming, "history.csv"), IM_EINVAL);
    char expected[8192];
    snprintf(expected, sizeof expected, "would be one of the run's outputs, %s/history.csv: move it", dir);
    assert_non_null(strstr(im_last_error(), expected));
    const run_folder_rules anything = {.dir = dir, .wisdom_advice = "keep it elsewhere"};
    assert_int_equal(wisdom_status(&anything, "fftw.wisdom"), IM_EINVAL);
    snprintf(expected, sizeof expected, "lies in the output folder %s, where this run writes: keep it elsewhere",
             dir);
    assert_non_null(strstr(im_last_error(), expected));
    assert_int_equal(wisdom_status(&anything, "../fftw.wisdom"), IM_OK); /* beside the folder, not in it */
}

static void folder_locked_and_cleared(void **state)
{
    (void)state;
    const char *dir = test_path("opened/deeper"); /* made with its parent */
    char left[4096], subfolder[4096], left_below[8192];
    const run_folder_rules rules = claiming_rules(dir);
    run_folder first, second;
    assert_int_equal(run_folder_open(&rules, 0, &first), IM_OK);
    assert_int_equal(first.temporaries_removed, 0);
    assert_int_equal(run_folder_open(&rules, 0, &second), IM_EIO); /* held by the first */
    assert_non_null(strstr(im_last_error(), "give another --out"));
    run_folder_close(&second);
    snprintf(left, sizeof left, "%s/history.csv.tmp.99999", dir);
    snprintf(subfolder, sizeof subfolder, "%s/frames", dir);
    snprintf(left_below, sizeof left_below, "%s/contact_0001.png.tmp.99999", subfolder);
    test_write_bytes(left, "x", 1);
    assert_int_equal(mkdir(subfolder, 0755), 0);
    test_write_bytes(left_below, "x", 1);
    run_folder_close(&first);
    assert_int_equal(run_folder_open(&rules, 0, &second), IM_OK); /* released: a later run takes it */
    assert_int_equal(second.temporaries_removed, 1);
    struct stat info;
    assert_int_not_equal(stat(left, &info), 0);
    assert_int_equal(stat(left_below, &info), 0); /* depth 0: the folder only */
    run_folder_close(&second);
    assert_int_equal(run_folder_open(&rules, 1, &second), IM_OK);
    assert_int_equal(second.temporaries_removed, 1);
    run_folder_close(&second);
}

static void run_error_kept(void **state)
{
    (void)state;
    const char *dir = fresh_folder("failed");
    const run_folder_rules rules = claiming_rules(dir);
    run_folder folder;
    assert_int_equal(run_folder_open(&rules, 0, &folder), IM_OK);
    json_t *record = json_object();
    im_fail(IM_EIO, "step 3 failed");
    assert_int_equal(run_folder_record(&folder, record, 2, IM_EIO), IM_EIO);
    assert_string_equal(im_last_error(), "step 3 failed");
    json_decref(record);
    assert_int_equal(run_folder_page(&folder, "a failed run", 0, IM_EIO), IM_EIO);
    assert_string_equal(im_last_error(), "step 3 failed");
    char path[4096];
    snprintf(path, sizeof path, "%s/run.json", dir);
    json_t *written = json_load_file(path, 0, NULL);
    assert_non_null(written);
    assert_string_equal(json_string_value(json_object_get(written, "error")), "step 3 failed");
    assert_string_equal(json_string_value(json_object_get(written, "status")), im_strstatus(IM_EIO));
    assert_int_equal(json_integer_value(json_object_get(written, "steps_completed")), 2);
    json_decref(written);
    snprintf(path, sizeof path, "%s/index.html", dir);
    struct stat info;
    assert_int_equal(stat(path, &info), 0);
    run_folder_close(&folder);
}

/* Where run.json and index.html cannot be written (folders hold their names): a run that succeeded did
 * not finish, and a run that failed keeps its own status and message first, then says which record was not
 * written either and why (reliability finding 13: on a full disk run.json was gone, unsaid). */
static void write_failures_reported(void **state)
{
    (void)state;
    const char *dir = fresh_folder("unwritable");
    char path[4096];
    snprintf(path, sizeof path, "%s/index.html", dir);
    assert_int_equal(mkdir(path, 0755), 0);
    snprintf(path, sizeof path, "%s/run.json", dir);
    assert_int_equal(mkdir(path, 0755), 0);
    const run_folder_rules rules = claiming_rules(dir);
    run_folder folder;
    assert_int_equal(run_folder_open(&rules, 0, &folder), IM_OK);
    json_t *record = json_object();
    assert_int_not_equal(run_folder_record(&folder, record, 1, IM_OK), IM_OK);
    assert_int_not_equal(run_folder_page(&folder, "a run", 0, IM_OK), IM_OK);
    im_fail(IM_EINTERRUPTED, "interrupted by signal 2");
    assert_int_equal(run_folder_record(&folder, record, 1, IM_EINTERRUPTED), IM_EINTERRUPTED);
    char expected[8192];
    snprintf(expected, sizeof expected,
             "interrupted by signal 2; run.json was not written either (%s/run.json: cannot move into place: Is a "
             "directory)",
             dir);
    assert_string_equal(im_last_error(), expected);
    im_fail(IM_EINTERRUPTED, "interrupted by signal 2");
    assert_int_equal(run_folder_page(&folder, "a run", 0, IM_EINTERRUPTED), IM_EINTERRUPTED);
    assert_non_null(strstr(im_last_error(), "interrupted by signal 2; index.html was not written either ("));
    json_decref(record);
    run_folder_close(&folder);
}

/* ---- indent's files (indent_run.h) ---- */

static void indent_names_claimed(void **state)
{
    (void)state;
    const indent_files elastic = {.fields = 1, .steps = 12};
    const indent_files plastic = {.fields = 1, .hardness = 0.1, .distributions = 1, .steps = 12};
    const indent_files history_only = {.steps = 12};
    const char *const always[] = {"history.csv", "run.json",        "index.html",
                                  "history.png", "indentation.csv", "force_distance.pdf"};
    for (size_t i = 0; i < sizeof always / sizeof *always; ++i)
        assert_true(indent_files_claims(always[i], &history_only));
    assert_true(indent_files_claims("force_0001.npy", &elastic));
    assert_true(indent_files_claims("displacement_0012.npy.json", &elastic));
    assert_false(indent_files_claims("force_0013.npy", &elastic));   /* beyond the steps */
    assert_false(indent_files_claims("force_0000.npy", &elastic));   /* steps count from 1 */
    assert_false(indent_files_claims("force_00001.npy", &elastic));  /* the run writes four digits */
    assert_false(indent_files_claims("plastic_0001.npy", &elastic)); /* only with a hardness */
    assert_true(indent_files_claims("plastic_0001.npy", &plastic));
    assert_false(indent_files_claims("force_0001.npy", &history_only)); /* no --fields */
    assert_true(indent_files_claims("distributions_0012_patch_list.csv", &plastic));
    assert_false(indent_files_claims("distributions_0001_gaps.csv", &elastic));
    assert_false(indent_files_claims("distributions_0001_other.csv", &plastic));
    assert_false(indent_files_claims("notes.txt", &plastic));
}

/* What an earlier run left is removed, whatever its steps; other files and inputs stay. */
static void earlier_run_cleared(void **state)
{
    (void)state;
    const char *dir = fresh_folder("earlier");
    char frames[4096], path[8192], input[8192];
    snprintf(frames, sizeof frames, "%s/frames", dir);
    assert_int_equal(mkdir(frames, 0755), 0);
    const char *const removed[] = {"force_0007.npy", "plastic_12345.npy.json", "distributions_0002_gaps.csv",
                                   "history.png",    "load_displacement.pdf",  "frames/contact_0003.png"};
    const char *const kept[] = {"history.csv", "notes.txt", "force_07.npy", "frames/height_0003.png", "gap_0001.npy"};
    for (size_t i = 0; i < sizeof removed / sizeof *removed; ++i) {
        snprintf(path, sizeof path, "%s/%s", dir, removed[i]);
        test_write_bytes(path, "x", 1);
    }
    for (size_t i = 0; i < sizeof kept / sizeof *kept; ++i) {
        snprintf(path, sizeof path, "%s/%s", dir, kept[i]);
        test_write_bytes(path, "x", 1);
    }
    snprintf(input, sizeof input, "%s/gap_0001.npy", dir);
    assert_int_equal(im_output_protect(input), IM_OK); /* an input named like a field file */
    assert_int_equal(indent_files_clear(dir), IM_OK);
    struct stat info;
    for (size_t i = 0; i < sizeof removed / sizeof *removed; ++i) {
        snprintf(path, sizeof path, "%s/%s", dir, removed[i]);
        if (stat(path, &info) == 0)
            fail_msg("%s was left", removed[i]);
    }
    for (size_t i = 0; i < sizeof kept / sizeof *kept; ++i) {
        snprintf(path, sizeof path, "%s/%s", dir, kept[i]);
        if (stat(path, &info) != 0)
            fail_msg("%s was removed", kept[i]);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(claimed_inputs_refused),    cmocka_unit_test(wisdom_rule),
        cmocka_unit_test(folder_locked_and_cleared), cmocka_unit_test(run_error_kept),
        cmocka_unit_test(write_failures_reported),   cmocka_unit_test(indent_names_claimed),
        cmocka_unit_test(earlier_run_cleared),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
