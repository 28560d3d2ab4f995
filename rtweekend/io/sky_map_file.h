#pragma once
// load_sky_map(path, scale): an environment map (render/environment_map.h) read from a picture
// file, for camera::sky_map: the text scene's `sky_map FILE [scale]` line and render's --sky-map.
//
//   cam.sky_map = rt::load_sky_map("studio.hdr", 1.0);   // throws scene_error naming the file
//
// Any picture image_read.h reads. High-dynamic-range files (EXR, Radiance HDR, PFM) hold radiance
// as it is; an 8-bit picture (PNG, JPEG, BMP, PPM) is sRGB-encoded and decoded to linear values
// in [0, 1], as textures are. The course's environment lights read their 8-bit codes as they are
// (0 to 255) instead: render's xml_path_environment builds those maps itself.

#include "../core/scene_error.h"
#include "../image/image_read.h"
#include "../render/environment_map.h"
#include "../rtw_stb_image.h"

#include <memory>
#include <string>

namespace rt {

inline std::shared_ptr<const environment_map> load_sky_map(const std::string& path, double scale) {
    loaded_image file = read_image(path);
    if (file.display_encoded) {
        for (float& v : file.pixels.data()) v = static_cast<float>(srgb_to_linear(v / 255.0));
    }
    try {
        return std::make_shared<const environment_map>(file.pixels, static_cast<float>(scale));
    } catch (const scene_error& e) {
        throw scene_error(path + ": " + e.what());
    }
}

} // namespace rt
