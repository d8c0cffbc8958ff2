// The accuracy bench's peers never keep fewer positions than ours at a fraction.
#include "commands/levels.h"

#include <gtest/gtest.h>

namespace crowdbake::bench {
namespace {

TEST(PeerTargets, TheAskedFractionOrWhatOursKeepsWhenThatIsMore) {
  const std::vector<double> fractions = {0.25, 0.1, 0.02};
  // Ours reaches every fraction: the peers get the fraction.
  EXPECT_EQ(peer_targets(fractions, 1000, {250, 100, 20}), (std::vector<uint32_t>{250, 100, 20}));
  EXPECT_EQ(peer_targets(fractions, 1000, {240, 90, 12}), (std::vector<uint32_t>{250, 100, 20}));
  // Ours stops at a minimum of 60 positions, above 2%: the peers keep 60 there too.
  EXPECT_EQ(peer_targets(fractions, 1000, {250, 100, 60}), (std::vector<uint32_t>{250, 100, 60}));
  // No level of ours (a configuration that did not run): the fractions.
  EXPECT_EQ(peer_targets(fractions, 1000, {}), (std::vector<uint32_t>{250, 100, 20}));
}

}  // namespace
}  // namespace crowdbake::bench
