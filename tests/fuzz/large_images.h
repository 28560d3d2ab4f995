#pragma once
// fuzz::too_large_to_decode(bytes): whether an image that stb_image would decode passes the
// project's checks (rt::detail::stb_input_problem: headers, the 2^28-pixel limit, what the file's
// length can hold) yet claims more than 2^22 pixels. Such an image is legitimate (a few kilobytes
// of PNG hold millions of blank pixels), but decoding it under the sanitizers takes seconds, which
// libFuzzer would report as a timeout; the image harnesses skip it, after the checks have run. So
// with a JPEG of many scans (each a pass over the image): pixels x scans above 2^24.

#include <rtweekend/rtw_stb_image.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>

namespace fuzz {

inline bool too_large_to_decode(const std::string& bytes) {
    if (!rt::detail::stb_input_problem(bytes).empty()) return false; // refused: cheap, and worth fuzzing
    int w = 0, h = 0, channels = 0;
    if (!stbi_info_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), int(bytes.size()), &w, &h, &channels))
        return false;
    const uint64_t pixels = uint64_t(w) * uint64_t(h);
    // A JPEG costs a pass over the image per scan (up to rt::max_jpeg_scans): 2^22 pixels in 4 of
    // them, or fewer pixels in more.
    size_t scans = 1;
    if (rt::detail::jpeg_after_soi(bytes)) rt::detail::jpeg_header_problem(bytes, &scans);
    return pixels * std::max<uint64_t>(scans, 4) > (uint64_t(1) << 24);
}

} // namespace fuzz
