// Bake configuration files (docs/bake-config.md): JSON over the defaults, every key
// checked, paths resolved against the file's folder.
#include <array>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <utility>

#include "crowdbake/base/json_reader.h"
#include "crowdbake/formats/pack_format.h"
#include "crowdbake/pipeline/bake.h"
#include "crowdbake/pipeline/error.h"

namespace crowdbake {
namespace {

using nlohmann::json;

using json_reader::Json;

constexpr std::array<std::pair<const char*, DqemForm>, 2> kForms = {
    {{"pullback", DqemForm::kPullback}, {"exact", DqemForm::kExact}}};
constexpr std::array<std::pair<const char*, PoseSource>, 2> kSources = {
    {{"sampled", PoseSource::kSampled}, {"clips", PoseSource::kClips}}};
constexpr std::array<std::pair<const char*, AnimationEncoding>, 3> kEncodings = {
    {{"float32", AnimationEncoding::kFloat32},
     {"float16", AnimationEncoding::kFloat16},
     {"quantized", AnimationEncoding::kQuantized}}};
constexpr std::array<std::pair<const char*, PackCompression>, 2> kCompressions = {
    {{"zstd", PackCompression::kZstd}, {"none", PackCompression::kNone}}};
constexpr std::array<std::pair<const char*, bool>, 2> kImageCodings = {
    {{"optimized", true}, {"source", false}}};
constexpr std::array<std::pair<const char*, GeometryCodec>, 4> kCodecs = {
    {{"predictive", GeometryCodec::kPredictive},
     {"draco", GeometryCodec::kDraco},
     {"meshopt", GeometryCodec::kMeshopt},
     {"raw", GeometryCodec::kRaw}}};

template <typename T, size_t N>
std::string name_of(const std::array<std::pair<const char*, T>, N>& names, T value) {
  for (const auto& [name, v] : names)
    if (v == value) return name;
  return "?";
}

// Each section's keys, checked with json_reader (base/json_reader.h): a problem is
// "<section.key>: <problem>".
class ConfigReader {
 public:
  ConfigReader(const std::string& path, BakeSettings& out) : path_(path), out_(out) {}

  void read(const Json& doc) {
    json_reader::check_object(doc, "",
                              {"comment", "simplify", "level_errors", "animation", "partition",
                               "geometry", "pack", "variants", "impostor"});
    if (const Json* p = find(doc, "simplify")) simplify(*p);
    if (const Json* p = find(doc, "level_errors")) level_errors(*p);
    if (const Json* p = find(doc, "animation")) animation(*p);
    if (const Json* p = find(doc, "partition")) partition(*p);
    if (const Json* p = find(doc, "geometry")) geometry(*p);
    if (const Json* p = find(doc, "pack")) pack(*p);
    if (const Json* p = find(doc, "variants")) variants(*p);
    if (const Json* p = find(doc, "impostor")) impostor(*p);
  }

 private:
  static const Json* find(const Json& object, const char* key) {
    return json_reader::find(object, key);
  }
  static double number(const Json& v, const std::string& key, double lo, double hi) {
    return json_reader::number_in(v, key, lo, hi);
  }

  void simplify(const Json& body) {
    SimplifyOptions& s = out_.simplify;
    if (body.is_object() && find(body, "relax_when_stuck"))
      json_reader::fail("simplify.relax_when_stuck",
                        "is no longer an option: the simplifier keeps one set of rules down to "
                        "its minimum (docs/simplification.md); remove the key");
    json_reader::check_object(
        body, "simplify",
        {"samples", "seed", "stratified", "form", "pose_source", "check_flips_in_all_poses",
         "max_pose_priced_positions", "max_stand_off_priced_positions", "split_positions",
         "max_collapse_cost", "small_area_floor", "keep_joint_ends", "ranges"});
    if (const Json* p = find(body, "samples"))
      s.samples = static_cast<int>(json_reader::integer(*p, "simplify.samples", 1, 4096));
    if (const Json* p = find(body, "seed"))
      s.seed = static_cast<uint64_t>(
          json_reader::integer(*p, "simplify.seed", 0, int64_t{9007199254740991}));
    if (const Json* p = find(body, "stratified"))
      s.stratified = json_reader::boolean(*p, "simplify.stratified");
    if (const Json* p = find(body, "form"))
      s.form = json_reader::choice(*p, "simplify.form", kForms);
    if (const Json* p = find(body, "pose_source"))
      s.pose_source = json_reader::choice(*p, "simplify.pose_source", kSources);
    if (const Json* p = find(body, "check_flips_in_all_poses"))
      s.check_flips_in_all_poses = json_reader::boolean(*p, "simplify.check_flips_in_all_poses");
    if (const Json* p = find(body, "max_pose_priced_positions"))
      s.max_pose_priced_positions = static_cast<uint32_t>(
          json_reader::integer(*p, "simplify.max_pose_priced_positions", 0, int64_t{UINT32_MAX}));
    if (const Json* p = find(body, "max_stand_off_priced_positions"))
      s.max_stand_off_priced_positions = static_cast<uint32_t>(json_reader::integer(
          *p, "simplify.max_stand_off_priced_positions", 0, int64_t{UINT32_MAX}));
    if (const Json* p = find(body, "split_positions"))
      s.split_positions = static_cast<uint32_t>(
          json_reader::integer(*p, "simplify.split_positions", 0, int64_t{UINT32_MAX}));
    if (const Json* p = find(body, "max_collapse_cost"))
      s.max_collapse_cost = number(*p, "simplify.max_collapse_cost", 0.0, 1e9);
    if (const Json* p = find(body, "small_area_floor"))
      s.small_area_floor = number(*p, "simplify.small_area_floor", 0.0, 10.0);
    if (const Json* p = find(body, "keep_joint_ends"))
      s.keep_joint_ends = json_reader::boolean(*p, "simplify.keep_joint_ends");
    if (const Json* p = find(body, "ranges"))
      s.ranges_file =
          (std::filesystem::path(path_).parent_path() / json_reader::string(*p, "simplify.ranges"))
              .string();
  }

