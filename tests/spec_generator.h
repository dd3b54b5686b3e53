// A seeded generator of random, valid spec v1 documents, for round-trip and
// property tests (tests/spec_generator_test.cc, tests/dsl_roundtrip_test.cc).
//
// generate_spec(seed) returns a document that the JSON reader accepts and
// that passes every type rule (check_structure, resolve, check_resolved) when
// read with base_dir = examples/ (meshes are examples/meshes/*.obj). Over a
// few hundred seeds the documents use every field of spec v1, every part
// role, geometry kind, joint, mapping and effect type with all their optional
// fields, nested compounds, chains of functions, and `x-` keys at every object
// level holding arbitrary JSON (nested values, strings with quotes,
// backslashes, unicode, newlines and control characters, extreme integers and
// doubles). Numbers are deliberately awkward: negative, tiny, large, 0.1, 1/3,
// pi/2, full-precision doubles, range endpoints, integers.
//
// Only std::mt19937_64's raw output is used (its sequence is fixed by the
// standard); every distribution is written here, so a seed gives the same
// document with every standard library.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace efc::testing {

namespace spec_gen_detail {

using nlohmann::json;

constexpr double kPi = 3.14159265358979323846;

class Rng {
 public:
  explicit Rng(uint64_t seed) : eng_(seed * 0x9E3779B97F4A7C15ULL + 0x2545F4914F6CDD1DULL) {}

  uint64_t bits() { return eng_(); }
  // [0, 1), 53 random bits.
  double unit() { return static_cast<double>(bits() >> 11) * 0x1.0p-53; }
  // An integer in [lo, hi] (the modulo bias is irrelevant here).
  int64_t between(int64_t lo, int64_t hi) {
    const uint64_t span = static_cast<uint64_t>(hi - lo) + 1;
    return lo + static_cast<int64_t>(span == 0 ? bits() : bits() % span);
  }
  size_t index(size_t n) { return static_cast<size_t>(between(0, static_cast<int64_t>(n) - 1)); }
  bool chance(double p) { return unit() < p; }
  double uniform(double lo, double hi) {
    const double x = lo + (hi - lo) * unit();
    return std::min(std::max(x, lo), hi);
  }
  template <class T>
  const T& pick(const std::vector<T>& v) {
    return v[index(v.size())];
  }
  template <class T>
  void shuffle(std::vector<T>& v) {
    for (size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[index(i)]);
  }

 private:
  std::mt19937_64 eng_;
};

// What the generator knows about a part's joint when it builds functions.
struct JointInfo {
  std::string type;  // "" for the root
  bool bounded = false;
  double lo = 0, hi = 0;
  bool movable() const { return type == "revolute" || type == "continuous" || type == "prismatic"; }
};

class Generator {
 public:
  explicit Generator(uint64_t seed) : rng_(seed) {}

  json spec() {
    json doc = json::object();
    doc["efc"] = 1;
    doc["name"] = name();
    if (rng_.chance(0.4)) doc["description"] = text();
    maybe_ext(doc, 0.35);

    // Parts in creation order (a parent is always created before its child),
    // written in a shuffled order so references point forwards and backwards.
    const size_t n = static_cast<size_t>(rng_.between(1, 7));
    std::vector<json> parts(n);
    std::vector<JointInfo> joints(n);
    std::vector<std::string> names = unique_names(n);
    for (size_t i = 0; i < n; ++i) {
      json p = json::object();
      p["name"] = names[i];
      if (rng_.chance(0.85)) p["role"] = rng_.pick(std::vector<std::string>{"base", "receptor", "effector", "other"});
      p["geometry"] = geometry(0);
      if (rng_.chance(0.4)) p["mass"] = positive(i % 3 == 0 ? 2e4 : 20);
      if (rng_.chance(0.35)) p["rgba"] = json::array({in(0, 1), in(0, 1), in(0, 1), in(0, 1)});
      if (i > 0) {
        const size_t parent = rng_.index(i);
        p["joint"] = joint(names[parent], &joints[i]);
      }
      maybe_ext(p, 0.3);
      parts[i] = std::move(p);
    }

    json functions = json::array();
    build_functions(names, joints, functions);

    std::vector<size_t> order(n);
    for (size_t i = 0; i < n; ++i) order[i] = i;
    rng_.shuffle(order);
    json parts_json = json::array();
    for (size_t i : order) parts_json.push_back(parts[i]);
    doc["parts"] = std::move(parts_json);
    if (!functions.empty() || rng_.chance(0.2)) doc["functions"] = std::move(functions);
    return doc;
  }

