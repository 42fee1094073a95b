/* Status messages (status.h) and a failure's message kept across the cleanup after it
 * (core/error_keep.h): what a run reports is its own error, whatever its cleanup recorded since. */
#include "support.h"

#include "core/error_keep.h"
#include "indentmap/status.h"

#include <string.h>

/* Cleanup that fails on its own: a record that cannot be written, a frame that cannot be drawn. */
static int cleanup_that_fails(void) { return im_fail(IM_EIO, "run.json: cannot be written (disk full)"); }

static void test_a_kept_message_survives_a_cleanup_that_fails(void **state)
{
    (void)state;
    im_fail(IM_ENOCONV, "step 3: no convergence after 500 iterations");
    kept_error kept;
    error_keep(&kept);
    assert_int_equal(cleanup_that_fails(), IM_EIO);
    im_fail_context(IM_EIO, "closing the run");
    assert_string_equal(im_last_error(), "closing the run: run.json: cannot be written (disk full)");
    assert_int_equal(error_restore(&kept, IM_ENOCONV), IM_ENOCONV);
    assert_string_equal(im_last_error(), "step 3: no convergence after 500 iterations");
}

/* The longest message status.c records (1023 bytes) is kept whole, and a run without an error keeps "". */
static void test_the_longest_message_and_none_are_kept_whole(void **state)
{
    (void)state;
    char longest[1024];
    memset(longest, 'x', sizeof longest - 1);
    longest[sizeof longest - 1] = '\0';
    im_fail(IM_EINVAL, "%s", longest);
    kept_error kept;
    error_keep(&kept);
    cleanup_that_fails();
    error_restore(&kept, IM_EINVAL);
    assert_int_equal(strlen(im_last_error()), sizeof longest - 1);
    assert_string_equal(im_last_error(), longest);
    im_fail(IM_OK, "%s", "");
    error_keep(&kept);
    cleanup_that_fails();
    assert_int_equal(error_restore(&kept, IM_OK), IM_OK);
    assert_string_equal(im_last_error(), "");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_kept_message_survives_a_cleanup_that_fails),
        cmocka_unit_test(test_the_longest_message_and_none_are_kept_whole),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
