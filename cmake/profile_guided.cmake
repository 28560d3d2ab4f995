# Profile-guided optimisation of the apps' path tracer (-DRTWEEKEND_PGO=ON, GCC only).
#
# The path tracer the apps link (rtweekend_engine, rtweekend/engine.cpp) holds
# every hot loop: the BVH walks, the shape and material kernels, the sampler. With PGO, g++ first
# builds an instrumented copy of it (rtweekend_pgo_instrumented) and a driver (rtweekend_pgo_train,
# the render app linked against that copy), renders small versions of the test scenes with it,
# one thread each so that the counts and hence the optimised code are the same on every build,
# and then compiles the library the apps link with the counts it recorded: which branches go
# which way, which calls are hot. Every scene kind trains (spheres, triangles, quads, lights,
# textures, media, caustics), so none is laid out as cold code. The images stay deterministic
# for a given build; another build (with or without PGO) may differ in the last bits, as
# builds for other processors do. The measured gain: docs/speed.md; the cost: docs/testing.md.
#
# The counts go next to the instrumented object (g++'s default); a custom command copies them to
# where the optimised compile of the same source looks for its own (its object's name + .gcda).
if(NOT RTWEEKEND_PGO)
  return()
endif()
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  message(WARNING "RTWEEKEND_PGO is ON but the compiler is ${CMAKE_CXX_COMPILER_ID}, not GNU: PGO is not used")
  return()
endif()
if(RTWEEKEND_SANITIZE OR RTWEEKEND_TSAN)
  message(STATUS "RTWEEKEND_PGO: not used with the sanitizers")
  return()
endif()
if(NOT RTWEEKEND_BUILD_APPS)
  message(STATUS "RTWEEKEND_PGO: not used without the apps (the training renders with apps/render.cpp)")
  return()
endif()

add_library(rtweekend_pgo_instrumented STATIC rtweekend/engine.cpp)
target_link_libraries(rtweekend_pgo_instrumented PUBLIC rtweekend PRIVATE rtweekend_project_flags)
target_compile_definitions(rtweekend_pgo_instrumented INTERFACE RTWEEKEND_LINK_ENGINE)
target_compile_options(rtweekend_pgo_instrumented PRIVATE -fprofile-generate -fprofile-update=atomic)
target_link_options(rtweekend_pgo_instrumented INTERFACE -fprofile-generate)

add_executable(rtweekend_pgo_train apps/render.cpp apps/app_options.cpp)
target_link_libraries(rtweekend_pgo_train PRIVATE rtweekend_pgo_instrumented rtweekend rtweekend_project_flags)
target_compile_definitions(rtweekend_pgo_train PRIVATE RTWEEKEND_TEXTURE_DIR="${PROJECT_SOURCE_DIR}/tests/data/textures")

set(pgo_train_counts
    ${PROJECT_BINARY_DIR}/CMakeFiles/rtweekend_pgo_instrumented.dir/rtweekend/engine.cpp.gcda)
set(pgo_use_counts
    ${PROJECT_BINARY_DIR}/CMakeFiles/rtweekend_engine.dir/rtweekend/engine.cpp.gcda)
set(pgo_out ${PROJECT_BINARY_DIR}/pgo_training)
set(pgo_scenes ${PROJECT_SOURCE_DIR}/tests/data)
# Small sizes: 3.6 s for all of them in the instrumented build on the Xeon of BENCHMARKS.md
# section 24. The cover has the most samples, as the scene the speed targets are set on.
set(pgo_renders
    "rtiow_cover.txt --width 400 --spp 4"
    "bunny.txt --width 200 --spp 4"
    "cornell_box.txt --width 150 --spp 8"
    "sphere_room.txt --width 150 --spp 4"
    "next_week_final.txt --width 120 --spp 8"
    "cornell_smoke.txt --width 100 --spp 8"
    "materials.txt --width 150 --spp 4"
    "earth.txt --width 100 --spp 4"
    "quads.txt --width 100 --spp 4")
set(pgo_commands)
foreach(render IN LISTS pgo_renders)
  separate_arguments(args UNIX_COMMAND "${render}")
  list(GET args 0 scene)
  list(REMOVE_AT args 0)
  list(APPEND pgo_commands COMMAND $<TARGET_FILE:rtweekend_pgo_train> ${pgo_scenes}/${scene} ${args} --threads 1
       --quiet -o ${pgo_out}/${scene}.pfm)
endforeach()
add_custom_command(OUTPUT ${pgo_use_counts}
  COMMAND ${CMAKE_COMMAND} -E rm -f ${pgo_train_counts}
  COMMAND ${CMAKE_COMMAND} -E make_directory ${pgo_out}
  ${pgo_commands}
  COMMAND ${CMAKE_COMMAND} -E copy ${pgo_train_counts} ${pgo_use_counts}
  DEPENDS rtweekend_pgo_train
  COMMENT "PGO: training the path tracer on small renders of the test scenes"
  VERBATIM)
add_custom_target(rtweekend_pgo_profile DEPENDS ${pgo_use_counts})
add_dependencies(rtweekend_engine rtweekend_pgo_profile)
# Functions no training render reaches (other estimators, caustics of other kinds) keep the
# ordinary optimisation (-fprofile-partial-training); g++ would name each of them in a warning.
target_compile_options(rtweekend_engine PRIVATE -fprofile-use -fprofile-partial-training -Wno-missing-profile)
message(STATUS "RTWEEKEND_PGO: the apps' path tracer is compiled with profile-guided optimisation")
