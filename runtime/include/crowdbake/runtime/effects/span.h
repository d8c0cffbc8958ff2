// Span<T> for the effects jobs: the runtime's header-only span (no link dependency on
// crowdbake_runtime), named in this namespace so effects code reads as before.
#pragma once

#include "crowdbake/runtime/span.h"

namespace crowdbake::effects {

using runtime::Span;

}  // namespace crowdbake::effects
