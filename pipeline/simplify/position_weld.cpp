#include "simplify/position_weld.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace crowdbake {
namespace {

constexpr uint32_t kNone = 0xffffffffu;
constexpr double kCellsPerRadius = 16.0;
constexpr double kGridLimit = 4.0e18;  // cell numbers stay inside int64

}  // namespace

size_t PositionWeld::CellHash::operator()(const Cell& c) const {
  return hash_words(static_cast<uint64_t>(c.x), static_cast<uint64_t>(c.y),
                    static_cast<uint64_t>(c.z));
}

PositionWeld::PositionWeld(double radius)
    : radius_(std::isfinite(radius) && radius > 0.0 ? radius : 0.0),
      cell_(kCellsPerRadius * radius_) {}

uint32_t PositionWeld::add(const glm::vec3& p) {
  const glm::dvec3 x(p);
  const glm::dvec3 q = cell_ > 0.0 ? x / cell_ : glm::dvec3(0.0);
  if (!(cell_ > 0.0) ||
      !(std::abs(q.x) < kGridLimit && std::abs(q.y) < kGridLimit && std::abs(q.z) < kGridLimit))
    return add_exact(p);
  const Cell home{static_cast<int64_t>(std::floor(q.x)), static_cast<int64_t>(std::floor(q.y)),
                  static_cast<int64_t>(std::floor(q.z))};
  // Per axis, the neighbouring cell whose face lies within radius (0: none).
  int side[3];
  for (int a = 0; a < 3; ++a) {
    const int64_t c = a == 0 ? home.x : a == 1 ? home.y : home.z;
    side[a] = x[a] - static_cast<double>(c) * cell_ <= radius_       ? -1
              : static_cast<double>(c + 1) * cell_ - x[a] <= radius_ ? 1
                                                                     : 0;
  }
  uint32_t best = kNone;
  for (int dx = 0; dx <= (side[0] != 0); ++dx)
    for (int dy = 0; dy <= (side[1] != 0); ++dy)
      for (int dz = 0; dz <= (side[2] != 0); ++dz) {
        const Cell c{home.x + dx * side[0], home.y + dy * side[1], home.z + dz * side[2]};
        const uint32_t* last = last_in_cell_.find(c);
        if (!last) continue;
        for (uint32_t k = *last; k != kNone; k = previous_in_cell_[k]) {
          const glm::dvec3 d = glm::abs(where_[k] - x);
          if (d.x <= radius_ && d.y <= radius_ && d.z <= radius_) best = std::min(best, k);
        }
      }
  if (best != kNone) return best;
  const uint32_t id = count_++;
  auto [last, fresh] = last_in_cell_.emplace(home, id);
  previous_in_cell_.push_back(fresh ? kNone : *last);
  *last = id;
  where_.push_back(x);
  return id;
}

uint32_t PositionWeld::add_exact(glm::vec3 p) {
  for (int a = 0; a < 3; ++a)
    if (p[a] == 0.0f) p[a] = 0.0f;
  uint32_t b[3];
  std::memcpy(b, &p, sizeof(b));
  const Cell key{b[0], b[1], b[2]};
  const auto [id, fresh] = exact_.emplace(key, count_);
  if (!fresh) return *id;
  previous_in_cell_.push_back(kNone);
  where_.push_back(glm::dvec3(p));
  return count_++;
}

double weld_radius(const glm::dvec3& lo, const glm::dvec3& hi) {
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  return std::isfinite(extent) && extent > 0.0 ? kWeldTolerance * extent : 0.0;
}

}  // namespace crowdbake
