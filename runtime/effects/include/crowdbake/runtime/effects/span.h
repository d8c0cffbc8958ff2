// Span<T> (base/span.h) in the effects' namespace, for the effects jobs.
#pragma once

#include "crowdbake/base/span.h"

namespace crowdbake::effects {

using crowdbake::Span;

}  // namespace crowdbake::effects
