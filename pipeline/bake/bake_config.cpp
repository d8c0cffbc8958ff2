// Bake configuration files (docs/bake-config.md): JSON over the defaults, every key
// checked, paths resolved against the file's folder.
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "crowdbake/formats/pack_format.h"
#include "crowdbake/pipeline/bake.h"
#include "crowdbake/pipeline/error.h"

namespace crowdbake {
namespace {

using nlohmann::json;

const std::map<std::string, DqemForm> kForms = {{"pullback", DqemForm::kPullback},
                                                {"exact", DqemForm::kExact}};
const std::map<std::string, PoseSource> kSources = {{"sampled", PoseSource::kSampled},
                                                    {"clips", PoseSource::kClips}};
const std::map<std::string, AnimationEncoding> kEncodings = {
    {"float32", AnimationEncoding::kFloat32},
    {"float16", AnimationEncoding::kFloat16},
    {"quantized", AnimationEncoding::kQuantized}};
const std::map<std::string, PackCompression> kCompressions = {{"zstd", PackCompression::kZstd},
                                                              {"none", PackCompression::kNone}};
const std::map<std::string, GeometryCodec> kCodecs = {{"draco", GeometryCodec::kDraco},
                                                      {"meshopt", GeometryCodec::kMeshopt},
                                                      {"raw", GeometryCodec::kRaw}};

template <typename T>
std::string name_of(const std::map<std::string, T>& names, T value) {
  for (const auto& [name, v] : names)
    if (v == value) return name;
  return "?";
}

class ConfigReader {
 public:
  ConfigReader(const std::string& path, BakeSettings& out) : path_(path), out_(out) {}

  void read() {
    std::ifstream in(path_);
    if (!in) throw input_error(path_, "bake config: cannot open the file; check the path");
    json doc;
    try {
      doc = json::parse(in);
    } catch (const json::exception& e) {
      throw input_error(path_, std::string("bake config: not valid JSON (") + e.what() + ")");
    }
    if (!doc.is_object()) fail("", "the top level must be an object");
    for (const auto& [section, body] : doc.items()) {
      if (section == "comment") continue;
      if (!body.is_object()) fail(section, "must be an object");
      if (section == "simplify")
        simplify(body);
      else if (section == "animation")
        animation(body);
      else if (section == "partition")
        partition(body);
      else if (section == "geometry")
        geometry(body);
      else if (section == "level_errors")
        level_errors(body);
      else if (section == "pack")
        pack(body);
      else
        fail(section,
             "unknown section (expected simplify, level_errors, animation, partition, "
             "geometry or pack)");
    }
  }

 private:
  [[noreturn]] void fail(const std::string& key, const std::string& why) const {
    throw input_error(path_, "bake config" + (key.empty() ? std::string() : ", key '" + key + "'") +
                                 ": " + why + "; see docs/bake-config.md");
  }

  double number(const std::string& key, const json& v, double lo, double hi) const {
    if (!v.is_number()) fail(key, "must be a number");
    const double x = v.get<double>();
    if (!(x >= lo && x <= hi))
      fail(key, "must be in [" + json(lo).dump() + ", " + json(hi).dump() + "]");
    return x;
  }
  bool boolean(const std::string& key, const json& v) const {
    if (!v.is_boolean()) fail(key, "must be true or false");
    return v.get<bool>();
  }
  template <typename T>
  T choice(const std::string& key, const json& v, const std::map<std::string, T>& names) const {
    if (v.is_string()) {
      auto it = names.find(v.get<std::string>());
      if (it != names.end()) return it->second;
    }
    std::string list;
    for (const auto& [name, value] : names) list += (list.empty() ? "" : ", ") + name;
    fail(key, "must be one of " + list);
  }

  void simplify(const json& body) {
    SimplifyOptions& s = out_.simplify;
    for (const auto& [k, v] : body.items()) {
      const std::string key = "simplify." + k;
      if (k == "samples")
        s.samples = static_cast<int>(number(key, v, 1, 4096));
      else if (k == "seed")
        s.seed = static_cast<uint64_t>(number(key, v, 0, 9007199254740991.0));
      else if (k == "stratified")
        s.stratified = boolean(key, v);
      else if (k == "form")
        s.form = choice(key, v, kForms);
      else if (k == "pose_source")
        s.pose_source = choice(key, v, kSources);
      else if (k == "check_flips_in_all_poses")
        s.check_flips_in_all_poses = boolean(key, v);
      else if (k == "relax_when_stuck")
        fail(key,
             "is no longer an option: the simplifier keeps one set of rules down to its minimum "
             "(docs/simplification.md); remove the key");
      else if (k == "ranges") {
        if (!v.is_string()) fail(key, "must be a path");
        s.ranges_file =
            (std::filesystem::path(path_).parent_path() / v.get<std::string>()).string();
      } else
        fail(key, "unknown key");
    }
  }

