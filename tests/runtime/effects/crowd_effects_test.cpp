// CrowdEffects (crowd_effects.h): only declared systems are built and run, the counters prove
// it, and the wiring FSM → animation sharing → pose buffer / GPU crossfade works on the baked
// spectator pack's own clips.
#include "crowdbake/runtime/effects/crowd_effects.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

#include "crowdbake/runtime/effects/pack_pose.h"
#include "crowdbake/runtime/effects/pose_jobs.h"
#include "crowdbake/runtime/frame.h"
#include "crowdbake/runtime/skin_job.h"
#include "runtime/effects/scene_effects_support.h"

namespace crowdbake::effects {
namespace {

using runtime::EffectFrame;
using runtime::Scene;
using runtime::Status;

class CrowdEffectsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string error;
    ASSERT_TRUE(files_.add_spectator(&error)) << error;
  }
  // Loads the spectator scene with `effects` and builds its CrowdEffects.
  void load(const std::string& effects) {
    const Status s = files_.load(test::spectator_scene(effects), scene_);
    ASSERT_TRUE(s.ok()) << s.message();
    const Status c = CrowdEffects::create(scene_, effects_);
    ASSERT_TRUE(c.ok()) << c.message();
  }
  // Runs update() from `from` to `to` seconds at `fps`.
  void run(float from, float to, float fps = 30.0f) {
    for (float t = from; t <= to + 1e-4f; t += 1.0f / fps) {
      const Status s = effects_->update(scene_, t, 1.0f / fps, frame_);
      ASSERT_TRUE(s.ok()) << s.message();
      ++calls_;
    }
  }
  const EffectCounters& counters() const { return effects_->counters(); }
  size_t n() const { return scene_.instances.size(); }

  test::EffectScenes files_;
  Scene scene_;
  std::unique_ptr<CrowdEffects> effects_;
  EffectFrame frame_;
  uint64_t calls_ = 0;
};

void expect_all_zero(const EffectCounters& c) {
  EXPECT_EQ(c.constructed_systems, 0u);
  EXPECT_FALSE(c.behaviour_fsm || c.animation_sharing || c.crossfade);
  EXPECT_EQ(c.state_instances, 0u);
  EXPECT_EQ(c.transition_instances, 0u);
  EXPECT_EQ(c.driven_instances, 0u);
  EXPECT_EQ(c.updates, 0u);
  EXPECT_EQ(c.poses_evaluated, 0u);
  EXPECT_EQ(c.pose_bytes, 0u);
  EXPECT_EQ(c.crossfades_started, 0u);
}

TEST_F(CrowdEffectsTest, BakedLoopsOnlyLeaveTheFrameEmptyAndTheCountersZero) {
  load("");  // no "effects" at all
  run(0.0f, 2.0f);
  EXPECT_TRUE(frame_.empty());
  expect_all_zero(counters());

  // Declaring only renderer-side effects builds nothing on the CPU either; a frame that had
  // arrays before is cleared.
  load(R"({"lod": true, "texture_partition": false, "color_variety": true})");
  frame_.pose.assign(n(), 0);
  frame_.pose_buffers.resize(1, std::vector<float>(12, 1.0f));
  run(0.0f, 1.0f);
  EXPECT_TRUE(frame_.empty());
  expect_all_zero(counters());
}

TEST_F(CrowdEffectsTest, WithoutEventsTheFsmIsNeverInstantiated) {
  // Spectators declared (teams, reactions, no events, no idle edges) + shared states.
  load(std::string("{") + test::kStates + R"(, "animation_sharing": true, )" +
       test::spectators_block(R"("events": [])") + "}");
  run(0.0f, 3.0f);
  EXPECT_FALSE(counters().behaviour_fsm);
  EXPECT_EQ(counters().fsm_individuals, 0u);
  EXPECT_EQ(counters().fsm_state_changes, 0u);
  EXPECT_EQ(effects_->behaviour_state(0), "");
  // Sharing still runs: every instance plays "idle", the clip of state "stand".
  EXPECT_TRUE(counters().animation_sharing);
  EXPECT_EQ(counters().constructed_systems, 1u);
  EXPECT_EQ(counters().driven_instances, n());
  EXPECT_GT(counters().poses_evaluated, 0u);
  ASSERT_EQ(frame_.pose.size(), n());
  EXPECT_TRUE(frame_.clip.empty());
  EXPECT_TRUE(frame_.fade_clip.empty());
}

