/* grass_version: the installed library's version (libmeadow alone; the
 * in-tree program has its own). */
#include "grass/grass.h"

const char *grass_version(void) { return MEADOW_VERSION; }