 private:
  // ------------------------------------------------------------ numbers
  // A number in [lo, hi] (finite, lo <= hi), written awkwardly: an endpoint,
  // a special value (0.1, 1/3, pi/2, 1e-7, ...), an integer, a short decimal,
  // or a full-precision double.
  json in(double lo, double hi) {
    static const double kSpecials[] = {
        0.0,         0.1,          0.2,         0.3,          0.7,         1.0 / 3,
        2.0 / 3,     -1.0 / 3,     kPi / 2,     kPi,          2 * kPi,     -kPi / 2,
        -kPi / 4,    kPi / 180,    1e-7,        -1e-7,        1e-3,        0.004,
        0.5,         1.0,          -1.0,        12.5,         100.0,       273.15,
        -273.15,     0.1 + 0.2,    1e6,         3.0e-5,       123456.789,  0.9999999999999999,
        1.0000000000000002, 2.5e-4, -0.05,      9.81,         1e5,         -123.456789012345};
    for (int attempt = 0; attempt < 4; ++attempt) {
      switch (rng_.between(0, 9)) {
        case 0:
          return rng_.chance(0.5) ? num(lo) : num(hi);
        case 1:
        case 2: {
          std::vector<double> inside;
          for (double s : kSpecials)
            if (s >= lo && s <= hi) inside.push_back(s);
          if (inside.empty()) continue;
          return rng_.pick(inside);
        }
        case 3: {
          const double a = std::ceil(lo), b = std::floor(hi);
          if (a > b || a < -1e15 || b > 1e15) continue;
          const int64_t k = rng_.between(static_cast<int64_t>(a),
                                         std::min(static_cast<int64_t>(b), static_cast<int64_t>(a) + 1000));
          return json(k);  // a JSON integer
        }
        case 4:
        case 5: {
          const double scale = std::pow(10.0, static_cast<double>(rng_.between(0, 4)));
          const double x = std::round(rng_.uniform(lo, hi) * scale) / scale;
          if (x < lo || x > hi) continue;
          return x;
        }
        default:
          return rng_.uniform(lo, hi);  // 15-17 significant digits
      }
    }
    return rng_.uniform(lo, hi);
  }
  // Endpoints stay integers when they are integral (as a person writes them).
  static json num(double v) {
    if (v == std::floor(v) && std::fabs(v) < 1e15 && !(v == 0 && std::signbit(v)))
      return json(static_cast<int64_t>(v));
    return v;
  }
  json positive(double hi) { return in(1e-7, hi); }  // > 0
  json nonzero(double lo, double hi) {
    for (;;) {
      json v = in(lo, hi);
      if (v.get<double>() != 0) return v;
    }
  }
  // Two different numbers in [lo, hi], in increasing order.
  std::pair<json, json> ordered(double lo, double hi) {
    for (int attempt = 0; attempt < 20; ++attempt) {
      json a = in(lo, hi), b = in(lo, hi);
      if (a.get<double>() == b.get<double>()) continue;
      if (a.get<double>() > b.get<double>()) std::swap(a, b);
      return {a, b};
    }
    return {num(lo), num(hi)};
  }
  json vec3(double lo, double hi) { return json::array({in(lo, hi), in(lo, hi), in(lo, hi)}); }
  json position() { return vec3(-2, 2); }
  // A non-zero direction: a unit axis, a full-precision unit vector, or
  // (rarely, a warning only) one of another length.
  json direction() {
    switch (rng_.between(0, 4)) {
      case 0:
      case 1: {
        json a = json::array({0, 0, 0});
        a[rng_.index(3)] = rng_.chance(0.5) ? 1 : -1;
        return a;
      }
      case 2: {
        double x = rng_.uniform(-1, 1), y = rng_.uniform(-1, 1), z = rng_.uniform(-1, 1);
        double n = std::sqrt(x * x + y * y + z * z);
        if (n < 1e-3) return json::array({0, 0, 1});
        return json::array({x / n, y / n, z / n});
      }
      case 3:
        return rng_.pick(std::vector<json>{json::array({0, 0.6, -0.8}), json::array({0.0, 0.0, -1.0}),
                                           json::array({std::sqrt(0.5), 0, std::sqrt(0.5)}),
                                           json::array({1.0 / 3, 2.0 / 3, 2.0 / 3})});
      default: {
        json a = vec3(-3, 3);
        if (a[0].get<double>() == 0 && a[1].get<double>() == 0 && a[2].get<double>() == 0) a[2] = 1;
        return a;
      }
    }
  }

