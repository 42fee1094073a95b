/* indent's arguments in its run record, and the run made again from them (`indent --from-record`). */
#include "cli/indent_record.h"
#include "cli/figure_provenance.h"
#include "front/front.h"

#include "indentmap/io.h"
#include "indentmap/status.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int append_text(indent_arguments *arguments, const char *text)
{
    char utf8[4 * PATH_MAX + 1];
    arguments->escaped |= im_path_utf8(text, utf8, sizeof utf8);
    if (!arguments->list)
        arguments->list = json_array();
    if (!arguments->list || json_array_append_new(arguments->list, json_string(utf8)) != 0)
        return im_fail(IM_ENOMEM, "run.json: out of memory");
    return IM_OK;
}

int indent_arguments_add(indent_arguments *arguments, const char *option, const char *value, int is_path)
{
    char absolute[PATH_MAX], dashed[64];
    snprintf(dashed, sizeof dashed, "--%s", option ? option : "");
    int status = option ? append_text(arguments, dashed) : IM_OK;
    if (status == IM_OK && value && is_path)
        status = im_path_absolute(value, absolute, sizeof absolute);
    if (status == IM_OK && value)
        status = append_text(arguments, is_path ? absolute : value);
    return status;
}

char *indent_arguments_command(const indent_arguments *arguments)
{
    static const char PROGRAM[] = "indentmap indent";
    size_t size = sizeof PROGRAM, i;
    json_t *argument;
    json_array_foreach(arguments->list, i, argument) size += cli_shell_word_room(json_string_value(argument));
    char *text = malloc(size);
    if (!text)
        return NULL;
    size_t used = (size_t)snprintf(text, size, "%s", PROGRAM);
    json_array_foreach(arguments->list, i, argument)
        used = cli_shell_append(text, size, used, json_string_value(argument));
    return text;
}

/* Each recorded input still has its recorded SHA-256 (front.h: run_record_check_input). */
static int check_inputs(const char *record, const json_t *root)
{
    json_t *inputs = json_object_get(root, "inputs");
    if (!json_is_array(inputs))
        return im_fail(IM_EFORMAT, "%s: no inputs: expected the list of the run's input files (empty for none)",
                       record);
    size_t i;
    json_t *input;
    json_array_foreach(inputs, i, input)
    {
        const char *key = json_string_value(json_object_get(input, "key"));
        const char *path = json_string_value(json_object_get(input, "path"));
        const char *sha256 = json_string_value(json_object_get(input, "sha256"));
        if (!key || !path || !sha256)
            return im_fail(IM_EFORMAT, "%s: inputs[%zu]: expected its key, path and sha256", record, i);
        int status = run_record_check_input(record, key, path, sha256);
        if (status != IM_OK)
            return status;
    }
    return IM_OK;
}

/* The record's arguments, each a string; refused when one was recorded escaped. */
static int recorded_arguments(const char *record, const json_t *root, json_t **arguments)
{
    *arguments = json_object_get(root, "arguments");
    if (!json_is_array(*arguments))
        return im_fail(IM_EFORMAT,
                       "%s: no arguments: expected the record of an indent run by a version that keeps "
                       "them (issue 31); run indent with its options instead",
                       record);
    if (json_object_get(root, "arguments_encoding"))
        return im_fail(IM_EFORMAT,
                       "%s: an argument was not UTF-8 and is recorded escaped: its bytes cannot be given "
                       "again; run indent with its options instead",
                       record);
    size_t i;
    json_t *argument;
    json_array_foreach(*arguments, i, argument) if (!json_is_string(argument)) return im_fail(
        IM_EFORMAT, "%s: arguments[%zu]: expected a string", record, i);
    return IM_OK;
}

/* The folder of the record, where its run wrote. */
static int record_folder(const char *record, char *out, size_t size)
{
    const char *slash = strrchr(record, '/');
    int length = slash ? snprintf(out, size, "%.*s", slash == record ? 1 : (int)(slash - record), record)
                       : snprintf(out, size, ".");
    return length >= 0 && (size_t)length < size ? IM_OK : im_fail(IM_EINVAL, "%s: path too long", record);
}

/* "indent", the arguments, --out and the wisdom options into replay->argv. */
static int build_command(const json_t *arguments, const indent_replay_options *given, int estimated,
                         indent_replay *replay)
{
    size_t count = json_array_size(arguments);
    replay->argv = calloc(count + 6, sizeof *replay->argv);
    if (!replay->argv)
        return im_fail(IM_ENOMEM, "--from-record: out of memory");
    char **argv = replay->argv;
    int argc = 0;
    argv[argc++] = "indent";
    for (size_t i = 0; i < count; ++i)
        argv[argc++] = (char *)json_string_value(json_array_get(arguments, i)); /* getopt reads, never writes */
    argv[argc++] = "--out";
    argv[argc++] = replay->out;
    if (given->wisdom) {
        argv[argc++] = "--wisdom";
        argv[argc++] = (char *)given->wisdom;
    } else if (given->no_wisdom || estimated) {
        argv[argc++] = "--no-wisdom";
    }
    replay->argc = argc;
    return IM_OK;
}

static int replay_from(const char *record, const indent_replay_options *given, indent_replay *replay)
{
    json_t *arguments = NULL;
    int status = run_record_check_origin(record, replay->root, "indentmap indent", "an indent run");
    if (status == IM_OK)
        status = recorded_arguments(record, replay->root, &arguments);
    if (status == IM_OK)
        status = check_inputs(record, replay->root);
    if (status == IM_OK && given->out)
        status = snprintf(replay->out, sizeof replay->out, "%s", given->out) < (int)sizeof replay->out
                     ? IM_OK
                     : im_fail(IM_EINVAL, "--out %s: path too long", given->out);
    else if (status == IM_OK)
        status = record_folder(record, replay->out, sizeof replay->out);
    const int estimated = !json_is_true(json_object_get(json_object_get(replay->root, "solver"), "fftw_wisdom"));
    return status == IM_OK ? build_command(arguments, given, estimated, replay) : status;
}

int indent_replay_load(const char *record, const indent_replay_options *given, indent_replay *replay)
{
    *replay = (indent_replay){0};
    int status = run_record_load(record, &replay->root);
    if (status != IM_OK)
        return status;
    status = replay_from(record, given, replay);
    if (status != IM_OK)
        indent_replay_free(replay);
    return status;
}

void indent_replay_free(indent_replay *replay)
{
    json_decref(replay->root);
    free(replay->argv);
    replay->root = NULL;
    replay->argv = NULL;
}
