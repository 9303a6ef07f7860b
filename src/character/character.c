/* character: GPU skinning (skin.comp, linear blend skinning, the twin of
 * character_skin_cpu), lit drawing, walking characters and their collision
 * proxies for the blades (spheres, Jahrmann & Wimmer 2017) and the
 * billboards (skinned mesh + bounding sphere, Orthmann et al. 2009). All GL
 * objects come from gfx. See character.h. */
#include "character/character.h"
#include "character/character_walk.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/bindings_character.glsl"

character_set_desc_t character_set_desc_defaults(const character_set_desc_t *d)
{
    character_set_desc_t r = *d;
    if (!r.capsules) r.capsules = CHARACTER_DEFAULT_CAPSULES;
    return r;
}

/* ---- assets ------------------------------------------------------------------ */
static void asset_free(character_asset_t *a)
{
    gfx_buffer_destroy(&a->vertices);
    gfx_buffer_destroy(&a->indices);
    if (a->texture.id) gfx_texture_destroy(&a->texture);
    free(a->bone_spheres);
    character_model_free(&a->model);
    memset(a, 0, sizeof *a);
}

/* Per bone: a sphere around every vertex it influences, in bind model space,
 * grown by how far its morph targets can move it (character_morph_reach).
 * A skinned vertex is a convex combination of S_i p over its bones, so the
 * spheres moved by S_i bound the skinned mesh (see instance_bounds). */
static bool asset_bone_spheres(character_asset_t *a)
{
    const character_model_t *m = &a->model;
    a->bone_spheres = malloc((size_t)m->bone_count * sizeof *a->bone_spheres);
    double(*sum)[4] = calloc((size_t)m->bone_count, sizeof *sum);
    if (!a->bone_spheres || !sum) {
        free(sum);
        core_log_error("%s: out of memory", a->path);
        return false;
    }
    for (int v = 0; v < m->vertex_count; v++)
        for (int k = 0; k < CHARACTER_MAX_INFLUENCES; k++) {
            if (m->vertices[v].weights[k] <= 0.0f) continue;
            double *s = sum[m->vertices[v].joints[k]];
            for (int c = 0; c < 3; c++) s[c] += m->vertices[v].pos[c];
            s[3] += 1.0;
        }
    for (int b = 0; b < m->bone_count; b++) {
        float *bs = a->bone_spheres[b];
        bs[3] = -1.0f;
        if (sum[b][3] == 0.0) continue;
        for (int c = 0; c < 3; c++) bs[c] = (float)(sum[b][c] / sum[b][3]);
        bs[3] = 0.0f;
    }
    for (int v = 0; v < m->vertex_count; v++)
        for (int k = 0; k < CHARACTER_MAX_INFLUENCES; k++) {
            if (m->vertices[v].weights[k] <= 0.0f) continue;
            float *bs = a->bone_spheres[m->vertices[v].joints[k]];
            const float *p = m->vertices[v].pos;
            float d = sqrtf((p[0] - bs[0]) * (p[0] - bs[0]) + (p[1] - bs[1]) * (p[1] - bs[1]) +
                            (p[2] - bs[2]) * (p[2] - bs[2])) + character_morph_reach(m, v);
            bs[3] = fmaxf(bs[3], d * 1.0001f + 1e-6f);
        }
    free(sum);
    return true;
}

/* The model's texture (embedded or a file) as a GL texture; problems are
 * warnings and leave the plain base colour. */
static void asset_texture(character_asset_t *a)
{
    const character_model_t *m = &a->model;
    const character_image_t *e = &m->texture_embedded;
    core_image_t img = {0};
    char why[256] = "";
    bool ok = false;
    if (e->data && e->height > 0) {
        ok = core_image_alloc(&img, e->width, e->height, 4);
        for (size_t i = 0; ok && i < (size_t)e->width * (size_t)e->height; i++) {
            const unsigned char *bgra = e->data + 4 * i;
            img.px[4 * i] = bgra[2], img.px[4 * i + 1] = bgra[1], img.px[4 * i + 2] = bgra[0];
            img.px[4 * i + 3] = bgra[3];
        }
        if (!ok) snprintf(why, sizeof why, "out of memory");
    } else if (e->data) {
        ok = core_image_decode(&img, e->data, e->size, 4, why, sizeof why);
    } else if (m->texture_path[0]) {
        size_t size = 0;
        char *file = core_fs_read(m->texture_path, &size, why, sizeof why);
        ok = file && core_image_decode(&img, file, size, 4, why, sizeof why);
        free(file);
    } else {
        return;
    }
    if (!ok) {
        core_log_warn("%s: texture %s unreadable (%s); using the base colour", a->path,
                      e->data ? "(embedded)" : m->texture_path, why);
        core_image_free(&img);
        return;
    }
    a->texture = gfx_texture_make(&(gfx_texture_desc_t){.w = img.w, .h = img.h, .mip_levels = -1, .wrap = GL_REPEAT,
                                                        .format = GL_SRGB8_ALPHA8, .data = img.px,
                                                        .label = "character.texture"});
    core_image_free(&img);
}

