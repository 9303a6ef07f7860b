/* blade: GPU driver of the Jahrmann & Wimmer 2017 blades: upload, physics
 * dispatch (eq. 3-16), the patch test and per-blade culling (eq. 17-20)
 * on the GPU into an indirect command, tessellated or vertex-pulled
 * drawing (eq. 21-24), statistics read back a frame late; beyond both
 * papers, depth cube-map colliders in the physics (Orthmann et al. 2009
 * eq. 1-5). GL objects come from gfx only. */
#include "blade/blade_local.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* g->counters, uint words (blade_patch.glsl's Counters): culled per test,
 * the patch test's culled blades and listed patches, blade_cull.comp's
 * indirect dispatch (x, y, z, invocations), the distance buckets. The
 * readback takes the first CNT_READ words, then the command's 4. */
enum { CNT_PATCH_CULLED = 4, CNT_LISTED = 5, CNT_READ = 6, CNT_DISPATCH = 6, CNT_BUCKETS = 10,
       CNT_WORDS = CNT_BUCKETS + BLADE_PATCH_BUCKETS };

blade_gpu_desc_t blade_gpu_desc_defaults(const blade_gpu_desc_t *desc)
{
    blade_gpu_desc_t d = *desc;
    if (d.max_tess_level == 0) d.max_tess_level = 8;
    if (d.lod_distance == 0.0f) d.lod_distance = 30.0f;
    if (!d.label) d.label = "blade";
    d.cull = blade_cull_desc_defaults(&d.cull);
    assert(d.max_tess_level >= 1 && d.max_tess_level <= 64);
    assert(d.shape >= BLADE_SHAPE_QUADRATIC && d.shape <= BLADE_SHAPE_DANDELION);
    assert(d.path == BLADE_PATH_TESSELLATION || d.path == BLADE_PATH_PULLING);
    return d;
}

static gfx_buffer_t make_store(const blade_gpu_t *g, const char *what, size_t size, const void *data,
                               bool uninitialized)
{
    char label[128];
    snprintf(label, sizeof label, "%s.%s", g->desc.label, what);
    return gfx_buffer_make(&(gfx_buffer_desc_t){.size = size ? size : 16, .data = data, .dynamic = true,
                                                .uninitialized = uninitialized, .label = label});
}

static gfx_buffer_t make_buffer(const blade_gpu_t *g, const char *what, size_t size, const void *data)
{
    return make_store(g, what, size, data, false);
}

uint32_t blade_strip_vertices(int max_level, float displacement)
{
    uint32_t s = 2u * (uint32_t)(max_level + 1);
    return displacement > 0.0f ? 2u * s + 2u : s;
}

/* Indirect command layout: {count, instanceCount, first, baseInstance}. The
 * tessellation path counts patches (count, one instance), vertex pulling
 * counts instances of one strip (blade_strip_vertices). */
static void command_initial(const blade_gpu_t *g, uint32_t cmd[4])
{
    bool pull = g->desc.path == BLADE_PATH_PULLING;
    cmd[0] = pull ? blade_strip_vertices(g->desc.max_tess_level, g->desc.displacement) : 0u;
    cmd[1] = pull ? 0u : 1u;
    cmd[2] = 0u;
    cmd[3] = 0u;
}

