#include "indentmap/io.h"

#include "indentmap/status.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int im_atomic_open(im_atomic_file *file, const char *path)
{
    memset(file, 0, sizeof *file);
    if (strlen(path) >= sizeof file->path)
        return im_fail(IM_EINVAL, "%.64s...: path too long", path);
    strcpy(file->path, path);
    snprintf(file->temp_path, sizeof file->temp_path, "%s.tmp.%ld", path, (long)getpid());
    file->stream = fopen(file->temp_path, "wb");
    if (!file->stream)
        return im_fail(IM_EIO, "%s: cannot open for writing: %s", path, strerror(errno));
    return IM_OK;
}

int im_atomic_commit(im_atomic_file *file)
{
    int failed = ferror(file->stream) || fflush(file->stream) != 0 || fsync(fileno(file->stream)) != 0;
    int saved_errno = errno;
    failed |= fclose(file->stream) != 0;
    file->stream = NULL;
    if (failed) {
        remove(file->temp_path);
        return im_fail(IM_EIO, "%s: write failed: %s", file->path, strerror(saved_errno));
    }
    if (rename(file->temp_path, file->path) != 0) {
        saved_errno = errno;
        remove(file->temp_path);
        return im_fail(IM_EIO, "%s: cannot move into place: %s", file->path, strerror(saved_errno));
    }
    return IM_OK;
}

void im_atomic_abort(im_atomic_file *file)
{
    if (file->stream) {
        fclose(file->stream);
        file->stream = NULL;
        remove(file->temp_path);
    }
}

int im_write_file_atomic(const char *path, const void *data, size_t size)
{
    im_atomic_file file;
    int status = im_atomic_open(&file, path);
    if (status != IM_OK)
        return status;
    if (size > 0 && fwrite(data, 1, size, file.stream) != size) {
        im_atomic_abort(&file);
        return im_fail(IM_EIO, "%s: write failed: %s", path, strerror(errno));
    }
    return im_atomic_commit(&file);
}

int im_make_directories(const char *path)
{
    char buffer[4096];
    if (strlen(path) >= sizeof buffer)
        return im_fail(IM_EINVAL, "%.64s...: path too long", path);
    strcpy(buffer, path);
    for (char *p = buffer + 1; *p; ++p) {
        if (*p != '/')
            continue;
        *p = '\0';
        if (mkdir(buffer, 0777) != 0 && errno != EEXIST)
            return im_fail(IM_EIO, "%s: cannot create directory: %s", buffer, strerror(errno));
        *p = '/';
    }
    if (mkdir(buffer, 0777) != 0 && errno != EEXIST)
        return im_fail(IM_EIO, "%s: cannot create directory: %s", buffer, strerror(errno));
    struct stat info;
    if (stat(buffer, &info) != 0 || !S_ISDIR(info.st_mode))
        return im_fail(IM_EIO, "%s: exists and is not a directory", buffer);
    return IM_OK;
}
