/* gi.c: the volumes' textures and their binding (gi.h). The irradiance's
 * 12 floats per cell go to three RGBA16F textures in order (a.rgb, Bx.r |
 * Bx.gb, By.rg | By.b, Bz.rgb), as common/gi.glsl reads them back. */
#include "gi/gi.h"

#include <stdlib.h>
#include <string.h>

#include "common/bindings_gi.glsl"
#include "core/core.h"

bool gi_gpu_make(gi_gpu_t *g, const gi_volume_t *v)
{
    memset(g, 0, sizeof *g);
    size_t cells = (size_t)v->res[0] * (size_t)v->res[1] * (size_t)v->res[2];
    float *part = malloc(sizeof(float) * 4 * cells);
    if (!part) {
        core_log_error("gi: out of memory for the volumes' upload");
        return false;
    }
    gfx_texture_desc_t d = {.target = GL_TEXTURE_3D, .w = v->res[0], .h = v->res[1], .layers = v->res[2],
                            .format = GL_R16F, .data = v->ao, .upload_format = GL_RED, .upload_type = GL_FLOAT,
                            .label = "gi.ao"};
    g->ao = gfx_texture_make(&d);
    static const char *const labels[3] = {"gi.irradiance0", "gi.irradiance1", "gi.irradiance2"};
    bool ok = g->ao.id != 0;
    for (int t = 0; t < 3 && ok; t++) {
        for (size_t c = 0; c < cells; c++) memcpy(&part[4 * c], &v->irr[c * GI_IRR_FLOATS + 4 * (size_t)t], 16);
        d.format = GL_RGBA16F;
        d.upload_format = GL_RGBA;
        d.data = part;
        d.label = labels[t];
        g->irr[t] = gfx_texture_make(&d);
        ok = g->irr[t].id != 0;
    }
    free(part);
    if (!ok) {
        gi_gpu_destroy(g);
        return false;
    }
    memcpy(g->lo, v->lo, sizeof g->lo);
    memcpy(g->hi, v->hi, sizeof g->hi);
    memcpy(g->bounce, v->bounce, sizeof g->bounce);
    return true;
}

void gi_gpu_destroy(gi_gpu_t *g)
{
    gfx_texture_destroy(&g->ao);
    for (int t = 0; t < 3; t++) gfx_texture_destroy(&g->irr[t]);
    memset(g, 0, sizeof *g);
}

gi_bind_t gi_gpu_bind(const gi_gpu_t *g)
{
    gi_bind_t b = {0};
    if (!g || !g->ao.id) return b;
    b.ao = g->ao.id;
    for (int t = 0; t < 3; t++) {
        b.irr[t] = g->irr[t].id;
        b.lo[t] = g->lo[t];
        b.inv_size[t] = 1.0f / (g->hi[t] - g->lo[t]);
        b.bounce[t] = g->bounce[t];
    }
    return b;
}

void gi_set_uniforms(GLuint p, const gi_bind_t *b)
{
    gfx_program_t gp = {.id = p};
    bool on = b && b->ao;
    glUniform1i(gfx_uniform(gp, "u_gi_on"), on);
    if (!on) return;
    glUniform3fv(gfx_uniform(gp, "u_gi_lo"), 1, b->lo);
    glUniform3fv(gfx_uniform(gp, "u_gi_inv_size"), 1, b->inv_size);
    glUniform3fv(gfx_uniform(gp, "u_gi_bounce"), 1, b->bounce);
    glBindTextureUnit(GI_TEX_AO, b->ao);
    for (int t = 0; t < 3; t++) glBindTextureUnit(GI_TEX_IRR0 + (GLuint)t, b->irr[t]);
}
