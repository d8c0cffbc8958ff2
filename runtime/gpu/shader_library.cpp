#include "crowdbake/runtime/gpu/shader_library.h"

#include <cstring>

namespace crowdbake::runtime::gpu {

Span<const uint32_t> find_spirv(const char* name) {
  if (name == nullptr) return {};
  for (const detail::EmbeddedShader* s = detail::kEmbeddedShaders; s->name != nullptr; ++s)
    if (std::strcmp(s->name, name) == 0) return {s->words, s->word_count};
  return {};
}

}  // namespace crowdbake::runtime::gpu
