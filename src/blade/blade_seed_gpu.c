/* blade_seed_gpu: blade mode's field seeded on the GPU (blade_seed_plan.h).
 * The plan's triangle order and offsets and the mesh go up (a few MB for a
 * field of millions of blades), blade_seed.comp writes every blade and
 * blade_seed_boxes.comp the patch boxes; only the thinned count comes
 * back. The programs and the upload are released when it is done. */
#include "blade/blade_local.h"

#include <stdio.h>

/* Dispatches that cover n invocations of groups of `local`, at most the GL's
 * guaranteed 65535 (the shaders stride over the rest). */
static GLuint seed_groups(size_t n, size_t local)
{
    size_t groups = (n + local - 1) / local;
    return (GLuint)(groups > 65535 ? 65535 : groups ? groups : 1);
}

bool blade_gpu_seed(blade_gpu_t *g, const blade_gpu_seed_t *seed)
{
    const blade_seed_plan_t *plan = seed->plan;
    const blade_mesh_t *mesh = seed->mesh;
    char labels[8][128];
    static const char *const what[8] = {"seed",        "seed_boxes", "seed.positions", "seed.normals",
                                        "seed.indices", "seed.order", "seed.offsets",   "seed.thinned"};
    for (int k = 0; k < 8; k++) snprintf(labels[k], sizeof labels[k], "%s.%s", g->desc.label, what[k]);
    char buckets[64]; /* blade_patch.glsl's Counters, as blade.c builds the patch test */
    snprintf(buckets, sizeof buckets, "#define BLADE_PATCH_BUCKETS %d\n", BLADE_PATCH_BUCKETS);
    gfx_program_desc_t pds[2] = {{.cs = "blade/blade_seed.comp", .label = labels[0]},
                                 {.cs = "blade/blade_seed_boxes.comp", .defines = buckets, .label = labels[1]}};
    gfx_program_t progs[2] = {{0}, {0}};
    bool ok = gfx_programs_make(2, pds, progs);
    const void *data[5] = {mesh->positions, mesh->normals, mesh->indices, plan->order, plan->offsets};
    size_t sizes[5] = {mesh->vertex_count * 3 * sizeof(float), mesh->normals ? mesh->vertex_count * 3 * sizeof(float) : 0,
                       mesh->index_count * sizeof(uint32_t), plan->tri_count * sizeof(uint32_t),
                       (plan->tri_count + 1) * sizeof(uint32_t)};
    gfx_buffer_t bufs[6] = {{0}};
    for (int k = 0; k < 5; k++) {
        bufs[k] = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizes[k] ? sizes[k] : 16, .data = sizes[k] ? data[k] : NULL,
                                                       .label = labels[2 + k]});
        ok = ok && bufs[k].id;
    }
    bufs[5] = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof(uint32_t), .label = labels[7]});
    ok = ok && bufs[5].id;
    if (ok) {
        const blade_seed_desc_t *d = &plan->desc;
        const blade_population_t *pop = &d->population;
        gfx_program_t p = progs[0];
        glUseProgram(p.id);
        glUniform1ui(gfx_uniform(p, "u_blade_count"), (GLuint)plan->blade_count);
        glUniform1ui(gfx_uniform(p, "u_padded_count"), (GLuint)plan->padded_count);
        glUniform1ui(gfx_uniform(p, "u_tri_count"), (GLuint)plan->tri_count);
        glUniform1ui(gfx_uniform(p, "u_key"), plan->key);
        glUniform1i(gfx_uniform(p, "u_normals"), mesh->normals ? 1 : 0);
        glUniform2f(gfx_uniform(p, "u_height"), pop->height[0], pop->height[1]);
        glUniform2f(gfx_uniform(p, "u_width"), pop->width[0], pop->width[1]);
        glUniform2f(gfx_uniform(p, "u_stiffness"), pop->stiffness[0], pop->stiffness[1]);
        glUniform2f(gfx_uniform(p, "u_angle"), d->angle_min, d->angle_max);
        glUniform1i(gfx_uniform(p, "u_extent"), seed->extent_texture ? 1 : 0);
        glUniform2f(gfx_uniform(p, "u_extent_origin"), seed->extent_origin[0], seed->extent_origin[1]);
        glUniform1f(gfx_uniform(p, "u_extent_spacing"), seed->extent_spacing);
        glUniform1ui(gfx_uniform(p, "u_extent_key"), seed->extent_key);
        glBindTextureUnit(BLADE_SEED_TEX_EXTENT, seed->extent_texture);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_BLADES, g->blades.id);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_ETA, g->eta.id);
        static const GLuint binds[6] = {BLADE_SEED_BIND_POSITIONS, BLADE_SEED_BIND_NORMALS, BLADE_SEED_BIND_INDICES,
                                        BLADE_SEED_BIND_ORDER,     BLADE_SEED_BIND_OFFSETS, BLADE_SEED_BIND_THINNED};
        for (int k = 0; k < 6; k++) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binds[k], bufs[k].id);
        glDispatchCompute(seed_groups(plan->padded_count, 256), 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        glBindTextureUnit(BLADE_SEED_TEX_EXTENT, 0);

        p = progs[1];
        glUseProgram(p.id);
        glUniform1ui(gfx_uniform(p, "u_patch_count"), g->patch_count);
        glUniform1ui(gfx_uniform(p, "u_patch_size"), g->patch_size);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_PATCH_BOXES, g->patch_boxes.id);
        glDispatchCompute(seed_groups(g->patch_count, 64), 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        glUseProgram(0);
        ok = gfx_buffer_read(bufs[5], 0, sizeof g->thinned, &g->thinned);
    }
    for (int k = 0; k < 6; k++)
        if (bufs[k].id) gfx_buffer_destroy(&bufs[k]);
    for (int k = 0; k < 2; k++)
        if (progs[k].id) gfx_program_destroy(&progs[k]);
    if (!ok) core_log_error("blade_gpu_make: could not seed '%s' on the GPU", g->desc.label);
    return ok;
}