TEST_F(CrowdEffectsTest, WithoutTransitionsNoTransitionInstanceIsAllocated) {
  load(std::string("{") + test::kStates + R"(, "animation_sharing": {"instances_per_state": 2}, )" +
       test::spectators_block() + "}");
  run(0.0f, 4.0f);
  EXPECT_TRUE(counters().behaviour_fsm);
  EXPECT_GT(counters().fsm_state_changes, 0u) << "the goal made team A change state";
  EXPECT_EQ(counters().transition_instances, 0u);
  EXPECT_EQ(counters().transitions_started, 0u);
  EXPECT_EQ(counters().frame_alive_transitions, 0u);
  EXPECT_EQ(counters().state_instances, 3u * 2u);
}

TEST_F(CrowdEffectsTest, DeclaredEffectsMoveTheCounters) {
  load(
      std::string("{") + test::kStates +
      R"(, "animation_sharing": {"instances_per_state": 2, "transitions": {"time": 0.5, "max": 6}}, )" +
      test::spectators_block() + "}");
  EXPECT_EQ(counters().constructed_systems, 2u);
  EXPECT_TRUE(counters().behaviour_fsm && counters().animation_sharing);
  EXPECT_FALSE(counters().crossfade);
  EXPECT_EQ(counters().transition_instances, 6u);
  EXPECT_EQ(counters().fsm_individuals, n());
  run(0.0f, 0.9f);
  EXPECT_EQ(counters().fsm_state_changes, 0u) << "nothing happens before the goal";
  run(1.0f, 3.0f);
  const EffectCounters& c = counters();
  EXPECT_EQ(c.updates, calls_);
  EXPECT_GT(c.fsm_state_changes, 0u);
  EXPECT_GT(c.transitions_started, 0u);
  EXPECT_GT(c.poses_evaluated, 0u);
  EXPECT_LE(c.frame_poses_evaluated, 3u * 2u + 6u) << "bounded by instances + transitions";

  // The pose buffer: every pose slot's joints, every instance pointing into it.
  const runtime::Pack& pack = scene_.types[0].pack;
  const size_t joints = pack.contents().joints.size();
  const size_t slots = 3u * 2u + 6u;
  ASSERT_EQ(frame_.pose_buffers.size(), 1u);
  ASSERT_EQ(frame_.pose_buffers[0].size(), slots * joints * 12);
  EXPECT_EQ(c.frame_pose_bytes, slots * joints * 12 * sizeof(float));
  EXPECT_EQ(c.pose_bytes, c.updates * c.frame_pose_bytes);
  ASSERT_EQ(frame_.pose.size(), n());
  std::set<uint32_t> used;
  for (uint32_t p : frame_.pose) {
    ASSERT_LT(p, slots);
    used.insert(p);
  }
  for (uint32_t p : used)
    for (size_t k = 0; k < joints * 12; ++k)
      ASSERT_TRUE(std::isfinite(frame_.pose_buffers[0][p * joints * 12 + k]));
  EXPECT_TRUE(frame_.clip.empty()) << "poses replace the baked clips";
  EXPECT_TRUE(frame_.fade_clip.empty());

  // Team A reacted (cheer), team B had no reason to.
  uint32_t a = 0, b = 0;
  for (uint32_t i = 0; i < scene_.generated[0].count; ++i) a += effects_->is_reacting(i);
  for (uint32_t i = scene_.generated[1].first; i < n(); ++i) b += effects_->is_reacting(i);
  EXPECT_GT(a, scene_.generated[0].count / 2);
  EXPECT_EQ(b, 0u);

  const std::vector<std::string> lines = format_effect_counters(c);
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_NE(lines[4].find("mean per update"), std::string::npos) << lines[4];
  EXPECT_NE(lines[0].find("2 systems constructed"), std::string::npos) << lines[0];
}