static bool asset_load(character_asset_t *a, const char *resolved, int index)
{
    char err[512];
    snprintf(a->path, sizeof a->path, "%s", resolved);
    if (!character_load(&a->model, resolved, err, sizeof err)) return false; /* logged by the loader */
    if (!character_import(&a->model, resolved, &a->import_desc, &a->import, err, sizeof err) ||
        !character_walk_face(&a->model, resolved, a->import_desc.yaw, &a->import, err, sizeof err)) {
        core_log_error("character %d: %s: %s", index, resolved, err);
        return false;
    }
    character_import_report(resolved, &a->import);
    const character_model_t *m = &a->model;
    a->vertices = gfx_buffer_make(&(gfx_buffer_desc_t){.size = (size_t)m->vertex_count * sizeof(character_vertex_t),
                                                       .data = m->vertices, .label = "character.bind_vertices"});
    a->indices = gfx_buffer_make(&(gfx_buffer_desc_t){.size = (size_t)m->index_count * sizeof(uint32_t),
                                                      .data = m->indices, .label = "character.indices"});
    if (!a->vertices.id || !a->indices.id) return false;
    asset_texture(a);
    return asset_bone_spheres(a);
}

/* Finds the asset for a (repository-relative or absolute) path and import
 * settings, loading it the first time. Returns its index or -1 after one
 * error line. */
static int asset_get(character_set_t *set, const char *path, const character_import_desc_t *imp, int index)
{
    char resolved[1024];
    if (!core_fs_resolve(path, resolved, sizeof resolved)) {
        core_log_error("character %d: model file %s not found", index, path);
        return -1;
    }
    for (int i = 0; i < set->asset_count; i++)
        if (strcmp(set->assets[i].path, resolved) == 0 && !memcmp(&set->assets[i].import_desc, imp, sizeof *imp))
            return i;
    character_asset_t *a = &set->assets[set->asset_count++];
    a->import_desc = *imp;
    return asset_load(a, resolved, index) ? set->asset_count - 1 : -1;
}

/* ---- instances ------------------------------------------------------------------ */
/* The clip `spec` names for a character of model m (file `path`): a name of
 * its scene entry's "clips" (a range of clip 0), else a clip of the file
 * (character_clip_find); a still clip (duration 0) gives way to the next
 * one that moves, with a warning. False after one error line: an unknown
 * clip (the message lists the model's clips and the scene's ranges) or a
 * range off the model's timeline. */
static bool instance_clip(character_instance_t *inst, int index, character_model_t *m, const char *path,
                          const char *spec)
{
    const scene_character_t *d = &inst->desc;
    char why[192];
    double a, b;
    inst->clip = -1;
    for (int i = 0; i < d->clip_range_count && inst->clip < 0; i++) {
        const scene_clip_range_t *r = &d->clip_ranges[i];
        if (strcmp(r->name, spec) != 0) continue;
        if (!character_clip_range_check(m, r->range[0], r->range[1], why, sizeof why)) {
            core_log_error("character %d: clips.%s [%g, %g] in %s: %s", index, r->name, (double)r->range[0],
                           (double)r->range[1], path, why);
            return false;
        }
        inst->clip = character_clip_range(m, r->name, r->range[0], r->range[1]);
        if (inst->clip < 0) return false; /* out of memory, logged */
    }
    if (inst->clip < 0 && character_clip_parse_range(spec, &a, &b) &&
        !character_clip_range_check(m, a, b, why, sizeof why)) {
        core_log_error("character %d: clip range \"%s\" in %s: %s", index, spec, path, why);
        return false;
    }
    if (inst->clip < 0) inst->clip = character_clip_find(m, spec);
    if (inst->clip < 0) {
        char list[768], ranges[SCENE_MAX_CLIP_RANGES * (SCENE_NAME_MAX + 4)] = "";
        size_t n = 0;
        for (int i = 0; i < d->clip_range_count && n < sizeof ranges; i++) {
            int w = snprintf(ranges + n, sizeof ranges - n, "%s'%s'", i ? ", " : "; its scene ranges: ",
                             d->clip_ranges[i].name);
            n += w > 0 ? (size_t)w : 0;
        }
        character_clip_list(m, list, sizeof list);
        core_log_error("character %d: no clip \"%s\" in %s; its clips: %s%s", index, spec, path, list, ranges);
        return false;
    }
    int play = character_clip_playable(m, inst->clip);
    if (play != inst->clip) {
        core_log_warn("character %d: clip '%s' of %s has no duration (one frame); playing '%s', the next clip "
                      "that moves",
                      index, m->clips[inst->clip].name, path, m->clips[play].name);
        inst->clip = play;
    }
    return true;
}

