/* core_rng: PCG32 generator and stateless hashes shared with the shaders. */
#include "core.h"

void core_rng_seed(core_rng_t *rng, uint64_t seed, uint64_t stream)
{
    rng->state = 0u;
    rng->inc = (stream << 1u) | 1u;
    core_rng_u32(rng);
    rng->state += seed;
    core_rng_u32(rng);
}

uint32_t core_rng_u32(core_rng_t *rng)
{
    uint64_t old = rng->state;
    rng->state = old * 6364136223846793005ULL + rng->inc;
    uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = (uint32_t)(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((-rot) & 31));
}

float core_rng_float(core_rng_t *rng)
{
    return (float)(core_rng_u32(rng) >> 8) * (1.0f / 16777216.0f);
}

float core_rng_range(core_rng_t *rng, float lo, float hi)
{
    return lo + (hi - lo) * core_rng_float(rng);
}

uint32_t core_hash_u32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

float core_hash_float(uint32_t x)
{
    return (float)(core_hash_u32(x) >> 8) * (1.0f / 16777216.0f);
}

uint64_t core_hash_bytes(const void *data, size_t size, uint64_t h)
{
    const uint8_t *p = data;
    if (h == 0) h = 1469598103934665603ULL;
    for (size_t i = 0; i < size; i++) {
        h ^= p[i];
        h *= 1099511628211ULL;
    }
    return h;
}