TEST_F(CrowdEffectsTest, SeveralSkeletonTypesShareStatesEachInTheirOwnPoseBuffer) {
  const std::string json = R"({
  "camera": {"position": [0, 6, 20], "target": [0, 1, 0]},
  "animation": {"root_motion": false},
  "character_types": [{"name": "spectator", "pack": "packs/spectator.crowdpack"},
                      {"name": "other", "pack": "packs/spectator3.crowdpack"}],
  "generators": [
    {"kind": "seat_grid", "type": "spectator", "origin": [-6, 0, 0], "rows": 4, "columns": 6,
     "spacing": [0.6, 0.9], "clip": "idle"},
    {"kind": "seat_grid", "type": "other", "origin": [3, 0, 0], "rows": 4, "columns": 6,
     "spacing": [0.6, 0.9], "clip": "idle"}],
  "effects": {"types": ["spectator", "other"], )" +
                           std::string(test::kStates) +
                           R"(, "animation_sharing": {"instances_per_state": 2,
      "transitions": {"max": 3}}, )" +
                           test::spectators_block() + "}}";
  const Status s = files_.load(json, scene_);
  ASSERT_TRUE(s.ok()) << s.message();
  ASSERT_NE(find_scene_effects(scene_), nullptr);
  ASSERT_EQ(find_scene_effects(scene_)->types, (std::vector<uint32_t>{0, 1}));
  ASSERT_TRUE(CrowdEffects::create(scene_, effects_).ok());
  EXPECT_EQ(counters().state_instances, 2u * 3u * 2u);
  EXPECT_EQ(counters().transition_instances, 2u * 3u);
  EXPECT_EQ(counters().fsm_individuals, n());
  run(0.0f, 3.0f);
  ASSERT_EQ(frame_.pose_buffers.size(), 2u);
  for (uint32_t t = 0; t < 2; ++t) {
    const size_t joints = scene_.types[t].pack.contents().joints.size();
    EXPECT_EQ(frame_.pose_buffers[t].size(), (3u * 2u + 3u) * joints * 12) << "type " << t;
  }
  for (uint32_t p : frame_.pose) EXPECT_NE(p, runtime::kNoPose);
  uint32_t a = 0;
  for (uint32_t i = 0; i < scene_.generated[0].count; ++i) a += effects_->is_reacting(i);
  EXPECT_GT(a, 0u);
  // The two skeletons differ (seed 3 is another body): the same state's poses differ too.
  EXPECT_NE(frame_.pose_buffers[0][3], frame_.pose_buffers[1][3]);

  test::EffectScenes other;
  std::string error;
  ASSERT_TRUE(other.add_spectator(&error)) << error;
  runtime::Scene bad;
  std::string wrong = json;
  wrong.replace(wrong.find(R"("types": ["spectator", "other"])"), 31, R"("type": "spectator")");
  const Status e = other.load(wrong, bad);
  EXPECT_NE(e.message().find("effects.spectators.teams[1].generators[0]: generator 1 makes "
                             "instances of character type 'other', which the effects do not "
                             "drive"),
            std::string::npos)
      << e.message();
}

