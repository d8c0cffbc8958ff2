// Frame choice and root motion (frame_choice.h).
#include "crowdbake/formats/frame_choice.h"

#include <cmath>

namespace crowdbake {
namespace {

constexpr double kTwoPi = 6.283185307179586476925;

// Floor of a float as a 64-bit integer, saturated far beyond any clip length.
int64_t floor_to_int(float value) {
  if (!(value == value)) return 0;  // note: NaN time plays frame 0
  const float limit = 4.0e18f;
  if (value > limit) value = limit;
  if (value < -limit) value = -limit;
  return static_cast<int64_t>(std::floor(value));
}

// Floor division and non-negative remainder.
void divide(int64_t value, uint32_t count, int64_t& quotient, uint32_t& remainder) {
  int64_t q = value / count, r = value % count;
  if (r < 0) {
    r += count;
    q -= 1;
  }
  quotient = q;
  remainder = static_cast<uint32_t>(r);
}

int32_t saturate_cycle(int64_t cycle) {
  if (cycle > INT32_MAX) return INT32_MAX;
  if (cycle < INT32_MIN) return INT32_MIN;
  return static_cast<int32_t>(cycle);
}

}  // namespace

FrameChoice choose_frame(const PackClip& clip, float time, float speed, float time_offset,
                         FrameFilter filter) {
  FrameChoice out;
  const uint32_t count = clip.frame_count;
  if (count <= 1) return out;
  const float f = (time + time_offset) * clip.fps * speed;
  if (filter == FrameFilter::kNearest) {
    const int64_t played = floor_to_int(f + 0.5f);
    if (clip.looping) {
      int64_t cycle = 0;
      divide(played, count, cycle, out.frame0);
      out.cycle = saturate_cycle(cycle);
    } else {
      out.frame0 = played <= 0 ? 0 : played >= count ? count - 1 : static_cast<uint32_t>(played);
    }
    out.frame1 = out.frame0;
    return out;
  }
  if (clip.looping) {
    const int64_t k = floor_to_int(f);
    int64_t cycle = 0;
    divide(k, count, cycle, out.frame0);
    out.frame1 = out.frame0 + 1 == count ? 0 : out.frame0 + 1;
    out.cycle = saturate_cycle(cycle);
    const float u = (f == f) ? f - std::floor(f) : 0.0f;
    out.blend = u < 1.0f ? u : 0.0f;  // note: f - floor(f) can round up to 1 for tiny negative f
    if (u >= 1.0f) {
      out.frame0 = out.frame1;
      out.frame1 = out.frame0 + 1 == count ? 0 : out.frame0 + 1;
      if (out.frame0 == 0) out.cycle = saturate_cycle(cycle + 1);
    }
    return out;
  }
  const float last = static_cast<float>(count - 1);
  if (!(f > 0.0f)) return out;  // before the start (or NaN): frame 0
  if (f >= last) {
    out.frame0 = out.frame1 = count - 1;
    return out;
  }
  out.frame0 = static_cast<uint32_t>(std::floor(f));
  out.frame1 = out.frame0 + 1 < count ? out.frame0 + 1 : out.frame0;
  out.blend = f - std::floor(f);
  return out;
}

void frame_root_motion(const PackClip& clip, const FrameChoice& frame, float out[3]) {
  out[0] = out[1] = out[2] = 0.0f;
  const size_t n = clip.frame_count;
  if (clip.root_motion.size() != 3 * n || n == 0 || frame.frame0 >= n || frame.frame1 >= n) return;
  const float* a = &clip.root_motion[3 * size_t{frame.frame0}];
  const float* b = &clip.root_motion[3 * size_t{frame.frame1}];
  // note: a looping clip blending its last frame into frame 0 of the next cycle: in this
  // cycle's terms that frame sits at D ∘ motion(0) = D = motion(last), so the root holds.
  if (clip.looping && frame.frame1 < frame.frame0) b = a;
  double m[3];
  for (int i = 0; i < 3; ++i)
    m[i] = frame.blend == 0.0f ? double{a[i]} : double{a[i] + (b[i] - a[i]) * frame.blend};
  if (frame.cycle != 0 && clip.looping) {
    // note: with w = z + i·x, RotateY(θ) multiplies w by e^{iθ}, so one cycle D = (t, θ)
    // repeated c times is (t · Σ_{k<c} e^{ikθ}, c·θ), and the geometric sum is
    // e^{i(c−1)θ/2} · sin(cθ/2) / sin(θ/2) (c when θ → 0). Negative c uses D⁻¹.
    const float* last = &clip.root_motion[3 * (n - 1)];
    double tz = last[1], tx = last[0], theta = last[2];
    double c = frame.cycle;
    if (c < 0) {  // D⁻¹ = (−R(−θ)·t, −θ)
      const double cs = std::cos(theta), sn = std::sin(theta);
      const double iz = -(cs * tz + sn * tx), ix = -(cs * tx - sn * tz);
      tz = iz, tx = ix, theta = -theta, c = -c;
    }
    const double half = 0.5 * theta;
    const double ratio =
        std::fabs(std::sin(half)) < 1e-12 ? c : std::sin(c * half) / std::sin(half);
    const double phase = (c - 1.0) * half;
    const double sz = ratio * std::cos(phase), sx = ratio * std::sin(phase);
    const double cz = tz * sz - tx * sx, cx = tz * sx + tx * sz;  // t_c = w_t · sum
    const double yaw_c = c * theta;
    const double cs = std::cos(yaw_c), sn = std::sin(yaw_c);
    const double fz = m[1], fx = m[0];
    m[0] = cx + cs * fx + sn * fz;  // D^c ∘ m: t_c + R(cθ)·t_m, yaw adds
    m[1] = cz - sn * fx + cs * fz;
    m[2] = std::remainder(yaw_c + m[2], kTwoPi);
  }
  for (int i = 0; i < 3; ++i) out[i] = static_cast<float>(m[i]);
}

}  // namespace crowdbake
