/* bb_octree: octree of billboard ranges with the collision / recovery state
 * machine of Orthmann et al. 2009 (sec. 4); see bb_octree.h. */
#include "billboard/bb_octree.h"

#include "core/core.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

bb_octree_desc_t bb_octree_desc_defaults(const bb_octree_desc_t *desc)
{
    bb_octree_desc_t d = *desc;
    if (d.max_depth == 0) d.max_depth = 4;
    if (d.min_size == 0.0f) d.min_size = 1.0f;
    if (d.margin == 0.0f) d.margin = 1.0f;
    return d;
}

/* Spreads the low 6 bits of v to every third bit. */
static uint32_t bb_spread3(uint32_t v)
{
    uint32_t r = 0;
    for (int b = 0; b < BB_OCTREE_MAX_DEPTH; b++) r |= ((v >> b) & 1u) << (3 * b);
    return r;
}

static uint32_t bb_compact3(uint32_t v)
{
    uint32_t r = 0;
    for (int b = 0; b < BB_OCTREE_MAX_DEPTH; b++) r |= ((v >> (3 * b)) & 1u) << b;
    return r;
}

static float bb_cell_coord(const bb_octree_desc_t *d, int axis, uint32_t k, int level)
{
    return d->min[axis] + (d->max[axis] - d->min[axis]) * ((float)k / (float)(1u << level));
}

bool bb_octree_build(bb_octree_t *tree, const bb_octree_desc_t *desc)
{
    memset(tree, 0, sizeof *tree);
    bb_octree_desc_t d = bb_octree_desc_defaults(desc);
    float ext = 0.0f;
    for (int a = 0; a < 3; a++) {
        if (!(d.max[a] > d.min[a])) {
            core_log_error("octree AABB axis %d is empty (%g..%g)", a,
                           (double)d.min[a], (double)d.max[a]);
            return false;
        }
        ext = fmaxf(ext, d.max[a] - d.min[a]);
    }
    if (d.max_depth > BB_OCTREE_MAX_DEPTH) {
        core_log_warn("octree max_depth %d capped at %d", d.max_depth, BB_OCTREE_MAX_DEPTH);
        d.max_depth = BB_OCTREE_MAX_DEPTH;
    }
    int depth = 0;
    while (depth < d.max_depth && ext / (float)(1u << (depth + 1)) >= d.min_size) depth++;
    tree->desc = d;
    tree->depth = depth;
    tree->side = 1 << depth;
    tree->leaf_count = 1 << (3 * depth);
    int count = 0;
    for (int l = 0; l <= depth; l++) {
        tree->level_start[l] = count;
        count += 1 << (3 * l);
    }
    tree->level_start[depth + 1] = count;
    tree->node_count = count;
    size_t n = (size_t)count;
    tree->lo = malloc(n * sizeof *tree->lo);
    tree->hi = malloc(n * sizeof *tree->hi);
    tree->first = calloc(n, sizeof *tree->first);
    tree->count = calloc(n, sizeof *tree->count);
    tree->state = calloc(n, 1);
    tree->mask = malloc(n);
    tree->timer = calloc(n, sizeof *tree->timer);
    if (!tree->lo || !tree->hi || !tree->first || !tree->count || !tree->state || !tree->mask ||
        !tree->timer) {
        core_log_error("out of memory for an octree of %d nodes", count);
        bb_octree_free(tree);
        return false;
    }
    memset(tree->mask, BB_NODE_MASK(BB_NODE_IDLE), n);
    for (int l = 0; l <= depth; l++) {
        for (uint32_t k = 0; k < (1u << (3 * l)); k++) {
            int node = tree->level_start[l] + (int)k;
            uint32_t c[3] = {bb_compact3(k), bb_compact3(k >> 1), bb_compact3(k >> 2)};
            for (int a = 0; a < 3; a++) {
                tree->lo[node][a] = bb_cell_coord(&d, a, c[a], l);
                tree->hi[node][a] = bb_cell_coord(&d, a, c[a] + 1, l);
            }
        }
    }
    return true;
}