static bool instance_make(character_set_t *set, character_instance_t *inst, int index, const char *clip_override)
{
    character_asset_t *a = &set->assets[inst->asset];
    character_model_t *m = &a->model;
    char spec[SCENE_NAME_MAX + 16];
    if (clip_override && clip_override[0]) snprintf(spec, sizeof spec, "%s", clip_override);
    else if (inst->desc.clip_name[0]) snprintf(spec, sizeof spec, "%s", inst->desc.clip_name);
    else snprintf(spec, sizeof spec, "%d", inst->desc.clip_index);
    if (m->clip_count == 0) {
        inst->clip = -1; /* rigid or unanimated: bind pose */
    } else if (!instance_clip(inst, index, m, a->path, spec)) {
        return false;
    }
    if (inst->clip >= 0) character_clip_stride(m, inst->clip, &inst->stride);
    inst->rate = character_walk_rate(&inst->stride, inst->desc.speed, inst->desc.scale);

    inst->index_count = m->index_count;
    if (!character_pose_init(&inst->pose, m)) return false;
    inst->bones = gfx_buffer_make(&(gfx_buffer_desc_t){.size = (size_t)m->bone_count * 16 * sizeof(float),
                                                       .dynamic = true, .label = "character.bones"});
    inst->skinned = gfx_buffer_make(&(gfx_buffer_desc_t){
        .size = (size_t)m->vertex_count * sizeof(character_skinned_vertex_t),
        .label = "character.skinned"});
    if (!inst->bones.id || !inst->skinned.id) return false;
    if (m->morph_count) {
        inst->morphed = malloc((size_t)m->vertex_count * sizeof *inst->morphed);
        inst->morph_vertices = gfx_buffer_make(&(gfx_buffer_desc_t){
            .size = (size_t)m->vertex_count * sizeof(character_vertex_t), .dynamic = true,
            .label = "character.morph_vertices"});
        if (!inst->morphed || !inst->morph_vertices.id) {
            core_log_error("character %d: out of memory for %d morphed vertices", index, m->vertex_count);
            return false;
        }
    }
    inst->vao = gfx_vertex_array_make("character.vao");
    glVertexArrayVertexBuffer(inst->vao, 0, inst->skinned.id, 0, sizeof(character_skinned_vertex_t));
    glVertexArrayVertexBuffer(inst->vao, 1, a->vertices.id, 0, sizeof(character_vertex_t));
    glVertexArrayElementBuffer(inst->vao, a->indices.id);
    for (GLuint k = 0; k < 2; k++) {
        glEnableVertexArrayAttrib(inst->vao, k);
        glVertexArrayAttribFormat(inst->vao, k, 3, GL_FLOAT, GL_FALSE, k * 4 * sizeof(float));
        glVertexArrayAttribBinding(inst->vao, k, 0);
    }
    glEnableVertexArrayAttrib(inst->vao, 2);
    glVertexArrayAttribFormat(inst->vao, 2, 2, GL_FLOAT, GL_FALSE, offsetof(character_vertex_t, uv));
    glVertexArrayAttribBinding(inst->vao, 2, 1);

    /* Capsules fitted once at the bind pose (straight limbs give the best
     * principal axes); later frames move their bone-space ends rigidly. */
    float *bind = malloc((size_t)m->vertex_count * 3 * sizeof(float));
    inst->capsules = malloc((size_t)set->capsules * sizeof *inst->capsules);
    if (!bind || !inst->capsules) {
        free(bind);
        core_log_error("character %d: out of memory", index);
        return false;
    }
    character_skin_cpu(m, &inst->pose, bind, NULL);
    inst->capsule_count = character_fit_capsules(m, &inst->pose, bind, inst->capsules, set->capsules);
    free(bind);
    inst->capsule_first_sphere = malloc((size_t)(inst->capsule_count + 1) * sizeof(int));
    if (!inst->capsule_first_sphere) return false;
    inst->sphere_count = 0;
    for (int c = 0; c < inst->capsule_count; c++) {
        inst->capsule_first_sphere[c] = inst->sphere_count;
        inst->sphere_count += character_capsule_sphere_count(&inst->capsules[c]);
    }
    inst->capsule_first_sphere[inst->capsule_count] = inst->sphere_count;
    inst->spheres = calloc((size_t)inst->sphere_count + 1, sizeof *inst->spheres);
    inst->sphere_now = calloc((size_t)inst->sphere_count + 1, sizeof *inst->sphere_now);
    if (!inst->spheres || !inst->sphere_now) {
        core_log_error("character %d: out of memory", index);
        return false;
    }
    return true;
}

