/* bb_update: bb_field_update (Orthmann et al. 2009 sec. 5): the objects'
 * bounds into the CPU octree broad phase, for colliding leaves the depth
 * cube maps of the objects their batches test (bb_cube.vert) and the
 * collide pass (bb_batch.c), for colliding and recovering leaves the
 * recovery pass (bb_recover.comp), and the fenced pool-header readback
 * that never waits; objects the hybrid hides (bb_field_set_hidden); the
 * cube maps uploaded by tests and lent to the blades. */
#include "billboard/bb_local.h"

#include <assert.h>
#include <math.h>
#include <string.h>

/* The octree keeps a leaf RECOVERING this much longer than a billboard's own
 * recovery (bb_recover.comp), so float drift in the two timers can never
 * leave a billboard deformed in a leaf that already went IDLE. */
#define BB_LEAF_RECOVER_SLACK 0.25f

void bb_field_set_cube(bb_field_t *f, int object, const collide_cubemap_t *cube)
{
    assert(object >= 0 && object < f->desc.max_objects && cube->res == f->desc.cube_res);
    glTextureSubImage3D(f->cubes.id, 0, 0, 0, 6 * object, cube->res, cube->res, 6, GL_RGBA, GL_FLOAT, cube->texels);
    glm_vec3_copy((float *)cube->centre, f->cube_centre[object]);
    f->cube_half[object] = cube->half;
}

void bb_field_lend_cubes(const bb_field_t *f, collide_set_t *colliders)
{
    int count = colliders->object_count < f->desc.max_objects ? colliders->object_count : f->desc.max_objects;
    /* Proxy k reads layers 6k .. 6k+5: an object without a rendered map
     * keeps its index with a skipped proxy (sphere radius 0) rather than
     * shifting the later objects onto its layers. */
    for (int k = 0; k < count && colliders->cube_count < COLLIDE_MAX_CUBES; k++) {
        collide_cube_proxy_t *out = &colliders->cubes[colliders->cube_count++];
        float half = f->cube_half[k];
        if (half > 0.0f) collide_make_cube_proxy(colliders->objects[k].model, f->cube_centre[k], half, out);
        else memset(out, 0, sizeof *out);
    }
    colliders->cube_texture = f->cubes.id;
    colliders->cube_res = f->desc.cube_res;
}

/* Object k's six faces into layers 6k .. 6k+5 of f->cubes: the faces'
 * backgrounds, then its mesh, each one instanced draw (instance = face; the
 * layered target's depth was cleared to 1 and the depth test is LEQUAL). */
static void render_cube(bb_field_t *f, const collide_object_t *o, int k)
{
    gfx_program_t p = f->cube_prog;
    glUniform3fv(gfx_uniform(p, "u_centre"), 1, o->centre);
    glUniform1f(gfx_uniform(p, "u_half"), o->radius);
    glUniform1i(gfx_uniform(p, "u_layer"), 6 * k);
    glUniform1i(gfx_uniform(p, "u_background"), 1);
    glBindVertexArray(f->empty_vao);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, 6);
    glUniform1i(gfx_uniform(p, "u_background"), 0);
    glBindVertexArray(o->vao);
    glDrawElementsInstanced(GL_TRIANGLES, o->index_count, o->index_type, NULL, 6);
    glm_vec3_copy((float *)o->centre, f->cube_centre[k]);
    f->cube_half[k] = o->radius;
}

static float max_scale(const float *m)
{
    float s = 0.0f;
    for (int c = 0; c < 3; c++) s = fmaxf(s, sqrtf(m[4 * c] * m[4 * c] + m[4 * c + 1] * m[4 * c + 1] + m[4 * c + 2] * m[4 * c + 2]));
    return s;
}

/* Reads every readback slot whose fence has passed (the copy has completed,
 * so the read does not wait), oldest first, and logs pool exhaustion the
 * first time and whenever the refused count has doubled since the last
 * warning (no per-frame spam). */
static void poll_readbacks(bb_field_t *f)
{
    int slot;
    while ((slot = gfx_readback_poll(&f->readback, false)) >= 0) {
        uint32_t hdr[2];
        gfx_readback_read(&f->readback, slot, 0, sizeof hdr, hdr);
        f->deformed_last = f->desc.max_deformed - (int32_t)hdr[0];
        f->exhausted_last = (int)hdr[1] > f->exhausted_last ? (int)hdr[1] : f->exhausted_last;
        if (f->exhausted_last > 0 && f->exhausted_last >= 2 * f->exhausted_logged) {
            core_log_warn("bb: deformed-mesh pool of %d slots exhausted: %d collisions left undeformed so far "
                          "(raise grass.deformed_pool)", f->desc.max_deformed, f->exhausted_last);
            f->exhausted_logged = f->exhausted_last;
        }
    }
}

/* Queues a fenced copy of the pool header. When every slot is still in
 * flight the copy is skipped (a later one reports the same running
 * counters). */
