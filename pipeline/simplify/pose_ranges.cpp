// Reader for explicit per-joint angle ranges (docs/pose-ranges.md). The whole file is
// checked before anything is applied, so a bad file leaves the distribution untouched.
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "crowdbake/base/json_reader.h"
#include "crowdbake/pipeline/error.h"
#include "simplify/pose_sampler.h"

namespace crowdbake {
namespace {

using json_reader::Json;

constexpr double kPi = 3.14159265358979323846;
constexpr const char* kAngleNames[3] = {"roll", "pitch", "yaw"};
// note: roll and yaw cover every rotation within ±180° and pitch within ±90° (the range
// to_euler returns); wider ranges would only count some rotations twice.
constexpr double kAngleLimits[3] = {180.0, 90.0, 180.0};
constexpr const char* kFormatHint = "see docs/pose-ranges.md";

struct Range {
  int joint;      // -1: "default", every joint
  int angle;      // 0 roll, 1 pitch, 2 yaw
  double lo, hi;  // radians
};

// The value as written, shortened: the user sees what was read.
std::string shown(const Json& j) {
  std::string text = j.dump();
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return text;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Names that contain the unknown one or are contained in it, ignoring case (a Mixamo rig
// calls "LeftArm" "mixamorig:LeftArm"); otherwise the first few names of the skeleton.
std::string unknown_joint(const Skeleton& skeleton, const std::string& name) {
  std::string message = "unknown joint '" + name + "'";
  const std::string wanted = lower(name);
  std::vector<std::string> similar;
  for (const Joint& joint : skeleton.joints) {
    const std::string have = lower(joint.name);
    if (!have.empty() &&
        (have.find(wanted) != std::string::npos || wanted.find(have) != std::string::npos))
      similar.push_back(joint.name);
  }
  const auto list = [](const std::vector<std::string>& names, size_t most) {
    std::string out;
    for (size_t i = 0; i < names.size() && i < most; ++i) out += (i ? ", '" : "'") + names[i] + "'";
    return out + (names.size() > most ? ", ..." : "");
  };
  if (!similar.empty()) {
    const bool case_only = lower(similar.front()) == wanted && similar.size() == 1;
    return message + "; did you mean " + list(similar, 3) + "?" +
           (case_only ? " (names are case-sensitive)" : "");
  }
  std::vector<std::string> all;
  for (const Joint& joint : skeleton.joints) all.push_back(joint.name);
  return message + "; the skeleton's " + std::to_string(all.size()) + " joints include " +
         list(all, 8);
}

// Walks the document with json_reader (base/json_reader.h): a problem is "<key path>:
// <problem>", e.g. "joints.LeftArm.roll: min 80 > max -10; write [min, max]".
class Reader {
 public:
  explicit Reader(const Skeleton& skeleton) : skeleton_(skeleton) {}

  std::vector<Range> read(const Json& doc) const {
    json_reader::check_object(doc, "", {"comment", "default", "joints"});
    std::vector<Range> ranges;
    if (const Json* p = json_reader::find(doc, "default")) angles(*p, "default", -1, ranges);
    if (const Json* p = json_reader::find(doc, "joints")) {
      if (!p->is_object())
        json_reader::fail("joints", "expected an object mapping joint names to ranges, got " +
                                        json_reader::describe(*p));
      for (const auto& [name, joint_ranges] : p->items()) {
        const int joint = skeleton_.find(name);
        if (joint < 0) json_reader::fail("joints." + name, unknown_joint(skeleton_, name));
        angles(joint_ranges, "joints." + name, joint, ranges);
      }
    }
    return ranges;
  }

 private:
  void angles(const Json& object, const std::string& where, int joint,
              std::vector<Range>& out) const {
    json_reader::check_object(object, where, {"roll", "pitch", "yaw"});
    for (const auto& [key, value] : object.items()) {
      int k = 0;
      while (k < 3 && key != kAngleNames[k]) ++k;
      const std::string at = where + "." + key;
      if (!value.is_array() || value.size() != 2 || !value[0].is_number() || !value[1].is_number())
        json_reader::fail(at, "expected [min, max] in degrees, got " + shown(value));
      const double lo = value[0].get<double>(), hi = value[1].get<double>();
      if (!std::isfinite(lo) || !std::isfinite(hi)) json_reader::fail(at, "is not finite");
      if (lo > hi)
        json_reader::fail(
            at, "min " + value[0].dump() + " > max " + value[1].dump() + "; write [min, max]");
      const double limit = kAngleLimits[k];
      if (lo < -limit || hi > limit)
        json_reader::fail(at, shown(value) + " is outside [-" +
                                  std::to_string(static_cast<int>(limit)) + ", " +
                                  std::to_string(static_cast<int>(limit)) +
                                  "] degrees (wider ranges only repeat rotations)");
      out.push_back({joint, k, lo * kPi / 180.0, hi * kPi / 180.0});
    }
  }

  const Skeleton& skeleton_;
};

[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw input_error(path, "pose ranges: " + why + " (" + kFormatHint + ")");
}

std::vector<Range> read_ranges(const std::string& path, const Skeleton& skeleton) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(path, "file not found; check the path");
  if (std::filesystem::is_directory(path, ec))
    fail(path, "this is a directory; give the JSON file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the file for reading; check its permissions");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Json doc;
  std::vector<Range> ranges;
  Status s = json_reader::parse_json(text, "pose ranges", StatusCode::kInvalidArgument, doc);
  if (s.ok())
    s = json_reader::read_json("pose ranges", StatusCode::kInvalidArgument,
                               [&] { ranges = Reader(skeleton).read(doc); });
  if (!s.ok()) throw input_error(path, s.message() + " (" + kFormatHint + ")");
  return ranges;
}

AngleDensity uniform(double lo, double hi) {
  if (hi > lo) return AngleDensity{lo, hi, {1.0}};
  return AngleDensity{lo, lo, {}};  // min == max: the angle stays there
}

}  // namespace

void apply_pose_ranges(PoseDistribution& distribution, const Skeleton& skeleton,
                       const std::string& path) {
  if (distribution.joints.size() != skeleton.joints.size())
    throw Error(Error::Kind::kUsage, path,
                "pose distribution has " + std::to_string(distribution.joints.size()) +
                    " joints but the skeleton has " + std::to_string(skeleton.joints.size()));
  const std::vector<Range> ranges = read_ranges(path, skeleton);
  // note: "default" first, so a joint's own entry wins whatever the key order in the file.
  size_t overridden = 0;
  std::vector<bool> named(skeleton.joints.size(), false);
  bool has_default = false;
  for (const Range& r : ranges)
    if (r.joint < 0) {
      has_default = true;
      for (JointDensity& jd : distribution.joints) jd.angles[r.angle] = uniform(r.lo, r.hi);
    }
  for (const Range& r : ranges)
    if (r.joint >= 0) {
      // note: names may repeat in odd files; every joint of that name gets the range.
      for (size_t j = 0; j < skeleton.joints.size(); ++j)
        if (skeleton.joints[j].name == skeleton.joints[r.joint].name) {
          distribution.joints[j].angles[r.angle] = uniform(r.lo, r.hi);
          overridden += named[j] ? 0 : 1;
          named[j] = true;
        }
    }
  distribution.estimator += "; ranges from " + std::filesystem::path(path).filename().string() +
                            " (" + (has_default ? "default for every joint, " : "") +
                            std::to_string(overridden) + " joints named)";
}

}  // namespace crowdbake
