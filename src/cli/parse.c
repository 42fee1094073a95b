#include "cli/cli.h"

#include "indentmap/status.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

int cli_parse_int(const char *option, const char *text, long min, long max, int *out)
{
    char *end;
    errno = 0;
    long value = strtol(text, &end, 10);
    if (end == text || *end != '\0' || errno == ERANGE) {
        fprintf(stderr, "indentmap: %s: '%s' is not an integer\n", option, text);
        return -1;
    }
    if (value < min || value > max) {
        fprintf(stderr, "indentmap: %s = %ld: expected an integer in [%ld, %ld]\n", option, value, min, max);
        return -1;
    }
    *out = (int)value;
    return 0;
}

int cli_parse_u64(const char *option, const char *text, uint64_t *out)
{
    char *end;
    errno = 0;
    unsigned long long value = strtoull(text, &end, 10);
    if (end == text || *end != '\0' || errno == ERANGE || text[0] == '-') {
        fprintf(stderr, "indentmap: %s: '%s' is not a non-negative integer\n", option, text);
        return -1;
    }
    *out = value;
    return 0;
}

int cli_parse_double(const char *option, const char *text, double min, double max, double *out)
{
    char *end;
    double value = strtod(text, &end);
    if (end == text || *end != '\0' || !isfinite(value)) {
        fprintf(stderr, "indentmap: %s: '%s' is not a finite number\n", option, text);
        return -1;
    }
    if (value < min || value > max) {
        fprintf(stderr, "indentmap: %s = %g: expected a number in [%g, %g]\n", option, value, min, max);
        return -1;
    }
    *out = value;
    return 0;
}

int cli_report(int status)
{
    fprintf(stderr, "indentmap: %s\n", im_last_error()[0] ? im_last_error() : im_strstatus(status));
    return (status == IM_EINVAL || status == IM_EFORMAT || status == IM_ENOMEM) ? CLI_EXIT_USAGE
                                                                               : CLI_EXIT_FAILURE;
}

int cli_parse_options(int argc, char **argv, const struct option *options, int help_code, void (*usage)(FILE *),
                      int (*apply)(int code, const char *arg, void *state), void *state)
{
    int code;
    optind = 1;
    while ((code = getopt_long(argc, argv, "h", options, NULL)) != -1) {
        if (code == help_code || code == 'h') {
            usage(stdout);
            return 1;
        }
        if (code == '?' || apply(code, optarg, state) != 0)
            return -1;
    }
    return 0;
}