void bb_octree_free(bb_octree_t *tree)
{
    free(tree->lo);
    free(tree->hi);
    free(tree->first);
    free(tree->count);
    free(tree->state);
    free(tree->mask);
    free(tree->timer);
    free(tree->scratch);
    memset(tree, 0, sizeof *tree);
}

static int bb_leaf_coord(const bb_octree_t *tree, int a, float p, bool *clamped)
{
    const bb_octree_desc_t *d = &tree->desc;
    float f = (p - d->min[a]) / (d->max[a] - d->min[a]) * (float)tree->side;
    int c = (int)floorf(f);
    if (!(f >= 0.0f)) {
        c = 0;
        *clamped = true;
    } else if (c >= tree->side) {
        if (p > d->max[a]) *clamped = true;
        c = tree->side - 1;
    }
    return c;
}

uint32_t bb_octree_leaf_at(const int c[3])
{
    uint32_t m = 0;
    for (int a = 0; a < 3; a++) m |= bb_spread3((uint32_t)c[a]) << a;
    return m;
}

void bb_octree_leaf_coords(uint32_t leaf, int c[3])
{
    for (int a = 0; a < 3; a++) c[a] = (int)bb_compact3(leaf >> a);
}

static uint32_t bb_leaf_of(const bb_octree_t *tree, const float pos[3], bool *clamped)
{
    int c[3];
    for (int a = 0; a < 3; a++) c[a] = bb_leaf_coord(tree, a, pos[a], clamped);
    return bb_octree_leaf_at(c);
}

uint32_t bb_octree_leaf_of(const bb_octree_t *tree, const float pos[3])
{
    bool clamped = false;
    return bb_leaf_of(tree, pos, &clamped);
}

void bb_octree_assign(bb_octree_t *tree, const float (*positions)[3], int n, uint32_t *order_out)
{
    int leaf0 = tree->level_start[tree->depth];
    memset(tree->count, 0, sizeof *tree->count * (size_t)tree->node_count);
    uint32_t *leaf = malloc(sizeof *leaf * (size_t)(n > 0 ? n : 1));
    assert(leaf);
    int outside = 0;
    for (int i = 0; i < n; i++) {
        bool clamped = false;
        leaf[i] = bb_leaf_of(tree, positions[i], &clamped);
        outside += clamped;
        tree->count[leaf0 + leaf[i]]++;
    }
    if (outside)
        core_log_warn("bb_octree_assign: %d of %d billboards lie outside the octree AABB; "
                      "clamped to border leaves", outside, n);
    uint32_t run = 0;
    for (int k = 0; k < tree->leaf_count; k++) {
        tree->first[leaf0 + k] = run;
        run += tree->count[leaf0 + k];
    }
    for (int l = tree->depth - 1; l >= 0; l--) {
        for (int k = 0; k < (1 << (3 * l)); k++) {
            int node = tree->level_start[l] + k, child = tree->level_start[l + 1] + 8 * k;
            tree->first[node] = tree->first[child];
            uint32_t c = 0;
            for (int q = 0; q < 8; q++) c += tree->count[child + q];
            tree->count[node] = c;
        }
    }
    uint32_t *fill = calloc((size_t)tree->leaf_count, sizeof *fill);
    assert(fill);
    for (int i = 0; i < n; i++) {
        order_out[tree->first[leaf0 + leaf[i]] + fill[leaf[i]]] = (uint32_t)i;
        fill[leaf[i]]++;
    }
    free(fill);
    free(leaf);
}

bool bb_bound_overlaps_box(const bb_bound_t *b, const float lo[3], const float hi[3], float margin)
{
    if (b->kind == BB_BOUND_NONE) return false;
    if (b->kind == BB_BOUND_SPHERE) {
        float l[3], h[3];
        for (int a = 0; a < 3; a++) l[a] = lo[a] - margin, h[a] = hi[a] + margin;
        return core_box_dist2(b->centre, l, h) <= b->radius * b->radius;
    }
    for (int a = 0; a < 3; a++) {
        if (b->centre[a] + b->half[a] < lo[a] - margin) return false;
        if (b->centre[a] - b->half[a] > hi[a] + margin) return false;
    }
    return true;
}

