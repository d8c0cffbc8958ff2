#include "import/gltf_accessor.h"

#include <algorithm>
#include <cstring>

#include "crowdbake/pipeline/error.h"

namespace crowdbake {
namespace {

int component_size(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    case TINYGLTF_COMPONENT_TYPE_DOUBLE:
      return 8;
    default:
      return 0;
  }
}

int component_count(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    case TINYGLTF_TYPE_MAT2:
      return 4;
    case TINYGLTF_TYPE_MAT3:
      return 9;
    case TINYGLTF_TYPE_MAT4:
      return 16;
    default:
      return 0;
  }
}

template <typename T>
T load(const unsigned char* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

// glTF §3.11: normalized integers map to [0,1] (unsigned) or [-1,1] (signed, clamped).
double decode(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const double v = load<int8_t>(p);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const double v = load<uint8_t>(p);
      return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const double v = load<int16_t>(p);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const double v = load<uint16_t>(p);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_INT:
      return load<int32_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return load<uint32_t>(p);
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return load<float>(p);
    case TINYGLTF_COMPONENT_TYPE_DOUBLE:
      return load<double>(p);
    default:
      return 0.0;
  }
}

struct View {
  const unsigned char* data = nullptr;
  size_t size = 0;
  size_t stride = 0;
};

View view_of(const tg::Model& model, int index, size_t element_size, const std::string& file,
             const std::string& what) {
  if (index < 0 || index >= static_cast<int>(model.bufferViews.size()))
    throw input_error(file,
                      what + ": bufferView index out of range; the file is corrupt, re-export it");
  const tg::BufferView& bv = model.bufferViews[index];
  if (bv.buffer < 0 || bv.buffer >= static_cast<int>(model.buffers.size()))
    throw input_error(file,
                      what + ": buffer index out of range; the file is corrupt, re-export it");
  const std::vector<unsigned char>& buffer = model.buffers[bv.buffer].data;
  if (bv.byteOffset > buffer.size() || bv.byteLength > buffer.size() - bv.byteOffset)
    throw input_error(
        file, what + ": bufferView lies outside its buffer; the file is truncated or corrupt");
  View v;
  v.data = buffer.data() + bv.byteOffset;
  v.size = bv.byteLength;
  v.stride = bv.byteStride ? bv.byteStride : element_size;
  return v;
}

void check_range(const View& view, size_t offset, size_t count, size_t element_size,
                 const std::string& file, const std::string& what) {
  if (count == 0) return;
  const size_t last = view.stride * (count - 1);
  if (view.stride != 0 && last / view.stride != count - 1)
    throw input_error(file, what + ": accessor size overflows; the file is corrupt");
  if (offset > view.size || last > view.size - offset || element_size > view.size - offset - last)
    throw input_error(
        file, what + ": accessor reads past the end of its bufferView; the file is corrupt");
}

}  // namespace

AccessorData read_accessor(const tg::Model& model, int index,
                           std::initializer_list<int> allowed_components, const std::string& file,
                           const std::string& what) {
  if (index < 0 || index >= static_cast<int>(model.accessors.size()))
    throw input_error(file,
                      what + ": accessor index out of range; the file is corrupt, re-export it");
  const tg::Accessor& acc = model.accessors[index];
  const int csize = component_size(acc.componentType);
  const int ccount = component_count(acc.type);
  if (csize == 0 || ccount == 0)
    throw input_error(file, what + ": unknown accessor component type; the file is corrupt");
  if (std::find(allowed_components.begin(), allowed_components.end(), ccount) ==
      allowed_components.end())
    throw input_error(file, what + ": accessor has " + std::to_string(ccount) +
                                " components per element, which this attribute cannot have");
  // note: a limit far above any real character keeps a hostile count from allocating
  // gigabytes before the range check below can reject it.
  if (acc.count > (size_t{1} << 28))
    throw input_error(
        file, what + ": accessor count " + std::to_string(acc.count) + " is implausibly large");

  AccessorData out;
  out.count = acc.count;
  out.components = ccount;
  out.values.assign(acc.count * ccount, 0.0);
  const size_t element_size = static_cast<size_t>(csize) * ccount;

  if (acc.bufferView >= 0) {
    const View view = view_of(model, acc.bufferView, element_size, file, what);
    check_range(view, acc.byteOffset, acc.count, element_size, file, what);
    for (size_t e = 0; e < acc.count; ++e) {
      const unsigned char* p = view.data + acc.byteOffset + e * view.stride;
      for (int c = 0; c < ccount; ++c)
        out.values[e * ccount + c] = decode(p + c * csize, acc.componentType, acc.normalized);
    }
  }

  if (acc.sparse.isSparse && acc.sparse.count > 0) {
    const size_t n = static_cast<size_t>(acc.sparse.count);
    if (n > acc.count)
      throw input_error(file, what + ": sparse count exceeds accessor count; the file is corrupt");
    const int isize = component_size(acc.sparse.indices.componentType);
    if (isize == 0 || isize > 4)
      throw input_error(file, what + ": bad sparse index type; the file is corrupt");
    const View iv =
        view_of(model, acc.sparse.indices.bufferView, isize, file, what + " (sparse indices)");
    const View vv =
        view_of(model, acc.sparse.values.bufferView, element_size, file, what + " (sparse values)");
    // note: sparse index and value views are always tightly packed (glTF §3.6.2.3).
    const View ti{iv.data, iv.size, static_cast<size_t>(isize)};
    const View tv{vv.data, vv.size, element_size};
    check_range(ti, acc.sparse.indices.byteOffset, n, isize, file, what + " (sparse indices)");
    check_range(tv, acc.sparse.values.byteOffset, n, element_size, file, what + " (sparse values)");
    for (size_t s = 0; s < n; ++s) {
      const double target = decode(ti.data + acc.sparse.indices.byteOffset + s * isize,
                                   acc.sparse.indices.componentType, false);
      if (!(target >= 0.0) || target >= static_cast<double>(acc.count))
        throw input_error(file, what + ": sparse index out of range; the file is corrupt");
      const unsigned char* p = tv.data + acc.sparse.values.byteOffset + s * element_size;
      for (int c = 0; c < ccount; ++c)
        out.values[static_cast<size_t>(target) * ccount + c] =
            decode(p + c * csize, acc.componentType, acc.normalized);
    }
  }
  return out;
}

}  // namespace crowdbake
