/* cull_counts.glsl: the culled counts of a workgroup (blade_cull.comp,
 * tiles_cull.comp). Each culled blade adds to its test's word in shared
 * memory; the workgroup then adds each word to the global counter once
 * (one global atomic per culled blade put every blade of a test on one
 * address: the tiles' cull took twice the time with it on the H200). */
#ifndef CULL_COUNTS_GLSL
#define CULL_COUNTS_GLSL

shared uint s_culled[4];

/* Before the workgroup's first barrier. */
void cull_counts_clear()
{
    if (gl_LocalInvocationIndex < 4u) s_culled[gl_LocalInvocationIndex] = 0u;
}

/* A blade culled by test `why` (BLADE_CULL_*, one bit). */
void cull_counts_add(uint why)
{
    atomicAdd(s_culled[findLSB(why)], 1u);
}

/* After a barrier that follows every cull_counts_add: the count this
 * invocation adds to word gl_LocalInvocationIndex of the global counters
 * (0 for invocations past the fourth and for empty words). */
uint cull_counts_mine()
{
    return gl_LocalInvocationIndex < 4u ? s_culled[gl_LocalInvocationIndex] : 0u;
}

#endif
