/* Internal: the memory probe behind field.h's im_memory_available and im_memory_check (memory.c). */
#ifndef INDENTMAP_CORE_MEMORY_H
#define INDENTMAP_CORE_MEMORY_H

#include <stddef.h>

/* MemAvailable of /proc/meminfo in bytes; 0 if it cannot be read. */
size_t memory_meminfo_available(void);

/* This process's virtual size in bytes (/proc/self/statm); 0 if it cannot be read. */
size_t memory_virtual_size(void);

#endif
