#pragma once
// The one place that recognises the books' objects by their exact class: which of a list of
// classes an object is, a subclass of one of them being none of them. A user's subclass of a
// built-in class (a sphere whose hit() is their own, a lambertian whose scatter() is) must reach
// the renderer through its virtual functions, so an object is taken for a built-in class only
// when its dynamic type is exactly that class. The scene compiler asks it of hittables,
// materials and textures (scene/classify.h holds the lists of the classes it knows).
//
//   exact_kind<kind_list<sphere, quad>>(object)    0 for a sphere, 1 for a quad, 2 for anything else
//   is_exactly<solid_color>(texture)               whether texture is a solid_color, not a subclass

#include "kind_list.h"

#include <cstddef>
#include <typeinfo>

namespace rt {

namespace detail {
template <class... Kinds>
size_t exact_kind_of(const std::type_info& type, kind_list<Kinds...>) {
    const std::type_info* const kinds[] = {&typeid(Kinds)...};
    for (size_t i = 0; i < sizeof...(Kinds); ++i)
        if (type == *kinds[i]) return i;
    return sizeof...(Kinds);
}
} // namespace detail

// The number in List of the class `object` is exactly, or List::size for none of them.
template <class List, class Base>
size_t exact_kind(const Base& object) {
    return detail::exact_kind_of(typeid(object), List{});
}

template <class Class, class Base>
bool is_exactly(const Base& object) {
    return exact_kind<kind_list<Class>>(object) == 0;
}

} // namespace rt
