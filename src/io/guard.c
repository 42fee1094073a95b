/* The output guard: the inputs of the process (and their sidecars, PATH.json) may not be written,
 * and an existing file is replaced only by one of its kind. Inputs are compared by identity (device
 * and inode, with and without following a symlink) and by name (the folder resolved, the name as
 * given), so that another spelling, a symlink or a hard link of an input is refused too. */
#include "indentmap/io.h"
#include "core/args.h"

#include "io/guard.h"
#include "indentmap/status.h"

#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

typedef struct identity {
    dev_t device;
    ino_t inode;
    int known;
} identity;

typedef struct protected_input {
    char given[PATH_MAX];                 /* as named, for messages */
    char named[PATH_MAX], full[PATH_MAX]; /* folder resolved; everything resolved */
    identity itself, target, sidecar;     /* lstat, stat, stat of PATH.json */
} protected_input;

static pthread_mutex_t inputs_lock = PTHREAD_MUTEX_INITIALIZER;
static protected_input *inputs;
static int input_count, input_capacity;

static identity identity_of(const char *path, int follow)
{
    struct stat info;
    int found = (follow ? stat(path, &info) : lstat(path, &info)) == 0;
    return (identity){found ? info.st_dev : 0, found ? info.st_ino : 0, found};
}

static int same_identity(identity a, identity b)
{
    return a.known && b.known && a.device == b.device && a.inode == b.inode;
}

int im_path_absolute(const char *path, char *out, size_t size)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(out, "out");
    char prefix[PATH_MAX], resolved[PATH_MAX];
    if (snprintf(prefix, sizeof prefix, "%s", path) >= (int)sizeof prefix)
        return im_fail(IM_EINVAL, "%.64s...: path too long", path);
    /* shorten by whole components until what is left resolves; nothing left: the working folder */
    size_t n = strlen(prefix);
    while (n > 0 && !realpath(prefix, resolved)) {
        char *slash = strrchr(prefix, '/');
        n = !slash ? 0 : slash == prefix ? 1 : (size_t)(slash - prefix);
        prefix[n] = '\0';
    }
    if (n == 0 && !realpath(".", resolved))
        return im_fail(IM_EIO, "%s: cannot resolve the working folder", path);
    const char *tail = path + n;
    while (*tail == '/')
        ++tail;
    int length = snprintf(out, size, "%s%s%s", resolved, *tail && strcmp(resolved, "/") ? "/" : "", tail);
    return length >= 0 && (size_t)length < size ? IM_OK : im_fail(IM_EINVAL, "%.64s...: path too long", path);
}

/* The path with its folder resolved as far as it exists and its last component as given ("" if
 * it does not fit). */
static void named_form(const char *path, char *out)
{
    char folder[PATH_MAX], resolved[PATH_MAX];
    const char *slash = strrchr(path, '/');
    snprintf(folder, sizeof folder, "%.*s", slash ? (int)(slash - path) + 1 : 1, slash ? path : ".");
    out[0] = '\0';
    if (im_path_absolute(folder, resolved, sizeof resolved) == IM_OK) {
        int length = snprintf(out, PATH_MAX, "%s/%s", strcmp(resolved, "/") ? resolved : "",
                              slash ? slash + 1 : path);
        if (length < 0 || length >= PATH_MAX)
            out[0] = '\0';
    }
}

static int same_name(const char *a, const char *b) { return a[0] && strcmp(a, b) == 0; }

/* Whether name is form + ".json". */
static int is_sidecar_name(const char *name, const char *form)
{
    size_t n = strlen(form);
    return form[0] && strncmp(name, form, n) == 0 && strcmp(name + n, ".json") == 0;
}

