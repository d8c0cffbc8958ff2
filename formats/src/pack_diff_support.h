// What the section comparisons of diff_packs (pack_diff.h) share: the tolerance rules, the
// figures' formatting and the sections kept in their own files. Internal to formats.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "crowdbake/formats/pack_diff.h"

namespace crowdbake::diff {

using nlohmann::ordered_json;

// How values compare: lengths relative to D, everything else absolute.
struct Compare {
  double tolerance = 0.0;
  double diagonal = 1.0;
  bool length_beyond(double d) const { return d / diagonal > tolerance; }
  bool beyond(double d) const { return d > tolerance; }
};

// The largest difference seen and where.
struct MaxDiff {
  double value = 0.0;
  int64_t at = -1;
  void add(double d, int64_t where) {
    if (d > value) value = d, at = where;
  }
};

inline std::string num(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.3g", v);
  return s;
}

inline std::string quoted(const std::string& s) { return "\"" + s + "\""; }

template <typename T>
std::string arrow(const T& a, const T& b) {
  if constexpr (std::is_same_v<T, std::string>)
    return quoted(a) + " -> " + quoted(b);
  else
    return std::to_string(a) + " -> " + std::to_string(b);
}

// note: enough digits that two different floats never print alike.
inline std::string arrow_num(double a, double b) {
  char s[64];
  std::snprintf(s, sizeof s, "%.9g -> %.9g", a, b);
  return s;
}

inline DiffSection section(const char* name) {
  DiffSection s;
  s.name = name;
  return s;
}

inline void differ(DiffSection& s, std::string line) {
  s.differs = true;
  s.differences.push_back(std::move(line));
}

// First index where two arrays differ over their common length; -1 when that prefix is
// equal (check the lengths separately).
template <typename T>
int64_t first_difference(const std::vector<T>& a, const std::vector<T>& b) {
  const size_t n = std::min(a.size(), b.size());
  for (size_t i = 0; i < n; ++i)
    if (a[i] != b[i]) return static_cast<int64_t>(i);
  return -1;
}

// Max |a - b| of the 3x3 part (entries 0-2, 4-6, 8-10) and of the translation (3, 7, 11).
inline void matrix_diff(const float* a, const float* b, double& linear, double& translation) {
  linear = translation = 0.0;
  for (int k = 0; k < 12; ++k) {
    const double d = std::abs(double{a[k]} - double{b[k]});
    double& slot = k % 4 == 3 ? translation : linear;
    slot = std::max(slot, d);
  }
}

// Geometry and progressive arrays (pack_diff_geometry.cpp).
DiffSection diff_geometry(const PackContents& pa, const PackContents& pb, const Compare& cmp);
DiffSection diff_progressive(const PackContents& a, const PackContents& b);

}  // namespace crowdbake::diff
