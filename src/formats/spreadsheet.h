/* formats/spreadsheet.h: Office Open XML spreadsheets (.xlsx), which profilers' software exports (Mitutoyo
 * SurfTest): recognised, their sheets' columns of numbers counted, and refused naming what they hold. */
#ifndef INDENTMAP_FORMATS_SPREADSHEET_H
#define INDENTMAP_FORMATS_SPREADSHEET_H

/* 1 when path is a zip archive holding xl/workbook.xml (an Office Open XML spreadsheet), else 0. */
int spreadsheet_is_one(const char *path);

/* Refuses the spreadsheet at path (always IM_EFORMAT naming it, or IM_ENOMEM): as a line scan when its
 * fullest sheet holds numbers in at most two columns (position and height), naming the sheet, the
 * columns and the rows; else as a spreadsheet no reader here reads, with the size of that sheet. */
int spreadsheet_refuse(const char *path);

#endif
