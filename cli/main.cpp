// crowdbake: flags in, calls into the libraries, errors out as one line each.
// Exit codes: 0 success, 1 bad input, 2 usage, 3 output could not be written.
#include <cstdio>
#include <exception>
#include <iostream>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "crowdbake/pipeline/error.h"

namespace {

void add_import_options(CLI::App& command, crowdbake::ImportOptions& options) {
  command.add_option("--character", options.character,
                     "Which character to import when the file holds several (0-based); "
                     "default: the one with the most skinned vertices");
  command.add_option("--importer", options.importer, "auto, gltf or assimp")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, crowdbake::ImporterKind>{{"auto", crowdbake::ImporterKind::kAuto},
                                                        {"gltf", crowdbake::ImporterKind::kGltf},
                                                        {"assimp", crowdbake::ImporterKind::kAssimp}},
          CLI::ignore_case));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"crowdbake: bake skinned characters into crowd packs and render crowds", "crowdbake"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "crowdbake " CROWDBAKE_VERSION);

  crowdbake::cli::InspectSettings inspect;
  CLI::App* inspect_cmd = app.add_subcommand("inspect", "Describe a character file: skeleton, meshes, clips, warnings");
  inspect_cmd->add_option("FILE", inspect.input, "Character file (.gltf, .glb, .fbx, or anything Assimp reads)")
      ->required();
  inspect_cmd->add_flag("--json", inspect.json, "Print one JSON object to stdout");
  add_import_options(*inspect_cmd, inspect.import);

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
    if (*inspect_cmd) return crowdbake::cli::run_inspect(inspect);
  } catch (const crowdbake::Error& e) {
    std::cerr << "error: " << e.file() << ": " << e.what() << "\n";
    return e.exit_code();
  } catch (const std::bad_alloc&) {
    std::cerr << "error: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "error: internal error: " << e.what() << " (please report this with the input file)\n";
    return 1;
  }
  return 2;
}