static void queue_readback(bb_field_t *f)
{
    if (gfx_readback_busy(&f->readback)) return;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gfx_readback_copy(&f->readback, f->pool, 0, 0, 16);
    gfx_readback_fence(&f->readback);
}

void bb_field_set_hidden(bb_field_t *f, const float camera[3], float fade_start)
{
    for (int a = 0; a < 3; a++) f->hidden[a] = camera[a];
    f->hidden[3] = fade_start > 0.0f ? fade_start : 0.0f;
}

/* True when bound b cannot reach a drawn billboard (bb_field_set_hidden).
 * A drawn billboard's root is at least fade_start - r from the camera
 * (bb_fade_dropped: r = half its diagonal, at most its bounding sphere's
 * radius), its sphere's centre at most r above the root and its geometry
 * within the sphere, so all of it lies beyond fade_start - 3 r. */
static bool bound_hidden(const bb_field_t *f, const bb_bound_t *b)
{
    if (f->hidden[3] <= 0.0f) return false;
    float reach = b->radius;
    if (b->kind == BB_BOUND_AABB) reach = glm_vec3_norm((float *)b->half);
    return glm_vec3_distance((float *)f->hidden, (float *)b->centre) + reach < f->hidden[3] - 3.0f * f->sphere_max;
}

/* Each object's broad-phase bound (its sphere, or a moving object's step
 * boxed; BB_BOUND_NONE when hidden) and its collide-pass entry without the
 * cube (filled once its map is drawn). Returns the objects hidden. */
static int object_bounds(const bb_field_t *f, const collide_object_t *objs, int count, bb_bound_t *bounds,
                         bb_object_gpu_t *gpu)
{
    int hidden = 0;
    for (int k = 0; k < count; k++) {
        mat4 model, inv;
        memcpy(model, objs[k].model, sizeof model);
        glm_mat4_inv(model, inv);
        vec3 c;
        glm_mat4_mulv3(model, (float *)objs[k].centre, 1.0f, c);
        float radius = objs[k].radius * max_scale(objs[k].model);
        vec3 sweep;
        glm_vec3_sub((float *)objs[k].prev_position, (float *)objs[k].position, sweep);
        bounds[k] = (bb_bound_t){.kind = BB_BOUND_SPHERE, .centre = {c[0], c[1], c[2]}, .radius = radius};
        if (glm_vec3_norm2(sweep) > 0.0f) {
            /* the step's capsule, boxed (broad phase only) */
            bounds[k].kind = BB_BOUND_AABB;
            for (int a = 0; a < 3; a++) {
                bounds[k].centre[a] = c[a] + 0.5f * sweep[a];
                bounds[k].half[a] = 0.5f * fabsf(sweep[a]) + radius;
            }
        }
        if (bound_hidden(f, &bounds[k])) {
            bounds[k].kind = BB_BOUND_NONE;
            hidden++;
        }
        memcpy(gpu[k].sweep, sweep, sizeof sweep);
        gpu[k].sweep[3] = 0.0f;
        memcpy(gpu[k].w2c, inv, sizeof inv);
        memcpy(gpu[k].c2w, model, sizeof model);
        memcpy(gpu[k].sphere, c, sizeof c);
        gpu[k].sphere[3] = -1.0f;
        gpu[k].layer[0] = 6 * k;
        gpu[k].layer[1] = gpu[k].layer[2] = gpu[k].layer[3] = 0;
    }
    return hidden;
}

/* The cube maps of the objects with a mesh that a batch needs (timer
 * "bb.cubemaps"); the caller's framebuffer and viewport are restored. */
static void render_cubes(bb_field_t *f, const collide_object_t *objs, int count, const bool *need)
{
    GLint fbo = 0, vp[4];
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    glGetIntegerv(GL_VIEWPORT, vp);
    gfx_timer_begin(GFX_PASS_BB_CUBEMAPS);
    glBindFramebuffer(GL_FRAMEBUFFER, f->cube_target.fbo);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glViewport(0, 0, f->desc.cube_res, f->desc.cube_res);
    float one = 1.0f;
    glClearBufferfv(GL_DEPTH, 0, &one); /* every layer */
    glUseProgram(f->cube_prog.id);
    for (int k = 0; k < count; k++)
        if (need[k] && objs[k].vao) render_cube(f, &objs[k], k);
    glDepthFunc(GL_LESS);
    gfx_timer_end();
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)fbo);
    glViewport(vp[0], vp[1], vp[2], vp[3]);
}

/* The colliding leaves' ncol ranges (in f->ranges): batches, the cube maps
 * they need and the collide pass (timer "bb.collide"). True when GPU work
 * was queued. */
