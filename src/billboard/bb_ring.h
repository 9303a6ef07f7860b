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
 * Memory and the per-follow loop depend on W, not on the world. */
#ifndef MEADOW_BB_RING_H
#define MEADOW_BB_RING_H

#include <stdbool.h>
#include <stdint.h>

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
} bb_ring_window_t;

/* W for a reach of `reach` m with cells of `cell` m: every cell within
 * reach + 1 m of the camera's cell and one more, 2 ceil((reach + 1) /
 * cell) + 3 (the tiles' rule, hybrid_desc_t.window). */
int bb_ring_side(float reach, float cell);
/* K for cells of about `cell` m at candidate `spacing`: round(cell /
 * spacing) rounded up to a multiple of `tile` (the generation's tile of
 * tile x tile candidates), at least tile. */
int bb_ring_cand(float cell, float spacing, int tile);
/* Every slot empty. False when out of memory. */
bool bb_ring_window_make(bb_ring_window_t *w, int side, int cand, float spacing, const float origin[2]);
void bb_ring_window_free(bb_ring_window_t *w);
/* The ring cell under world (x, z). */
void bb_ring_cell_of(const bb_ring_window_t *w, float x, float z, int32_t out[2]);
/* The slot of ring cell c in a window of `side`. */
int bb_ring_slot(int side, const int32_t c[2]);
/* The slot holding cell c, or -1. */
int bb_ring_window_find(const bb_ring_window_t *w, const int32_t c[2]);
/* Centres the window on the camera's cell: writes each slot whose cell
 * changes (slots[k], the cell it takes coords[k]; room for W^2), marks
 * them held and returns how many. */
int bb_ring_window_plan(bb_ring_window_t *w, const float camera[3], int *slots, int32_t (*coords)[2]);

#endif
