/* Lines of text above a text file's numbers, and the line scans they tell apart from maps. */
#include "formats/text_preamble.h"

#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "indentmap/status.h"
#include "formats/readers.h"
#include "core/number.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* Exports recognised by their first line of text: the profilers that write only profiles this way. */
static const struct {
    const char *first_line, *what;
} VENDORS[] = {
    {"Scan Parameters", "a Bruker Dektak profilometer's CSV export of a stylus profile"},
};

int text_preamble_is_text(const char *line)
{
    const char *at = line + strspn(line, " \t\r\n");
    if (!*at)
        return 0;
    char *end;
    (void)number_parse(at, &end); /* a name that starts like "inf" or "nan" ("info") is a name */
    return end == at || (isalpha((unsigned char)*at) && (isalnum((unsigned char)*end) || *end == '_'));
}

/* line without leading blanks, up to its end of line, control bytes as '?', cut to fit out (size
 * bytes) between UTF-8 characters. */
static void copy_visible(char *out, size_t size, const char *line)
{
    line += strspn(line, " \t");
    size_t used = 0;
    for (; line[used] && line[used] != '\r' && line[used] != '\n' && used + 1 < size; ++used)
        out[used] = (unsigned char)line[used] < 0x20 || line[used] == 0x7f ? '?' : line[used];
    if (line[used] && line[used] != '\r' && line[used] != '\n')
        while (used > 0 && ((unsigned char)out[used] & 0xc0) == 0x80) /* out[used] would start the next */
            --used;
    out[used] = '\0';
}

/* The separators between a row's fields: commas, semicolons or tabs when it has any (names may hold
 * blanks: "x in µm"), else blanks. */
static const char *field_separators(const char *line) { return strpbrk(line, ",;\t") ? ",;\t\r\n" : " \r\n"; }

/* The first word of a field (after blanks and a quote), lowercased, into word. */
static void first_word(const char *field, size_t length, char *word, size_t size)
{
    size_t skip = strspn(field, " \"'"), used = 0;
    for (size_t k = skip; k < length && isalnum((unsigned char)field[k]) && used + 1 < size; ++k)
        word[used++] = (char)tolower((unsigned char)field[k]);
    word[used] = '\0';
}

static int names_an_index(const char *word)
{
    return !strcmp(word, "index") || !strcmp(word, "no") || !strcmp(word, "nr") || !strcmp(word, "point");
}

static int names_a_validity_flag(const char *word) { return !strcmp(word, "valid") || !strcmp(word, "validity"); }

/* Finds the columns a row of names calls an index or a validity flag; the number of names. */
static int find_index_and_validity(text_preamble *preamble, const char *line)
{
    const char *separators = field_separators(line);
    preamble->index_column = preamble->valid_column = 0;
    int count = 0;
    for (const char *at = line + strspn(line, separators); *at; at += strspn(at, separators)) {
        size_t length = strcspn(at, separators);
        char word[24];
        first_word(at, length, word, sizeof word);
        ++count;
        if (names_an_index(word) && !preamble->index_column) {
            preamble->index_column = count;
            memcpy(preamble->index_name, word, sizeof word);
        } else if (names_a_validity_flag(word) && !preamble->valid_column) {
            preamble->valid_column = count;
            memcpy(preamble->valid_name, word, sizeof word);
        }
        at += length;
    }
    return count;
}

/* 1 when each field of line is a unit: in brackets ("[mm]", "(1/0)") or a length unit's name. */
static int is_row_of_units(const char *line)
{
    const char *separators = field_separators(line);
    int fields = 0;
    for (const char *at = line + strspn(line, separators); *at; at += strspn(at, separators), ++fields) {
        size_t length = strcspn(at, separators);
        char field[32];
        if (length >= sizeof field)
            return 0;
        memcpy(field, at, length);
        field[length] = '\0';
        char *close = field[0] == '[' ? strchr(field, ']') : field[0] == '(' ? strchr(field, ')') : NULL;
        char *tail = close ? close + 1 + strspn(close + 1, " \"'") : NULL;
        if (!(tail && *tail == '\0') && im_length_unit_metres(field, NULL) == 0.0)
            return 0;
        at += length;
    }
    return fields > 0;
}