static void instance_free(character_instance_t *inst)
{
    character_pose_free(&inst->pose);
    gfx_buffer_destroy(&inst->bones);
    gfx_buffer_destroy(&inst->skinned);
    gfx_buffer_destroy(&inst->morph_vertices);
    free(inst->morphed);
    if (inst->vao) gfx_vertex_array_destroy(&inst->vao);
    free(inst->capsules);
    free(inst->capsule_first_sphere);
    free(inst->spheres);
    free(inst->sphere_now);
}

bool character_set_make(character_set_t *set, const character_set_desc_t *desc_in)
{
    character_set_desc_t d = character_set_desc_defaults(desc_in);
    memset(set, 0, sizeof *set);
    set->terrain = d.terrain;
    set->capsules = d.capsules;
    int count = d.count;
    bool synthetic = count == 0 && d.model_override && d.model_override[0];
    if (synthetic) count = 1;
    if (count == 0) return true;
    set->items = calloc((size_t)count, sizeof *set->items);
    set->assets = calloc((size_t)count, sizeof *set->assets);
    if (!set->items || !set->assets) {
        core_log_error("characters: out of memory for %d characters", count);
        character_set_destroy(set);
        return false;
    }
    gfx_program_t progs[2];
    gfx_programs_make(2,
                      (gfx_program_desc_t[2]){{.cs = "character/skin.comp", .label = "character.skin"},
                                              {.vs = "character/character.vert", .fs = "character/character.frag",
                                               .label = "character.draw"}},
                      progs);
    set->skin_prog = progs[0];
    set->draw_prog = progs[1];
    if (!set->skin_prog.id || !set->draw_prog.id) {
        character_set_destroy(set);
        return false;
    }
    for (int i = 0; i < count; i++) {
        character_instance_t *inst = &set->items[i];
        set->count = i + 1;
        if (synthetic) {
            inst->desc = (scene_character_t){.speed = 1.2f, .scale = 1.0f};
        } else {
            inst->desc = d.characters[i];
        }
        if (d.model_override && d.model_override[0])
            snprintf(inst->desc.model, sizeof inst->desc.model, "%s", d.model_override);
        if (inst->desc.scale <= 0.0f) inst->desc.scale = 1.0f;
        if (d.height_override > 0.0f) inst->desc.height = d.height_override;
        character_import_desc_t imp = {.height = inst->desc.height, .up = scene_axis_code(inst->desc.up),
                                       .forward = scene_axis_code(inst->desc.forward), .yaw = inst->desc.rotation};
        inst->asset = asset_get(set, inst->desc.model, &imp, i);
        if (inst->asset < 0 || !instance_make(set, inst, i, d.clip_override)) {
            character_set_destroy(set);
            return false;
        }
    }
    character_set_update(set, 0.0f, 0.0f);
    return true;
}

void character_set_destroy(character_set_t *set)
{
    for (int i = 0; i < set->count; i++) instance_free(&set->items[i]);
    for (int i = 0; i < set->asset_count; i++) asset_free(&set->assets[i]);
    if (set->skin_prog.id) gfx_program_destroy(&set->skin_prog);
    if (set->draw_prog.id) gfx_program_destroy(&set->draw_prog);
    free(set->items);
    free(set->assets);
    memset(set, 0, sizeof *set);
}

