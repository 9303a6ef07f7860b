/* app_terrain: uploads a terrain mesh and draws it (lit soil-and-grass
 * ground), and draws the sky gradient behind everything. */
#include "app/app_world.h"
#include "scene/scene_fields.h"

#include <string.h>

bool app_terrain_make(app_terrain_t *t, const terrain_mesh_t *mesh)
{
    memset(t, 0, sizeof *t);
    size_t nv = mesh->vertex_count;
    float *interleaved = malloc(nv * 8 * sizeof(float));
    if (!interleaved) return false;
    for (size_t i = 0; i < nv; i++) {
        memcpy(interleaved + i * 8, mesh->positions + i * 3, 3 * sizeof(float));
        memcpy(interleaved + i * 8 + 3, mesh->normals + i * 3, 3 * sizeof(float));
        memcpy(interleaved + i * 8 + 6, mesh->uvs + i * 2, 2 * sizeof(float));
    }
    t->vbo = gfx_buffer_make(&(gfx_buffer_desc_t){.size = nv * 8 * sizeof(float), .data = interleaved,
                                                  .label = "terrain.vertices"});
    free(interleaved);
    t->ibo = gfx_buffer_make(&(gfx_buffer_desc_t){.size = mesh->index_count * sizeof(uint32_t),
                                                  .data = mesh->indices, .label = "terrain.indices"});
    t->index_count = (int)mesh->index_count;
    t->vao = gfx_vertex_array_make("terrain.vao");
    glVertexArrayVertexBuffer(t->vao, 0, t->vbo.id, 0, 8 * sizeof(float));
    glVertexArrayElementBuffer(t->vao, t->ibo.id);
    for (int a = 0; a < 3; a++) {
        static const int sizes[3] = {3, 3, 2}, offsets[3] = {0, 3, 6};
        glEnableVertexArrayAttrib(t->vao, (GLuint)a);
        glVertexArrayAttribFormat(t->vao, (GLuint)a, sizes[a], GL_FLOAT, GL_FALSE,
                                  (GLuint)(offsets[a] * sizeof(float)));
        glVertexArrayAttribBinding(t->vao, (GLuint)a, 0);
    }
    t->prog = gfx_program_make(&(gfx_program_desc_t){.vs = "app/terrain.vert", .fs = "app/terrain.frag",
                                                     .label = "terrain.program"});
    t->sky = gfx_program_make(&(gfx_program_desc_t){.vs = "app/sky.vert", .fs = "app/sky.frag",
                                                    .label = "sky.program"});
    t->empty_vao = gfx_vertex_array_make("sky.vao");
    return t->vbo.id && t->ibo.id && t->prog.id && t->sky.id;
}

void app_terrain_set_canopy(app_terrain_t *t, const blade_canopy_t *c, GLuint extent, const float origin[2],
                            float spacing)
{
    blade_canopy_pack(c, &t->canopy);
    t->extent = extent;
    memcpy(t->extent_origin, origin, sizeof t->extent_origin);
    t->extent_spacing = spacing;
}

void app_terrain_destroy(app_terrain_t *t)
{
    gfx_buffer_destroy(&t->vbo);
    gfx_buffer_destroy(&t->ibo);
    gfx_vertex_array_destroy(&t->vao);
    gfx_vertex_array_destroy(&t->empty_vao);
    gfx_program_destroy(&t->prog);
    gfx_program_destroy(&t->sky);
}

void app_terrain_draw(const app_terrain_t *t, const app_view_t *v)
{
    glUseProgram(t->prog.id);
    glUniformMatrix4fv(gfx_uniform(t->prog, "u_viewproj"), 1, GL_FALSE, (const float *)v->viewproj);
    glUniform3fv(gfx_uniform(t->prog, "u_camera"), 1, v->camera);
    glUniform3fv(gfx_uniform(t->prog, "u_sun"), 1, v->sun_dir);
    gi_set_uniforms(t->prog.id, &t->gi);
    bool canopy = t->canopy.rows > 1 && t->canopy_fade[1] > 0.0f;
    glUniform2f(gfx_uniform(t->prog, "u_canopy_fade"), canopy ? t->canopy_fade[0] : 0.0f,
                canopy ? t->canopy_fade[1] : 0.0f);
    if (canopy) {
        static const float root[3] = SCENE_DEFAULT_ALBEDO_ROOT, tip[3] = SCENE_DEFAULT_ALBEDO_TIP;
        const blade_canopy_uniforms_t *u = &t->canopy;
        glUniform1i(gfx_uniform(t->prog, "u_canopy_rows"), u->rows);
        glUniform1fv(gfx_uniform(t->prog, "u_canopy_cover"), u->rows, u->cover);
        glUniform4fv(gfx_uniform(t->prog, "u_canopy_amb"), u->rows, &u->amb[0][0]);
        glUniform2fv(gfx_uniform(t->prog, "u_canopy_sun"), u->rows * BLADE_CANOPY_AZIMUTHS, &u->sun[0][0]);
        glUniform3fv(gfx_uniform(t->prog, "u_canopy_albedo_root"), 1, root);
        glUniform3fv(gfx_uniform(t->prog, "u_canopy_albedo_tip"), 1, tip);
        glUniform1i(gfx_uniform(t->prog, "u_extent_on"), t->extent != 0);
        glUniform1i(gfx_uniform(t->prog, "u_extent"), 0);
        glUniform2fv(gfx_uniform(t->prog, "u_extent_origin"), 1, t->extent_origin);
        glUniform1f(gfx_uniform(t->prog, "u_extent_spacing"), t->extent_spacing);
        glBindTextureUnit(0, t->extent);
    }
    glBindVertexArray(t->vao);
    glDrawElements(GL_TRIANGLES, t->index_count, GL_UNSIGNED_INT, NULL);

    /* Sky after the ground, at the far plane with LEQUAL and no depth write:
     * only pixels the terrain left empty run the sky shader. */
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glUseProgram(t->sky.id);
    glUniformMatrix4fv(gfx_uniform(t->sky, "u_inv_viewproj"), 1, GL_FALSE, (const float *)v->inv_viewproj);
    glBindVertexArray(t->empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glBindVertexArray(0);
}
