// crowdbake bake: import → build_pack → write_pack, written atomically, with an optional
// depfile and JSON report. Progress goes to stderr on a terminal only.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/missing_joints.h"
#include "crowdbake/formats/pack.h"
#include "crowdbake/pipeline/bake.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/import.h"
#include "crowdbake/pipeline/output_file.h"

namespace crowdbake::cli {
namespace {

std::string tag_name(uint32_t tag) {
  std::string s(4, ' ');
  for (int i = 0; i < 4; ++i) s[i] = static_cast<char>((tag >> (8 * i)) & 0xff);
  return s;
}

// Make/Ninja depfile: "OUT: dep dep ..." with spaces escaped. Only files that exist are
// listed: a missing texture path from an artist's machine would break the build tool.
std::string depfile_text(const std::string& output, const std::vector<std::string>& files) {
  auto escape = [](const std::string& p) {
    std::string out;
    for (char c : p) {
      if (c == ' ' || c == '#') out += '\\';
      if (c == '$') out += '$';
      out += c;
    }
    return out;
  };
  std::string text = escape(output) + ":";
  for (const std::string& f : files)
    if (std::filesystem::is_regular_file(f)) text += " \\\n  " + escape(f);
  return text + "\n";
}

class Progress {
 public:
  explicit Progress(bool on) : on_(on) {}
  void say(const std::string& what) const {
    if (on_) std::fprintf(stderr, "crowdbake: %s\n", what.c_str());
  }

