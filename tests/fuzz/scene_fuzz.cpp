// libFuzzer target: scene.json text -> Scene (parse_scene, with the "effects" section's reader
// registered; relaxation generators have no placer, so they are refused) -> one CPU-reference frame
// (update_frame: crowd update, culling, LoD selection) and one reconstructed level. The
// scene's packs resolve against a private folder holding one small pack, "type.crowdpack".
// Property beyond "no crash, no leak, no huge allocation": an accepted scene yields a
// frame whose arrays match its instance count.
#include <cstdint>
#include <cstdlib>
#include <fstream>

#include "crowdbake/runtime/cpu_reference.h"
#include "crowdbake/runtime/effects/scene_effects.h"
#include "crowdbake/runtime/scene.h"
#include "fuzz_input_file.h"
#include "small_pack.h"

namespace {

// A frame over more instances than this costs the fuzzer seconds per input; bigger scenes
// are still parsed (their limits are checked there) but not updated.
constexpr uint32_t kFrameInstances = 20000;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  std::vector<uint8_t> pack;
  if (!crowdbake::write_pack(crowdbake::fuzz::small_pack_contents(3, 7), {}, pack)) std::abort();
  crowdbake::fuzz::write_input("type.crowdpack", pack.data(), pack.size());
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace crowdbake::runtime;
  Scene scene;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  SceneLoadOptions options;
  options.sections.push_back(crowdbake::effects::scene_effects_section());
  const Status parsed =
      parse_scene(text, "scene.json", crowdbake::fuzz::private_folder(), scene, options);
  if (!parsed) {
    crowdbake::fuzz::refused(parsed.message());
    return 0;
  }
  const auto n = static_cast<uint32_t>(scene.instances.size());
  if (n > kFrameInstances) return 0;
  FrameState state;
  const Status updated = update_frame(scene, 0.5f, state);
  if (!updated) crowdbake::fuzz::refused(updated.message());
  if (updated) {
    if (state.vertex_count.size() != n) std::abort();
    std::vector<uint32_t> triangles;
    for (uint32_t i = 0; i < n && i < 4; ++i)
      (void)reconstruct_lod(scene, scene.instances.type[i], state.vertex_count[i], triangles);
  }
  return 0;
}
