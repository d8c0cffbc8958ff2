// Instantiates tinygltf's implementation under crowdbake's private namespace
// (see tinygltf.h for why).
#define TINYGLTF_IMPLEMENTATION
#include "import/tinygltf.h"
