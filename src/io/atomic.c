/* Atomic writes: a temporary file with a short unique name beside the destination, renamed over it
 * when complete; a destination that is a symbolic link is the link's target (the link stays). Every
 * file the program writes goes through here, and so through the output guard (guard.c): no input, no
 * sidecar of an input, no file of another kind is ever replaced. */
#include "indentmap/io.h"
#include "core/args.h"

#include "io/guard.h"
#include "indentmap/status.h"

#include <errno.h>
#include <fcntl.h>
#include <stdatomic.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- temporary files being written, for removal on a fatal signal ---- */

/* A slot is free (0), being filled (1) or holds the path of a temporary file in use (2). The
 * signal handler only reads slots in state 2 and unlinks their paths: lock-free atomics and
 * unlink(2) are async-signal-safe. */
enum { TEMPORARY_SLOTS = 256, SLOT_FREE = 0, SLOT_FILLING = 1, SLOT_READY = 2 };
static atomic_int slot_state[TEMPORARY_SLOTS];
static char slot_path[TEMPORARY_SLOTS][sizeof(((im_atomic_file *)0)->temp_path)];

/* Claims a slot for path, or returns -1 when all are taken (the file is then written unlisted). */
static int claim_slot(const char *path)
{
    for (int i = 0; i < TEMPORARY_SLOTS; ++i) {
        int expected = SLOT_FREE;
        if (atomic_compare_exchange_strong(&slot_state[i], &expected, SLOT_FILLING)) {
            snprintf(slot_path[i], sizeof slot_path[i], "%s", path);
            atomic_store(&slot_state[i], SLOT_READY);
            return i;
        }
    }
    return -1;
}

static void release_slot(int slot)
{
    if (slot >= 0)
        atomic_store(&slot_state[slot], SLOT_FREE);
}

void im_atomic_remove_temporaries(void)
{
    for (int i = 0; i < TEMPORARY_SLOTS; ++i)
        if (atomic_load(&slot_state[i]) == SLOT_READY)
            unlink(slot_path[i]);
}

/* ---- temporary names ---- */

/* DIR/.im.tmp.PID.N[SUFFIX] in the destination's folder: unique per process (pid) and per call
 * (N, shared by all threads), and short, so that any legal final name leaves room for it. */
static int temporary_name(const char *path, const char *suffix, char *out, size_t size)
{
    static atomic_ulong counter;
    const char *slash = strrchr(path, '/');
    int folder = slash ? (int)(slash - path) + 1 : 0;
    int length = snprintf(out, size, "%.*s.im.tmp.%ld.%lu%s", folder, path, (long)getpid(),
                          (unsigned long)atomic_fetch_add(&counter, 1), suffix);
    return length > 0 && (size_t)length < size ? IM_OK : im_fail(IM_EINVAL, "%.64s...: path too long", path);
}

/* Digits only, at least one. */
static int all_digits(const char *text, size_t length)
{
    for (size_t i = 0; i < length; ++i)
        if (text[i] < '0' || text[i] > '9')
            return 0;
    return length > 0;
}

int im_atomic_is_temporary_name(const char *name)
{
    ARG_REQUIRE_OR(name, "name", 0);
    if (strncmp(name, ".im.tmp.", 8) == 0)
        return 1;
    const char *marker = strstr(name, ".tmp.");
    while (marker && strstr(marker + 1, ".tmp."))
        marker = strstr(marker + 1, ".tmp."); /* the last one */
    if (!marker || marker == name)
        return 0;
    const char *pid = marker + 5;
    size_t length = strlen(pid);
    if (length > 4 && strcmp(pid + length - 4, ".mp4") == 0)
        length -= 4;
    return all_digits(pid, length);
}

/* ---- symbolic links ---- */

enum { LINKS_FOLLOWED_AT_MOST = 40 }; /* Linux's own limit: more links in a row are a loop */

/* Where the link `link` points: `target` when absolute, else `target` in the link's folder. */
static int link_destination(const char *link, const char *target, char *out, size_t size)
{
    const char *slash = strrchr(link, '/');
    int folder = target[0] == '/' || !slash ? 0 : (int)(slash - link) + 1;
    int length = snprintf(out, size, "%.*s%s", folder, link, target);
    return length > 0 && (size_t)length < size ? IM_OK : im_fail(IM_EINVAL, "%.64s...: path too long", link);
}

/* The file that path names once its symbolic links are followed (path itself when it is none, or a
 * dangling link's target), so that the new file replaces the target in its folder and a link stays a
 * link, pointing at the new content. A loop of links is refused naming path. */
