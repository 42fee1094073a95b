/* An output folder's lock, FOLDER/.lock, shared by `run` (scenes) and `indent`: an flock(2) on the
 * file decides who holds it (the kernel drops it when its holder dies, so a crash can never leave
 * the folder locked for ever); the file holds the holder's pid for the messages, and is removed
 * when the run ends. */
#include "indentmap/io.h"
#include "core/args.h"

#include "indentmap/status.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

/* The pid written in the lock file, or 0 if it holds none. */
static long lock_owner(int fd)
{
    char text[32] = {0};
    ssize_t length = pread(fd, text, sizeof text - 1, 0);
    long pid = 0;
    return length > 0 && sscanf(text, "%ld", &pid) == 1 ? pid : 0;
}

/* Whether fd is still the file at path (a holder that has just finished unlinks it: a lock taken on
 * the unlinked file would protect nothing). */
static int still_linked(int fd, const char *path)
{
    struct stat opened, named;
    return fstat(fd, &opened) == 0 && stat(path, &named) == 0 && opened.st_ino == named.st_ino &&
           opened.st_dev == named.st_dev;
}

/* IM_EIO: the lock file at path (open as fd, closed here) is held by another live run. */
static int in_use(int fd, const char *folder, const char *path, const char *advice)
{
    char owner[32] = "pid not written yet";
    if (lock_owner(fd) > 0)
        snprintf(owner, sizeof owner, "pid %ld", lock_owner(fd));
    close(fd);
    return im_fail(IM_EIO,
                   "output folder %s is in use by another indentmap run (%s, lock file %s); wait for it to end or %s",
                   folder, owner, path, advice);
}

static int write_owner(int fd, const char *path)
{
    char text[32];
    int length = snprintf(text, sizeof text, "%ld\n", (long)getpid());
    if (ftruncate(fd, 0) != 0 || pwrite(fd, text, (size_t)length, 0) != length)
        return im_fail(IM_EIO, "%s: cannot write the lock file: %s", path, strerror(errno));
    return IM_OK;
}

int im_folder_lock_acquire(const char *folder, const char *advice, im_folder_lock *lock)
{
    ARG_REQUIRE(folder, "folder");
    ARG_REQUIRE(lock, "lock");
    lock->fd = -1;
    lock->stale_pid = 0;
    int status = im_path_join(lock->path, sizeof lock->path, folder, ".lock");
    for (int attempt = 0; status == IM_OK && attempt < 100; ++attempt) {
        int fd = open(lock->path, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        if (fd < 0)
            return im_fail(IM_EIO, "%s: cannot create the lock file: %s", lock->path, strerror(errno));
        if (flock(fd, LOCK_EX | LOCK_NB) != 0)
            return in_use(fd, folder, lock->path, advice);
        if (!still_linked(fd, lock->path)) {
            close(fd); /* its holder removed it as we opened it: take the new one */
            continue;
        }
        long stale = lock_owner(fd);
        lock->stale_pid = stale > 0 && stale != (long)getpid() ? stale : 0; /* the caller warns */
        status = write_owner(fd, lock->path);
        if (status != IM_OK) {
            close(fd);
            return status;
        }
        lock->fd = fd;
        return IM_OK;
    }
    return status == IM_OK ? im_fail(IM_EIO, "%s: the lock file keeps changing", lock->path) : status;
}

int im_folder_lock_probe(const char *folder, const char *advice)
{
    ARG_REQUIRE(folder, "folder");
    ARG_REQUIRE(advice, "advice");
    char path[sizeof((im_folder_lock *)0)->path];
    int status = im_path_join(path, sizeof path, folder, ".lock");
    int fd = status == IM_OK ? open(path, O_RDONLY | O_CLOEXEC) : -1;
    if (fd < 0)
        return status; /* no lock file (or one we cannot read, which acquiring reports): free */
    if (flock(fd, LOCK_EX | LOCK_NB) != 0)
        return in_use(fd, folder, path, advice);
    close(fd); /* closing the only descriptor releases the probe's lock */
    return IM_OK;
}

void im_folder_lock_release(im_folder_lock *lock)
{
    if (!lock || lock->fd < 0)
        return;
    unlink(lock->path); /* before the lock goes: no one can lock the old file in between and keep it */
    close(lock->fd);
    lock->fd = -1;
}

int im_pair_writers_lock(const char *path)
{
    ARG_REQUIRE_OR(path, "path", -1);
    char folder[4096];
    if (strlen(path) >= sizeof folder) {
        im_fail(IM_EINVAL, "%.64s...: path too long", path);
        return -1;
    }
    strcpy(folder, path);
    char *slash = strrchr(folder, '/');
    if (!slash)
        strcpy(folder, ".");
    else
        slash[slash == folder] = '\0'; /* "/name" is in "/" */
    int fd = open(folder, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    int locked = fd >= 0 ? flock(fd, LOCK_EX) : -1;
    while (locked != 0 && fd >= 0 && errno == EINTR)
        locked = flock(fd, LOCK_EX);
    if (locked == 0)
        return fd;
    im_fail(IM_EIO, "%s: cannot lock the folder for writing %s and its sidecar: %s", folder, path, strerror(errno));
    if (fd >= 0)
        close(fd);
    return -1;
}

void im_pair_writers_unlock(int fd)
{
    if (fd >= 0)
        close(fd); /* closing the only descriptor releases the flock */
}

int im_folder_remove_temporaries(const char *folder, int depth)
{
    ARG_REQUIRE_OR(folder, "folder", 0);
    DIR *listing = opendir(folder);
    if (!listing)
        return 0;
    int removed = 0;
    for (struct dirent *entry; (entry = readdir(listing)) != NULL;) {
        if (strcmp(entry->d_name, ".") == 0 || strcmp(entry->d_name, "..") == 0)
            continue;
        char path[8192];
        if (snprintf(path, sizeof path, "%s/%s", folder, entry->d_name) >= (int)sizeof path)
            continue;
        struct stat info;
        if (lstat(path, &info) != 0)
            continue;
        if (S_ISDIR(info.st_mode) && depth > 0)
            removed += im_folder_remove_temporaries(path, depth - 1);
        else if (S_ISREG(info.st_mode) && im_atomic_is_temporary_name(entry->d_name) && unlink(path) == 0)
            ++removed;
    }
    closedir(listing);
    return removed;
}
