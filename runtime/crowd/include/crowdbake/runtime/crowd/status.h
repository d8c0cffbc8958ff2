// Error reporting for the crowd behaviour and placement modules: crowdbake's one Status
// (base/status.h), whose message names the offending item ("state 'cheer' clip 'cheer_2':
// duration -1 s must be > 0"). Builders return a Status and leave their output untouched on
// error.
#pragma once

#include "crowdbake/base/status.h"

namespace crowdbake::crowd {

using crowdbake::Status;
using crowdbake::StatusCode;

}  // namespace crowdbake::crowd
