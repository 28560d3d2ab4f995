// libFuzzer harness: text scene files (rtweekend/io/scene_file.h), then a tiny render.
//
// The input is the text of a scene file, read by rt::decode_scene as if it were a file in
// tests/data, so that its relative mesh and texture paths (meshes/bunny_npm.obj, ply/quad.ply,
// textures/rows_4x2.png) reach real files. A scene it accepts is rendered at 8x8 pixels, 2 samples
// per pixel and depth 4 (tiny_render.h): the camera's and the scene compiler's checks and the path
// tracer see every value the parser let through. A refused scene must give one clear error line.

#include "fuzz_support.h"
#include "tiny_render.h"

#include <rtweekend/camera.h>
#include <rtweekend/io/scene_file.h>

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        rt::scene_description scene = rt::decode_scene(fuzz::bytes(data, size), RTWEEKEND_TEST_DATA "/fuzz_input.txt");
        fuzz::shrink(scene.cam);
        rt::render(scene.cam, scene.world, scene.point_lights);
    } catch (const rt::scene_error& e) {
        fuzz::refused(e);
    }
    return 0;
}