/* Fills the zeroed g; false (logged) on failure, the caller releases. */
static bool gpu_init(blade_gpu_t *g, const blade_gpu_desc_t *desc)
{
    const blade_field_t *f = desc->field;
    const blade_gpu_seed_t *seed = desc->seed;
    assert((f != NULL) != (seed != NULL));
    g->desc = blade_gpu_desc_defaults(desc);
    g->desc.field = NULL;
    g->desc.seed = NULL;
    g->desc.cull.depth = NULL;
    const blade_seed_plan_t *plan = seed ? seed->plan : NULL;
    g->blade_count = (uint32_t)(f ? f->blade_count : plan->blade_count);
    g->padded_count = (uint32_t)(f ? f->padded_count : plan->padded_count);
    g->patch_count = (uint32_t)(f ? f->patch_count : plan->patch_count);
    int ps = f ? f->patch_size : plan->patch_size;
    g->patch_size = (uint32_t)(ps > 0 ? ps : 1);
    /* the patch boxes (blade_patch.glsl's PatchBox), lo.w their real blades;
     * a GPU seeding writes them itself */
    size_t np = g->patch_count ? g->patch_count : 1;
    float(*boxes)[8] = f ? calloc(np, sizeof *boxes) : NULL;
    if (f && !boxes) {
        core_log_error("blade_gpu_make: out of memory (%u patches)", g->patch_count);
        return false;
    }
    for (uint32_t p = 0; f && p < g->patch_count; p++) {
        memcpy(boxes[p], f->patch_aabbs[p].min, 3 * sizeof(float));
        memcpy(boxes[p] + 4, f->patch_aabbs[p].max, 3 * sizeof(float));
    }
    for (uint32_t i = 0; f && i < g->padded_count; i++) {
        if (f->blades[i].v1[3] <= 0.0f) continue;
        uint32_t real;
        memcpy(&real, &boxes[i / g->patch_size][3], sizeof real);
        real++;
        memcpy(&boxes[i / g->patch_size][3], &real, sizeof real);
    }

    size_t nb = g->padded_count;
    /* a GPU seeding writes every blade and eta; the cull writes the
     * survivors that the draws read */
    g->blades = make_store(g, "blades", nb * sizeof(blade_t), f ? f->blades : NULL, seed != NULL);
    g->eta = make_store(g, "eta", nb * sizeof(float), f ? f->eta : NULL, seed != NULL);
    g->winds = make_buffer(g, "winds", BLADE_MAX_WINDS * sizeof(blade_wind_t), NULL);
    g->sphere_capacity = BLADE_SPHERES_FIRST;
    g->spheres = make_buffer(g, "spheres", (size_t)g->sphere_capacity * sizeof(blade_sphere_t), NULL);
    g->survivors = make_store(g, "survivors", nb * 2 * sizeof(uint32_t), NULL, true); /* index, width factor */
    g->cube_objects = make_buffer(g, "cube_objects", BLADE_MAX_CUBES * sizeof(collide_cube_proxy_t), NULL);
    uint32_t cmd[4];
    command_initial(g, cmd);
    g->command = make_buffer(g, "command", sizeof cmd, cmd);
    g->counters = make_buffer(g, "counters", CNT_WORDS * sizeof(uint32_t), NULL);
    g->patches = make_buffer(g, "patches", np * sizeof(uint32_t), NULL);
    g->patch_boxes = make_buffer(g, "patch_boxes", np * sizeof *boxes, boxes);
    g->patch_keys = make_buffer(g, "patch_keys", np * 2 * sizeof(uint32_t), NULL);
    free(boxes);
    bool ok = g->blades.id && g->eta.id && g->winds.id && g->spheres.id && g->survivors.id && g->cube_objects.id &&
              g->command.id && g->counters.id && g->patches.id && g->patch_boxes.id && g->patch_keys.id;
    char label[128];
    snprintf(label, sizeof label, "%s.readback", g->desc.label);
    g->readback = gfx_readback_make((CNT_READ + 4) * sizeof(uint32_t), BLADE_GPU_READBACK_SLOTS, label);
    ok = ok && g->readback.depth;
    /* built side by side */
    bool tess = g->desc.path == BLADE_PATH_TESSELLATION;
    char buckets[64];
    snprintf(buckets, sizeof buckets, "#define BLADE_PATCH_BUCKETS %d\n", BLADE_PATCH_BUCKETS);
    enum { PROGRAMS = 7 };
    static const char *const what[PROGRAMS - 2] = {"physics", "physics_cubes", "cull", "patch_cull", "patch_list"};
    char labels[PROGRAMS][128];
    gfx_program_desc_t pds[PROGRAMS] = {
        {.cs = "blade/blade_physics.comp"},
        {.cs = "blade/blade_physics.comp", .defines = "#define BLADE_CUBES 1\n"},
        {.cs = "blade/blade_cull.comp", .defines = buckets},
        {.cs = "blade/blade_patch_cull.comp", .defines = buckets},
        {.cs = "blade/blade_patch_list.comp", .defines = buckets},
    };
    for (int k = 0; k < PROGRAMS - 2; k++) snprintf(labels[k], sizeof labels[k], "%s.%s", g->desc.label, what[k]);
    for (int fade = 0; fade < 2; fade++) {
        int k = PROGRAMS - 2 + fade;
        pds[k] = (gfx_program_desc_t){.vs = tess ? "blade/blade_tess.vert" : "blade/blade_pull.vert",
                                      .tcs = tess ? "blade/blade.tesc" : NULL,
                                      .tes = tess ? "blade/blade.tese" : NULL,
                                      .fs = "blade/blade.frag",
                                      .defines = fade ? "#define BLADE_FADE 1\n" : NULL};
        snprintf(labels[k], sizeof labels[k], "%s.draw_%s%s", g->desc.label, tess ? "tess" : "pull",
                 fade ? "_fade" : "");
    }
    for (int k = 0; k < PROGRAMS; k++) pds[k].label = labels[k];
    gfx_program_t progs[PROGRAMS];
    ok = gfx_programs_make(PROGRAMS, pds, progs) && ok;
    g->physics = progs[0];
    g->physics_cubes = progs[1];
    g->cull = progs[2];
    g->patch_cull = progs[3];
    g->patch_list = progs[4];
    g->draw = progs[5];
    g->draw_fade = progs[6];
    snprintf(label, sizeof label, "%s.vao", g->desc.label);
    g->vao = gfx_vertex_array_make(label);
    ok = ok && g->physics.id && g->physics_cubes.id && g->cull.id && g->patch_cull.id && g->patch_list.id && g->vao;
    if (!ok) {
        core_log_error("blade_gpu_make: could not create the GL objects of '%s'", g->desc.label);
        return false;
    }
    if (seed && g->blade_count && !blade_gpu_seed(g, seed)) return false;
    g->stats.total = g->blade_count;
    return true;
}

