// Stage 1 of reading a scene.json (scene_file.h): the file's own keys, checked where they are
// read with json_reader (base/json_reader.h), then the registered sections.
#include "scene_file.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace crowdbake::runtime::scene_file {

using namespace json_reader;
using scene_file::fail;

std::array<float, 4> yaw_quaternion(float degrees) {
  const float half = 0.5f * degrees * kPi / 180.0f;
  return {0.0f, std::sin(half), 0.0f, std::cos(half)};
}

namespace {

Range range(const Json& v, const std::string& path, double lo, bool inclusive) {
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

void check_view(const Camera& camera, const std::string& path) {
  View view;
  if (const Status s = make_view(camera, view); !s) fail(path, s.message());
}

void parse_camera(const Json& v, RawScene& s) {
  const std::string path = "camera";
  check_object(v, path,
               {"position", "target", "up", "fov_degrees", "near", "far", "resolution", "path"});
  Camera& c = s.camera;
  const Json* keys = find(v, "path");
  const bool has_path = keys != nullptr;
  if (const Json* p = find(v, "position"))
    c.position = numbers<3>(*p, path + ".position");
  else if (!has_path)
    fail(path + ".position", "missing (required unless camera.path is given)");
  if (const Json* p = find(v, "target"))
    c.target = numbers<3>(*p, path + ".target");
  else if (!has_path)
    fail(path + ".target", "missing (required unless camera.path is given)");
  if (const Json* p = find(v, "up")) c.up = numbers<3>(*p, path + ".up");
  if (const Json* p = find(v, "fov_degrees")) {
    const double fov = number(*p, path + ".fov_degrees");
    if (!(fov > 0.0 && fov < 180.0))
      fail(path + ".fov_degrees", "must be in (0, 180), got " + show(fov));
    c.fov_y_degrees = static_cast<float>(fov);
  }
  if (const Json* p = find(v, "near"))
    c.near_plane = static_cast<float>(number_at_least(*p, path + ".near", 0.0, false));
  if (const Json* p = find(v, "far")) {
    c.far_plane = static_cast<float>(number(*p, path + ".far"));
    if (!(c.far_plane > c.near_plane))
      fail(path + ".far",
           "must be beyond near (" + show(c.near_plane) + "), got " + show(c.far_plane));
  } else if (!(c.far_plane > c.near_plane)) {
    fail(path + ".near",
         "must be below far (" + show(c.far_plane) + "), got " + show(c.near_plane));
  }
  if (const Json* p = find(v, "resolution")) {
    const std::string rp = path + ".resolution";
    if (!p->is_array() || p->size() != 2)
      fail(rp, "expected [width, height] in pixels, got " +
                   (p->is_array() ? "an array of " + std::to_string(p->size()) : describe(*p)));
    const char* names[2] = {"width", "height"};
    uint32_t size[2];
    for (int i = 0; i < 2; ++i) {
      const Json& e = (*p)[i];
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
    const Json& arr = array(*keys, path + ".path");
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

void parse_lod(const Json& v, RawScene& s) {
  const std::string path = "lod";
  check_object(v, path,
               {"mode", "budget", "alpha", "min_t", "drop_below_min_t", "max_pixel_error",
                "geomorph", "discrete_levels", "impostor_pixels"});
  LodSettings& l = s.lod;
  if (const Json* p = find(v, "mode")) {
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
  if (const Json* p = find(v, "budget"))
    l.budget = static_cast<uint32_t>(integer(*p, path + ".budget", 1, UINT32_MAX));
  if (const Json* p = find(v, "alpha")) {
    const double a = number(*p, path + ".alpha");
    if (!(a > 1.0))
      fail(path + ".alpha", "must be > 1 (beta = alpha - 1 must be positive), got " + show(a));
    l.alpha = static_cast<float>(a);
  }
  if (const Json* p = find(v, "min_t")) {
    const double t = number(*p, path + ".min_t");
    if (!(t >= 0.0 && t <= 1.0)) fail(path + ".min_t", "must be in [0, 1], got " + show(t));
    l.min_t = static_cast<float>(t);
  }
  if (const Json* p = find(v, "max_pixel_error")) {
    const double e = number(*p, path + ".max_pixel_error");
    if (!(e > 0.0) || !std::isfinite(e) || e > 1e6)
      fail(path + ".max_pixel_error", "must be a number of pixels > 0, got " + show(e));
    l.max_pixel_error = static_cast<float>(e);
  }
  if (const Json* p = find(v, "geomorph")) {
    const double f = number(*p, path + ".geomorph");
    if (!(f >= 0.0 && f < 1.0))
      fail(path + ".geomorph", "must be a fraction in [0, 1) (0: off), got " + show(f));
    l.geomorph = static_cast<float>(f);
  }
  if (const Json* p = find(v, "impostor_pixels")) {
    const double px = number(*p, path + ".impostor_pixels");
    if (!(px >= 0.0) || !std::isfinite(px) || px > 1e6)
      fail(path + ".impostor_pixels", "must be a number of pixels >= 0 (0: off), got " + show(px));
    l.impostor_pixels = static_cast<float>(px);
  }
  if (const Json* p = find(v, "drop_below_min_t"))
    l.drop_below_min_t = boolean(*p, path + ".drop_below_min_t");
  if (const Json* p = find(v, "discrete_levels")) {
    const std::string lp = path + ".discrete_levels";
    const Json& arr = array(*p, lp);
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

void parse_animation(const Json& v, RawScene& s) {
  const std::string path = "animation";
  check_object(v, path, {"interpolation", "root_motion"});
  if (const Json* p = find(v, "interpolation")) {
    const std::string mode = string(*p, path + ".interpolation");
    if (mode == "nearest")
      s.animation.filter = FrameFilter::kNearest;
    else if (mode == "linear")
      s.animation.filter = FrameFilter::kLinear;
    else
      fail(path + ".interpolation",
           "unknown interpolation \"" + mode + "\" (expected nearest or linear)");
  }
  if (const Json* p = find(v, "root_motion"))
    s.animation.root_motion = boolean(*p, path + ".root_motion");
}

void parse_types(const Json& v, RawScene& s) {
  const std::string path = "character_types";
  const Json& arr = array(v, path);
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
    if (const Json* p = find(arr[i], "texture_variants")) {
      const std::string vp = tp + ".texture_variants";
      check_object(*p, vp, {"head", "upper_body", "trousers"});
      t.variants_given = true;
      uint32_t* fields[3] = {&t.variants.head, &t.variants.upper_body, &t.variants.trousers};
      const char* names[3] = {"head", "upper_body", "trousers"};
      for (int k = 0; k < 3; ++k)
        if (const Json* q = find(*p, names[k]))
          *fields[k] = static_cast<uint32_t>(integer(*q, vp + "." + names[k], 1, 256));
    }
    if (const Json* p = find(arr[i], "shading")) {
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

void parse_textures(const Json& v, const std::string& path, bool allow_random, RawTextures& out) {
  out.path = path;
  if (allow_random && v.is_string()) {
    if (v.get<std::string>() != "random")
      fail(path, "expected \"random\" or an object of variant indices, got " + describe(v));
    out.random = {true, true, true};
    return;
  }
  check_object(v, path, {"head", "upper_body", "trousers"});
  const char* names[3] = {"head", "upper_body", "trousers"};
  for (int k = 0; k < 3; ++k) {
    const Json* q = find(v, names[k]);
    if (!q) continue;
    const std::string qp = path + "." + names[k];
    if (allow_random && q->is_string()) {
      if (q->get<std::string>() != "random")
        fail(qp, "expected a variant index or \"random\", got " + describe(*q));
      out.random[k] = true;
    } else {
      out.value[k] = integer(*q, qp, 0, 255);
    }
  }
}

// Keys every instance description (listed or generated) may have.
void parse_attributes(const Json& v, const std::string& path, bool generator, RawAttributes& a) {
  a.path = path;
  if (const Json* p = find(v, "type")) {
    a.type = string(*p, path + ".type");
  }
  const Json* clip = find(v, "clip");
  const Json* clips = generator ? find(v, "clips") : nullptr;
  if (clip && clips) fail(path + ".clips", "give either clip or clips, not both");
  if (clip) a.clips.push_back(string(*clip, path + ".clip"));
  if (clips) {
    const Json& arr = array(*clips, path + ".clips");
    if (arr.empty()) fail(path + ".clips", "needs at least one clip name");
    for (size_t i = 0; i < arr.size(); ++i)
      a.clips.push_back(string(arr[i], item_path(path + ".clips", i)));
  }
  const auto value_or_range = [&](const char* key, double lo, bool inclusive, Range& out) {
    const Json* p = find(v, key);
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
  if (const Json* p = find(v, "textures"))
    parse_textures(*p, path + ".textures", generator, a.textures);
  if (const Json* p = find(v, "neck_height"))
    a.neck_height = static_cast<float>(number(*p, path + ".neck_height"));
  if (const Json* p = find(v, "waist_height"))
    a.waist_height = static_cast<float>(number(*p, path + ".waist_height"));
  {
    if (const Json* p = find(v, "color")) {
      const std::string cp = path + ".color";
      check_object(*p, cp, {"hue", "saturation", "brightness"});
      if (const Json* q = find(*p, "hue")) {
        const double h = number(*q, cp + ".hue");
        if (!(h >= -180.0 && h <= 180.0))
          fail(cp + ".hue", "must be in [-180, 180] degrees, got " + show(h));
        a.color[0] = static_cast<float>(h);
      }
      if (const Json* q = find(*p, "saturation"))
        a.color[1] = static_cast<float>(number_at_least(*q, cp + ".saturation", 0.0, true));
      if (const Json* q = find(*p, "brightness"))
        a.color[2] = static_cast<float>(number_at_least(*q, cp + ".brightness", 0.0, true));
    }
  }
  if (const Json* p = generator ? find(v, "color_variation") : nullptr) {
    const std::string cp = path + ".color_variation";
    check_object(*p, cp, {"hue", "saturation", "brightness"});
    if (const Json* q = find(*p, "hue")) {
      const double h = number_at_least(*q, cp + ".hue", 0.0, true);
      if (h > 180.0) fail(cp + ".hue", "must be at most 180 degrees, got " + show(h));
      a.color_variation[0] = static_cast<float>(h);
    }
    const char* names[2] = {"saturation", "brightness"};
    for (int k = 0; k < 2; ++k)
      if (const Json* q = find(*p, names[k])) {
        const double x = number_at_least(*q, cp + "." + names[k], 0.0, true);
        if (x > 1.0) fail(cp + "." + names[k], "must be at most 1, got " + show(x));
        a.color_variation[k + 1] = static_cast<float>(x);
      }
  }
}

void parse_instances(const Json& v, RawScene& s) {
  const std::string path = "instances";
  const Json& arr = array(v, path);
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
    const Json* rotation = find(arr[i], "rotation");
    const Json* yaw = find(arr[i], "yaw_degrees");
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

Rgb color(const Json& v, const std::string& path) {
  const std::array<float, 3> c = numbers<3>(v, path);
  for (int k = 0; k < 3; ++k)
    if (!(c[k] >= 0.0f && c[k] <= 1.0f))
      fail(item_path(path, k), "a colour channel must be in [0, 1], got " + show(c[k]));
  return c;
}

// A seat_grid's "stand": true, false or an object of StandStyle's keys.
std::optional<StandStyle> parse_stand(const Json& v, const std::string& path,
                                      const RawGenerator& g) {
  StandStyle style;
  if (v.is_boolean()) {
    if (!v.get<bool>()) return std::nullopt;
  } else {
    check_object(v, path, {"color", "seat_color", "seat_height", "seat_back", "seats"});
    if (const Json* p = find(v, "color")) style.color = color(*p, path + ".color");
    if (const Json* p = find(v, "seat_color")) style.seat_color = color(*p, path + ".seat_color");
    if (const Json* p = find(v, "seat_height"))
      style.seat_height = static_cast<float>(number_at_least(*p, path + ".seat_height", 0, true));
    if (const Json* p = find(v, "seat_back"))
      style.seat_back = static_cast<float>(number_at_least(*p, path + ".seat_back", 0, true));
    if (const Json* p = find(v, "seats")) style.seats = boolean(*p, path + ".seats");
  }
  if (stand_vertex_bound(g.shape(), style) > kMaxStaticVertices)
    fail(path, "a stand under " + std::to_string(uint64_t{g.rows} * g.columns) +
                   " seats would need more than " + std::to_string(kMaxStaticVertices) +
                   " vertices: draw it without seats (\"seats\": false) or split the grid");
  if (!(g.row_rise >= 0.0f))
    fail(path,
         "a stand needs row_rise >= 0 (its rows stand on the plane of the grid's origin), "
         "got " +
             show(g.row_rise));
  return style;
}

void parse_pitch(const Json& v, RawScene& s) {
  const std::string path = "pitch";
  check_object(v, path,
               {"center", "length", "width", "yaw_degrees", "color", "line_color", "stripes"});
  Pitch p;
  if (const Json* q = find(v, "center")) p.center = numbers<3>(*q, path + ".center");
  if (const Json* q = find(v, "length"))
    p.length = static_cast<float>(number_at_least(*q, path + ".length", 0, false));
  if (const Json* q = find(v, "width"))
    p.width = static_cast<float>(number_at_least(*q, path + ".width", 0, false));
  if (const Json* q = find(v, "yaw_degrees"))
    p.yaw_degrees = static_cast<float>(number(*q, path + ".yaw_degrees"));
  if (const Json* q = find(v, "color")) p.color = color(*q, path + ".color");
  if (const Json* q = find(v, "line_color")) p.line_color = color(*q, path + ".line_color");
  if (const Json* q = find(v, "stripes"))
    p.stripes = static_cast<uint32_t>(integer(*q, path + ".stripes", 0, 1000));
  s.pitch = p;
}

void parse_seat_grid(const Json& v, const std::string& gp, RawGenerator& g) {
  check_object(v, gp, {"kind",        "type",
                       "seed",        "origin",
                       "rows",        "columns",
                       "spacing",     "row_rise",
                       "yaw_degrees", "empty_probability",
                       "clip",        "clips",
                       "speed",       "time_offset",
                       "scale",       "textures",
                       "color",       "color_variation",
                       "neck_height", "waist_height",
                       "stand"});
  g.grid = true;
  if (const Json* p = find(v, "origin")) g.origin = numbers<3>(*p, gp + ".origin");
  g.rows = static_cast<uint32_t>(integer(require(v, "rows", gp), gp + ".rows", 1, kMaxInstances));
  g.columns =
      static_cast<uint32_t>(integer(require(v, "columns", gp), gp + ".columns", 1, kMaxInstances));
  if (uint64_t{g.rows} * g.columns > kMaxInstances)
    fail(gp, std::to_string(g.rows) + " rows x " + std::to_string(g.columns) +
                 " columns exceed the limit of " + std::to_string(kMaxInstances) + " instances");
  const std::array<float, 2> spacing = numbers<2>(require(v, "spacing", gp), gp + ".spacing");
  for (int k = 0; k < 2; ++k)
    if (!(spacing[k] > 0.0f))
      fail(item_path(gp + ".spacing", k), "must be > 0, got " + show(spacing[k]));
  g.spacing[0] = spacing[0];
  g.spacing[1] = spacing[1];
  if (const Json* p = find(v, "row_rise"))
    g.row_rise = static_cast<float>(number(*p, gp + ".row_rise"));
  if (const Json* p = find(v, "yaw_degrees"))
    g.yaw_degrees = static_cast<float>(number(*p, gp + ".yaw_degrees"));
  if (const Json* p = find(v, "empty_probability")) {
    const double e = number(*p, gp + ".empty_probability");
    if (!(e >= 0.0 && e <= 1.0))
      fail(gp + ".empty_probability", "must be in [0, 1], got " + show(e));
    g.empty_probability = static_cast<float>(e);
  }
  if (const Json* p = find(v, "stand")) g.stand = parse_stand(*p, gp + ".stand", g);
}

void parse_generators(const Json& v, RawScene& s) {
  const std::string path = "generators";
  const Json& arr = array(v, path);
  for (size_t i = 0; i < arr.size(); ++i) {
    const std::string gp = item_path(path, i);
    if (!arr[i].is_object()) fail(gp, "expected an object, got " + describe(arr[i]));
    const std::string kind = string(require(arr[i], "kind", gp), gp + ".kind");
    RawGenerator g;
    if (kind == "seat_grid") {
      parse_seat_grid(arr[i], gp, g);
    } else if (kind == "scatter") {
      check_object(arr[i], gp,
                   {"kind", "type", "seed", "count", "rectangle", "y", "yaw_degrees", "clip",
                    "clips", "speed", "time_offset", "scale", "textures", "color",
                    "color_variation", "neck_height", "waist_height"});
      g.grid = false;
      g.count = static_cast<uint32_t>(
          integer(require(arr[i], "count", gp), gp + ".count", 0, kMaxInstances));
      const std::string rp = gp + ".rectangle";
      const Json& rect = require(arr[i], "rectangle", gp);
      check_object(rect, rp, {"min", "max"});
      const std::array<float, 2> lo = numbers<2>(require(rect, "min", rp), rp + ".min");
      const std::array<float, 2> hi = numbers<2>(require(rect, "max", rp), rp + ".max");
      for (int k = 0; k < 2; ++k)
        if (!(hi[k] > lo[k]))
          fail(rp, std::string("max must exceed min in ") + (k == 0 ? "x" : "z") + " (min " +
                       show(lo[k]) + ", max " + show(hi[k]) + ")");
      g.rect_min[0] = lo[0], g.rect_min[1] = lo[1], g.rect_max[0] = hi[0], g.rect_max[1] = hi[1];
      if (const Json* p = find(arr[i], "y")) g.y = static_cast<float>(number(*p, gp + ".y"));
      g.random_yaw = true;
      if (const Json* p = find(arr[i], "yaw_degrees")) {
        if (p->is_string() && p->get<std::string>() == "random")
          g.random_yaw = true;
        else if (p->is_number())
          g.random_yaw = false, g.yaw_degrees = static_cast<float>(number(*p, gp + ".yaw_degrees"));
        else
          fail(gp + ".yaw_degrees", "expected a number or \"random\", got " + describe(*p));
      }
    } else if (kind == "relaxation") {
      check_object(arr[i], gp, {"kind",         "type",          "seed",
                                "region",       "count",         "y",
                                "min_distance", "group_spacing", "single_fraction",
                                "iterations",   "clip",          "clips",
                                "speed",        "time_offset",   "scale",
                                "textures",     "color",         "color_variation",
                                "neck_height",  "waist_height"});
      g.grid = false;
      g.relaxation = true;
      g.count = static_cast<uint32_t>(
          integer(require(arr[i], "count", gp), gp + ".count", 0, kMaxInstances));
      g.relax.people = g.count;
      const std::string rp = gp + ".region";
      const Json& region = array(require(arr[i], "region", gp), rp);
      if (region.size() < 3)
        fail(rp, "a polygon needs at least 3 [x, z] points, got " + std::to_string(region.size()));
      for (size_t k = 0; k < region.size(); ++k)
        g.relax.region.push_back(numbers<2>(region[k], item_path(rp, k)));
      if (const Json* p = find(arr[i], "y")) g.y = static_cast<float>(number(*p, gp + ".y"));
      if (const Json* p = find(arr[i], "min_distance"))
        g.relax.min_distance =
            static_cast<float>(number_at_least(*p, gp + ".min_distance", 0.0, false));
      if (const Json* p = find(arr[i], "group_spacing"))
        g.relax.group_spacing =
            static_cast<float>(number_at_least(*p, gp + ".group_spacing", 0.0, false));
      if (!(g.relax.group_spacing >= g.relax.min_distance))
        fail(gp + ".group_spacing", "must be at least min_distance (" + show(g.relax.min_distance) +
                                        "), got " + show(g.relax.group_spacing));
      if (const Json* p = find(arr[i], "single_fraction")) {
        const double f = number(*p, gp + ".single_fraction");
        if (!(f >= 0.0 && f <= 1.0))
          fail(gp + ".single_fraction", "must be in [0, 1], got " + show(f));
        g.relax.single_fraction = static_cast<float>(f);
      }
      if (const Json* p = find(arr[i], "iterations"))
        g.relax.iterations = static_cast<int>(integer(*p, gp + ".iterations", 0, 10000));
    } else {
      fail(gp + ".kind",
           "unknown generator \"" + kind + "\" (expected seat_grid, scatter or relaxation)");
    }
    g.path = gp;
    if (const Json* p = find(arr[i], "seed"))
      g.seed = static_cast<uint64_t>(integer(*p, gp + ".seed", 0, INT64_MAX));
    g.relax.seed = g.seed;
    parse_attributes(arr[i], gp, true, g.a);
    s.generators.push_back(std::move(g));
  }
}

// The sections other libraries read (SceneLoadOptions::sections), once the core's own keys
// are read and checked.
void read_sections(const Json& root, const SceneLoadOptions& options, RawScene& s) {
  SceneOutline outline;
  for (const RawType& t : s.types) outline.type_names.push_back(t.name);
  outline.generators = static_cast<uint32_t>(s.generators.size());
  s.sections.resize(options.sections.size());
  for (size_t i = 0; i < options.sections.size(); ++i) {
    const SceneSection& section = options.sections[i];
    const Json* p = find(root, section.key.c_str());
    if (!p) continue;
    if (!section.read) fail(section.key, "the section's reader has no read function");
    const Status read = section.read(*p, outline, s.sections[i]);
    if (!read) throw JsonError{"", read.message(), read.code()};
  }
}

}  // namespace

RawScene read_scene_file(const Json& root, const SceneLoadOptions& options) {
  RawScene s;
  std::vector<std::string> keys = {"version",         "camera",    "lod",        "animation",
                                   "character_types", "instances", "generators", "pitch"};
  for (const SceneSection& section : options.sections) {
    if (std::find(keys.begin(), keys.end(), section.key) != keys.end())
      fail(section.key, "two readers were given for this key (SceneLoadOptions::sections)",
           StatusCode::kInvalidArgument);
    keys.push_back(section.key);
  }
  check_keys(root, "", keys,
             "; a key another library reads needs its reader in SceneLoadOptions::sections, as "
             "crowd_scene_load_options() gives for \"effects\"");
  if (const Json* p = find(root, "version")) {
    const int64_t version = integer(*p, "version", 0, INT32_MAX);
    if (version != 1)
      fail("version",
           "unsupported scene version " + std::to_string(version) + " (this build reads 1)");
  }
  parse_camera(require(root, "camera", ""), s);
  if (const Json* p = find(root, "lod")) parse_lod(*p, s);
  if (const Json* p = find(root, "animation")) parse_animation(*p, s);
  parse_types(require(root, "character_types", ""), s);
  if (const Json* p = find(root, "instances")) parse_instances(*p, s);
  if (const Json* p = find(root, "generators")) parse_generators(*p, s);
  if (const Json* p = find(root, "pitch")) parse_pitch(*p, s);
  read_sections(root, options, s);
  uint64_t total = s.instances.size();
  for (const RawGenerator& g : s.generators)
    total += g.grid ? uint64_t{g.rows} * g.columns : g.count;
  if (total > kMaxInstances)
    fail("generators", "the scene would hold " + std::to_string(total) +
                           " instances, above the limit of " + std::to_string(kMaxInstances));
  uint64_t static_vertices = 0;
  for (const RawGenerator& g : s.generators) {
    if (!g.stand) continue;
    static_vertices += stand_vertex_bound(g.shape(), *g.stand);
  }
  if (static_vertices > kMaxStaticVertices)
    fail("generators", "the stands together would need " + std::to_string(static_vertices) +
                           " vertices, above the limit of " + std::to_string(kMaxStaticVertices) +
                           ": draw some without seats (\"seats\": false)");
  return s;
}

}  // namespace crowdbake::runtime::scene_file
