/* scene_lod: reads the bench's lod.json and picks the switch distances for
 * a renderer and rasterizer path (see scene_lod.h). */
#include "scene/scene_lod.h"

#include "core/core.h"
#include "scene/scene_json.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const scene_json_t *member(const scene_json_t *o, const char *key, scene_json_type_t type)
{
    const scene_json_t *v = o && o->type == SCENE_JSON_OBJECT ? scene_json_get(o, key) : NULL;
    return v && v->type == type ? v : NULL;
}

static bool read_path(const scene_json_t *p, scene_lod_pick_t *out, const char *name, const char *file, char *err,
                      size_t err_size)
{
    static const char *const keys[] = {"switch_distance", "canopy_distance", "gpu_ms", "image_error", "budget"};
    double v[5];
    for (int k = 0; k < 5; k++) {
        const scene_json_t *n = member(p, keys[k], SCENE_JSON_NUMBER);
        if (!n) {
            snprintf(err, err_size, "%s:%d: paths.%s needs a number \"%s\"", file, p->line, name, keys[k]);
            return false;
        }
        v[k] = n->number;
    }
    const scene_json_t *met = member(p, "met", SCENE_JSON_BOOL), *cand = member(p, "candidates", SCENE_JSON_NUMBER);
    const scene_json_t *label = member(p, "label", SCENE_JSON_STRING);
    const scene_json_t *bb = member(p, "billboards", SCENE_JSON_STRING), *wall = member(p, "wall_ms", SCENE_JSON_NUMBER);
    if (bb && strcmp(bb->string, "ring") != 0 && strcmp(bb->string, "none") != 0) {
        snprintf(err, err_size, "%s:%d: paths.%s.billboards: \"%s\" is not \"ring\" or \"none\"", file, bb->line, name,
                 bb->string);
        return false;
    }
    if (v[0] < 0.0 || v[1] < v[0] || !met) {
        snprintf(err, err_size, "%s:%d: paths.%s: switch_distance >= 0, canopy_distance >= switch_distance and a "
                 "boolean \"met\" are required", file, p->line, name);
        return false;
    }
    *out = (scene_lod_pick_t){.present = true, .switch_distance = (float)v[0], .canopy_distance = (float)v[1],
                              .gpu_ms = v[2], .image_error = v[3], .budget = v[4], .met = met->boolean,
                              .candidates = cand ? (int)cand->number : 0,
                              .billboards = bb && strcmp(bb->string, "none") == 0 ? SCENE_HYBRID_BILLBOARDS_NONE
                                                                                 : SCENE_HYBRID_BILLBOARDS_RING,
                              .wall_ms = wall ? wall->number : v[2]};
    if (label) snprintf(out->label, sizeof out->label, "%s", label->string);
    return true;
}

bool scene_lod_read(scene_lod_t *t, const char *path, char *err, size_t err_size)
{
    memset(t, 0, sizeof *t);
    char why[256];
    char *text = core_fs_read(path, NULL, why, sizeof why);
    if (!text) {
        snprintf(err, err_size, "%s: %s", path, why);
        return false;
    }
    scene_json_doc_t doc = {0};
    bool ok = scene_json_parse(&doc, text, path, err, err_size);
    free(text);
    if (!ok) return false;
    const scene_json_t *renderer = member(doc.root, "renderer", SCENE_JSON_STRING);
    const scene_json_t *paths = member(doc.root, "paths", SCENE_JSON_OBJECT);
    if (!renderer || !paths) {
        snprintf(err, err_size, "%s: not a lod.json (needs a \"renderer\" string and a \"paths\" object)", path);
        ok = false;
    }
    static const char *const names[2] = {"hw", "compute"};
    for (int k = 0; ok && k < 2; k++) {
        const scene_json_t *p = member(paths, names[k], SCENE_JSON_OBJECT);
        if (p) ok = read_path(p, &t->path[k], names[k], path, err, err_size);
    }
    if (ok && !t->path[0].present && !t->path[1].present) {
        snprintf(err, err_size, "%s: \"paths\" holds neither \"hw\" nor \"compute\"", path);
        ok = false;
    }
    if (ok) snprintf(t->renderer, sizeof t->renderer, "%s", renderer->string);
    scene_json_free(&doc);
    return ok;
}

const scene_lod_pick_t *scene_lod_choose(const scene_lod_t *t, const char *renderer, int path, bool *compute)
{
    if (!renderer || strcmp(renderer, t->renderer) != 0) return NULL;
    if (path < 0) {
        const scene_lod_pick_t *hw = &t->path[0], *cs = &t->path[1];
        path = !hw->present || (cs->present && cs->wall_ms < hw->wall_ms) ? 1 : 0;
    }
    *compute = path == 1;
    return t->path[path].present ? &t->path[path] : NULL;
}

bool scene_lod_apply(scene_desc_t *s, const char *renderer, bool *compute, char *note, size_t note_size)
{
    scene_grass_desc_t *g = &s->grass;
    char path[1024], err[1024];
    if (!core_fs_resolve(g->lod_table, path, sizeof path)) snprintf(path, sizeof path, "%s", g->lod_table);
    scene_lod_t t;
    if (!scene_lod_read(&t, path, err, sizeof err)) {
        core_log_warn("grass.lod_table: %s; keeping the scene's distances", err);
        snprintf(note, note_size, "not read (%.400s): the scene's distances", err);
        return false;
    }
    bool auto_path = s->raster == SCENE_RASTER_AUTO;
    const scene_lod_pick_t *p = scene_lod_choose(&t, renderer, auto_path ? -1 : (*compute ? 1 : 0), compute);
    if (!p) {
        core_log_warn("grass.lod_table %s: measured on '%s' (or without the %s path), this GL is '%s': keeping the "
                      "scene's distances", g->lod_table, t.renderer, *compute ? "compute" : "hw", renderer);
        snprintf(note, note_size, "%.200s measured on '%.200s', not this GL: the scene's distances", g->lod_table,
                 t.renderer);
        return false;
    }
    g->switch_distance = p->switch_distance;
    g->canopy_distance = p->canopy_distance;
    g->billboards = p->billboards;
    bool ring = p->billboards == SCENE_HYBRID_BILLBOARDS_RING;
    snprintf(note, note_size,
             "%s path%s, from %.200s: %s; %.3f ms wall (%.3f ms GPU) at image error %.3f, %s budget %.3f; the "
             "cheapest within it of %d hybrid configurations",
             *compute ? "compute" : "hw", auto_path ? " (the table's cheaper)" : "", g->lod_table,
             ring ? "blades, billboards, canopy" : "blades, canopy (no billboards)", p->wall_ms, p->gpu_ms,
             p->image_error, p->met ? "within its" : "NOT within its (the least error within the memory instead)", p->budget,
             p->candidates);
    core_log_info("lod: switch %.1f m, canopy %.1f m, %s", g->switch_distance,
                  ring ? g->canopy_distance : g->switch_distance, note);
    return true;
}
