/* hybrid: tile representation with hysteresis, Fan et al. 2015 activation
 * with a fixed pool of simulation slots, and per-tile object lists (one
 * growable array, every touching object listed). */
#include "hybrid/hybrid.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"

hybrid_desc_t hybrid_desc_defaults(const hybrid_desc_t *in)
{
    hybrid_desc_t d = *in;
    if (d.tile_size <= 0) d.tile_size = HYBRID_DEFAULT_TILE_SIZE;
    if (d.grass_height <= 0) d.grass_height = 1.0f;
    if (d.switch_distance <= 0) d.switch_distance = HYBRID_DEFAULT_SWITCH_DISTANCE;
    if (d.hysteresis <= 0) d.hysteresis = 1.0f;
    if (d.recover_timeout <= 0) d.recover_timeout = 5.0f;
    if (d.motion_epsilon <= 0) d.motion_epsilon = HYBRID_DEFAULT_MOTION_EPSILON;
    if (d.pool_slots <= 0) d.pool_slots = HYBRID_DEFAULT_POOL_SLOTS;
    if (d.memory <= 0) d.memory = HYBRID_DEFAULT_MEMORY;
    return d;
}

/* Places the held tile at index i over field tile (gi, gj): its box, and a
 * fresh IDLE state. */
static void place_tile(const hybrid_grid_t *g, hybrid_tile_t *t, int gi, int gj)
{
    const hybrid_desc_t *d = &g->desc;
    t->coord[0] = gi;
    t->coord[1] = gj;
    t->present = gi >= 0 && gj >= 0 && gi < g->field_nx && gj < g->field_nz;
    t->min[0] = d->min_x + (float)gi * d->tile_size;
    t->min[2] = d->min_z + (float)gj * d->tile_size;
    t->max[0] = fminf(t->min[0] + d->tile_size, d->min_x + d->size_x);
    t->max[2] = fminf(t->min[2] + d->tile_size, d->min_z + d->size_z);
    float y[2] = {d->min_y, d->max_y};
    if (d->window > 0 && d->tile_range && t->present)
        d->tile_range(d->range_user, (float[2]){t->min[0], t->min[2]}, (float[2]){t->max[0], t->max[2]}, y);
    t->min[1] = y[0];
    t->max[1] = y[1] + d->grass_height;
    t->state = HYBRID_IDLE;
    t->rep = HYBRID_REP_BILLBOARD;
    t->recover_left = t->motion = t->memory_left = 0.0f;
    t->slot = t->handover_slot = -1;
    t->seed = false;
    t->object_count = 0;
}

/* Window: the field tile coordinate the index along one axis holds when the
 * window starts at `base` (the one in [base, base + W) congruent to i). */
static int window_coord(int i, int base, int w) { return base + ((i - base) % w + w) % w; }

bool hybrid_grid_make(hybrid_grid_t *g, const hybrid_desc_t *desc)
{
    memset(g, 0, sizeof *g);
    g->desc = hybrid_desc_defaults(desc);
    const hybrid_desc_t *d = &g->desc;
    if (d->size_x <= 0 || d->size_z <= 0 || d->window < 0) {
        core_log_error("hybrid: field size %gx%g m must be positive (window %d)", d->size_x, d->size_z, d->window);
        return false;
    }
    g->field_nx = (int)ceilf(d->size_x / d->tile_size);
    g->field_nz = (int)ceilf(d->size_z / d->tile_size);
    g->nx = d->window > 0 ? d->window : g->field_nx;
    g->nz = d->window > 0 ? d->window : g->field_nz;
    g->tiles = calloc((size_t)g->nx * (size_t)g->nz, sizeof *g->tiles);
    g->free_slots = malloc((size_t)d->pool_slots * sizeof(int));
    g->away = d->window > 0 ? malloc((size_t)d->pool_slots * sizeof *g->away) : NULL;
    if (!g->tiles || !g->free_slots || (d->window > 0 && !g->away)) {
        hybrid_grid_free(g);
        return false;
    }
    for (int j = 0; j < g->nz; j++)
        for (int i = 0; i < g->nx; i++) place_tile(g, &g->tiles[j * g->nx + i], i, j);
    for (int s = 0; s < d->pool_slots; s++) g->free_slots[s] = d->pool_slots - 1 - s;
    g->free_count = d->pool_slots;
    return true;
}

