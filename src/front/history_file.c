/* history.csv appended step by step (front.h). */
#include "front/front.h"

#include "indentmap/io.h"
#include "indentmap/status.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

int history_start(const char *dir, history_file *h)
{
    h->fd = -1;
    int status = im_path_join(h->path, sizeof h->path, dir, "history.csv");
    char header[IM_HISTORY_LINE_MAX];
    snprintf(header, sizeof header, "%s\n", im_history_columns());
    if (status == IM_OK)
        status = im_write_file_atomic(h->path, header, strlen(header));
    if (status != IM_OK)
        return status;
    h->fd = open(h->path, O_WRONLY | O_APPEND | O_CLOEXEC);
    if (h->fd < 0)
        return im_fail(IM_EIO, "%s: cannot open for appending: %s", h->path, strerror(errno));
    h->size = (off_t)strlen(header);
    return IM_OK;
}

int history_append(history_file *h, const im_history_row *row)
{
    char line[IM_HISTORY_LINE_MAX];
    int length = im_history_format(row, line, sizeof line);
    ssize_t written = write(h->fd, line, (size_t)length);
    if (written == length && fdatasync(h->fd) == 0) {
        h->size += length;
        return IM_OK;
    }
    int saved = written < 0 || written == length ? errno : ENOSPC; /* a short write: the disk filled */
    if (ftruncate(h->fd, h->size) != 0)                            /* no torn last line */
        return im_fail(IM_EIO, "%s: write failed: %s; its last line is incomplete (cutting it failed: %s)", h->path,
                       strerror(saved), strerror(errno));
    return im_fail(IM_EIO, "%s: write failed: %s", h->path, strerror(saved));
}

void history_close(history_file *h)
{
    if (h->fd >= 0)
        close(h->fd);
    h->fd = -1;
}
