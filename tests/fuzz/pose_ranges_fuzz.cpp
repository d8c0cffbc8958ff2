// libFuzzer target: pose-range JSON (docs/pose-ranges.md) applied to the generated
// spectator's pose distribution. Property beyond "no crash, no leak, no huge allocation":
// an accepted file leaves every density's range ordered and finite, and a refused one
// leaves the distribution as it was.
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "crowdbake/pipeline/error.h"
#include "fuzz_input_file.h"
#include "simplify/pose_sampler.h"
#include "spectator_character.h"

namespace {

const crowdbake::SkinnedAsset& spectator() {
  static const crowdbake::SkinnedAsset asset = crowdbake::samples::make_spectator_character();
  return asset;
}

const crowdbake::PoseDistribution& estimated() {
  static const crowdbake::PoseDistribution d = crowdbake::estimate_pose_distribution(spectator());
  return d;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace crowdbake;
  const std::string path = fuzz::write_input("ranges.json", data, size);
  PoseDistribution d = estimated();
  try {
    apply_pose_ranges(d, spectator().skeleton, path);
  } catch (const Error& e) {
    fuzz::refused(e.what());
    if (d.estimator != estimated().estimator) std::abort();
    return 0;
  }
  for (const JointDensity& j : d.joints)
    for (const AngleDensity& a : j.angles)
      if (!std::isfinite(a.lo) || !std::isfinite(a.hi) || a.hi < a.lo) std::abort();
  return 0;
}