void hybrid_grid_free(hybrid_grid_t *g)
{
    free(g->tiles);
    free(g->free_slots);
    free(g->away);
    free(g->objects);
    memset(g, 0, sizeof *g);
}

/* Index of field tile (gi, gj), -1 outside the field or the window. */
static int index_of(const hybrid_grid_t *g, int gi, int gj)
{
    if (gi < 0 || gj < 0 || gi >= g->field_nx || gj >= g->field_nz) return -1;
    if (g->desc.window <= 0) return gj * g->nx + gi;
    int w = g->desc.window;
    if (gi < g->base[0] || gj < g->base[1] || gi >= g->base[0] + w || gj >= g->base[1] + w) return -1;
    return (gj % w) * w + gi % w;
}

int hybrid_tile_at(const hybrid_grid_t *g, float x, float z)
{
    return index_of(g, (int)floorf((x - g->desc.min_x) / g->desc.tile_size),
                    (int)floorf((z - g->desc.min_z) / g->desc.tile_size));
}

bool hybrid_tile_touched_brute(const hybrid_grid_t *g, int i, const hybrid_object_t *o, int count)
{
    const hybrid_tile_t *t = &g->tiles[i];
    for (int k = 0; k < count; k++) {
        float r = o[k].sphere[3];
        if (core_box_dist2(o[k].sphere, t->min, t->max) <= r * r) return true;
    }
    return false;
}

static void release_slot(hybrid_grid_t *g, hybrid_tile_t *t)
{
    if (t->slot < 0) return;
    g->free_slots[g->free_count++] = t->slot;
    t->slot = -1;
}

/* Window: centres the window on the camera's tile and moves every index
 * whose field tile left it to the one that entered: the leaving tile keeps
 * its slot away from the camera, the entering one takes back the slot it
 * kept away, if any, or starts IDLE. */
static void recentre(hybrid_grid_t *g, const float cam[3], hybrid_stats_t *st)
{
    const hybrid_desc_t *d = &g->desc;
    int w = d->window;
    g->base[0] = (int)floorf((cam[0] - d->min_x) / d->tile_size) - w / 2;
    g->base[1] = (int)floorf((cam[2] - d->min_z) / d->tile_size) - w / 2;
    for (int j = 0; j < w; j++)
        for (int i = 0; i < w; i++) {
            hybrid_tile_t *t = &g->tiles[j * w + i];
            t->reattached = false;
            int gi = window_coord(i, g->base[0], w), gj = window_coord(j, g->base[1], w);
            if (t->coord[0] == gi && t->coord[1] == gj) continue;
            st->streamed++;
            if (t->slot >= 0) {
                g->away[g->away_count++] = (hybrid_away_t){
                    .coord = {t->coord[0], t->coord[1]},
                    .slot = t->slot,
                    .recover_left = t->state == HYBRID_RECOVERING ? t->recover_left : d->recover_timeout,
                    .memory_left = t->memory_left};
                st->detached++;
            }
            place_tile(g, t, gi, gj);
            t->epoch++;
            for (int k = 0; k < g->away_count; k++) {
                hybrid_away_t *a = &g->away[k];
                if (a->coord[0] != gi || a->coord[1] != gj) continue;
                t->slot = a->slot;
                t->state = HYBRID_RECOVERING;
                t->recover_left = a->recover_left;
                t->memory_left = a->memory_left;
                t->reattached = true;
                st->reattached++;
                *a = g->away[--g->away_count];
                break;
            }
        }
}

