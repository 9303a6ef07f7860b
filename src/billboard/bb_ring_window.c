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
    w->held = malloc(sizeof *w->held * (size_t)side * (size_t)side);
    if (!w->held) return false;
    for (int s = 0; s < side * side; s++) w->held[s][0] = w->held[s][1] = BB_RING_NONE;
    return true;
}

void bb_ring_window_free(bb_ring_window_t *w)
{
    free(w->held);
    w->held = NULL;
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

int bb_ring_window_plan(bb_ring_window_t *w, const float camera[3], int *slots, int32_t (*coords)[2])
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
            n++;
        }
    }
    return n;
}
