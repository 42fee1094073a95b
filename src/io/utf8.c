/* Paths in records (run.json, sidecars): a path is bytes, JSON text is UTF-8. */
#include "indentmap/io.h"
#include "core/args.h"

#include <stdio.h>
#include <string.h>

/* The length of the valid UTF-8 sequence at s (1 to 4 bytes), or 0 if none starts there. */
static size_t utf8_sequence(const unsigned char *s)
{
    size_t length = s[0] < 0x80             ? 1
                    : (s[0] & 0xe0) == 0xc0 ? 2
                    : (s[0] & 0xf0) == 0xe0 ? 3
                    : (s[0] & 0xf8) == 0xf0 ? 4
                                            : 0;
    for (size_t i = 1; i < length; ++i)
        if ((s[i] & 0xc0) != 0x80)
            return 0;
    unsigned long code = length == 1   ? s[0]
                         : length == 2 ? s[0] & 0x1fUL
                         : length == 3 ? s[0] & 0x0fUL
                                       : s[0] & 0x07UL;
    for (size_t i = 1; i < length; ++i)
        code = code << 6 | (s[i] & 0x3fUL);
    static const unsigned long SMALLEST[5] = {0, 0, 0x80, 0x800, 0x10000}; /* overlong forms are invalid */
    if (length == 0 || code < SMALLEST[length] || code > 0x10ffff || (code >= 0xd800 && code <= 0xdfff))
        return 0;
    return length;
}

static int is_utf8(const char *text)
{
    for (const unsigned char *s = (const unsigned char *)text; *s;) {
        size_t length = utf8_sequence(s);
        if (!length)
            return 0;
        s += length;
    }
    return 1;
}

int im_path_utf8(const char *path, char *out, size_t size)
{
    ARG_REQUIRE_OR(out, "out", 0);
    if (size > 0)
        out[0] = '\0'; /* a NULL path gives "" */
    ARG_REQUIRE_OR(path, "path", 0);
    if (is_utf8(path)) {
        snprintf(out, size, "%s", path);
        return 0;
    }
    size_t used = 0;
    for (const unsigned char *s = (const unsigned char *)path; *s && used + 5 < size;) {
        size_t length = utf8_sequence(s);
        if (length && *s != '\\') {
            memcpy(out + used, s, length);
            used += length;
            s += length;
        } else {
            used += (size_t)snprintf(out + used, size - used, *s == '\\' ? "\\\\" : "\\x%02x", *s);
            ++s;
        }
    }
    if (size > 0)
        out[used < size ? used : size - 1] = '\0';
    return 1;
}
