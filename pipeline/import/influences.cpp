#include "import/influences.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace crowdbake {

void reduce_influences(std::vector<Influence>& influences, int fallback_joint,
                       std::array<uint16_t, 4>& joints, std::array<float, 4>& weights,
                       ImportStats& stats) {
  // Merge duplicates of one joint first: some exporters list a joint twice.
  std::sort(influences.begin(), influences.end(),
            [](const Influence& a, const Influence& b) { return a.joint < b.joint; });
  size_t unique = 0;
  for (size_t i = 0; i < influences.size(); ++i) {
    const Influence& in = influences[i];
    if (!(in.weight > 0.0f) || !std::isfinite(in.weight)) continue;
    if (unique > 0 && influences[unique - 1].joint == in.joint)
      influences[unique - 1].weight += in.weight;
    else
      influences[unique++] = in;
  }
  influences.resize(unique);
  stats.max_influences = std::max(stats.max_influences, static_cast<int>(unique));

  joints = {0, 0, 0, 0};
  weights = {0.0f, 0.0f, 0.0f, 0.0f};
  if (influences.empty()) {
    ++stats.vertices_without_weights;
    joints[0] = static_cast<uint16_t>(fallback_joint);
    weights[0] = 1.0f;
    return;
  }
  double sum = 0.0;
  for (const Influence& in : influences) sum += in.weight;
  if (std::fabs(sum - 1.0) > 1e-3) ++stats.vertices_renormalized;
  if (influences.size() > 4) {
    ++stats.vertices_over_4_influences;
    std::partial_sort(influences.begin(), influences.begin() + 4, influences.end(),
                      [](const Influence& a, const Influence& b) {
                        return a.weight != b.weight ? a.weight > b.weight : a.joint < b.joint;
                      });
    influences.resize(4);
  }
  double kept_sum = 0.0;
  for (const Influence& in : influences) kept_sum += in.weight;
  for (size_t k = 0; k < influences.size(); ++k) {
    joints[k] = static_cast<uint16_t>(influences[k].joint);
    weights[k] = static_cast<float>(influences[k].weight / kept_sum);
  }
}

void report_import_stats(const ImportStats& stats, std::vector<std::string>& warnings) {
  if (stats.vertices_over_4_influences > 0)
    warnings.push_back(std::to_string(stats.vertices_over_4_influences) +
                       " vertices had more than 4 influences (up to " +
                       std::to_string(stats.max_influences) +
                       "); kept the 4 largest and renormalised");
  if (stats.vertices_renormalized > 0)
    warnings.push_back(std::to_string(stats.vertices_renormalized) +
                       " vertices had skin weights not summing to 1; renormalised");
  if (stats.vertices_without_weights > 0)
    warnings.push_back(std::to_string(stats.vertices_without_weights) +
                       " skinned vertices had no weight; bound fully to their mesh's joint");
  if (stats.polygons_triangulated > 0)
    warnings.push_back(std::to_string(stats.polygons_triangulated) +
                       " polygons with more than 3 sides were triangulated");
}

}  // namespace crowdbake