void hybrid_grid_settle_away(hybrid_grid_t *g, const float *slot_motion)
{
    for (int k = 0; k < g->away_count; k++)
        if (slot_motion[g->away[k].slot] < g->desc.motion_epsilon) g->away[k].recover_left = 0.0f;
}

/* Window: tiles away from the camera recover without objects until their
 * time is up (or hybrid_grid_settle_away ended it), then free their slot. */
static void recover_away(hybrid_grid_t *g, float dt)
{
    for (int k = 0; k < g->away_count;) {
        hybrid_away_t *a = &g->away[k];
        a->recover_left -= dt;
        a->memory_left = fmaxf(a->memory_left - dt, 0.0f);
        if (a->recover_left > 0.0f) {
            k++;
            continue;
        }
        g->free_slots[g->free_count++] = a->slot;
        *a = g->away[--g->away_count];
    }
}

/* Grows g->objects to hold `total` entries (doubling); out of memory:
 * logged, then abort(). */
static void fit_objects(hybrid_grid_t *g, int total)
{
    if (total <= g->object_capacity) return;
    int cap = g->object_capacity > 0 ? g->object_capacity : 256;
    while (cap < total) cap *= 2;
    uint32_t *grown = realloc(g->objects, (size_t)cap * sizeof *grown);
    if (!grown) {
        core_log_error("hybrid: out of memory for %d per-tile object list entries", cap);
        abort();
    }
    g->objects = grown;
    g->object_capacity = cap;
}

/* The per-tile object lists: every object touching a tile, in ascending
 * order. Two passes over the tiles under each object's bounds (one tile of
 * margin so spheres touching a tile edge exactly are found by the exact
 * test): the first counts, a prefix sum places each tile's list in
 * g->objects (grown to the total), the second fills. Returns the total. */
static int list_objects(hybrid_grid_t *g, const hybrid_object_t *objects, int count)
{
    const hybrid_desc_t *d = &g->desc;
    int ntiles = g->nx * g->nz, total = 0;
    for (int i = 0; i < ntiles; i++) g->tiles[i].object_count = 0;
    int lo[2] = {0, 0}, hi[2] = {g->field_nx - 1, g->field_nz - 1};
    for (int a = 0; a < 2 && d->window > 0; a++) {
        lo[a] = g->base[a] > lo[a] ? g->base[a] : lo[a];
        hi[a] = g->base[a] + d->window - 1 < hi[a] ? g->base[a] + d->window - 1 : hi[a];
    }
    for (int pass = 0; pass < 2; pass++) {
        for (int k = 0; k < count; k++) {
            const float *s = objects[k].sphere;
            int i0 = (int)floorf((s[0] - s[3] - d->min_x) / d->tile_size) - 1;
            int i1 = (int)floorf((s[0] + s[3] - d->min_x) / d->tile_size) + 1;
            int j0 = (int)floorf((s[2] - s[3] - d->min_z) / d->tile_size) - 1;
            int j1 = (int)floorf((s[2] + s[3] - d->min_z) / d->tile_size) + 1;
            for (int j = j0 > lo[1] ? j0 : lo[1]; j <= j1 && j <= hi[1]; j++)
                for (int i = i0 > lo[0] ? i0 : lo[0]; i <= i1 && i <= hi[0]; i++) {
                    int ti = index_of(g, i, j);
                    assert(ti >= 0); /* lo, hi keep (i, j) in the field and the window */
                    hybrid_tile_t *t = &g->tiles[ti];
                    if (core_box_dist2(s, t->min, t->max) > s[3] * s[3]) continue;
                    if (pass) g->objects[t->object_first + t->object_count] = (uint32_t)k;
                    t->object_count++;
                }
        }
        if (pass) break;
        for (int i = 0; i < ntiles; i++) {
            g->tiles[i].object_first = total;
            total += g->tiles[i].object_count;
            g->tiles[i].object_count = 0;
        }
        fit_objects(g, total);
    }
    return total;
}

