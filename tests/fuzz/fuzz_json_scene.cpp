// libFuzzer harness: CENG795 scenes in the course's JSON form (rtweekend/io/course_json.h, read
// through rtweekend/io/xml_scene.h) with the PLY files they reference, then a tiny Whitted render
// (course_scene_harness.h says how).

#include "course_scene_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    fuzz::course_scene(data, size, "scene.json");
    return 0;
}
