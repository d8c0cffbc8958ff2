// scene.json → Scene (docs/scene-format.md). Three stages, so a file's own mistakes are
// reported before any pack is opened: (1) read every key into plain structs, checking types,
// ranges and unknown keys; (2) open the packs; (3) resolve names against the packs (clips)
// and build the instance arrays, listed instances first, then each generator in order.
// Errors are thrown inside this file as scene_error and returned as a Status at the boundary.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <new>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "crowdbake/base/random.h"
#include "crowdbake/runtime/scene.h"

namespace crowdbake::runtime {
namespace {

using json = nlohmann::json;

constexpr float kPi = 3.14159265358979323846f;

struct scene_error {
  StatusCode code;
  std::string message;  // "<key path>: <problem>"
};

[[noreturn]] void fail(const std::string& path, const std::string& problem,
                       StatusCode code = StatusCode::kInvalidScene) {
  throw scene_error{code, (path.empty() ? std::string("scene") : path) + ": " + problem};
}

std::string key_path(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}
std::string item_path(const std::string& path, size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

std::string show(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.7g", v);  // note: values end up as float
  return buffer;
}

// "string \"abc\"", "number 3", "array", ...: what was found instead.
std::string describe(const json& v) {
  if (v.is_string()) return "string \"" + v.get<std::string>() + "\"";
  if (v.is_number()) return "number " + v.dump();
  if (v.is_boolean()) return std::string("boolean ") + (v.get<bool>() ? "true" : "false");
  return v.type_name();
}

const json* find(const json& object, const char* key) {
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

void check_object(const json& v, const std::string& path, std::initializer_list<const char*> keys) {
  if (!v.is_object()) fail(path, "expected an object, got " + describe(v));
  for (const auto& item : v.items()) {
    bool known = false;
    for (const char* k : keys) known = known || item.key() == k;
    if (!known) {
      std::string list;
      for (const char* k : keys) list += std::string(list.empty() ? "" : ", ") + k;
      fail(key_path(path, item.key()), "unknown key (expected one of: " + list + ")");
    }
  }
}

const json& require(const json& object, const char* key, const std::string& path) {
  const json* v = find(object, key);
  if (!v) fail(key_path(path, key), "missing (required)");
  return *v;
}

double number(const json& v, const std::string& path) {
  if (!v.is_number()) fail(path, "expected a number, got " + describe(v));
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(path, "must be a finite number");
  // note: values are stored as float; a double beyond float range would become infinite.
  if (std::fabs(d) > 1e30) fail(path, "must be within ±1e30, got " + show(d));
  return d;
}

double number_at_least(const json& v, const std::string& path, double lo, bool inclusive) {
  const double d = number(v, path);
  if (inclusive ? d < lo : d <= lo)
    fail(path,
         std::string("must be ") + (inclusive ? ">= " : "> ") + show(lo) + ", got " + show(d));
  return d;
}

int64_t integer(const json& v, const std::string& path, int64_t lo, int64_t hi) {
  if (!v.is_number_integer()) fail(path, "expected an integer, got " + describe(v));
  if (v.is_number_unsigned()) {
    const uint64_t u = v.get<uint64_t>();
    if (lo > 0 && u < static_cast<uint64_t>(lo))
      fail(path, "must be at least " + std::to_string(lo) + ", got " + v.dump());
    if (u > static_cast<uint64_t>(hi))
      fail(path, "must be at most " + std::to_string(hi) + ", got " + v.dump());
    return static_cast<int64_t>(u);
  }
  const int64_t i = v.get<int64_t>();
  if (i < lo) fail(path, "must be at least " + std::to_string(lo) + ", got " + std::to_string(i));
  if (i > hi) fail(path, "must be at most " + std::to_string(hi) + ", got " + std::to_string(i));
  return i;
}

std::string string(const json& v, const std::string& path) {
  if (!v.is_string()) fail(path, "expected a string, got " + describe(v));
  return v.get<std::string>();
}

bool boolean(const json& v, const std::string& path) {
  if (!v.is_boolean()) fail(path, "expected true or false, got " + describe(v));
  return v.get<bool>();
}

const json& array(const json& v, const std::string& path) {
  if (!v.is_array()) fail(path, "expected an array, got " + describe(v));
  return v;
}

template <size_t N>
std::array<float, N> numbers(const json& v, const std::string& path) {
  if (!v.is_array() || v.size() != N)
    fail(path, "expected an array of " + std::to_string(N) + " numbers, got " +
                   (v.is_array() ? "an array of " + std::to_string(v.size()) : describe(v)));
  std::array<float, N> out{};
  for (size_t i = 0; i < N; ++i) out[i] = static_cast<float>(number(v[i], item_path(path, i)));
  return out;
}

// A number, or a range [min, max] drawn uniformly per instance.
struct Range {
  float lo = 0.0f, hi = 0.0f;
};

Range range(const json& v, const std::string& path, double lo, bool inclusive) {
  if (v.is_array()) {
    if (v.size() != 2)
      fail(path,
           "expected a number or a range [min, max], got an array of " + std::to_string(v.size()));
    const double a = number_at_least(v[0], item_path(path, 0), lo, inclusive);
    const double b = number_at_least(v[1], item_path(path, 1), lo, inclusive);
    if (b < a) fail(path, "range [" + show(a) + ", " + show(b) + "] has max < min");
    return {static_cast<float>(a), static_cast<float>(b)};
  }
  if (!v.is_number()) fail(path, "expected a number or a range [min, max], got " + describe(v));
  const float x = static_cast<float>(number_at_least(v, path, lo, inclusive));
  return {x, x};
}

// Generators' draws (the same on every platform, base/random.h).
class Random {
 public:
  explicit Random(uint64_t seed) : bits_(seed) {}
  uint64_t next() { return bits_.next(); }
  float unit() { return bits_.next_float(); }  // [0, 1)
  float in(const Range& r) { return r.lo + (r.hi - r.lo) * unit(); }
  uint32_t below(uint32_t n) {
    return std::min(n - 1, static_cast<uint32_t>(unit() * static_cast<float>(n)));
  }

 private:
  SplitMix64 bits_;
};

uint64_t mix(uint64_t seed, uint64_t index, uint64_t stream) {
  Random r(seed ^ (index * 0xD1B54A32D192ED03ull) ^ (stream * 0x8CB92BA72F3D8DD7ull));
  return r.next();
}

std::array<float, 4> yaw_quaternion(float degrees) {
  const float half = 0.5f * degrees * kPi / 180.0f;
  return {0.0f, std::sin(half), 0.0f, std::cos(half)};
}

// ---- Stage 1: the file's own content ----------------------------------------------------

struct RawTextures {
  bool random = false;
  std::array<int64_t, 3> value{0, 0, 0};
  std::string path;
};

struct RawColor {
  Vec3 value{0.0f, 1.0f, 1.0f};
};

struct RawType {
  std::string name, pack, path;
  TextureVariants variants;
  Shading shading = Shading::kAuto;
};

// Attributes shared by listed instances and generators (generators allow ranges).
struct RawAttributes {
  std::string path;
  std::string type;                // empty: the only type
  std::vector<std::string> clips;  // empty: clip 0; several: one drawn per instance
  Range speed{1.0f, 1.0f};
  Range time_offset{0.0f, 0.0f};
  Range scale{1.0f, 1.0f};
  RawTextures textures;
  Vec3 color{0.0f, 1.0f, 1.0f};            // listed instances
  Vec3 color_variation{0.0f, 0.0f, 0.0f};  // generators: ± hue (deg), saturation, brightness
  std::optional<float> neck_height, waist_height;
};

struct RawInstance {
  RawAttributes a;
  Vec3 position{};
  std::array<float, 4> rotation{0.0f, 0.0f, 0.0f, 1.0f};
};

struct RawGenerator {
  RawAttributes a;
  bool grid = true;
  bool relaxation = false;  // "relaxation" (grid is false then)
  std::string path;
  RelaxationRequest relax;
  uint64_t seed = 0;
  // seat_grid
  Vec3 origin{0.0f, 0.0f, 0.0f};
  uint32_t rows = 0, columns = 0;
  float spacing[2] = {0.0f, 0.0f};
  float row_rise = 0.0f;
  float yaw_degrees = 0.0f;
  bool random_yaw = false;
  float empty_probability = 0.0f;
  // scatter
  uint32_t count = 0;
  float rect_min[2] = {0.0f, 0.0f}, rect_max[2] = {0.0f, 0.0f};
  float y = 0.0f;
};

struct RawScene {
  Camera camera;
  std::vector<CameraKey> path;
  // note: scenes select by error unless they name a mode (version-1 scenes name "continuous").
  LodSettings lod = [] {
    LodSettings l;
    l.mode = LodMode::kError;
    return l;
  }();
  AnimationSettings animation;
  std::vector<RawType> types;
  std::vector<RawInstance> instances;
  std::vector<RawGenerator> generators;
  SceneEffects effects;
  std::vector<std::string> effects_types;  // empty = the only type
  std::string effects_types_path;
};

void check_view(const Camera& camera, const std::string& path) {
  View view;
  std::string why;
  if (!make_view(camera, view, &why)) fail(path, why);
}

void parse_camera(const json& v, RawScene& s) {
  const std::string path = "camera";
  check_object(v, path,
               {"position", "target", "up", "fov_degrees", "near", "far", "resolution", "path"});
  Camera& c = s.camera;
  const json* keys = find(v, "path");
  const bool has_path = keys != nullptr;
  if (const json* p = find(v, "position"))
    c.position = numbers<3>(*p, path + ".position");
  else if (!has_path)
    fail(path + ".position", "missing (required unless camera.path is given)");
  if (const json* p = find(v, "target"))
    c.target = numbers<3>(*p, path + ".target");
  else if (!has_path)
    fail(path + ".target", "missing (required unless camera.path is given)");
  if (const json* p = find(v, "up")) c.up = numbers<3>(*p, path + ".up");
  if (const json* p = find(v, "fov_degrees")) {
    const double fov = number(*p, path + ".fov_degrees");
    if (!(fov > 0.0 && fov < 180.0))
      fail(path + ".fov_degrees", "must be in (0, 180), got " + show(fov));
    c.fov_y_degrees = static_cast<float>(fov);
  }
  if (const json* p = find(v, "near"))
    c.near_plane = static_cast<float>(number_at_least(*p, path + ".near", 0.0, false));
  if (const json* p = find(v, "far")) {
    c.far_plane = static_cast<float>(number(*p, path + ".far"));
    if (!(c.far_plane > c.near_plane))
      fail(path + ".far",
           "must be beyond near (" + show(c.near_plane) + "), got " + show(c.far_plane));
  } else if (!(c.far_plane > c.near_plane)) {
    fail(path + ".near",
         "must be below far (" + show(c.far_plane) + "), got " + show(c.near_plane));
  }
  if (const json* p = find(v, "resolution")) {
    const std::string rp = path + ".resolution";
    if (!p->is_array() || p->size() != 2)
      fail(rp, "expected [width, height] in pixels, got " +
                   (p->is_array() ? "an array of " + std::to_string(p->size()) : describe(*p)));
    const char* names[2] = {"width", "height"};
    uint32_t size[2];
    for (int i = 0; i < 2; ++i) {
      const json& e = (*p)[i];
      if (!e.is_number_integer())
        fail(item_path(rp, i),
             "expected an integer " + std::string(names[i]) + ", got " + describe(e));
      const bool negative = !e.is_number_unsigned() && e.get<int64_t>() < 0;
      const uint64_t value = negative ? 0 : e.get<uint64_t>();
      if (negative || value < 1 || value > kMaxResolution)
        fail(rp, std::string(names[i]) + " must be 1.." + std::to_string(kMaxResolution) +
                     " pixels, got " + e.dump());
      size[i] = static_cast<uint32_t>(value);
    }
    c.width = size[0];
    c.height = size[1];
  }
  if (has_path) {
    const json& arr = array(*keys, path + ".path");
    if (arr.empty()) fail(path + ".path", "needs at least one key");
    for (size_t i = 0; i < arr.size(); ++i) {
      const std::string kp = item_path(path + ".path", i);
      check_object(arr[i], kp, {"time", "position", "target"});
      CameraKey key;
      key.time =
          static_cast<float>(number_at_least(require(arr[i], "time", kp), kp + ".time", 0.0, true));
      key.position = numbers<3>(require(arr[i], "position", kp), kp + ".position");
      key.target = numbers<3>(require(arr[i], "target", kp), kp + ".target");
      if (!s.path.empty() && !(key.time > s.path.back().time))
        fail(kp + ".time", "keys must be in increasing time order (" + show(key.time) +
                               " follows " + show(s.path.back().time) + ")");
      Camera at = c;
      at.position = key.position;
      at.target = key.target;
      check_view(at, kp);
      s.path.push_back(key);
    }
    if (!find(v, "position")) c.position = s.path.front().position;
    if (!find(v, "target")) c.target = s.path.front().target;
  }
  check_view(c, path);
}

void parse_lod(const json& v, RawScene& s) {
  const std::string path = "lod";
  check_object(v, path,
               {"mode", "budget", "alpha", "min_t", "drop_below_min_t", "max_pixel_error",
                "geomorph", "discrete_levels"});
  LodSettings& l = s.lod;
  if (const json* p = find(v, "mode")) {
    const std::string mode = string(*p, path + ".mode");
    if (mode == "continuous" || mode == "budget")
      l.mode = LodMode::kContinuous;
    else if (mode == "error")
      l.mode = LodMode::kError;
    else if (mode == "discrete")
      l.mode = LodMode::kDiscrete;
    else if (mode == "full")
      l.mode = LodMode::kFull;
    else
      fail(path + ".mode",
           "unknown mode \"" + mode + "\" (expected error, budget, continuous, discrete or full)");
  }
  if (const json* p = find(v, "budget"))
    l.budget = static_cast<uint32_t>(integer(*p, path + ".budget", 1, UINT32_MAX));
  if (const json* p = find(v, "alpha")) {
    const double a = number(*p, path + ".alpha");
    if (!(a > 1.0))
      fail(path + ".alpha", "must be > 1 (beta = alpha - 1 must be positive), got " + show(a));
    l.alpha = static_cast<float>(a);
  }
  if (const json* p = find(v, "min_t")) {
    const double t = number(*p, path + ".min_t");
    if (!(t >= 0.0 && t <= 1.0)) fail(path + ".min_t", "must be in [0, 1], got " + show(t));
    l.min_t = static_cast<float>(t);
  }
  if (const json* p = find(v, "max_pixel_error")) {
    const double e = number(*p, path + ".max_pixel_error");
    if (!(e > 0.0) || !std::isfinite(e) || e > 1e6)
      fail(path + ".max_pixel_error", "must be a number of pixels > 0, got " + show(e));
    l.max_pixel_error = static_cast<float>(e);
  }
  if (const json* p = find(v, "geomorph")) {
    const double f = number(*p, path + ".geomorph");
    if (!(f >= 0.0 && f < 1.0))
      fail(path + ".geomorph", "must be a fraction in [0, 1) (0: off), got " + show(f));
    l.geomorph = static_cast<float>(f);
  }
  if (const json* p = find(v, "drop_below_min_t"))
    l.drop_below_min_t = boolean(*p, path + ".drop_below_min_t");
  if (const json* p = find(v, "discrete_levels")) {
    const std::string lp = path + ".discrete_levels";
    const json& arr = array(*p, lp);
    if (arr.empty() || arr.size() > kMaxDiscreteLevels)
      fail(lp, "needs 1 to " + std::to_string(kMaxDiscreteLevels) + " levels, got " +
                   std::to_string(arr.size()));
    for (size_t i = 0; i < arr.size(); ++i) {
      const double f = number(arr[i], item_path(lp, i));
      if (!(f > 0.0 && f <= 1.0))
        fail(item_path(lp, i), "must be a fraction in (0, 1], got " + show(f));
      if (i > 0 && !(f < l.discrete_levels[i - 1]))
        fail(item_path(lp, i), "levels must be strictly decreasing (" + show(f) + " follows " +
                                   show(l.discrete_levels[i - 1]) + ")");
      l.discrete_levels[i] = static_cast<float>(f);
    }
    l.discrete_level_count = static_cast<uint32_t>(arr.size());
  }
}

void parse_animation(const json& v, RawScene& s) {
  const std::string path = "animation";
  check_object(v, path, {"interpolation", "root_motion"});
  if (const json* p = find(v, "interpolation")) {
    const std::string mode = string(*p, path + ".interpolation");
    if (mode == "nearest")
      s.animation.filter = FrameFilter::kNearest;
    else if (mode == "linear")
      s.animation.filter = FrameFilter::kLinear;
    else
      fail(path + ".interpolation",
           "unknown interpolation \"" + mode + "\" (expected nearest or linear)");
  }
  if (const json* p = find(v, "root_motion"))
    s.animation.root_motion = boolean(*p, path + ".root_motion");
}

void parse_types(const json& v, RawScene& s) {
  const std::string path = "character_types";
  const json& arr = array(v, path);
  if (arr.empty()) fail(path, "needs at least one character type");
  for (size_t i = 0; i < arr.size(); ++i) {
    const std::string tp = item_path(path, i);
    check_object(arr[i], tp, {"name", "pack", "texture_variants", "shading"});
    RawType t;
    t.path = tp;
    t.name = string(require(arr[i], "name", tp), tp + ".name");
    if (t.name.empty()) fail(tp + ".name", "must not be empty");
    for (const RawType& other : s.types)
      if (other.name == t.name)
        fail(tp + ".name", "\"" + t.name + "\" is already the name of " + other.path);
    t.pack = string(require(arr[i], "pack", tp), tp + ".pack");
    if (t.pack.empty()) fail(tp + ".pack", "must not be empty");
    if (const json* p = find(arr[i], "texture_variants")) {
      const std::string vp = tp + ".texture_variants";
      check_object(*p, vp, {"head", "upper_body", "trousers"});
      uint32_t* fields[3] = {&t.variants.head, &t.variants.upper_body, &t.variants.trousers};
      const char* names[3] = {"head", "upper_body", "trousers"};
      for (int k = 0; k < 3; ++k)
        if (const json* q = find(*p, names[k]))
          *fields[k] = static_cast<uint32_t>(integer(*q, vp + "." + names[k], 1, 256));
    }
    if (const json* p = find(arr[i], "shading")) {
      const std::string mode = string(*p, tp + ".shading");
      if (mode == "auto")
        t.shading = Shading::kAuto;
      else if (mode == "material")
        t.shading = Shading::kMaterial;
      else if (mode == "swatches")
        t.shading = Shading::kSwatches;
      else
        fail(tp + ".shading",
             "unknown shading \"" + mode + "\" (expected auto, material or swatches)");
    }
    s.types.push_back(std::move(t));
  }
}

void parse_textures(const json& v, const std::string& path, bool allow_random, RawTextures& out) {
  out.path = path;
  if (allow_random && v.is_string()) {
    if (v.get<std::string>() != "random")
      fail(path, "expected \"random\" or an object of variant indices, got " + describe(v));
    out.random = true;
    return;
  }
  check_object(v, path, {"head", "upper_body", "trousers"});
  const char* names[3] = {"head", "upper_body", "trousers"};
  for (int k = 0; k < 3; ++k)
    if (const json* q = find(v, names[k]))
      out.value[k] = integer(*q, path + "." + names[k], 0, 255);
}

// Keys every instance description (listed or generated) may have.
void parse_attributes(const json& v, const std::string& path, bool generator, RawAttributes& a) {
  a.path = path;
  if (const json* p = find(v, "type")) {
    a.type = string(*p, path + ".type");
  }
  const json* clip = find(v, "clip");
  const json* clips = generator ? find(v, "clips") : nullptr;
  if (clip && clips) fail(path + ".clips", "give either clip or clips, not both");
  if (clip) a.clips.push_back(string(*clip, path + ".clip"));
  if (clips) {
    const json& arr = array(*clips, path + ".clips");
    if (arr.empty()) fail(path + ".clips", "needs at least one clip name");
    for (size_t i = 0; i < arr.size(); ++i)
      a.clips.push_back(string(arr[i], item_path(path + ".clips", i)));
  }
  const auto value_or_range = [&](const char* key, double lo, bool inclusive, Range& out) {
    const json* p = find(v, key);
    if (!p) return;
    if (generator) {
      out = range(*p, path + "." + key, lo, inclusive);
    } else {
      const float x = static_cast<float>(number_at_least(*p, path + "." + key, lo, inclusive));
      out = {x, x};
    }
  };
  value_or_range("speed", 0.0, true, a.speed);
  value_or_range("time_offset", 0.0, true, a.time_offset);
  value_or_range("scale", 0.0, false, a.scale);
  if (const json* p = find(v, "textures"))
    parse_textures(*p, path + ".textures", generator, a.textures);
  if (const json* p = find(v, "neck_height"))
    a.neck_height = static_cast<float>(number(*p, path + ".neck_height"));
  if (const json* p = find(v, "waist_height"))
    a.waist_height = static_cast<float>(number(*p, path + ".waist_height"));
  if (!generator) {
    if (const json* p = find(v, "color")) {
      const std::string cp = path + ".color";
      check_object(*p, cp, {"hue", "saturation", "brightness"});
      if (const json* q = find(*p, "hue")) {
        const double h = number(*q, cp + ".hue");
        if (!(h >= -180.0 && h <= 180.0))
          fail(cp + ".hue", "must be in [-180, 180] degrees, got " + show(h));
        a.color[0] = static_cast<float>(h);
      }
      if (const json* q = find(*p, "saturation"))
        a.color[1] = static_cast<float>(number_at_least(*q, cp + ".saturation", 0.0, true));
      if (const json* q = find(*p, "brightness"))
        a.color[2] = static_cast<float>(number_at_least(*q, cp + ".brightness", 0.0, true));
    }
  } else if (const json* p = find(v, "color_variation")) {
    const std::string cp = path + ".color_variation";
    check_object(*p, cp, {"hue", "saturation", "brightness"});
    if (const json* q = find(*p, "hue")) {
      const double h = number_at_least(*q, cp + ".hue", 0.0, true);
      if (h > 180.0) fail(cp + ".hue", "must be at most 180 degrees, got " + show(h));
      a.color_variation[0] = static_cast<float>(h);
    }
    const char* names[2] = {"saturation", "brightness"};
    for (int k = 0; k < 2; ++k)
      if (const json* q = find(*p, names[k])) {
        const double x = number_at_least(*q, cp + "." + names[k], 0.0, true);
        if (x > 1.0) fail(cp + "." + names[k], "must be at most 1, got " + show(x));
        a.color_variation[k + 1] = static_cast<float>(x);
      }
  }
}

void parse_instances(const json& v, RawScene& s) {
  const std::string path = "instances";
  const json& arr = array(v, path);
  if (arr.size() > kMaxInstances)
    fail(path, std::to_string(arr.size()) + " instances exceed the limit of " +
                   std::to_string(kMaxInstances));
  s.instances.reserve(arr.size());
  for (size_t i = 0; i < arr.size(); ++i) {
    const std::string ip = item_path(path, i);
    check_object(arr[i], ip,
                 {"type", "position", "rotation", "yaw_degrees", "scale", "clip", "speed",
                  "time_offset", "textures", "neck_height", "waist_height", "color"});
    RawInstance r;
    parse_attributes(arr[i], ip, false, r.a);
    r.position = numbers<3>(require(arr[i], "position", ip), ip + ".position");
    const json* rotation = find(arr[i], "rotation");
    const json* yaw = find(arr[i], "yaw_degrees");
    if (rotation && yaw) fail(ip + ".yaw_degrees", "give either rotation or yaw_degrees, not both");
    if (rotation) {
      std::array<float, 4> q = numbers<4>(*rotation, ip + ".rotation");
      const double len = std::sqrt(double{q[0]} * q[0] + double{q[1]} * q[1] + double{q[2]} * q[2] +
                                   double{q[3]} * q[3]);
      if (!(len > 1e-6)) fail(ip + ".rotation", "quaternion [x, y, z, w] must not be zero");
      for (float& c : q) c = static_cast<float>(c / len);
      r.rotation = q;
    }
    if (yaw) r.rotation = yaw_quaternion(static_cast<float>(number(*yaw, ip + ".yaw_degrees")));
    s.instances.push_back(std::move(r));
  }
}

void parse_generators(const json& v, RawScene& s) {
  const std::string path = "generators";
  const json& arr = array(v, path);
  for (size_t i = 0; i < arr.size(); ++i) {
    const std::string gp = item_path(path, i);
    if (!arr[i].is_object()) fail(gp, "expected an object, got " + describe(arr[i]));
    const std::string kind = string(require(arr[i], "kind", gp), gp + ".kind");
    RawGenerator g;
    if (kind == "seat_grid") {
      check_object(arr[i], gp,
                   {"kind", "type", "seed", "origin", "rows", "columns", "spacing", "row_rise",
                    "yaw_degrees", "empty_probability", "clip", "clips", "speed", "time_offset",
                    "scale", "textures", "color_variation", "neck_height", "waist_height"});
      g.grid = true;
      if (const json* p = find(arr[i], "origin")) g.origin = numbers<3>(*p, gp + ".origin");
      g.rows = static_cast<uint32_t>(
          integer(require(arr[i], "rows", gp), gp + ".rows", 1, kMaxInstances));
      g.columns = static_cast<uint32_t>(
          integer(require(arr[i], "columns", gp), gp + ".columns", 1, kMaxInstances));
      if (uint64_t{g.rows} * g.columns > kMaxInstances)
        fail(gp, std::to_string(g.rows) + " rows x " + std::to_string(g.columns) +
                     " columns exceed the limit of " + std::to_string(kMaxInstances) +
                     " instances");
      const std::array<float, 2> spacing =
          numbers<2>(require(arr[i], "spacing", gp), gp + ".spacing");
      for (int k = 0; k < 2; ++k)
        if (!(spacing[k] > 0.0f))
          fail(item_path(gp + ".spacing", k), "must be > 0, got " + show(spacing[k]));
      g.spacing[0] = spacing[0];
      g.spacing[1] = spacing[1];
      if (const json* p = find(arr[i], "row_rise"))
        g.row_rise = static_cast<float>(number(*p, gp + ".row_rise"));
      if (const json* p = find(arr[i], "yaw_degrees"))
        g.yaw_degrees = static_cast<float>(number(*p, gp + ".yaw_degrees"));
      if (const json* p = find(arr[i], "empty_probability")) {
        const double e = number(*p, gp + ".empty_probability");
        if (!(e >= 0.0 && e <= 1.0))
          fail(gp + ".empty_probability", "must be in [0, 1], got " + show(e));
        g.empty_probability = static_cast<float>(e);
      }
    } else if (kind == "scatter") {
      check_object(arr[i], gp,
                   {"kind", "type", "seed", "count", "rectangle", "y", "yaw_degrees", "clip",
                    "clips", "speed", "time_offset", "scale", "textures", "color_variation",
                    "neck_height", "waist_height"});
      g.grid = false;
      g.count = static_cast<uint32_t>(
          integer(require(arr[i], "count", gp), gp + ".count", 0, kMaxInstances));
      const std::string rp = gp + ".rectangle";
      const json& rect = require(arr[i], "rectangle", gp);
      check_object(rect, rp, {"min", "max"});
      const std::array<float, 2> lo = numbers<2>(require(rect, "min", rp), rp + ".min");
      const std::array<float, 2> hi = numbers<2>(require(rect, "max", rp), rp + ".max");
      for (int k = 0; k < 2; ++k)
        if (!(hi[k] > lo[k]))
          fail(rp, std::string("max must exceed min in ") + (k == 0 ? "x" : "z") + " (min " +
                       show(lo[k]) + ", max " + show(hi[k]) + ")");
      g.rect_min[0] = lo[0], g.rect_min[1] = lo[1], g.rect_max[0] = hi[0], g.rect_max[1] = hi[1];
      if (const json* p = find(arr[i], "y")) g.y = static_cast<float>(number(*p, gp + ".y"));
      g.random_yaw = true;
      if (const json* p = find(arr[i], "yaw_degrees")) {
        if (p->is_string() && p->get<std::string>() == "random")
          g.random_yaw = true;
        else if (p->is_number())
          g.random_yaw = false, g.yaw_degrees = static_cast<float>(number(*p, gp + ".yaw_degrees"));
        else
          fail(gp + ".yaw_degrees", "expected a number or \"random\", got " + describe(*p));
      }
    } else if (kind == "relaxation") {
      check_object(arr[i], gp,
                   {"kind", "type", "seed", "region", "count", "y", "min_distance", "group_spacing",
                    "single_fraction", "iterations", "clip", "clips", "speed", "time_offset",
                    "scale", "textures", "color_variation", "neck_height", "waist_height"});
      g.grid = false;
      g.relaxation = true;
      g.count = static_cast<uint32_t>(
          integer(require(arr[i], "count", gp), gp + ".count", 0, kMaxInstances));
      g.relax.people = g.count;
      const std::string rp = gp + ".region";
      const json& region = array(require(arr[i], "region", gp), rp);
      if (region.size() < 3)
        fail(rp, "a polygon needs at least 3 [x, z] points, got " + std::to_string(region.size()));
      for (size_t k = 0; k < region.size(); ++k)
        g.relax.region.push_back(numbers<2>(region[k], item_path(rp, k)));
      if (const json* p = find(arr[i], "y")) g.y = static_cast<float>(number(*p, gp + ".y"));
      if (const json* p = find(arr[i], "min_distance"))
        g.relax.min_distance =
            static_cast<float>(number_at_least(*p, gp + ".min_distance", 0.0, false));
      if (const json* p = find(arr[i], "group_spacing"))
        g.relax.group_spacing =
            static_cast<float>(number_at_least(*p, gp + ".group_spacing", 0.0, false));
      if (!(g.relax.group_spacing >= g.relax.min_distance))
        fail(gp + ".group_spacing", "must be at least min_distance (" + show(g.relax.min_distance) +
                                        "), got " + show(g.relax.group_spacing));
      if (const json* p = find(arr[i], "single_fraction")) {
        const double f = number(*p, gp + ".single_fraction");
        if (!(f >= 0.0 && f <= 1.0))
          fail(gp + ".single_fraction", "must be in [0, 1], got " + show(f));
        g.relax.single_fraction = static_cast<float>(f);
      }
      if (const json* p = find(arr[i], "iterations"))
        g.relax.iterations = static_cast<int>(integer(*p, gp + ".iterations", 0, 10000));
    } else {
      fail(gp + ".kind",
           "unknown generator \"" + kind + "\" (expected seat_grid, scatter or relaxation)");
    }
    g.path = gp;
    if (const json* p = find(arr[i], "seed"))
      g.seed = static_cast<uint64_t>(integer(*p, gp + ".seed", 0, INT64_MAX));
    g.relax.seed = g.seed;
    parse_attributes(arr[i], gp, true, g.a);
    s.generators.push_back(std::move(g));
  }
}

// ---- The effects declaration (scene_effects.h) ------------------------------------------

std::string in_quotes(const std::string& name) { return "\"" + name + "\""; }

std::string name_list(const std::vector<EffectState>& states) {
  std::string out;
  for (const EffectState& st : states) out += (out.empty() ? "" : ", ") + st.name;
  return out;
}

int32_t find_state(const std::vector<EffectState>& states, const std::string& name) {
  for (size_t i = 0; i < states.size(); ++i)
    if (states[i].name == name) return static_cast<int32_t>(i);
  return -1;
}

// The index of a declared state, or an "unknown state" error at `path`.
uint32_t known_state(const SceneEffects& e, const std::string& name, const std::string& path) {
  const int32_t i = find_state(e.states, name);
  if (i < 0)
    fail(path,
         "unknown state " + in_quotes(name) + " (effects.states: " + name_list(e.states) + ")");
  return static_cast<uint32_t>(i);
}

float seconds_at_least(const json& v, const std::string& path, double lo, bool inclusive) {
  return static_cast<float>(number_at_least(v, path, lo, inclusive));
}

void parse_effect_states(const json& v, SceneEffects& e) {
  const std::string path = "effects.states";
  const json& arr = array(v, path);
  if (arr.empty()) fail(path, "needs at least one state");
  for (size_t i = 0; i < arr.size(); ++i) {
    const std::string sp = item_path(path, i);
    check_object(arr[i], sp,
                 {"name", "clips", "pose", "pose_in", "pose_out", "rest", "interruptible",
                  "contagious", "additive", "mask", "instances"});
    EffectState st;
    st.name = string(require(arr[i], "name", sp), sp + ".name");
    if (st.name.empty()) fail(sp + ".name", "must not be empty");
    if (find_state(e.states, st.name) >= 0)
      fail(sp + ".name", in_quotes(st.name) + " is declared twice");
    const json& clips = array(require(arr[i], "clips", sp), sp + ".clips");
    if (clips.empty()) fail(sp + ".clips", "needs at least one clip");
    double total = 0.0;
    for (size_t k = 0; k < clips.size(); ++k) {
      const std::string cp = item_path(sp + ".clips", k);
      EffectClip c;
      if (clips[k].is_string()) {
        c.clip = clips[k].get<std::string>();
      } else {
        check_object(clips[k], cp, {"clip", "weight", "hold"});
        c.clip = string(require(clips[k], "clip", cp), cp + ".clip");
        if (const json* p = find(clips[k], "weight"))
          c.weight = static_cast<float>(number_at_least(*p, cp + ".weight", 0.0, true));
        if (const json* p = find(clips[k], "hold")) c.hold = boolean(*p, cp + ".hold");
      }
      if (c.clip.empty()) fail(cp, "the clip name must not be empty");
      total += c.weight;
      st.clips.push_back(std::move(c));
    }
    if (!(total > 0.0)) fail(sp + ".clips", "every clip weight is 0");
    const json* pose = find(arr[i], "pose");
    const json* pose_in = find(arr[i], "pose_in");
    const json* pose_out = find(arr[i], "pose_out");
    if (pose && (pose_in || pose_out))
      fail(sp + ".pose", "give either pose or pose_in/pose_out, not both");
    st.pose_in = st.pose_out = pose ? string(*pose, sp + ".pose") : "default";
    if (pose_in) st.pose_in = string(*pose_in, sp + ".pose_in");
    if (pose_out) st.pose_out = string(*pose_out, sp + ".pose_out");
    if (st.pose_in.empty() || st.pose_out.empty()) fail(sp + ".pose", "must not be empty");
    if (const json* p = find(arr[i], "rest")) st.rest = boolean(*p, sp + ".rest");
    if (const json* p = find(arr[i], "interruptible"))
      st.interruptible = boolean(*p, sp + ".interruptible");
    if (const json* p = find(arr[i], "contagious")) st.contagious = boolean(*p, sp + ".contagious");
    if (const json* p = find(arr[i], "additive")) st.additive = boolean(*p, sp + ".additive");
    if (st.rest && st.pose_in != st.pose_out)
      fail(sp + ".rest", "a rest state loops, so it must end in the pose it starts in (pose_in " +
                             in_quotes(st.pose_in) + ", pose_out " + in_quotes(st.pose_out) + ")");
    if (const json* p = find(arr[i], "mask")) {
      const json& mask = array(*p, sp + ".mask");
      if (!st.additive) fail(sp + ".mask", "only additive states have a skeletal mask");
      for (size_t k = 0; k < mask.size(); ++k)
        st.mask.push_back(string(mask[k], item_path(sp + ".mask", k)));
    }
    if (const json* p = find(arr[i], "instances"))
      st.instances = static_cast<uint32_t>(integer(*p, sp + ".instances", 1, 1024));
    e.states.push_back(std::move(st));
  }
}

void parse_animation_sharing(const json& v, SceneEffects& e) {
  const std::string path = "effects.animation_sharing";
  e.animation_sharing = true;
  if (v.is_boolean()) {
    e.animation_sharing = v.get<bool>();
    return;
  }
  check_object(v, path, {"instances_per_state", "transitions", "additive_layers"});
  if (const json* p = find(v, "instances_per_state"))
    e.instances_per_state =
        static_cast<uint32_t>(integer(*p, path + ".instances_per_state", 1, 1024));
  if (const json* p = find(v, "transitions")) {
    const std::string tp = path + ".transitions";
    if (p->is_boolean()) {
      e.transitions = p->get<bool>();
    } else {
      check_object(*p, tp, {"time", "max", "join_window"});
      e.transitions = true;
      if (const json* q = find(*p, "time"))
        e.transition_time = seconds_at_least(*q, tp + ".time", 0.0, false);
      if (const json* q = find(*p, "max"))
        e.max_transitions = static_cast<uint32_t>(integer(*q, tp + ".max", 1, 65536));
      if (const json* q = find(*p, "join_window"))
        e.transition_join_window = seconds_at_least(*q, tp + ".join_window", 0.0, true);
    }
  }
  if (const json* p = find(v, "additive_layers"))
    e.additive_layers = boolean(*p, path + ".additive_layers");
}

void parse_spectators(const json& v, size_t generator_count, SceneEffects& e) {
  const std::string path = "effects.spectators";
  check_object(v, path,
               {"transitions", "reactions", "teams", "events", "home_state", "parameters", "seed"});
  e.spectators = true;
  if (const json* p = find(v, "transitions")) {
    const std::string tp = path + ".transitions";
    const json& arr = array(*p, tp);
    for (size_t i = 0; i < arr.size(); ++i) {
      const std::string ip = item_path(tp, i);
      check_object(arr[i], ip, {"from", "to", "idle_weight"});
      EffectTransition t;
      t.from = string(require(arr[i], "from", ip), ip + ".from");
      t.to = string(require(arr[i], "to", ip), ip + ".to");
      if (const json* q = find(arr[i], "idle_weight"))
        t.idle_weight = static_cast<float>(number_at_least(*q, ip + ".idle_weight", 0.0, true));
      const EffectState& from = e.states[known_state(e, t.from, ip + ".from")];
      const EffectState& to = e.states[known_state(e, t.to, ip + ".to")];
      if (from.pose_out != to.pose_in)
        fail(ip, in_quotes(t.from) + " ends in pose " + in_quotes(from.pose_out) + " but " +
                     in_quotes(t.to) + " starts in pose " + in_quotes(to.pose_in));
      for (const EffectTransition& other : e.fsm_transitions)
        if (other.from == t.from && other.to == t.to)
          fail(ip, "the transition " + in_quotes(t.from) + " -> " + in_quotes(t.to) +
                       " is declared twice");
      e.fsm_transitions.push_back(std::move(t));
    }
  }
  const json& reactions = array(require(v, "reactions", path), path + ".reactions");
  for (size_t i = 0; i < reactions.size(); ++i) {
    const std::string rp = item_path(path + ".reactions", i);
    check_object(reactions[i], rp, {"event", "supporters", "opponents", "decay"});
    EffectReaction r;
    r.event = string(require(reactions[i], "event", rp), rp + ".event");
    if (r.event.empty()) fail(rp + ".event", "must not be empty");
    for (const EffectReaction& other : e.reactions)
      if (other.event == r.event) fail(rp + ".event", in_quotes(r.event) + " is declared twice");
    r.supporters = string(require(reactions[i], "supporters", rp), rp + ".supporters");
    known_state(e, r.supporters, rp + ".supporters");
    if (const json* q = find(reactions[i], "opponents")) {
      r.opponents = string(*q, rp + ".opponents");
      if (!r.opponents.empty()) known_state(e, r.opponents, rp + ".opponents");
    }
    if (const json* q = find(reactions[i], "decay"))
      r.decay = seconds_at_least(*q, rp + ".decay", 0.0, false);
    e.reactions.push_back(std::move(r));
  }
  const json& teams = array(require(v, "teams", path), path + ".teams");
  if (teams.empty()) fail(path + ".teams", "needs at least one team");
  std::vector<int> owner(generator_count, -1);
  for (size_t i = 0; i < teams.size(); ++i) {
    const std::string tp = item_path(path + ".teams", i);
    check_object(teams[i], tp, {"name", "generators", "embarrassment", "embarrassment_spread"});
    EffectTeam t;
    t.name = string(require(teams[i], "name", tp), tp + ".name");
    if (t.name.empty()) fail(tp + ".name", "must not be empty");
    for (const EffectTeam& other : e.teams)
      if (other.name == t.name) fail(tp + ".name", in_quotes(t.name) + " is declared twice");
    const json& gens = array(require(teams[i], "generators", tp), tp + ".generators");
    if (gens.empty()) fail(tp + ".generators", "needs at least one generator index");
    for (size_t k = 0; k < gens.size(); ++k) {
      const std::string gp = item_path(tp + ".generators", k);
      const int64_t g = integer(gens[k], gp, 0, INT32_MAX);
      if (static_cast<size_t>(g) >= generator_count)
        fail(gp, "generator " + std::to_string(g) + " does not exist (the scene has " +
                     std::to_string(generator_count) + " generators)");
      if (owner[static_cast<size_t>(g)] >= 0)
        fail(gp, "generator " + std::to_string(g) + " already belongs to team " +
                     in_quotes(e.teams[static_cast<size_t>(owner[static_cast<size_t>(g)])].name));
      owner[static_cast<size_t>(g)] = static_cast<int>(i);
      t.generators.push_back(static_cast<uint32_t>(g));
    }
    if (const json* q = find(teams[i], "embarrassment"))
      t.embarrassment = static_cast<float>(number_at_least(*q, tp + ".embarrassment", 0.0, true));
    if (const json* q = find(teams[i], "embarrassment_spread"))
      t.embarrassment_spread =
          static_cast<float>(number_at_least(*q, tp + ".embarrassment_spread", 0.0, true));
    e.teams.push_back(std::move(t));
  }
  if (const json* p = find(v, "events")) {
    const std::string ep = path + ".events";
    const json& arr = array(*p, ep);
    for (size_t i = 0; i < arr.size(); ++i) {
      const std::string ip = item_path(ep, i);
      check_object(arr[i], ip, {"kind", "time", "team", "excitement"});
      EffectEvent ev;
      ev.kind = string(require(arr[i], "kind", ip), ip + ".kind");
      bool reaction = false;
      std::string events;
      for (const EffectReaction& r : e.reactions) {
        reaction = reaction || r.event == ev.kind;
        events += (events.empty() ? "" : ", ") + r.event;
      }
      if (!reaction)
        fail(ip + ".kind", "no reaction to " + in_quotes(ev.kind) +
                               " (effects.spectators.reactions: " + events + ")");
      ev.time = seconds_at_least(require(arr[i], "time", ip), ip + ".time", 0.0, true);
      if (const json* q = find(arr[i], "team")) {
        ev.team = string(*q, ip + ".team");
        bool known = ev.team.empty();
        std::string names;
        for (const EffectTeam& t : e.teams) {
          known = known || t.name == ev.team;
          names += (names.empty() ? "" : ", ") + t.name;
        }
        if (!known) fail(ip + ".team", "no team " + in_quotes(ev.team) + " (teams: " + names + ")");
      }
      if (const json* q = find(arr[i], "excitement"))
        ev.excitement = static_cast<float>(number_at_least(*q, ip + ".excitement", 0.0, true));
      e.events.push_back(std::move(ev));
    }
  }
  EffectSpectatorParams& pr = e.params;
  if (const json* p = find(v, "home_state")) {
    pr.home_state = string(*p, path + ".home_state");
    const uint32_t h = known_state(e, pr.home_state, path + ".home_state");
    if (!e.states[h].rest)
      fail(path + ".home_state", in_quotes(pr.home_state) + " is not a rest state");
  }
  if (const json* p = find(v, "seed"))
    pr.seed = static_cast<uint64_t>(integer(*p, path + ".seed", 0, INT64_MAX));
  if (const json* p = find(v, "parameters")) {
    const std::string pp = path + ".parameters";
    check_object(*p, pp,
                 {"tick", "neighbour_radius", "contagion_threshold", "social_gain", "fatigue_per_s",
                  "recovery_per_s", "start_delay_max", "min_reaction", "restart_delay"});
    struct Field {
      const char* key;
      float* value;
      bool positive;
    };
    const Field fields[] = {{"tick", &pr.tick, true},
                            {"neighbour_radius", &pr.neighbour_radius, true},
                            {"contagion_threshold", &pr.contagion_threshold, true},
                            {"social_gain", &pr.social_gain, false},
                            {"fatigue_per_s", &pr.fatigue_per_s, false},
                            {"recovery_per_s", &pr.recovery_per_s, false},
                            {"start_delay_max", &pr.start_delay_max, false},
                            {"min_reaction", &pr.min_reaction, false},
                            {"restart_delay", &pr.restart_delay, false}};
    for (const Field& f : fields)
      if (const json* q = find(*p, f.key))
        *f.value = static_cast<float>(number_at_least(*q, pp + "." + f.key, 0.0, !f.positive));
    if (pr.contagion_threshold > 1.0f)
      fail(pp + ".contagion_threshold", "must be in (0, 1], got " + show(pr.contagion_threshold));
  }
  // The FSM must have an exit: every state reaches a rest state (the behaviour module checks
  // this again when it compiles the FSM; the file gets the error first, with its key).
  const size_t n = e.states.size();
  std::vector<uint8_t> exits(n, 0);
  bool any_rest = false;
  for (size_t i = 0; i < n; ++i) exits[i] = e.states[i].rest, any_rest = any_rest || exits[i];
  if (!any_rest)
    fail("effects.states",
         "the spectator FSM has no rest state (mark the idle states, e.g. sit "
         "or stand, \"rest\": true)");
  for (bool changed = true; changed;) {
    changed = false;
    for (const EffectTransition& t : e.fsm_transitions) {
      const size_t from = static_cast<size_t>(find_state(e.states, t.from));
      const size_t to = static_cast<size_t>(find_state(e.states, t.to));
      if (!exits[from] && exits[to]) exits[from] = 1, changed = true;
    }
  }
  std::string trapped;
  for (size_t i = 0; i < n; ++i)
    if (!exits[i]) trapped += (trapped.empty() ? "" : ", ") + in_quotes(e.states[i].name);
  if (!trapped.empty())
    fail(path + ".transitions",
         "cyclic FSM without exit: no path from " + trapped + " to a rest state");
  // A reaction's states loop while the reaction lasts and must be reachable from every rest
  // state (where reactions start).
  for (size_t r = 0; r < e.reactions.size(); ++r) {
    const std::string rp = item_path(path + ".reactions", r);
    const std::string* roles[2] = {&e.reactions[r].supporters, &e.reactions[r].opponents};
    const char* keys[2] = {"supporters", "opponents"};
    for (int k = 0; k < 2; ++k) {
      if (roles[k]->empty()) continue;
      const size_t target = static_cast<size_t>(find_state(e.states, *roles[k]));
      const EffectState& st = e.states[target];
      if (st.pose_in != st.pose_out)
        fail(rp + "." + keys[k], "state " + in_quotes(st.name) +
                                     " repeats while the reaction lasts, so it must end in the "
                                     "pose it starts in (pose_in " +
                                     in_quotes(st.pose_in) + ", pose_out " +
                                     in_quotes(st.pose_out) + ")");
      for (size_t from = 0; from < n; ++from) {
        if (!e.states[from].rest) continue;
        std::vector<uint8_t> seen(n, 0);
        std::vector<size_t> queue{from};
        seen[from] = 1;
        for (size_t q = 0; q < queue.size(); ++q)
          for (const EffectTransition& t : e.fsm_transitions)
            if (static_cast<size_t>(find_state(e.states, t.from)) == queue[q]) {
              const size_t to = static_cast<size_t>(find_state(e.states, t.to));
              if (!seen[to]) seen[to] = 1, queue.push_back(to);
            }
        if (!seen[target])
          fail(rp + "." + keys[k], "state " + in_quotes(st.name) +
                                       " cannot be reached from the rest state " +
                                       in_quotes(e.states[from].name));
      }
    }
  }
}

void parse_effects(const json& v, RawScene& s) {
  const std::string path = "effects";
  check_object(v, path,
               {"type", "types", "lod", "texture_partition", "color_variety", "states",
                "animation_sharing", "spectators", "crossfade"});
  SceneEffects& e = s.effects;
  e.declared = true;
  const json* type = find(v, "type");
  const json* types = find(v, "types");
  if (type && types) fail(path + ".types", "give either type or types, not both");
  if (type) {
    s.effects_types.push_back(string(*type, path + ".type"));
    s.effects_types_path = path + ".type";
  }
  if (types) {
    const json& arr = array(*types, path + ".types");
    if (arr.empty()) fail(path + ".types", "needs at least one character type");
    for (size_t i = 0; i < arr.size(); ++i)
      s.effects_types.push_back(string(arr[i], item_path(path + ".types", i)));
    s.effects_types_path = path + ".types";
  }
  if (const json* p = find(v, "lod")) e.lod = boolean(*p, path + ".lod");
  if (const json* p = find(v, "texture_partition"))
    e.texture_partition = boolean(*p, path + ".texture_partition");
  if (const json* p = find(v, "color_variety"))
    e.color_variety = boolean(*p, path + ".color_variety");
  if (const json* p = find(v, "states")) parse_effect_states(*p, e);
  if (const json* p = find(v, "animation_sharing")) parse_animation_sharing(*p, e);
  if (const json* p = find(v, "crossfade")) {
    const std::string cp = path + ".crossfade";
    if (p->is_boolean()) {
      e.crossfade = p->get<bool>();
    } else {
      check_object(*p, cp, {"time"});
      e.crossfade = true;
      if (const json* q = find(*p, "time"))
        e.crossfade_time = seconds_at_least(*q, cp + ".time", 0.0, true);
    }
  }
  const bool uses_states = e.animation_sharing || find(v, "spectators") != nullptr;
  if (uses_states && e.states.empty())
    fail(path + ".states", "missing (animation_sharing and spectators need the states)");
  if (!uses_states && !e.states.empty())
    fail(path + ".states", "declared, but neither animation_sharing nor spectators uses them");
  if (const json* p = find(v, "spectators")) parse_spectators(*p, s.generators.size(), e);
  if (e.crossfade && e.animation_sharing)
    fail(path + ".crossfade",
         "animation_sharing already blends the FSM's changes on the CPU (transitions); declare "
         "one of them");
  if (e.crossfade && !e.spectators)
    fail(path + ".crossfade", "nothing changes clips to fade (declare spectators)");
  for (size_t i = 0; i < e.states.size(); ++i)
    if (e.states[i].additive && !(e.animation_sharing && e.additive_layers))
      fail(item_path(path + ".states", i) + ".additive",
           "additive layers are not declared (effects.animation_sharing.additive_layers)");
}

RawScene parse_raw(const json& root) {
  RawScene s;
  check_object(root, "",
               {"version", "camera", "lod", "animation", "character_types", "instances",
                "generators", "effects"});
  if (const json* p = find(root, "version")) {
    const int64_t version = integer(*p, "version", 0, INT32_MAX);
    if (version != 1)
      fail("version",
           "unsupported scene version " + std::to_string(version) + " (this build reads 1)");
  }
  parse_camera(require(root, "camera", ""), s);
  if (const json* p = find(root, "lod")) parse_lod(*p, s);
  if (const json* p = find(root, "animation")) parse_animation(*p, s);
  parse_types(require(root, "character_types", ""), s);
  if (const json* p = find(root, "instances")) parse_instances(*p, s);
  if (const json* p = find(root, "generators")) parse_generators(*p, s);
  if (const json* p = find(root, "effects")) parse_effects(*p, s);
  for (const RawGenerator& g : s.generators)
    s.effects.placement = s.effects.placement || g.relaxation;
  uint64_t total = s.instances.size();
  for (const RawGenerator& g : s.generators)
    total += g.grid ? uint64_t{g.rows} * g.columns : g.count;
  if (total > kMaxInstances)
    fail("generators", "the scene would hold " + std::to_string(total) +
                           " instances, above the limit of " + std::to_string(kMaxInstances));
  return s;
}

// ---- Stages 2 and 3: packs, names, instances --------------------------------------------

struct Resolved {
  uint32_t type = 0;
  std::vector<uint32_t> clips;  // Scene::clips indices
  float neck = 0.0f, waist = 0.0f;
};

std::string clip_list(const Pack& pack) {
  std::string out;
  const auto& clips = pack.contents().clips;
  for (size_t i = 0; i < clips.size() && i < 12; ++i) out += (i ? ", " : "") + clips[i].name;
  if (clips.size() > 12) out += ", ...";
  return out;
}

Resolved resolve(const Scene& scene, const RawAttributes& a) {
  Resolved r;
  if (a.type.empty()) {
    if (scene.types.size() != 1)
      fail(a.path + ".type", "missing (required when the scene has several character types)");
    r.type = 0;
  } else {
    const int32_t t = scene.find_type(a.type);
    if (t < 0) {
      std::string names;
      for (const CharacterType& ct : scene.types) names += (names.empty() ? "" : ", ") + ct.name;
      fail(a.path + ".type", "unknown character type \"" + a.type + "\" (types: " + names + ")");
    }
    r.type = static_cast<uint32_t>(t);
  }
  const CharacterType& type = scene.types[r.type];
  const bool several = a.clips.size() > 1;
  for (size_t k = 0; k < a.clips.size(); ++k) {
    const int32_t c = scene.find_clip(r.type, a.clips[k]);
    if (c < 0)
      fail(several ? item_path(a.path + ".clips", k) : a.path + ".clip",
           "character type '" + type.name + "' has no clip \"" + a.clips[k] +
               "\" (its clips: " + clip_list(type.pack) + ")");
    r.clips.push_back(static_cast<uint32_t>(c));
  }
  if (r.clips.empty()) r.clips.push_back(type.first_clip);
  const TextureVariants& v = type.texture_variants;
  const uint32_t counts[3] = {v.head, v.upper_body, v.trousers};
  const char* names[3] = {"head", "upper_body", "trousers"};
  if (!a.textures.random)
    for (int k = 0; k < 3; ++k)
      if (a.textures.value[k] >= counts[k])
        fail(a.textures.path + "." + names[k],
             "variant " + std::to_string(a.textures.value[k]) +
                 " is out of range: character type '" + type.name + "' has " +
                 std::to_string(counts[k]) + " " + names[k] +
                 " variant(s) (character_types texture_variants)");
  const PartitionMask& part = type.pack.contents().partition;
  r.neck = a.neck_height.value_or(part.neck_height);
  r.waist = a.waist_height.value_or(part.waist_height);
  if (r.waist > r.neck)
    fail(a.path + (a.waist_height ? ".waist_height" : ".neck_height"),
         "waist height " + show(r.waist) + " is above neck height " + show(r.neck));
  return r;
}

// Draws one instance's attributes (always the same number of draws, in the same order, so
// changing one attribute's range does not reshuffle the others).
Instance make_instance(const Scene& scene, const RawAttributes& a, const Resolved& r, Random& rng) {
  Instance in;
  in.type = r.type;
  const uint32_t pick = rng.below(static_cast<uint32_t>(r.clips.size()));
  in.clip = r.clips[pick];
  in.speed = rng.in(a.speed);
  in.time_offset = rng.in(a.time_offset);
  in.scale = rng.in(a.scale);
  const TextureVariants& v = scene.types[r.type].texture_variants;
  const uint32_t counts[3] = {v.head, v.upper_body, v.trousers};
  for (int k = 0; k < 3; ++k) {
    const uint32_t drawn = rng.below(counts[k]);
    in.textures[k] = static_cast<uint8_t>(
        a.textures.random ? drawn : static_cast<uint32_t>(a.textures.value[k]));
  }
  const float h = rng.unit() * 2.0f - 1.0f, s = rng.unit() * 2.0f - 1.0f,
              b = rng.unit() * 2.0f - 1.0f;
  in.color = {a.color[0] + h * a.color_variation[0], a.color[1] * (1.0f + s * a.color_variation[1]),
              a.color[2] * (1.0f + b * a.color_variation[2])};
  in.neck_height = r.neck;
  in.waist_height = r.waist;
  return in;
}

void open_packs(const RawScene& raw, const std::string& base_dir, const SceneLoadOptions& options,
                Scene& scene) {
  for (const RawType& t : raw.types) {
    std::filesystem::path p(t.pack);
    if (p.is_relative() && !base_dir.empty()) p = std::filesystem::path(base_dir) / p;
    Pack pack;
    const Status s =
        Pack::open_file(p.lexically_normal().string(), pack, options.pack_parts | kPackPartition);
    if (!s) fail(t.path + ".pack", s.message(), s.code());
    if (pack.contents().clips.empty())
      fail(t.path + ".pack", pack.source_name() + ": the pack has no clips to play");
    uint32_t index = 0;
    const Status added = add_character_type(scene, t.name, std::move(pack), t.variants, &index);
    if (!added) fail(t.path, added.message());
    scene.types[index].shading = t.shading;
  }
}

// Places a relaxation generator's people through the caller's placer (crowdbake_crowd).
void build_relaxation(const RawGenerator& g, const Resolved& r, const SceneLoadOptions& options,
                      Scene& scene) {
  if (!options.relaxation)
    fail(g.path + ".kind",
         "relaxation placement needs a placer: load the scene with crowdbake_scene_effects' "
         "crowd_scene_load_options() (SceneLoadOptions::relaxation)");
  RelaxationResult placed;
  const Status s = options.relaxation(g.relax, placed);
  if (!s) fail(g.path, s.message());
  if (placed.positions.size() != g.count || placed.yaw_degrees.size() != g.count)
    fail(g.path, "the placer returned " + std::to_string(placed.positions.size()) +
                     " positions for " + std::to_string(g.count) + " people");
  for (uint32_t k = 0; k < g.count; ++k) {
    Random rng(mix(g.seed, k, 2));
    Instance in = make_instance(scene, g.a, r, rng);
    in.position = {placed.positions[k][0], g.y, placed.positions[k][1]};
    in.rotation = yaw_quaternion(placed.yaw_degrees[k]);
    scene.instances.add(in);
  }
}

// Names in the effects declaration that need the packs: the driven type, clips, mask joints.
void resolve_effects(const RawScene& raw, Scene& scene) {
  SceneEffects e = raw.effects;
  if (!e.declared) {
    scene.effects.placement = e.placement;
    return;
  }
  std::vector<uint8_t> driven(scene.types.size(), 0);
  if (raw.effects_types.empty()) {
    if (scene.types.size() != 1 && !e.states.empty())
      fail("effects.type", "missing (required when the scene has several character types)");
    e.types = {0};
  } else {
    for (size_t k = 0; k < raw.effects_types.size(); ++k) {
      const std::string tp =
          raw.effects_types.size() > 1 || raw.effects_types_path == "effects.types"
              ? item_path(raw.effects_types_path, k)
              : raw.effects_types_path;
      const int32_t t = scene.find_type(raw.effects_types[k]);
      if (t < 0) fail(tp, "unknown character type \"" + raw.effects_types[k] + "\"");
      if (driven[static_cast<size_t>(t)])
        fail(tp, "character type \"" + raw.effects_types[k] + "\" is listed twice");
      driven[static_cast<size_t>(t)] = 1;
      e.types.push_back(static_cast<uint32_t>(t));
    }
  }
  e.type = e.types.front();
  std::fill(driven.begin(), driven.end(), 0);
  for (uint32_t t : e.types) driven[t] = 1;
  for (uint32_t t : e.types) {
    const CharacterType& type = scene.types[t];
    for (size_t i = 0; i < e.states.size(); ++i) {
      const std::string sp = item_path("effects.states", i);
      for (size_t k = 0; k < e.states[i].clips.size(); ++k) {
        const EffectClip& c = e.states[i].clips[k];
        const std::string cp = item_path(sp + ".clips", k);
        const int32_t index = type.pack.find_clip(c.clip);
        if (index < 0)
          fail(cp, "character type '" + type.name + "' has no clip \"" + c.clip +
                       "\" (its clips: " + clip_list(type.pack) + ")");
        const PackClip& clip = type.pack.contents().clips[static_cast<size_t>(index)];
        if (c.hold && clip.looping)
          fail(cp + ".hold",
               "clip \"" + c.clip + "\" loops; only a non-looping clip can hold its last frame");
        if (!(clip.duration > 0.0f) && e.spectators)
          fail(cp, "clip \"" + c.clip + "\" lasts " + show(clip.duration) +
                       " s; a behaviour state needs clips longer than 0 s");
      }
      for (size_t k = 0; k < e.states[i].mask.size(); ++k)
        if (type.pack.find_joint(e.states[i].mask[k]) < 0)
          fail(item_path(sp + ".mask", k),
               "character type '" + type.name + "' has no joint \"" + e.states[i].mask[k] + "\"");
    }
  }
  for (size_t t = 0; t < e.teams.size(); ++t)
    for (size_t k = 0; k < e.teams[t].generators.size(); ++k) {
      const InstanceRange& range = scene.generated[e.teams[t].generators[k]];
      for (uint32_t i = range.first; i < range.first + range.count; ++i)
        if (!driven[scene.instances.type[i]])
          fail(item_path(item_path("effects.spectators.teams", t) + ".generators", k),
               "generator " + std::to_string(e.teams[t].generators[k]) +
                   " makes instances of character type '" +
                   scene.types[scene.instances.type[i]].name +
                   "', which the effects do not drive (effects.type / effects.types)");
    }
  // Renderer-side effects turned off: applied to the data here, so every renderer (and the
  // CPU reference path) shows the same thing without an effect it was told not to use.
  if (!e.lod) scene.lod.mode = LodMode::kFull;
  if (!e.color_variety)
    for (size_t i = 0; i < scene.instances.size(); ++i) {
      scene.instances.color[3 * i] = 0.0f;
      scene.instances.color[3 * i + 1] = 1.0f;
      scene.instances.color[3 * i + 2] = 1.0f;
    }
  if (!e.texture_partition)
    std::fill(scene.instances.textures.begin(), scene.instances.textures.end(), 0u);
  scene.effects = std::move(e);
}

void build_instances(const RawScene& raw, const SceneLoadOptions& options, Scene& scene) {
  InstanceArrays& out = scene.instances;
  uint64_t total = raw.instances.size();
  for (const RawGenerator& g : raw.generators)
    total += g.grid ? uint64_t{g.rows} * g.columns : g.count;
  out.reserve(static_cast<size_t>(total));
  for (const RawInstance& ri : raw.instances) {
    const Resolved r = resolve(scene, ri.a);
    Random rng(0);
    Instance in = make_instance(scene, ri.a, r, rng);
    in.position = ri.position;
    in.rotation = ri.rotation;
    out.add(in);
  }
  for (const RawGenerator& g : raw.generators) {
    const Resolved r = resolve(scene, g.a);
    const uint32_t first = static_cast<uint32_t>(out.size());
    if (g.relaxation) {
      build_relaxation(g, r, options, scene);
    } else if (g.grid) {
      const float yaw = g.yaw_degrees * kPi / 180.0f;
      const float c = std::cos(yaw), s = std::sin(yaw);
      const std::array<float, 4> rotation = yaw_quaternion(g.yaw_degrees);
      for (uint32_t row = 0; row < g.rows; ++row) {
        for (uint32_t col = 0; col < g.columns; ++col) {
          const uint64_t seat = uint64_t{row} * g.columns + col;
          Random gaps(mix(g.seed, seat, 1));
          if (gaps.unit() < g.empty_probability) continue;
          Random rng(mix(g.seed, seat, 2));
          Instance in = make_instance(scene, g.a, r, rng);
          // note: seats go along +X of the grid, rows back along -Z and up by row_rise; the
          // crowd faces +Z of the grid (the spectator faces +Z), turned by yaw about +Y.
          const float lx = static_cast<float>(col) * g.spacing[0];
          const float lz = -static_cast<float>(row) * g.spacing[1];
          in.position = {g.origin[0] + c * lx + s * lz,
                         g.origin[1] + static_cast<float>(row) * g.row_rise,
                         g.origin[2] - s * lx + c * lz};
          in.rotation = rotation;
          out.add(in);
        }
      }
    } else {
      for (uint32_t k = 0; k < g.count; ++k) {
        Random rng(mix(g.seed, k, 2));
        Instance in = make_instance(scene, g.a, r, rng);
        Random place(mix(g.seed, k, 3));
        const float x = g.rect_min[0] + (g.rect_max[0] - g.rect_min[0]) * place.unit();
        const float z = g.rect_min[1] + (g.rect_max[1] - g.rect_min[1]) * place.unit();
        const float yaw = place.unit() * 360.0f - 180.0f;
        in.position = {x, g.y, z};
        in.rotation = yaw_quaternion(g.random_yaw ? yaw : g.yaw_degrees);
        out.add(in);
      }
    }
    scene.generated.push_back({first, static_cast<uint32_t>(out.size()) - first});
  }
}

Status build(const json& root, const std::string& base_dir, const SceneLoadOptions& options,
             Scene& out) {
  const RawScene raw = parse_raw(root);
  Scene scene;
  scene.camera = raw.camera;
  scene.camera_path = raw.path;
  scene.lod = raw.lod;
  scene.animation = raw.animation;
  open_packs(raw, base_dir, options, scene);
  build_instances(raw, options, scene);
  resolve_effects(raw, scene);
  out = std::move(scene);
  return {};
}

}  // namespace

Status parse_scene(std::string_view text, const std::string& name, const std::string& base_dir,
                   Scene& out, const SceneLoadOptions& options) {
  try {
    json root;
    try {
      root = json::parse(text.begin(), text.end());
    } catch (const json::parse_error& e) {
      std::string what = e.what();
      const size_t bracket = what.find("] ");
      if (what.rfind("[json.exception", 0) == 0 && bracket != std::string::npos)
        what = what.substr(bracket + 2);
      return {StatusCode::kInvalidScene, name + ": not valid JSON: " + what};
    }
    return build(root, base_dir, options, out);
  } catch (const scene_error& e) {
    return {e.code, name + ": " + e.message};
  } catch (const std::bad_alloc&) {
    return {StatusCode::kOutOfMemory, name + ": out of memory while loading the scene"};
  } catch (const std::exception& e) {
    return {StatusCode::kInvalidScene, name + ": " + e.what()};
  }
}

Status load_scene(const std::string& path, Scene& out, const SceneLoadOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {StatusCode::kIoError, path + ": cannot open: " + std::strerror(errno)};
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return {StatusCode::kIoError, path + ": read failed"};
  const std::filesystem::path base = std::filesystem::path(path).parent_path();
  return parse_scene(text.str(), path, base.string(), out, options);
}

}  // namespace crowdbake::runtime
