// stadium_timeline: runs the stadium scene's effects (or any scene's) on the CPU and prints,
// every half second, how many of each team's spectators are in each behaviour state, then the
// effect counters — the numbers behind samples/stadium/README.md.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <map>
#include <memory>
#include <string>

#include "crowdbake/runtime/effects/crowd_effects.h"
#include "crowdbake/runtime/scene.h"

int main(int argc, char** argv) {
  CLI::App app{"Prints the behaviour timeline of a scene's declared effects"};
  std::string scene_path;
  float duration = 10.0f, fps = 30.0f;
  app.add_option("scene", scene_path, "scene.json")->required();
  app.add_option("--duration", duration, "seconds to simulate")->check(CLI::Range(0.0f, 3600.0f));
  app.add_option("--fps", fps, "updates per second")->check(CLI::Range(1.0f, 1000.0f));
  CLI11_PARSE(app, argc, argv);

  using namespace crowdbake;
  runtime::Scene scene;
  if (runtime::Status s =
          runtime::load_scene(scene_path, scene, effects::crowd_scene_load_options());
      !s) {
    std::fprintf(stderr, "error: %s\n", s.message().c_str());
    return 2;
  }
  std::unique_ptr<effects::CrowdEffects> fx;
  if (runtime::Status s = effects::CrowdEffects::create(scene, fx); !s) {
    std::fprintf(stderr, "error: %s\n", s.message().c_str());
    return 2;
  }
  runtime::EffectFrame frame;
  const effects::SceneEffects* declared = effects::find_scene_effects(scene);
  const std::vector<effects::EffectTeam> teams =
      declared ? declared->teams : std::vector<effects::EffectTeam>{};
  const int steps = static_cast<int>(duration * fps);
  const int every = std::max(1, static_cast<int>(fps / 2));
  for (int step = 0; step <= steps; ++step) {
    const float t = static_cast<float>(step) / fps;
    if (runtime::Status s = fx->update(scene, t, 1.0f / fps, frame); !s) {
      std::fprintf(stderr, "error: %s\n", s.message().c_str());
      return 1;
    }
    if (step % every != 0) continue;
    std::printf("t = %5.1f s", t);
    for (const auto& team : teams) {
      std::map<std::string, int> states;
      int reacting = 0;
      for (uint32_t g : team.generators) {
        const runtime::InstanceRange r = scene.generated[g];
        for (uint32_t i = r.first; i < r.first + r.count; ++i) {
          ++states[fx->behaviour_state(i)];
          reacting += fx->is_reacting(i);
        }
      }
      std::printf("  | team %s: %3d reacting:", team.name.c_str(), reacting);
      for (const auto& [name, count] : states) std::printf(" %s %d", name.c_str(), count);
    }
    std::printf("\n");
  }
  for (const std::string& line : effects::format_effect_counters(fx->counters()))
    std::printf("%s\n", line.c_str());
  return 0;
}