  void animation(const Json& body) {
    AnimationBakeOptions& a = out_.animation;
    json_reader::check_object(body, "animation", {"fps", "encoding", "root_motion", "max_error"});
    if (const Json* p = find(body, "fps")) a.fps = number(*p, "animation.fps", 1, 240);
    if (const Json* p = find(body, "encoding"))
      a.encoding = json_reader::choice(*p, "animation.encoding", kEncodings);
    if (const Json* p = find(body, "root_motion"))
      a.extract_root_motion = json_reader::boolean(*p, "animation.root_motion");
    if (const Json* p = find(body, "max_error"))
      out_.pack.animation_error = number(*p, "animation.max_error", 0, 0.1);
  }

  void level_errors(const Json& body) {
    LevelErrorOptions& e = out_.level_errors;
    json_reader::check_object(body, "level_errors", {"samples", "fps"});
    if (const Json* p = find(body, "samples")) {
      e.samples = static_cast<uint32_t>(json_reader::integer(*p, "level_errors.samples", 0, 64));
      if (e.samples == 1) json_reader::fail("level_errors.samples", "must be 0 (none) or 2..64");
    }
    if (const Json* p = find(body, "fps")) e.fps = number(*p, "level_errors.fps", 0.1, 240);
  }

  void partition(const Json& body) {
    PartitionOptions& p = out_.partition;
    json_reader::check_object(body, "partition", {"size", "neck_height", "waist_height"});
    if (const Json* v = find(body, "size"))
      p.size = static_cast<uint32_t>(json_reader::integer(*v, "partition.size", 1, 8192));
    if (const Json* v = find(body, "neck_height"))
      p.neck_height = static_cast<float>(json_reader::number(*v, "partition.neck_height"));
    if (const Json* v = find(body, "waist_height"))
      p.waist_height = static_cast<float>(json_reader::number(*v, "partition.waist_height"));
  }

  void geometry(const Json& body) {
    PackWriteOptions& g = out_.pack;
    json_reader::check_object(body, "geometry",
                              {"codec", "position_bits", "normal_bits", "uv_bits", "weight_bits"});
    if (const Json* p = find(body, "codec"))
      g.codec = json_reader::choice(*p, "geometry.codec", kCodecs);
    const struct {
      const char* key;
      int* bits;
      int most;
    } fields[] = {{"position_bits", &g.position_bits, 30},
                  {"normal_bits", &g.normal_bits, 30},
                  {"uv_bits", &g.uv_bits, 30},
                  {"weight_bits", &g.weight_bits, pack_format::kMaxWeightBits}};
    for (const auto& f : fields)
      if (const Json* p = find(body, f.key))
        *f.bits =
            static_cast<int>(json_reader::integer(*p, std::string("geometry.") + f.key, 0, f.most));
  }

  void pack(const Json& body) {
    json_reader::check_object(body, "pack", {"compression", "images"});
    if (const Json* p = find(body, "compression"))
      out_.pack.compression = json_reader::choice(*p, "pack.compression", kCompressions);
    if (const Json* p = find(body, "images"))
      out_.optimize_images = json_reader::choice(*p, "pack.images", kImageCodings);
  }

  void impostor(const Json& body) {
    ImpostorOptions& o = out_.impostor;
    json_reader::check_object(body, "impostor", {"views", "frames_per_clip", "height"});
    const int64_t side = pack_format::kMaxImpostorSide;
    if (const Json* p = find(body, "views"))
      o.views = static_cast<uint32_t>(json_reader::integer(*p, "impostor.views", 0, side));
    if (const Json* p = find(body, "frames_per_clip"))
      o.frames_per_clip =
          static_cast<uint32_t>(json_reader::integer(*p, "impostor.frames_per_clip", 1, 1024));
    if (const Json* p = find(body, "height"))
      o.height = static_cast<uint32_t>(json_reader::integer(*p, "impostor.height", 1, side));
  }

