// pack_summary PACK: opens a pack with the installed runtime, places a 3 x 3 crowd of it in a
// scene built from code and runs one CPU frame. Prints one line; exit 1 on any failure.
#include <crowdbake/runtime/runtime.h>

#include <cstdio>

int main(int argc, char** argv) {
  using namespace crowdbake::runtime;
  if (argc != 2) {
    std::fprintf(stderr, "usage: pack_summary PACK.crowdpack\n");
    return 2;
  }
  Pack pack;
  Status status = Pack::open_file(argv[1], pack, kPackAll);
  const uint32_t levels_low = status ? pack.min_vertices() : 0;
  const uint32_t levels_high = status ? pack.max_vertices() : 0;
  Scene scene;
  if (status) status = add_character_type(scene, "character", std::move(pack));
  for (int i = 0; status && i < 9; ++i) {
    Instance instance;
    instance.position = {static_cast<float>(i % 3), 0.0f, -2.0f * static_cast<float>(i / 3)};
    scene.instances.add(instance);
  }
  scene.camera.position = {1.0f, 1.5f, 6.0f};
  scene.camera.target = {1.0f, 1.0f, 0.0f};
  FrameState frame;
  if (status) status = update_frame(scene, 0.5f, frame);
  if (!status) {
    std::fprintf(stderr, "pack_summary: %s: %s\n", status_code_name(status.code()),
                 status.message().c_str());
    return 1;
  }
  std::printf("vertices %u..%u, clips %zu, instances %zu, visible %u\n", levels_low, levels_high,
              scene.clips.size(), scene.instances.size(), frame.visible_count);
  return frame.visible_count > 0 ? 0 : 1;
}
