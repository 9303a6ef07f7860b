/* bb_lod: coverage-preserving thinning of the billboard cards (issue 45;
 * Cook, Halstead, Planck and Ryu 2007, as blade_lod.h does it for the
 * blades): fewer cards with distance, the kept ones wider. GL-free; the
 * GLSL twin is shaders/billboard/bb_lod.glsl (bb_lod_card).
 *
 * The cards take blade_lod.h's rule, rank, shrink window and widening,
 * with the card in place of the blade:
 *   - its width (size[0]) for the blade's width in the rule (WIDTH: u = 1
 *     nearer than max(start, width * focal_px / width_px), D / d beyond);
 *   - its seed for the blade's index in the rank (blade_lod_rank): the
 *     seed is the card's own hash, fixed for its life, where its place in
 *     the points buffer moves as leaves change state and the ring refills;
 *   - the distance of its root to the eye.
 * A card of weight w and widening s is drawn w * s times as wide (a
 * deformed card's mesh stretched about its root along its right axis), its
 * height kept: as u falls a card narrows to nothing over the shrink window
 * before it is culled, so nothing pops, and the cards kept cover 1 / A(u, s)
 * times their area (up to max_scale), the area the full field covers.
 * The cards have no cull distance of their own (the hybrid's bands and the
 * world ring's canopy fade end them): no end fade, and the levels rules
 * need a level_distance. */
#ifndef MEADOW_BB_LOD_H
#define MEADOW_BB_LOD_H

#include <float.h>

#include "billboard/bb_ref.h"
#include "blade/blade_lod.h"

/* The cull distance the cards' rule runs with (none). */
#define BB_LOD_CULL FLT_MAX

/* The cards' rule from the blades' `lod` (NULL: off, rule BLADE_LOD_OFF,
 * which draws every card as it is), resolved, without the end fade. */
blade_lod_t bb_lod_rule(const blade_lod_t *lod);

/* Card p seen from `eye`: its weight (0: culled) and widening (rule off:
 * 1 and 1 at once); `rule` from bb_lod_rule, focal_px as blade_lod_focal. */
blade_lod_draw_t bb_lod_card(const blade_lod_t *rule, const bb_point_t *p, const float eye[3], float focal_px);

/* How much farther than unwidened (m) a card of base width card_width
 * (bb_field_desc_t.size[0]; cards are up to 1.2 times as wide) can reach
 * from its root when the rule widens it: 0.6 card_width (max_scale - 1),
 * 0 with the rule off or without compensation. The hardware path grows the
 * octree's leaf boxes by it when it culls leaves against the frustum
 * (bb_octree_collect), so a widened card at the screen's edge is not
 * culled with its leaf. */
float bb_lod_reach(const blade_lod_t *rule, float card_width);

#endif
