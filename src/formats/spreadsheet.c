/* Office Open XML spreadsheets: a zip (libzip) of SpreadsheetML parts (libxml2's streaming reader,
 * without network access), looked into only to say what a sheet holds. */
#include "formats/spreadsheet.h"

#include "indentmap/field.h"
#include "indentmap/status.h"
#include "formats/readers.h"
#include "formats/zip_entry.h"

#include <libxml/xmlreader.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zip.h>

enum { MAX_COLUMNS = 16384 }; /* Excel's XFD */
static const size_t MAX_PART_BYTES = (size_t)1 << 28;

/* Numeric cells counted per column of one sheet. */
typedef struct sheet_numbers {
    long *per_column;      /* MAX_COLUMNS counts */
    long fullest;          /* the largest count */
    int columns_near_full; /* columns holding at least half the fullest's count */
    int first_column, second_column;
} sheet_numbers;

int spreadsheet_is_one(const char *path)
{
    zip_t *archive = zip_open(path, ZIP_RDONLY, NULL);
    int found = archive && zip_name_locate(archive, "xl/workbook.xml", 0) >= 0;
    if (archive)
        zip_discard(archive);
    return found;
}

/* The column (from 0) of a cell reference like "E12", or -1. */
static int column_of(const char *reference)
{
    int column = 0, letters = 0;
    for (; reference[letters] >= 'A' && reference[letters] <= 'Z' && letters < 3; ++letters)
        column = column * 26 + (reference[letters] - 'A' + 1);
    return letters && column <= MAX_COLUMNS ? column - 1 : -1;
}

/* Counts the cell the reader stands on when it holds a number: a non-empty <c> of no type or "n". */
static void count_cell(xmlTextReaderPtr reader, sheet_numbers *numbers)
{
    if (xmlTextReaderNodeType(reader) != XML_READER_TYPE_ELEMENT || xmlTextReaderIsEmptyElement(reader) ||
        strcmp((const char *)xmlTextReaderConstLocalName(reader), "c") != 0)
        return;
    xmlChar *type = xmlTextReaderGetAttribute(reader, (const xmlChar *)"t");
    xmlChar *reference = xmlTextReaderGetAttribute(reader, (const xmlChar *)"r");
    int column = reference ? column_of((const char *)reference) : -1;
    if (column >= 0 && (!type || strcmp((const char *)type, "n") == 0))
        ++numbers->per_column[column];
    xmlFree(type);
    xmlFree(reference);
}

/* The fullest column, and the columns holding at least half as many numbers. */
static void summarise(sheet_numbers *numbers)
{
    numbers->fullest = 0;
    for (int k = 0; k < MAX_COLUMNS; ++k)
        numbers->fullest = numbers->per_column[k] > numbers->fullest ? numbers->per_column[k] : numbers->fullest;
    numbers->columns_near_full = 0;
    numbers->first_column = numbers->second_column = -1;
    for (int k = 0; k < MAX_COLUMNS && numbers->fullest > 0; ++k) {
        if (2 * numbers->per_column[k] < numbers->fullest)
            continue;
        if (numbers->columns_near_full++ == 0)
            numbers->first_column = k;
        else if (numbers->columns_near_full == 2)
            numbers->second_column = k;
    }
}

