#include "cli/cli.h"

#include "indentmap/io.h"
#include "indentmap/formats.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "core/number.h"

#include <errno.h>
#include <getopt.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
    double value = number_parse(text, &end);
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

int cli_parse_length_unit(const char *option, const char *text, char *out)
{
    const char *canonical = text;
    if (strlen(text) >= 16 || im_length_unit_metres(text, &canonical) == 0.0) {
        fprintf(stderr, "indentmap: %s '%s': expected a length unit (m, cm, mm, \u00b5m or um, nm, pm, \u00c5)\n",
                option, text);
        return -1;
    }
    snprintf(out, 16, "%s", canonical);
    return 0;
}

int cli_parse_channel(const char *text, char *out)
{
    if (!text[0] || strlen(text) >= 64) {
        fprintf(stderr, "indentmap: --channel '%.70s': expected a channel's index or title of 1 to 63 bytes\n", text);
        return -1;
    }
    snprintf(out, 64, "%s", text);
    return 0;
}

int cli_parse_npy_order(const char *text, enum im_npy_order *out)
{
    if (strcmp(text, "yx") == 0 || strcmp(text, "xy") == 0) {
        *out = text[0] == 'x' ? IM_NPY_ORDER_XY : IM_NPY_ORDER_YX;
        return 0;
    }
    fprintf(stderr,
            "indentmap: --npy-order '%.20s': expected yx (rows are y) or xy (the first index is x, as "
            "SurfaceTopography's heights() arrays)\n",
            text);
    return -1;
}

int cli_parse_path(const char *option, const char *text, const char **out)
{
    if (text[0] == '\0') {
        fprintf(stderr, "indentmap: %s '': expected a file or folder name\n", option);
        return -1;
    }
    *out = text;
    return 0;
}

int cli_parse_name(const char *option, const char *text, char *out, size_t size)
{
    size_t length = strlen(text);
    if (length == 0 || length >= size || strpbrk(text, " \t\n\"\\") != NULL) {
        fprintf(stderr, "indentmap: %s '%s': expected a unit name of 1 to %zu bytes, no blanks or quotes\n", option,
                text, size - 1);
        return -1;
    }
    memcpy(out, text, length + 1);
    return 0;
}

int cli_report(int status)
{
    fprintf(stderr, "indentmap: %s\n", im_last_error()[0] ? im_last_error() : im_strstatus(status));
    return (status == IM_EINVAL || status == IM_EFORMAT || status == IM_ENOMEM) ? CLI_EXIT_USAGE : CLI_EXIT_FAILURE;
}

/* An option with a value given before (seen[index] its first value): refused, naming it, whatever the
 * option (a value is one setting: the last must not win silently over the first, issue T10). Flags may be
 * repeated: saying one twice changes nothing. */
static int refuse_repeated_value(const struct option *option, const char **seen, const char *arg)
{
    if (option->has_arg == no_argument)
        return 0;
    if (*seen) {
        fprintf(stderr, "indentmap: --%s given twice ('%s', then '%s'): expected it once\n", option->name, *seen,
                arg);
        return -1;
    }
    *seen = arg;
    return 0;
}

int cli_parse_options(int argc, char **argv, const struct option *options, int help_code, void (*usage)(FILE *),
                      int (*apply)(int code, const char *arg, void *state), void *state)
{
    enum { OPTIONS_MAX = 128 }; /* more than any subcommand's table */
    const char *seen[OPTIONS_MAX] = {0};
    int code, index = -1, count = 0;
    while (options[count].name)
        ++count;
    if (count > OPTIONS_MAX) {
        fprintf(stderr, "indentmap: %d options: expected at most %d (OPTIONS_MAX, parse.c)\n", count, OPTIONS_MAX);
        return -1;
    }
    optind = 1;
    while ((code = getopt_long(argc, argv, "h", options, &index)) != -1) {
        if (code == help_code || code == 'h') {
            usage(stdout);
            return 1;
        }
        if (code == '?' || (index >= 0 && refuse_repeated_value(&options[index], &seen[index], optarg) != 0) ||
            apply(code, optarg, state) != 0)
            return -1;
        index = -1; /* getopt_long sets it for long options only */
    }
    return 0;
}

int cli_parse_adhesion_law(const char *text, int *law)
{
    if (im_adhesion_law_parse(text, law) == IM_OK)
        return 0;
    fprintf(stderr, "indentmap: --adhesion-law: %s\n", im_last_error());
    return -1;
}

/* ---- outputs never overwrite inputs ---- */

int cli_protect_inputs(const char *const *inputs, int count)
{
    for (int i = 0; i < count; ++i)
        if (inputs[i] && im_output_protect(inputs[i]) != IM_OK) {
            fprintf(stderr, "indentmap: %s\n", im_last_error());
            return -1;
        }
    return 0;
}

int cli_check_output_file(const char *option, const char *output)
{
    if (!output || im_output_check(output) == IM_OK)
        return 0;
    fprintf(stderr, "indentmap: %s %s\n", option, im_last_error());
    return -1;
}
