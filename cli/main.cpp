// crowdbake: flags in, calls into the libraries, errors out as one line each.
// Exit codes: 0 success, 1 bad input, 2 usage, 3 output could not be written.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>

#include "cli/commands.h"
#include "cli/huge_pages.h"
#include "cli/render_plan.h"
#include "crowdbake/bench/bench.h"
#include "crowdbake/pipeline/error.h"

namespace {

void add_import_options(CLI::App& command, crowdbake::ImportOptions& options) {
  command.add_option("--character", options.character,
                     "Which character to import when the file holds several (0-based); "
                     "default: the one with the most skinned vertices");
  command.add_option("--importer", options.importer, "auto, gltf or assimp")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, crowdbake::ImporterKind>{
              {"auto", crowdbake::ImporterKind::kAuto},
              {"gltf", crowdbake::ImporterKind::kGltf},
              {"assimp", crowdbake::ImporterKind::kAssimp}},
          CLI::ignore_case));
  command
      .add_option("--import-timeout", options.limits.timeout_seconds,
                  "Seconds one import may take before it is stopped (0: no limit)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  command
      .add_option("--import-memory", options.limits.memory_mib,
                  "Address space in MiB the importing process may use (0: no limit)")
      ->capture_default_str();
  command.add_flag("--strict-textures", options.strict_textures,
                   "A base colour texture that cannot be stored (missing, not PNG/JPEG, "
                   "corrupt, too large) is an error instead of a warning");
  command.add_flag("!--keep-duplicate-vertices", options.weld,
                   "Keep vertices that repeat another of their primitive in every attribute "
                   "(by default they are merged; normals need only agree within 1e-5)");
  command.add_flag("!--import-in-process", options.limits.isolate,
                   "Import in crowdbake's own process (no limits; a crash in the importer "
                   "ends crowdbake): for debugging importers");
}

// Every command's settings, as the flags fill them, and what says which command ran.
struct Commands {
  crowdbake::cli::InspectSettings inspect;
  crowdbake::cli::LodSettings lod;
  crowdbake::bench::BenchSettings bench;
  crowdbake::bench::BenchScaleSettings bench_scale;
  crowdbake::bench::BenchRenderSettings bench_render;
  crowdbake::cli::BakeCommandSettings bake;
  std::string bake_preview;
  crowdbake::cli::DiffSettings diff;
  crowdbake::cli::RenderSettings render;
  crowdbake::cli::PreviewSettings preview;
  std::string preview_cell;
  CLI::App *inspect_cmd = nullptr, *lod_cmd = nullptr, *bench_cmd = nullptr,
           *bench_simplify_cmd = nullptr, *bench_scale_cmd = nullptr, *bench_render_cmd = nullptr,
           *bake_cmd = nullptr, *diff_cmd = nullptr, *render_cmd = nullptr, *preview_cmd = nullptr;
  CLI::Option *frames_opt = nullptr, *fps_opt = nullptr, *budget_opt = nullptr,
              *geomorph_opt = nullptr;
};

void add_inspect(CLI::App& app, Commands& c) {
  crowdbake::cli::InspectSettings& inspect = c.inspect;
  CLI::App* inspect_cmd = c.inspect_cmd =
      app.add_subcommand("inspect", "Describe a character file: skeleton, meshes, clips, warnings");
  inspect_cmd
      ->add_option("FILE", inspect.input,
                   "Character file (.gltf, .glb, .fbx, or anything Assimp reads) or a .crowdpack")
      ->required();
  inspect_cmd->add_flag("--json", inspect.json, "Print one JSON object to stdout");
  add_import_options(*inspect_cmd, inspect.import);
}

