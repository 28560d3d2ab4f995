// libFuzzer harness: Wavefront OBJ meshes through the project's loader (rtweekend/io/obj.h:
// check_obj_text, then tinyobjloader), and apps/subdivide's Loop subdivision of what it reads.
//
// The input is an OBJ file, read from memory by rt::decode_obj. tinyobjloader is compiled into
// the harness from Debian's header (tinyobjloader_impl.cpp), so the sanitizers and the coverage
// feedback see inside it too. A mesh it accepts, of at most 2000 triangles, goes through one level
// of Loop subdivision (apps/loop_subdivision.h), which may refuse it with one error line
// (non-manifold, say); what subdivide would write (encode_obj) must read back with four times the
// triangles. A refused file must give one clear error line.

#include "fuzz_support.h"

#include "loop_subdivision.h"

#include <rtweekend/io/obj.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::shared_ptr<rt::triangle_mesh> mesh;
    try {
        mesh = rt::decode_obj(fuzz::bytes(data, size), "fuzz.obj", nullptr);
    } catch (const rt::scene_error& e) {
        fuzz::refused(e);
        return 0;
    }
    if (mesh->faces.size() > 2000) return 0;
    app::tri_mesh finer;
    try {
        finer = app::loop_subdivide({mesh->positions, mesh->faces}, 1);
    } catch (const rt::scene_error& e) {
        fuzz::refused(e);
        return 0;
    }
    try {
        std::shared_ptr<rt::triangle_mesh> again = rt::decode_obj(app::encode_obj(finer), "subdivided.obj", nullptr);
        if (again->faces.size() != 4 * mesh->faces.size()) {
            std::fprintf(stderr, "fuzz: subdivision made %zu triangles of %zu, %zu read back\n", finer.triangles.size(),
                         mesh->faces.size(), again->faces.size());
            std::abort();
        }
    } catch (const rt::scene_error& e) {
        std::fprintf(stderr, "fuzz: the subdivided mesh does not read back: %s\n", e.what());
        std::abort();
    }
    return 0;
}