void text_preamble_take(text_preamble *preamble, long line_number, const char *line, const char *names_refusal)
{
    if (!preamble->lines++) {
        preamble->first_line = line_number;
        copy_visible(preamble->first, sizeof preamble->first, line);
        for (size_t k = 0; k < sizeof VENDORS / sizeof VENDORS[0]; ++k)
            if (strcmp(preamble->first, VENDORS[k].first_line) == 0)
                preamble->vendor = VENDORS[k].what;
    }
    if (is_row_of_units(line)) {
        preamble->units_line = line_number;
        copy_visible(preamble->units, sizeof preamble->units, line);
        return;
    }
    preamble->names_line = line_number;
    copy_visible(preamble->names, sizeof preamble->names, line);
    snprintf(preamble->names_refusal, sizeof preamble->names_refusal, "%s", names_refusal);
    preamble->names_fields = find_index_and_validity(preamble, line);
}

void text_preamble_take_count(text_preamble *preamble, long line_number, double count)
{
    ++preamble->lines;
    preamble->count_line = line_number;
    preamble->count = count;
}

/* What stood above the numbers, for a message: "the header row 'x,h' (line 1) and a row of units ...". */
static void describe_preamble(const text_preamble *preamble, char *out, size_t size)
{
    size_t used = 0;
    out[0] = '\0';
    if (preamble->vendor)
        used += (size_t)snprintf(out, size, "%s ('%s', line %ld)", preamble->vendor, preamble->first,
                                 preamble->first_line);
    if (preamble->names_line && used < size)
        used += (size_t)snprintf(out + used, size - used, "%sthe header row '%s' (line %ld)", used ? ", " : "",
                                 preamble->names, preamble->names_line);
    if (preamble->units_line && used < size)
        used += (size_t)snprintf(out + used, size - used, "%sa row of units '%s' (line %ld)", used ? ", " : "",
                                 preamble->units, preamble->units_line);
    if (preamble->count_line && used < size)
        snprintf(out + used, size - used, "%sa lone number, %g (line %ld)", used ? ", " : "", preamble->count,
                 preamble->count_line);
}

static int refuse_line_scan(const char *path, const text_preamble *preamble, long columns, long rows, int index,
                            int valid)
{
    char above[400], beside_index[64] = "", beside_valid[64] = "";
    describe_preamble(preamble, above, sizeof above);
    if (index)
        snprintf(beside_index, sizeof beside_index, ", beside an index column '%s'", preamble->index_name);
    if (valid)
        snprintf(beside_valid, sizeof beside_valid, "%s a validity column '%s'", index ? " and" : ", beside",
                 preamble->valid_name);
    long profile = columns - index - valid;
    return im_fail(IM_EFORMAT,
                   "%s: %ld column%s x %ld row%s of numbers under %s: " LINE_SCAN_REFUSAL
                   " (%s%s%s); " LINE_SCAN_ADVICE,
                   path, columns, columns == 1 ? "" : "s", rows, rows == 1 ? "" : "s", above,
                   profile == 1 ? "heights" : "positions and heights", beside_index, beside_valid);
}

int text_preamble_refuse(const char *path, const text_preamble *preamble, long columns, long rows)
{
    int named = preamble->names_line && preamble->names_fields == columns; /* its names are the columns' */
    int index = named && preamble->index_column, valid = named && preamble->valid_column;
    long profile = columns - index - valid;
    if (rows > 0 && profile >= 1 && profile <= 2)
        return refuse_line_scan(path, preamble, columns, rows, index, valid);
    if (rows == 0)
        return im_fail(IM_EFORMAT,
                       "%s: no numbers: %ld line%s of text (line %ld: '%s'): expected a matrix of "
                       "heights, or x y z points under a header row naming x, y and a height",
                       path, preamble->lines, preamble->lines == 1 ? "" : "s", preamble->first_line, preamble->first);
    if (preamble->names_refusal[0])
        return im_fail(IM_EFORMAT, "%s", preamble->names_refusal);
    if (!preamble->first_line)
        return im_fail(IM_EFORMAT,
                       "%s:%ld: a lone number, %g, above rows of %ld values: expected a matrix of "
                       "heights with no count above it",
                       path, preamble->count_line, preamble->count, columns);
    return im_fail(IM_EFORMAT,
                   "%s:%ld: '%s' is text above %ld columns of numbers: expected a matrix of heights "
                   "with no text above it but '#' comments, or x y z points under a header row naming x, y and a "
                   "height",
                   path, preamble->first_line, preamble->first, columns);
}
