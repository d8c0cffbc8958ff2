// A procedurally generated stadium spectator: a skinned, animated humanoid built
// entirely in code, used as crowdbake's sample character and test input.
//
// The character stands at the origin facing +Z, Y up, in metres, about 1.75 m tall.
// Its skeleton has 21 joints (hips root, spine, chest, neck, head, and per side
// shoulder, upper_arm, forearm, hand, upper_leg, leg, foot, toe, prefixed "left_" or
// "right_"); every rest rotation is the identity and the bind pose is the rest pose.
// The mesh is five primitives (skin, shirt, trousers, shoes, hair) with normals, UVs
// and up to four smooth skin weights per vertex. Eight LINEAR clips at 30 keys/s:
// idle, sit, stand-up, arm-up, clap, cheer, arm-down, walk (walk carries root motion
// as a hips translation track).
#pragma once

#include <cstdint>

#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake::samples {

struct SpectatorOptions {
  // Mesh resolution: 0 = low (about 2k triangles), 1 = default (about 4.5k),
  // 2 = high (about 10k). Values outside 0..2 are clamped.
  int detail = 1;
  // 0 = the reference look; any other value varies height (±6%), girth, skin tone and
  // clothes colours deterministically.
  uint32_t seed = 0;
};

// Builds the character. Deterministic: equal options give an identical asset.
SkinnedAsset make_spectator_character(const SpectatorOptions& options = {});

}  // namespace crowdbake::samples