static bool collide(bb_field_t *f, int ncol, const collide_object_t *objs, int count, const bb_bound_t *bounds,
                    bb_object_gpu_t *gpu, float time)
{
    const bb_field_desc_t *d = &f->desc;
    /* Cube maps only for objects in a collide batch. */
    bool need[BB_MAX_OBJECTS] = {0};
    bool planned = bb_plan_batches(f, ncol, bounds, count, need);
    int nneed = 0;
    for (int k = 0; k < count; k++) nneed += need[k] && objs[k].vao;
    if (nneed > 0) render_cubes(f, objs, count, need);
    for (int k = 0; k < count; k++) {
        if (!need[k]) continue;
        glm_vec3_copy(f->cube_centre[k], gpu[k].cube);
        gpu[k].cube[3] = f->cube_half[k];
        gpu[k].sphere[3] = bounds[k].radius;
    }
    gfx_program_t p = f->collide_prog;
    glUseProgram(p.id);
    glBindTextureUnit(BB_TEX_CUBES, f->cubes.id);
    bb_set_heights(f, p);
    glUniform1i(gfx_uniform(p, "u_res"), d->cube_res);
    glUniform1f(gfx_uniform(p, "u_time"), time);
    glUniform1f(gfx_uniform(p, "u_recover"), d->recover_time);
    glUniform1f(gfx_uniform(p, "u_r1"), d->r1);
    glUniform1f(gfx_uniform(p, "u_r2"), d->r2);
    glUniform1i(gfx_uniform(p, "u_iterations"), d->iterations);
    glUniform1i(gfx_uniform(p, "u_paper"), d->paper ? 1 : 0);
    bb_set_wind(p.id, &d->wind);
    f->batches_last = planned ? f->plan.count : 0;
    bool gpu_work = false;
    if (f->batches_last > 0) {
        gfx_timer_begin(GFX_PASS_BB_COLLIDE);
        gpu_work = bb_collide_batches(f, gpu);
        gfx_timer_end();
    }
    return gpu_work;
}

/* The recovery pass over the nrec colliding and recovering leaves' ranges
 * (in f->ranges; timer "bb.recover"). */
static void recover(bb_field_t *f, int nrec, float time, float dt)
{
    int nr = bb_merge_ranges(f, nrec);
    uint32_t threads = 0;
    for (int i = 0; i < nr; i++) {
        f->recover_ranges[4 * i + 0] = (uint32_t)f->firsts[i];
        f->recover_ranges[4 * i + 1] = (uint32_t)f->counts_gl[i];
        f->recover_ranges[4 * i + 2] = threads;
        threads += (uint32_t)f->counts_gl[i];
    }
    gfx_program_t p = f->recover_prog;
    glUseProgram(p.id);
    glUniform1f(gfx_uniform(p, "u_time"), time);
    glUniform1f(gfx_uniform(p, "u_dt"), dt);
    glUniform1i(gfx_uniform(p, "u_range_count"), nr);
    glUniform1ui(gfx_uniform(p, "u_threads"), threads);
    bb_set_wind(p.id, &f->desc.wind);
    gfx_timer_begin(GFX_PASS_BB_RECOVER);
    gfx_buffer_update(f->recover_range_buf, 0, (size_t)nr * 16, f->recover_ranges);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BB_BIND_POOL, f->pool.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BB_BIND_MESHES, f->meshes.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BB_BIND_POINTS, f->points.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BB_BIND_RANGES, f->recover_range_buf.id);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    glDispatchCompute((threads + 63u) / 64u, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT |
                    GL_BUFFER_UPDATE_BARRIER_BIT);
    gfx_timer_end();
    gfx_count_add("bb.recovered", bb_range_total(f->counts_gl, nr));
}

/* The leaves (the ring's slots) in state_mask as ranges in f->ranges. */
static int collect(bb_field_t *f, uint32_t state_mask)
{
    if (f->ring_on) return bb_ring_collect(f, state_mask);
    return bb_octree_collect(&f->tree, state_mask, NULL, 0.0f, f->ranges, f->tree.leaf_count);
}

void bb_field_update(bb_field_t *f, const collide_set_t *colliders, float time, float dt)
{
    const collide_object_t *objs = colliders ? colliders->objects : NULL;
    int count = colliders ? colliders->object_count : 0;
    assert(count >= 0 && count <= f->desc.max_objects);
    f->time = time;
    f->batches_last = 0;
    poll_readbacks(f);
    bool gpu_work = false;
    bb_bound_t bounds[BB_MAX_OBJECTS];
    bb_object_gpu_t gpu[BB_MAX_OBJECTS];
    f->hidden_last = object_bounds(f, objs, count, bounds, gpu);
    float recover_time = f->desc.recover_time + BB_LEAF_RECOVER_SLACK;
    if (f->ring_on) bb_ring_window_touch(&f->ring, bounds, count, dt, recover_time);
    else bb_octree_update(&f->tree, bounds, count, dt, recover_time);
    int ncol = collect(f, BB_NODE_MASK(BB_NODE_COLLIDING));
    if (ncol > 0) gpu_work = collide(f, ncol, objs, count, bounds, gpu, time);
    int nrec = collect(f, BB_NODE_MASK(BB_NODE_COLLIDING) | BB_NODE_MASK(BB_NODE_RECOVERING));
    if (nrec > 0) {
        recover(f, nrec, time, dt);
        gpu_work = true;
    }
    if (gpu_work) queue_readback(f);
}
