/* formats/utf16_text.h: UTF-16 text (as spreadsheet programs save "Unicode text") read as the UTF-8 it
 * spells, so that the text reader judges its content. */
#ifndef INDENTMAP_FORMATS_UTF16_TEXT_H
#define INDENTMAP_FORMATS_UTF16_TEXT_H

#include <stdio.h>

/* When the regular file behind *stream starts with a UTF-16 byte-order mark (FF FE: little-endian,
 * FE FF: big-endian), reads it whole (checked against the memory available), decodes it to UTF-8 and
 * replaces *stream by a stream of that text (the mark dropped), closing the original; *encoding is then
 * "UTF-16LE" or "UTF-16BE", else NULL and the stream rewound and kept (a pipe is kept as it is).
 * IM_EFORMAT naming path and the byte offset for a lone surrogate, a NUL character or an odd length;
 * IM_ENOMEM or IM_EIO naming path. On failure the original is closed and *stream is NULL. */
int formats_utf16_decode_if_marked(FILE **stream, const char *path, const char **encoding);

#endif
