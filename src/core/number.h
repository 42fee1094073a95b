/* Internal: a number written in decimal, as every reader of text in indentmap takes it (options, scene
 * values, text and instrument files). strtod alone also reads C99's hexadecimal floating point ("0x10" is
 * 16, "0x1p3" 8), which no instrument writes and a user means only by mistake (issue T11): here "0x..."
 * ends after its "0", as in a reader of decimals, so the caller's check that the whole field was read
 * refuses it with the caller's message (the option, or the file and line). Everything else is strtod's:
 * signs, exponents, leading blanks, "inf", "nan" (the formats' missing points). */
#ifndef INDENTMAP_CORE_NUMBER_H
#define INDENTMAP_CORE_NUMBER_H

/* strtod(text, end) for decimal text; "0x..." (after blanks and a sign) reads as 0 with *end at the x.
 * end may be NULL. */
double number_parse(const char *text, char **end);

#endif
