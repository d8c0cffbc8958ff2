// The Markdown tables of `crowdbake bench simplify` (accuracy-tables.md beside its CSV):
// written by the program from the run itself, so the docs quote them instead of copying
// numbers by hand (copies went stale for several sessions).
#include <cmath>
#include <cstdio>
#include <sstream>

#include "commands/report.h"

namespace crowdbake::bench {
namespace {

// An error in % of the diagonal: two decimals below 10, one above.
std::string percent(double fraction) {
  if (!std::isfinite(fraction)) return "-";
  const double x = 100.0 * fraction;
  char text[32];
  std::snprintf(text, sizeof text, x < 10.0 ? "%.2f" : "%.1f", x);
  return text;
}

std::string fixed(double x, int decimals) {
  if (!std::isfinite(x)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, x);
  return text;
}

std::string fraction_label(double f) { return fixed(100.0 * f, 0) + "%"; }

// " (7%)" where a level keeps more than 1.1× the positions asked for (a minimum above the
// fraction, or a peer that could not go lower); nothing otherwise.
std::string reached(const BenchLevel& level) {
  return level.kept_positions > 1.1 * level.target
             ? " (" + fixed(100.0 * level.kept_positions, 0) + "%)"
             : std::string();
}

// A table's head: the column names and under them their alignments ("---", "---:").
void header(std::ostringstream& out, const std::vector<std::string>& columns,
            const std::vector<std::string>& aligns) {
  out << "|";
  for (const std::string& c : columns) out << " " << c << " |";
  out << "\n|";
  for (const std::string& a : aligns) out << a << "|";
  out << "\n";
}

void summary_table(std::ostringstream& out, const BenchResult& result) {
  std::vector<std::string> columns = {"config"}, aligns = {"---"};
  for (double f : result.fractions) {
    columns.push_back(fraction_label(f) + ": max below both / RMS ÷ better peer");
    aligns.push_back("---:");
  }
  header(out, columns, aligns);
  for (const std::string& config : result_configs(result)) {
    out << "| " << config << " |";
    for (double f : result.fractions) {
      const Versus v = versus_peers(result, config, f);
      out << " " << v.max_below_both << " of " << v.assets << " / "
          << fixed(v.assets ? v.rms_ratio_sum / v.assets : NAN, 2) << " |";
    }
    out << "\n";
  }
}

// Max as DQEM / meshopt / gltfpack (bold where below both) and mean-RMS over the better peer.
void default_table(std::ostringstream& out, const BenchResult& result, const std::string& config) {
  std::vector<std::string> columns = {"asset"}, aligns = {"---"};
  for (double f : result.fractions) {
    columns.insert(columns.end(), {fraction_label(f) + ": max", fraction_label(f) + ": RMS ratio"});
    aligns.insert(aligns.end(), {"---", "---:"});
  }
  header(out, columns, aligns);
  for (const BenchAsset& a : result.assets) {
    out << "| " << a.name << " |";
    for (double f : result.fractions) {
      const AgainstPeers p = against_peers(a, config, f);
      if (!p.mine) {
        out << " - | - |";
        continue;
      }
      std::string max = percent(p.mine->error.max);
      if (p.mine->error.max < p.peer_max) max = "**" + max + "**";
      out << " " << max << reached(*p.mine) << " / "
          << (p.meshopt ? percent(p.meshopt->error.max) : "-") << " / "
          << (p.gltfpack ? percent(p.gltfpack->error.max) : "-") << " | "
          << (std::isfinite(p.peer_rms) && p.peer_rms > 0.0
                  ? fixed(p.mine->error.mean_rms / p.peer_rms, 2)
                  : "-")
          << " |";
    }
    out << "\n";
  }
}

void asset_table(std::ostringstream& out, const BenchAsset& a,
                 const std::vector<double>& fractions) {
  out << "### " << a.name << "\n\n"
      << a.vertices << " vertices, " << a.positions << " positions, " << a.triangles
      << " triangles, " << a.clips << " clips, " << a.frames
      << " frames; animated error measured in " << fixed(a.seconds_error, 0) << " s\n\n";
  std::vector<std::string> columns = {"config", "time (s)", "peak RSS (MB)"},
                           aligns = {"---", "---:", "---:"};
  for (double f : fractions) {
    columns.push_back(fraction_label(f) + ": RMS / max");
    aligns.push_back("---");
  }
  header(out, columns, aligns);
  for (const BenchRow& r : a.rows) {
    out << "| " << r.config << " | " << fixed(r.seconds, 3) << " | "
        << (r.peak_rss_mb >= 0.0 ? fixed(r.peak_rss_mb, 1) : "-") << " |";
    for (double f : fractions) {
      const BenchLevel* l = level_at(r, f);
      if (l)
        out << " " << percent(l->error.mean_rms) << " / " << percent(l->error.max) << reached(*l)
            << " |";
      else
        out << " - |";
    }
    out << "\n";
  }
  out << "\n";
}

}  // namespace

std::string markdown_tables(const BenchResult& result, const std::string& default_config) {
  std::ostringstream out;
  out << "# bench simplify: the tables\n\n"
      << "Written by `crowdbake bench simplify` with accuracy.csv and accuracy.json beside it ("
      << result.assets.size() << " assets, frame stride " << result.frame_stride
      << (result.quick ? ", quick" : "") << ", " << fixed(result.total_seconds, 0) << " s"
      << (result.gltfpack.empty() ? "; gltfpack not found, its rows are empty" : "")
      << "). Do not edit: run the bench again, or write this file from a run's JSON with "
         "`crowdbake bench simplify --tables-from accuracy.json`. docs/accuracy.md explains "
         "the measure.\n\n";
  out << "## Every configuration against the peers\n\n"
      << "On how many assets the configuration's animated max is below both peers', and its "
         "mean-RMS over the better peer's, averaged over assets:\n\n";
  summary_table(out, result);
  out << "\n## The default (" << default_config << ") per asset\n\n"
      << "Max in % of the diagonal as DQEM / meshopt / gltfpack (bold: below both peers; in "
         "brackets the fraction of positions kept where the minimum is above the asked one: "
         "the peers were asked for as many) and mean-RMS over the better peer's:\n\n";
  default_table(out, result, default_config);
  out << "\n## Per asset\n\n"
      << "Animated error in % of the bind-pose diagonal, as mean-RMS / max; a bracket gives "
         "the kept fraction of positions actually reached when it differs from the column's. "
         "Time is the simplification alone (DQEM: all levels in one run; peers: the four "
         "final runs summed).\n\n";
  for (const BenchAsset& a : result.assets) asset_table(out, a, result.fractions);
  std::string text = out.str();
  text.pop_back();  // one newline at the end, not a blank line
  return text;
}

}  // namespace crowdbake::bench
