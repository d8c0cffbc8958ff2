#include "cli/render_profile.h"

#include <cmath>
#include <cstdio>
#include <map>

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
  std::snprintf(line, sizeof line,
                "  instances %u, visible %u, drawn %u, not drawn (buffer full) %u\n"
                "  vertices %llu, triangles %llu\n",
                profile.instances, profile.visible, profile.drawn, profile.overflow,
                static_cast<unsigned long long>(profile.vertices),
                static_cast<unsigned long long>(profile.triangles));
  out += line;
  return out;
}

}  // namespace crowdbake::cli
