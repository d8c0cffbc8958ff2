// CPU time per frame of animation state sharing vs. a per-character baseline, for crowds of
// 1k–1M characters (docs/performance.md, "Animation state sharing"). Speed targets live here,
// never in unit tests.
//
// Rig: 48 joints (a crowd-LoD humanoid), 30-frame clips. Shared setup: 5 base states × 8
// instances + an additive upper-body wave × 4 + 32 transition instances = a budget of 76 poses.
// Each frame `churn` ‰ of the characters (chosen by a fixed stride) want a new state; the
// baseline applies the same schedule to characters that each sample (and, within 0.25 s of a
// switch, blend) their own clips and run local → model.
// note: the baseline writes each character's matrices into one reused buffer, not a per-
// character buffer (1M × 48 matrices would be 3 GB); that flatters the baseline slightly.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "crowdbake/runtime/effects/anim_sharing.h"
#include "crowdbake/runtime/effects/crossfade.h"
#include "crowdbake/runtime/effects/pose_jobs.h"
#include "runtime/effects/test_rigs.h"

namespace crowdbake::effects {
namespace {

constexpr uint32_t kJoints = 48;
constexpr float kDt = 1.0f / 30.0f;
constexpr float kTransitionTime = 0.25f;
constexpr uint32_t kBaseStates = 5;  // ids 0..4; 5 = additive wave
constexpr StateId kWaveState = 5;

AnimSharingSetup bench_setup(ProcessPolicy policy) {
  AnimSharingSetup setup;
  setup.skeleton = testing::make_skeleton(kJoints);
  for (uint32_t c = 0; c < 2 * kBaseStates + 1; ++c) {
    setup.clips.push_back(
        testing::make_clip("clip" + std::to_string(c), kJoints, 30, 1.0f + 0.1f * c, 1000 + c));
  }
  for (uint32_t s = 0; s < kBaseStates; ++s) {
    setup.states.push_back(AnimState{s, {2 * s, 2 * s + 1}, false, {}, 8});
  }
  AnimState wave{kWaveState, {2 * kBaseStates}, true, std::vector<float>(kJoints, 0.0f), 4};
  for (uint32_t j = kJoints / 2; j < kJoints; ++j) wave.skeletal_mask[j] = 1.0f;
  setup.states.push_back(wave);
  setup.processor = [](StateId, Span<const float> p) {
    return StateDecision{static_cast<StateId>(p[0]), true};
  };
  setup.max_transition_count = 32;
  setup.transition_time = kTransitionTime;
  setup.transition_join_window = 0.1f;
  setup.process_policy = policy;
  return setup;
}

// The schedule both sides follow: each frame, `count` characters from a rolling cursor with
// a stride coprime to n want another state (1 in 8 of them the wave layer).
struct Schedule {
  uint32_t n = 0;
  uint32_t count = 0;
  uint64_t cursor = 0;
  uint64_t frame = 0;
  template <typename F>
  void next_frame(F&& change) {
    ++frame;
    for (uint32_t k = 0; k < count; ++k) {
      cursor = (cursor + 7919) % n;  // 7919 is prime; n is a power of ten
      const uint64_t h = (cursor * 2654435761u + frame * 40503u) >> 7;
      const StateId state = h % 8 == 0 ? kWaveState : static_cast<StateId>(h % kBaseStates);
      change(static_cast<uint32_t>(cursor), state);
    }
  }
};

// churn: switches per frame, as ‰ of the crowd (churn_permille) or a fixed count.
void run_shared(benchmark::State& bench, ProcessPolicy policy, uint32_t churn_permille,
                uint32_t churn_fixed = 0) {
  const uint32_t n = static_cast<uint32_t>(bench.range(0));
  std::unique_ptr<AnimSharingInstance> sharing;
  if (!AnimSharingInstance::create(bench_setup(policy), sharing)) {
    bench.SkipWithError("invalid setup");
    return;
  }
  std::vector<CharacterId> ids(n);
  for (uint32_t i = 0; i < n; ++i) {
    ids[i] = sharing->register_character(i, i % kBaseStates);
    sharing->set_parameter(ids[i], 0, static_cast<float>(i % kBaseStates));
  }
  Schedule schedule{n, churn_fixed + static_cast<uint32_t>(uint64_t{n} * churn_permille / 1000)};
  auto change = [&](uint32_t i, StateId state) {
    sharing->set_parameter(ids[i], 0, static_cast<float>(state));
  };
  for (int frame = 0; frame < 20; ++frame) {  // past the first transitions
    schedule.next_frame(change);
    sharing->update(kDt);
  }
  uint64_t poses = 0, processed = 0, frames = 0;
  for (auto _ : bench) {
    schedule.next_frame(change);
    sharing->update(kDt);
    poses += sharing->frame_stats().pose_evaluations;
    processed += sharing->frame_stats().processed_characters;
    ++frames;
  }
  bench.counters["poses/frame"] = static_cast<double>(poses) / frames;
  bench.counters["budget"] = sharing->pose_budget();
  bench.counters["processed/frame"] = static_cast<double>(processed) / frames;
}

// Per character: its own clip and time offset; after a switch it samples both clips and
// blends them for kTransitionTime. The wave layer is a second sample masked over the base.
struct BaselineCrowd {
  std::vector<uint32_t> clip, previous_clip, layer_clip;
  std::vector<float> offset, switch_time;
};

void run_baseline(benchmark::State& bench, uint32_t churn_permille) {
  const uint32_t n = static_cast<uint32_t>(bench.range(0));
  const AnimSharingSetup setup = bench_setup(ProcessPolicy::kChangedOnly);
  const std::vector<float>& wave_mask = setup.states[kWaveState].skeletal_mask;
  BaselineCrowd crowd;
  crowd.clip.resize(n);
  crowd.previous_clip.resize(n);
  crowd.layer_clip.assign(n, kNone);
  crowd.offset.resize(n);
  crowd.switch_time.assign(n, -1e9f);
  for (uint32_t i = 0; i < n; ++i) {
    crowd.clip[i] = crowd.previous_clip[i] = 2 * (i % kBaseStates) + (i / kBaseStates) % 2;
    crowd.offset[i] = 0.37f * static_cast<float>(i % 97);
  }
  Schedule schedule{n, static_cast<uint32_t>(uint64_t{n} * churn_permille / 1000)};
  double clock = 0.0;
  auto change = [&](uint32_t i, StateId state) {
    if (state == kWaveState) {
      crowd.layer_clip[i] = 2 * kBaseStates;
      return;
    }
    crowd.layer_clip[i] = kNone;
    crowd.previous_clip[i] = crowd.clip[i];
    crowd.clip[i] = 2 * state + i % 2;
    crowd.switch_time[i] = static_cast<float>(clock);
  };
  std::vector<Transform> pose(kJoints), other(kJoints);
  std::vector<glm::mat4> model(kJoints);
  uint64_t poses = 0;
  auto frame = [&]() {
    clock += kDt;
    schedule.next_frame(change);
    for (uint32_t i = 0; i < n; ++i) {
      const double t = clock + crowd.offset[i];
      SamplingJob{&setup.clips[crowd.clip[i]], t, pose}.Run();
      ++poses;
      const float s = static_cast<float>(clock - crowd.switch_time[i]) / kTransitionTime;
      if (s < 1.0f) {
        SamplingJob{&setup.clips[crowd.previous_clip[i]], t, other}.Run();
        BlendJob{other, pose, s, {}, pose}.Run();
        ++poses;
      }
      if (crowd.layer_clip[i] != kNone) {
        SamplingJob{&setup.clips[crowd.layer_clip[i]], t, other}.Run();
        BlendJob{pose, other, 1.0f, wave_mask, pose}.Run();
        ++poses;
      }
      LocalToModelJob{&setup.skeleton, pose, model}.Run();
      benchmark::DoNotOptimize(model.data());
    }
  };
  frame();
  poses = 0;
  uint64_t frames = 0;
  for (auto _ : bench) {
    frame();
    ++frames;
  }
  bench.counters["poses/frame"] = static_cast<double>(poses) / frames;
}

void BM_SharedSteady(benchmark::State& s) { run_shared(s, ProcessPolicy::kChangedOnly, 0); }
void BM_SharedChurn1pct(benchmark::State& s) { run_shared(s, ProcessPolicy::kChangedOnly, 10); }
void BM_SharedChurn100(benchmark::State& s) { run_shared(s, ProcessPolicy::kChangedOnly, 0, 100); }
void BM_SharedEveryFrameChurn1pct(benchmark::State& s) {
  run_shared(s, ProcessPolicy::kEveryFrame, 10);
}
void BM_BaselineChurn1pct(benchmark::State& s) { run_baseline(s, 10); }

void crowd_sizes(benchmark::internal::Benchmark* b) {
  for (int64_t n : {1000, 10000, 100000, 1000000}) b->Arg(n);
  b->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_SharedSteady)->Apply(crowd_sizes);
BENCHMARK(BM_SharedChurn100)->Apply(crowd_sizes);
BENCHMARK(BM_SharedChurn1pct)->Apply(crowd_sizes);
BENCHMARK(BM_SharedEveryFrameChurn1pct)->Apply(crowd_sizes);
BENCHMARK(BM_BaselineChurn1pct)->Apply(crowd_sizes);

// One joint of the GPU crossfade (crossfade.h) on the CPU: a rough relative cost of the three
// blends (the shader's cost is measured on a GPU, not here).
void BM_CrossfadeJoint(benchmark::State& bench) {
  const auto method = static_cast<CrossfadeBlend>(bench.range(0));
  std::vector<JointSample> a(1024), b(1024);
  for (size_t i = 0; i < a.size(); ++i) {
    a[i].rotation = glm::angleAxis(0.001f * i, glm::vec3(0, 1, 0));
    b[i].rotation = glm::angleAxis(1.0f + 0.002f * i, glm::normalize(glm::vec3(1, 1, 0)));
    a[i].translation = glm::vec3(0.001f * i);
    b[i].translation = glm::vec3(0.3f, 1.4f, 0.0f);
  }
  // note: the matrix blend reads matrices (float textures store them), the other two the
  // quaternion form (kQuantized textures).
  std::vector<glm::mat4> ma(a.size()), mb(b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    ma[i] = joint_matrix(a[i]);
    mb[i] = joint_matrix(b[i]);
  }
  float w = 0.3f;
  for (auto _ : bench) {
    for (size_t i = 0; i < a.size(); ++i) {
      glm::mat4 m = method == CrossfadeBlend::kMatrix ? blend_matrix(ma[i], mb[i], w)
                                                      : crossfade_joint(method, a[i], b[i], w);
      benchmark::DoNotOptimize(m);
    }
    w = w > 0.9f ? 0.1f : w + 0.01f;
  }
  bench.SetItemsProcessed(bench.iterations() * static_cast<int64_t>(a.size()));
}
BENCHMARK(BM_CrossfadeJoint)
    ->Arg(static_cast<int>(CrossfadeBlend::kMatrix))
    ->Arg(static_cast<int>(CrossfadeBlend::kQuaternion))
    ->Arg(static_cast<int>(CrossfadeBlend::kDualQuaternion));

}  // namespace
}  // namespace crowdbake::effects

BENCHMARK_MAIN();
