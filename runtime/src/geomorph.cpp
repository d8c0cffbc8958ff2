#include "crowdbake/runtime/geomorph.h"

#include <algorithm>
#include <cmath>

namespace crowdbake::runtime {

std::vector<GeomorphVertex> geomorph_table(const ProgressiveView& mesh) {
  std::vector<GeomorphVertex> table;
  const uint32_t n = mesh.vertex_count;
  if (mesh.collapse_to.size() != n || mesh.group_start.size() != n) return table;
  table.resize(n);
  // note: a group [s, e) is drawn for requests n >= e (usable_vertices rounds down to s).
  const uint32_t always = usable_vertices(mesh, mesh.min_vertices);
  uint32_t end = n;
  for (uint32_t v = n; v-- > 0;) {
    if (v + 1 < n && mesh.group_start[v + 1] != mesh.group_start[v]) end = v + 1;
    const uint32_t parent = mesh.collapse_to[v];
    const bool morphs = v >= always && parent < v;
    table[v] = {morphs ? parent : v, morphs ? end : kGeomorphNever};
  }
  return table;
}

float geomorph_weight(const GeomorphVertex& vertex, float x, float fraction) {
  if (vertex.removal == kGeomorphNever || !(fraction > 0.0f) || !(x > 0.0f) || !std::isfinite(x))
    return 0.0f;
  const float window = std::max(fraction * x, 1.0f);
  // note: 1 − (x − r) / W, not (r + W − x) / W: exactly 1 at x = r (x − r is then exact).
  const float m = 1.0f - (x - static_cast<float>(vertex.removal)) / window;
  return std::clamp(m, 0.0f, 1.0f);
}

bool geomorph_values(Span<const GeomorphVertex> table, float x, float fraction, uint32_t count,
                     Span<const float> values, Span<float> out) {
  if (count > table.size() || values.size() < 3 * size_t{count} || out.size() < 3 * size_t{count})
    return false;
  for (uint32_t v = 0; v < count; ++v) {
    // note: the skinning pass's loop (skin_pass.comp), so a vertex at m = 1 gets its target's
    // value bit for bit (0 + y == y) and an unmorphed one its own.
    float m = geomorph_weight(table[v], x, fraction);
    float sum[3];
    for (int k = 0; k < 3; ++k) sum[k] = (1.0f - m) * values[3 * size_t{v} + k];
    float weight = m;
    for (uint32_t a = table[v].parent; weight > 0.0f; a = table[a].parent) {
      m = geomorph_weight(table[a], x, fraction);
      const float keep = weight * (1.0f - m);
      for (int k = 0; k < 3; ++k) sum[k] = sum[k] + keep * values[3 * size_t{a} + k];
      weight = weight * m;
    }
    for (int k = 0; k < 3; ++k) out[3 * size_t{v} + k] = sum[k];
  }
  return true;
}

}  // namespace crowdbake::runtime
