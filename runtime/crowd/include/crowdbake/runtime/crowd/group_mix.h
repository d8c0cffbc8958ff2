// Small social groups (docs/design.md §3.9, crowd-patches paper §1–2): people stand, walk and sit
// with 1–4 companions, and a group is one unit ("patch") for placement and timing.
//
// The observed mix (71% pairs, 21% triples, 6% fours, 2% larger) counts groups, not people,
// and says nothing about people alone. Two decisions follow:
//  - "larger" is folded into fours, because a crowd patch holds at most 4 people (paper §1);
//    the default mix is therefore 71% / 21% / 8% of groups;
//  - people alone are a separate knob, `single_fraction` of all people (default 0.3).
#pragma once

#include <cstdint>
#include <vector>

#include "crowdbake/runtime/crowd/status.h"

namespace crowdbake::crowd {

struct GroupMix {
  float single_fraction = 0.3f;  // share of people who are alone; [0, 1]
  float pairs = 0.71f;           // relative frequencies of group sizes among groups of >= 2;
  float triples = 0.21f;         // each finite and >= 0, not all 0 (unless single_fraction
  float fours = 0.06f;           // is 1)
  float larger = 0.02f;          // folded into fours (at most 4 people per group)
};

// Checks the mix; kInvalidArgument naming the bad field.
Status validate_group_mix(const GroupMix& mix);

// Splits `people` into group sizes (1–4) that sum to exactly `people`, deterministic in
// `seed`: round(single_fraction · people) singles, then groups drawn from the mix until the
// people run out (a last draw larger than what is left is cut down to the rest; a cut to 1
// becomes a single). Sizes come out shuffled. The mix must be valid; people >= 0.
std::vector<uint8_t> draw_group_sizes(const GroupMix& mix, int people, uint64_t seed);

}  // namespace crowdbake::crowd
