// Bounds-checked reading of glTF accessors into doubles: every component type, the
// normalized-integer rule, byteStride, and sparse substitution. A file's offsets and
// counts are never trusted: anything outside its buffer throws a crowdbake::Error.
#pragma once

#include <string>
#include <vector>

#include "import/tinygltf.h"

namespace crowdbake {

struct AccessorData {
  size_t count = 0;
  int components = 0;          // 1 (SCALAR) .. 16 (MAT4)
  std::vector<double> values;  // count * components, row of one element after another

  double at(size_t element, int component) const {
    return values[element * components + component];
  }
};

// Reads accessor `index`, requiring one of `allowed_components` per element.
// `what` names the use ("POSITION of mesh 'body'") for error messages.
AccessorData read_accessor(const tg::Model& model, int index,
                           std::initializer_list<int> allowed_components, const std::string& file,
                           const std::string& what);

}  // namespace crowdbake
