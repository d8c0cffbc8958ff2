#include "cli/missing_joints.h"

#include "crowdbake/formats/progressive.h"

namespace crowdbake::cli {

std::vector<MissingJoint> joints_missing_at_min(const PackContents& pack,
                                                const std::vector<float>& weights) {
  const ProgressiveView view = progressive_view(pack);
  const std::vector<uint16_t> heaviest = heaviest_joints(pack.geometry.joints, weights);
  const std::vector<uint32_t> levels = coarsest_levels_by_joint(view, heaviest, pack.joints.size());
  std::vector<std::string> names;
  for (const PackJoint& j : pack.joints) names.push_back(j.name);
  // note: without progressive arrays the coarsest level is the full mesh.
  return joints_missing_below(levels, names, usable_vertices(view, 0));
}

std::vector<MissingJoint> joints_missing_below(const std::vector<uint32_t>& coarsest_levels,
                                               const std::vector<std::string>& names,
                                               uint32_t level) {
  std::vector<MissingJoint> out;
  for (size_t j = 0; j < coarsest_levels.size() && j < names.size(); ++j)
    if (coarsest_levels[j] > level) out.push_back({names[j], coarsest_levels[j]});
  return out;
}

nlohmann::ordered_json joints_missing_at_min_json(const PackContents& pack,
                                                  const std::vector<float>& weights) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const MissingJoint& m : joints_missing_at_min(pack, weights))
    out.push_back({{"joint", m.name}, {"coarsest_level", m.coarsest_level}});
  return out;
}

}  // namespace crowdbake::cli
