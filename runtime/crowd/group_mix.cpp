// Group sizes of a crowd (docs/design.md §3.9, crowd-patches paper §1).
#include "crowdbake/runtime/crowd/group_mix.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "random.h"

namespace crowdbake::crowd {

Status validate_group_mix(const GroupMix& mix) {
  auto bad = [](const char* field, float v, const char* rule) {
    return Status(StatusCode::kInvalidArgument, std::string("group mix: ") + field + " = " +
                                                    std::to_string(v) + " must be " + rule);
  };
  if (!std::isfinite(mix.single_fraction) || mix.single_fraction < 0.0f ||
      mix.single_fraction > 1.0f)
    return bad("single_fraction", mix.single_fraction, "in [0, 1]");
  const std::pair<const char*, float> sizes[] = {
      {"pairs", mix.pairs}, {"triples", mix.triples}, {"fours", mix.fours}, {"larger", mix.larger}};
  double total = 0.0;
  for (const auto& s : sizes) {
    if (!std::isfinite(s.second) || s.second < 0.0f)
      return bad(s.first, s.second, "finite and >= 0");
    total += s.second;
  }
  if (!(total > 0.0) && mix.single_fraction < 1.0f)
    return Status(StatusCode::kInvalidArgument,
                  "group mix: pairs, triples, fours and larger are all 0 but "
                  "single_fraction < 1 leaves people to put in groups");
  return Status();
}

std::vector<uint8_t> draw_group_sizes(const GroupMix& mix, int people, uint64_t seed) {
  std::vector<uint8_t> sizes;
  if (people <= 0) return sizes;
  detail::Rng rng(seed, detail::kStreamGroups);
  const int singles =
      static_cast<int>(std::lround(static_cast<double>(mix.single_fraction) * people));
  sizes.assign(static_cast<size_t>(singles), 1);
  // note: "larger" joins the fours, a patch holds at most 4 people (group_mix.h).
  const double w2 = mix.pairs, w3 = mix.triples, w4 = static_cast<double>(mix.fours) + mix.larger;
  const double total = w2 + w3 + w4;
  int left = people - singles;
  while (left > 0) {
    int size = 1;
    if (total > 0.0) {
      const double u = rng.next() * total;
      size = u < w2 ? 2 : u < w2 + w3 ? 3 : 4;
    }
    size = std::min(size, left);
    sizes.push_back(static_cast<uint8_t>(size));
    left -= size;
  }
  // Fisher–Yates, so singles are not all first.
  for (size_t i = sizes.size(); i > 1; --i) std::swap(sizes[i - 1], sizes[rng.below(i)]);
  return sizes;
}

}  // namespace crowdbake::crowd
