/* bb_octree: the spatial hierarchy of Orthmann et al. 2009 (sec. 4) that
 * decides which billboards need collision treatment. A complete octree over
 * the terrain AABB (a true octree, as in the paper: each node splits x, y and
 * z in half, so over flat terrain the cells are flat boxes). Each leaf owns a
 * contiguous range [first, first+count) of the billboard buffer once the
 * buffer is sorted by bb_octree_assign. Per frame, bb_octree_update tests
 * object bounds hierarchically: a leaf touched by any object is COLLIDING; a
 * leaf no longer touched is RECOVERING for recover_time seconds (the t of
 * eq. 8 is recover_left / recover_time), then IDLE. bb_octree_collect lists
 * the leaf ranges in given states, optionally culled against a frustum.
 *
 * Node storage: level l (0 = root) holds 8^l nodes at node index
 * level_start[l] + k, k the Morton code of the cell's integer coordinates
 * (bit 0 x, bit 1 y, bit 2 z of each octal digit); the children of (l, k) are
 * (l+1, 8k+c). Leaves are level `depth`, leaf index = Morton code. */
#ifndef MEADOW_BB_OCTREE_H
#define MEADOW_BB_OCTREE_H

#include <stdbool.h>
#include <stdint.h>

enum { BB_NODE_IDLE = 0, BB_NODE_COLLIDING = 1, BB_NODE_RECOVERING = 2 };
#define BB_NODE_MASK(state) (1u << (state))
#define BB_OCTREE_MAX_DEPTH 6

typedef struct bb_octree_desc_t {
    float min[3], max[3]; /* terrain AABB (required, min < max on every axis) */
    int max_depth;        /* default 4, at most BB_OCTREE_MAX_DEPTH */
    float min_size;       /* leaves stop splitting before their largest edge
                             drops below this; default 1 m */
    float margin;         /* leaf cells grow by this on every side for object
                             and frustum tests, since billboards stand up to
                             their height above (and half width beside) their
                             roots; default 1 m */
} bb_octree_desc_t;
bb_octree_desc_t bb_octree_desc_defaults(const bb_octree_desc_t *desc);

enum { BB_BOUND_SPHERE = 0, BB_BOUND_AABB = 1, BB_BOUND_NONE = 2 };
typedef struct bb_bound_t {
    int kind;         /* BB_BOUND_SPHERE, BB_BOUND_AABB, or BB_BOUND_NONE
                         (an object left out: overlaps nothing) */
    float centre[3];  /* world space */
    float radius;     /* sphere */
    float half[3];    /* AABB half extents */
} bb_bound_t;

typedef struct bb_range_t {
    uint32_t first, count; /* billboards [first, first+count) of the sorted buffer */
    uint32_t leaf;         /* leaf (Morton) index */
    uint32_t state;        /* BB_NODE_* */
    float recover_left;    /* seconds of recovery left (RECOVERING) */
} bb_range_t;

typedef struct bb_octree_t {
    bb_octree_desc_t desc;  /* resolved */
    int depth;              /* leaves live at this level */
    int side;               /* 2^depth leaves per axis */
    int node_count;
    int leaf_count;         /* 8^depth */
    int level_start[BB_OCTREE_MAX_DEPTH + 2];
    float (*lo)[3], (*hi)[3]; /* per node: cell box (without margin) */
    uint32_t *first, *count;  /* per node: billboard range (after assign) */
    uint8_t *state;           /* per leaf node: BB_NODE_*; internal: unused */
    uint8_t *mask;            /* per node: OR of BB_NODE_MASK over its leaves */
    float *timer;             /* per leaf node: recovery seconds left */
    int *scratch;             /* object index lists for the traversal */
    int scratch_cap;
} bb_octree_t;

/* Cell boxes use lo = min + (max-min) * (k / 2^l) on each axis, so parent and
 * child bounds nest bit for bit. Returns false (and logs) on bad input. */
bool bb_octree_build(bb_octree_t *tree, const bb_octree_desc_t *desc);
void bb_octree_free(bb_octree_t *tree);

