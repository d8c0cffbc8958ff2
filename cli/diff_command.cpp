// `crowdbake diff A B [--json] [--tolerance T] [--ignore SECTION,...]`: semantic comparison
// of two packs for content CI (docs/pack-diff.md). Exit 0 equal within tolerance, 1
// different, 2 error: unlike the other commands a bad pack is exit 2, so a CI script can
// tell "changed" from "could not compare".
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/pack_file.h"
#include "crowdbake/formats/pack_diff.h"
#include "crowdbake/pipeline/error.h"

namespace crowdbake::cli {
namespace {

constexpr size_t kMaxLinesPerSection = 20;  // the JSON has them all

const char* status_word(const DiffSection& s) {
  if (s.info_only) return "info";
  if (!s.differs) return "same";
  return s.ignored ? "ignored" : "DIFFERS";
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

void print_text(const DiffSettings& settings, const PackDiff& diff) {
  std::printf("A %s\nB %s\n", settings.a.c_str(), settings.b.c_str());
  std::printf("tolerance %g (lengths relative to the bbox diagonal %g, other values absolute)\n",
              diff.tolerance, diff.diagonal);
  for (const DiffSection& s : diff.sections) {
    std::printf("  %-12s %-8s %s\n", s.name.c_str(), status_word(s), s.summary.c_str());
    for (size_t i = 0; i < s.differences.size() && i < kMaxLinesPerSection; ++i)
      std::printf("  %-12s %-8s - %s\n", "", "", s.differences[i].c_str());
    if (s.differences.size() > kMaxLinesPerSection)
      std::printf("  %-12s %-8s - ... and %zu more (see --json)\n", "", "",
                  s.differences.size() - kMaxLinesPerSection);
  }
  const std::vector<std::string> differing = diff.differing();
  if (differing.empty())
    std::printf("equal within tolerance\n");
  else
    std::printf("different: %s\n", join(differing).c_str());
}

nlohmann::ordered_json to_json(const DiffSettings& settings, const PackDiff& diff) {
  nlohmann::ordered_json j;
  j["a"] = settings.a;
  j["b"] = settings.b;
  j["tolerance"] = diff.tolerance;
  j["diagonal"] = diff.diagonal;
  j["equal"] = diff.equal();
  j["differences"] = diff.differing();
  j["ignored"] = settings.ignore;
  j["sections"] = nlohmann::ordered_json::object();
  for (const DiffSection& s : diff.sections) {
    nlohmann::ordered_json section;
    section["status"] = status_word(s);
    section["differs"] = s.differs;
    section["summary"] = s.summary;
    section["differences"] = s.differences;
    for (const auto& [key, value] : s.figures.items()) section[key] = value;
    j["sections"][s.name] = section;
  }
  return j;
}

}  // namespace

int run_diff(const DiffSettings& settings) {
  // note: errors are caught here, not in main.cpp, because exit 1 means "different".
  try {
    const PackFile a = load_pack_file(settings.a);
    const PackFile b = load_pack_file(settings.b);
    const PackDiff diff = diff_packs(a, b, {settings.tolerance, settings.ignore});
    if (settings.json)
      std::cout << to_json(settings, diff).dump(2) << "\n";
    else
      print_text(settings, diff);
    return diff.equal() ? 0 : 1;
  } catch (const Error& e) {
    std::cerr << "error: " << crowdbake::status_of(e).message() << "\n";
  } catch (const std::bad_alloc&) {
    std::cerr << "error: out of memory\n";
  } catch (const std::exception& e) {
    std::cerr << "error: internal error: " << e.what() << " (please report this with the packs)\n";
  }
  return 2;
}

}  // namespace crowdbake::cli
