/* measure: measures of drawn frames shared by the program's summary
 * (src/app) and the evaluation harness (src/bench): the hybrid seam at the
 * switch and canopy bands and its noise floor (measure_seam.c,
 * docs/METRICS.md "Hybrid seam"), and the hardware and compute floors of
 * trivial triangles (measure_floor.c), the counts of a frame (measure_stats.c).
 * Through world.h and world_harness.h, and grass_harness.h for the grass's
 * drivers: the program and the harness (app, bench, perf, stability) reach
 * the drivers through measure alone. */
#ifndef MEADOW_MEASURE_H
#define MEADOW_MEASURE_H

#include "eval/eval_image.h"
#include "grass/grass_harness.h"
#include "world/world_harness.h"

/* The drivers of w's grass (all NULL before world_make_gpu): the one door
 * from the measures to the billboards, blades, tiles and rasterizer. */
grass_drivers_t measure_drivers(world_t *w);

/* ---- hybrid seam (measure_seam.c, docs/METRICS.md "Hybrid seam") ------------------ */
/* A frame for eval_image_seam: colour, distance to the visible surface and
 * class per pixel (row 0 at the top). */
typedef struct measure_seam_frame_t {
    core_image_t img;
    float *dist;
    uint8_t *cls;
} measure_seam_frame_t;
/* Reads the frame drawn into t with view v (blocking) by world_draw_as
 * (whose depth holds the grass's on either path): colour and distance;
 * cls EVAL_SEAM_GROUND where the visible surface is the terrain, else
 * EVAL_SEAM_SKIP (what a background frame needs). */
bool measure_seam_frame_read(world_t *w, const grass_view_t *v, const gfx_target_t *t, measure_seam_frame_t *f);
/* Classes of a frame against the background (the same view with no grass):
 * skipped where the background does not show the terrain, grass where the
 * colour differs from it by more than 8 levels in a channel, else ground. */
void measure_seam_frame_classify(measure_seam_frame_t *f, const measure_seam_frame_t *background);
/* Draws the view into t in `mode`, with no grass at all when !grass (the
 * background), and reads it (measure_seam_frame_read). The world's systems are
 * used as they are (nothing is built or simulated) and keep their state. */
bool measure_seam_frame_draw(world_t *w, const grass_view_t *v, const gfx_target_t *t, scene_mode_t mode, bool grass,
                         measure_seam_frame_t *f);
void measure_seam_frame_free(measure_seam_frame_t *f);
/* The scene's switch distance and the fade band of grass_draw. */
eval_seam_desc_t measure_seam_desc(world_t *w);
/* The seam of the hybrid frame of view v (drawn into t again, for its
 * depth), against the same
 * view drawn again with billboards only, both classified against it drawn
 * with no grass (which is what t holds afterwards). False when the world is
 * not in hybrid mode or a window of the band shows no grass or fewer than
 * 100 counted pixels (in either frame). */
bool measure_seam(world_t *w, const grass_view_t *v, const gfx_target_t *t, eval_seam_t *out);
/* The same at the canopy's band, the pixels of both images in the band's
 * windows by the terrain's distance: with billboards (grass.canopy_distance
 * +- GRASS_CANOPY_FADE) billboards to the ground canopy against billboards
 * to the horizon; without (grass.billboards none; the switch band) the
 * blades to the canopy against blades across the band (world_draw_tiles_to;
 * nearer than the band's centre the frame itself). False as measure_seam,
 * without a canopy, and when the reference's tiles cannot be made. */
/* The canopy seam's reference (without billboards) draws its blades this
 * far (m) beyond the band's far window: past the fade where they end (1 m)
 * and the tiles' hysteresis (1 m), as the truth runs' 60 m tiles did for a
 * 50 m switch (docs/journal/2026-11-29-canopy-seam-truth.md). */
#define MEASURE_SEAM_REACH 5.0f
/* Where that reference's blades end (m) for a band at switch_distance: its
 * far window's end (eval_seam_desc_defaults) plus MEASURE_SEAM_REACH. */
