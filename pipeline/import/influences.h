// Reduction of arbitrary per-vertex influence lists to the 4-influence, unit-sum form
// the whole product uses. Shared by every importer so the rules and the counts agree.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake {

struct Influence {
  int joint;
  float weight;
};

// Keeps the 4 largest positive, finite weights (ties broken by lower joint index so the
// result is deterministic), renormalises them to sum 1, and counts what it changed in
// stats. A vertex with no usable weight is bound fully to fallback_joint.
void reduce_influences(std::vector<Influence>& influences, int fallback_joint,
                       std::array<uint16_t, 4>& joints, std::array<float, 4>& weights,
                       ImportStats& stats);

// Turns nonzero counters in stats into warning lines (appended once, after import).
void report_import_stats(const ImportStats& stats, std::vector<std::string>& warnings);

}  // namespace crowdbake
