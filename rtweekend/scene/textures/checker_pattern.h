#pragma once
// checker_pattern: a texture kind (scene/texture_table.h): book 2's 3-D checker, cells of size
// 1 / inv_scale alternating between two textures of the table (its children, compiled first).

#include "../../core/vec3f.h"
#include "../../texture.h"
#include "../../vec3.h"

#include <cstdint>

namespace rt {

struct checker_pattern {
    static constexpr const char* name = "checker";
    uint32_t even = 0, odd = 0; // the children's entries in the table
    double inv_scale = 1;

    template <class Table>
    static checker_pattern compile(const checker_texture& c, Table& table) {
        checker_pattern k;
        k.inv_scale = c.inv_scale();
        k.even = table.add(*c.even()); // children first: a checker's entry follows its children's
        k.odd = table.add(*c.odd());
        return k;
    }
    template <class Table>
    vec3f eval(const Table& table, float u, float v, const vec3& p) const {
        return table.eval(checker_texture::is_even(inv_scale, p) ? even : odd, u, v, p);
    }
    // Over a surface large against the cells, half is even and half odd.
    template <class Table>
    float average(const Table& table) const { return 0.5f * (table.average(even) + table.average(odd)); }
    template <class Table>
    bool reads_uv(const Table& table) const { return table.reads_uv(even) || table.reads_uv(odd); }
    static constexpr bool calls_user_code = false;
};

} // namespace rt
