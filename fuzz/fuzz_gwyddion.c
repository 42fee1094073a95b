/* libFuzzer harness: the stream indentmap-gwyddion-read writes (src/formats/gwyddion.h), parsed and
 * finished as a read through Gwyddion is, on arbitrary bytes: it must return a status, never crash,
 * leak or trip a sanitizer, and what it accepts must be a well-formed, finite field. The stream comes
 * from vendor files through Gwyddion's modules, so a hostile file can shape it: header lines that lie
 * about sizes, titles with any bytes, data cut short. */
#include "fuzz_checks.h"
#include "fuzz_file.h"

#include "formats/gwyddion.h"

#include <stdio.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    im_field *field = NULL;
    int status = gwyddion_stream_file_read(fuzz_write_input(data, size), &field);
    const char *problem = fuzz_field_problem(status, field);
    if (problem) {
        fprintf(stderr, "fuzz_gwyddion: %s (status %d: %s)\n", problem, status, im_last_error());
        abort();
    }
    im_field_free(field);
    return 0;
}
