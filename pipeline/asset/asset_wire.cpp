#include "asset/asset_wire.h"

#include <cstdint>
#include <cstring>
#include <type_traits>

namespace crowdbake {
namespace {

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
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

class WireReader {
 public:
  explicit WireReader(const std::string& bytes) : bytes_(bytes) {}

  template <typename T>
  bool pod(T& v) {
    if (left() < sizeof v) return false;
    std::memcpy(&v, bytes_.data() + at_, sizeof v);
    at_ += sizeof v;
    return true;
  }
  bool text(std::string& s) {
    uint64_t n = 0;
    if (!pod(n) || left() < n) return false;
    s.assign(bytes_, at_, n);
    at_ += n;
    return true;
  }
  template <typename T>
  bool array(std::vector<T>& v) {
    uint64_t n = 0;
    if (!pod(n) || left() / sizeof(T) < n) return false;
    v.resize(n);
    // note: an empty vector's data() may be null, which memcpy must never see.
    if (n > 0) std::memcpy(v.data(), bytes_.data() + at_, n * sizeof(T));
    at_ += n * sizeof(T);
    return true;
  }
  // A count of items that each take at least `min_bytes`, bounded by what is left.
  bool count(uint64_t& n, size_t min_bytes) { return pod(n) && n <= left() / min_bytes; }
  bool done() const { return at_ == bytes_.size(); }

 private:
  size_t left() const { return bytes_.size() - at_; }
  const std::string& bytes_;
  size_t at_ = 0;
};

template <typename T>
void write_track(WireWriter& w, const Track<T>& t) {
  w.pod(t.interpolation);
  w.array(t.times);
  w.array(t.values);
}

template <typename T>
bool read_track(WireReader& r, Track<T>& t) {
  return r.pod(t.interpolation) && r.array(t.times) && r.array(t.values);
}

}  // namespace

std::string encode_asset(const SkinnedAsset& a) {
  WireWriter w;
  w.text(a.source);
  w.pod<uint64_t>(a.files.size());
  for (const std::string& f : a.files) w.text(f);
  w.pod<uint64_t>(a.skeleton.joints.size());
  for (const Joint& j : a.skeleton.joints) {
    w.text(j.name);
    w.pod(j.parent);
    w.pod(j.rest);
    w.pod(j.pre_transform);
    w.pod(j.inverse_bind);
  }
  w.pod<uint64_t>(a.materials.size());
  for (const Material& m : a.materials) {
    w.text(m.name);
    w.pod(m.base_color);
    w.text(m.base_color_texture);
    w.pod(m.base_color_image);
    w.pod(m.uv_transform);
    w.pod(m.alpha_mode);
    w.pod(m.alpha_cutoff);
    w.pod(m.double_sided);
  }
  w.pod<uint64_t>(a.images.size());
  for (const PackImage& i : a.images) {
    w.text(i.name);
    w.text(i.mime_type);
    w.pod(i.width);
    w.pod(i.height);
    w.array(i.data);
  }
  w.pod<uint64_t>(a.primitives.size());
  for (const Primitive& p : a.primitives) {
    w.text(p.name);
    w.pod(p.material);
    w.array(p.positions);
    w.array(p.normals);
    w.array(p.uvs);
    w.array(p.joints);
    w.array(p.weights);
    w.array(p.indices);
  }
  w.pod<uint64_t>(a.clips.size());
  for (const Clip& c : a.clips) {
    w.text(c.name);
    w.pod(c.duration);
    w.pod<uint64_t>(c.channels.size());
    for (const JointChannels& ch : c.channels) {
      write_track(w, ch.translation);
      write_track(w, ch.rotation);
      write_track(w, ch.scale);
    }
  }
  w.pod(a.stats);
  w.pod<uint64_t>(a.warnings.size());
  for (const std::string& s : a.warnings) w.text(s);
  return w.take();
}

bool decode_asset(const std::string& bytes, SkinnedAsset& a) {
  WireReader r(bytes);
  a = SkinnedAsset{};
  uint64_t n = 0;
  if (!r.text(a.source) || !r.count(n, 8)) return false;
  a.files.resize(n);
  for (std::string& f : a.files)
    if (!r.text(f)) return false;
  if (!r.count(n, 8)) return false;
  a.skeleton.joints.resize(n);
  for (Joint& j : a.skeleton.joints)
    if (!r.text(j.name) || !r.pod(j.parent) || !r.pod(j.rest) || !r.pod(j.pre_transform) ||
        !r.pod(j.inverse_bind))
      return false;
  if (!r.count(n, 8)) return false;
  a.materials.resize(n);
  for (Material& m : a.materials)
    if (!r.text(m.name) || !r.pod(m.base_color) || !r.text(m.base_color_texture) ||
        !r.pod(m.base_color_image) || !r.pod(m.uv_transform) || !r.pod(m.alpha_mode) ||
        !r.pod(m.alpha_cutoff) || !r.pod(m.double_sided))
      return false;
  if (!r.count(n, 8)) return false;
  a.images.resize(n);
  for (PackImage& i : a.images)
    if (!r.text(i.name) || !r.text(i.mime_type) || !r.pod(i.width) || !r.pod(i.height) ||
        !r.array(i.data))
      return false;
  if (!r.count(n, 8)) return false;
  a.primitives.resize(n);
  for (Primitive& p : a.primitives)
    if (!r.text(p.name) || !r.pod(p.material) || !r.array(p.positions) || !r.array(p.normals) ||
        !r.array(p.uvs) || !r.array(p.joints) || !r.array(p.weights) || !r.array(p.indices))
      return false;
  if (!r.count(n, 8)) return false;
  a.clips.resize(n);
  for (Clip& c : a.clips) {
    if (!r.text(c.name) || !r.pod(c.duration) || !r.count(n, 8)) return false;
    c.channels.resize(n);
    for (JointChannels& ch : c.channels)
      if (!read_track(r, ch.translation) || !read_track(r, ch.rotation) || !read_track(r, ch.scale))
        return false;
  }
  if (!r.pod(a.stats) || !r.count(n, 8)) return false;
  a.warnings.resize(n);
  for (std::string& s : a.warnings)
    if (!r.text(s)) return false;
  return r.done();
}

}  // namespace crowdbake
