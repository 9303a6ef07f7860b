/* grass_gi: the global illumination volumes (scene grass.gi, Orthmann
 * et al. 2009 sec. 6.1; gi_volume.h): the terrain's heights, the grass as a
 * layer of its mean blade height thinned by the extent map's cover, and the
 * static colliders as boxes (spheres and capsules by their bounding
 * boxes; moving colliders and characters are left out: the volumes are
 * computed once). The volume spans the terrain's box, from its lowest
 * point to APP_GI_TOP above the tallest blade over its highest. */
#include "grass/grass_local.h"

#include <math.h>
#include <string.h>

#include "core/core.h"

/* Metres of the volume above the grass tops over the highest ground. */
#define APP_GI_TOP 2.0f

typedef struct app_gi_src_t {
    const terrain_mesh_t *terrain;
    bb_layout_t lay;
    bb_gen_desc_t gen;
    bool have_layout;
} app_gi_src_t;

static float gi_height(const void *user, float x, float z)
{
    const app_gi_src_t *s = user;
    return terrain_height_at(s->terrain, x, z, NULL);
}

/* The extent map's accepted share at (x, z), as thin_blades_by_extent reads it. */
static float gi_cover(const void *user, float x, float z)
{
    const app_gi_src_t *s = user;
    if (!s->have_layout) return 1.0f;
    int ix = (int)floorf((x - s->gen.origin[0]) / s->gen.spacing);
    int iz = (int)floorf((z - s->gen.origin[1]) / s->gen.spacing);
    int w = s->lay.extent.w, h = s->lay.extent.h;
    int tx = ((ix / s->gen.cells_per_texel) % w + w) % w, tz = ((iz / s->gen.cells_per_texel) % h + h) % h;
    return (float)s->lay.extent.px[(size_t)tz * (size_t)w + (size_t)tx] / 255.0f;
}

/* Static colliders (a one-key path) as boxes; returns how many. */
static int static_boxes(const grass_t *gr, gi_object_t *out)
{
    int n = 0;
    for (int i = 0; i < gr->scene->collider_count; i++) {
        const scene_collider_t *c = &gr->scene->colliders[i];
        if (c->path.count != 1) continue;
        float centre[3], vel[3], half[3];
        scene_path_eval(&c->path, 0.0f, false, centre, vel);
        if (gr->terrain->grid_res > 0) centre[1] += terrain_height_at(gr->terrain, centre[0], centre[2], NULL);
        if (c->type == SCENE_COLLIDER_BOX) {
            memcpy(half, c->half_extents, sizeof half);
        } else {
            float r = c->radius, extra = c->type == SCENE_COLLIDER_CAPSULE ? 0.5f * c->length : 0.0f;
            half[0] = half[2] = r;
            half[1] = r + extra;
        }
        for (int k = 0; k < 3; k++) {
            out[n].lo[k] = centre[k] - half[k];
            out[n].hi[k] = centre[k] + half[k];
        }
        n++;
    }
    return n;
}

bool grass_gi_make(grass_t *gr)
{
    const scene_grass_desc_t *g = &gr->scene->grass;
    const terrain_mesh_t *t = gr->terrain;
    app_gi_src_t src = {.terrain = t};
    src.have_layout = grass_extent_layout(gr, &src.lay, &src.gen);
    gi_object_t boxes[SCENE_MAX_COLLIDERS];
    float grass_height = 0.5f * (g->population.height[0] + g->population.height[1]);
    gi_scene_t scene = {.height = gi_height,
                        .cover = gi_cover,
                        .user = &src,
                        .grass_height = grass_height,
                        /* blade area per volume (density x mean width) over 2 */
                        .grass_extinction =
                            0.5f * g->population.density * 0.5f * (g->population.width[0] + g->population.width[1]),
                        .objects = boxes,
                        .object_count = static_boxes(gr, boxes)};
    gi_volume_desc_t desc = {
        .lo = {t->aabb_min[0], t->aabb_min[1], t->aabb_min[2]},
        .hi = {t->aabb_max[0], t->aabb_max[1] + g->population.height[1] + APP_GI_TOP, t->aabb_max[2]}};
    gi_volume_t v;
    bool ok = gi_volume_make(&v, &desc, &scene);
    if (src.have_layout) bb_layout_free(&src.lay);
    if (!ok) return false;
    ok = gi_gpu_make(&gr->gi, &v);
    if (ok)
        core_log_info("gi: %dx%dx%d ambient-occlusion and irradiance volumes over %.0f x %.1f x %.0f m in %.1f ms",
                      v.res[0], v.res[1], v.res[2], (double)(v.hi[0] - v.lo[0]), (double)(v.hi[1] - v.lo[1]),
                      (double)(v.hi[2] - v.lo[2]), v.build_ms);
    gi_volume_free(&v);
    gr->gi_bind = gi_gpu_bind(ok ? &gr->gi : NULL);
    ground_set_gi(gr->ground, gr->gi_bind);
    return ok;
}
