#pragma once
// classify: which of the books' classes an object of the world is, by its exact class (a user's
// subclass of a built-in class is none of them: it renders through its virtual functions). The
// scene compiler (scene_compiler.h), the material compiler (material_compiler.h) and the texture
// table (texture_table.h) each ask it once per object and dispatch on the answer; the lists below
// are the only place that names the classes they compile, and a class added to a list without a
// compile rule of its own does not compile.
//
//   visit_book_class<book_hittables>(object, [&](const auto& exact) { ... },   // one of the list
//                                            [&](const hittable& other) { ... }); // none of them

#include "../bvh.h"
#include "../constant_medium.h"
#include "../core/kind_list.h"
#include "../core/recognise.h"
#include "../hittable.h"
#include "../hittable_list.h"
#include "../material.h"
#include "../mesh.h"
#include "../quad.h"
#include "../sphere.h"
#include "../transform.h"
#include "../texture.h"
#include "../triangle.h"
#include "../whitted_material.h"

#include <cstddef>

namespace rt {

// The hittables the scene compiler lays out itself: containers and transforms it walks through,
// and the shapes it compiles into shape kinds (scene/shapes/). Anything else is a user shape.
using book_hittables = kind_list<hittable_list, bvh_node, translate, rotate_y, transform, rotate, scale, moving, sphere,
                                 triangle, triangle_mesh, quad, constant_medium>;

// The materials the material compiler compiles into material kinds (material_compiler.h); anything
// else is a user material, rendered through its virtual scatter().
using book_materials = kind_list<lambertian, metal, dielectric, conductor, diffuse_light, isotropic, plastic, blinn_phong,
                                 whitted_material, rough_conductor, rough_dielectric, metal_roughness>;

// The textures the texture table compiles into texture kinds (texture_table.h); anything else is a
// user texture, whose value() is asked per hit.
using book_textures = kind_list<solid_color, checker_texture, image_texture, noise_texture>;

// Calls known(exact) with the object as the class of List it exactly is, or other(object) for
// none of them, and returns what it returns.
template <class List, class Base, class Known, class Other>
decltype(auto) visit_book_class(const Base& object, Known&& known, Other&& other) {
    const size_t i = exact_kind<List>(object);
    if (i == List::size) return other(object);
    return visit_kind<List>(i, [&](auto k) -> decltype(auto) {
        return known(static_cast<const typename decltype(k)::type&>(object));
    });
}

} // namespace rt
