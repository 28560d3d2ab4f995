#pragma once
// Where the engine's entry points are compiled: in every file that uses them (header-only, the
// default) or once, in the library rtweekend::engine (rtweekend/engine.cpp), that a program links.
//
// An entry point (path_trace, compile_scene, ...) is declared RTWEEKEND_ENGINE_FUNCTION and its
// body, with the internals only it uses, sits under `#if RTWEEKEND_ENGINE_BODIES`:
//
//   header-only         RTWEEKEND_ENGINE_FUNCTION = inline, bodies in every file (nothing to link)
//   linking the engine  RTWEEKEND_LINK_ENGINE defined (rtweekend::engine's users get it): the
//                       declarations alone, so a main compiles its own code and nothing else
//   the engine itself   RTWEEKEND_ENGINE_TU defined (engine.cpp): bodies, not inline, once
//
// Every file of one program must agree: the CMake target sets the macro for all its users.

#if defined(RTWEEKEND_ENGINE_TU)
#define RTWEEKEND_ENGINE_FUNCTION
#define RTWEEKEND_ENGINE_BODIES 1
#elif defined(RTWEEKEND_LINK_ENGINE)
#define RTWEEKEND_ENGINE_FUNCTION
#define RTWEEKEND_ENGINE_BODIES 0
#else
#define RTWEEKEND_ENGINE_FUNCTION inline
#define RTWEEKEND_ENGINE_BODIES 1
#endif