void hybrid_grid_update(hybrid_grid_t *g, const float cam[3], const hybrid_object_t *objects, int count,
                        const float *motion, float dt)
{
    const hybrid_desc_t *d = &g->desc;
    hybrid_stats_t st = {.tiles = g->nx * g->nz, .slots_total = d->pool_slots};
    int ntiles = g->nx * g->nz;
    if (d->window > 0) {
        recentre(g, cam, &st);
        recover_away(g, dt);
        st.away = g->away_count;
    }
    st.listed = list_objects(g, objects, count);
    for (int i = 0; i < ntiles; i++) {
        hybrid_tile_t *t = &g->tiles[i];
        if (!t->present) continue; /* a window tile beyond the field's edge */
        /* Representation with hysteresis on the switch distance (the eye
         * distance, shaders/common/switch.glsl) to the tile's box: no blade
         * of a billboard tile is nearer than the box. */
        float dist = sqrtf(core_box_dist2(cam, t->min, t->max));
        hybrid_rep_t rep = t->rep;
        if (dist < d->switch_distance - d->hysteresis) rep = HYBRID_REP_BLADE;
        else if (dist > d->switch_distance + d->hysteresis) rep = HYBRID_REP_BILLBOARD;
        if (rep != t->rep) st.rep_switches++;
        t->rep = rep;
        /* Activation. */
        if (motion) t->motion = motion[i];
        t->handover_slot = -1;
        t->seed = false;
        t->memory_left = fmaxf(t->memory_left - dt, 0.0f);
        if (t->object_count > 0) {
            if (t->slot < 0) {
                if (g->free_count > 0) {
                    t->slot = g->free_slots[--g->free_count];
                } else {
                    st.pool_denied++;
                }
            }
            t->state = t->slot >= 0 ? HYBRID_ACTIVE : HYBRID_IDLE;
            t->recover_left = d->recover_timeout;
            t->memory_left = d->memory;
        } else if (t->state == HYBRID_ACTIVE) {
            t->state = HYBRID_RECOVERING;
            t->recover_left = d->recover_timeout;
        } else if (t->state == HYBRID_RECOVERING) {
            t->recover_left -= dt;
            bool settled = motion && t->motion < d->motion_epsilon;
            if (t->recover_left <= 0 || settled) {
                t->state = HYBRID_IDLE;
                t->recover_left = 0;
                t->memory_left = 0; /* the blades were the newest state, and it died down */
                release_slot(g, t);
            }
        }
        if (!d->keep_state && t->state == HYBRID_RECOVERING && t->rep == HYBRID_REP_BILLBOARD) {
            t->handover_slot = t->slot;
            release_slot(g, t);
            t->state = HYBRID_IDLE;
            t->recover_left = 0;
            t->memory_left = d->memory;
            st.handovers++;
        } else if (!d->keep_state && t->state == HYBRID_IDLE && t->rep == HYBRID_REP_BLADE && t->slot < 0 &&
                   t->object_count == 0 && t->memory_left > 0) {
            if (g->free_count > 0) {
                t->slot = g->free_slots[--g->free_count];
                t->state = HYBRID_RECOVERING;
                t->recover_left = d->recover_timeout;
                t->seed = true;
                st.seeded++;
            } else {
                st.pool_denied++;
            }
        }
        st.blade_tiles += t->rep == HYBRID_REP_BLADE;
        st.idle += t->state == HYBRID_IDLE;
        st.active += t->state == HYBRID_ACTIVE;
        st.recovering += t->state == HYBRID_RECOVERING;
    }
    st.billboard_tiles = st.tiles - st.blade_tiles;
    st.slots_used = d->pool_slots - g->free_count;
    if (st.pool_denied && !g->warned_pool)
        core_log_warn("hybrid: simulation pool exhausted: %d tile(s) touched by objects got no state slot "
                      "(%d slots); raise grass.tile_pool",
                      st.pool_denied, d->pool_slots);
    g->warned_pool = st.pool_denied > 0;
    g->stats = st;
}
