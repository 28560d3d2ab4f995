#pragma once
// kind_list: a closed family of kinds named once, at compile time, from which every dispatch over
// the family is generated (in the spirit of pbrt-v4's tagged type lists). Each family of the
// renderer has one list: the shapes a BVH leaf holds (scene/shape_kinds.h), the materials of the
// contract (core/material_kinds.h), the lights (scene/light_kinds.h) and the textures
// (scene/texture_kinds.h). A kind is a type; its number is its place in the list.
//
//   using shapes = kind_list<sphere_set, triangle_set, quad_set>;
//   kind_index<quad_set, shapes>                  2
//   kind_at<2, shapes>                            quad_set
//   for_each_kind<shapes>([&](auto k) { using K = typename decltype(k)::type; ... });
//   visit_kind<shapes>(i, [&](auto k) { ... });   f for the kind numbered i (i < size), by a switch
//   kind_variant<shapes>                          std::variant of the kinds
//
// A dispatch generated here asks every kind of the list for what it needs: a kind that lacks a
// piece does not compile, where a hand-written switch would fall through to a default. A family
// may hold up to max_kinds kinds.

#include "force_inline.h"

#include <cstddef>
#include <cstdint>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>

namespace rt {

template <class... Kinds>
struct kind_list {
    static constexpr size_t size = sizeof...(Kinds);
};

// Names a kind as a value, for generic lambdas: typename decltype(tag)::type is the kind.
template <class Kind>
struct kind_tag {
    using type = Kind;
};

// The most kinds a family may have (visit_kind's switch has this many cases).
inline constexpr size_t max_kinds = 16;

namespace detail {
template <class Kind, class List>
struct kind_index_of;
template <class Kind, class... Kinds>
struct kind_index_of<Kind, kind_list<Kinds...>> {
    static constexpr size_t find() {
        constexpr bool matches[] = {std::is_same_v<Kind, Kinds>...};
        for (size_t i = 0; i < sizeof...(Kinds); ++i)
            if (matches[i]) return i;
        return sizeof...(Kinds);
    }
    static constexpr size_t value = find();
    static_assert(value < sizeof...(Kinds), "the kind is not in the list");
};

template <size_t I, class List>
struct kind_at_index;
template <size_t I, class... Kinds>
struct kind_at_index<I, kind_list<Kinds...>> {
    using type = std::tuple_element_t<I, std::tuple<Kinds...>>;
};

template <class List>
struct variant_of;
template <class... Kinds>
struct variant_of<kind_list<Kinds...>> {
    using type = std::variant<Kinds...>;
};

template <class List>
struct tuple_of;
template <class... Kinds>
struct tuple_of<kind_list<Kinds...>> {
    using type = std::tuple<Kinds...>;
};
} // namespace detail

namespace detail {
template <class A, class B>
struct concat_kinds;
template <class... As, class... Bs>
struct concat_kinds<kind_list<As...>, kind_list<Bs...>> {
    using type = kind_list<As..., Bs...>;
};
template <template <class> class Pred, class List>
struct filter_kinds;
template <template <class> class Pred>
struct filter_kinds<Pred, kind_list<>> {
    using type = kind_list<>;
};
template <template <class> class Pred, class K, class... Ks>
struct filter_kinds<Pred, kind_list<K, Ks...>> {
    using rest = typename filter_kinds<Pred, kind_list<Ks...>>::type;
    using type = std::conditional_t<Pred<K>::value, typename concat_kinds<kind_list<K>, rest>::type, rest>;
};
} // namespace detail

// The kinds K of List for which Pred<K>::value is true, in order.
template <template <class> class Pred, class List>
using kinds_where = typename detail::filter_kinds<Pred, List>::type;

// The number of Kind in List (a compile error when it is not there).
template <class Kind, class List>
inline constexpr uint8_t kind_index = uint8_t(detail::kind_index_of<Kind, List>::value);

// The kind numbered I in List.
template <size_t I, class List>
using kind_at = typename detail::kind_at_index<I, List>::type;

// One value of each kind, or one of the kinds.
template <class List>
using kind_tuple = typename detail::tuple_of<List>::type;
template <class List>
using kind_variant = typename detail::variant_of<List>::type;

namespace detail {
template <class List, class F, size_t... I>
void for_each_kind_in(F& f, std::index_sequence<I...>) {
    (f(kind_tag<kind_at<I, List>>{}), ...);
}
} // namespace detail

// Calls f(kind_tag<K>{}) for every kind K of List, in order.
template <class List, class F>
void for_each_kind(F&& f) {
    detail::for_each_kind_in<List>(f, std::make_index_sequence<List::size>{});
}

// Calls f(kind_tag<K>{}) for the kind K numbered `index` (which must be below List::size) and
// returns what it returns: a switch, which the compiler makes a jump table or a few compares, and
// within which f is inlined for each kind.
template <class List, class F>
RTWEEKEND_FORCE_INLINE decltype(auto) visit_kind(size_t index, F&& f) {
    static_assert(List::size >= 1 && List::size <= max_kinds, "a family holds 1 to max_kinds kinds");
#define RTWEEKEND_KIND_CASE(i)                                                                                          \
    case i:                                                                                                             \
        if constexpr (i < List::size) return f(kind_tag<kind_at<i, List>>{});                                          \
        break;
    switch (index) {
        RTWEEKEND_KIND_CASE(0)
        RTWEEKEND_KIND_CASE(1)
        RTWEEKEND_KIND_CASE(2)
        RTWEEKEND_KIND_CASE(3)
        RTWEEKEND_KIND_CASE(4)
        RTWEEKEND_KIND_CASE(5)
        RTWEEKEND_KIND_CASE(6)
        RTWEEKEND_KIND_CASE(7)
        RTWEEKEND_KIND_CASE(8)
        RTWEEKEND_KIND_CASE(9)
        RTWEEKEND_KIND_CASE(10)
        RTWEEKEND_KIND_CASE(11)
        RTWEEKEND_KIND_CASE(12)
        RTWEEKEND_KIND_CASE(13)
        RTWEEKEND_KIND_CASE(14)
        RTWEEKEND_KIND_CASE(15)
    default: break;
    }
#undef RTWEEKEND_KIND_CASE
    // Not reached for an index below List::size: the last kind, so that every path returns.
    return f(kind_tag<kind_at<List::size - 1, List>>{});
}

// visit_kind over the kind a variant of List holds, with that kind's value: f(value), value a
// reference to the held kind (const when the variant is).
template <class List, class Variant, class F>
RTWEEKEND_FORCE_INLINE decltype(auto) visit_value(Variant&& v, F&& f) {
    return visit_kind<List>(v.index(), [&](auto k) -> decltype(auto) {
        using K = typename decltype(k)::type;
        return f(*std::get_if<K>(&v));
    });
}

} // namespace rt
