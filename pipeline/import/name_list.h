// Names in a warning: the first five quoted, then how many more.
#pragma once

#include <string>
#include <vector>

namespace crowdbake {

inline std::string name_list(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size() && i < 5; ++i) out += (i ? ", '" : "'") + names[i] + "'";
  if (names.size() > 5) out += " and " + std::to_string(names.size() - 5) + " more";
  return out;
}

}  // namespace crowdbake
