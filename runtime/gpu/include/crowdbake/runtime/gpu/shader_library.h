// The SPIR-V of every shader in shaders/, compiled by glslc at build time and embedded into
// crowdbake_gpu (cmake/EmbedSpirv.cmake), so programs need no shader files at run time.
#pragma once

#include <cstddef>
#include <cstdint>

#include "crowdbake/runtime/span.h"

namespace crowdbake::runtime::gpu {

// The SPIR-V words of a shader, by its file name in shaders/ ("reconstruct.comp"); empty
// when no such shader was built.
Span<const uint32_t> find_spirv(const char* name);

namespace detail {
struct EmbeddedShader {
  const char* name;  // null ends the table
  const uint32_t* words;
  size_t word_count;
};
extern const EmbeddedShader kEmbeddedShaders[];
}  // namespace detail

}  // namespace crowdbake::runtime::gpu
