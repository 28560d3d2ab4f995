#pragma once
// texture: a colour that varies over a surface (book 2), looked up by the hit's surface
// coordinates (u, v) and its point p. solid_color is the constant one, what lambertian(color)
// and diffuse_light(color) wrap.
//
//   auto tex = make_shared<solid_color>(0.2, 0.3, 0.1);
//   auto mat = make_shared<lambertian>(tex);
//
// The renderer recognises a material whose texture is exactly a solid_color (exact_solid_color)
// and renders it without virtual calls; any other texture is looked up through value().

#include "color.h"
#include "vec3.h"

#include <typeinfo>

namespace rt {

class texture {
  public:
    virtual ~texture() = default;

    virtual color value(double u, double v, const point3& p) const = 0;
};

class solid_color : public texture {
  public:
    solid_color(const color& albedo) : albedo_(albedo) {}
    solid_color(double red, double green, double blue) : solid_color(color(red, green, blue)) {}

    color value(double /*u*/, double /*v*/, const point3& /*p*/) const override { return albedo_; }

    const color& albedo() const { return albedo_; }

  private:
    color albedo_;
};

// The texture as a solid_color if it is exactly one (not a subclass, which may override
// value()), else null: a material whose texture is one is rendered from its constant colour.
inline const solid_color* exact_solid_color(const texture* tex) {
    // dynamic_cast rather than a static_cast behind the typeid test: g++ 12 inlines the cast into
    // callers holding another texture and warns (-Warray-bounds) about the branch never taken.
    auto* solid = dynamic_cast<const solid_color*>(tex);
    return solid && typeid(*tex) == typeid(solid_color) ? solid : nullptr;
}

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::solid_color;
using rt::texture;
#endif
