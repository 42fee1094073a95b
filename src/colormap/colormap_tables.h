/* Internal: exact 256-entry 8-bit colour-map tables (generated, see colormap_tables.c). */
#ifndef INDENTMAP_COLORMAP_TABLES_H
#define INDENTMAP_COLORMAP_TABLES_H

#include <stdint.h>

extern const uint8_t im_colormap_table_viridis[256][3];
extern const uint8_t im_colormap_table_cividis[256][3];
extern const uint8_t im_colormap_table_magma[256][3];
extern const uint8_t im_colormap_table_inferno[256][3];
extern const uint8_t im_colormap_table_grey[256][3];
extern const uint8_t im_colormap_table_tension[256][3]; /* colormap_tension.c */

#endif