  // ------------------------------------------------------------ names and text
  std::string name() {
    static const std::vector<std::string> kWords = {
        // DSL keywords, literals, units and enum words are valid spec names.
        "part", "function", "joint", "object", "on", "mapping", "effect", "geometry", "box",
        "cylinder", "sphere", "mesh", "compound", "efc", "true", "false", "null", "m", "mm",
        "cm", "deg", "rad", "kg", "s", "C", "K", "lm", "x", "e", "E", "inf", "nan", "NaN",
        "base", "receptor", "effector", "other", "fixed", "revolute", "continuous", "prismatic",
        "binary", "step", "linear", "cumulative", "spring", "emitter", "outlet", "range",
        "type", "name", "_", "__", "_9", "a1", "e1", "E5", "x_", "handle", "door", "knob",
        "Lid", "BULB_2", "spout"};
    switch (rng_.between(0, 5)) {
      case 0:
      case 1:
      case 2:
        return rng_.pick(kWords);
      case 3:
        return std::string(64, 'n').replace(0, 1, "N");  // the longest name
      default: {
        static const std::string kFirst = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ_";
        static const std::string kRest = kFirst + "0123456789";
        std::string s(1, kFirst[rng_.index(kFirst.size())]);
        const size_t len = static_cast<size_t>(rng_.between(0, 12));
        for (size_t i = 0; i < len; ++i) s += kRest[rng_.index(kRest.size())];
        if (s.rfind("efc_", 0) == 0) s = "f" + s;  // efc_ is reserved
        return s;
      }
    }
  }
  std::vector<std::string> unique_names(size_t n) {
    std::vector<std::string> out;
    std::set<std::string> seen;
    while (out.size() < n) {
      std::string s = name();
      if (seen.insert(s).second) out.push_back(s);
    }
    return out;
  }
  // Free text (valid UTF-8) with everything a printer must escape.
  std::string text() {
    static const std::vector<std::string> kPieces = {
        "plain words",
        "with \"double quotes\"",
        "a back\\slash and \\n not a newline",
        "unicode: \xC3\xA9 \xC3\xBC \xE4\xB8\xAD\xE6\x96\x87 \xF0\x9F\x9A\x80 \xE2\x82\xAC",
        "new\nline",
        "crlf\r\n",
        "tab\there",
        "ctrl \x01\x1f\x7f",
        "",
        "true",
        "null",
        "1.5",
        "-0",
        "# not a comment",
        "// nor this /* */",
        "x-key",
        "{ } [ ] ( ) ; : , ..",
        "a -> b",
        "'single'",
        "line sep \xE2\x80\xA8 para sep \xE2\x80\xA9",
        "\\u0041 is not A",
        "0 .. 4 mm",
        " leading and trailing spaces ",
        "efc 1",
        "object thing {",
        "\"",
        "\\",
    };
    std::string s;
    const int pieces = static_cast<int>(rng_.between(1, 3));
    for (int i = 0; i < pieces; ++i) s += rng_.pick(kPieces);
    return s;
  }

