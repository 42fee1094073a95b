/* Shared by the fuzz harnesses: the readers take a path, so each input is written to one
 * temporary file per process (in $TMPDIR, else /tmp) and read back through the real reader. */
#ifndef INDENTMAP_FUZZ_FILE_H
#define INDENTMAP_FUZZ_FILE_H

#include <stddef.h>
#include <stdint.h>

/* The temporary file's path, now holding exactly data[0..size). Aborts (this is a harness, not
 * the library) if the file cannot be written, since every later input would be meaningless. */
const char *fuzz_write_input(const uint8_t *data, size_t size);

#endif