/* Every object and allocation of g (members without one are zero). */
static void release(blade_gpu_t *g)
{
    gfx_buffer_t *bufs[] = {&g->blades,   &g->eta,      &g->winds,   &g->spheres,     &g->survivors,
                            &g->command,  &g->counters, &g->patches, &g->patch_boxes, &g->patch_keys,
                            &g->cube_objects};
    for (size_t i = 0; i < sizeof bufs / sizeof bufs[0]; i++)
        if (bufs[i]->id) gfx_buffer_destroy(bufs[i]);
    gfx_readback_destroy(&g->readback);
    raster_program_destroy(&g->raster);
    gfx_program_t *progs[] = {&g->physics, &g->physics_cubes, &g->cull, &g->patch_cull, &g->patch_list,
                              &g->draw,    &g->draw_fade};
    for (size_t i = 0; i < sizeof progs / sizeof progs[0]; i++)
        if (progs[i]->id) gfx_program_destroy(progs[i]);
    if (g->vao) gfx_vertex_array_destroy(&g->vao);
    if (g->own_cubes.id) gfx_texture_destroy(&g->own_cubes);
}

blade_gpu_t *blade_gpu_make(const blade_gpu_desc_t *desc)
{
    blade_gpu_t *g = calloc(1, sizeof *g);
    if (!g) {
        core_log_error("blade_gpu_make: out of memory");
        return NULL;
    }
    if (!gpu_init(g, desc)) {
        blade_gpu_destroy(g);
        return NULL;
    }
    return g;
}

void blade_gpu_destroy(blade_gpu_t *g)
{
    if (!g) return;
    release(g);
    free(g);
}

blade_gpu_info_t blade_gpu_info(const blade_gpu_t *g)
{
    return (blade_gpu_info_t){.desc = g->desc,
                              .blade_count = g->blade_count,
                              .thinned = g->thinned,
                              .padded_count = g->padded_count,
                              .patch_count = g->patch_count,
                              .patch_size = g->patch_size};
}

bool blade_sphere_buffer_fit(gfx_buffer_t *buf, int *capacity, int count, const char *label)
{
    if (count <= *capacity) return true;
    int cap = *capacity > 0 ? *capacity : BLADE_SPHERES_FIRST;
    while (cap < count) cap *= 2;
    char name[128];
    snprintf(name, sizeof name, "%s.spheres", label);
    gfx_buffer_t grown = gfx_buffer_make(&(gfx_buffer_desc_t){
        .size = (size_t)cap * sizeof(blade_sphere_t), .dynamic = true, .label = name});
    if (!grown.id) {
        core_log_error("%s: cannot grow the sphere buffer to %d spheres", label, cap);
        return false;
    }
    if (buf->id) gfx_buffer_destroy(buf);
    *buf = grown;
    *capacity = cap;
    return true;
}

