#include "cli/render_profile.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>

namespace crowdbake::cli {

runtime::gpu::FrameProfile mean_profile(const std::vector<runtime::gpu::FrameProfile>& frames) {
  runtime::gpu::FrameProfile mean;
  if (frames.empty()) return mean;
  std::map<std::string, size_t> index;
  std::vector<int> seen;
  for (const runtime::gpu::FrameProfile& f : frames)
    for (const runtime::gpu::PassTiming& p : f.passes) {
      auto [it, added] = index.emplace(p.name, mean.passes.size());
      if (added) {
        mean.passes.push_back({p.name, 0.0, 0.0});
        seen.push_back(0);
      }
      mean.passes[it->second].cpu_ms += p.cpu_ms;
      mean.passes[it->second].gpu_ms += p.gpu_ms;
      ++seen[it->second];
    }
  for (size_t i = 0; i < mean.passes.size(); ++i) {
    mean.passes[i].cpu_ms /= seen[i];
    mean.passes[i].gpu_ms /= seen[i];
  }
  double instances = 0, visible = 0, drawn = 0, overflow = 0, vertices = 0, triangles = 0;
  for (const runtime::gpu::FrameProfile& f : frames) {
    instances += f.instances;
    visible += f.visible;
    drawn += f.drawn;
    overflow += f.overflow;
    vertices += static_cast<double>(f.vertices);
    triangles += static_cast<double>(f.triangles);
  }
  const double n = static_cast<double>(frames.size());
  mean.instances = static_cast<uint32_t>(std::lround(instances / n));
  mean.visible = static_cast<uint32_t>(std::lround(visible / n));
  mean.drawn = static_cast<uint32_t>(std::lround(drawn / n));
  mean.overflow = static_cast<uint32_t>(std::lround(overflow / n));
  mean.vertices = static_cast<uint64_t>(std::llround(vertices / n));
  mean.triangles = static_cast<uint64_t>(std::llround(triangles / n));
  return mean;
}

std::string format_profile(const runtime::gpu::FrameProfile& profile, const std::string& title) {
  std::string out = title + "\n";
  char line[160];
  std::snprintf(line, sizeof line, "  %-22s %10s %10s\n", "pass", "cpu ms", "gpu ms");
  out += line;
  double cpu = 0, gpu = 0;
  for (const runtime::gpu::PassTiming& p : profile.passes) {
    std::snprintf(line, sizeof line, "  %-22s %10.3f %10.3f\n", p.name.c_str(), p.cpu_ms, p.gpu_ms);
    out += line;
    cpu += p.cpu_ms;
    gpu += p.gpu_ms;
  }
  std::snprintf(line, sizeof line, "  %-22s %10.3f %10.3f\n", "total", cpu, gpu);
  out += line;
  std::snprintf(
      line, sizeof line,
      "  instances %u, visible %u, drawn %u (%u as impostors), not drawn (buffer full) %u\n"
      "  vertices %llu, triangles %llu\n",
      profile.instances, profile.visible, profile.drawn, profile.impostors, profile.overflow,
      static_cast<unsigned long long>(profile.vertices),
      static_cast<unsigned long long>(profile.triangles));
  out += line;
  return out;
}

std::string stats_json(const std::vector<runtime::gpu::FrameProfile>& frames,
                       const std::vector<float>& times, const std::string& device) {
  nlohmann::ordered_json out;
  out["device"] = device;
  out["frames"] = nlohmann::ordered_json::array();
  for (size_t i = 0; i < frames.size(); ++i) {
    const runtime::gpu::FrameProfile& f = frames[i];
    nlohmann::ordered_json j;
    j["time"] = i < times.size() ? times[i] : 0.0f;
    j["instances"] = f.instances;
    j["visible"] = f.visible;
    j["drawn"] = f.drawn;
    j["not_drawn"] = f.overflow;
    j["impostors"] = f.impostors;
    j["vertices"] = f.vertices;
    j["triangles"] = f.triangles;
    j["budget"] = f.budget;
    j["budget_exceeded"] = f.budget_exceeded;
    j["lod_mode"] = f.lod_mode;
    j["error_step"] = f.error_step;
    if (!f.lod_note.empty()) j["lod_note"] = f.lod_note;
    j["vertex_shader_skinned"] = f.vertex_shader_skinned;
    j["level_cache"] = {
        {"levels_drawn", f.levels_drawn}, {"levels_built", f.levels_built}, {"coarser", f.coarser}};
    const runtime::gpu::GpuMemory& m = f.memory;
    j["gpu_bytes"] = {{"total", m.total},
                      {"per_type", m.per_type},
                      {"level_cache", m.level_cache},
                      {"per_instance", m.per_instance},
                      {"instance_capacity", m.instance_capacity},
                      {"skinning", m.skinning}};
    nlohmann::ordered_json passes = nlohmann::ordered_json::array();
    double cpu = 0, gpu = 0;
    for (const runtime::gpu::PassTiming& p : f.passes) {
      passes.push_back({{"name", p.name}, {"cpu_ms", p.cpu_ms}, {"gpu_ms", p.gpu_ms}});
      cpu += p.cpu_ms;
      gpu += p.gpu_ms;
    }
    j["passes"] = std::move(passes);
    j["cpu_ms"] = cpu;
    j["gpu_ms"] = gpu;
    out["frames"].push_back(std::move(j));
  }
  return out.dump(2) + "\n";
}

}  // namespace crowdbake::cli