/* Leaf state rule shared in spirit with bb_octree_state_brute (written
 * twice on purpose so the test compares two implementations). */
void bb_leaf_step(uint8_t *state, float *timer, bool touched, float dt, float recover_time)
{
    if (touched) {
        *state = BB_NODE_COLLIDING;
        *timer = recover_time;
    } else if (*state == BB_NODE_COLLIDING) {
        *state = BB_NODE_RECOVERING;
        *timer = recover_time;
    } else if (*state == BB_NODE_RECOVERING) {
        *timer -= dt;
        if (*timer <= 0.0f) {
            *state = BB_NODE_IDLE;
            *timer = 0.0f;
        }
    }
}

static uint8_t bb_update_node(bb_octree_t *tree, int level, uint32_t k, const bb_bound_t *objects,
                              const int *list, int nlist, float dt, float recover_time)
{
    int node = tree->level_start[level] + (int)k;
    int *sub = tree->scratch + (size_t)(level + 1) * (size_t)tree->scratch_cap;
    int nsub = 0;
    for (int q = 0; q < nlist; q++)
        if (bb_bound_overlaps_box(&objects[list[q]], tree->lo[node], tree->hi[node], tree->desc.margin))
            sub[nsub++] = list[q];
    if (nsub == 0 && tree->mask[node] == BB_NODE_MASK(BB_NODE_IDLE)) return tree->mask[node];
    if (level == tree->depth) {
        bb_leaf_step(&tree->state[node], &tree->timer[node], nsub > 0, dt, recover_time);
        tree->mask[node] = (uint8_t)BB_NODE_MASK(tree->state[node]);
        return tree->mask[node];
    }
    uint8_t m = 0;
    for (uint32_t c = 0; c < 8; c++)
        m |= bb_update_node(tree, level + 1, 8 * k + c, objects, sub, nsub, dt, recover_time);
    tree->mask[node] = m;
    return m;
}

void bb_octree_update(bb_octree_t *tree, const bb_bound_t *objects, int n, float dt,
                      float recover_time)
{
    if (n > tree->scratch_cap) {
        free(tree->scratch);
        tree->scratch = malloc(sizeof(int) * (size_t)n * (size_t)(tree->depth + 2));
        assert(tree->scratch);
        tree->scratch_cap = n;
    }
    int *all = tree->scratch;
    for (int i = 0; i < n; i++) all[i] = i;
    bb_update_node(tree, 0, 0, objects, all, n, dt, recover_time);
}

static bool bb_box_outside_planes(const float lo[3], const float hi[3], float margin,
                                  const float (*planes)[4])
{
    for (int p = 0; p < 6; p++) {
        float s = planes[p][3];
        for (int a = 0; a < 3; a++) s += planes[p][a] * (planes[p][a] >= 0.0f ? hi[a] + margin : lo[a] - margin);
        if (s < 0.0f) return true;
    }
    return false;
}

static void bb_collect_node(const bb_octree_t *tree, int level, uint32_t k, uint32_t state_mask,
                            const float (*planes)[4], float margin, bb_range_t *out, int max_out, int *found)
{
    int node = tree->level_start[level] + (int)k;
    if (tree->count[node] == 0 || !(tree->mask[node] & state_mask)) return;
    if (planes && bb_box_outside_planes(tree->lo[node], tree->hi[node], margin, planes)) return;
    if (level < tree->depth) {
        for (uint32_t c = 0; c < 8; c++)
            bb_collect_node(tree, level + 1, 8 * k + c, state_mask, planes, margin, out, max_out, found);
        return;
    }
    if (*found < max_out)
        out[*found] = (bb_range_t){.first = tree->first[node], .count = tree->count[node], .leaf = k,
                                   .state = tree->state[node], .recover_left = tree->timer[node]};
    (*found)++;
}

