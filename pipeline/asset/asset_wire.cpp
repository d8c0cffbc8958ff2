#include "asset/asset_wire.h"

#include <cstdint>
#include <cstring>
#include <type_traits>

namespace crowdbake {
namespace {

// Writer and reader offer the same four operations, so one field list (transfer_asset)
// serves both directions and the two cannot drift apart.
class WireWriter {
 public:
  template <typename T>
  void pod(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void text(const std::string& s) {
    pod<uint64_t>(s.size());
    out_.append(s);
  }
  template <typename T>
  void array(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    pod<uint64_t>(v.size());
    if (!v.empty()) out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  template <typename T, typename Item>
  void list(const std::vector<T>& items, Item item) {
    pod<uint64_t>(items.size());
    for (const T& i : items) item(i);
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

// Fails once and stays failed: every later operation does nothing, so transfer_asset needs
// no early returns and ok() tells the whole story.
class WireReader {
 public:
  explicit WireReader(const std::string& bytes) : bytes_(bytes) {}

  template <typename T>
  void pod(T& v) {
    if (!take(sizeof v)) return;
    std::memcpy(&v, bytes_.data() + at_ - sizeof v, sizeof v);
  }
  void text(std::string& s) {
    uint64_t n = 0;
    pod(n);
    if (!take_items(n, 1)) return;
    s.assign(bytes_, at_ - n, n);
  }
  template <typename T>
  void array(std::vector<T>& v) {
    uint64_t n = 0;
    pod(n);
    if (!take_items(n, sizeof(T))) return;
    v.resize(n);
    // note: an empty vector's data() may be null, which memcpy must never see.
    if (n > 0) std::memcpy(v.data(), bytes_.data() + at_ - n * sizeof(T), n * sizeof(T));
  }
  // Every item takes at least 8 bytes, so a count beyond what is left is refused before
  // anything is allocated for it (a child may die half-way through writing).
  template <typename T, typename Item>
  void list(std::vector<T>& items, Item item) {
    uint64_t n = 0;
    pod(n);
    if (!ok_ || n > left() / 8) {
      ok_ = false;
      return;
    }
    items.resize(n);
    for (T& i : items) {
      if (!ok_) return;
      item(i);
    }
  }
  bool done() const { return ok_ && at_ == bytes_.size(); }

 private:
  size_t left() const { return bytes_.size() - at_; }
  bool take(size_t n) {
    if (!ok_ || left() < n) ok_ = false;
    if (ok_) at_ += n;
    return ok_;
  }
  bool take_items(uint64_t n, size_t item_bytes) {
    if (ok_ && left() / item_bytes < n) ok_ = false;
    return take(ok_ ? n * item_bytes : 0);
  }
  const std::string& bytes_;
  size_t at_ = 0;
  bool ok_ = true;
};

template <typename T>
struct IsVector : std::false_type {};
template <typename T>
struct IsVector<std::vector<T>> : std::true_type {};

// One call per struct: strings travel as text, vectors of plain values as arrays, and
// everything else as its bytes.
template <typename Wire, typename... T>
void fields(Wire& w, T&... values) {
  auto one = [&w](auto& v) {
    using U = std::remove_const_t<std::remove_reference_t<decltype(v)>>;
    if constexpr (std::is_same_v<U, std::string>)
      w.text(v);
    else if constexpr (IsVector<U>::value)
      w.array(v);
    else
      w.pod(v);
  };
  (one(values), ...);
}

// `Asset` is `const SkinnedAsset` for the writer and `SkinnedAsset` for the reader.
template <typename Wire, typename Asset>
void transfer_asset(Wire& w, Asset& a) {
  w.text(a.source);
  w.list(a.files, [&](auto& f) { w.text(f); });
  w.list(a.skeleton.joints,
         [&](auto& j) { fields(w, j.name, j.parent, j.rest, j.pre_transform, j.inverse_bind); });
  w.list(a.materials, [&](auto& m) {
    fields(w, m.name, m.base_color, m.base_color_texture, m.base_color_image, m.uv_transform,
           m.alpha_mode, m.alpha_cutoff, m.double_sided);
  });
  w.list(a.images, [&](auto& i) { fields(w, i.name, i.mime_type, i.width, i.height, i.data); });
  w.list(a.primitives, [&](auto& p) {
    fields(w, p.name, p.material, p.positions, p.normals, p.uvs, p.colors, p.joints, p.weights,
           p.indices);
  });
  w.list(a.clips, [&](auto& c) {
    fields(w, c.name, c.duration);
    w.list(c.channels, [&](auto& ch) {
      auto track = [&](auto& t) { fields(w, t.interpolation, t.times, t.values); };
      track(ch.translation);
      track(ch.rotation);
      track(ch.scale);
    });
  });
  w.pod(a.stats);
  w.list(a.warnings, [&](auto& s) { w.text(s); });
}

}  // namespace

std::string encode_asset(const SkinnedAsset& a) {
  WireWriter w;
  transfer_asset(w, a);
  return w.take();
}

bool decode_asset(const std::string& bytes, SkinnedAsset& a) {
  WireReader r(bytes);
  a = SkinnedAsset{};
  transfer_asset(r, a);
  return r.done();
}

}  // namespace crowdbake
