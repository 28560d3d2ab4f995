#pragma once
// Room for up to N objects of type T, built in place one after another and destroyed together:
// the hot loop's per-batch paths and samplers, and a hit's material when it has to be built.
//
//   in_place_array<camera_path, 16> paths;
//   camera_path& p = paths.emplace_back(...);
//
// std::optional<T>[N] would do the same job, but g++ 12 zero-fills an optional's whole storage
// when it is declared: 7.5 KB for a batch's sixteen paths and 120 bytes for every unused material
// of a bounce, some 4 % of the cover scene's instructions (callgrind). The room left unused here
// is never written.

#include <cstddef>
#include <new>
#include <utility>

namespace rt {

template <class T, int N>
class in_place_array {
  public:
    in_place_array() {} // storage_ is left as it is: that is the point
    in_place_array(const in_place_array&) = delete;
    in_place_array& operator=(const in_place_array&) = delete;
    ~in_place_array() {
        for (int i = size_; i > 0; --i) (*this)[i - 1].~T();
    }

    // Builds the next object (there must be room: size() < N) and returns it.
    template <class... Args>
    T& emplace_back(Args&&... args) {
        T* made = ::new (static_cast<void*>(storage_ + size_ * sizeof(T))) T(std::forward<Args>(args)...);
        ++size_;
        return *made;
    }
    T& operator[](int i) { return *std::launder(reinterpret_cast<T*>(storage_ + i * sizeof(T))); }
    const T& operator[](int i) const { return *std::launder(reinterpret_cast<const T*>(storage_ + i * sizeof(T))); }
    int size() const { return size_; }

  private:
    int size_ = 0; // first: an empty array's one written word shares the line of what precedes it
    alignas(T) unsigned char storage_[N * sizeof(T)];
};

} // namespace rt
