#include "pipeline/egofun3d/truth_spec.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <limits>

namespace efc::egofun3d {
namespace {

using nlohmann::json;

struct Bounds {
  std::array<double, 3> lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                           std::numeric_limits<double>::infinity()};
  std::array<double, 3> hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity()};
  bool empty() const { return lo[0] > hi[0]; }
  void add(const std::array<double, 3>& p) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  double min_extent() const { return std::min({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}); }
};

// A box fitted to the points (at least 1 mm a side, so a flat patch still
// has a volume for the mass and inertia).
json box_geometry(const Bounds& b) {
  json size = json::array(), center = json::array();
  for (int k = 0; k < 3; ++k) {
    size.push_back(std::max(b.hi[k] - b.lo[k], 1e-3));
    center.push_back((b.hi[k] + b.lo[k]) / 2);
  }
  return {{"box", {{"size", size}, {"center", center}}}};
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

// The part's geometry: a mesh of its faces, or a box. `member` marks the
// part's vertices.
json part_geometry(const std::string& name, const std::vector<char>& member, const Ply& ply, TruthSpec* out) {
  Bounds bounds;
  for (size_t v = 0; v < member.size(); ++v)
    if (member[v]) bounds.add(ply.vertices[v]);
  if (bounds.empty()) {
    // No vertex at all (the base, when every vertex is annotated): a 1 cm
    // cube at the middle of the whole geometry stands in for it.
    Bounds all;
    for (const auto& p : ply.vertices) all.add(p);
    std::array<double, 3> c{0, 0, 0};
    if (!all.empty())
      for (int k = 0; k < 3; ++k) c[k] = (all.lo[k] + all.hi[k]) / 2;
    out->notes.push_back("part '" + name + "' has no vertices; a 1 cm box at the geometry's centre stands in for it");
    Bounds b;
    b.add({c[0] - 0.005, c[1] - 0.005, c[2] - 0.005});
    b.add({c[0] + 0.005, c[1] + 0.005, c[2] + 0.005});
    return box_geometry(b);
  }
  std::vector<std::array<int, 3>> triangles;
  for (const auto& poly : ply.faces) {
    if (!std::all_of(poly.begin(), poly.end(), [&](int v) { return member[v] != 0; })) continue;
    for (size_t k = 1; k + 1 < poly.size(); ++k) triangles.push_back({poly[0], poly[k], poly[k + 1]});
  }
  if (triangles.empty() || bounds.min_extent() < 1e-6) {
    out->notes.push_back("part '" + name + "': " +
                         std::string(ply.faces.empty() ? "the PLY is a point cloud (no faces)"
                                     : triangles.empty() ? "no face has all its corners in the part"
                                                         : "its faces are flat") +
                         ", so the part is a box around its points");
    return box_geometry(bounds);
  }
  // Only the vertices the faces use, renumbered from 1 (OBJ).
  std::vector<int> remap(ply.vertices.size(), 0);
  std::string obj = "# " + name + ": from the EgoFun3D geometry, world frame (metres)\n";
  int next = 0;
  for (auto& t : triangles)
    for (int& v : t) {
      if (!remap[v]) {
        remap[v] = ++next;
        const auto& p = ply.vertices[v];
        obj += "v " + num(p[0]) + " " + num(p[1]) + " " + num(p[2]) + "\n";
      }
      v = remap[v];
    }
  for (const auto& t : triangles)
    obj += "f " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + "\n";
  const std::string rel = "meshes/" + name + ".obj";
  out->meshes.push_back({rel, obj});
  return {{"mesh", rel}};
}

json joint_json(const JointAnnotation& j, const std::string& parent, const std::string& part, TruthSpec* out) {
  if (!j.found) {
    out->notes.push_back("part '" + part + "' has no articulation entry; its joint is fixed");
    return {{"type", "fixed"}, {"parent", parent}};
  }
  if (j.degrees)
    out->notes.push_back("part '" + part + "': the revolute range exceeds a full turn, so it was read as degrees");
  json out_j = {{"type", j.type}, {"parent", parent}};
  if (j.type == "fixed") return out_j;
  out_j["axis"] = j.axis;
  if (j.type != "prismatic") out_j["origin"] = j.origin;
  if (j.type != "continuous") out_j["range"] = {j.lo, j.hi};
  return out_j;
}

// The effect's range the spec defaults to (efc-spec-v1.md), for the
// cumulative delta.
std::pair<double, double> default_effect_range(const std::string& physics, const JointAnnotation& effector) {
  if (physics == "illumination") return {0, 800};
  if (physics == "temperature") return {20, 200};
  if (physics == "fluid") return {0, 6};
  if (physics == "airflow") return {0, 10};
  if (effector.found && effector.type != "fixed" && effector.type != "continuous") return {effector.lo, effector.hi};
  return {0, 1};
}

}  // namespace

TruthSpec build_truth_spec(const TruthInput& in) {
  TruthSpec out;
  const Ply& ply = *in.ply;
  const FunctionInstance& fi = *in.instance;
  const size_t n = ply.vertices.size();
  std::vector<char> receptor(n, 0), effector(n, 0), base(n, 1);
  for (long long v : fi.receptor.indices) receptor[v] = 1, base[v] = 0;
  for (long long v : fi.effector.indices) effector[v] = 1, base[v] = 0;
  for (long long v : fi.removed) base[v] = 0;
  // A vertex annotated as both: the receptor keeps it (it is what the hand
  // touches); the effector is what remains.
  for (size_t v = 0; v < n; ++v)
    if (receptor[v]) effector[v] = 0;

  json parts = json::array();
  parts.push_back({{"name", in.base_name}, {"role", "base"}, {"geometry", part_geometry(in.base_name, base, ply, &out)}});
  parts.push_back({{"name", in.receptor_name},
                   {"role", "receptor"},
                   {"geometry", part_geometry(in.receptor_name, receptor, ply, &out)},
                   {"joint", joint_json(in.receptor_joint, in.base_name, in.receptor_name, &out)}});
  parts.push_back({{"name", in.effector_name},
                   {"role", "effector"},
                   {"geometry", part_geometry(in.effector_name, effector, ply, &out)},
                   {"joint", joint_json(in.effector_joint, in.base_name, in.effector_name, &out)}});

  json mapping = {{"type", in.function.func}};
  if (in.function.func == "cumulative") {
    const auto [lo, hi] = default_effect_range(in.function.physics, in.effector_joint);
    mapping["delta"] = (hi - lo) / 4;
    out.notes.push_back("function '" + in.function_name +
                        "': cumulative needs a step per press, which the annotation does not give; "
                        "delta is a quarter of the effect's range");
  }
  json function = {{"name", in.function_name},
                   {"receptor", in.receptor_name},
                   {"effector", in.effector_name},
                   {"mapping", mapping},
                   {"effect", {{"type", in.function.physics}}}};

  out.spec = {{"efc", 1},
              {"name", in.object_name},
              {"description", "imported from EgoFun3D; world frame of the camera extrinsics"},
              {"parts", parts},
              {"functions", json::array({function})},
              {"x-egofun3d", in.provenance}};
  return out;
}

}  // namespace efc::egofun3d
