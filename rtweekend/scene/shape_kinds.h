#pragma once
// The shape kinds: what a BVH leaf of the compiled scene can hold. Each kind is one header of
// scene/shapes/ and one entry in shape_kinds below; the compiled scene holds one set of each
// (compiled_scene.h), and every dispatch over shapes (the leaf kernels, hit completion, texture
// coordinates, light finding, culling, memory) is generated from this list.
//
// A kind K answers, in its header:
//   compiling
//     K::name                         for messages and tests
//     K::input                        one shape as the compiler collects it, before the BVH
//     K::add(compiler, book_object, xf)   (for the books' classes it compiles; see classify.h)
//     K::bounds(input, scene)         its box for the BVH, rounded outwards
//     k.lay_out(scene, inputs, order) the compiled shapes, in the BVH's leaf order, padded for
//                                     the kernel's SIMD loads
//     K::split_by_planes, K::corners  (optional) the BVH may split its shapes by planes (bvh.h)
//   tracing
//     K::ray_state                    what a ray's walk keeps for the kind (often nothing)
//     k.intersect_leaf<Q, Self>(scene, ray, first, n, t_best, best, state)
//                                     the leaf kernel (leaf_query.h says what it reports)
//     k.intersect_leaf_packet<Self>(rays, first, n, lanes, t_best, best)
//                                     (optional) one leaf for a packet of rays, one per lane
//     k.complete_hit(scene, ray, t, i, state, hit)   the surface_hit of shape i
//     k.surface_coordinates(hit, u, v)               the books' (u, v) at a hit
//   the rest of the engine
//     k.size()                        shapes laid out (padding not counted)
//     K::light_sampled, k.light_of(i) whether its emitters are light-sampled, and as which light
//                                     kind (scene/light_kinds.h)
//     k.bound_where(scene, selected, box)   grows box by the shapes whose material is selected
//     k.mark_culled(cullable)         back-face culling by material
//     k.bytes()                       memory held
//     K::own_walk                     whether a scene of this kind alone gets a walk of its own
//
// The order is the kinds' numbers (shape_id), which a leaf reference stores (bvh.h) and which
// break ties between hits at the same distance (leaf_query.h: beats).

#include "../core/kind_list.h"
#include "leaf_query.h"
#include "shapes/instance_set.h"
#include "shapes/moving_sphere_set.h"
#include "shapes/quad_set.h"
#include "shapes/sphere_set.h"
#include "shapes/triangle_set.h"
#include "shapes/user_shape_set.h"

#include <cstdint>
#include <tuple>
#include <type_traits>

namespace rt {

using shape_kinds = kind_list<sphere_set, triangle_set, quad_set, user_shape_set, moving_sphere_set, instance_set>;
inline constexpr int shape_kind_count = int(shape_kinds::size);

// The number of shape kind K.
template <class K>
inline constexpr shape_kind shape_id = shape_kind(kind_index<K, shape_kinds>);

// Calls f(kind_tag<K>{}) for the shape kind K numbered `kind`.
template <class F>
RTWEEKEND_FORCE_INLINE decltype(auto) with_shape_kind(shape_kind kind, F&& f) {
    return visit_kind<shape_kinds>(size_t(kind), f);
}

// What a ray's walk keeps, for every kind: leaf_state's element K is K::ray_state.
namespace detail {
template <class List>
struct ray_states;
template <class... Kinds>
struct ray_states<kind_list<Kinds...>> {
    using type = std::tuple<typename Kinds::ray_state...>;
};
} // namespace detail
using leaf_state = typename detail::ray_states<shape_kinds>::type;
template <class K>
typename K::ray_state& state_of(leaf_state& s) { return std::get<kind_index<K, shape_kinds>>(s); }
template <class K>
const typename K::ray_state& state_of(const leaf_state& s) { return std::get<kind_index<K, shape_kinds>>(s); }

// The kinds whose scenes are often of them alone (the books' spheres, a mesh's triangles, a box of
// quads): when every shape of a scene is of one of them, the walk calls its kernel without asking
// each leaf its kind (K::own_walk). Each costs a walk of its own to compile, so the rare ones share
// the mixed walk.
template <class K>
struct has_own_walk : std::bool_constant<K::own_walk> {};
using own_walk_kinds = kinds_where<has_own_walk, shape_kinds>;

// Whether kind K has a packet kernel, and whether the BVH may split its shapes.
template <class K, class = void>
struct has_packet_kernel : std::false_type {};
template <class K>
struct has_packet_kernel<K, std::void_t<decltype(&K::template intersect_leaf_packet<shape_kind{}>)>> : std::true_type {};
template <class K, class = void>
struct splits_by_planes : std::false_type {};
template <class K>
struct splits_by_planes<K, std::void_t<decltype(K::split_by_planes)>> : std::bool_constant<K::split_by_planes> {};

} // namespace rt
