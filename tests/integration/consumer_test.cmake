# consumer_test.cmake: builds and runs tests/integration/consumer against this checkout.
#
#   cmake -DMODE=install|subdir -DSOURCE_DIR=<checkout> -DBUILD_DIR=<its build dir>
#         -DCONSUMER_DIR=<consumer sources> -DWORK_DIR=<scratch dir, wiped first>
#         -DGENERATOR=... [-DGENERATOR_PLATFORM=...] [-DGENERATOR_TOOLSET=...] [-DMAKE_PROGRAM=...]
#         -DCXX_COMPILER=... [-DBUILD_TYPE=...] [-DCONFIG=...] [-DINSTALL_CONFIG=...] -P consumer_test.cmake
#
# BUILD_TYPE and CONFIG are the consumer's configuration; INSTALL_CONFIG the checkout build's, for
# `cmake --install` (multi-configuration generators).
#
# MODE=install: `cmake --install BUILD_DIR --prefix WORK_DIR/stage`, then the consumer finds the
#               package with find_package(rtweekend) and CMAKE_PREFIX_PATH=WORK_DIR/stage.
# MODE=subdir:  the consumer does add_subdirectory(SOURCE_DIR).
# Either way the consumer's app must build, run, and write a PNG.

cmake_minimum_required(VERSION 3.16)

foreach(var IN ITEMS MODE SOURCE_DIR CONSUMER_DIR WORK_DIR GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "consumer_test.cmake: ${var} is not set")
  endif()
endforeach()
if(NOT MODE MATCHES "^(install|subdir)$")
  message(FATAL_ERROR "consumer_test.cmake: MODE must be install or subdir, got '${MODE}'")
endif()

# Runs a command; stops the test with its output if it fails.
function(run step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc STREQUAL "0")
    string(REPLACE ";" " " shown "${ARGN}")
    message(FATAL_ERROR "${step} failed (exit status '${rc}')\ncommand: ${shown}\n"
                        "--- stdout ---\n${out}\n--- stderr ---\n${err}\n--------------")
  endif()
  set(last_stdout "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

set(config_args "")
if(CONFIG)
  set(config_args --config "${CONFIG}")
endif()
# The checkout's build is installed in its own configuration, which may differ from the consumer's.
set(install_config_args "")
if(INSTALL_CONFIG)
  set(install_config_args --config "${INSTALL_CONFIG}")
endif()

set(configure_args -S "${CONSUMER_DIR}" -B "${WORK_DIR}/build" -G "${GENERATOR}"
    "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
# One app each, as the suite must stay near a minute on 2 cores: the installed package, where the
# engine comes prebuilt, builds app_engine (rtweekend::engine, which links rtweekend::rtweekend);
# the subproject builds the header-only app (as a subproject, app_engine would compile all of
# engine.cpp in Debug, 25 s, to check the same linkage again; the target must still exist).
if(MODE STREQUAL "install")
  set(consumer_apps app_engine)
  list(APPEND configure_args -DCONSUMER_APPS=app_engine)
else()
  set(consumer_apps app)
  list(APPEND configure_args -DCONSUMER_APPS=app)
endif()
if(GENERATOR_PLATFORM)
  list(APPEND configure_args -A "${GENERATOR_PLATFORM}")
endif()
if(GENERATOR_TOOLSET)
  list(APPEND configure_args -T "${GENERATOR_TOOLSET}")
endif()
if(MAKE_PROGRAM)
  list(APPEND configure_args "-DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM}")
endif()
if(BUILD_TYPE)
  list(APPEND configure_args "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}")
endif()

if(MODE STREQUAL "install")
  if(NOT IS_DIRECTORY "${BUILD_DIR}")
    message(FATAL_ERROR "consumer_test.cmake: BUILD_DIR '${BUILD_DIR}' is not a directory")
  endif()
  set(stage "${WORK_DIR}/stage")
  run("cmake --install" "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${stage}" ${install_config_args})

  # Every header of the checkout is installed, and the package files are there.
  file(GLOB headers RELATIVE "${SOURCE_DIR}/rtweekend" "${SOURCE_DIR}/rtweekend/*.h")
  foreach(header IN LISTS headers)
    if(NOT EXISTS "${stage}/include/rtweekend/${header}")
      message(FATAL_ERROR "cmake --install did not install include/rtweekend/${header}")
    endif()
  endforeach()
  file(GLOB_RECURSE config_files "${stage}/*/rtweekendConfig.cmake")
  file(GLOB_RECURSE version_files "${stage}/*/rtweekendConfigVersion.cmake")
  file(GLOB_RECURSE target_files "${stage}/*/rtweekendTargets.cmake")
  if(NOT config_files OR NOT version_files OR NOT target_files)
    message(FATAL_ERROR "cmake --install did not install rtweekendConfig.cmake, rtweekendConfigVersion.cmake "
                        "and rtweekendTargets.cmake (found: ${config_files} ${version_files} ${target_files})")
  endif()

  list(APPEND configure_args "-DCMAKE_PREFIX_PATH=${stage}" "-DRTWEEKEND_EXPECTED_PREFIX=${stage}")
else()
  list(APPEND configure_args "-DRTWEEKEND_SOURCE_DIR=${SOURCE_DIR}")
endif()

run("configuring the consumer" "${CMAKE_COMMAND}" ${configure_args})
run("building the consumer" "${CMAKE_COMMAND}" --build "${WORK_DIR}/build" ${config_args})

# An installed package must not point back into the checkout: the consumer compiles against the
# installed headers only.
if(MODE STREQUAL "install" AND EXISTS "${WORK_DIR}/build/compile_commands.json")
  file(READ "${WORK_DIR}/build/compile_commands.json" commands)
  string(FIND "${commands}" "${SOURCE_DIR}/rtweekend" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "the consumer of the installed package compiles with the checkout's headers:\n${commands}")
  endif()
endif()

# The headers alone (app) or the engine compiled once (app_engine).
foreach(name IN LISTS consumer_apps)
  file(GLOB_RECURSE apps "${WORK_DIR}/build/${name}" "${WORK_DIR}/build/${name}.exe")
  list(FILTER apps EXCLUDE REGEX "/CMakeFiles/")
  if(NOT apps)
    message(FATAL_ERROR "the consumer build produced no '${name}' executable")
  endif()
  list(GET apps 0 app)
  set(png "${WORK_DIR}/${name}.png")
  run("running the consumer's ${name}" "${app}" "${png}")
  if(NOT EXISTS "${png}")
    message(FATAL_ERROR "the consumer's ${name} exited 0 but did not write ${png}")
  endif()
  file(READ "${png}" magic LIMIT 8 HEX)
  if(NOT magic STREQUAL "89504e470d0a1a0a")
    message(FATAL_ERROR "${png} is not a PNG: it starts with ${magic}")
  endif()
endforeach()
message(STATUS "consumer (${MODE}): ${last_stdout}")
