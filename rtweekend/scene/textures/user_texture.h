#pragma once
// user_texture: a texture kind (scene/texture_table.h): any other texture class, a user's own,
// called through its virtual value() in double. It may call random_double(): a scene with one
// calls user code (compiled_scene::calls_user_code).

#include "../../core/vec3f.h"
#include "../../texture.h"
#include "../../vec3.h"

namespace rt {

struct user_texture {
    static constexpr const char* name = "user texture";
    const texture* tex = nullptr; // owned by the world, like the materials

    template <class Table>
    vec3f eval(const Table&, float u, float v, const vec3& p) const { return vec3f(tex->value(u, v, p)); }
    // Unknown: as a white light would be.
    template <class Table>
    float average(const Table&) const { return 1.0f; }
    template <class Table>
    bool reads_uv(const Table&) const { return true; }
    static constexpr bool calls_user_code = true;
};

} // namespace rt