static int follow_links(const char *path, char *out, size_t size)
{
    char target[sizeof((im_atomic_file *)0)->path];
    snprintf(out, size, "%s", path);
    for (int followed = 0; followed <= LINKS_FOLLOWED_AT_MOST; ++followed) {
        ssize_t length = readlink(out, target, sizeof target);
        if (length < 0 && errno != ELOOP)
            return IM_OK; /* not a link (EINVAL), or nothing there yet: out is the file to write */
        if (length < 0)
            break; /* a loop among the folders above */
        if ((size_t)length == sizeof target)
            return im_fail(IM_EINVAL, "%s: the symbolic link's target is too long", path);
        target[length] = '\0';
        char link[sizeof target];
        snprintf(link, sizeof link, "%s", out);
        int status = link_destination(link, target, out, size);
        if (status != IM_OK)
            return status;
    }
    return im_fail(IM_EINVAL,
                   "%s: a loop of symbolic links (more than %d followed): expected a file, or a link to one, "
                   "to write",
                   path, LINKS_FOLLOWED_AT_MOST);
}

/* Creates the temporary file exclusively (O_EXCL: a name left by a dead process of the same pid is
 * skipped), readable back for the kind check at commit. */
static int create_temporary(im_atomic_file *file, const char *suffix)
{
    for (int attempt = 0; attempt < 100; ++attempt) {
        int status = temporary_name(file->path, suffix, file->temp_path, sizeof file->temp_path);
        if (status != IM_OK)
            return status;
        /* listed before it exists: a fatal signal between the open and the listing would leave it */
        file->slot = claim_slot(file->temp_path);
        int fd = open(file->temp_path, O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0) {
            int saved = errno;
            release_slot(file->slot);
            file->slot = -1;
            if (saved == EEXIST)
                continue;
            return im_fail(IM_EIO, "%s: cannot open for writing: %s", file->path, strerror(saved));
        }
        file->stream = fdopen(fd, "w+b");
        if (file->stream)
            return IM_OK;
        int saved = errno;
        close(fd);
        unlink(file->temp_path);
        release_slot(file->slot);
        return im_fail(IM_EIO, "%s: cannot open for writing: %s", file->path, strerror(saved));
    }
    return im_fail(IM_EIO, "%s: no unused temporary name beside it", file->path);
}

int im_atomic_open_suffixed(im_atomic_file *file, const char *path, const char *suffix)
{
    ARG_REQUIRE(file, "file");
    ARG_REQUIRE(path, "path");
    memset(file, 0, sizeof *file);
    file->slot = -1;
    if (strlen(path) >= sizeof file->path)
        return im_fail(IM_EINVAL, "%.64s...: path too long", path);
    int status = follow_links(path, file->path, sizeof file->path);
    if (status == IM_OK)
        status = im_output_check(path);
    return status == IM_OK ? create_temporary(file, suffix ? suffix : "") : status;
}

int im_atomic_open(im_atomic_file *file, const char *path)
{
    ARG_REQUIRE(file, "file");
    ARG_REQUIRE(path, "path");
    return im_atomic_open_suffixed(file, path, NULL);
}

/* Removes the temporary file and forgets it. */
static void discard(im_atomic_file *file)
{
    unlink(file->temp_path);
    release_slot(file->slot);
    file->slot = -1;
}

int im_atomic_commit(im_atomic_file *file)
{
    ARG_REQUIRE(file, "file");
    int failed = ferror(file->stream) || fflush(file->stream) != 0 || fsync(fileno(file->stream)) != 0;
    int saved_errno = errno;
    /* what was written and what it would replace are compared while the stream is open */
    int status = failed ? IM_OK : output_check_replace(file->path, fileno(file->stream));
    failed |= fclose(file->stream) != 0;
    file->stream = NULL;
    if (failed)
        status = im_fail(IM_EIO, "%s: write failed: %s", file->path, strerror(saved_errno ? saved_errno : EIO));
    else if (status == IM_OK && rename(file->temp_path, file->path) != 0)
        status = im_fail(IM_EIO, "%s: cannot move into place: %s", file->path, strerror(errno));
    if (status != IM_OK)
        discard(file);
    release_slot(file->slot);
    file->slot = -1;
    return status;
}

void im_atomic_abort(im_atomic_file *file)
{
    if (!file)
        return;
    if (file->stream) {
        fclose(file->stream);
        file->stream = NULL;
        discard(file);
    }
}

int im_write_file_atomic(const char *path, const void *data, size_t size)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(data || size == 0, "data");
    im_atomic_file file;
    int status = im_atomic_open(&file, path);
    if (status != IM_OK)
        return status;
    if (size > 0 && fwrite(data, 1, size, file.stream) != size) {
        int saved = errno;
        im_atomic_abort(&file);
        return im_fail(IM_EIO, "%s: write failed: %s", path, strerror(saved));
    }
    return im_atomic_commit(&file);
}

int im_make_directories(const char *path)
{
    ARG_REQUIRE(path, "path");
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
