// The path tracer (rtweekend/render/path_tracer.h), compiled once for all of this project's own
// programs: the apps and the unit tests link it (the CMake target rtweekend_compiled_path_tracer)
// instead of each compiling it again. Those programs are built with RTWEEKEND_LINK_PATH_TRACER,
// which leaves path_trace's definitions out of the header, so that it is declared there and
// defined only here. It is the library's heaviest code to compile: a milestone app that includes
// it compiles in about 23 s at -O3, one that links it in 6.5 s.
//
// Nothing changes for users: without the macro the header defines path_trace inline, as every
// header-only function is.
#define RTWEEKEND_PATH_TRACER_INLINE /* defined here, not inline */
#include <rtweekend/render/path_tracer.h>
