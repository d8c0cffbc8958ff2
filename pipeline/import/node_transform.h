// Splitting a node's 4x4 matrix into the TRS form joints animate in.
#pragma once

#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake {

// The nearest T * R * S to an affine matrix. A mirror (negative determinant) goes into
// scale.x; shear is dropped (Gram-Schmidt keeps the rotation orthonormal) and residual,
// when given, receives the largest element-wise difference between m and the recomposed
// TRS relative to m's largest element.
Transform decompose_transform(const glm::dmat4& m, double* residual = nullptr);

// Writes m = T * R * S into out and returns true when m is such a product (no shear,
// no projection, no zero scale) to within 1e-6 relative; otherwise returns false and
// leaves out untouched. A mirror (negative determinant) goes into scale.x.
bool split_transform(const glm::dmat4& m, Transform& out);

}  // namespace crowdbake