TEST_F(CrowdEffectsTest, AdditiveLayersFollowTheFsm) {
  // The goal raises the right arm ("arm-up" held at its end) as a masked layer over "stand".
  load(R"({"states": [
      {"name": "stand", "clips": ["idle"], "pose": "up", "rest": true, "interruptible": true},
      {"name": "wave", "clips": [{"clip": "arm-up", "hold": true}], "pose": "up",
       "additive": true, "mask": ["right_shoulder"], "instances": 4}],
    "animation_sharing": {"instances_per_state": 2, "additive_layers": true},
    "spectators": {"transitions": [{"from": "stand", "to": "wave"}, {"from": "wave", "to": "stand"}],
      "reactions": [{"event": "goal", "supporters": "wave"}],
      "teams": [{"name": "A", "generators": [0], "embarrassment": 0.1}, {"name": "B", "generators": [1]}],
      "events": [{"kind": "goal", "time": 1, "team": "A", "excitement": 1.5}]}})");
  EXPECT_EQ(counters().state_instances, 2u + 4u);
  run(0.0f, 3.0f);
  // Stand's instances are pose slots 0-1, wave's 2-5: the wavers are skinned by the layer.
  uint32_t layered = 0, waving = 0;
  for (uint32_t i = 0; i < n(); ++i) {
    if (effects_->behaviour_state(i) != "wave") continue;
    ++waving;
    layered += frame_.pose[i] >= 2u && frame_.pose[i] < 6u;
  }
  EXPECT_GT(waving, 0u);
  EXPECT_EQ(layered, waving);
  // The layer moves the right arm only: a left-arm joint's matrix equals stand's.
  const runtime::Pack& pack = scene_.types[0].pack;
  const size_t joints = pack.contents().joints.size();
  const uint32_t left = static_cast<uint32_t>(pack.find_joint("left_hand"));
  const uint32_t right = static_cast<uint32_t>(pack.find_joint("right_hand"));
  const float* buffer = frame_.pose_buffers[0].data();
  double left_diff = 0.0, right_diff = 0.0;
  for (uint32_t i = 0; i < n(); ++i) {
    if (frame_.pose[i] < 2u || frame_.pose[i] >= 6u) continue;
    // note: a layer binds to the stand instance its character was on; compare with both.
    double l = 1e9, r = 0.0;
    for (uint32_t base = 0; base < 2; ++base) {
      double dl = 0.0, dr = 0.0;
      for (int k = 0; k < 12; ++k) {
        dl += std::fabs(buffer[(frame_.pose[i] * joints + left) * 12 + k] -
                        buffer[(base * joints + left) * 12 + k]);
        dr += std::fabs(buffer[(frame_.pose[i] * joints + right) * 12 + k] -
                        buffer[(base * joints + right) * 12 + k]);
      }
      if (dl < l) l = dl, r = dr;
    }
    left_diff = std::max(left_diff, l);
    right_diff = std::max(right_diff, r);
  }
  EXPECT_LT(left_diff, 1e-5);
  EXPECT_GT(right_diff, 0.05);
}

TEST_F(CrowdEffectsTest, CrossfadeOnlyTurnsFsmChangesIntoGpuFades) {
  load(std::string("{") + test::kStates + R"(, "crossfade": {"time": 0.5}, )" +
       test::spectators_block() + "}");
  EXPECT_TRUE(counters().crossfade && counters().behaviour_fsm);
  EXPECT_EQ(counters().driven_instances, n());
  EXPECT_FALSE(counters().animation_sharing);
  const uint32_t cheer = static_cast<uint32_t>(scene_.find_clip(0, "cheer"));
  const uint32_t idle = static_cast<uint32_t>(scene_.find_clip(0, "idle"));
  bool fading = false;
  for (float t = 0.0f; t <= 4.0f; t += 1.0f / 30.0f) {
    ASSERT_TRUE(effects_->update(scene_, t, 1.0f / 30.0f, frame_).ok());
    ASSERT_EQ(frame_.fade_weight.size(), n());
    for (size_t i = 0; i < n(); ++i) {
      const float w = frame_.fade_weight[i];
      ASSERT_TRUE(w >= 0.0f && w < 1.0f);
      if (w > 0.0f && frame_.fade_clip[i] == cheer && frame_.clip[i] == idle) fading = true;
    }
  }
  EXPECT_TRUE(fading) << "some instance faded from idle to cheer";
  EXPECT_GT(counters().crossfades_started, 0u);
  EXPECT_EQ(counters().poses_evaluated, 0u) << "no CPU pose work on the GPU-only path";
  EXPECT_EQ(counters().pose_bytes, 0u);
  EXPECT_TRUE(frame_.pose.empty());
  EXPECT_TRUE(frame_.pose_buffers.empty());
  ASSERT_EQ(frame_.clip.size(), n());
  // Long after the goal's fade, team A's cheerers show cheer on their own side again.
  uint32_t cheering = 0;
  for (uint32_t i = 0; i < scene_.generated[0].count; ++i)
    if (effects_->behaviour_state(i) == "cheer" && frame_.fade_weight[i] == 0.0f)
      cheering += frame_.clip[i] == cheer;
  EXPECT_GT(cheering, 0u);
}