/* ---- per frame ------------------------------------------------------------------ */
static void mat4_point(const float m[16], const float p[3], float out[3])
{
    float r[3];
    for (int k = 0; k < 3; k++) r[k] = m[k] * p[0] + m[4 + k] * p[1] + m[8 + k] * p[2] + m[12 + k];
    memcpy(out, r, sizeof r);
}

/* Upper bound of the stretch of a 3x3 block: sqrt of the Gershgorin bound on
 * the largest eigenvalue of M^T M (exact for rotations times a scale). */
static float mat3_stretch(const float m[16])
{
    float g[3][3], best = 0.0f;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            g[i][j] = m[4 * i] * m[4 * j] + m[4 * i + 1] * m[4 * j + 1] + m[4 * i + 2] * m[4 * j + 2];
    for (int i = 0; i < 3; i++) best = fmaxf(best, fabsf(g[i][0]) + fabsf(g[i][1]) + fabsf(g[i][2]));
    return sqrtf(best);
}

/* World bounding sphere: each bone's vertex sphere moved by its skinning
 * matrix then the model matrix; the skinned mesh lies in their convex hull,
 * so a sphere holding all of them holds every skinned vertex. */
static void instance_bounds(const character_set_t *set, character_instance_t *inst)
{
    const character_asset_t *a = &set->assets[inst->asset];
    int nb = a->model.bone_count, used = 0;
    float lo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, hi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    float(*ws)[4] = malloc((size_t)nb * sizeof *ws);
    if (!ws) return;
    for (int b = 0; b < nb; b++) {
        if (a->bone_spheres[b][3] < 0.0f) continue;
        float full[16];
        character_mat4_mul(inst->model, inst->pose.skin[b], full);
        mat4_point(full, a->bone_spheres[b], ws[used]);
        ws[used][3] = a->bone_spheres[b][3] * mat3_stretch(full);
        for (int k = 0; k < 3; k++)
            lo[k] = fminf(lo[k], ws[used][k] - ws[used][3]), hi[k] = fmaxf(hi[k], ws[used][k] + ws[used][3]);
        used++;
    }
    float r = 0.0f;
    for (int k = 0; k < 3; k++) inst->centre[k] = 0.5f * (lo[k] + hi[k]);
    /* model = T(position) R s: its inverse is R^T (p - position) / s^2 */
    const float *m = inst->model;
    float d[3] = {inst->centre[0] - m[12], inst->centre[1] - m[13], inst->centre[2] - m[14]};
    float s2 = m[0] * m[0] + m[1] * m[1] + m[2] * m[2];
    for (int k = 0; k < 3; k++)
        inst->centre_model[k] = (m[4 * k] * d[0] + m[4 * k + 1] * d[1] + m[4 * k + 2] * d[2]) / s2;
    for (int i = 0; i < used; i++) {
        float dx = ws[i][0] - inst->centre[0], dy = ws[i][1] - inst->centre[1], dz = ws[i][2] - inst->centre[2];
        r = fmaxf(r, sqrtf(dx * dx + dy * dy + dz * dz) + ws[i][3]);
    }
    inst->radius = r;
    free(ws);
}

/* Blade spheres. The blade physics runs once per frame, so a limb that moves
 * more than a blade's width in one frame could pass through it. Each sphere
 * is therefore swept: centred halfway between its previous and current
 * centre, radius grown by half the distance, so it holds everything the
 * unswept sphere covered during the step (and its current position). */
static void instance_spheres(character_instance_t *inst, bool sweep)
{
    for (int c = 0; c < inst->capsule_count; c++) {
        const character_capsule_t *cap = &inst->capsules[c];
        float full[16], a[3], b[3];
        character_mat4_mul(inst->model, inst->pose.global[cap->bone], full);
        mat4_point(full, cap->local_a, a);
        mat4_point(full, cap->local_b, b);
        int first = inst->capsule_first_sphere[c], n = inst->capsule_first_sphere[c + 1] - first;
        character_capsule_spheres(a, b, cap->radius * inst->desc.scale, n, inst->spheres + first);
        for (int i = first; i < first + n; i++) {
            float cur[4], *out = inst->spheres[i], *prev = inst->sphere_now[i];
            memcpy(cur, out, sizeof cur);
            if (sweep) {
                float d2 = 0.0f;
                for (int k = 0; k < 3; k++) {
                    d2 += (cur[k] - prev[k]) * (cur[k] - prev[k]);
                    out[k] = 0.5f * (cur[k] + prev[k]);
                }
                out[3] = cur[3] + 0.5f * sqrtf(d2);
            }
            memcpy(prev, cur, sizeof cur);
        }
    }
}

