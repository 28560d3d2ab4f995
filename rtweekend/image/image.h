#pragma once
// image: a framebuffer of linear radiance, three floats per pixel, rows top to bottom. Renders
// produce one; image/image_write.h turns it into files (gamma and 8-bit quantisation happen only
// there), image/image_read.h reads files back into one.

#include "../color.h"

#include <cstddef>
#include <vector>

namespace rt {

class image {
  public:
    image() = default;
    image(int width, int height) : width_(width), height_(height), rgb_(size_t(width) * size_t(height) * 3, 0.0f) {}

    int width() const { return width_; }
    int height() const { return height_; }
    bool empty() const { return width_ <= 0 || height_ <= 0; }

    // Linear radiance of pixel (x, y); row 0 is the top of the picture.
    color pixel(int x, int y) const {
        const float* p = &rgb_[index(x, y)];
        return color(p[0], p[1], p[2]);
    }
    void set_pixel(int x, int y, const color& c) {
        float* p = &rgb_[index(x, y)];
        p[0] = static_cast<float>(c.x());
        p[1] = static_cast<float>(c.y());
        p[2] = static_cast<float>(c.z());
    }

    // Interleaved RGB floats, rows top to bottom.
    const std::vector<float>& data() const { return rgb_; }
    std::vector<float>& data() { return rgb_; }

  private:
    size_t index(int x, int y) const { return (size_t(y) * size_t(width_) + size_t(x)) * 3; }

    int width_ = 0, height_ = 0;
    std::vector<float> rgb_;
};

} // namespace rt