void blade_gpu_update(blade_gpu_t *g, const blade_env_t *env, const collide_set_t *colliders)
{
    blade_env_t e = blade_env_defaults(env);
    static const collide_set_t none;
    const collide_set_t *c = colliders ? colliders : &none;
    assert(c->sphere_count >= 0 && c->sphere_count <= BLADE_MAX_SPHERES);
    int sphere_count = c->sphere_count;
    if (!blade_sphere_buffer_fit(&g->spheres, &g->sphere_capacity, sphere_count, g->desc.label))
        sphere_count = g->sphere_capacity;
    assert(c->cube_count >= 0 && c->cube_count <= BLADE_MAX_CUBES);
    assert(c->cube_count == 0 || (c->cube_texture && c->cube_res > 0));
    int cubes = c->cube_texture ? c->cube_count : 0;
    if (cubes) gfx_buffer_update(g->cube_objects, 0, (size_t)cubes * sizeof(collide_cube_proxy_t), c->cubes);
    gfx_timer_begin(GFX_PASS_BLADE_PHYSICS);
    if (e.wind_count) gfx_buffer_update(g->winds, 0, (size_t)e.wind_count * sizeof(blade_wind_t), e.winds);
    if (sphere_count) gfx_buffer_update(g->spheres, 0, (size_t)sphere_count * sizeof(blade_sphere_t), c->spheres);
    g->sphere_count = sphere_count;
    gfx_program_t p = cubes ? g->physics_cubes : g->physics;
    glUseProgram(p.id);
    glUniform1ui(gfx_uniform(p, "u_blade_count"), g->padded_count);
    glUniform1f(gfx_uniform(p, "u_dt"), e.dt);
    glUniform1f(gfx_uniform(p, "u_time"), e.time);
    glUniform4f(gfx_uniform(p, "u_gravity"), e.gravity_dir[0], e.gravity_dir[1], e.gravity_dir[2], e.gravity);
    glUniform4f(gfx_uniform(p, "u_gravity_centre"), e.gravity_centre[0], e.gravity_centre[1],
                e.gravity_centre[2], e.gravity_centre_mix);
    glUniform1f(gfx_uniform(p, "u_collision_decay"), e.collision_decay);
    glUniform1f(gfx_uniform(p, "u_collision_gain"), e.collision_gain);
    glUniform1i(gfx_uniform(p, "u_wind_count"), e.wind_count);
    glUniform1i(gfx_uniform(p, "u_sphere_count"), sphere_count);
    glUniform1i(gfx_uniform(p, "u_length_mode"), e.length_mode);
    glUniform1i(gfx_uniform(p, "u_paper"), e.paper ? 1 : 0);
    if (cubes) {
        glUniform1i(gfx_uniform(p, "u_cube_count"), cubes);
        glUniform1i(gfx_uniform(p, "u_cube_res"), c->cube_res);
        glBindTextureUnit(BLADE_TEX_CUBES, c->cube_texture);
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_BLADES, g->blades.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_ETA, g->eta.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_WINDS, g->winds.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_SPHERES, g->spheres.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_CUBES, g->cube_objects.id);
    if (g->padded_count) glDispatchCompute((g->padded_count + 255u) / 256u, 1, 1);
    gfx_count_add("blade.simulated", (double)g->padded_count);
    glBindTextureUnit(BLADE_TEX_CUBES, 0);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    gfx_timer_end();
}

