/* formats/zip_entry.h: entries of a zip archive (libzip) read whole and checked, for the readers of
 * archives (.x3p, contact.engineering containers, .xlsx). */
#ifndef INDENTMAP_FORMATS_ZIP_ENTRY_H
#define INDENTMAP_FORMATS_ZIP_ENTRY_H

#include <stddef.h>
#include <zip.h>

/* Entry `name` of the archive at `path` read whole into *text (malloc'ed and NUL-terminated: the caller
 * frees it) and *size, then one byte past its stated size, so that libzip checks its CRC-32 and a
 * damaged entry is refused rather than read. IM_EFORMAT "PATH: absent" when the archive has no such
 * entry (absent says what the file then is not, e.g. "the archive has no main.xml: not an x3p file"),
 * and naming path and entry when it is larger than max_bytes or cannot be read whole; im_memory_check's
 * IM_ENOMEM. *text is NULL on any error. */
int zip_entry_read(zip_t *archive, const char *path, const char *name, size_t max_bytes, const char *absent,
                   char **text, size_t *size);

/* IM_OK when `file`, read to its stated size, has no byte more and libzip found no error (its CRC-32
 * is checked at the end); IM_EFORMAT naming path and entry otherwise. */
int zip_entry_check_end(zip_file_t *file, const char *path, const char *entry);

#endif
