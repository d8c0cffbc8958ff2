// Status: how every crowdbake_runtime call that can fail reports it (base/status.h: the one
// Status type of every library that does not throw, the crowd and effect modules included).
//
// No function of the runtime's public API throws: failures come back as a Status with a code
// (for programs) and a message (for people: it names the file, the key or the chunk and the
// problem, e.g. "scene.json: lod.budget: must be at least 1, got 0"). Out-of-memory inside a
// loader is caught and reported as kOutOfMemory. Jobs (*_job.h) return bool instead: their
// only failures are caller mistakes that Validate() lists.
#pragma once

#include "crowdbake/base/status.h"

namespace crowdbake::runtime {

using crowdbake::Status;
using crowdbake::status_code_name;
using crowdbake::StatusCode;

}  // namespace crowdbake::runtime
