/* The library's own version, for programs that check the one they run with (version.h). */
#include "indentmap/version.h"

const char *im_version(void) { return IM_VERSION_STRING; }