  // ------------------------------------------------------------ x- extensions
  std::string ext_key() {
    static const std::vector<std::string> kKeys = {
        "x-note", "x-a", "x-1", "x-a.b-c", "x-", "x--", "x-source.v2", "x-Tool_Name",
        "x-with space", "x-\xC3\xBC", "x-\"q\"", "x-back\\slash", "x-new\nline", "x-{", "x-;",
        "x-0.5", "x-true", "x-#"};
    return rng_.pick(kKeys);
  }
  json ext_value(int depth) {
    const int64_t kind = rng_.between(0, depth >= 3 ? 5 : 7);
    switch (kind) {
      case 0:
        return nullptr;
      case 1:
        return rng_.chance(0.5);
      case 2:
        return rng_.pick(std::vector<json>{
            json(0), json(1), json(-1), json(42), json(-273), json(std::numeric_limits<int64_t>::max()),
            json(std::numeric_limits<int64_t>::min()), json(std::numeric_limits<uint64_t>::max()),
            json(9007199254740993LL), json(static_cast<uint64_t>(1) << 63)});
      case 3:
        return rng_.pick(std::vector<json>{
            json(0.1), json(-0.0), json(1.0 / 3), json(kPi / 2), json(1e-7), json(-1e-7),
            json(5e-324), json(2.2250738585072014e-308), json(1.7976931348623157e308),
            json(-1.7976931348623157e308), json(1e300), json(1.5), json(2.0), json(-2.5e-10),
            json(0.30000000000000004), json(123456789.123456789), json(1e21), json(1e22)});
      case 4:
      case 5:
        return text();
      case 6: {
        json a = json::array();
        const int64_t k = rng_.between(0, 4);
        for (int64_t i = 0; i < k; ++i) a.push_back(ext_value(depth + 1));
        return a;
      }
      default: {
        json o = json::object();
        const int64_t k = rng_.between(0, 4);
        for (int64_t i = 0; i < k; ++i) {
          // Keys inside an x- value are free: x-, spec keys, odd text.
          std::string key;
          switch (rng_.between(0, 3)) {
            case 0: key = ext_key(); break;
            case 1: key = rng_.pick(std::vector<std::string>{"type", "range", "name", "parts", "efc", "a"}); break;
            default: key = text(); break;
          }
          o[key] = ext_value(depth + 1);
        }
        return o;
      }
    }
  }
  void maybe_ext(json& o, double p) {
    if (!rng_.chance(p)) return;
    const int64_t k = rng_.between(1, 2);
    for (int64_t i = 0; i < k; ++i) o[ext_key()] = ext_value(0);
  }

  // ------------------------------------------------------------ geometry
  json geometry(int depth) {
    json g = json::object();
    const int64_t kind = rng_.between(0, depth < 2 ? 4 : 3);
    switch (kind) {
      case 0: {
        g["mesh"] = rng_.pick(std::vector<std::string>{"meshes/faucet_handle.obj", "meshes/faucet_spout.obj",
                                                       "meshes/../meshes/faucet_spout.obj"});
        if (rng_.chance(0.5)) g["scale"] = json::array({in(0.05, 20), in(0.05, 20), in(0.05, 20)});
        break;
      }
      case 1: {
        json b = json::object();
        b["size"] = json::array({positive(3), positive(3), positive(3)});
        if (rng_.chance(0.5)) b["center"] = position();
        if (rng_.chance(0.4)) b["rpy"] = vec3(-kPi, kPi);
        maybe_ext(b, 0.3);
        g["box"] = std::move(b);
        break;
      }
      case 2: {
        json c = json::object();
        c["radius"] = positive(1);
        c["length"] = positive(3);
        if (rng_.chance(0.5)) c["center"] = position();
        if (rng_.chance(0.5)) c["axis"] = direction();
        maybe_ext(c, 0.3);
        g["cylinder"] = std::move(c);
        break;
      }
      case 3: {
        json s = json::object();
        s["radius"] = positive(1);
        if (rng_.chance(0.5)) s["center"] = position();
        maybe_ext(s, 0.3);
        g["sphere"] = std::move(s);
        break;
      }
      default: {
        json list = json::array();
        const int64_t k = rng_.between(1, 3);
        for (int64_t i = 0; i < k; ++i) list.push_back(geometry(depth + 1));
        g["compound"] = std::move(list);
        break;
      }
    }
    maybe_ext(g, 0.3);
    return g;
  }

