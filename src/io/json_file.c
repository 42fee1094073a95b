/* The JSON records' one writer and reader (json_file.h). */
#include "io/json_file.h"

#include "indentmap/io.h"
#include "indentmap/status.h"

#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The marker of an unsigned integer held as a string: a control character no record's text begins with,
 * then a name. As JSON text (json_dumps escapes the control character): ESCAPED_MARKER. */
#define UNSIGNED_MARKER "\001uint64:"
#define ESCAPED_MARKER "\"\\u0001uint64:"

char *json_text(const json_t *root, size_t flags)
{
    char *text = root ? json_dumps(root, flags) : NULL;
    if (!text)
        return NULL;
    /* Each marked string "\u0001uint64:DIGITS" becomes DIGITS; the text only shrinks. */
    char *read = text, *written = text, *marked;
    const size_t marker = strlen(ESCAPED_MARKER);
    while ((marked = strstr(read, ESCAPED_MARKER))) {
        const char *digits = marked + marker;
        const size_t count = strspn(digits, "-0123456789");
        const int whole = count > 0 && digits[count] == '"'; /* else a string that only begins so */
        const char *from = whole ? digits : marked, *end = whole ? digits + count : digits;
        memmove(written, read, (size_t)(marked - read));
        written += marked - read;
        memmove(written, from, (size_t)(end - from));
        written += end - from;
        read = (char *)end + whole; /* past the closing quote */
    }
    memmove(written, read, strlen(read) + 1);
    return text;
}

int json_file_write(const char *path, const json_t *root)
{
    char *text = json_text(root, JSON_INDENT(2) | JSON_REAL_PRECISION(17));
    if (!text)
        return im_fail(IM_ENOMEM, "%s: cannot build the JSON record", path);
    size_t length = strlen(text);
    text[length] = '\n'; /* json_dumps leaves room: its terminator becomes the newline */
    int status = im_write_file_atomic(path, text, length + 1);
    free(text);
    return status;
}

json_t *json_unsigned(uint64_t value)
{
    if (value <= INT64_MAX)
        return json_integer((json_int_t)value);
    char text[64];
    snprintf(text, sizeof text, UNSIGNED_MARKER "%" PRIu64, value);
    return json_string(text);
}

int json_unsigned_value(const json_t *value, uint64_t *out)
{
    if (json_is_integer(value)) {
        *out = (uint64_t)json_integer_value(value); /* negative: an older file's two's complement */
        return 0;
    }
    const char *text = json_string_value(value);
    const size_t marker = strlen(UNSIGNED_MARKER);
    if (!text || strncmp(text, UNSIGNED_MARKER, marker) != 0 || !(text[marker] >= '0' && text[marker] <= '9'))
        return -1;
    char *end;
    errno = 0;
    unsigned long long parsed = strtoull(text + marker, &end, 10);
    if (errno == ERANGE || *end != '\0')
        return -1;
    *out = (uint64_t)parsed;
    return 0;
}

/* Whether the integer token [start, start + length) (an optional '-' and digits) is beyond the signed
 * 64-bit range. */
static int beyond_signed(const char *start, size_t length)
{
    const int negative = *start == '-';
    const char *digits = start + negative;
    const size_t count = length - (size_t)negative;
    const char *limit = negative ? "9223372036854775808" : "9223372036854775807";
    return count > 19 || (count == 19 && strncmp(digits, limit, 19) > 0);
}

/* text with each integer beyond the signed range, outside strings, written as json_unsigned's marked
 * string; NULL when out of memory. The lines stay as they were (a parse error names the same line). */
static char *mark_big_integers(const char *text)
{
    const size_t length = strlen(text);
    char *out = malloc(2 * length + 1), *o = out;
    for (const char *c = text; out && *c;) {
        if (*c == '"') { /* a string, copied whole with its escapes */
            const char *s = c + 1;
            while (*s && *s != '"')
                s += s[0] == '\\' && s[1] ? 2 : 1;
            s += *s == '"';
            memcpy(o, c, (size_t)(s - c));
            o += s - c;
            c = s;
            continue;
        }
        const size_t sign = *c == '-', integer = sign + strspn(c + sign, "0123456789");
        const size_t number = integer > sign ? integer + strspn(c + integer, "0123456789.eE+-") : 1;
        if (number == integer && beyond_signed(c, integer)) {
            o += sprintf(o, ESCAPED_MARKER "%.*s\"", (int)integer, c);
        } else { /* a character, or a number within the range or with a fraction or exponent, as it is */
            memcpy(o, c, number);
            o += number;
        }
        c += number;
    }
    if (out)
        *o = '\0';
    return out;
}

json_t *json_text_load(const char *text, size_t flags, json_error_t *error)
{
    char *marked = mark_big_integers(text);
    json_t *root = marked ? json_loads(marked, flags, error) : NULL;
    if (!marked && error)
        snprintf(error->text, sizeof error->text, "out of memory");
    free(marked);
    return root;
}

/* A file not read, in jansson's words (line -1: no place in the text): NULL. */
static json_t *not_read(json_error_t *error, const char *verb, const char *path, const char *why)
{
    if (error) {
        *error = (json_error_t){.line = -1, .column = -1};
        snprintf(error->text, sizeof error->text, "unable to %s %s: %s", verb, path, why);
    }
    return NULL;
}

json_t *json_file_load(const char *path, size_t flags, json_error_t *error)
{
    FILE *file = fopen(path, "rb");
    if (!file)
        return not_read(error, "open", path, strerror(errno));
    char *text = NULL;
    size_t length = 0, size = 0;
    const char *failed = NULL; /* why */
    while (!failed && !feof(file)) {
        char *grown = length + 1 < size ? text : realloc(text, size = 2 * size + 4096);
        if (!grown) {
            failed = "out of memory";
            break;
        }
        text = grown;
        length += fread(text + length, 1, size - length - 1, file);
        failed = ferror(file) ? "a read error" : NULL;
    }
    fclose(file);
    json_t *root = failed ? not_read(error, "read", path, failed) : NULL;
    if (!failed) {
        text[length] = '\0';
        root = json_text_load(text, flags, error);
    }
    free(text);
    return root;
}