GLuint blade_gpu_upload_cubes(blade_gpu_t *g, const collide_cubemap_t *cubes, int count)
{
    assert(count >= 1 && count <= BLADE_MAX_CUBES);
    int res = cubes[0].res;
    if (g->own_cubes.id && (g->own_cubes.w != res || g->own_cubes.layers != 6 * count))
        gfx_texture_destroy(&g->own_cubes);
    if (!g->own_cubes.id) {
        char label[128];
        snprintf(label, sizeof label, "%s.cubes", g->desc.label);
        g->own_cubes = gfx_texture_make(&(gfx_texture_desc_t){.target = GL_TEXTURE_2D_ARRAY, .w = res, .h = res,
                                                               .layers = 6 * count, .format = GL_RGBA32F,
                                                               .filter = GL_NEAREST, .label = label});
        if (!g->own_cubes.id) {
            core_log_error("blade_gpu_upload_cubes: cannot make a %dx%d x %d texture", res, res, 6 * count);
            return 0;
        }
    }
    for (int k = 0; k < count; k++) {
        assert(cubes[k].res == res);
        glTextureSubImage3D(g->own_cubes.id, 0, 0, 0, 6 * k, res, res, 6, GL_RGBA, GL_FLOAT, cubes[k].texels);
    }
    return g->own_cubes.id;
}

void blade_lod_uniforms(gfx_program_t p, const blade_lod_t *lod, float focal_px, float cull)
{
    blade_lod_t l = blade_lod_defaults(lod);
    glUniform1i(gfx_uniform(p, "u_lod_rule"), (int)l.rule);
    glUniform1i(gfx_uniform(p, "u_lod_levels"), l.levels);
    glUniform4f(gfx_uniform(p, "u_lod_a"), l.start, l.width_px, l.level_distance, l.max_scale);
    glUniform4f(gfx_uniform(p, "u_lod_b"), l.shrink, l.fade, l.no_compensation ? 0.0f : 1.0f, focal_px);
    glUniform1f(gfx_uniform(p, "u_lod_cull"), cull);
}

/* The patch test on the GPU (blade_patch_cull.comp, blade_patch_list.comp):
 * the visible patches listed nearest bucket first and blade_cull.comp's
 * indirect dispatch written into g->counters. No CPU work per patch. */
static void list_patches(blade_gpu_t *g, const blade_cull_desc_t *d)
{
    uint32_t groups = (g->patch_count + 255u) / 256u;
    gfx_program_t p = g->patch_cull;
    glUseProgram(p.id);
    glUniform1ui(gfx_uniform(p, "u_patch_count"), g->patch_count);
    glUniformMatrix4fv(gfx_uniform(p, "u_view_proj"), 1, GL_FALSE, d->view.viewproj);
    glUniform3fv(gfx_uniform(p, "u_cam_pos"), 1, d->view.camera);
    glUniform1f(gfx_uniform(p, "u_frustum_tolerance"), d->frustum_tolerance);
    glUniform1i(gfx_uniform(p, "u_frustum"), (d->disable & BLADE_CULL_FRUSTUM) == 0);
    glUniform1f(gfx_uniform(p, "u_bucket_range"), d->max_distance);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_PATCH_BOXES, g->patch_boxes.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_PATCH_KEYS, g->patch_keys.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_COUNTERS, g->counters.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_PATCHES, g->patches.id);
    if (groups) glDispatchCompute(groups, 1, 1);
    gfx_count_add("blade.patches_tested", (double)g->patch_count);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    p = g->patch_list;
    glUseProgram(p.id);
    glUniform1ui(gfx_uniform(p, "u_patch_count"), g->patch_count);
    glUniform1ui(gfx_uniform(p, "u_patch_size"), g->patch_size);
    glDispatchCompute(groups ? groups : 1, 1, 1); /* group 0 writes the dispatch, even for no patch */
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