void character_set_view(character_set_t *set, const float camera[3], float lod_distance)
{
    memcpy(set->view_camera, camera, sizeof set->view_camera);
    set->lod_distance = lod_distance;
}

void character_set_update(character_set_t *set, float time, float dt)
{
    if (!set->count) return;
    int posed = 0;
    for (int i = 0; i < set->count; i++) {
        character_instance_t *inst = &set->items[i];
        const character_model_t *m = &set->assets[inst->asset].model;
        character_walk_place(&inst->desc, set->terrain, inst->rate, time, &inst->clip_time, inst->position,
                             inst->dir, inst->model);
        int step = 1;
        if (set->lod_distance > 0.0f) {
            /* horizontal, as the reaches it stands for (a walker under a
             * high camera is in the tile window) */
            float dx = inst->position[0] - set->view_camera[0], dz = inst->position[2] - set->view_camera[2];
            step = character_pose_step(sqrtf(dx * dx + dz * dz), set->lod_distance);
        }
        inst->posed = character_pose_due(set->updates, i, step);
        if (!inst->posed) {
            /* the last pose carried along its walk */
            mat4_point(inst->model, inst->centre_model, inst->centre);
            inst->have_previous = false;
            continue;
        }
        posed++;
        if (inst->clip >= 0) character_sample_clip(m, inst->clip, inst->clip_time, true, &inst->pose);
        else character_pose_bind(m, &inst->pose);
        character_pose_globals(m, &inst->pose);
        gfx_buffer_update(inst->bones, 0, (size_t)m->bone_count * 16 * sizeof(float), inst->pose.skin);
        if (inst->morphed) {
            character_morph_apply(m, &inst->pose, inst->morphed);
            gfx_buffer_update(inst->morph_vertices, 0, (size_t)m->vertex_count * sizeof *inst->morphed,
                              inst->morphed);
        }
        instance_spheres(inst, inst->have_previous && dt > 0.0f);
        inst->have_previous = true;
        instance_bounds(set, inst);
    }
    set->updates++;
    gfx_count_add("character.posed", (double)posed);
    gfx_timer_begin(GFX_PASS_CHARACTER_SKIN);
    glUseProgram(set->skin_prog.id);
    GLint loc = gfx_uniform(set->skin_prog, "u_vertex_count");
    for (int i = 0; i < set->count; i++) {
        const character_instance_t *inst = &set->items[i];
        const character_asset_t *a = &set->assets[inst->asset];
        if (!inst->posed) continue;
        glUniform1ui(loc, (GLuint)a->model.vertex_count);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CHARACTER_BIND_VERTICES,
                         inst->morphed ? inst->morph_vertices.id : a->vertices.id);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CHARACTER_BIND_BONES, inst->bones.id);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CHARACTER_BIND_SKINNED, inst->skinned.id);
        glDispatchCompute((GLuint)(a->model.vertex_count + 63) / 64, 1, 1);
        gfx_count_add("character.skinned", (double)a->model.vertex_count);
    }
    glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CHARACTER_BIND_VERTICES, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CHARACTER_BIND_BONES, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CHARACTER_BIND_SKINNED, 0);
    glUseProgram(0);
    gfx_timer_end();
}

void character_set_draw(const character_set_t *set, const float viewproj[16], const float camera[3],
                        const float sun[3])
{
    if (!set->count) return;
    gfx_timer_begin(GFX_PASS_CHARACTER_DRAW);
    gfx_program_t p = set->draw_prog;
    glUseProgram(p.id);
    glUniformMatrix4fv(gfx_uniform(p, "u_viewproj"), 1, GL_FALSE, viewproj);
    glUniform3fv(gfx_uniform(p, "u_camera"), 1, camera);
    glUniform3fv(gfx_uniform(p, "u_sun"), 1, sun);
    for (int i = 0; i < set->count; i++) {
        const character_instance_t *inst = &set->items[i];
        const character_asset_t *a = &set->assets[inst->asset];
        glUniformMatrix4fv(gfx_uniform(p, "u_model"), 1, GL_FALSE, inst->model);
        glUniform4fv(gfx_uniform(p, "u_base_color"), 1, a->model.base_color);
        glUniform1i(gfx_uniform(p, "u_use_texture"), a->texture.id != 0);
        if (a->texture.id) glBindTextureUnit(CHARACTER_TEX_DIFFUSE, a->texture.id);
        glBindVertexArray(inst->vao);
        glDrawElements(GL_TRIANGLES, a->model.index_count, GL_UNSIGNED_INT, NULL);
    }
    glBindVertexArray(0);
    glUseProgram(0);
    gfx_timer_end();
}