/* Leaf (Morton) index of a position; positions outside the AABB clamp to
 * the border leaf. */
uint32_t bb_octree_leaf_of(const bb_octree_t *tree, const float pos[3]);
/* Leaf (Morton) index of leaf coordinates c (each 0..side-1), and back. */
uint32_t bb_octree_leaf_at(const int c[3]);
void bb_octree_leaf_coords(uint32_t leaf, int c[3]);
/* Node index of leaf k. */
static inline int bb_octree_leaf_node(const bb_octree_t *tree, uint32_t leaf)
{
    return tree->level_start[tree->depth] + (int)leaf;
}

/* Sorts billboards by leaf: order_out[s] = original index of the billboard
 * that goes to slot s; afterwards every node's [first, first+count) is
 * contiguous (Morton order makes every subtree contiguous too). Positions
 * outside the AABB are clamped to border leaves with one warning. */
void bb_octree_assign(bb_octree_t *tree, const float (*positions)[3], int n, uint32_t *order_out);

/* One frame of the state machine (hierarchical AABB test, subtrees that are
 * untouched and all IDLE are skipped). */
void bb_octree_update(bb_octree_t *tree, const bb_bound_t *objects, int n, float dt,
                      float recover_time);

/* Writes up to max_out ranges of non-empty leaves whose state is in
 * state_mask (BB_NODE_MASK bits) and whose box grown by the margin plus
 * `grow` (m; the widest card's reach past the margin, bb_lod_reach) is not
 * outside any of the 6 planes (planes may be NULL: no culling; a point p
 * is inside plane (a,b,c,d) when a*px + b*py + c*pz + d >= 0). Returns the
 * number of matching ranges; when that exceeds max_out, logs a warning and
 * writes the first max_out only. */
int bb_octree_collect(const bb_octree_t *tree, uint32_t state_mask, const float (*planes)[4], float grow,
                      bb_range_t *out, int max_out);

/* Orders ranges[0..n) nearest first: by the distance from eye to the cell
 * box (without margin; 0 inside it) of each range's leaf's parent, ties by
 * leaf index, so the leaves of one parent stay in Morton order (adjacent in
 * the buffer: a draw merges them into one range) and a draw in this order
 * lets the depth test reject what nearer cells already cover. keys: scratch
 * of at least n entries (the caller's, so a draw allocates nothing). */
typedef struct bb_range_key_t {
    float dist2;
    bb_range_t range;
} bb_range_key_t;
void bb_octree_sort_near_first(const bb_octree_t *tree, const float eye[3], bb_range_t *ranges, int n,
                               bb_range_key_t *keys);

/* Keeps the ranges[0..n) whose leaf's margin-grown box comes within dist
 * of eye (core_box_dist2), in their order; returns how many. The hybrid's
 * billboards end at the ground canopy's fade (bb_draw_desc_t.far_end). */
int bb_octree_keep_near(const bb_octree_t *tree, const float eye[3], float dist, bb_range_t *ranges, int n);

/* Independent brute-force twin of bb_octree_update for tests: loops over
 * all leaves, computes each leaf box from its integer coordinates, tests it
 * against every object and applies the same state rule to the caller's
 * per-leaf arrays (leaf_count entries, indexed by Morton leaf index). */
void bb_octree_state_brute(const bb_octree_t *tree, const bb_bound_t *objects, int n, float dt,
                           float recover_time, uint8_t *states, float *timers);

/* One update of a leaf's state (BB_NODE_*) and recovery timer: COLLIDING
 * while touched, then RECOVERING for recover_time (counted down by dt),
 * then IDLE. bb_octree_update's leaves and the billboard ring's slots. */
void bb_leaf_step(uint8_t *state, float *timer, bool touched, float dt, float recover_time);
/* True when the box [lo-margin, hi+margin] overlaps the bound. */
bool bb_bound_overlaps_box(const bb_bound_t *b, const float lo[3], const float hi[3], float margin);

#endif