TEST_F(CrowdEffectsTest, CrossfadePathHoldsAndStartsOneShotClips) {
  // Seated = "sit" held at its last frame; stand_up plays "stand-up" from each switch.
  load(R"({"states": [
      {"name": "seated", "clips": [{"clip": "sit", "hold": true}], "pose": "down", "rest": true,
       "interruptible": true},
      {"name": "stand_up", "clips": ["stand-up"], "pose_in": "down", "pose_out": "up"},
      {"name": "cheer", "clips": ["cheer"], "pose": "up", "interruptible": true},
      {"name": "sit_down", "clips": ["sit"], "pose_in": "up", "pose_out": "down"}],
    "crossfade": {"time": 0.3},
    "spectators": {"transitions": [{"from": "seated", "to": "stand_up"},
        {"from": "stand_up", "to": "cheer"}, {"from": "cheer", "to": "sit_down"},
        {"from": "sit_down", "to": "seated"}],
      "reactions": [{"event": "goal", "supporters": "cheer"}],
      "teams": [{"name": "A", "generators": [0], "embarrassment": 0}, {"name": "B", "generators": [1]}],
      "events": [{"kind": "goal", "time": 1, "team": "A", "excitement": 2}]}})");
  const uint32_t sit = static_cast<uint32_t>(scene_.find_clip(0, "sit"));
  const uint32_t stand_up = static_cast<uint32_t>(scene_.find_clip(0, "stand-up"));
  const PackClip& sit_clip = *scene_.clips[sit].clip;
  const PackClip& stand_clip = *scene_.clips[stand_up].clip;
  const float dt = 1.0f / 30.0f;
  uint32_t seated_checked = 0, started_checked = 0;
  std::vector<float> switched_at(n(), -1.0f);
  for (int step = 0; step <= 75; ++step) {
    const float t = static_cast<float>(step) * dt;
    ASSERT_TRUE(effects_->update(scene_, t, dt, frame_).ok());
    for (uint32_t i = 0; i < n(); ++i) {
      const std::string state = effects_->behaviour_state(i);
      if (state == "seated" && frame_.fade_weight[i] == 0.0f) {
        ASSERT_EQ(frame_.clip[i], sit);
        const runtime::FrameChoice f = runtime::choose_frame(
            sit_clip, t, scene_.instances.speed[i], frame_.time_offset[i], scene_.animation.filter);
        ASSERT_EQ(f.frame0, sit_clip.frame_count - 1) << "held at the last frame";
        ++seated_checked;
      }
      if (state == "stand_up" && switched_at[i] < 0.0f) {
        switched_at[i] = t;
        // The fade target starts the clip where the FSM switched (within one tick).
        ASSERT_EQ(frame_.fade_clip[i], stand_up);
        const runtime::FrameChoice f = runtime::choose_frame(
            stand_clip, t, 1.0f, frame_.fade_time_offset[i], FrameFilter::kNearest);
        EXPECT_LE(f.frame0, 4u) << "instance " << i << " at " << t << " s";
        ++started_checked;
      }
    }
  }
  EXPECT_GT(seated_checked, n());
  EXPECT_GT(started_checked, 0u);
  EXPECT_EQ(counters().poses_evaluated, 0u);
}

TEST_F(CrowdEffectsTest, FsmWithoutSharingOrCrossfadeSwitchesClips) {
  load(std::string("{") + test::kStates + ", " + test::spectators_block() + "}");
  run(0.0f, 3.0f);
  EXPECT_EQ(counters().constructed_systems, 1u);
  ASSERT_EQ(frame_.clip.size(), n());
  ASSERT_EQ(frame_.time_offset.size(), n());
  EXPECT_TRUE(frame_.fade_clip.empty());
  EXPECT_TRUE(frame_.pose.empty());
  const uint32_t cheer = static_cast<uint32_t>(scene_.find_clip(0, "cheer"));
  uint32_t switched = 0;
  for (size_t i = 0; i < n(); ++i) switched += frame_.clip[i] == cheer;
  EXPECT_GT(switched, 0u);
}

