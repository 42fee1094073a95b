#include "fuzz_file.h"

#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

static char input_path[4096];
static int input_fd = -1;

static void remove_input(void)
{
    if (input_fd >= 0)
        unlink(input_path);
}

static void create_input(void)
{
    const char *dir = getenv("TMPDIR");
    snprintf(input_path, sizeof input_path, "%s/indentmap-fuzz-XXXXXX", dir && *dir ? dir : "/tmp");
    input_fd = mkstemp(input_path);
    if (input_fd < 0) {
        perror("fuzz: mkstemp");
        abort();
    }
    atexit(remove_input);
}

const char *fuzz_write_input(const uint8_t *data, size_t size)
{
    if (input_fd < 0)
        create_input();
    size_t written = 0;
    while (written < size) {
        ssize_t n = pwrite(input_fd, data + written, size - written, (off_t)written);
        if (n <= 0) {
            perror("fuzz: pwrite");
            abort();
        }
        written += (size_t)n;
    }
    if (ftruncate(input_fd, (off_t)size) != 0) {
        perror("fuzz: ftruncate");
        abort();
    }
    return input_path;
}
