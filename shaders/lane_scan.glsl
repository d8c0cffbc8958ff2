// One workgroup of 256 lanes, each owning a contiguous run of keys: the exclusive prefix of
// the lanes' (sum, max) pairs in lane order. The single-workgroup passes walk their keys in
// runs of at most key_total / 256, so no lane loops over every key: lavapipe (llvmpipe) ends
// every loop of a shader invocation after 65,535 iterations in all (LP_MAX_TGSI_LOOP_ITERATIONS),
// silently, and a pass that walked every key in one invocation stopped short at scale.
#ifndef CROWDBAKE_LANE_SCAN_GLSL
#define CROWDBAKE_LANE_SCAN_GLSL

const uint kScanLanes = 256u;

shared uvec2 lane_scan_values[kScanLanes];

// The keys lane `lane` owns: [first, last).
uvec2 lane_run(uint lane, uint key_total) {
  const uint run = (key_total + kScanLanes - 1u) / kScanLanes;
  const uint first = min(lane * run, key_total);
  return uvec2(first, min(first + run, key_total));
}

// The lanes before `lane`: (sum of their x, max of their y); (0, 0) for lane 0.
uvec2 lane_exclusive_scan(uint lane, uvec2 value) {
  lane_scan_values[lane] = value;
  barrier();
  for (uint offset = 1u; offset < kScanLanes; offset <<= 1) {
    const uvec2 other = lane >= offset ? lane_scan_values[lane - offset] : uvec2(0u);
    barrier();
    const uvec2 mine = lane_scan_values[lane];
    lane_scan_values[lane] = uvec2(mine.x + other.x, max(mine.y, other.y));
    barrier();
  }
  const uvec2 before = lane > 0u ? lane_scan_values[lane - 1u] : uvec2(0u);
  barrier();
  return before;
}

#endif
