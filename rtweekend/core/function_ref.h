#pragma once
// function_ref<R(Args...)>: a reference to any callable, called through one indirect call, for
// code that should be compiled once rather than once per caller's lambda (the scheduler takes the
// integrators' sample functions so: render/scheduler.h). It does not own what it refers to, which
// must outlive it.

#include <type_traits>
#include <utility>

namespace rt {

template <class Signature>
class function_ref;

template <class R, class... Args>
class function_ref<R(Args...)> {
  public:
    template <class F, class = std::enable_if_t<!std::is_same_v<std::decay_t<F>, function_ref> &&
                                                std::is_invocable_r_v<R, F&, Args...>>>
    function_ref(F&& f) // NOLINT: implicit, as a parameter type
        : object_(const_cast<void*>(static_cast<const void*>(&f))), call_([](void* o, Args... args) -> R {
              return (*static_cast<std::remove_reference_t<F>*>(o))(std::forward<Args>(args)...);
          }) {}

    R operator()(Args... args) const { return call_(object_, std::forward<Args>(args)...); }

  private:
    void* object_;
    R (*call_)(void*, Args...);
};

} // namespace rt