  void animation(const json& body) {
    AnimationBakeOptions& a = out_.animation;
    for (const auto& [k, v] : body.items()) {
      const std::string key = "animation." + k;
      if (k == "fps")
        a.fps = number(key, v, 1, 240);
      else if (k == "encoding")
        a.encoding = choice(key, v, kEncodings);
      else if (k == "root_motion")
        a.extract_root_motion = boolean(key, v);
      else if (k == "max_error")
        out_.pack.animation_error = number(key, v, 0, 0.1);
      else
        fail(key, "unknown key");
    }
  }

  void level_errors(const json& body) {
    LevelErrorOptions& e = out_.level_errors;
    for (const auto& [k, v] : body.items()) {
      const std::string key = "level_errors." + k;
      if (k == "samples") {
        e.samples = static_cast<uint32_t>(number(key, v, 0, 64));
        if (e.samples == 1) fail(key, "must be 0 (none) or 2..64");
      } else if (k == "fps") {
        e.fps = number(key, v, 0.1, 240);
      } else {
        fail(key, "unknown key");
      }
    }
  }

  void partition(const json& body) {
    PartitionOptions& p = out_.partition;
    for (const auto& [k, v] : body.items()) {
      const std::string key = "partition." + k;
      if (k == "size")
        p.size = static_cast<uint32_t>(number(key, v, 1, 8192));
      else if (k == "neck_height")
        p.neck_height = static_cast<float>(number(key, v, -1e30, 1e30));
      else if (k == "waist_height")
        p.waist_height = static_cast<float>(number(key, v, -1e30, 1e30));
      else
        fail(key, "unknown key");
    }
  }

  void geometry(const json& body) {
    PackWriteOptions& g = out_.pack;
    for (const auto& [k, v] : body.items()) {
      const std::string key = "geometry." + k;
      if (k == "codec")
        g.codec = choice(key, v, kCodecs);
      else if (k == "position_bits")
        g.position_bits = static_cast<int>(number(key, v, 0, 30));
      else if (k == "normal_bits")
        g.normal_bits = static_cast<int>(number(key, v, 0, 30));
      else if (k == "uv_bits")
        g.uv_bits = static_cast<int>(number(key, v, 0, 30));
      else if (k == "weight_bits")
        g.weight_bits = static_cast<int>(number(key, v, 0, pack_format::kMaxWeightBits));
      else
        fail(key, "unknown key");
    }
  }

  void pack(const json& body) {
    for (const auto& [k, v] : body.items()) {
      const std::string key = "pack." + k;
      if (k == "compression")
        out_.pack.compression = choice(key, v, kCompressions);
      else
        fail(key, "unknown key");
    }
  }

  std::string path_;
  BakeSettings& out_;
};

}  // namespace

BakeSettings read_bake_config(const std::string& path) {
  BakeSettings settings;
  ConfigReader(path, settings).read();
  return settings;
}

std::string bake_settings_json(const BakeSettings& s) {
  // note: ordered_json keeps the keys in this order, so equal settings give equal bytes;
  // file paths are reduced to their names so a pack does not depend on where it was baked.
  nlohmann::ordered_json j;
  j["simplify"]["samples"] = s.simplify.samples;
  j["simplify"]["seed"] = s.simplify.seed;
  j["simplify"]["stratified"] = s.simplify.stratified;
  j["simplify"]["form"] = name_of(kForms, s.simplify.form);
  j["simplify"]["pose_source"] = name_of(kSources, s.simplify.pose_source);
  j["simplify"]["check_flips_in_all_poses"] = s.simplify.check_flips_in_all_poses;
  j["simplify"]["ranges"] = std::filesystem::path(s.simplify.ranges_file).filename().string();
  j["level_errors"]["samples"] = s.level_errors.samples;
  j["level_errors"]["fps"] = s.level_errors.fps;
  j["animation"]["fps"] = s.animation.fps;
  j["animation"]["encoding"] = name_of(kEncodings, s.animation.encoding);
  j["animation"]["root_motion"] = s.animation.extract_root_motion;
  j["animation"]["max_error"] = s.pack.animation_error;
  j["partition"]["size"] = s.partition.size;
  j["partition"]["neck_height"] =
      s.partition.neck_height ? json(*s.partition.neck_height) : json(nullptr);
  j["partition"]["waist_height"] =
      s.partition.waist_height ? json(*s.partition.waist_height) : json(nullptr);
  j["geometry"]["codec"] = name_of(kCodecs, s.pack.codec);
  j["geometry"]["position_bits"] = s.pack.position_bits;
  j["geometry"]["normal_bits"] = s.pack.normal_bits;
  j["geometry"]["uv_bits"] = s.pack.uv_bits;
  j["geometry"]["weight_bits"] = s.pack.weight_bits;
  j["pack"]["compression"] = name_of(kCompressions, s.pack.compression);
  return j.dump();
}

}  // namespace crowdbake
