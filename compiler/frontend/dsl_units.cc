#include "compiler/frontend/dsl_units.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace efc::dsl {
namespace {

using nlohmann::json;

constexpr Unit kUnits[] = {
    {"m", Dim::Length},       {"cm", Dim::Length},   {"mm", Dim::Length}, {"rad", Dim::Angle},
    {"deg", Dim::Angle},      {"kg", Dim::Mass},     {"s", Dim::Time},    {"C", Dim::Temperature},
    {"K", Dim::Temperature},  {"lm", Dim::Luminous}, {"L/min", Dim::Flow}, {"m/s", Dim::Speed},
};

// Units the printer may choose for a dimension, SI first.
std::vector<const Unit*> candidates(Dim d) {
  std::vector<const Unit*> out;
  auto add = [&](const char* n) { out.push_back(find_unit(n)); };
  switch (d) {
    case Dim::Length: add("m"); add("cm"); add("mm"); break;
    case Dim::Angle: add("rad"); add("deg"); break;
    case Dim::Mass: add("kg"); break;
    case Dim::Time: add("s"); break;
    case Dim::Temperature:
    case Dim::TemperatureDelta: add("C"); break;
    case Dim::Luminous: add("lm"); break;
    case Dim::Flow: add("L/min"); break;
    case Dim::Speed: add("m/s"); break;
    case Dim::None:
    case Dim::Unknown: break;
  }
  return out;
}

double from_si(const Unit& u, double v) {
  std::string_view n = u.name;
  if (n == "cm") return v * 100;
  if (n == "mm") return v * 1000;
  if (n == "deg") return v / M_PI * 180;
  return v;
}

const json* member(const json* j, const char* key) {
  if (!j || !j->is_object()) return nullptr;
  auto it = j->find(key);
  return it == j->end() ? nullptr : &*it;
}

const json* element(const json* j, const std::string& index) {
  if (!j || !j->is_array() || index.empty() || index.size() > 9) return nullptr;
  for (char c : index)
    if (c < '0' || c > '9') return nullptr;
  size_t i = std::stoul(index);
  return i < j->size() ? &(*j)[i] : nullptr;
}

std::string string_at(const json* j) { return j && j->is_string() ? j->get<std::string>() : ""; }

Dim geometry_dim(const std::vector<std::string>& p, size_t i) {
  // p[i] is "geometry"; skip compound elements down to the primitive.
  ++i;
  while (i + 1 < p.size() && p[i] == "compound") i += 2;
  if (i >= p.size()) return Dim::Unknown;
  const std::string& kind = p[i];
  if (kind == "scale" && i + 1 == p.size()) return Dim::None;
  if (kind != "box" && kind != "cylinder" && kind != "sphere") return Dim::Unknown;
  if (i + 2 != p.size()) return Dim::Unknown;
  const std::string& f = p[i + 1];
  if (f == "size" || f == "center" || f == "radius" || f == "length") return Dim::Length;
  if (f == "rpy") return Dim::Angle;
  if (f == "axis") return Dim::None;
  return Dim::Unknown;
}

}  // namespace

const Unit* find_unit(std::string_view name) {
  for (const Unit& u : kUnits)
    if (name == u.name) return &u;
  return nullptr;
}

std::string unit_list() {
  std::string out;
  for (const Unit& u : kUnits) {
    if (!out.empty()) out += ", ";
    out += u.name;
  }
  return out;
}

std::string describe_dim(Dim d) {
  switch (d) {
    case Dim::None: return "unitless";
    case Dim::Length: return "a length (m, cm, mm)";
    case Dim::Angle: return "an angle (rad, deg)";
    case Dim::Mass: return "a mass (kg)";
    case Dim::Time: return "a time (s)";
    case Dim::Temperature: return "a temperature (C, K)";
    case Dim::TemperatureDelta: return "a temperature difference (C, K)";
    case Dim::Luminous: return "a light output (lm)";
    case Dim::Flow: return "a liquid flow (L/min)";
    case Dim::Speed: return "a speed (m/s)";
    case Dim::Unknown: return "of unknown dimension";
  }
  return "";
}

bool unit_fits(const Unit& u, Dim d) {
  if (d == Dim::Unknown) return true;
  if (d == Dim::TemperatureDelta) return u.dim == Dim::Temperature;
  return u.dim == d;
}

double to_si(const Unit& u, double v, Dim field) {
  std::string_view n = u.name;
  if (n == "cm") return v / 100;
  if (n == "mm") return v / 1000;
  if (n == "deg") return v / 180 * M_PI;
  if (n == "K") return field == Dim::TemperatureDelta ? v : v - 273.15;
  return v;
}

FieldDimensions::FieldDimensions(const json& doc) : doc_(doc) {
  const json* parts = member(&doc, "parts");
  if (!parts || !parts->is_array()) return;
  for (const json& p : *parts) {
    const json* name = member(&p, "name");
    if (!name || !name->is_string()) continue;
    std::string type = string_at(member(member(&p, "joint"), "type"));
    Dim d = Dim::Unknown;
    if (type == "revolute" || type == "continuous") d = Dim::Angle;
    if (type == "prismatic") d = Dim::Length;
    joints_.emplace(name->get<std::string>(), d);  // the first part of a name, as the checks do
  }
}

