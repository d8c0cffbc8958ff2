// Span<T> (base/span.h) in the runtime's namespace: jobs take their inputs and outputs as spans
// so they never own or allocate memory.
#pragma once

#include "crowdbake/base/span.h"

namespace crowdbake::runtime {

using crowdbake::Span;

}  // namespace crowdbake::runtime
