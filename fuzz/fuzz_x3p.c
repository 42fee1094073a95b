/* libFuzzer harness: im_x3p_read on arbitrary bytes must return a status, never crash, leak or
 * trip a sanitizer; what it accepts must be a well-formed, finite field (fuzz_checks.h). */
#include "fuzz_checks.h"
#include "fuzz_file.h"

#include "indentmap/io.h"
#include "indentmap/formats.h"

#include <stdio.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    im_field *field = NULL;
    int status = im_x3p_read(fuzz_write_input(data, size), &field);
    const char *problem = fuzz_field_problem(status, field);
    if (problem) {
        fprintf(stderr, "fuzz_x3p: %s (status %d: %s)\n", problem, status, im_last_error());
        abort();
    }
    im_field_free(field);
    return 0;
}
