#pragma once

// The scene loaders report failures as messages: their Expected is the one of
// the support library with Failure as the error.

#include "support/expected.h"

namespace spire::scene {

using Error = Failure;

template <class T>
using Expected = spire::Expected<T, Failure>;

}  // namespace spire::scene
