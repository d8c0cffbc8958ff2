#include "cli/missing_joints.h"

#include "crowdbake/formats/progressive.h"

namespace crowdbake::cli {

namespace {

// A pack's joints by their coarsest levels, and the vertex count of its coarsest level.
struct PackJointLevels {
  std::vector<uint32_t> levels;
  std::vector<int> parents;
  std::vector<std::string> names;
  uint32_t coarsest = 0;
};

PackJointLevels pack_joint_levels(const PackContents& pack, const std::vector<float>& weights) {
  const ProgressiveView view = progressive_view(pack);
  PackJointLevels out;
  const std::vector<uint16_t> heaviest = heaviest_joints(pack.geometry.joints, weights);
  out.levels = coarsest_levels_by_joint(view, heaviest, pack.joints.size());
  for (const PackJoint& j : pack.joints)
    out.names.push_back(j.name), out.parents.push_back(j.parent);
  // note: without progressive arrays the coarsest level is the full mesh.
  out.coarsest = usable_vertices(view, 0);
  return out;
}

nlohmann::ordered_json to_json(const std::vector<MissingJoint>& joints) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const MissingJoint& m : joints)
    out.push_back({{"joint", m.name}, {"coarsest_level", m.coarsest_level}});
  return out;
}

}  // namespace

std::vector<MissingJoint> joints_missing_at_min(const PackContents& pack,
                                                const std::vector<float>& weights) {
  const PackJointLevels p = pack_joint_levels(pack, weights);
  return joints_missing_below(p.levels, p.names, p.coarsest);
}

std::vector<MissingJoint> joints_unreached_at_min(const PackContents& pack,
                                                  const std::vector<float>& weights) {
  const PackJointLevels p = pack_joint_levels(pack, weights);
  return joints_unreached_below(p.levels, p.parents, p.names, p.coarsest);
}

std::vector<uint32_t> coarsest_levels_reaching(const std::vector<uint32_t>& coarsest_levels,
                                               const std::vector<int>& parents) {
  std::vector<uint32_t> out = coarsest_levels;
  for (size_t k = 0; k < coarsest_levels.size(); ++k) {
    if (coarsest_levels[k] == 0) continue;
    // note: the parent walk is bounded, so a malformed hierarchy (a loop) cannot hang it.
    int j = k < parents.size() ? parents[k] : -1;
    for (size_t steps = 0; j >= 0 && static_cast<size_t>(j) < out.size() && steps < out.size();
         ++steps, j = static_cast<size_t>(j) < parents.size() ? parents[j] : -1)
      if (out[j] == 0 || coarsest_levels[k] < out[j]) out[j] = coarsest_levels[k];
  }
  return out;
}

std::vector<MissingJoint> joints_unreached_below(const std::vector<uint32_t>& coarsest_levels,
                                                 const std::vector<int>& parents,
                                                 const std::vector<std::string>& names,
                                                 uint32_t level) {
  const std::vector<uint32_t> reaching = coarsest_levels_reaching(coarsest_levels, parents);
  std::vector<MissingJoint> out;
  for (size_t j = 0; j < coarsest_levels.size() && j < names.size(); ++j)
    if (coarsest_levels[j] > 0 && reaching[j] > level)
      out.push_back({names[j], reaching[j], static_cast<uint32_t>(j)});
  return out;
}

std::vector<MissingJoint> joints_missing_below(const std::vector<uint32_t>& coarsest_levels,
                                               const std::vector<std::string>& names,
                                               uint32_t level) {
  std::vector<MissingJoint> out;
  for (size_t j = 0; j < coarsest_levels.size() && j < names.size(); ++j)
    if (coarsest_levels[j] > level)
      out.push_back({names[j], coarsest_levels[j], static_cast<uint32_t>(j)});
  return out;
}

nlohmann::ordered_json joints_missing_at_min_json(const PackContents& pack,
                                                  const std::vector<float>& weights) {
  return to_json(joints_missing_at_min(pack, weights));
}

nlohmann::ordered_json joints_unreached_at_min_json(const PackContents& pack,
                                                    const std::vector<float>& weights) {
  return to_json(joints_unreached_at_min(pack, weights));
}

}  // namespace crowdbake::cli