void add_lod(CLI::App& app, Commands& c) {
  crowdbake::cli::LodSettings& lod = c.lod;
  CLI::App* lod_cmd = c.lod_cmd =
      app.add_subcommand("lod",
                         "Simplify a character with the pose-aware metric and "
                         "write one level of detail as a skinned .glb");
  lod_cmd->add_option("INPUT", lod.input, "Character file")->required();
  lod_cmd->add_option("-o,--output", lod.output, "Output .glb")->required();
  auto* ratio = lod_cmd->add_option("--ratio", lod.ratio, "Kept fraction of vertices, in (0, 1]");
  auto* count = lod_cmd->add_option("--vertices", lod.vertices, "Kept number of vertices");
  ratio->excludes(count);
  count->excludes(ratio);
  lod_cmd->add_option("--samples", lod.simplify.samples,
                      "Poses S, bind pose included (1 = classic QEM)");
  lod_cmd->add_option("--seed", lod.simplify.seed, "Seed of the pose sampler");
  lod_cmd->add_option("--pose-source", lod.simplify.pose_source, "sampled or clips")
      ->transform(CLI::CheckedTransformer(std::map<std::string, crowdbake::PoseSource>{
          {"sampled", crowdbake::PoseSource::kSampled}, {"clips", crowdbake::PoseSource::kClips}}));
  lod_cmd
      ->add_option("--form", lod.simplify.form,
                   "DQEM form: pullback (one quadric per vertex) or exact")
      ->transform(CLI::CheckedTransformer(std::map<std::string, crowdbake::DqemForm>{
          {"pullback", crowdbake::DqemForm::kPullback}, {"exact", crowdbake::DqemForm::kExact}}));
  lod_cmd->add_option("--max-collapse-cost", lod.simplify.max_collapse_cost,
                      "Stop before the first collapse costing more (normalised quadric units; "
                      "0 = as far as topology allows; default 0.005)");
  lod_cmd->add_option("--small-area-floor", lod.simplify.small_area_floor,
                      "Price a collapse whose faces are smaller than this share of the mean area "
                      "around a live position as if they had it (0 = off; default 0.3; "
                      "docs/simplification.md, \"Small areas\")");
  lod_cmd->add_flag("--keep-joint-ends,!--no-keep-joint-ends", lod.simplify.keep_joint_ends,
                    "The end of every branch of the skeleton keeps a vertex at every level, so "
                    "no foot, head or tail vanishes (the default; --no-keep-joint-ends: the limb "
                    "tips only, lower minimums; docs/simplification.md, \"Joint ends\")");
  lod_cmd->add_option("--measure", lod.measure_fps,
                      "Also measure the level's animated error against the original over every "
                      "clip at this many frames a second (e.g. 10), and say where its max is");
  lod_cmd->add_option("--ranges", lod.simplify.ranges_file,
                      "Per-joint angle ranges (JSON, docs/pose-ranges.md)");
  lod_cmd->add_flag("--quiet", lod.quiet, "Print nothing on success");
  add_import_options(*lod_cmd, lod.import);
}

// "bench render" (a subcommand of "bench").
void add_bench_render(Commands& c) {
  CLI::App* bench_cmd = c.bench_cmd;
  crowdbake::bench::BenchRenderSettings& bench_render = c.bench_render;
  CLI::App* bench_render_cmd = c.bench_render_cmd = bench_cmd->add_subcommand(
      "render",
      "Frame time, triangles and image error of continuous/discrete LoD vs. full resolution on "
      "lavapipe; popping over a camera dolly (docs/performance.md)");
  bench_render_cmd->add_option("--pack", bench_render.pack,
                               "Pack to render (default: bake the generated spectator)");
  bench_render_cmd
      ->add_option("--sizes", bench_render.sizes, "Instance counts (default 1000,10000,50000)")
      ->delimiter(',');
  bench_render_cmd
      ->add_option("--budgets", bench_render.budgets,
                   "LoD budgets N in vertices (default 100000,300000,1000000,3000000,6000000)")
      ->delimiter(',');
  bench_render_cmd
      ->add_option("--pixel-errors", bench_render.pixel_errors,
                   "Error-driven rows: lod.max_pixel_error values in pixels (default 0.5,1,2)")
      ->delimiter(',');
  bench_render_cmd
      ->add_option("--uniform-levels", bench_render.uniform_levels,
                   "Uniform rows: every instance at this fraction of the full vertex count, in "
                   "(0, 1] (default none)")
      ->delimiter(',');
  bench_render_cmd->add_option("--frames", bench_render.frames,
                               "Timed frames per configuration after one warm-up (default 3)");
  bench_render_cmd->add_option("--resolution", bench_render.resolution,
                               "Image size WIDTHxHEIGHT (default 1280x720)");
  bench_render_cmd->add_option(
      "--full-single-frame", bench_render.full_single_frame_triangles,
      "Full resolution above this many triangles is timed on one frame (default 20000000)");
  bench_render_cmd->add_option("--pop-size", bench_render.pop_size,
                               "Instances of the popping dolly (default 1000; 0 = skip)");
  bench_render_cmd->add_option("--pop-frames", bench_render.pop_frames,
                               "Frames of the dolly at 30 frames/s (default 60)");
  bench_render_cmd->add_option("--far-size", bench_render.far_size,
                               "Seats of the far stand, 200 a row (default 10000; 0 = skip)");
  bench_render_cmd->add_option("--pop-budget", bench_render.pop_budget,
                               "Continuous budget of the dolly (default 25% of full vertices)");
  bench_render_cmd->add_flag("--pop-only", bench_render.pop_only,
                             "Only the popping measure; keeps the table's files");
  bench_render_cmd->add_option(
      "--out", bench_render.out,
      "Folder for render-bench.csv, render-popping.csv (default docs/data)");
  bench_render_cmd->add_option("--plot", bench_render.plot,
                               "PNG plot (default docs/render-bench.png; '' = none)");
  bench_render_cmd->add_option("--plot-script", bench_render.plot_script,
                               "gnuplot script (default scripts/plot-render.gp)");
  bench_render_cmd->add_option("--frames-dir", bench_render.frames_dir,
                               "Write the dolly's frames as PNGs into this folder");
  bench_render_cmd->add_flag("!--no-shadows", bench_render.shadows, "No shadow map");
  bench_render_cmd->add_option("--msaa", bench_render.msaa,
                               "Samples per pixel of every image (default 4; 1 = off)");
  bench_render_cmd->add_option("--geomorph", bench_render.geomorph,
                               "The dolly is also rendered with this lod.geomorph, in (0, 1) "
                               "(default 0.25)");
  bench_render_cmd->add_flag("--quick", bench_render.quick,
                             "Tiny sizes, resolution and dolly (CI smoke test)");
}