Dim FieldDimensions::joint_dim(const std::string& part) const {
  auto it = joints_.find(part);
  return it == joints_.end() ? Dim::Unknown : it->second;
}

Dim FieldDimensions::effect_dim(const json* function, bool difference) const {
  std::string type = string_at(member(member(function, "effect"), "type"));
  if (type == "geometry") return joint_dim(string_at(member(function, "effector")));
  if (type == "illumination") return Dim::Luminous;
  if (type == "temperature") return difference ? Dim::TemperatureDelta : Dim::Temperature;
  if (type == "fluid") return Dim::Flow;
  if (type == "airflow") return Dim::Speed;
  return Dim::Unknown;
}

Dim FieldDimensions::of(const std::vector<std::string>& p) const {
  const json& doc = doc_;
  if (p.size() == 1 && p[0] == "efc") return Dim::None;
  if (p.size() >= 3 && p[0] == "parts") {
    const json* part = element(member(&doc, "parts"), p[1]);
    const std::string& f = p[2];
    if (p.size() == 3) {
      if (f == "mass") return Dim::Mass;
      if (f == "rgba") return Dim::None;
      return Dim::Unknown;
    }
    if (f == "geometry") return geometry_dim(p, 2);
    if (f != "joint") return Dim::Unknown;
    const std::string name = string_at(member(part, "name"));
    if (p.size() == 4) {
      const std::string& g = p[3];
      if (g == "range" || g == "initial") return joint_dim(name);
      if (g == "origin") return Dim::Length;
      if (g == "axis" || g == "damping" || g == "friction") return Dim::None;
      return Dim::Unknown;
    }
    if (p.size() == 5 && p[3] == "spring") {
      if (p[4] == "rest") return joint_dim(name);
      if (p[4] == "stiffness") return Dim::None;
    }
    return Dim::Unknown;
  }
  if (p.size() >= 4 && p[0] == "functions") {
    const json* fn = element(member(&doc, "functions"), p[1]);
    const std::string& block = p[2];
    const std::string& f = p[3];
    if (block == "mapping" && p.size() == 4) {
      if (f == "threshold" || f == "hysteresis")
        return joint_dim(string_at(member(fn, "receptor")));
      if (f == "offset" || f == "initial") return effect_dim(fn, false);
      if (f == "delta") return effect_dim(fn, true);
      if (f == "gain") return Dim::None;
      return Dim::Unknown;
    }
    if (block != "effect") return Dim::Unknown;
    if (p.size() == 4) {
      if (f == "range") return effect_dim(fn, false);
      if (f == "stiffness" || f == "damping" || f == "color") return Dim::None;
      if (f == "position" || f == "droplet_radius" || f == "reach") return Dim::Length;
      if (f == "time_constant") return Dim::Time;
      if (f == "speed") return Dim::Speed;
      if (f == "cone_angle") return Dim::Angle;
      return Dim::Unknown;
    }
    if (p.size() == 5 && (f == "emitter" || f == "outlet")) {
      if (p[4] == "position") return Dim::Length;
      if (p[4] == "direction") return Dim::None;
    }
    return Dim::Unknown;
  }
  return Dim::Unknown;
}

std::string shortest(double v) {
  char buf[64];
  // Beyond 2^53 a plain digit string would read back as an exact integer
  // (the parser keeps integer literals exact): write the exponent instead.
  auto r = std::fabs(v) >= 9007199254740992.0
               ? std::to_chars(buf, buf + sizeof buf, v, std::chars_format::scientific)
               : std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

Spelled spell(const std::vector<double>& si, Dim d) {
  Spelled best;
  for (double v : si) best.numbers.push_back(shortest(v));
  auto width = [](const Spelled& s) {
    size_t n = s.unit.size();
    for (const auto& x : s.numbers) n += x.size();
    return n;
  };
  const auto units = candidates(d);
  if (units.empty()) return best;
  best.unit = units[0]->name;  // SI: exact by construction
  size_t best_width = width(best);
  for (size_t k = 1; k < units.size(); ++k) {
    const Unit& u = *units[k];
    Spelled s;
    s.unit = u.name;
    bool exact = true;
    for (double v : si) {
      double x = from_si(u, v);
      if (!std::isfinite(x)) {
        exact = false;
        break;
      }
      // The fewest significant digits that convert back to exactly v.
      std::string found;
      for (int digits = 1; digits <= 17 && found.empty(); ++digits) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.*g", digits, x);
        double y = std::strtod(buf, nullptr);
        if (to_si(u, y, d) == v) found = shortest(y);
      }
      if (found.empty()) {
        exact = false;
        break;
      }
      s.numbers.push_back(found);
    }
    if (exact && width(s) < best_width) {
      best_width = width(s);
      best = s;
    }
  }
  return best;
}

}  // namespace efc::dsl
