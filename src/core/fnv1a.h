/* Internal: FNV-1a (64 bits), the quick hash of bytes that kept results' keys and checksums
 * (scene/key.c) and the MPI ranks' agreement on their inputs (mpi/inputs.c) compare. Not a
 * cryptographic hash: run records name their input files by SHA-256 (io/checksum.h). */
#ifndef INDENTMAP_CORE_FNV1A_H
#define INDENTMAP_CORE_FNV1A_H

#include <stddef.h>
#include <stdint.h>

#define FNV1A_START UINT64_C(0xcbf29ce484222325) /* the hash of no bytes */

/* hash extended by length bytes: fnv1a_add(fnv1a_add(FNV1A_START, a, n), b, m) is the hash of a then b. */
static inline uint64_t fnv1a_add(uint64_t hash, const void *bytes, size_t length)
{
    const unsigned char *byte = bytes;
    for (size_t i = 0; i < length; ++i) {
        hash ^= byte[i];
        hash *= UINT64_C(0x100000001b3);
    }
    return hash;
}

#endif
