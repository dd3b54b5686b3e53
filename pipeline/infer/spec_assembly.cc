#include "pipeline/infer/spec_assembly.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <map>
#include <set>

namespace efc::pipeline {

using ojson = nlohmann::ordered_json;

std::string spec_name(const std::string& text) {
  std::string out;
  for (char c : text) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
    out += ok ? c : '_';
  }
  if (out.empty() || (out[0] >= '0' && out[0] <= '9')) out = "_" + out;
  if (out.size() > 64) out.resize(64);
  return out;
}

namespace {

// Short decimal text for a double: 9 significant digits, small noise to 0.
double tidy(double v) {
  if (std::fabs(v) < 1e-12) return 0.0;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return std::strtod(buf, nullptr);
}

ojson vec(const Eigen::Vector3d& v) { return ojson::array({tidy(v.x()), tidy(v.y()), tidy(v.z())}); }

std::string spec_role(const std::string& meta_role, bool root) {
  if (root) return "base";
  if (meta_role == "receptor" || meta_role == "receptor+effector") return "receptor";
  if (meta_role == "effector") return "effector";
  return "other";
}

}  // namespace

ojson assemble_spec(const std::string& object_name, const std::string& description,
                    const std::vector<AssembledPart>& parts, const std::vector<InferredFunction>& functions,
                    const StandIns& unseen, const Eigen::Isometry3d& object_to_world, const std::string& meta_file,
                    Diagnostics& diags) {
  ojson spec;
  spec["efc"] = 1;
  spec["name"] = spec_name(object_name);
  spec["description"] = description;
  ojson jparts = ojson::array();
  std::map<std::string, const AssembledPart*> by_name;
  for (const AssembledPart& p : parts) {
    by_name[p.name] = &p;
    ojson jp;
    jp["name"] = p.name;
    jp["role"] = spec_role(p.role, p.root);
    jp["geometry"] = {{"mesh", p.mesh}};
    if (!p.root) {
      const JointEstimate& j = p.joint;
      ojson joint;
      joint["type"] = j.type;
      joint["parent"] = p.parent;
      if (j.type != "fixed") joint["axis"] = vec(j.axis);
      if (j.type == "revolute" || j.type == "continuous") joint["origin"] = vec(j.origin);
      if (j.type == "revolute" || j.type == "prismatic")
        joint["range"] = ojson::array({j.range_lo, j.range_hi});  // exact: thresholds and effect ranges are checked against it
      jp["joint"] = joint;
    }
    jparts.push_back(jp);
  }
  spec["parts"] = ojson::array();  // (here in the key order; filled below, with the stand-ins the functions need)
  const std::string root = parts.empty() ? std::string() : parts.front().name;
  std::set<std::string> stood_in;
  ojson jfunctions = ojson::array();
  for (const InferredFunction& f : functions) {
    auto r = by_name.find(f.receptor);
    auto e = by_name.find(f.effector);
    const bool unseen_effector = e == by_name.end() && !root.empty() &&
                                 std::count(unseen.names.begin(), unseen.names.end(), f.effector) > 0;
    const bool receptor_moves = r != by_name.end() && !r->second->root && r->second->joint.type != "fixed";
    // An effector never seen, of a function otherwise kept, stands in as a
    // sphere (once); one whose effect is its own motion cannot (a fixed
    // stand-in does not move) and is left out below with the others.
    if (unseen_effector && receptor_moves && !f.mapping.is_null() && !f.effect.is_null() &&
        f.effect.value("type", "") != "geometry") {
      if (stood_in.insert(f.effector).second) {
        diags.warning("E1066", meta_file, 0, 0, "/parts/" + f.effector,
                      "function '" + f.name + "': its effector '" + f.effector +
                          "' was never seen; a sphere of " + std::to_string(static_cast<int>(kStandInRadius * 1000)) +
                          " mm in the middle of '" + root + "' stands in for it",
                      "film the effector, or move its stand-in in the spec");
        ojson jp;
        jp["name"] = f.effector;
        jp["role"] = "effector";
        jp["geometry"] = {{"sphere", {{"radius", kStandInRadius}, {"center", vec(unseen.centre)}}}};
        jp["joint"] = {{"type", "fixed"}, {"parent", root}};
        jparts.push_back(jp);
      }
    } else if (r == by_name.end() || e == by_name.end()) {
      diags.warning("E1055", meta_file, 0, 0, "/functions",
                    "function '" + f.name + "' is left out: its " +
                        (r == by_name.end() ? "receptor '" + f.receptor : "effector '" + f.effector) +
                        "' has no reconstruction");
      continue;
    }
    if (r->second->root || r->second->joint.type == "fixed") {
      diags.warning("E1055", meta_file, 0, 0, "/functions",
                    "function '" + f.name + "' is left out: its receptor '" + f.receptor +
                        "' was never seen to move, and a receptor must have a movable joint",
                    "record the receptor being operated, in view");
      continue;
    }
    if (f.mapping.is_null() || f.effect.is_null()) continue;
    ojson jf;
    jf["name"] = spec_name(f.name);
    jf["receptor"] = f.receptor;
    jf["effector"] = f.effector;
    jf["mapping"] = ojson::parse(f.mapping.dump());
    jf["effect"] = ojson::parse(f.effect.dump());
    jfunctions.push_back(jf);
  }
  spec["parts"] = jparts;
  spec["functions"] = jfunctions;
  ojson m = ojson::array();
  const Eigen::Matrix4d M = object_to_world.matrix();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m.push_back(tidy(M(r, c)));
  spec["x-efc-object-to-world"] = m;
  return spec;
}

}  // namespace efc::pipeline
