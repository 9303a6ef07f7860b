/* hash.glsl: stateless integer hash shared with the CPU. hash_u32 is
 * lowbias32, bit-identical to core_hash_u32 in src/core/core_rng.c;
 * hash_float maps to [0,1) with the top 24 bits, identical to
 * core_hash_float (exact in float on both sides). */
#ifndef HASH_GLSL
#define HASH_GLSL

uint hash_u32(uint x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

float hash_float(uint x)
{
    return float(hash_u32(x) >> 8) * (1.0 / 16777216.0);
}

#endif
