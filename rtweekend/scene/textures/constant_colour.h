#pragma once
// constant_colour: a texture kind (scene/texture_table.h says what a kind answers): one colour
// everywhere, the books' solid_color.

#include "../../core/vec3f.h"
#include "../../texture.h"
#include "../../vec3.h"

namespace rt {

struct constant_colour {
    static constexpr const char* name = "solid colour";
    vec3f value;

    template <class Table>
    static constant_colour compile(const solid_color& c, Table&) { return {vec3f(c.albedo())}; }
    template <class Table>
    vec3f eval(const Table&, float, float, const vec3&) const { return value; }
    template <class Table>
    float average(const Table&) const { return (value.x + value.y + value.z) / 3; }
    template <class Table>
    bool reads_uv(const Table&) const { return false; }
    static constexpr bool calls_user_code = false;
};

} // namespace rt
