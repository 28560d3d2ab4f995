# rt_write_if_changed(path content): writes `content` to `path` only when it differs from what the
# file holds, so that a configure or a build step that regenerates a file does not make what
# depends on it rebuild. Included by tests/integration/CMakeLists.txt and tests/label_tests.cmake.
function(rt_write_if_changed path content)
  set(old "")
  if(EXISTS ${path})
    file(READ ${path} old)
  endif()
  if(NOT old STREQUAL content)
    file(WRITE ${path} "${content}")
  endif()
endfunction()
