/* Internal: a counter-based random generator. A value depends only on its key, never on the order
 * in which keys are drawn, so parallel loops give the same numbers for any thread count. */
#ifndef INDENTMAP_CORE_RANDOM_H
#define INDENTMAP_CORE_RANDOM_H

#include <stdint.h>

/* SplitMix64's finaliser: a bijective 64-bit mix with full avalanche. */
static inline uint64_t mix64(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

/* Hash of a seed and two signed integer coordinates. */
static inline uint64_t hash3(uint64_t seed, int32_t a, int32_t b)
{
    uint64_t h = mix64(seed);
    h = mix64(h ^ (uint64_t)(uint32_t)a);
    return mix64(h ^ ((uint64_t)(uint32_t)b << 32));
}

/* Uniform double in (0, 1] from the top 53 bits of a hash. */
static inline double uniform_open0(uint64_t h) { return (double)((h >> 11) + 1u) * 0x1.0p-53; }

#endif