void blade_gpu_cull(blade_gpu_t *g, const blade_cull_desc_t *desc, GLuint depth_texture)
{
    blade_cull_desc_t d = desc ? blade_cull_desc_defaults(desc) : g->desc.cull;
    gfx_timer_begin(GFX_PASS_BLADE_CULL);
    bool use_patches = !g->desc.no_patch_cull;
    /* reset: the command's counted field and the counters (blade_patch.glsl),
     * each its own command before the dispatches */
    bool pull = g->desc.path == BLADE_PATH_PULLING;
    uint32_t zero = 0;
    glClearNamedBufferSubData(g->command.id, GL_R32UI, pull ? 4 : 0, 4, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glClearNamedBufferData(g->counters.id, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    if (use_patches) list_patches(g, &d);

    gfx_program_t p = g->cull;
    glUseProgram(p.id);
    glUniform1ui(gfx_uniform(p, "u_blade_count"), g->padded_count);
    glUniform3fv(gfx_uniform(p, "u_cam_pos"), 1, d.view.camera);
    glUniformMatrix4fv(gfx_uniform(p, "u_view_proj"), 1, GL_FALSE, d.view.viewproj);
    glUniform1f(gfx_uniform(p, "u_max_distance"), d.max_distance);
    blade_lod_uniforms(p, &d.lod, d.focal_px, d.max_distance);
    glUniform1f(gfx_uniform(p, "u_orientation_threshold"), d.orientation_threshold);
    glUniform1f(gfx_uniform(p, "u_frustum_tolerance"), d.frustum_tolerance);
    glUniform1f(gfx_uniform(p, "u_depth_bias"), d.depth_bias);
    glUniform1i(gfx_uniform(p, "u_use_depth"), depth_texture != 0);
    glUniform1ui(gfx_uniform(p, "u_disable"), d.disable);
    glUniform1i(gfx_uniform(p, "u_count_instances"), pull);
    glUniform1i(gfx_uniform(p, "u_use_patches"), use_patches);
    glUniform1ui(gfx_uniform(p, "u_patch_size"), g->patch_size);
    glBindTextureUnit(BLADE_TEX_DEPTH, depth_texture);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_BLADES, g->blades.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_SURVIVORS, g->survivors.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_COMMAND, g->command.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_COUNTERS, g->counters.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_PATCHES, g->patches.id);
    if (use_patches) {
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, g->counters.id);
        glDispatchComputeIndirect(CNT_DISPATCH * sizeof(uint32_t));
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    } else if (g->padded_count) {
        glDispatchCompute((g->padded_count + 255u) / 256u, 1, 1);
        gfx_count_add("blade.cull_tested", (double)g->padded_count);
    }
    glBindTextureUnit(BLADE_TEX_DEPTH, 0);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);

    /* statistics: the counters and the command into a fenced ring slot,
     * read once the fence has passed */
    gfx_readback_copy(&g->readback, g->counters, 0, 0, CNT_READ * sizeof(uint32_t));
    gfx_readback_copy(&g->readback, g->command, 0, CNT_READ * sizeof(uint32_t), 4 * sizeof(uint32_t));
    gfx_readback_fence(&g->readback);
    g->culled_once = true;
    gfx_timer_end();
}

blade_gpu_stats_t blade_gpu_stats(blade_gpu_t *g, bool wait)
{
    int slot = gfx_readback_latest(&g->readback, wait);
    if (slot < 0) return g->stats;
    uint32_t v[CNT_READ + 4];
    gfx_readback_read(&g->readback, slot, 0, sizeof v, v);
    bool pull = g->desc.path == BLADE_PATH_PULLING;
    for (int i = 0; i < 4; i++) g->stats.culled[i] = v[i];
    g->stats.survivors = pull ? v[CNT_READ + 1] : v[CNT_READ];
    g->stats.patch_culled = v[CNT_PATCH_CULLED];
    g->stats.patches_drawn = g->desc.no_patch_cull ? g->patch_count : v[CNT_LISTED];
    g->stats.total = g->blade_count;
    g->stats.valid = true;
    g->stats.triangles_max = (long)g->stats.survivors * 2 * g->desc.max_tess_level;
    return g->stats;
}

