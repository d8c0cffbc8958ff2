// Options that must not change what the simplifier makes (threads, the lookahead): one
// character simplified with two option sets gives the same arrays and counts.
#pragma once

#include <gtest/gtest.h>

#include "crowdbake/pipeline/simplify.h"
#include "pipeline_calls.h"

namespace crowdbake::test {

// Returns the report of the `reference` run.
inline SimplifyReport expect_same_simplification(const SkinnedAsset& a,
                                                 const SimplifyOptions& reference,
                                                 const SimplifyOptions& other) {
  SimplifyReport r1, r2;
  const ProgressiveMesh x = simplify_or_throw(a, reference, &r1);
  const ProgressiveMesh y = simplify_or_throw(a, other, &r2);
  EXPECT_EQ(x.vertex_source, y.vertex_source);
  EXPECT_EQ(x.triangles, y.triangles);
  EXPECT_EQ(x.collapse_to, y.collapse_to);
  EXPECT_EQ(r1.priced_flips, r2.priced_flips);
  EXPECT_EQ(r1.rejected_flips, r2.rejected_flips);
  EXPECT_EQ(r1.seam_crossings, r2.seam_crossings);
  return r1;
}

}  // namespace crowdbake::test
