// libFuzzer harness: MTL material libraries through the OBJ model reader (rtweekend/io/obj_model.h:
// check_mtl_text, tinyobjloader's MTL parser, material_from_mtl), then a tiny render.
//
// The input is the text of an MTL file, read by rt::decode_obj_model beside a fixed OBJ of two
// squares with materials `a` and `b` (textured), as if it were tests/data/models/fuzz_input.mtl, so
// that texture names such as still_life_tiles.png reach a real file. A model it accepts is rendered
// at 8x8 pixels, 2 samples per pixel, depth 4 (tiny_render.h), under a white sky: every material
// the rules make meets the scene compiler's checks and the path tracer. A refused library must
// give one clear error line.

#include "fuzz_support.h"
#include "tiny_render.h"

#include <rtweekend/camera.h>
#include <rtweekend/io/obj_model.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace {
const char* const model_obj = "mtllib fuzz_input.mtl\n"
                              "v -1 -1 0\nv 0 -1 0\nv 0 1 0\nv -1 1 0\nv 0 -1 0\nv 1 -1 0\nv 1 1 0\nv 0 1 0\n"
                              "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
                              "usemtl a\nf 1//1 2//1 3//1\nf 1//1 3//1 4//1\n"
                              "usemtl b\nf 5/1 6/2 7/3\nf 5/1 7/3 8/4\n";
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        rt::obj_model model = rt::decode_obj_model(model_obj, RTWEEKEND_TEST_DATA "/models/fuzz_input.obj",
                                                   fuzz::bytes(data, size), RTWEEKEND_TEST_DATA "/models/fuzz_input.mtl");
        for (const std::string& w : model.warnings) fuzz::check_one_line(w);
        fuzz::render_model(std::move(model.world));
    } catch (const rt::scene_error& e) {
        fuzz::refused(e);
    }
    return 0;
}
