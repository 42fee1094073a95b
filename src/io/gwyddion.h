/* io/gwyddion.h: instrument formats read through Gwyddion's file modules.
 *
 * Gwyddion's modules run in a separate program, indentmap-gwyddion-read (src/io/gwyddion/), built
 * when Gwyddion's development files are present; this side starts it, reads its stream and turns the
 * chosen channel into a raw field with the units it states. See the program's source for the stream. */
#ifndef INDENTMAP_IO_GWYDDION_H
#define INDENTMAP_IO_GWYDDION_H

#include "io/readers.h"

#include <stdio.h>

/* Reads path through Gwyddion: channel is an index or a title ("" for the first channel holding
 * lengths). Masked (invalid) points become NaN. IM_EFORMAT naming path when Gwyddion cannot read it,
 * when the channel asked for is not there (the message lists the channels), when the chosen channel's
 * values are not lengths, or when the program fails; IM_EUNSUPPORTED when this build has no program. */
int gwyddion_read_raw(const char *path, const char *channel, im_field **out, surface_stated *stated);

/* Parses the program's stream into a raw field and its stated units, as gwyddion_read_raw does. */
int gwyddion_stream_parse(FILE *stream, const char *path, im_field **out, surface_stated *stated);

/* A file holding such a stream, parsed and finished (units applied, missing points refused) as a read
 * through the program would be: what fuzz/fuzz_gwyddion.c and its regression test feed. */
int gwyddion_stream_file_read(const char *path, im_field **out);

#endif