void add_bench(CLI::App& app, Commands& c) {
  crowdbake::bench::BenchSettings& bench = c.bench;
  CLI::App* bench_cmd = c.bench_cmd =
      app.add_subcommand("bench", "Benchmarks (see docs/accuracy.md)");
  bench_cmd->require_subcommand(1);
  CLI::App* bench_simplify_cmd = c.bench_simplify_cmd = bench_cmd->add_subcommand(
      "simplify", "Animated error vs. simplification time: DQEM settings and two peers");
  bench_simplify_cmd->add_option("--assets", bench.assets,
                                 "Folder with MANIFEST.json (default ../shared/assets)");
  bench_simplify_cmd->add_option("--out", bench.out,
                                 "Folder for accuracy.csv, accuracy.json and accuracy-tables.md "
                                 "(default docs/data)");
  bench_simplify_cmd->add_option(
      "--plot", bench.plot, "PNG plot to write (default docs/accuracy-vs-time.png; '' = none)");
  bench_simplify_cmd->add_option("--plot-script", bench.plot_script,
                                 "gnuplot script (default scripts/plot-accuracy.gp)");
  bench_simplify_cmd->add_flag("--quick", bench.quick,
                               "Fewer configurations and frames (CI smoke test)");
  bench_simplify_cmd->add_flag("--spectator-only", bench.spectator_only,
                               "Only the generated spectator");
  bench_simplify_cmd->add_option("--threads", bench.threads, "Threads (0 = all cores)");
  bench_simplify_cmd
      ->add_option("--frame-stride", bench.frame_stride,
                   "Measure every k-th frame of 30 fps (default 1; 6 with --quick)")
      ->check(CLI::Range(1, 1000));
  bench_simplify_cmd->add_option(
      "--tables-from", bench.tables_from,
      "Measure nothing: write --out/accuracy-tables.md from an earlier run's accuracy.json");

  crowdbake::bench::BenchScaleSettings& bench_scale = c.bench_scale;
  CLI::App* bench_scale_cmd = c.bench_scale_cmd = bench_cmd->add_subcommand(
      "scale", "Simplify time and peak memory of big characters, against meshoptimizer");
  bench_scale_cmd->add_option("files", bench_scale.files, "Characters (make_limb_chain)")
      ->required();
  bench_scale_cmd->add_option("--threads", bench_scale.threads, "Threads (0 = all cores)");
  add_bench_render(c);
}

void add_bake(CLI::App& app, Commands& c) {
  crowdbake::cli::BakeCommandSettings& bake = c.bake;
  CLI::App* bake_cmd = c.bake_cmd =
      app.add_subcommand("bake",
                         "Bake a character into a .crowdpack (progressive mesh, animation "
                         "texture, partition mask, Draco geometry)");
  bake_cmd->add_option("INPUT", bake.input, "Character file")->required();
  bake_cmd->add_option("-o,--output", bake.output, "Output .crowdpack")->required();
  bake_cmd->add_option("--config", bake.config, "Bake settings (JSON, docs/bake-config.md)");
  bake_cmd->add_option("--jobs", bake.jobs,
                       "Threads (0 = all cores); the pack is the same for any value");
  bake_cmd->add_option("--depfile", bake.depfile,
                       "Write a Make/Ninja depfile listing every file read");
  bake_cmd->add_option("--report", bake.report,
                       "Write a JSON report (stats, timings, settings, chunk sizes)");
  bake_cmd->add_flag("--quiet", bake.quiet, "No progress and no summary");
  std::string& bake_preview = c.bake_preview;
  bake_cmd->add_option("--preview", bake_preview,
                       "Also write the pack's contact sheet (crowdbake preview) to this .png");
  add_import_options(*bake_cmd, bake.import);
}

