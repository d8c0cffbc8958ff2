// The Markdown tables and JSON of `crowdbake bench simplify` (bench/commands/report*.cpp),
// and docs/accuracy.md quoting the tables of the run on record.
#include "commands/report.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "crowdbake/pipeline/error.h"
#include "temp_dir.h"

namespace crowdbake::bench {
namespace {

BenchLevel level(double target, double kept, double rms, double max) {
  BenchLevel l;
  l.target = target;
  l.kept_positions = kept;
  l.kept_vertices = kept;
  l.triangles = 10;
  l.error.mean_rms = rms;
  l.error.max = max;
  l.measured = true;
  return l;
}

BenchRow row(const std::string& config, const std::string& method, std::vector<BenchLevel> levels) {
  BenchRow r;
  r.config = config;
  r.method = method;
  r.seconds = 0.25;
  r.peak_rss_mb = method == "gltfpack" ? -1.0 : 3.5;
  r.levels = std::move(levels);
  return r;
}

// Two assets at 10% and 2%, both keeping 7% at 2% (a minimum above the fraction). The first
// is below both peers at 10% and above gltfpack at 2%; the second is above gltfpack at 10%,
// and its gltfpack 2% level was never measured (below meshopt is below both there).
BenchResult two_assets() {
  BenchResult result;
  result.fractions = {0.10, 0.02};
  result.frame_stride = 3;
  result.total_seconds = 12.0;
  result.gltfpack = "gltfpack";
  BenchAsset a;
  a.name = "first";
  a.vertices = 100, a.positions = 90, a.triangles = 160, a.clips = 2, a.frames = 40;
  a.seconds_error = 1.4;
  a.rows = {
      row("S=16 exact", "dqem", {level(0.10, 0.10, 0.01, 0.03), level(0.02, 0.07, 0.02, 0.125)}),
      row("meshopt", "meshopt", {level(0.10, 0.10, 0.02, 0.05), level(0.02, 0.07, 0.05, 0.2)}),
      row("gltfpack", "gltfpack", {level(0.10, 0.10, 0.04, 0.04), level(0.02, 0.07, 0.04, 0.1)})};
  BenchAsset b = a;
  b.name = "second";
  b.rows[0].levels[0].error.max = 0.045;  // above gltfpack's 0.04
  b.rows[2].levels[1] = BenchLevel{};
  b.rows[2].levels[1].target = 0.02;
  result.assets = {a, b};
  return result;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

bool has_line(const std::string& text, const std::string& line) {
  for (const std::string& l : lines(text))
    if (l == line) return true;
  return false;
}

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(MarkdownTables, CountWinsAgainstTheBetterPeer) {
  const std::string md = markdown_tables(two_assets(), "S=16 exact");
  // RMS over the better peer: 0.01/0.02 on both at 10%; 0.02/0.04 and 0.02/0.05 at 2%.
  EXPECT_TRUE(has_line(md, "| S=16 exact | 1 of 2 / 0.50 | 1 of 2 / 0.45 |")) << md;
}

TEST(MarkdownTables, BoldWhereBelowBothPeersAndBracketsAMinimumAboveTheFraction) {
  const std::string md = markdown_tables(two_assets(), "S=16 exact");
  EXPECT_TRUE(
      has_line(md, "| first | **3.00** / 5.00 / 4.00 | 0.50 | 12.5 (7%) / 20.0 / 10.0 | 0.50 |"))
      << md;
  EXPECT_TRUE(
      has_line(md, "| second | 4.50 / 5.00 / 4.00 | 0.50 | **12.5** (7%) / 20.0 / - | 0.40 |"))
      << md;
  EXPECT_TRUE(has_line(md, "| gltfpack | 0.250 | - | 4.00 / 4.00 | 4.00 / 10.0 (7%) |")) << md;
  EXPECT_TRUE(has_line(md,
                       "100 vertices, 90 positions, 160 triangles, 2 clips, 40 frames; "
                       "animated error measured in 1 s"))
      << md;
}

TEST(MarkdownTables, AnUnknownDefaultConfigurationLeavesItsCellsEmpty) {
  const std::string md = markdown_tables(two_assets(), "S=64 exact");
  EXPECT_TRUE(has_line(md, "| first | - | - | - | - |")) << md;
}

TEST(BenchJson, ReadsBackWhatItWrote) {
  const test::TempDir dir;
  const BenchResult result = two_assets();
  const std::string path = (dir / "accuracy.json").string();
  write_json(result, path);
  const BenchResult back = read_json(path);
  ASSERT_EQ(back.assets.size(), 2u);
  EXPECT_EQ(back.assets[1].rows[2].peak_rss_mb, -1.0);
  EXPECT_FALSE(back.assets[1].rows[2].levels[1].measured);
  EXPECT_EQ(back.assets[0].rows[0].levels[1].error.max, 0.125);
  EXPECT_EQ(markdown_tables(back, "S=16 exact"), markdown_tables(result, "S=16 exact"));
}

TEST(BenchJson, AFileOfAnotherKindIsAnErrorNamingIt) {
  const test::TempDir dir;
  const std::string path = (dir / "other.json").string();
  std::ofstream(path) << "{\"assets\": [{\"name\": 3}]}";
  try {
    read_json(path);
    FAIL() << "read";
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(std::string(e.what()).find("bench simplify"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_json((dir / "missing.json").string()), Error);
}

// The run on record: docs/data/accuracy-tables.md is what its accuracy.json gives, and the two
// tables docs/accuracy.md shows are copies of that file's. A rerun of the bench that is not
// copied into the doc fails here.
TEST(AccuracyDocs, QuoteTheTablesOfTheRunOnRecord) {
  const std::string data = std::string(CROWDBAKE_SOURCE_DIR) + "/docs/data/";
  const std::string tables =
      markdown_tables(read_json(data + "accuracy.json"), default_config_label());
  EXPECT_EQ(tables, read(data + "accuracy-tables.md"))
      << "run: crowdbake bench simplify --tables-from docs/data/accuracy.json";
  const std::vector<std::string> doc =
      lines(read(std::string(CROWDBAKE_SOURCE_DIR) + "/docs/accuracy.md"));
  const std::vector<std::string> generated = lines(tables);
  for (const std::string head : {"| config | 25%: max below both", "| asset | 25%: max |"}) {
    size_t g = 0;
    while (g < generated.size() && generated[g].rfind(head, 0) != 0) ++g;
    ASSERT_LT(g, generated.size()) << head;
    size_t d = 0;
    while (d < doc.size() && doc[d] != generated[g]) ++d;
    ASSERT_LT(d, doc.size()) << "docs/accuracy.md lacks the table " << generated[g];
    for (; g < generated.size() && !generated[g].empty(); ++g, ++d)
      ASSERT_EQ(d < doc.size() ? doc[d] : "", generated[g])
          << "docs/accuracy.md: copy the table from docs/data/accuracy-tables.md";
  }
}

}  // namespace
}  // namespace crowdbake::bench
