/* blade_patch.glsl: the counters of blade mode's cull (blade_cull.comp)
 * and of its patch test on the GPU (blade_patch_cull.comp,
 * blade_patch_list.comp; beyond Jahrmann & Wimmer 2017: the
 * Morton-ordered patches of blade_seed with their boxes). The host zeroes
 * the whole block before the patch test (blade.c blade_gpu_cull) and
 * defines BLADE_PATCH_BUCKETS (blade_ref.h); its fenced readback reads the
 * first six words. */
#ifndef BLADE_PATCH_GLSL
#define BLADE_PATCH_GLSL

/* A patch's box; lo.w holds its real blades (uint bits, padding excluded). */
struct PatchBox {
    vec4 lo;
    vec4 hi;
};

layout(std430, binding = BLADE_BIND_COUNTERS) buffer Counters {
    uint culled[4];      /* per test: orientation, frustum, distance, occlusion */
    uint patch_culled;   /* real blades of the patches outside the frustum */
    uint patches_listed; /* patches in the list */
    uint dispatch[4];    /* blade_cull.comp's work groups x, y, z (indirect), its invocations */
    uint buckets[BLADE_PATCH_BUCKETS]; /* listed patches per distance bucket */
} counts;

#endif
