/* bb_ring: the billboard field on a world terrain (terrain.type "world",
 * docs/WORLD.md "Streaming: the billboard ring"), the window of square
 * cells that follows the camera (GL-free; the GPU half is bb_ring.c).
 *
 * A ring cell is K x K candidate cells of the generation rule
 * (bb_layout.h) from the field's candidate origin, so cell (ci, cj) holds
 * candidates [ci K, ci K + K) x [cj K, cj K + K) and a cell is a pure
 * function of its coordinates, the seed and the layout. The window holds
 * W x W cells; cell (ci, cj) lives in slot (cj mod W) W + (ci mod W) while
 * it is inside the window, which is centred on the camera's cell (its
 * first corner at the camera's cell - W / 2) each time it follows. A slot
 * whose cell changed is generated again (bb_ring_window_plan lists them).
 * Collision state per slot, as the octree's per leaf (bb_octree.h):
 * COLLIDING while an object's bound meets the cell's box (grown by the
 * margin), then RECOVERING for recover_time, then IDLE. A slot that takes
 * a new cell drops its state (the caller frees the cell's deformed meshes).
 * Memory and the per-follow loop depend on W, not on the world. */
#ifndef MEADOW_BB_RING_H
#define MEADOW_BB_RING_H

#include <stdbool.h>
#include <stdint.h>

#include "billboard/bb_octree.h"

/* bb_ring_window_t.held of a slot that holds no cell yet. */
#define BB_RING_NONE INT32_MIN
/* Default ring cell side (m; bb_field_desc_t.ring_cell). */
#define BB_RING_CELL_DEFAULT 8.0f
/* Default reach (m; bb_field_desc_t.ring_reach): every billboard within it
 * of the camera is held. */
#define BB_RING_REACH_DEFAULT 64.0f

typedef struct bb_ring_window_t {
    int side;           /* W: cells per side */
    int cand;           /* K: candidate cells per ring cell side */
    float spacing;      /* candidate spacing (m) */
    float origin[2];    /* world xz of candidate cell (0, 0) */
    int32_t (*held)[2]; /* per slot: the ring cell it holds, or BB_RING_NONE */
    uint8_t *state;     /* per slot: BB_NODE_* */
    float *timer;       /* per slot: recovery seconds left (RECOVERING) */
    float y[2];         /* height range of the cells' boxes (m) */
    float margin;       /* broad-phase margin of the boxes (m) */
} bb_ring_window_t;

/* W for a reach of `reach` m with cells of `cell` m: every cell within
 * reach + 1 m of the camera's cell and one more, 2 ceil((reach + 1) /
 * cell) + 3 (the tiles' rule, hybrid_desc_t.window). */
int bb_ring_side(float reach, float cell);
/* K for cells of about `cell` m at candidate `spacing`: round(cell /
 * spacing) rounded up to a multiple of `tile` (the generation's tile of
 * tile x tile candidates), at least tile. */
int bb_ring_cand(float cell, float spacing, int tile);
/* Every slot empty and IDLE; y range and margin zero (set them). False
 * when out of memory. */
bool bb_ring_window_make(bb_ring_window_t *w, int side, int cand, float spacing, const float origin[2]);
void bb_ring_window_free(bb_ring_window_t *w);
/* The ring cell under world (x, z). */
void bb_ring_cell_of(const bb_ring_window_t *w, float x, float z, int32_t out[2]);
/* The slot of ring cell c in a window of `side`. */
int bb_ring_slot(int side, const int32_t c[2]);
/* The slot holding cell c, or -1. */
int bb_ring_window_find(const bb_ring_window_t *w, const int32_t c[2]);
/* Centres the window on the camera's cell: writes each slot whose cell
 * changes (slots[k], the cell it takes coords[k], dropped[k] whether its
 * state was not IDLE; room for W^2), marks them held and IDLE and returns
 * how many. */
int bb_ring_window_plan(bb_ring_window_t *w, const float camera[3], int *slots, int32_t (*coords)[2],
                        bool *dropped);
/* The box of slot s's cell (xz of the cell, y range); false when it holds
 * none. */
bool bb_ring_slot_box(const bb_ring_window_t *w, int s, float lo[3], float hi[3]);
/* One broad-phase update of every held slot against objects[0..n) (the
 * octree's leaf state machine, bb_octree_update). */
void bb_ring_window_touch(bb_ring_window_t *w, const bb_bound_t *objects, int n, float dt, float recover_time);

#endif
