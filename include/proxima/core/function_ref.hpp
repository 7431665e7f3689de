#pragma once
/// @file function_ref.hpp
/// FunctionRef<R(Args...)>: a non-owning reference to a callable (an object pointer and a
/// function pointer; no allocation, one indirect call per invocation). It is the library's
/// type erasure for callbacks that only live for the duration of one call: the executor's
/// task body and AnyBroadPhase's query callbacks. The referenced callable must outlive the
/// FunctionRef, so it is meant for parameters only, never for storage: `FunctionRef f =
/// [](...) {...};` refers to a temporary that is gone after that statement.

#include <functional>
#include <memory>
#include <type_traits>
#include <utility>

namespace proxima {

template <class Signature>
class FunctionRef;

/// Non-owning reference to any callable invocable as R(Args...) (see the file comment).
template <class R, class... Args>
class FunctionRef<R(Args...)> {
 public:
  /// Refers to `f` (a lambda, a function object or a function pointer); `f` must outlive this.
  template <class F>
  requires(!std::is_same_v<std::remove_cvref_t<F>, FunctionRef> && std::is_object_v<std::remove_reference_t<F>> &&
           std::is_invocable_r_v<R, F&, Args...>) FunctionRef(F&& f)
  noexcept  // NOLINT(google-explicit-constructor): implicit like std::function
      : object_(const_cast<void*>(static_cast<const void*>(std::addressof(f)))),
        call_(&invoke<std::remove_reference_t<F>>) {}

  /// Calls the referenced callable.
  R operator()(Args... args) const { return call_(object_, std::forward<Args>(args)...); }

 private:
  template <class F>
  static R invoke(void* object, Args... args) {
    return std::invoke(*static_cast<F*>(object), std::forward<Args>(args)...);
  }

  void* object_;
  R (*call_)(void*, Args...);
};

}  // namespace proxima
