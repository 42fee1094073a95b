/* Zip entries read whole and checked (zip_entry.h). */
#include "formats/zip_entry.h"

#include "indentmap/field.h"
#include "indentmap/status.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

int zip_entry_check_end(zip_file_t *file, const char *path, const char *entry)
{
    uint8_t extra;
    zip_int64_t got = zip_fread(file, &extra, 1);
    if (got == 0)
        return IM_OK;
    return im_fail(IM_EFORMAT, "%s: %s: %s", path, entry, got < 0 ? zip_file_strerror(file) : "longer than its size");
}

int zip_entry_read(zip_t *archive, const char *path, const char *name, size_t max_bytes, const char *absent,
                   char **text, size_t *size)
{
    *text = NULL;
    zip_stat_t info;
    zip_stat_init(&info);
    if (zip_stat(archive, name, 0, &info) != 0 || !(info.valid & ZIP_STAT_SIZE))
        return im_fail(IM_EFORMAT, "%s: %s", path, absent);
    if (info.size > max_bytes)
        return im_fail(IM_EFORMAT, "%s: %s is %llu bytes: expected at most %zu", path, name,
                       (unsigned long long)info.size, max_bytes);
    char what[4200];
    snprintf(what, sizeof what, "%s: %s", path, name);
    int status = im_memory_check((double)info.size + 1, what);
    char *buffer = status == IM_OK ? malloc((size_t)info.size + 1) : NULL;
    if (status != IM_OK || !buffer)
        return status != IM_OK ? status : im_fail(IM_ENOMEM, "%s: allocation failed", what);
    zip_file_t *file = zip_fopen(archive, name, 0);
    zip_int64_t got = file ? zip_fread(file, buffer, info.size) : -1;
    status = got == (zip_int64_t)info.size
                 ? zip_entry_check_end(file, path, name)
                 : im_fail(IM_EFORMAT, "%s cannot be read from the archive: %s", what, zip_strerror(archive));
    if (file)
        zip_fclose(file);
    if (status != IM_OK) {
        free(buffer);
        return status;
    }
    buffer[info.size] = '\0';
    *text = buffer;
    *size = (size_t)info.size;
    return IM_OK;
}