float measure_canopy_seam_reach(float switch_distance);
bool measure_canopy_seam(world_t *w, const grass_view_t *v, const gfx_target_t *t, eval_seam_t *out);
/* The seam's noise floor for this view: the billboards built again with
 * MEASURE_SEAM_FLOOR_PLACEMENTS other placement seeds, each drawn
 * billboard-only (undeformed) against the world's own billboard-only frame:
 * what the measure reads where only where billboards stand differs
 * (docs/METRICS.md). One placement's score varies by 2-7x from seed to
 * seed (meadow_large at frame 120 on the H100: 0.039, 0.208, 0.049), so
 * the floor is their mean (score and terms), each placement's score kept
 * beside it. The world's billboards are kept and restored. False as
 * measure_seam, or when a field cannot be built. */
#define MEASURE_SEAM_FLOOR_PLACEMENTS 3
typedef struct measure_seam_floor_t {
    eval_seam_t mean; /* score, delta_e, delta_l, coverage: means over the placements */
    double score[MEASURE_SEAM_FLOOR_PLACEMENTS];
} measure_seam_floor_t;
bool measure_seam_floor(world_t *w, const grass_view_t *v, const gfx_target_t *t, measure_seam_floor_t *out);
/* GPU ms to draw `triangles` trivial triangles from a prebuilt buffer into a
 * w x h target with `samples` MSAA (median of 12 draws); -1 on failure. */
double measure_floor_ms(long triangles, int w, int h, int samples);
/* The same triangles through the compute rasterizer (raster_samples per
 * pixel: 1 or 4) into a w x h target of `samples`: raster_begin, the draw
 * with trivial shading and raster_end, median GPU ms of 12; -1 when it
 * cannot be measured, 0 for no triangles. */
double measure_floor_compute_ms(long triangles, int w, int h, int samples, int raster_samples);

typedef struct measure_stats_t {
    long blades;            /* real blades on the GPU */
    long blade_survivors;   /* in the last draw command */
    unsigned blade_culled[4]; /* orientation, frustum, distance, occlusion */
    long blade_patch_culled;
    unsigned tiles_culled[4]; /* the hybrid's tiles: orientation, frustum, distance, occlusion */
    long tiles_tile_culled;   /* blades of blade tiles culled by the CPU frustum test */
    long billboards;
    int bb_deformed;
    double bb_generate_ms, bb_make_ms; /* GPU generation pass, CPU make (once) */
    double bb_make_stage_ms[BB_MAKE_STAGES];
    int characters;
    int tiles_active, tiles_recovering, tiles_blade, tile_slots_used, tile_slots_total;
    long tile_blades_simulated;
    long tile_handovers, tile_seeded; /* blades -> billboards, billboards -> blades, run totals */
    long triangles;         /* estimated triangles drawn by the grass */
} measure_stats_t;

/* Counts of the last frame (blocking reads: for summaries, not the frame). */
void measure_stats(world_t *w, measure_stats_t *st);
/* The name of billboard start-up stage k < MEASURE_BB_STAGES
 * (measure_stats_t.bb_make_stage_ms). */
#define MEASURE_BB_STAGES BB_MAKE_STAGES
const char *measure_bb_stage_name(int k);

/* What the harness and the program's logs read of the grass beyond
 * measure_stats, the parts asked for (zero where the grass lacks the
 * system): sizes the measures' buffers need (CPU state), the billboard
 * octree's leaves by state (a walk over the leaves), the tiles' work
 * (wait: this frame's counters, blocking; else the latest read back). */
enum { MEASURE_GRASS_SIZES = 1, MEASURE_GRASS_LEAVES = 2, MEASURE_GRASS_TILES = 4 };
typedef struct measure_grass_t {
    uint32_t blade_padded;    /* the blade field's blades with padding */
    long blades_total;        /* the blade field's real blades */
    int bb_billboards, bb_mesh_vertices;
    long bb_leaves_colliding, bb_leaves_recovering; /* octree leaves in those states */
    int tiles_active, tiles_recovering, tile_slots_dispatched;
    long tile_blades_dispatched, tiles_streamed_total;
} measure_grass_t;
void measure_grass(world_t *w, unsigned parts, bool wait, measure_grass_t *out);
/* summary.txt's lines on a world's billboard ring and tile window and on
 * the compute rasterizer's buffers, into buf; the characters written. */
int measure_grass_lines(world_t *w, char *buf, size_t size);

#endif