static int count_sheet(zip_t *archive, const char *path, const char *name, sheet_numbers *numbers)
{
    char *text;
    size_t size;
    int status = zip_entry_read(archive, path, name, MAX_PART_BYTES, "a spreadsheet without the sheet it lists",
                                &text, &size);
    if (status != IM_OK)
        return status;
    memset(numbers->per_column, 0, MAX_COLUMNS * sizeof *numbers->per_column);
    xmlTextReaderPtr reader = xmlReaderForMemory(text, (int)size, name, NULL,
                                                 XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
    int step = reader ? xmlTextReaderRead(reader) : -1;
    for (; step == 1; step = xmlTextReaderRead(reader))
        count_cell(reader, numbers);
    if (reader)
        xmlFreeTextReader(reader);
    free(text);
    if (step != 0)
        return im_fail(IM_EFORMAT, "%s: spreadsheet part %s is not well-formed XML", path, name);
    summarise(numbers);
    return IM_OK;
}

/* A column's letters ("E") from its index. */
static void column_letters(int column, char out[4])
{
    char reversed[4];
    int length = 0;
    for (int k = column + 1; k > 0 && length < 3; k = (k - 1) / 26)
        reversed[length++] = (char)('A' + (k - 1) % 26);
    for (int k = 0; k < length; ++k)
        out[k] = reversed[length - 1 - k];
    out[length] = '\0';
}

/* 1 when the archive's shared strings name Mitutoyo's SurfTest, whose exports are profiles. */
static int is_surftest_export(zip_t *archive, const char *path)
{
    char *text = NULL;
    size_t size;
    int found = zip_name_locate(archive, "xl/sharedStrings.xml", 0) >= 0 &&
                zip_entry_read(archive, path, "xl/sharedStrings.xml", MAX_PART_BYTES, "(no shared strings)", &text,
                               &size) == IM_OK &&
                strstr(text, "SurfTest") != NULL;
    free(text);
    return found;
}

static int refuse_sheet(const char *path, const char *what, const char *name, const sheet_numbers *sheet)
{
    if (sheet->fullest == 0)
        return im_fail(IM_EFORMAT, "%s: %s whose sheets hold no numbers: expected a surface file", path, what);
    char first[4], second[4] = "";
    column_letters(sheet->first_column, first);
    if (sheet->second_column >= 0)
        column_letters(sheet->second_column, second);
    if (sheet->columns_near_full <= 2)
        return im_fail(IM_EFORMAT,
                       "%s: %s: its fullest sheet, %s, holds numbers in %d column%s (%s%s%s) of %ld "
                       "rows: " LINE_SCAN_REFUSAL " (positions and heights); " LINE_SCAN_ADVICE,
                       path, what, name, sheet->columns_near_full, sheet->columns_near_full == 1 ? "" : "s", first,
                       second[0] ? ", " : "", second, sheet->fullest);
    return im_fail(IM_EFORMAT,
                   "%s: %s: no reader here reads spreadsheets; its fullest sheet, %s, holds numbers in %d "
                   "columns (from %s) of %ld rows: save that sheet's heights as text (CSV) to read them as a matrix",
                   path, what, name, sheet->columns_near_full, first, sheet->fullest);
}

/* Each worksheet counted; the fullest kept in *fullest, its part name in name. */
static int count_sheets(zip_t *archive, const char *path, sheet_numbers *fullest, char *name, size_t size)
{
    sheet_numbers sheet = {.per_column = calloc(MAX_COLUMNS, sizeof(long))};
    if (!sheet.per_column)
        return im_fail(IM_ENOMEM, "%s: allocation failed", path);
    int status = IM_OK;
    zip_int64_t entries = zip_get_num_entries(archive, 0);
    for (zip_int64_t k = 0; status == IM_OK && k < entries; ++k) {
        const char *entry = zip_get_name(archive, (zip_uint64_t)k, 0);
        if (!entry || strncmp(entry, "xl/worksheets/", 14) != 0 || strchr(entry + 14, '/') ||
            strcmp(entry + strlen(entry) - 4, ".xml") != 0)
            continue;
        status = count_sheet(archive, path, entry, &sheet);
        if (status == IM_OK && sheet.fullest > fullest->fullest) {
            *fullest = (sheet_numbers){.fullest = sheet.fullest,
                                       .columns_near_full = sheet.columns_near_full,
                                       .first_column = sheet.first_column,
                                       .second_column = sheet.second_column};
            snprintf(name, size, "%s", entry);
        }
    }
    free(sheet.per_column);
    return status;
}

int spreadsheet_refuse(const char *path)
{
    int error = 0;
    zip_t *archive = zip_open(path, ZIP_RDONLY, &error);
    if (!archive)
        return im_fail(IM_EFORMAT, "%s: an Office Open XML spreadsheet that cannot be opened (zip error %d)", path,
                       error);
    const char *what = is_surftest_export(archive, path)
                           ? "an Office Open XML spreadsheet (.xlsx), a Mitutoyo SurfTest export"
                           : "an Office Open XML spreadsheet (.xlsx)";
    sheet_numbers fullest = {0};
    char name[256] = "";
    int status = count_sheets(archive, path, &fullest, name, sizeof name);
    zip_discard(archive);
    return status == IM_OK ? refuse_sheet(path, what, name, &fullest) : status;
}
