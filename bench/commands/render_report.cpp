#include "commands/render_report.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/output_file.h"

namespace crowdbake::bench {
namespace {

std::string num(double x, const char* format = "%.2f") {
  if (!std::isfinite(x)) return x > 0 ? "inf" : "-";
  char text[48];
  std::snprintf(text, sizeof text, format, x);
  return text;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

void print_render_rows(const std::vector<RenderBenchRow>& rows, bool header) {
  if (header)
    std::printf("%9s %-10s %9s %9s %9s %12s %8s %8s %8s %8s %8s  %s\n", "instances", "mode",
                "budget", "frame ms", "gpu ms", "triangles", "drawn", "PSNR dB", "PSNR/4",
                "mean|d|", "speed-up", "note");
  for (const RenderBenchRow& r : rows)
    std::printf("%9u %-10s %9s %9s %9s %12llu %8u %8s %8s %8s %8s  %s\n", r.instances,
                r.mode.c_str(), r.budget ? std::to_string(r.budget).c_str() : "-",
                r.frames ? num(r.frame_ms, "%.1f").c_str() : "-",
                r.frames ? num(r.gpu_ms, "%.1f").c_str() : "-",
                static_cast<unsigned long long>(r.triangles), r.drawn, num(r.psnr).c_str(),
                num(r.psnr_4x).c_str(), num(r.mean_abs_diff, "%.3f").c_str(),
                num(r.speedup, "%.1fx").c_str(), r.note.c_str());
  std::fflush(stdout);
}

void print_pop_rows(const RenderBenchResult& result) {
  std::printf(
      "popping: %u instances, camera dolly over %u frames (animation frozen), per frame "
      "pair: change = mean |dLoD - dFull|, /4 = on 4x-shrunk images; pops = %% of "
      "4x-shrunk pixels with |dLoD - dFull| > %d; jump = |e(t+1) - e(t)|, e = mean "
      "|LoD - full| (8-bit units)\n",
      result.pop_instances, result.pop_frames, kPopThreshold);
  std::printf("  %-10s %9s %-16s %10s %8s %8s %8s %8s %8s %8s %8s %8s %8s\n", "mode", "budget",
              "chosen for", "triangles", "change", "max", "change/4", "max/4", "pops %", "max %",
              "jump", "max jump", "PSNR dB");
  for (const PopRow& p : result.pops)
    std::printf("  %-10s %9s %-16s %10.0f %8s %8s %8s %8s %8s %8s %8s %8s %8s\n", p.mode.c_str(),
                p.budget ? std::to_string(p.budget).c_str() : "-", p.why.c_str(), p.mean_triangles,
                num(p.mean_change, "%.3f").c_str(), num(p.max_change, "%.3f").c_str(),
                num(p.mean_change_4x, "%.4f").c_str(), num(p.max_change_4x, "%.4f").c_str(),
                num(p.mean_pop_pixels, "%.4f").c_str(), num(p.max_pop_pixels, "%.4f").c_str(),
                num(p.mean_jump, "%.4f").c_str(), num(p.max_jump, "%.4f").c_str(),
                num(p.mean_psnr).c_str());
  std::fflush(stdout);
}

void write_render_csv(const RenderBenchResult& result, const std::string& path) {
  std::ostringstream out;
  out << "device,width,height,shadows,instances,visible,mode,budget,frames,frame_ms,gpu_ms,"
         "vertices,triangles,drawn,overflow,psnr_db,psnr_4x_db,mean_abs_diff,speedup_vs_full,"
         "note\n";
  for (const RenderBenchRow& r : result.rows)
    out << csv_field(result.device) << ',' << result.width << ',' << result.height << ','
        << (result.shadows ? 1 : 0) << ',' << r.instances << ',' << r.visible << ',' << r.mode
        << ',' << r.budget << ',' << r.frames << ',' << num(r.frame_ms, "%.3f") << ','
        << num(r.gpu_ms, "%.3f") << ',' << r.vertices << ',' << r.triangles << ',' << r.drawn << ','
        << r.overflow << ',' << num(r.psnr, "%.3f") << ',' << num(r.psnr_4x, "%.3f") << ','
        << num(r.mean_abs_diff, "%.4f") << ',' << num(r.speedup, "%.3f") << ',' << csv_field(r.note)
        << '\n';
  throw_if_failed(write_file_atomically(path, out.str()));
}

void write_pop_csv(const RenderBenchResult& result, const std::string& path) {
  std::ostringstream out;
  out << "device,width,height,instances,frames,mode,budget,chosen_for,mean_triangles,mean_change,"
         "p95_change,max_change,mean_change_4x,p95_change_4x,max_change_4x,mean_error_jump,"
         "max_error_jump,mean_pop_pixels_percent,max_pop_pixels_percent,mean_psnr_db\n";
  for (const PopRow& p : result.pops)
    out << csv_field(result.device) << ',' << result.width << ',' << result.height << ','
        << result.pop_instances << ',' << result.pop_frames << ',' << p.mode << ',' << p.budget
        << ',' << csv_field(p.why) << ',' << num(p.mean_triangles, "%.0f") << ','
        << num(p.mean_change, "%.5f") << ',' << num(p.p95_change, "%.5f") << ','
        << num(p.max_change, "%.5f") << ',' << num(p.mean_change_4x, "%.5f") << ','
        << num(p.p95_change_4x, "%.5f") << ',' << num(p.max_change_4x, "%.5f") << ','
        << num(p.mean_jump, "%.5f") << ',' << num(p.max_jump, "%.5f") << ','
        << num(p.mean_pop_pixels, "%.5f") << ',' << num(p.max_pop_pixels, "%.5f") << ','
        << num(p.mean_psnr, "%.3f") << '\n';
  throw_if_failed(write_file_atomically(path, out.str()));
}

void write_render_plot_data(const RenderBenchResult& result, const std::string& path) {
  std::ostringstream out;
  uint32_t block = 0;
  for (size_t i = 0; i < result.rows.size(); ++i) {
    const RenderBenchRow& r = result.rows[i];
    if (i == 0 || r.instances != result.rows[i - 1].instances) {
      if (i > 0) out << "\n\n";
      out << "# block " << block++ << ": " << r.instances
          << " instances; mode budget frame_ms psnr triangles\n";
    }
    // note: a frame whose corner buffer overflowed misses instances; its point would mislead.
    if (r.frames == 0 || r.overflow > 0) continue;
    // note: an identical image (full vs itself) has infinite PSNR; the plot puts it on a
    // ceiling so the reference still shows.
    out << r.mode << ' ' << r.budget << ' ' << num(r.frame_ms, "%.3f") << ' '
        << (std::isfinite(r.psnr) ? num(r.psnr, "%.3f") : std::string("60")) << ' ' << r.triangles
        << ' ' << (std::isfinite(r.psnr_4x) ? num(r.psnr_4x, "%.3f") : std::string("60")) << '\n';
  }
  throw_if_failed(write_file_atomically(path, out.str()));
}

void write_pop_plot_data(const RenderBenchResult& result, const std::string& path) {
  std::ostringstream out;
  out << "# popping, " << result.pop_instances << " instances; pair";
  for (const PopRow& p : result.pops)
    out << ' ' << p.mode << '/' << p.why << "(change_4x jump pops%)";
  out << '\n';
  const size_t pairs = result.pops.empty() ? 0 : result.pops[0].per_pair_4x.size();
  for (size_t k = 0; k < pairs; ++k) {
    out << k;
    for (const PopRow& p : result.pops)
      out << ' ' << num(p.per_pair_4x[k], "%.5f") << ' ' << num(p.error_jumps[k], "%.5f") << ' '
          << num(p.pop_pixels[k], "%.5f");
    out << '\n';
  }
  throw_if_failed(write_file_atomically(path, out.str()));
}

}  // namespace crowdbake::bench
