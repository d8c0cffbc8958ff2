#include "simplify/lane_merge.h"

#include <utility>

namespace crowdbake {

std::vector<CollapseRecord> merge_in_cost_order(std::vector<CollapseRecord> (&records)[2],
                                                const std::vector<Done> (&done)[2],
                                                uint32_t& first_crossing) {
  first_crossing = UINT32_MAX;
  std::vector<CollapseRecord> out;
  out.reserve(records[0].size() + records[1].size());
  size_t i = 0, j = 0;
  while (i < records[0].size() || j < records[1].size()) {
    const bool first =
        j == records[1].size() || (i < records[0].size() && done[0][i].cost <= done[1][j].cost);
    if ((first ? done[0][i] : done[1][j]).crossed && first_crossing == UINT32_MAX)
      first_crossing = static_cast<uint32_t>(out.size());
    out.push_back(std::move(first ? records[0][i++] : records[1][j++]));
  }
  return out;
}

}  // namespace crowdbake
