// make_limb_chain: writes a generated skinned limb chain of a given size as .glb, for
// measuring the pipeline at scale (docs/accuracy.md, "At scale").
#include <CLI/CLI.hpp>
#include <cstdio>

#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/gltf_export.h"
#include "limb_chain.h"

int main(int argc, char** argv) {
  CLI::App app{"Writes a generated skinned limb chain (a capped tube on a joint chain) as .glb"};
  crowdbake::samples::LimbChainOptions options;
  std::string output;
  app.add_option("-o,--output", output, "output .glb")->required();
  app.add_option("--triangles", options.triangles, "approximate triangle count")
      ->check(CLI::Range(100u, 20000000u));
  app.add_option("--joints", options.joints, "joints in the chain")->check(CLI::Range(1, 256));
  app.add_flag("--vertex-colors", options.vertex_colors,
               "give every vertex a colour (COLOR_0), red at the root to blue at the tip");
  CLI11_PARSE(app, argc, argv);
  try {
    const crowdbake::SkinnedAsset asset = crowdbake::samples::make_limb_chain(options);
    crowdbake::throw_if_failed(crowdbake::export_glb(asset, output));
    std::printf("%s: %zu vertices, %zu triangles, %d joints\n", output.c_str(),
                asset.vertex_count(), asset.triangle_count(), options.joints);
  } catch (const crowdbake::Error& e) {
    std::fprintf(stderr, "error: %s\n", crowdbake::status_of(e).message().c_str());
    return e.exit_code();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s: %s\n", output.c_str(), e.what());
    return 1;
  }
  return 0;
}
