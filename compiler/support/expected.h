// A value or an error, for code that reports failures as values rather than
// exceptions or aborts (GCC 12 has no std::expected). Each layer names its own
// error type: the Vulkan layer a VkError that carries the VkResult, the engine
// an error with a scene-file range, the compiler a CompileError with its
// diagnostics. Layers whose failures are a message for a person and nothing
// more (file I/O, the scene loaders, the tuner's files) use Failure.
#pragma once

#include <string>
#include <utility>
#include <variant>

namespace spire {

// A failure that is only a message. Wrapping it keeps Expected<std::string,
// Failure> unambiguous.
struct Failure {
  std::string message;
};

template <class T, class E>
class [[nodiscard]] Expected {
 public:
  Expected(T value) : state_(std::in_place_index<0>, std::move(value)) {}  // NOLINT(google-explicit-constructor)
  Expected(E error) : state_(std::in_place_index<1>, std::move(error)) {}  // NOLINT(google-explicit-constructor)

  bool ok() const { return state_.index() == 0; }
  explicit operator bool() const { return ok(); }

  // Accessing the wrong alternative is a programming error and throws
  // std::bad_variant_access.
  T& value() & { return std::get<0>(state_); }
  const T& value() const& { return std::get<0>(state_); }
  T&& value() && { return std::get<0>(std::move(state_)); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }
  const E& error() const { return std::get<1>(state_); }

 private:
  std::variant<T, E> state_;
};

// Success or an error, for operations without a result value.
template <class E>
class [[nodiscard]] Expected<void, E> {
 public:
  Expected() = default;
  Expected(E error) : error_(std::move(error)), ok_(false) {}  // NOLINT(google-explicit-constructor)

  bool ok() const { return ok_; }
  explicit operator bool() const { return ok_; }
  const E& error() const { return error_; }

 private:
  E error_{};
  bool ok_ = true;
};

}  // namespace spire
