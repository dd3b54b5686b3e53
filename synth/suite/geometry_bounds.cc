#include "synth/suite/geometry_bounds.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>

namespace efc::synth::suite {
namespace {

double number_or(const SpecJson& j, const char* key, double fallback) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
}

V3 vec_or(const SpecJson& j, const char* key, const V3& fallback) {
  V3 v = fallback;
  if (j.contains(key)) read_vec(j[key], &v);
  return v;
}

void add_box(const SpecJson& box, Bounds* out) {
  V3 size{0, 0, 0};
  read_vec(box.value("size", SpecJson()), &size);
  const V3 c = vec_or(box, "center", {0, 0, 0});
  const V3 rpy = vec_or(box, "rpy", {0, 0, 0});
  V3 half = scale(size, 0.5);
  if (rpy != V3{0, 0, 0}) {  // any orientation: the circumscribed sphere
    const double r = std::sqrt(half[0] * half[0] + half[1] * half[1] + half[2] * half[2]);
    half = {r, r, r};
  }
  out->add_point(add(c, scale(half, -1)));
  out->add_point(add(c, half));
}

void add_cylinder(const SpecJson& cyl, Bounds* out) {
  const double r = number_or(cyl, "radius", 0), l = number_or(cyl, "length", 0);
  const V3 c = vec_or(cyl, "center", {0, 0, 0});
  V3 a = vec_or(cyl, "axis", {0, 0, 1});
  if (a == V3{0, 0, 0}) a = {0, 0, 1};
  a = unit(a);
  V3 half;
  for (int k = 0; k < 3; ++k)
    half[k] = std::fabs(a[k]) * l / 2 + r * std::sqrt(std::max(0.0, 1 - a[k] * a[k]));
  out->add_point(add(c, scale(half, -1)));
  out->add_point(add(c, half));
}

bool add_obj_mesh(const std::string& path, const V3& s, Bounds* out, std::string* error) {
  std::ifstream in(path);
  if (!in) {
    *error = "cannot read mesh " + path;
    return false;
  }
  std::string line;
  while (std::getline(in, line)) {
    if (line.size() < 2 || line[0] != 'v' || (line[1] != ' ' && line[1] != '\t')) continue;
    const char* p = line.c_str() + 1;
    V3 v;
    for (int k = 0; k < 3; ++k) {
      char* end = nullptr;
      v[k] = std::strtod(p, &end) * s[k];
      if (end == p) {
        *error = "bad vertex line in " + path + ": " + line;
        return false;
      }
      p = end;
    }
    out->add_point(v);
  }
  return true;
}

bool add_mesh(const SpecJson& g, const std::string& base_dir, Bounds* out, std::string* error) {
  if (!g["mesh"].is_string()) {
    *error = "mesh path is not a string";
    return false;
  }
  const std::string rel = g["mesh"].get<std::string>();
  const std::string ext = rel.size() >= 4 ? rel.substr(rel.size() - 4) : rel;
  if (ext != ".obj" && ext != ".OBJ") {
    *error = "only OBJ meshes can be measured: " + rel;
    return false;
  }
  return add_obj_mesh(base_dir + "/" + rel, vec_or(g, "scale", {1, 1, 1}), out, error);
}

}  // namespace

void Bounds::add_point(const V3& p) {
  for (int k = 0; k < 3; ++k) {
    lo[k] = std::min(lo[k], p[k]);
    hi[k] = std::max(hi[k], p[k]);
  }
}

double Bounds::max_extent() const {
  if (empty()) return 0;
  return std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
}

bool add_geometry_bounds(const SpecJson& g, const std::string& base_dir, Bounds* out,
                         std::string* error) {
  if (!g.is_object()) {
    *error = "geometry is not an object";
    return false;
  }
  if (g.contains("mesh")) return add_mesh(g, base_dir, out, error);
  if (g.contains("box") && g["box"].is_object()) {
    add_box(g["box"], out);
  } else if (g.contains("cylinder") && g["cylinder"].is_object()) {
    add_cylinder(g["cylinder"], out);
  } else if (g.contains("sphere") && g["sphere"].is_object()) {
    const double r = number_or(g["sphere"], "radius", 0);
    const V3 c = vec_or(g["sphere"], "center", {0, 0, 0});
    out->add_point(add(c, {-r, -r, -r}));
    out->add_point(add(c, {r, r, r}));
  } else if (g.contains("compound") && g["compound"].is_array()) {
    for (const auto& child : g["compound"])
      if (!add_geometry_bounds(child, base_dir, out, error)) return false;
  } else {
    *error = "geometry has no box, cylinder, sphere, mesh or compound";
    return false;
  }
  return true;
}

}  // namespace efc::synth::suite