/* ---- proxies ------------------------------------------------------------------ */
/* Spheres a caller's array had no room for: counted
 * ("character.spheres_dropped") and warned at every call that drops some. */
static void report_dropped(const char *what, int needed, int max)
{
    if (needed <= max) return;
    gfx_count_add("character.spheres_dropped", needed - max);
    core_log_warn("%s: %d proxy spheres needed, room for %d: %d left out", what, needed, max, needed - max);
}

int character_proxy_spheres(const character_instance_t *inst, float (*out)[4], int max)
{
    int n = inst->sphere_count < max ? inst->sphere_count : max;
    if (n > 0) memcpy(out, inst->spheres, (size_t)n * sizeof *out);
    report_dropped("character", inst->sphere_count, max);
    return inst->sphere_count;
}

int character_set_spheres(const character_set_t *set, float (*out)[4], int max)
{
    return character_set_spheres_near(set, NULL, 0.0f, out, max);
}

int character_set_spheres_near(const character_set_t *set, const float centre[3], float reach, float (*out)[4],
                               int max)
{
    int total = 0;
    for (int i = 0; i < set->count; i++) {
        const character_instance_t *inst = &set->items[i];
        if (centre && reach > 0.0f) {
            float dx = inst->centre[0] - centre[0], dz = inst->centre[2] - centre[2], r = reach + inst->radius;
            if (dx * dx + dz * dz > r * r) continue;
        }
        int room = max - total > 0 ? max - total : 0, n = inst->sphere_count < room ? inst->sphere_count : room;
        if (n > 0) memcpy(out + total, inst->spheres, (size_t)n * sizeof *out);
        total += inst->sphere_count;
    }
    report_dropped("characters", total, max);
    return total;
}

void character_bb_object(const character_instance_t *inst, character_object_t *out)
{
    out->vao = inst->vao;
    out->index_count = inst->index_count;
    out->index_type = GL_UNSIGNED_INT;
    memcpy(out->model, inst->model, sizeof out->model);
    memcpy(out->centre, inst->centre, sizeof out->centre);
    out->radius = inst->radius;
}

int character_set_objects(const character_set_t *set, character_object_t *out, int max)
{
    static bool warned;
    for (int i = 0; i < set->count && i < max; i++) {
        character_bb_object(&set->items[i], &out[i]);
    }
    if (set->count > max && !warned) {
        core_log_warn("characters: %d billboard objects, room for %d (logged once)", set->count, max);
        warned = true;
    }
    return set->count;
}

int character_set_count(const character_set_t *set) { return set->count; }

int character_set_describe(const character_set_t *set, char *buf, size_t size)
{
    size_t n = 0;
    if (size) buf[0] = 0;
    for (int i = 0; i < set->count && n < size; i++) {
        const character_instance_t *inst = &set->items[i];
        const character_asset_t *a = &set->assets[inst->asset];
        const character_import_t *im = &a->import;
        float sc = inst->desc.scale;
        int w = snprintf(buf + n, size - n,
                         "character %d: %s: height %.3f m, scale %.6g (units: %s; up %s: %s; forward %s: %s); "
                         "drawn box %.3f %.3f %.3f .. %.3f %.3f %.3f m; confidence %.2f%s\n",
                         i, inst->desc.model, (double)(im->height * sc), (double)(im->scale * sc), im->scale_from,
                         character_axis_name(im->up), im->up_from, character_axis_name(im->forward), im->forward_from,
                         (double)(im->box_min[0] * sc), (double)(im->box_min[1] * sc), (double)(im->box_min[2] * sc),
                         (double)(im->box_max[0] * sc), (double)(im->box_max[1] * sc), (double)(im->box_max[2] * sc),
                         (double)character_import_confidence(im),
                         character_import_confidence(im) < CHARACTER_IMPORT_LOW_CONFIDENCE ? " (low)" : "");
        if (w < 0) break;
        n += (size_t)w;
    }
    return set->count;
}
