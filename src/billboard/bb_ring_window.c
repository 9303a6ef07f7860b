/* bb_ring_window: the billboard ring's window of cells around the camera
 * (bb_ring.h): its size, the slot of a cell, and which slots a follow
 * generates again. GL-free; tested by test_bb_ring. */
#include "billboard/bb_ring.h"

#include <math.h>
#include <stdlib.h>

int bb_ring_side(float reach, float cell)
{
    return 2 * (int)ceilf((reach + 1.0f) / cell) + 3;
}

int bb_ring_cand(float cell, float spacing, int tile)
{
    int k = (int)lroundf(cell / spacing);
    k = (k + tile - 1) / tile * tile;
    return k < tile ? tile : k;
}

bool bb_ring_window_make(bb_ring_window_t *w, int side, int cand, float spacing, const float origin[2])
{
    *w = (bb_ring_window_t){.side = side, .cand = cand, .spacing = spacing, .origin = {origin[0], origin[1]}};
    size_t n = (size_t)side * (size_t)side;
    w->held = malloc(sizeof *w->held * n);
    w->state = calloc(n, sizeof *w->state);
    w->timer = calloc(n, sizeof *w->timer);
    if (!w->held || !w->state || !w->timer) return false;
    for (size_t s = 0; s < n; s++) w->held[s][0] = w->held[s][1] = BB_RING_NONE;
    return true;
}

void bb_ring_window_free(bb_ring_window_t *w)
{
    free(w->held);
    free(w->state);
    free(w->timer);
    w->held = NULL;
    w->state = NULL;
    w->timer = NULL;
}

void bb_ring_cell_of(const bb_ring_window_t *w, float x, float z, int32_t out[2])
{
    double cell = (double)w->spacing * (double)w->cand;
    out[0] = (int32_t)floor(((double)x - (double)w->origin[0]) / cell);
    out[1] = (int32_t)floor(((double)z - (double)w->origin[1]) / cell);
}

int bb_ring_slot(int side, const int32_t c[2])
{
    int i = (int)(((int64_t)c[0] % side + side) % side), j = (int)(((int64_t)c[1] % side + side) % side);
    return j * side + i;
}

int bb_ring_window_find(const bb_ring_window_t *w, const int32_t c[2])
{
    int s = bb_ring_slot(w->side, c);
    return w->held[s][0] == c[0] && w->held[s][1] == c[1] ? s : -1;
}

int bb_ring_window_plan(bb_ring_window_t *w, const float camera[3], int *slots, int32_t (*coords)[2],
                        bool *dropped)
{
    int32_t centre[2];
    bb_ring_cell_of(w, camera[0], camera[2], centre);
    int n = 0, half = w->side / 2;
    for (int j = 0; j < w->side; j++) {
        for (int i = 0; i < w->side; i++) {
            int32_t c[2] = {centre[0] - half + i, centre[1] - half + j};
            int s = bb_ring_slot(w->side, c);
            if (w->held[s][0] == c[0] && w->held[s][1] == c[1]) continue;
            w->held[s][0] = c[0], w->held[s][1] = c[1];
            slots[n] = s;
            coords[n][0] = c[0], coords[n][1] = c[1];
            dropped[n] = w->state[s] != BB_NODE_IDLE;
            w->state[s] = BB_NODE_IDLE;
            w->timer[s] = 0.0f;
            n++;
        }
    }
    return n;
}

bool bb_ring_slot_box(const bb_ring_window_t *w, int s, float lo[3], float hi[3])
{
    const int32_t *c = w->held[s];
    if (c[0] == BB_RING_NONE) return false;
    float cell = (float)w->cand * w->spacing;
    lo[0] = w->origin[0] + (float)c[0] * cell, lo[1] = w->y[0], lo[2] = w->origin[1] + (float)c[1] * cell;
    hi[0] = lo[0] + cell, hi[1] = w->y[1], hi[2] = lo[2] + cell;
    return true;
}

void bb_ring_window_touch(bb_ring_window_t *w, const bb_bound_t *objects, int n, float dt, float recover_time)
{
    for (int s = 0; s < w->side * w->side; s++) {
        float lo[3], hi[3];
        if (!bb_ring_slot_box(w, s, lo, hi)) continue;
        bool hit = false;
        for (int k = 0; k < n && !hit; k++) hit = bb_bound_overlaps_box(&objects[k], lo, hi, w->margin);
        bb_leaf_step(&w->state[s], &w->timer[s], hit, dt, recover_time);
    }
}