 private:
  bool on_;
};

}  // namespace

int run_bake(const BakeCommandSettings& s) {
  BakeSettings settings;
  if (!s.config.empty()) throw_if_failed(read_bake_config(s.config, settings));
  settings.simplify.threads = s.jobs;
  settings.pack.threads = s.jobs;
  const Progress progress(!s.quiet && ::isatty(STDERR_FILENO));
  const auto start = std::chrono::steady_clock::now();

  progress.say("importing " + s.input);
  SkinnedAsset asset;
  throw_if_failed(import_asset(s.input, s.import, asset));
  progress.say("baking " + std::to_string(asset.vertex_count()) + " vertices, " +
               std::to_string(asset.skeleton.joints.size()) + " joints, " +
               std::to_string(asset.clips.size()) + " clips");
  BakeReport report;
  StoredAnimation animation;
  PackContents pack;
  throw_if_failed(build_pack(asset, settings, report, pack, &animation));
  progress.say("writing " + s.output);
  const auto write_start = std::chrono::steady_clock::now();
  std::vector<uint8_t> bytes;
  // note: a pack the bake built breaks no rule, so a failure here is a codec's.
  if (const Status w = write_pack(pack, settings.pack, animation, bytes); !w.ok())
    throw Error(Error::Kind::kOutput, s.output, w.message());
  throw_if_failed(write_file_atomically(s.output, bytes));
  report.stages.push_back(
      {"write",
       std::chrono::duration<double>(std::chrono::steady_clock::now() - write_start).count()});
  const double total =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::vector<PackChunk> chunks;
  read_pack_chunks(bytes.data(), bytes.size(), chunks);

  if (!s.depfile.empty()) {
    std::vector<std::string> files = asset.files;
    if (!s.config.empty()) files.push_back(s.config);
    if (!settings.simplify.ranges_file.empty()) files.push_back(settings.simplify.ranges_file);
    for (const auto& region : settings.variant_images)
      files.insert(files.end(), region.begin(), region.end());
    throw_if_failed(write_file_atomically(s.depfile, depfile_text(s.output, files)));
  }
  const bool summary = !s.quiet && ::isatty(STDOUT_FILENO);
  // note: the joints are told from the weights as the pack stores them (quantized), which is
  // what `inspect` and the runtime read; the bake's own floats can break ties otherwise.
  const std::vector<float> weights = !s.report.empty() || summary
                                         ? stored_weights(pack.geometry, settings.pack)
                                         : std::vector<float>{};
  if (!s.report.empty()) {
    nlohmann::ordered_json j;
    j["input"] = {{"file", s.input},
                  {"joints", asset.skeleton.joints.size()},
                  {"vertices", asset.vertex_count()},
                  {"welded_vertices", asset.stats.vertices_welded},
                  {"triangles", asset.triangle_count()},
                  {"clips", asset.clips.size()}};
    j["output"] = {{"file", s.output}, {"bytes", bytes.size()}};
    j["settings"] = nlohmann::ordered_json::parse(pack.settings_json);
    j["warnings"] = report.warnings;
    j["stages"] = nlohmann::json::array();
    for (const BakeStage& stage : report.stages)
      j["stages"].push_back({{"name", stage.name}, {"seconds", stage.seconds}});
    j["seconds"] = total;
    j["lod"] = {{"min_vertices", pack.progressive.min_vertices},
                {"seamless_min_vertices", report.simplify.seamless_min_vertices},
                {"stopped_at_cost_ceiling", report.simplify.stopped_at_cost_ceiling},
                {"unpriced_collapses", report.simplify.unpriced_collapses},
                {"collapses_before_stand_off", report.simplify.collapses_before_stand_off},
                {"split_collapses", report.simplify.split_collapses},
                {"max_vertices", pack.geometry.vertex_count()},
                {"max_triangles", pack.geometry.triangle_count()},
                {"joints_missing_at_min", joints_missing_at_min_json(pack, weights)},
                {"joints_unreached_at_min", joints_unreached_at_min_json(pack, weights)}};
    j["chunks"] = nlohmann::json::array();
    for (const PackChunk& c : chunks)
      j["chunks"].push_back({{"tag", tag_name(c.tag)}, {"bytes", c.size}});
    j["accuracy"] = {
        {"animation_mean_error", report.animation_mean_error},
        {"animation_max_error", report.animation_max_error},
        {"animation_coding", report.animation_coding},
        {"animation_coding_mean_error", report.animation_coding_mean_error},
        {"animation_coding_max_error", report.animation_coding_max_error},
        {"note",
         "animation: the texture as the pack stores it vs direct evaluation at the baked frames; "
         "animation_coding: what the pack's animation coding alone moved a vertex; both / bbox "
         "diagonal"}};
    j["images"] = {{"count", pack.images.size()}, {"bytes_saved", report.image_bytes_saved}};
    j["partition"] = {{"heights", report.partition_heights},
                      {"neck_height", pack.partition.neck_height},
                      {"waist_height", pack.partition.waist_height}};
    throw_if_failed(write_file_atomically(s.report, j.dump(2) + "\n"));
  }

  if (summary) {
    std::printf("%s -> %s (%zu bytes, %.2f s)\n", s.input.c_str(), s.output.c_str(), bytes.size(),
                total);
    std::printf("  %-10s %8s\n", "stage", "seconds");
    for (const BakeStage& stage : report.stages)
      std::printf("  %-10s %8.3f\n", stage.name.c_str(), stage.seconds);
    std::printf("  %-10s %8s\n", "chunk", "bytes");
    for (const PackChunk& c : chunks)
      std::printf("  %-10s %8llu\n", tag_name(c.tag).c_str(),
                  static_cast<unsigned long long>(c.size));
    std::printf("  lod        %u..%u vertices\n", pack.progressive.min_vertices,
                pack.geometry.vertex_count());
    // note: an artist baking by hand sees here that a foot or a head is gone at the far end of
    // a crowd, and which setting keeps it (docs/simplification.md, "Joint ends").
    const std::vector<MissingJoint> lost = joints_unreached_at_min(pack, weights);
    if (!lost.empty()) {
      // note: a part is named by its topmost lost joint (a palm, not its fingers as well).
      std::vector<char> is_lost(pack.joints.size(), 0);
      for (const MissingJoint& m : lost) is_lost[m.joint] = 1;
      std::string names;
      for (const MissingJoint& m : lost) {
        const int parent = pack.joints[m.joint].parent;
        if (parent < 0 || !is_lost[static_cast<size_t>(parent)])
          names += (names.empty() ? "" : ", ") + m.name;
      }
      std::printf(
          "  lost       at %u vertices: %s, with the joints below them (no vertex left%s)\n",
          pack.progressive.min_vertices, names.c_str(),
          settings.simplify.keep_joint_ends
              ? ""
              : "; simplify.keep_joint_ends, off here, keeps one of each");
    }
    std::printf("  animation  max error %.2e of the bbox diagonal (%s coding: %.2e of it)\n",
                report.animation_max_error, report.animation_coding.c_str(),
                report.animation_coding_max_error);
    for (const std::string& w : report.warnings) std::printf("  warning    %s\n", w.c_str());
  }
  return 0;
}

}  // namespace crowdbake::cli