void blade_set_surface_uniforms(gfx_program_t p, const blade_surface_t *surf, const blade_draw_desc_t *desc)
{
    float sun[3] = {desc->view.sun[0], desc->view.sun[1], desc->view.sun[2]};
    float sl = sqrtf(sun[0] * sun[0] + sun[1] * sun[1] + sun[2] * sun[2]);
    if (sl < 1e-6f) {
        sun[0] = 0.4f, sun[1] = 0.8f, sun[2] = 0.3f;
        sl = sqrtf(0.89f);
    }
    for (int i = 0; i < 3; i++) sun[i] /= sl;
    const float *root = desc->albedo_root, *tip = desc->albedo_tip;
    static const float root_def[3] = BLADE_DEFAULT_ALBEDO_ROOT, tip_def[3] = BLADE_DEFAULT_ALBEDO_TIP;
    if (root[0] == 0.0f && root[1] == 0.0f && root[2] == 0.0f) root = root_def;
    if (tip[0] == 0.0f && tip[1] == 0.0f && tip[2] == 0.0f) tip = tip_def;
    glUniformMatrix4fv(gfx_uniform(p, "u_view_proj"), 1, GL_FALSE, desc->view.viewproj);
    glUniform3fv(gfx_uniform(p, "u_camera"), 1, desc->view.camera);
    glUniform3fv(gfx_uniform(p, "u_sun"), 1, sun);
    glUniform2f(gfx_uniform(p, "u_fade"), desc->fade_start, desc->fade_end);
    glUniform3fv(gfx_uniform(p, "u_albedo_root"), 1, root);
    glUniform3fv(gfx_uniform(p, "u_albedo_tip"), 1, tip);
    glUniform1i(gfx_uniform(p, "u_shape"), (int)surf->shape);
    glUniform1f(gfx_uniform(p, "u_displacement"), surf->displacement);
    glUniform1f(gfx_uniform(p, "u_width_correction"), surf->width_correction);
    glUniform3f(gfx_uniform(p, "u_width_printed"), surf->width_printed[0], surf->width_printed[1],
                desc->focal_px > 0.0f ? desc->focal_px : 1000.0f);
    glUniform1i(gfx_uniform(p, "u_max_level"), surf->max_level);
    glUniform1f(gfx_uniform(p, "u_lod_distance"), surf->lod_distance);
    gi_set_uniforms(p.id, &desc->gi);
}

static blade_surface_t surface_of(const blade_gpu_desc_t *d)
{
    return (blade_surface_t){.shape = d->shape, .displacement = d->displacement,
                             .width_correction = d->width_correction,
                             .width_printed = {d->width_printed[0], d->width_printed[1]},
                             .max_level = d->max_tess_level,
                             .lod_distance = d->lod_distance};
}

void blade_gpu_draw(blade_gpu_t *g, const blade_draw_desc_t *desc)
{
    gfx_timer_begin(GFX_PASS_BLADE_DRAW);
    if (!g->culled_once) {
        gfx_timer_end();
        return;
    }
    bool pull = g->desc.path == BLADE_PATH_PULLING;
    bool fade = desc->fade_end > desc->fade_start;
    gfx_program_t p = fade ? g->draw_fade : g->draw;

    glUseProgram(p.id);
    blade_surface_t surf = surface_of(&g->desc);
    blade_set_surface_uniforms(p, &surf, desc);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_BLADES, g->blades.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_SURVIVORS, g->survivors.id);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, g->command.id);
    glBindVertexArray(g->vao);
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    if (pull) {
        glDrawArraysIndirect(GL_TRIANGLE_STRIP, NULL);
    } else {
        glPatchParameteri(GL_PATCH_VERTICES, 1);
        glDrawArraysIndirect(GL_PATCHES, NULL);
    }
    glBindVertexArray(0);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    gfx_timer_end();
}

typedef struct raster_bind_t {
    const blade_surface_t *surf;
    const blade_draw_desc_t *draw;
    gfx_buffer_t blades, ids, count;
    uint32_t count_index;
} raster_bind_t;

static void bind_raster(gfx_program_t p, void *user)
{
    const raster_bind_t *b = user;
    blade_set_surface_uniforms(p, b->surf, b->draw);
    glUniform1i(gfx_uniform(p, "u_use_ids"), b->ids.id != 0);
    glUniform1ui(gfx_uniform(p, "u_count_index"), b->count_index);
    glUniform1ui(gfx_uniform(p, "u_count_max"), 0xffffffffu);
    glUniform1f(gfx_uniform(p, "u_segment_pixels"), BLADE_RASTER_SEGMENT_PIXELS);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_BLADES, b->blades.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_RASTER_IDS, b->ids.id ? b->ids.id : b->blades.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_RASTER_COUNT, b->count.id);
}

/* Without GI its code is compiled out: compiled in and unused it cost
 * blade.raster 10-22 % on the H100 (nature, helicopter, meadow_large). */
static const char *raster_defines(bool gi) { return gi ? NULL : "#define GRASS_GI_OFF 1\n"; }

void blade_raster_prefetch(const raster_desc_t *rd, bool gi)
{
    raster_program_prefetch(rd, "blade/blade_raster.comp", raster_defines(gi));
}

