// libFuzzer harness: CENG795 XML scenes (rtweekend/io/xml_scene.h) with the PLY files they
// reference (rtweekend/io/ply.h), then a tiny Whitted render (course_scene_harness.h says how).

#include "course_scene_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    fuzz::course_scene(data, size, "scene.xml");
    return 0;
}
