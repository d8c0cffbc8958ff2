// How the crowd module's messages show names and numbers: 'name' in quotes, numbers with the
// stream's default precision (shortest readable form).
#pragma once

#include <sstream>
#include <string>

namespace crowdbake::crowd::detail {

inline std::string quote(const std::string& s) { return "'" + s + "'"; }

inline std::string format_number(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

}  // namespace crowdbake::crowd::detail
