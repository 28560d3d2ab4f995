// libFuzzer harness: glTF 2.0 models through the glTF reader (rtweekend/io/gltf_model.h: tinygltf's
// JSON and GLB parser, then the accessors, node hierarchy, materials, pictures, camera and lights),
// then a tiny render.
//
// The input is a whole .gltf (JSON, buffers as data URIs) or .glb file, read as if it were
// tests/data/models/fuzz_input.gltf, so that relative file names reach that folder (its PNG
// still_life_tiles.png among them). A model it accepts is rendered at 8x8 pixels, 2 samples per
// pixel, depth 4 (tiny_render.h), under a white sky with its point lights: every material and
// placement the reader makes meets the scene compiler's checks and the path tracer. A refused
// file must give one clear error line, and each warning is one line.

#include "fuzz_support.h"
#include "tiny_render.h"

#include <rtweekend/camera.h>
#include <rtweekend/io/gltf_model.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        rt::gltf_model model = rt::decode_gltf_model(fuzz::bytes(data, size), RTWEEKEND_TEST_DATA "/models/fuzz_input.gltf");
        for (const std::string& w : model.warnings) fuzz::check_one_line(w);
        fuzz::render_model(std::move(model.world), model.point_lights);
    } catch (const rt::scene_error& e) {
        fuzz::refused(e);
    }
    return 0;
}