bool blade_raster_list(raster_t *r, raster_program_t *prog, const blade_surface_t *surf,
                       const blade_draw_desc_t *desc, gfx_buffer_t blades, gfx_buffer_t ids, gfx_buffer_t count,
                       uint32_t count_index, uint32_t count_max)
{
    if (!raster_program_ensure(r, prog, "blade/blade_raster.comp", raster_defines(desc->gi.ao != 0), "blade.raster"))
        return false;
    raster_bind_t b = {.surf = surf, .draw = desc, .blades = blades, .ids = ids, .count = count,
                       .count_index = count_index};
    raster_items_t items = {.count_buffer = count, .count_index = count_index, .count_max = count_max};
    raster_draw(r, prog, &items, bind_raster, &b);
    return true;
}

bool blade_gpu_raster(blade_gpu_t *g, raster_t *r, const blade_draw_desc_t *desc)
{
    gfx_timer_begin(GFX_PASS_BLADE_RASTER);
    blade_surface_t surf = surface_of(&g->desc);
    bool ok = !g->culled_once ||
              blade_raster_list(r, &g->raster, &surf, desc, g->blades, g->survivors, g->command,
                                g->desc.path == BLADE_PATH_PULLING ? 1u : 0u, g->padded_count);
    gfx_timer_end();
    return ok;
}

void blade_gpu_read_blades(const blade_gpu_t *g, blade_t *out, float *eta_out)
{
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    if (out) gfx_buffer_read(g->blades, 0, g->padded_count * sizeof(blade_t), out);
    if (eta_out) gfx_buffer_read(g->eta, 0, g->padded_count * sizeof(float), eta_out);
}

void blade_gpu_read_patch_boxes(const blade_gpu_t *g, float (*out)[8])
{
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    if (g->patch_count) gfx_buffer_read(g->patch_boxes, 0, g->patch_count * 8 * sizeof(float), out);
}

int blade_gpu_read_spheres(const blade_gpu_t *g, blade_sphere_t *out, int max)
{
    int n = g->sphere_count < max ? g->sphere_count : max;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    if (n > 0) gfx_buffer_read(g->spheres, 0, (size_t)n * sizeof(blade_sphere_t), out);
    return g->sphere_count;
}

uint32_t blade_gpu_read_survivors(const blade_gpu_t *g, uint32_t *ids, float *factors)
{
    uint32_t cmd[4];
    blade_gpu_read_command(g, cmd);
    uint32_t n = g->desc.path == BLADE_PATH_PULLING ? cmd[1] : cmd[0];
    assert(n <= g->padded_count);
    uint32_t *pairs = malloc((n ? n : 1) * 2 * sizeof *pairs);
    if (!pairs) {
        core_log_error("blade_gpu_read_survivors: out of memory (%u survivors)", n);
        return 0;
    }
    if (n) gfx_buffer_read(g->survivors, 0, n * 2 * sizeof(uint32_t), pairs);
    for (uint32_t i = 0; i < n; i++) {
        ids[i] = pairs[2 * i];
        if (factors) memcpy(&factors[i], &pairs[2 * i + 1], sizeof(float));
    }
    free(pairs);
    return n;
}

uint32_t blade_gpu_read_patches(const blade_gpu_t *g, uint32_t *out)
{
    if (g->desc.no_patch_cull || !g->culled_once) return 0;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    uint32_t n;
    gfx_buffer_read(g->counters, CNT_LISTED * sizeof(uint32_t), sizeof n, &n);
    assert(n <= g->patch_count);
    if (n) gfx_buffer_read(g->patches, 0, n * sizeof(uint32_t), out);
    return n;
}

void blade_gpu_read_command(const blade_gpu_t *g, uint32_t out[4])
{
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gfx_buffer_read(g->command, 0, 4 * sizeof(uint32_t), out);
}

void blade_gpu_write_blades(blade_gpu_t *g, const blade_t *blades, const float *eta)
{
    gfx_buffer_update(g->blades, 0, g->padded_count * sizeof(blade_t), blades);
    if (eta) {
        gfx_buffer_update(g->eta, 0, g->padded_count * sizeof(float), eta);
    } else {
        float zero = 0.0f;
        glClearNamedBufferData(g->eta.id, GL_R32F, GL_RED, GL_FLOAT, &zero);
    }
}
