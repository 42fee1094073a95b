/* formats/gwyddion.h: instrument formats read through Gwyddion's file modules.
 *
 * Gwyddion's modules run in a separate program, indentmap-gwyddion-read (src/formats/gwyddion/), built
 * when Gwyddion's development files are present; this side starts it, reads its stream and turns the
 * chosen channel into a raw field with the units it states. See the program's source for the stream. */
#ifndef INDENTMAP_FORMATS_GWYDDION_H
#define INDENTMAP_FORMATS_GWYDDION_H

#include "formats/readers.h"

#include <stdio.h>

/* The words of the refusal when no Gwyddion module reads a file's format (callers look for them). */
#define GWYDDION_UNKNOWN_FORMAT "no Gwyddion file module reads this format"

/* Reads path through Gwyddion: options->channel is an index or a title ("" for the first channel
 * holding lengths; options may be NULL). Masked (invalid) points become NaN. IM_EFORMAT naming path
 * when this build has no program, when Gwyddion cannot read the file, when the channel asked for is
 * not there, when the chosen channel's values are not lengths (the message lists the channels), when
 * they have no unit beside a lateral unit and options->set.height gives none, or when the program
 * crashes, runs out of time or ends without a field (its last line of errors quoted). */
int gwyddion_read_raw(const char *path, const im_surface_read_options *options, im_field **out,
                      surface_stated *stated);

/* A file holding such a stream, parsed and finished (units applied, missing points refused) as a read
 * through the program would be: what fuzz/fuzz_gwyddion.c and its regression test feed. */
int gwyddion_stream_file_read(const char *path, im_field **out);

#endif
