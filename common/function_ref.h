// A non-owning reference to something callable with a given signature (C++26's std::function_ref,
// which GCC 12 lacks): two pointers, no allocation, one indirect call. It lets a task be an
// ordinary function in a .cpp file while its caller passes a lambda: the BVH's traversal calls the
// aggregate's primitive test through it. The callable must outlive the reference, as an argument
// does for the call it is passed to.
#pragma once

#include <memory>
#include <type_traits>
#include <utility>

namespace rt {

template <class Signature>
class FunctionRef;

template <class Result, class... Args>
class FunctionRef<Result(Args...)> {
 public:
  template <class Callable>
    requires(!std::is_same_v<std::remove_cvref_t<Callable>, FunctionRef> &&
             std::is_invocable_r_v<Result, Callable&, Args...>)
  FunctionRef(Callable&& callable)  // NOLINT: implicit, like std::function_ref
      : object_(const_cast<void*>(static_cast<const void*>(std::addressof(callable)))),
        call_([](void* object, Args... args) -> Result {
          return (*static_cast<std::remove_reference_t<Callable>*>(object))(std::forward<Args>(args)...);
        }) {}

  Result operator()(Args... args) const { return call_(object_, std::forward<Args>(args)...); }

 private:
  void* object_;
  Result (*call_)(void*, Args...);
};

}  // namespace rt
