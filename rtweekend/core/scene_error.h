#pragma once
// scene_error: the one exception the renderer throws for input it cannot use (a bad camera
// setting, NaN coordinates, a malformed scene file, an unwritable output path). Its message is a
// single line that names the problem.

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace rt {

class scene_error : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// A number as a message shows it: nine significant digits at most ("1e+308", "0.1", "-2.5"), where
// std::to_string writes six decimals, and 309 digits for 1e308.
inline std::string number_text(double v) {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.9g", v);
    return buffer;
}

// A word of the input as a message quotes it: at most 40 characters of it, control characters
// written as \xNN, and its length when it was cut (a 100 MB "number" gave a 100 MB error line).
inline std::string token_text(const std::string& word) {
    constexpr size_t shown = 40;
    static const char digits[] = "0123456789abcdef";
    std::string out;
    for (size_t i = 0; i < word.size() && i < shown; ++i) {
        const unsigned char u = static_cast<unsigned char>(word[i]);
        if (u < 0x20 || u == 0x7f) {
            out += "\\x";
            out += digits[u >> 4];
            out += digits[u & 15];
        } else {
            out += word[i];
        }
    }
    if (word.size() > shown) out += "... (" + std::to_string(word.size()) + " characters)";
    return out;
}

} // namespace rt
