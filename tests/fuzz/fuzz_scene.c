/* fuzz_scene: libFuzzer target for the scene-file parser. Feeds arbitrary
 * bytes (made NUL-terminated, as scene_load does after core_fs_read) to
 * scene_parse(); on success it also builds the t = 0 camera and evaluates
 * every parsed path, so values that passed validation are exercised too.
 * A crash, an ASan/UBSan report or an error message that does not start with
 * the file name is a finding. No paper equations. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"
#include "scene/scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    if (!text) return 0;
    memcpy(text, data, size);
    text[size] = 0;

    static scene_desc_t desc; /* about 60 KiB: keep it off the stack */
    char err[512];
    if (scene_parse(&desc, text, "fuzz.json", err, sizeof err)) {
        cam_t cam;
        scene_camera_init(&desc, &cam);
        mat4 vp;
        cam_viewproj(&cam, vp);
        for (float t = -1.0f; t <= 4.0f; t += 0.75f) {
            cam_path_eval(&desc.camera.path, t, &cam);
            for (int i = 0; i < desc.collider_count; i++) {
                vec3 pos, vel;
                scene_path_eval(&desc.colliders[i].path, t, desc.colliders[i].loop, pos, vel);
            }
            for (int i = 0; i < desc.character_count; i++) {
                const scene_character_t *ch = &desc.characters[i];
                vec2 pos, dir;
                scene_walk_eval((const vec2 *)ch->waypoints, ch->waypoint_count, ch->speed, t,
                                ch->loop, pos, dir);
            }
        }
        scene_free(&desc);
    } else if (strncmp(err, "fuzz.json:", 10) != 0) {
        /* Every parse error must name file:line; anything else is a bug. */
        abort();
    }
    free(text);
    return 0;
}
