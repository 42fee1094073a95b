#include "core/number.h"

#include <stdlib.h>
#include <string.h>

double number_parse(const char *text, char **end)
{
    const char *sign = text + strspn(text, " \t\n\v\f\r");
    const char *digits = sign + (*sign == '+' || *sign == '-');
    if (digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) {
        if (end)
            *end = (char *)(digits + 1);
        return *sign == '-' ? -0.0 : 0.0;
    }
    return strtod(text, end);
}