  // ------------------------------------------------------------ joints
  json joint(const std::string& parent, JointInfo* info) {
    json j = json::object();
    const std::string type = rng_.pick(std::vector<std::string>{"fixed", "revolute", "continuous", "prismatic"});
    info->type = type;
    j["type"] = type;
    j["parent"] = parent;
    if (rng_.chance(0.4)) j["origin"] = position();
    if (type != "fixed") {
      if (rng_.chance(0.6)) j["axis"] = direction();
      if (type != "continuous") {
        auto [lo, hi] = type == "revolute" ? ordered(-2 * kPi, 2 * kPi) : ordered(-0.5, 0.5);
        j["range"] = json::array({lo, hi});
        info->bounded = true;
        info->lo = lo.get<double>();
        info->hi = hi.get<double>();
      }
      if (rng_.chance(0.4)) j["initial"] = info->bounded ? in(info->lo, info->hi) : in(-10, 10);
      if (rng_.chance(0.4)) j["damping"] = in(0, 50);
      if (rng_.chance(0.4)) j["friction"] = in(0, 50);
      if (rng_.chance(0.35)) {
        json s = json::object();
        s["stiffness"] = positive(rng_.chance(0.2) ? 1e6 : 100);
        if (rng_.chance(0.6)) s["rest"] = info->bounded ? in(info->lo - 1, info->hi + 1) : in(-7, 7);
        maybe_ext(s, 0.3);
        j["spring"] = std::move(s);
      }
    }
    maybe_ext(j, 0.3);
    return j;
  }

  // ------------------------------------------------------------ functions
  // Functions go from a lower to a higher rank (a random order of the parts),
  // so the function graph has no cycle; one writer per (effector, effect type).
  void build_functions(const std::vector<std::string>& names, const std::vector<JointInfo>& joints,
                       json& out) {
    const size_t n = names.size();
    std::vector<size_t> movable;
    for (size_t i = 0; i < n; ++i)
      if (joints[i].movable()) movable.push_back(i);
    if (movable.empty()) return;
    std::vector<size_t> rank(n);
    {
      std::vector<size_t> order(n);
      for (size_t i = 0; i < n; ++i) order[i] = i;
      rng_.shuffle(order);
      for (size_t r = 0; r < n; ++r) rank[order[r]] = r;
    }
    static const std::vector<std::string> kEffects = {"geometry", "illumination", "temperature", "fluid",
                                                      "airflow"};
    std::set<std::pair<size_t, std::string>> written;
    std::set<std::string> fn_names;
    std::vector<size_t> effectors;
    const int64_t count = rng_.between(0, 5);
    for (int64_t k = 0; k < count; ++k) {
      for (int attempt = 0; attempt < 30; ++attempt) {
        size_t r = rng_.pick(movable);
        // Prefer a chain: the receptor is an earlier function's (movable) effector.
        if (!effectors.empty() && rng_.chance(0.5)) {
          size_t e = rng_.pick(effectors);
          if (joints[e].movable()) r = e;
        }
        const size_t e = rng_.index(n);
        if (e == r || rank[r] >= rank[e]) continue;
        std::vector<std::string> types;
        for (const auto& t : kEffects) {
          if (written.count({e, t})) continue;
          if (t == "geometry" && !joints[e].movable()) continue;
          types.push_back(t);
        }
        if (types.empty()) continue;
        const std::string effect_type = rng_.pick(types);
        written.insert({e, effect_type});
        effectors.push_back(e);

        json f = json::object();
        std::string fname;
        do fname = name(); while (!fn_names.insert(fname).second);
        f["name"] = fname;
        f["receptor"] = names[r];
        f["effector"] = names[e];
        double e_lo = 0, e_hi = 0;
        f["effect"] = effect(effect_type, joints[e], &e_lo, &e_hi);
        f["mapping"] = mapping(joints[r], e_lo, e_hi);
        maybe_ext(f, 0.3);
        out.push_back(std::move(f));
        break;
      }
    }
  }

