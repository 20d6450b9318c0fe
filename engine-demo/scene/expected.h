#pragma once

// Errors as values for the scene library. GCC 12 has no std::expected, so this
// is the minimal subset the loaders need: a value or an error message.

#include <optional>
#include <string>
#include <utility>
#include <variant>

namespace spire::scene {

// Wrapping the message in its own type keeps Expected<std::string> unambiguous.
struct Error {
  std::string message;
};

template <typename T>
class Expected {
public:
  Expected(T value) : state_(std::in_place_index<0>, std::move(value)) {}
  Expected(Error error) : state_(std::in_place_index<1>, std::move(error)) {}

  [[nodiscard]] bool hasValue() const { return state_.index() == 0; }
  explicit operator bool() const { return hasValue(); }

  // Accessing the wrong alternative throws std::bad_variant_access.
  [[nodiscard]] T& value() & { return std::get<0>(state_); }
  [[nodiscard]] const T& value() const& { return std::get<0>(state_); }
  [[nodiscard]] T&& value() && { return std::get<0>(std::move(state_)); }
  [[nodiscard]] const std::string& error() const { return std::get<1>(state_).message; }

  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }

private:
  std::variant<T, Error> state_;
};

// Success carries nothing; failure carries the message.
template <>
class Expected<void> {
public:
  Expected() = default;
  Expected(Error error) : error_(std::move(error)) {}

  [[nodiscard]] bool hasValue() const { return !error_.has_value(); }
  explicit operator bool() const { return hasValue(); }
  [[nodiscard]] const std::string& error() const { return error_.value().message; }

private:
  std::optional<Error> error_;
};

}  // namespace spire::scene
