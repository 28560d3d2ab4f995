// The engine compiled once, as the CMake target rtweekend::engine builds it: every entry point
// declared RTWEEKEND_ENGINE_FUNCTION (path_trace, compile_scene, the Whitted renderer, the scene
// and mesh readers, ...) with everything they stand on (the BVH, the kernels, the scheduler).
// A program that links it is compiled with RTWEEKEND_LINK_ENGINE, which leaves those bodies out of
// the headers (core/engine_linkage.h), so its own files compile their own code and nothing else:
// with the headers precompiled, as rtweekend::engine sets up, an edited main rebuilds in seconds
// (BENCHMARKS.md, section 30).
//
// Nothing changes for a program that does not link it: without the macro every header defines its
// functions inline, as a header-only library does.
#define RTWEEKEND_ENGINE_TU
#include "rtweekend.h"
#include "scene/scene_compiler.h"
#include "io/xml_scene.h"
#include "io/gltf_model.h"
#include "io/model_scene.h"
#include "render/guides.h"