  // The effect; *lo, *hi get its effective range (given or default).
  json effect(const std::string& type, const JointInfo& effector, double* lo, double* hi) {
    json e = json::object();
    e["type"] = type;
    const bool range = rng_.chance(0.7) || (type == "geometry" && !effector.bounded);
    double floor = 0, top = 0;
    if (type == "geometry") {
      if (effector.bounded) {
        floor = effector.lo;
        top = effector.hi;
      } else {
        floor = -4 * kPi;
        top = 4 * kPi;
      }
      *lo = effector.lo;
      *hi = effector.hi;
    } else if (type == "illumination") {
      floor = 0, top = 5000, *lo = 0, *hi = 800;
    } else if (type == "temperature") {
      floor = -273.15, top = 2000, *lo = 20, *hi = 200;
    } else if (type == "fluid") {
      floor = 0, top = 60, *lo = 0, *hi = 6;
    } else {
      floor = 0, top = 50, *lo = 0, *hi = 10;
    }
    if (range) {
      auto [a, b] = ordered(floor, top);
      if (rng_.chance(0.3)) std::swap(a, b);  // [off, on] may run downwards
      *lo = a.get<double>();
      *hi = b.get<double>();
      e["range"] = json::array({a, b});
    }
    auto point = [&](const char* key) {
      json p = json::object();
      if (rng_.chance(0.7)) p["position"] = position();
      if (rng_.chance(0.7)) p["direction"] = direction();
      maybe_ext(p, 0.3);
      e[key] = std::move(p);
    };
    if (type == "geometry") {
      if (rng_.chance(0.5)) e["stiffness"] = in(0, 5000);
      if (rng_.chance(0.5)) e["damping"] = in(0, 200);
    } else if (type == "illumination") {
      if (rng_.chance(0.5)) e["color"] = json::array({in(0, 1), in(0, 1), in(0, 1)});
      if (rng_.chance(0.5)) e["position"] = position();
    } else if (type == "temperature") {
      if (rng_.chance(0.5)) e["time_constant"] = positive(rng_.chance(0.2) ? 1e5 : 600);
      if (rng_.chance(0.5)) e["position"] = position();
    } else if (type == "fluid") {
      if (rng_.chance(0.6)) point("emitter");
      if (rng_.chance(0.5)) e["speed"] = positive(20);
      if (rng_.chance(0.5)) e["droplet_radius"] = positive(0.05);
    } else {
      if (rng_.chance(0.6)) point("outlet");
      if (rng_.chance(0.5)) e["cone_angle"] = in(1e-7, std::nextafter(kPi / 2, 0.0));
      if (rng_.chance(0.5)) e["reach"] = positive(rng_.chance(0.2) ? 1e4 : 5);
    }
    maybe_ext(e, 0.3);
    return e;
  }

  // The mapping for a receptor joint; [e_lo, e_hi] is the effect's effective range.
  json mapping(const JointInfo& receptor, double e_lo, double e_hi) {
    json m = json::object();
    const std::string type = rng_.pick(std::vector<std::string>{"binary", "step", "linear", "cumulative"});
    m["type"] = type;
    const bool continuous = !receptor.bounded;  // continuous receptors need explicit parameters
    auto threshold = [&] {
      if (continuous || rng_.chance(0.5))
        m["threshold"] = receptor.bounded ? in(receptor.lo, receptor.hi) : in(-2 * kPi, 4 * kPi);
    };
    if (type == "binary") {
      threshold();
      if (rng_.chance(0.5)) m["latching"] = rng_.chance(0.5);
    } else if (type == "step") {
      threshold();
      if (rng_.chance(0.5))
        m["hysteresis"] = in(0, receptor.bounded ? (receptor.hi - receptor.lo) / 4 : 1.0);
    } else if (type == "linear") {
      if (continuous || rng_.chance(0.5)) m["gain"] = nonzero(-1e4, 1e4);
      if (rng_.chance(0.5)) m["offset"] = in(-1000, 1000);
    } else {
      threshold();
      m["delta"] = nonzero(-100, 100);
      if (rng_.chance(0.5)) m["initial"] = in(std::min(e_lo, e_hi), std::max(e_lo, e_hi));
    }
    maybe_ext(m, 0.3);
    return m;
  }

  Rng rng_;
};

}  // namespace spec_gen_detail

// A valid spec v1 document (read it with base_dir = examples/).
inline nlohmann::json generate_spec(uint64_t seed) {
  return spec_gen_detail::Generator(seed).spec();
}

}  // namespace efc::testing