  void variants(const Json& body) {
    static const char* const kRegions[3] = {"head", "upper_body", "trousers"};
    json_reader::check_object(body, "variants", {"head", "upper_body", "trousers"});
    const std::filesystem::path folder = std::filesystem::path(path_).parent_path();
    for (int r = 0; r < 3; ++r) {
      const Json* list = find(body, kRegions[r]);
      if (!list) continue;
      const std::string key = std::string("variants.") + kRegions[r];
      const Json& files = json_reader::array(*list, key);
      if (files.size() > pack_format::kMaxVariantImages)
        json_reader::fail(key, std::to_string(files.size()) + " images exceed the limit of " +
                                   std::to_string(pack_format::kMaxVariantImages) +
                                   " per region (an instance's choice is one byte)");
      for (size_t i = 0; i < files.size(); ++i) {
        const std::string file = json_reader::string(files[i], json_reader::item_path(key, i));
        if (file.empty()) json_reader::fail(json_reader::item_path(key, i), "empty file name");
        out_.variant_images[r].push_back((folder / file).lexically_normal().string());
      }
    }
  }

  std::string path_;
  BakeSettings& out_;
};

BakeSettings read_or_throw(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw input_error(path, "bake config: cannot open the file; check the path");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  json_reader::Json doc;
  BakeSettings settings;
  Status s = json_reader::parse_json(text, "bake config", StatusCode::kInvalidArgument, doc);
  if (s.ok())
    s = json_reader::read_json("bake config", StatusCode::kInvalidArgument,
                               [&] { ConfigReader(path, settings).read(doc); });
  if (!s.ok()) throw input_error(path, s.message() + "; see docs/bake-config.md");
  return settings;
}

}  // namespace

Status read_bake_config(const std::string& path, BakeSettings& out) {
  return capture_errors([&] { out = read_or_throw(path); });
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
  // note: only when not the default, so packs baked before the key existed keep their text.
  if (s.simplify.max_pose_priced_positions != SimplifyOptions{}.max_pose_priced_positions)
    j["simplify"]["max_pose_priced_positions"] = s.simplify.max_pose_priced_positions;
  if (s.simplify.max_stand_off_priced_positions != SimplifyOptions{}.max_stand_off_priced_positions)
    j["simplify"]["max_stand_off_priced_positions"] = s.simplify.max_stand_off_priced_positions;
  if (s.simplify.split_positions != SimplifyOptions{}.split_positions)
    j["simplify"]["split_positions"] = s.simplify.split_positions;
  // note: always written: packs baked before the key existed had no ceiling.
  j["simplify"]["max_collapse_cost"] = s.simplify.max_collapse_cost;
  // note: always written: packs baked before the key existed had no floor.
  j["simplify"]["small_area_floor"] = s.simplify.small_area_floor;
  // note: always written: packs baked before the key existed kept no joint ends.
  j["simplify"]["keep_joint_ends"] = s.simplify.keep_joint_ends;
  j["simplify"]["ranges"] = std::filesystem::path(s.simplify.ranges_file).filename().string();
  j["level_errors"]["samples"] = s.level_errors.samples;
  j["level_errors"]["fps"] = s.level_errors.fps;
  j["animation"]["fps"] = s.animation.fps;
  j["animation"]["encoding"] = name_of(kEncodings, s.animation.encoding);
  j["animation"]["root_motion"] = s.animation.extract_root_motion;
  j["animation"]["max_error"] = s.pack.animation_error;
  j["partition"]["size"] = s.partition.size;
  j["partition"]["neck_height"] =
      s.partition.neck_height ? Json(*s.partition.neck_height) : Json(nullptr);
  j["partition"]["waist_height"] =
      s.partition.waist_height ? Json(*s.partition.waist_height) : Json(nullptr);
  j["geometry"]["codec"] = name_of(kCodecs, s.pack.codec);
  j["geometry"]["position_bits"] = s.pack.position_bits;
  j["geometry"]["normal_bits"] = s.pack.normal_bits;
  j["geometry"]["uv_bits"] = s.pack.uv_bits;
  j["geometry"]["weight_bits"] = s.pack.weight_bits;
  j["pack"]["compression"] = name_of(kCompressions, s.pack.compression);
  j["pack"]["images"] = name_of(kImageCodings, s.optimize_images);
  // note: only when given, so packs baked without variants keep their settings text.
  static const char* const kRegions[3] = {"head", "upper_body", "trousers"};
  for (int r = 0; r < 3; ++r)
    for (const std::string& file : s.variant_images[r])
      j["variants"][kRegions[r]].push_back(std::filesystem::path(file).filename().string());
  if (s.impostor.views > 0) {  // note: only when on, so other packs keep their settings text
    j["impostor"]["views"] = s.impostor.views;
    j["impostor"]["frames_per_clip"] = s.impostor.frames_per_clip;
    j["impostor"]["height"] = s.impostor.height;
  }
  return j.dump();
}

}  // namespace crowdbake