int bb_octree_collect(const bb_octree_t *tree, uint32_t state_mask, const float (*planes)[4], float grow,
                      bb_range_t *out, int max_out)
{
    int found = 0;
    bb_collect_node(tree, 0, 0, state_mask, planes, tree->desc.margin + grow, out, max_out, &found);
    if (found > max_out)
        core_log_warn("bb_octree_collect: %d ranges match but only %d fit; rest dropped", found, max_out);
    return found;
}

static int bb_range_key_cmp(const void *pa, const void *pb)
{
    const bb_range_key_t *a = pa, *b = pb;
    if (a->dist2 != b->dist2) return a->dist2 < b->dist2 ? -1 : 1;
    return (a->range.leaf > b->range.leaf) - (a->range.leaf < b->range.leaf);
}

void bb_octree_sort_near_first(const bb_octree_t *tree, const float eye[3], bb_range_t *ranges, int n,
                               bb_range_key_t *keys)
{
    if (n < 2) return;
    int level = tree->depth > 0 ? tree->depth - 1 : 0;
    for (int i = 0; i < n; i++) {
        int node = tree->level_start[level] + (int)(ranges[i].leaf >> (3 * (tree->depth - level)));
        keys[i] = (bb_range_key_t){.dist2 = core_box_dist2(eye, tree->lo[node], tree->hi[node]),
                                   .range = ranges[i]};
    }
    qsort(keys, (size_t)n, sizeof *keys, bb_range_key_cmp);
    for (int i = 0; i < n; i++) ranges[i] = keys[i].range;
}

int bb_octree_keep_near(const bb_octree_t *tree, const float eye[3], float dist, bb_range_t *ranges, int n)
{
    float reach = dist + tree->desc.margin;
    int kept = 0;
    for (int i = 0; i < n; i++) {
        int node = bb_octree_leaf_node(tree, ranges[i].leaf);
        if (core_box_dist2(eye, tree->lo[node], tree->hi[node]) <= reach * reach) ranges[kept++] = ranges[i];
    }
    return kept;
}

void bb_octree_state_brute(const bb_octree_t *tree, const bb_bound_t *objects, int n, float dt,
                           float recover_time, uint8_t *states, float *timers)
{
    const bb_octree_desc_t *d = &tree->desc;
    for (int z = 0; z < tree->side; z++) {
        for (int y = 0; y < tree->side; y++) {
            for (int x = 0; x < tree->side; x++) {
                int c[3] = {x, y, z};
                float lo[3], hi[3];
                for (int a = 0; a < 3; a++) {
                    float ext = d->max[a] - d->min[a];
                    lo[a] = d->min[a] + ext * ((float)c[a] / (float)tree->side);
                    hi[a] = d->min[a] + ext * ((float)(c[a] + 1) / (float)tree->side);
                }
                uint32_t leaf = 0;
                for (int b = 0; b < tree->depth; b++)
                    for (int a = 0; a < 3; a++) leaf |= (uint32_t)((c[a] >> b) & 1) << (3 * b + a);
                bool touched = false;
                for (int i = 0; i < n && !touched; i++)
                    touched = bb_bound_overlaps_box(&objects[i], lo, hi, d->margin);
                uint8_t *s = &states[leaf];
                float *t = &timers[leaf];
                switch (*s) {
                case BB_NODE_IDLE:
                    if (touched) {
                        *s = BB_NODE_COLLIDING;
                        *t = recover_time;
                    }
                    break;
                case BB_NODE_COLLIDING:
                    if (!touched) *s = BB_NODE_RECOVERING;
                    *t = recover_time;
                    break;
                default:
                    if (touched) {
                        *s = BB_NODE_COLLIDING;
                        *t = recover_time;
                    } else if ((*t -= dt) <= 0.0f) {
                        *s = BB_NODE_IDLE;
                        *t = 0.0f;
                    }
                    break;
                }
            }
        }
    }
}
