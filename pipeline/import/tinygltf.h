// The one way crowdbake includes tinygltf.
//
// Debian's libdraco.so exports its own, older copy of tinygltf with 71 symbols mangled
// exactly like libtinygltf.so's (docs/toolchain.md §3), and Assimp links libdraco. With two
// providers of one symbol the dynamic loader binds each call to whichever library comes
// first in search order, so a link-order change would silently run a different parser
// revision with a different struct layout. Instead of relying on link order we compile
// Debian's tinygltf header ourselves (tinygltf_impl.cpp) inside a namespace of our own:
// no crowdbake symbol can bind to libdraco's copy. tests/pipeline/symbol_binding_test
// checks this on the built executable.
#pragma once

#define tinygltf crowdbake_tinygltf
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>
#undef tinygltf

namespace tg = ::crowdbake_tinygltf;