void add_diff(CLI::App& app, Commands& c) {
  crowdbake::cli::DiffSettings& diff = c.diff;
  CLI::App* diff_cmd = c.diff_cmd =
      app.add_subcommand("diff",
                         "Compare two packs semantically (docs/pack-diff.md). "
                         "Exit 0: equal within tolerance, 1: different, "
                         "2: error (a missing or corrupt pack is 2, not 1)");
  diff_cmd->add_option("A", diff.a, "First .crowdpack")->required();
  diff_cmd->add_option("B", diff.b, "Second .crowdpack")->required();
  diff_cmd->add_flag("--json", diff.json, "Print one JSON object to stdout");
  diff_cmd
      ->add_option(
          "--tolerance", diff.tolerance,
          "Float comparisons: lengths (positions, translations, bounds, heights, root motion x/z) "
          "as "
          "|a-b| / bbox diagonal <= T, everything else (3x3 matrix parts, rotations, normals, UVs, "
          "weights, yaw, fps) as |a-b| <= T; default 0 = exact. Names, counts, indices, order, "
          "progressive arrays and mask texels always compare exactly")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            char* end = nullptr;
            const double t = std::strtod(text.c_str(), &end);
            return end != text.c_str() && *end == 0 && std::isfinite(t) && t >= 0
                       ? ""
                       : "must be a number >= 0";
          },
          "T>=0"));
  diff_cmd
      ->add_option("--ignore", diff.ignore,
                   "Sections whose differences do not count (comma-separated)")
      ->delimiter(',')
      ->check(CLI::IsMember({"header", "settings", "skeleton", "clips", "materials", "bounds",
                             "geometry", "progressive", "animation", "partition"}));
}

void add_render(CLI::App& app, Commands& c) {
  crowdbake::cli::RenderSettings& render = c.render;
  CLI::App* render_cmd = c.render_cmd = app.add_subcommand(
      "render",
      "Render a scene.json (docs/scene-format.md) offscreen with Vulkan and write PNGs; "
      "without a GPU it runs on lavapipe (mesa-vulkan-drivers)");
  render_cmd->add_option("SCENE", render.scene, "Scene file (scene.json)")->required();
  render_cmd
      ->add_option("-o,--output", render.output,
                   "Output .png, or with --frames a folder for frame_0000.png ...")
      ->required();
  render_cmd->add_option("--time", render.time, "Scene time in seconds (default 0)");
  c.frames_opt = render_cmd->add_option(
      "--frames", render.frames, "Render a sequence of N frames from --time into the -o folder");
  c.fps_opt = render_cmd->add_option("--fps", render.fps, "Sequence frame rate (default 30)");
  c.budget_opt = render_cmd->add_option("--budget", render.budget,
                                        "LoD budget N: vertices for all visible instances (>= 1)");
  render_cmd->add_option(
      "--lod", render.lod,
      "LoD mode: error, budget (= continuous), discrete or full (default: the scene's)");
  c.geomorph_opt = render_cmd->add_option(
      "--geomorph", render.geomorph,
      "Geomorph window as a fraction of each instance's vertex count, in [0, 1); 0 = off "
      "(default: the scene's lod.geomorph, off)");
  render_cmd->add_option("--resolution", render.resolution,
                         "Image size WIDTHxHEIGHT, e.g. 1280x720");
  render_cmd->add_option("--contact-sheet", render.contact_sheet,
                         "With --frames: also tile every frame into this PNG");
  render_cmd->add_option("--sheet-columns", render.sheet_columns,
                         "Contact sheet columns (default ceil(sqrt(frames)))");
  render_cmd->add_flag("--profile", render.profile,
                       "Print per-pass CPU/GPU milliseconds, counts and effect counters");
  render_cmd->add_option("--stats", render.stats,
                         "Write the frames' numbers (counts, budget, GPU bytes, per-pass CPU/GPU "
                         "ms) as JSON to this file");
  render_cmd->add_option("--msaa", render.msaa,
                         "Samples per pixel, antialiasing (default 4; 1 = off; the device must "
                         "support the count)");
  render_cmd->add_flag("!--no-shadows", render.shadows, "No shadow map");
  render_cmd->add_flag("--validate", render.validation,
                       "Enable the Vulkan validation layer; any validation error fails the run");
  render_cmd->add_flag("--quiet", render.quiet, "Print nothing on success");
}