TEST_F(CrowdEffectsTest, TimeMustNotGoBack) {
  load(std::string("{") + test::kStates + ", " + test::spectators_block() + "}");
  ASSERT_TRUE(effects_->update(scene_, 2.0f, 0.0f, frame_).ok());
  EXPECT_EQ(effects_->update(scene_, 1.0f, 0.0f, frame_).code(),
            runtime::StatusCode::kInvalidArgument);
}

TEST_F(CrowdEffectsTest, DocumentedExampleLoadsAndRuns) {
  // The json block of docs/scene-format.md's "Effects" section, on the two-grid scene.
  std::ifstream in(std::string(CROWDBAKE_SOURCE_DIR) + "/docs/scene-format.md");
  const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t section = doc.find("\n## Effects\n");
  ASSERT_NE(section, std::string::npos);
  const size_t start = doc.find("```json\n", section);
  ASSERT_NE(start, std::string::npos);
  const size_t end = doc.find("```", start + 8);
  const std::string block = doc.substr(start + 8, end - start - 8);
  const size_t open = block.find("\"effects\": ") + 11, close = block.rfind('}');
  load(block.substr(open, close - open));
  EXPECT_EQ(counters().constructed_systems, 2u);
  EXPECT_EQ(counters().transition_instances, 24u);
  run(0.0f, 5.0f, 10.0f);
  EXPECT_GT(counters().fsm_state_changes, 0u);
}

// Poses come from the pack itself: sampling a clip built from the animation texture at a key
// and taking it back through local → model → S_j = G_j · B_j⁻¹ gives the texture row.
TEST_F(CrowdEffectsTest, SharedPosesReproduceTheAnimationTextureRows) {
  load("");
  const runtime::Pack& pack = scene_.types[0].pack;
  Skeleton skeleton;
  const Status read = skeleton_from_pack(pack, skeleton);
  ASSERT_TRUE(read) << read.message();
  const std::vector<glm::mat4> inverse_bind = inverse_bind_matrices(pack);
  const size_t joints = skeleton.joint_count();
  std::vector<Transform> local(joints);
  std::vector<glm::mat4> model(joints);
  std::vector<float> skin(12 * joints);
  double worst = 0.0;
  for (uint32_t c = 0; c < pack.contents().clips.size(); ++c) {
    KeyframeClip clip;
    const Status decoded = keyframe_clip_from_pack(pack, c, false, clip);
    ASSERT_TRUE(decoded) << decoded.message();
    const PackClip& pc = pack.contents().clips[c];
    for (uint32_t f = 0; f < pc.frame_count; f += 7) {
      SamplingJob sample{&clip, f / static_cast<double>(pc.fps), local};
      ASSERT_TRUE(sample.Run());
      for (const Transform& t : local) {
        ASSERT_TRUE(is_valid_transform(t));
        ASSERT_NEAR(glm::length(t.rotation), 1.0f, 1e-5f);
      }
      LocalToModelJob to_model{&skeleton, local, model};
      ASSERT_TRUE(to_model.Run());
      skinning_matrices(model, inverse_bind, skin.data());
      for (uint32_t j = 0; j < joints; ++j) {
        float row[12];
        runtime::decode_skinning_matrix(pack.contents().animation, pc.first_row + f,
                                        pc.first_row + f, 0.0f, j, row);
        for (int k = 0; k < 12; ++k)
          worst = std::max(worst, static_cast<double>(std::fabs(row[k] - skin[12 * j + k])));
      }
    }
  }
  EXPECT_LT(worst, 1e-4) << "largest difference between a shared pose and its texture row";
}

}  // namespace
}  // namespace crowdbake::effects