int im_output_protect(const char *path)
{
    ARG_REQUIRE(path, "path");
    protected_input entry = {0};
    snprintf(entry.given, sizeof entry.given, "%s", path);
    named_form(path, entry.named);
    if (!realpath(path, entry.full))
        entry.full[0] = '\0';
    entry.itself = identity_of(path, 0);
    entry.target = identity_of(path, 1);
    char sidecar[PATH_MAX + 8];
    snprintf(sidecar, sizeof sidecar, "%s.json", path);
    entry.sidecar = identity_of(sidecar, 1);
    pthread_mutex_lock(&inputs_lock);
    int status = IM_OK;
    if (input_count == input_capacity) {
        int capacity = input_capacity ? 2 * input_capacity : 8;
        protected_input *grown = realloc(inputs, sizeof *inputs * (size_t)capacity);
        if (grown) {
            inputs = grown;
            input_capacity = capacity;
        } else {
            status = im_fail(IM_ENOMEM, "%s: cannot note the input", path);
        }
    }
    if (status == IM_OK)
        inputs[input_count++] = entry;
    pthread_mutex_unlock(&inputs_lock);
    return status;
}

void im_output_protect_reset(void)
{
    pthread_mutex_lock(&inputs_lock);
    free(inputs);
    inputs = NULL;
    input_count = input_capacity = 0;
    pthread_mutex_unlock(&inputs_lock);
}

static int meets_input(const protected_input *in, const char *named, identity itself, identity target)
{
    return same_identity(itself, in->itself) || same_identity(target, in->target) || same_name(named, in->named) ||
           same_name(named, in->full);
}

static int meets_sidecar(const protected_input *in, const char *named, identity target)
{
    return same_identity(target, in->sidecar) || is_sidecar_name(named, in->named) ||
           is_sidecar_name(named, in->full);
}

/* What a path that is not a regular file or a folder names, for the refusal below. */
static const char *special_kind(mode_t mode)
{
    return S_ISCHR(mode)    ? "character device"
           : S_ISBLK(mode)  ? "block device"
           : S_ISFIFO(mode) ? "FIFO"
           : S_ISSOCK(mode) ? "socket"
                            : "special file";
}

/* Outputs are written by renaming a new file over the old one: over a device node or a FIFO (as root:
 * /dev/stdout, /dev/full) that would replace the node itself. Refused: a regular file, a folder (the
 * rename then fails with its own message) or a new name are fine. */
static int check_replaceable(const char *path)
{
    struct stat info;
    if (stat(path, &info) != 0 || S_ISREG(info.st_mode) || S_ISDIR(info.st_mode))
        return IM_OK;
    return im_fail(IM_EINVAL,
                   "%s is a %s, not a regular file: an output replaces its file by renaming a new one "
                   "over it, which would replace the %s itself; give a file name",
                   path, special_kind(info.st_mode), special_kind(info.st_mode));
}

int im_output_check(const char *path)
{
    ARG_REQUIRE(path, "path");
    char named[PATH_MAX];
    named_form(path, named);
    identity itself = identity_of(path, 0), target = identity_of(path, 1);
    int status = IM_OK;
    pthread_mutex_lock(&inputs_lock);
    for (int i = 0; i < input_count && status == IM_OK; ++i) {
        const protected_input *in = &inputs[i];
        if (meets_input(in, named, itself, target))
            status = im_fail(IM_EINVAL, "%s would overwrite the input file %s (%s); write it elsewhere", path,
                             in->given, in->full[0] ? in->full : in->named);
        else if (meets_sidecar(in, named, target))
            status = im_fail(IM_EINVAL,
                             "%s would overwrite %s.json, the sidecar of the input file %s; write it "
                             "elsewhere",
                             path, in->given, in->given);
    }
    pthread_mutex_unlock(&inputs_lock);
    return status == IM_OK ? check_replaceable(path) : status;
}

/* ---- kinds of files ---- */

static const char *const KIND_NAMES[] = {[IM_KIND_NONE] = "nothing",
                                         [IM_KIND_NPY] = "a NumPy array (.npy)",
                                         [IM_KIND_PNG] = "a PNG image",
                                         [IM_KIND_GIF] = "a GIF image",
                                         [IM_KIND_PDF] = "a PDF document",
                                         [IM_KIND_SVG] = "an SVG image",
                                         [IM_KIND_MP4] = "an MP4 video",
                                         [IM_KIND_GSF] = "a Gwyddion Simple Field (.gsf)",
                                         [IM_KIND_WISDOM] = "FFTW wisdom",
                                         [IM_KIND_JSON] = "JSON",
                                         [IM_KIND_INI] = "an INI file (a scene)",
                                         [IM_KIND_TEXT] = "text",
                                         [IM_KIND_BINARY] = "binary data of an unknown kind"};

