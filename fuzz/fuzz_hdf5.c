/* libFuzzer harness: the plain HDF5 reader on arbitrary bytes must return a status, never crash, leak or trip a
 * sanitizer; what it accepts must be a well-formed, finite field (fuzz_checks.h). */
#include "fuzz_checks.h"
#include "fuzz_file.h"

#include "formats/hdf5.h"

#include <stdio.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    im_field *field = NULL;
    int status = surface_read_channel_format(fuzz_write_input(data, size), hdf5_read_in_process, NULL, &field, NULL);
    const char *problem = fuzz_field_problem(status, field);
    if (problem) {
        fprintf(stderr, "fuzz_hdf5: %s (status %d: %s)\n", problem, status, im_last_error());
        abort();
    }
    im_field_free(field);
    return 0;
}
