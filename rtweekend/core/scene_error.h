#pragma once
// scene_error: the one exception the renderer throws for input it cannot use (a bad camera
// setting, NaN coordinates, a malformed scene file, an unwritable output path). Its message is a
// single line that names the problem.

#include <stdexcept>

namespace rt {

class scene_error : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

} // namespace rt