void add_preview(CLI::App& app, Commands& c) {
  crowdbake::cli::PreviewSettings& preview = c.preview;
  CLI::App* preview_cmd = c.preview_cmd = app.add_subcommand(
      "preview",
      "Contact sheet of a baked character: one row per LoD level, one column per sampled frame "
      "of its clips, each cell labelled with vertices, triangles and the level's error");
  preview_cmd->add_option("PACK", preview.pack, "Baked .crowdpack")->required();
  preview_cmd->add_option("-o,--output", preview.output, "Output .png")->required();
  preview_cmd->add_option("--clip", preview.clips, "Clips to show (default: every clip)");
  preview_cmd->add_option("--levels", preview.levels,
                          "Levels as fractions of the vertices in (0, 1] or 'min' (default "
                          "1 0.5 0.25 0.1 min)");
  preview_cmd->add_option("--frames", preview.frames, "Frames per clip (default 3)");
  std::string& preview_cell = c.preview_cell;
  preview_cmd->add_option("--cell", preview_cell, "Cell size WIDTHxHEIGHT (default 160x240)");
  preview_cmd->add_option("--msaa", preview.msaa, "Samples per pixel (default 4)");
  preview_cmd->add_flag("--quiet", preview.quiet, "Print nothing on success");
}

// Runs the command the flags chose.
int run_command(Commands& c) {
  if (*c.inspect_cmd) return crowdbake::cli::run_inspect(c.inspect);
  if (*c.lod_cmd) return crowdbake::cli::run_lod(c.lod);
  if (*c.bake_cmd) {
    if (!c.bake_preview.empty() && !crowdbake::cli::is_png_path(c.bake_preview))
      throw crowdbake::Error(crowdbake::Error::Kind::kUsage, "--preview",
                             "must name a .png file, got '" + c.bake_preview + "'");
    const int baked = crowdbake::cli::run_bake(c.bake);
    if (baked != 0 || c.bake_preview.empty()) return baked;
    crowdbake::cli::PreviewSettings sheet;
    sheet.pack = c.bake.output;
    sheet.output = c.bake_preview;
    sheet.quiet = c.bake.quiet;
    return crowdbake::cli::run_preview(sheet);
  }
  if (*c.preview_cmd) {
    if (!c.preview_cell.empty())
      crowdbake::cli::parse_size("--cell", c.preview_cell, c.preview.cell_width,
                                 c.preview.cell_height);
    return crowdbake::cli::run_preview(c.preview);
  }
  if (*c.diff_cmd) return crowdbake::cli::run_diff(c.diff);
  if (*c.bench_simplify_cmd) return crowdbake::bench::run_bench_simplify(c.bench);
  if (*c.bench_scale_cmd) return crowdbake::bench::run_bench_scale(c.bench_scale);
  if (*c.bench_render_cmd) return crowdbake::bench::run_bench_render(c.bench_render);
  if (*c.render_cmd) {
    c.render.frames_given = c.frames_opt->count() > 0;
    c.render.fps_given = c.fps_opt->count() > 0;
    c.render.budget_given = c.budget_opt->count() > 0;
    c.render.geomorph_given = c.geomorph_opt->count() > 0;
    return crowdbake::cli::run_render(c.render);
  }
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  crowdbake::cli::prefer_huge_pages();
  CLI::App app{"crowdbake: bake skinned characters into crowd packs and render crowds",
               "crowdbake"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "crowdbake " CROWDBAKE_VERSION);
  Commands c;
  add_inspect(app, c);
  add_lod(app, c);
  add_bench(app, c);
  add_bake(app, c);
  add_diff(app, c);
  add_render(app, c);
  add_preview(app, c);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "error: " << e.what() << " (run 'crowdbake --help' for usage)\n";
    return 2;
  }

  try {
    return run_command(c);
  } catch (const crowdbake::Error& e) {
    std::cerr << "error: " << crowdbake::status_of(e).message() << "\n";
    return e.exit_code();
  } catch (const std::bad_alloc&) {
    std::cerr << "error: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "error: internal error: " << e.what()
              << " (please report this with the input file)\n";
    return 1;
  }
}
