// Errors of the engine layer: a message, and where known the scene-file
// range it is about, so the demo renders it like a compiler diagnostic.
#pragma once

#include <string>
#include <utility>

#include "support/expected.h"
#include "support/source_manager.h"
#include "vk/result.h"

namespace spire::engine {

struct Error {
  Error(std::string text = {}, SourceRange where = {}, std::string extra = {})  // NOLINT(google-explicit-constructor)
      : message(std::move(text)), range(where), details(std::move(extra)) {}
  // The scene loaders' and the file writers' failures are messages only.
  Error(const Failure& failure) : message(failure.message) {}  // NOLINT(google-explicit-constructor)

  std::string message;
  SourceRange range;    // invalid when the error is not about a scene-file value
  std::string details;  // already-rendered text shown after the message (compiler diagnostics)

  static Error fromVk(const vk::VkError& error) { return Error(error.message()); }
};

template <class T>
using Expected = spire::Expected<T, Error>;

}  // namespace spire::engine