const char *im_file_kind_name(enum im_file_kind kind)
{
    return (size_t)kind < sizeof KIND_NAMES / sizeof *KIND_NAMES ? KIND_NAMES[kind] : "unknown"; /* also < 0 */
}

static int starts_with(const char *head, size_t length, const char *prefix)
{
    size_t n = strlen(prefix);
    return length >= n && memcmp(head, prefix, n) == 0;
}

/* Text: its first line that is not blank or a comment ('#', ';') starts a section: an INI file. */
static enum im_file_kind text_kind(const char *head, size_t length)
{
    size_t i = 0;
    while (i < length) {
        while (i < length && (head[i] == ' ' || head[i] == '\t' || head[i] == '\r' || head[i] == '\n'))
            ++i;
        if (i < length && head[i] != '#' && head[i] != ';')
            return head[i] == '[' ? IM_KIND_INI : IM_KIND_TEXT;
        while (i < length && head[i] != '\n')
            ++i;
    }
    return IM_KIND_TEXT;
}

enum im_file_kind im_file_kind_of_bytes(const void *bytes, size_t length)
{
    ARG_REQUIRE_OR(bytes, "bytes", IM_KIND_NONE);
    const char *head = bytes;
    static const struct {
        const char *magic;
        enum im_file_kind kind;
    } MAGICS[] = {{"\x93NUMPY", IM_KIND_NPY},
                  {"\x89PNG\r\n\x1a\n", IM_KIND_PNG},
                  {"GIF8", IM_KIND_GIF},
                  {"%PDF-", IM_KIND_PDF},
                  {"Gwyddion Simple Field", IM_KIND_GSF},
                  {"(fftw-", IM_KIND_WISDOM},
                  {"<?xml", IM_KIND_SVG},
                  {"<svg", IM_KIND_SVG},
                  {"{", IM_KIND_JSON}};
    if (length == 0)
        return IM_KIND_NONE;
    for (size_t i = 0; i < sizeof MAGICS / sizeof MAGICS[0]; ++i)
        if (starts_with(head, length, MAGICS[i].magic))
            return MAGICS[i].kind;
    if (length >= 8 && memcmp(head + 4, "ftyp", 4) == 0)
        return IM_KIND_MP4;
    return memchr(head, '\0', length) ? IM_KIND_BINARY : text_kind(head, length);
}

enum { HEAD_BYTES = 512 };

static enum im_file_kind kind_of_descriptor(int fd)
{
    char head[HEAD_BYTES];
    ssize_t length = pread(fd, head, sizeof head, 0);
    return im_file_kind_of_bytes(head, length > 0 ? (size_t)length : 0);
}

int im_file_kind_of(const char *path, enum im_file_kind *kind)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(kind, "kind");
    struct stat info;
    *kind = IM_KIND_NONE;
    if (stat(path, &info) != 0)
        return IM_OK;
    if (!S_ISREG(info.st_mode))
        return im_fail(IM_EINVAL, "%s is not a regular file", path);
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return IM_OK; /* unreadable: its writer will report it */
    *kind = kind_of_descriptor(fd);
    close(fd);
    return IM_OK;
}

int output_check_replace(const char *path, int written_fd)
{
    struct stat info;
    if (lstat(path, &info) != 0 || !S_ISREG(info.st_mode) || info.st_size == 0)
        return IM_OK;
    enum im_file_kind existing, written = kind_of_descriptor(written_fd);
    if (im_file_kind_of(path, &existing) != IM_OK || existing == IM_KIND_NONE || existing == written)
        return IM_OK;
    return im_fail(IM_EINVAL,
                   "%s holds %s, not %s like the file written here: it was left as it is (remove it "
                   "or write elsewhere)",
                   path, im_file_kind_name(existing), im_file_kind_name(written));
}
