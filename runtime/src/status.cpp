#include "crowdbake/runtime/status.h"

namespace crowdbake::runtime {

const char* status_code_name(StatusCode code) {
  switch (code) {
    case StatusCode::kOk:
      return "ok";
    case StatusCode::kIoError:
      return "io error";
    case StatusCode::kInvalidPack:
      return "invalid pack";
    case StatusCode::kInvalidScene:
      return "invalid scene";
    case StatusCode::kInvalidArgument:
      return "invalid argument";
    case StatusCode::kNotLoaded:
      return "not loaded";
    case StatusCode::kOutOfMemory:
      return "out of memory";
  }
  return "unknown";
}

}  // namespace crowdbake::runtime
