/* world_colliders: the scene's analytic colliders (spheres, capsules, boxes on
 * keyed paths): meshes on the GPU, positions per frame, and drawing. */
#include "world/world_local.h"

#include <string.h>

bool world_colliders_make(world_colliders_t *c, const scene_desc_t *s)
{
    memset(c, 0, sizeof *c);
    c->count = s->collider_count;
    for (int i = 0; i < c->count; i++) {
        world_collider_t *a = &c->items[i];
        a->desc = s->colliders[i];
        collide_shape_t shape = scene_collider_shape(&a->desc);
        if (!collide_make_mesh(&a->mesh, &shape)) return false;
        size_t nv = a->mesh.vertex_count;
        float *vn = malloc(nv * 6 * sizeof(float));
        if (!vn) return false;
        for (size_t k = 0; k < nv; k++) {
            memcpy(vn + k * 6, a->mesh.positions + k * 3, 3 * sizeof(float));
            memcpy(vn + k * 6 + 3, a->mesh.normals + k * 3, 3 * sizeof(float));
        }
        a->vbo = gfx_buffer_make(&(gfx_buffer_desc_t){.size = nv * 6 * sizeof(float), .data = vn,
                                                      .label = "collider.vertices"});
        free(vn);
        a->ibo = gfx_buffer_make(&(gfx_buffer_desc_t){.size = a->mesh.index_count * sizeof(uint32_t),
                                                      .data = a->mesh.indices, .label = "collider.indices"});
        a->vao = gfx_vertex_array_make("collider.vao");
        glVertexArrayVertexBuffer(a->vao, 0, a->vbo.id, 0, 6 * sizeof(float));
        glVertexArrayElementBuffer(a->vao, a->ibo.id);
        for (GLuint k = 0; k < 2; k++) {
            glEnableVertexArrayAttrib(a->vao, k);
            glVertexArrayAttribFormat(a->vao, k, 3, GL_FLOAT, GL_FALSE, k * 3 * sizeof(float));
            glVertexArrayAttribBinding(a->vao, k, 0);
        }
        a->bound_radius = collide_bounding_radius(&shape);
    }
    c->prog = gfx_program_make(&(gfx_program_desc_t){.vs = "world/object.vert", .fs = "world/object.frag",
                                                     .label = "collider.program"});
    return c->prog.id != 0;
}

void world_colliders_destroy(world_colliders_t *c)
{
    for (int i = 0; i < c->count; i++) {
        world_collider_t *a = &c->items[i];
        gfx_buffer_destroy(&a->vbo);
        gfx_buffer_destroy(&a->ibo);
        gfx_vertex_array_destroy(&a->vao);
        collide_free_mesh(&a->mesh);
    }
    gfx_program_destroy(&c->prog);
    c->count = 0;
}

void world_colliders_update(world_colliders_t *c, const terrain_mesh_t *terrain, float t)
{
    for (int i = 0; i < c->count; i++) {
        world_collider_t *a = &c->items[i];
        scene_path_eval(&a->desc.path, t, a->desc.loop, a->position, a->velocity);
        if (terrain->grid_res > 0) a->position[1] += terrain_height_at(terrain, a->position[0], a->position[2], NULL);
    }
}

void world_colliders_draw(const world_colliders_t *c, const grass_view_t *v)
{
    if (!c->count) return;
    gfx_timer_begin(GFX_PASS_COLLIDERS);
    glUseProgram(c->prog.id);
    glUniformMatrix4fv(gfx_uniform(c->prog, "u_viewproj"), 1, GL_FALSE, v->viewproj);
    glUniform3fv(gfx_uniform(c->prog, "u_sun"), 1, v->sun);
    glUniform3fv(gfx_uniform(c->prog, "u_camera"), 1, v->camera);
    glUniform3f(gfx_uniform(c->prog, "u_albedo"), 0.75f, 0.22f, 0.15f);
    for (int i = 0; i < c->count; i++) {
        const world_collider_t *a = &c->items[i];
        mat4 model;
        glm_translate_make(model, (float *)a->position);
        glUniformMatrix4fv(gfx_uniform(c->prog, "u_model"), 1, GL_FALSE, (const float *)model);
        glBindVertexArray(a->vao);
        glDrawElements(GL_TRIANGLES, (GLsizei)a->mesh.index_count, GL_UNSIGNED_INT, NULL);
    }
    glBindVertexArray(0);
    gfx_timer_end();
}
