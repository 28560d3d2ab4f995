#pragma once
// input_limits: the largest inputs the readers accept. Each limit keeps a damaged or hostile file
// from making a reader allocate or compute without bound; each is far above what a real scene,
// mesh or image needs, and each is named in the one error line that refuses an input beyond it.
//
//   max_input_file_bytes   4 GiB: any file a reader loads whole (scenes, meshes, images, rays)
//   max_image_pixels       2^28 (16384 x 16384): an image read (a texture, an image to compare);
//                          at 3 floats a pixel that is 3 GiB, the most one image may take
//   max_render_pixels      2^26 (8192 x 8192, or any shape of that area): an image rendered, or a
//                          slice of one. A render keeps, besides its float image (12 bytes a
//                          pixel), exact sums of its samples (28 bytes a pixel) and, with light
//                          tracing, its splats (48 bytes a pixel): 38 bytes a pixel in all, 2.6 GB
//                          at this limit (86 bytes, 5.8 GB, with light tracing). docs/rendering.md
//                          gives the measured peaks
//   max_image_side         2^24: one side of an image (stb_image's own limit)
//   max_obj_face_corners   1024: corners of one OBJ polygon (tinyobjloader triangulates a polygon
//                          in time quadratic in its corners)
//   max_jpeg_scans         100: scans (SOS segments) of one JPEG; stb_image decodes each over the
//                          whole image, so a few kilobytes of empty scans cost seconds. libjpeg's
//                          progressive script writes 10
//
//   check_image_size(w, h, what)   throws scene_error "WHAT is WxH = N pixels, more than the limit
//                                  of 268435456 (2^28) pixels" (or names a zero side)
//   check_render_size(w, h, what)  the same against max_render_pixels: "... more than the limit of
//                                  67108864 (2^26) pixels for a render"

#include "scene_error.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace rt {

inline constexpr uint64_t max_input_file_bytes = uint64_t(4) << 30;
inline constexpr uint64_t max_image_pixels = uint64_t(1) << 28;
inline constexpr uint64_t max_render_pixels = uint64_t(1) << 26;
inline constexpr uint64_t max_image_side = uint64_t(1) << 24;
inline constexpr size_t max_obj_face_corners = 1024;
inline constexpr size_t max_jpeg_scans = 100;

// "4 GiB (4294967296 bytes)" for messages.
inline std::string byte_limit_text(uint64_t bytes) {
    std::string exact = std::to_string(bytes) + " bytes";
    if (bytes >= (uint64_t(1) << 30) && bytes % (uint64_t(1) << 30) == 0)
        return std::to_string(bytes >> 30) + " GiB (" + exact + ")";
    return exact;
}

namespace detail {
inline void check_pixels(uint64_t w, uint64_t h, const std::string& what, uint64_t limit, int log2_limit,
                         const char* limit_of) {
    if (w == 0 || h == 0)
        throw scene_error(what + " is " + std::to_string(w) + "x" + std::to_string(h) + ": a side of 0 pixels");
    // Sides first: their product cannot then overflow 64 bits.
    if (w > max_image_side || h > max_image_side)
        throw scene_error(what + " is " + std::to_string(w) + "x" + std::to_string(h) + ", a side longer than the limit of " +
                          std::to_string(max_image_side) + " (2^24) pixels");
    if (w * h > limit)
        throw scene_error(what + " is " + std::to_string(w) + "x" + std::to_string(h) + " = " + std::to_string(w * h) +
                          " pixels, more than the limit of " + std::to_string(limit) + " (2^" +
                          std::to_string(log2_limit) + ") pixels" + limit_of);
}
} // namespace detail

// Throws unless a w x h image is within the limits above. `what` starts the message ("PNG image").
inline void check_image_size(uint64_t w, uint64_t h, const std::string& what) {
    detail::check_pixels(w, h, what, max_image_pixels, 28, "");
}

// Throws unless a w x h image may be rendered (max_render_pixels).
inline void check_render_size(uint64_t w, uint64_t h, const std::string& what) {
    detail::check_pixels(w, h, what, max_render_pixels, 26, " for a render");
}

} // namespace rt
