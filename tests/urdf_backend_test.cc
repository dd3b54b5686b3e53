// The URDF target: for every example, the URDF passes check_urdf, parses with
// urdfdom with one link per part plus one per effect point, one movable joint
// per movable part with the spec's type, axis, limits and dynamics, the
// compiler's inertials, primitives as primitives and meshes as relative STL
// files in the link frame; its forward kinematics (urdfdom + Eigen) moves every
// part exactly as the MuJoCo model does at many joint configurations; the
// sidecar names links and joints that exist. Plus: springs and initial
// positions warn (W0900), generated names never collide, comments are safe,
// and `efc compile --target urdf` works end to end.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <unistd.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "backends/common/lowering.h"
#include "backends/mujoco/mujoco_backend.h"
#include "backends/urdf/urdf_backend.h"
#include "compiler/core/load.h"
#include "compiler/geometry/geometry.h"
#include "compiler/ir.h"
#include "harness/mujoco_errors.h"

namespace {

namespace fs = std::filesystem;
using efc::Vec3;
using nlohmann::json;

// ------------------------------------------------------------------ helpers

std::string temp_dir(const std::string& tag) {
  const fs::path p = fs::temp_directory_path() / ("efc_urdf_" + tag + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p.string();
}

std::vector<std::string> example_names() {
  std::vector<std::string> names;
  const fs::path dir = fs::path(EFC_SOURCE_DIR) / "examples";
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

efc::Object load(const std::string& path, efc::Diagnostics* diags_out = nullptr) {
  efc::Diagnostics diags;
  auto obj = efc::load_spec(path, efc::LoadOptions{}, diags);
  std::ostringstream os;
  diags.print(os, false);
  if (!obj) ADD_FAILURE() << "cannot load " << path << ":\n" << os.str();
  if (diags_out) *diags_out = diags;
  return obj ? *obj : efc::Object{};
}

// Emits the URDF target into <dir>/urdf through the registry, as `efc compile` does.
std::string emit(const efc::Object& obj, const std::string& dir, efc::Diagnostics* diags_out = nullptr) {
  const efc::Backend* b = efc::find_backend("urdf");
  EXPECT_NE(b, nullptr);
  if (!b) return "";
  efc::Diagnostics diags;
  const std::string out = dir + "/urdf";
  fs::create_directories(out);
  EXPECT_TRUE(b->emit(obj, out, diags));
  EXPECT_FALSE(diags.has_errors());
  if (diags_out) *diags_out = diags;
  return out + "/" + obj.name + ".urdf";
}

std::string read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

int check_urdf(const std::string& path, std::string* log) {
  const std::string out = path + ".check.log";
  const std::string cmd = "check_urdf '" + path + "' > '" + out + "' 2>&1";
  const int rc = std::system(cmd.c_str());
  *log = read_file(out);
  return rc;
}

Eigen::Vector3d ev(const Vec3& v) { return {v[0], v[1], v[2]}; }
Eigen::Vector3d ev(const urdf::Vector3& v) { return {v.x, v.y, v.z}; }

Eigen::Isometry3d pose(const urdf::Pose& p) {
  double x, y, z, w;
  p.rotation.getQuaternion(x, y, z, w);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
  T.translation() = ev(p.position);
  return T;
}

Eigen::Matrix3d em(const efc::Mat3& m) {
  Eigen::Matrix3d r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = m[i][j];
  return r;
}

// Forward kinematics of a urdfdom model: every link's world transform for
// joint positions q (by joint name; missing = 0).
std::map<std::string, Eigen::Isometry3d> urdf_fk(const urdf::ModelInterface& model,
                                                 const std::map<std::string, double>& q) {
  std::map<std::string, Eigen::Isometry3d> out;
  std::vector<std::pair<urdf::LinkConstSharedPtr, Eigen::Isometry3d>> stack;
  stack.push_back({model.getRoot(), Eigen::Isometry3d::Identity()});
  while (!stack.empty()) {
    auto [link, T] = stack.back();
    stack.pop_back();
    out[link->name] = T;
    for (const auto& child : link->child_links) {
      const urdf::Joint& j = *child->parent_joint;
      Eigen::Isometry3d C = T * pose(j.parent_to_joint_origin_transform);
      const auto it = q.find(j.name);
      const double v = it == q.end() ? 0.0 : it->second;
      const Eigen::Vector3d axis = ev(j.axis);
      if (j.type == urdf::Joint::REVOLUTE || j.type == urdf::Joint::CONTINUOUS)
        C = C * Eigen::AngleAxisd(v, axis);
      else if (j.type == urdf::Joint::PRISMATIC)
        C = C * Eigen::Translation3d(v * axis);
      stack.push_back({child, C});
    }
  }
  return out;
}

// Leaf geometries of a part, in the order the backend writes them.
void leaves(const efc::Geometry& g, std::vector<const efc::Geometry*>* out) {
  if (g.kind == efc::GeomKind::Compound) {
    for (const auto& c : g.children) leaves(c, out);
  } else {
    out->push_back(&g);
  }
}

int expected_sites(const efc::Object& obj) {
  int n = 0;
  for (const auto& f : obj.functions) n += f.effect.type != efc::EffectType::Geometry;
  return n;
}

struct StlTriangle {
  float v[3][3];
};
std::vector<StlTriangle> read_stl(const std::string& path) {
  std::vector<StlTriangle> tris;
  std::ifstream f(path, std::ios::binary);
  if (!f) return tris;
  char header[80];
  f.read(header, 80);
  uint32_t n = 0;
  f.read(reinterpret_cast<char*>(&n), 4);
  for (uint32_t i = 0; i < n && f; ++i) {
    float normal[3];
    StlTriangle t;
    char attr[2];
    f.read(reinterpret_cast<char*>(normal), 12);
    f.read(reinterpret_cast<char*>(t.v), 36);
    f.read(attr, 2);
    if (f) tris.push_back(t);
  }
  return tris;
}

// ------------------------------------------------------------------ per example

class UrdfExample : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    spec_ = std::string(EFC_SOURCE_DIR) + "/examples/" + GetParam() + ".json";
    obj_ = load(spec_);
    ASSERT_FALSE(obj_.parts.empty());
    dir_ = temp_dir(GetParam());
    path_ = emit(obj_, dir_);
    model_ = urdf::parseURDFFile(path_);
    ASSERT_TRUE(model_) << "urdfdom cannot parse " << path_;
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string spec_, dir_, path_;
  efc::Object obj_;
  urdf::ModelInterfaceSharedPtr model_;
};

TEST_P(UrdfExample, PassesCheckUrdf) {
  std::string log;
  EXPECT_EQ(check_urdf(path_, &log), 0) << log;
  EXPECT_NE(log.find("Successfully Parsed XML"), std::string::npos) << log;
}

TEST_P(UrdfExample, LinksJointsLimitsAxes) {
  std::vector<urdf::LinkSharedPtr> links;
  model_->getLinks(links);
  EXPECT_EQ(links.size(), obj_.parts.size() + expected_sites(obj_));
  EXPECT_EQ(model_->getRoot()->name, obj_.parts[obj_.root_index()].name);
  int movable = 0;
  for (const auto& [name, j] : model_->joints_)
    movable += j->type != urdf::Joint::FIXED && j->type != urdf::Joint::UNKNOWN;
  int expected_movable = 0;
  for (const efc::Part& p : obj_.parts) {
    ASSERT_TRUE(model_->getLink(p.name)) << p.name;
    if (!p.joint) continue;
    const auto j = model_->getJoint(p.name);
    ASSERT_TRUE(j) << "joint " << p.name;
    EXPECT_EQ(j->child_link_name, p.name);
    EXPECT_EQ(j->parent_link_name, p.joint->parent);
    const efc::Joint& J = *p.joint;
    switch (J.type) {
      case efc::JointType::Fixed: EXPECT_EQ(j->type, urdf::Joint::FIXED) << p.name; break;
      case efc::JointType::Revolute: EXPECT_EQ(j->type, urdf::Joint::REVOLUTE) << p.name; break;
      case efc::JointType::Continuous: EXPECT_EQ(j->type, urdf::Joint::CONTINUOUS) << p.name; break;
      case efc::JointType::Prismatic: EXPECT_EQ(j->type, urdf::Joint::PRISMATIC) << p.name; break;
    }
    if (!J.movable()) continue;
    ++expected_movable;
    // Link frames are axis-aligned with the object frame: the axis is the spec's.
    EXPECT_EQ(j->axis.x, J.axis[0]) << p.name;
    EXPECT_EQ(j->axis.y, J.axis[1]) << p.name;
    EXPECT_EQ(j->axis.z, J.axis[2]) << p.name;
    if (J.type == efc::JointType::Continuous) {
      EXPECT_FALSE(j->limits) << p.name;
    } else {
      ASSERT_TRUE(j->limits) << p.name;
      EXPECT_EQ(j->limits->lower, J.lo) << p.name;  // round-trip exact
      EXPECT_EQ(j->limits->upper, J.hi) << p.name;
      EXPECT_GT(j->limits->effort, 0);
      EXPECT_GT(j->limits->velocity, 0);
    }
    ASSERT_TRUE(j->dynamics) << p.name;
    EXPECT_EQ(j->dynamics->damping, J.damping);
    EXPECT_EQ(j->dynamics->friction, J.friction);
  }
  EXPECT_EQ(movable, expected_movable);
}

TEST_P(UrdfExample, InertialsAreTheCompilers) {
  const auto fk = urdf_fk(*model_, {});
  for (const efc::Part& p : obj_.parts) {
    const auto link = model_->getLink(p.name);
    ASSERT_TRUE(link && link->inertial) << p.name;
    const urdf::Inertial& in = *link->inertial;
    const efc::MassProperties& mp = p.mass_props;
    EXPECT_EQ(in.mass, mp.mass) << p.name;
    EXPECT_GT(in.mass, 1e-4) << p.name;  // a real mass, not a placeholder
    const Eigen::Vector3d com = fk.at(p.name) * ev(in.origin.position);
    EXPECT_LT((com - ev(mp.com)).norm(), 1e-12) << p.name;
    EXPECT_EQ(in.ixx, mp.inertia[0][0]);
    EXPECT_EQ(in.ixy, mp.inertia[0][1]);
    EXPECT_EQ(in.ixz, mp.inertia[0][2]);
    EXPECT_EQ(in.iyy, mp.inertia[1][1]);
    EXPECT_EQ(in.iyz, mp.inertia[1][2]);
    EXPECT_EQ(in.izz, mp.inertia[2][2]);
  }
}

TEST_P(UrdfExample, GeometryPrimitivesAndRelativeMeshes) {
  // Copy the output elsewhere and read it from another working directory:
  // every mesh must resolve relative to the URDF file.
  const std::string moved = dir_ + "/moved";
  fs::copy(dir_ + "/urdf", moved, fs::copy_options::recursive);
  struct Cwd {  // restored even when an ASSERT returns early
    fs::path old = fs::current_path();
    ~Cwd() { fs::current_path(old); }
  } cwd;
  fs::current_path(fs::temp_directory_path());
  const auto model = urdf::parseURDFFile(moved + "/" + obj_.name + ".urdf");
  ASSERT_TRUE(model);
  const auto fk = urdf_fk(*model, {});
  for (const efc::Part& p : obj_.parts) {
    const auto link = model->getLink(p.name);
    std::vector<const efc::Geometry*> g;
    leaves(p.geometry, &g);
    ASSERT_EQ(link->visual_array.size(), g.size()) << p.name;
    ASSERT_EQ(link->collision_array.size(), g.size()) << p.name;
    const Eigen::Isometry3d L = fk.at(p.name);
    for (size_t i = 0; i < g.size(); ++i) {
      const auto& vis = *link->visual_array[i];
      const auto& col = *link->collision_array[i];
      const Eigen::Isometry3d T = L * pose(vis.origin);
      EXPECT_LT((T.matrix() - (L * pose(col.origin)).matrix()).norm(), 1e-15);
      ASSERT_TRUE(vis.material) << p.name;
      if (p.rgba) {
        EXPECT_FLOAT_EQ(vis.material->color.r, static_cast<float>((*p.rgba)[0]));  // urdfdom keeps floats
        EXPECT_FLOAT_EQ(vis.material->color.a, static_cast<float>((*p.rgba)[3]));
      }
      const efc::Geometry& G = *g[i];
      switch (G.kind) {
        case efc::GeomKind::Box: {
          auto b = std::dynamic_pointer_cast<urdf::Box>(vis.geometry);
          ASSERT_TRUE(b) << p.name;
          EXPECT_EQ(b->dim.x, G.size[0]);
          EXPECT_EQ(b->dim.y, G.size[1]);
          EXPECT_EQ(b->dim.z, G.size[2]);
          EXPECT_LT((T.translation() - ev(G.center)).norm(), 1e-12);
          EXPECT_LT((T.linear() - em(efc::rpy_to_matrix(G.rpy))).norm(), 1e-9);
          break;
        }
        case efc::GeomKind::Cylinder: {
          auto c = std::dynamic_pointer_cast<urdf::Cylinder>(vis.geometry);
          ASSERT_TRUE(c) << p.name;
          EXPECT_EQ(c->radius, G.radius);
          EXPECT_EQ(c->length, G.length);
          EXPECT_LT((T.translation() - ev(G.center)).norm(), 1e-12);
          EXPECT_LT((T.linear().col(2) - ev(G.axis).normalized()).norm(), 1e-9) << p.name;
          break;
        }
        case efc::GeomKind::Sphere: {
          auto s = std::dynamic_pointer_cast<urdf::Sphere>(vis.geometry);
          ASSERT_TRUE(s) << p.name;
          EXPECT_EQ(s->radius, G.radius);
          EXPECT_LT((T.translation() - ev(G.center)).norm(), 1e-12);
          break;
        }
        case efc::GeomKind::Mesh: {
          auto m = std::dynamic_pointer_cast<urdf::Mesh>(vis.geometry);
          ASSERT_TRUE(m) << p.name;
          ASSERT_FALSE(m->filename.empty());
          EXPECT_NE(m->filename[0], '/') << m->filename;
          EXPECT_EQ(m->filename.find(".."), std::string::npos) << m->filename;
          EXPECT_EQ(m->filename.find("://"), std::string::npos) << m->filename;
          const std::string file = moved + "/" + m->filename;
          ASSERT_TRUE(fs::exists(file)) << file;
          ASSERT_TRUE(G.mesh);
          const auto tris = read_stl(file);
          ASSERT_EQ(tris.size(), G.mesh->triangles.size()) << file;
          // Vertices in the link frame: back through the link's pose at q = 0
          // they are the spec's (object-frame) vertices, to float precision.
          for (size_t t = 0; t < tris.size(); t += std::max<size_t>(1, tris.size() / 50))
            for (int c = 0; c < 3; ++c) {
              const Eigen::Vector3d v(tris[t].v[c][0], tris[t].v[c][1], tris[t].v[c][2]);
              const Vec3& want = G.mesh->vertices[G.mesh->triangles[t][c]];
              EXPECT_LT((T * v - ev(want)).norm(), 1e-5) << file;
            }
          break;
        }
        case efc::GeomKind::Compound:
          break;
      }
    }
  }
}

TEST_P(UrdfExample, SidecarNamesWhatTheUrdfHas) {
  const std::string side = dir_ + "/urdf/" + obj_.name + ".functions.json";
  ASSERT_TRUE(fs::exists(side));
  const json j = json::parse(read_file(side));
  EXPECT_EQ(j["object"], obj_.name);
  EXPECT_EQ(j["urdf"], obj_.name + ".urdf");
  EXPECT_NE(read_file(path_).find(obj_.name + ".functions.json"), std::string::npos)
      << "the URDF's comment names the sidecar";
  ASSERT_EQ(j["functions"].size(), obj_.functions.size());
  const auto fk = urdf_fk(*model_, {});
  for (size_t i = 0; i < obj_.functions.size(); ++i) {
    const efc::Function& f = obj_.functions[i];
    const json& F = j["functions"][i];
    EXPECT_EQ(F["name"], f.name);
    EXPECT_EQ(F["receptor"]["part"], f.receptor);
    const std::string rl = F["receptor"]["link"], rj = F["receptor"]["joint"];
    EXPECT_TRUE(model_->getLink(rl)) << rl;
    ASSERT_TRUE(model_->getJoint(rj)) << rj;
    EXPECT_NE(model_->getJoint(rj)->type, urdf::Joint::FIXED);
    EXPECT_EQ(model_->getJoint(rj)->child_link_name, rl);
    const std::string el = F["effector"]["link"];
    EXPECT_TRUE(model_->getLink(el)) << el;
    if (F["effector"]["joint"].is_null()) {
      EXPECT_EQ(el, model_->getRoot()->name);
    } else {
      const auto ej = model_->getJoint(F["effector"]["joint"].get<std::string>());
      ASSERT_TRUE(ej);
      EXPECT_EQ(ej->child_link_name, el);
    }
    ASSERT_EQ(F["receptor_range"].size(), 2u);
    // The resolved mapping: every parameter the runtime needs is present.
    const json& M = F["mapping"];
    EXPECT_EQ(M["type"], efc::to_string(f.mapping.type));
    switch (f.mapping.type) {
      case efc::MappingType::Binary: EXPECT_TRUE(M.contains("threshold") && M.contains("latching")); break;
      case efc::MappingType::Step: EXPECT_TRUE(M.contains("threshold") && M.contains("hysteresis")); break;
      case efc::MappingType::Linear: EXPECT_TRUE(M.contains("gain") && M.contains("offset")); break;
      case efc::MappingType::Cumulative:
        EXPECT_TRUE(M.contains("threshold") && M.contains("delta") && M.contains("initial"));
        break;
    }
    const json& E = F["effect"];
    EXPECT_EQ(E["type"], efc::to_string(f.effect.type));
    EXPECT_EQ(E["range"][0].get<double>(), f.effect.lo);
    EXPECT_EQ(E["range"][1].get<double>(), f.effect.hi);
    if (f.effect.type == efc::EffectType::Geometry) {
      EXPECT_TRUE(E["site"].is_null());
      continue;
    }
    const std::string sl = E["site"]["link"];
    const auto site = model_->getLink(sl);
    ASSERT_TRUE(site) << sl;
    ASSERT_TRUE(site->parent_joint);
    EXPECT_EQ(site->parent_joint->type, urdf::Joint::FIXED);
    EXPECT_EQ(site->parent_joint->name, E["site"]["joint"]);
    EXPECT_EQ(site->parent_joint->parent_link_name, el);
    ASSERT_TRUE(f.effect.position);
    EXPECT_LT((fk.at(sl).translation() - ev(*f.effect.position)).norm(), 1e-12) << sl;
    if (f.effect.type == efc::EffectType::Fluid || f.effect.type == efc::EffectType::Airflow) {
      ASSERT_TRUE(f.effect.direction);
      EXPECT_LT((fk.at(sl).linear().col(2) - ev(*f.effect.direction).normalized()).norm(), 1e-9) << sl;
    }
  }
  // Joint state URDF cannot hold.
  for (const efc::Part& p : obj_.parts) {
    if (!p.joint || !p.joint->movable()) continue;
    ASSERT_TRUE(j["joints"].contains(p.name)) << p.name;
    const json& J = j["joints"][p.name];
    EXPECT_EQ(J["initial"].get<double>(), p.joint->initial.value_or(0.0));
    if (p.joint->spring) {
      EXPECT_EQ(J["spring"]["stiffness"].get<double>(), p.joint->spring->stiffness);
    } else {
      EXPECT_TRUE(J["spring"].is_null());
    }
  }
}

// MuJoCo's own URDF importer loads every example (Genesis and Isaac Lab load
// the same file): meshes found, every movable joint there by name with its
// type and limits, carrying the mass of its part and everything on it.
TEST_P(UrdfExample, LoadsInMujocosUrdfImporter) {
  efc::install_mujoco_handlers();
  char err[1000] = "";
  std::unique_ptr<mjModel, void (*)(mjModel*)> m(mj_loadXML(path_.c_str(), nullptr, err, sizeof err),
                                                 mj_deleteModel);
  ASSERT_TRUE(m) << err;
  const efc::lowering::Layout layout = efc::lowering::make_layout(obj_);
  std::function<double(int)> carried = [&](int part) {
    double mass = obj_.parts[part].mass_props.mass;
    for (int c : layout.children[part]) mass += carried(c);
    return mass;
  };
  for (size_t i = 0; i < obj_.parts.size(); ++i) {
    const efc::Part& p = obj_.parts[i];
    if (!p.joint || !p.joint->movable()) continue;
    const int j = mj_name2id(m.get(), mjOBJ_JOINT, p.name.c_str());
    ASSERT_GE(j, 0) << p.name;
    EXPECT_EQ(m->jnt_type[j], p.joint->type == efc::JointType::Prismatic ? mjJNT_SLIDE : mjJNT_HINGE);
    if (p.joint->type != efc::JointType::Continuous) {
      EXPECT_TRUE(m->jnt_limited[j]) << p.name;
      EXPECT_DOUBLE_EQ(m->jnt_range[2 * j], p.joint->lo);
      EXPECT_DOUBLE_EQ(m->jnt_range[2 * j + 1], p.joint->hi);
    }
    // Site links weigh 1e-6 kg each.
    EXPECT_NEAR(m->body_subtreemass[m->jnt_bodyid[j]], carried(static_cast<int>(i)), 1e-4) << p.name;
  }
  EXPECT_GT(m->ngeom, 0);
}

// Forward kinematics: every part's frame (three points fixed to it) lands where
// the MuJoCo model puts the same body, at many joint configurations.
void expect_fk_matches_mujoco(const efc::Object& obj_, const urdf::ModelInterfaceSharedPtr& model_,
                              const std::string& dir_) {
  efc::install_mujoco_handlers();
  efc::Diagnostics diags;
  std::string xml;
  fs::create_directories(dir_ + "/mujoco");
  ASSERT_TRUE(efc::write_mujoco_model(obj_, dir_ + "/mujoco", efc::MjcfOptions{}, diags, &xml));
  char err[1000] = "";
  std::unique_ptr<mjModel, void (*)(mjModel*)> m(mj_loadXML(xml.c_str(), nullptr, err, sizeof err),
                                                 mj_deleteModel);
  ASSERT_TRUE(m) << err;
  std::unique_ptr<mjData, void (*)(mjData*)> d(mj_makeData(m.get()), mj_deleteData);

  // Configurations: all zero; each movable joint at lo, hi, mid (others 0);
  // all at lo, all at hi, all at mid; and a few pseudo-random mixes.
  struct Range {
    std::string name;
    double lo, hi;
  };
  std::vector<Range> ranges;
  for (const efc::Part& p : obj_.parts)
    if (p.joint && p.joint->movable()) {
      if (p.joint->type == efc::JointType::Continuous)
        ranges.push_back({p.name, -2.5, 2.5});
      else
        ranges.push_back({p.name, p.joint->lo, p.joint->hi});
    }
  std::vector<std::map<std::string, double>> configs(1);
  for (const Range& r : ranges)
    for (double t : {0.0, 1.0, 0.5}) configs.push_back({{r.name, r.lo + t * (r.hi - r.lo)}});
  for (double t : {0.0, 1.0, 0.5, 0.25}) {
    std::map<std::string, double> c;
    for (const Range& r : ranges) c[r.name] = r.lo + t * (r.hi - r.lo);
    configs.push_back(c);
  }
  unsigned seed = 12345;
  for (int k = 0; k < 5; ++k) {
    std::map<std::string, double> c;
    for (const Range& r : ranges) {
      seed = seed * 1103515245u + 12345u;
      c[r.name] = r.lo + (seed % 10000) / 9999.0 * (r.hi - r.lo);
    }
    configs.push_back(c);
  }

  auto mj_pose = [&](const std::map<std::string, double>& q) {
    mju_copy(d->qpos, m->qpos0, m->nq);
    for (const auto& [name, v] : q) {
      const int jid = mj_name2id(m.get(), mjOBJ_JOINT, name.c_str());
      EXPECT_GE(jid, 0) << name;
      if (jid >= 0) d->qpos[m->jnt_qposadr[jid]] = v;
    }
    mj_kinematics(m.get(), d.get());
    std::map<std::string, Eigen::Isometry3d> out;
    for (const efc::Part& p : obj_.parts) {
      const int b = mj_name2id(m.get(), mjOBJ_BODY, p.name.c_str());
      EXPECT_GE(b, 0) << p.name;
      if (b < 0) continue;
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      for (int r = 0; r < 3; ++r) {
        T.translation()[r] = d->xpos[3 * b + r];
        for (int c = 0; c < 3; ++c) T.linear()(r, c) = d->xmat[9 * b + 3 * r + c];
      }
      out[p.name] = T;
    }
    return out;
  };

  const auto mj0 = mj_pose({});
  const auto ur0 = urdf_fk(*model_, {});
  for (const auto& q : configs) {
    const auto mj = mj_pose(q);
    const auto ur = urdf_fk(*model_, q);
    for (const efc::Part& p : obj_.parts) {
      const Eigen::Vector3d com = ev(p.mass_props.com);
      for (const Eigen::Vector3d& pt :
           {com, Eigen::Vector3d(com + Eigen::Vector3d(0.1, 0, 0)),
            Eigen::Vector3d(com + Eigen::Vector3d(0, 0.1, 0)), Eigen::Vector3d(com + Eigen::Vector3d(0, 0, 0.1))}) {
        // The point is fixed to the part: carry it from the zero configuration.
        const Eigen::Vector3d in_mj = mj.at(p.name) * (mj0.at(p.name).inverse() * pt);
        const Eigen::Vector3d in_ur = ur.at(p.name) * (ur0.at(p.name).inverse() * pt);
        std::string cfg;
        for (const auto& [n, v] : q) cfg += n + "=" + std::to_string(v) + " ";
        EXPECT_LT((in_mj - in_ur).norm(), 1e-9) << p.name << " at " << cfg << "\n mujoco "
                                                << in_mj.transpose() << "\n urdf " << in_ur.transpose();
      }
    }
  }
}

TEST_P(UrdfExample, ForwardKinematicsMatchesMujoco) { expect_fk_matches_mujoco(obj_, model_, dir_); }

INSTANTIATE_TEST_SUITE_P(Examples, UrdfExample, ::testing::ValuesIn(example_names()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

// ------------------------------------------------------------------ warnings, names, text

bool has_warning(const efc::Diagnostics& diags, const std::string& word) {
  for (const auto& d : diags.items())
    if (d.severity == efc::Severity::Warning && d.code == "W0900" &&
        d.message.find(word) != std::string::npos)
      return true;
  return false;
}

TEST(UrdfBackend, SpringAndInitialWarnAndGoToSidecar) {
  const std::string dir = temp_dir("spring");
  const std::string spec = dir + "/sprung.json";
  std::ofstream(spec) << R"({
  "efc": 1, "name": "sprung",
  "parts": [
    {"name": "base", "role": "base", "geometry": {"box": {"size": [0.2, 0.2, 0.02]}}},
    {"name": "door", "role": "receptor",
     "geometry": {"box": {"size": [0.01, 0.2, 0.2], "center": [0.1, 0, 0.11]}},
     "joint": {"type": "revolute", "parent": "base", "axis": [0, 1, 0], "origin": [0.1, 0, 0.01],
               "range": [0, 1.5], "initial": 0.3, "damping": 0.01,
               "spring": {"stiffness": 0.5, "rest": 0}}},
    {"name": "bulb", "role": "effector",
     "geometry": {"sphere": {"radius": 0.02, "center": [0, 0, 0.1]}},
     "joint": {"type": "fixed", "parent": "base"}}
  ],
  "functions": [
    {"name": "light", "receptor": "door", "effector": "bulb",
     "mapping": {"type": "binary"}, "effect": {"type": "illumination"}}
  ]
})";
  efc::Object obj = load(spec);
  ASSERT_EQ(obj.parts.size(), 3u);
  efc::Diagnostics diags;
  const std::string path = emit(obj, dir, &diags);
  EXPECT_TRUE(has_warning(diags, "spring")) << "a spring must be reported";
  EXPECT_TRUE(has_warning(diags, "initial")) << "an initial position must be reported";
  EXPECT_TRUE(has_warning(diags, "function templates"));
  for (const auto& d : diags.items())
    if (d.message.find("spring") != std::string::npos) {
      EXPECT_GT(d.line, 0) << "points into the spec";
    }
  std::string log;
  EXPECT_EQ(check_urdf(path, &log), 0) << log;
  const json j = json::parse(read_file(dir + "/urdf/sprung.functions.json"));
  EXPECT_EQ(j["joints"]["door"]["spring"]["stiffness"].get<double>(), 0.5);
  EXPECT_EQ(j["joints"]["door"]["initial"].get<double>(), 0.3);
  fs::remove_all(dir);
}

TEST(UrdfBackend, GeneratedNamesNeverCollide) {
  // Parts named like the generated site link and site joint.
  const std::string dir = temp_dir("names");
  const std::string spec = dir + "/clash.json";
  std::ofstream(spec) << R"({
  "efc": 1, "name": "clash", "description": "dashes -- in a comment --- end -",
  "parts": [
    {"name": "base", "role": "base", "geometry": {"box": {"size": [0.2, 0.2, 0.02]}}},
    {"name": "knob", "role": "receptor",
     "geometry": {"cylinder": {"radius": 0.01, "length": 0.02, "center": [0.05, 0, 0.02], "axis": [1, 1, 0]}},
     "joint": {"type": "continuous", "parent": "base", "axis": [1, 2, 2], "origin": [0.05, 0.01, 0.02]}},
    {"name": "arm", "role": "other",
     "geometry": {"box": {"size": [0.1, 0.01, 0.01], "center": [0.1, 0.02, 0.05], "rpy": [0.2, 0.3, 0.4]}},
     "joint": {"type": "revolute", "parent": "knob", "axis": [0.3, -0.4, 0.5], "origin": [0.06, 0.02, 0.04],
               "range": [-0.5, 1.0]}},
    {"name": "slider", "role": "other",
     "geometry": {"sphere": {"radius": 0.01, "center": [0.15, 0.02, 0.05]}},
     "joint": {"type": "prismatic", "parent": "arm", "axis": [1, 0.5, 0.25], "range": [-0.02, 0.03]}},
    {"name": "light_site", "role": "effector",
     "geometry": {"sphere": {"radius": 0.02, "center": [0, 0, 0.1]}},
     "joint": {"type": "fixed", "parent": "base"}},
    {"name": "light_site_2_joint", "role": "other",
     "geometry": {"box": {"size": [0.01, 0.01, 0.01], "center": [0, 0.05, 0.02], "rpy": [0.1, 1.5707963267948966, 0.3]}},
     "joint": {"type": "prismatic", "parent": "light_site", "axis": [0, 0, -1], "range": [-0.01, 0.01]}}
  ],
  "functions": [
    {"name": "light", "receptor": "knob", "effector": "light_site",
     "mapping": {"type": "binary", "threshold": 1.0}, "effect": {"type": "illumination"}}
  ]
})";
  efc::Object obj = load(spec);
  ASSERT_EQ(obj.parts.size(), 6u);
  const std::string path = emit(obj, dir);
  std::string log;
  EXPECT_EQ(check_urdf(path, &log), 0) << log;
  const auto model = urdf::parseURDFFile(path);
  ASSERT_TRUE(model);
  std::vector<urdf::LinkSharedPtr> links;
  model->getLinks(links);
  EXPECT_EQ(links.size(), 7u);
  EXPECT_EQ(model->joints_.size(), 6u);
  // Skew axes, a chain three joints deep: the frames still agree with MuJoCo.
  const efc::Joint& arm = *obj.parts[obj.find_part("arm")].joint;
  EXPECT_EQ(model->getJoint("arm")->axis.x, arm.axis[0]);
  EXPECT_EQ(model->getJoint("arm")->axis.z, arm.axis[2]);
  expect_fk_matches_mujoco(obj, model, dir);
  const json j = json::parse(read_file(dir + "/urdf/clash.functions.json"));
  const std::string site = j["functions"][0]["effect"]["site"]["link"];
  const std::string sjoint = j["functions"][0]["effect"]["site"]["joint"];
  EXPECT_EQ(site, "light_site_2");
  EXPECT_NE(sjoint, "light_site_2_joint");
  EXPECT_TRUE(model->getLink(site));
  EXPECT_TRUE(model->getJoint(sjoint));
  EXPECT_EQ(model->getLink(site)->parent_joint->parent_link_name, "light_site");
  // The description is in a comment that stays a comment.
  const std::string text = read_file(path);
  EXPECT_NE(text.find("dashes - - in a comment - - - end -"), std::string::npos);
  // Continuous joint: no limits; rotated box and tilted cylinder placed right.
  EXPECT_EQ(model->getJoint("knob")->type, urdf::Joint::CONTINUOUS);
  const auto fk = urdf_fk(*model, {});
  const auto& cyl = *model->getLink("knob")->visual_array[0];
  EXPECT_LT(((fk.at("knob") * pose(cyl.origin)).linear().col(2) - Eigen::Vector3d(1, 1, 0).normalized()).norm(), 1e-9);
  const auto& box = *model->getLink("light_site_2_joint")->visual_array[0];
  EXPECT_LT(((fk.at("light_site_2_joint") * pose(box.origin)).linear() -
             em(efc::rpy_to_matrix({0.1, 1.5707963267948966, 0.3}))).norm(), 1e-9);
  fs::remove_all(dir);
}

TEST(UrdfBackend, RpyRoundTrip) {
  for (const Vec3& rpy : std::vector<Vec3>{{0, 0, 0}, {0.3, -0.2, 1.1}, {3.0, 1.2, -2.9},
                                          {0.4, 1.5707963267948966, -0.7}, {0.4, -1.5707963267948966, 0.2}}) {
    const efc::Mat3 R = efc::rpy_to_matrix(rpy);
    const efc::Mat3 back = efc::rpy_to_matrix(efc::urdf::matrix_to_rpy(R));
    EXPECT_LT((em(R) - em(back)).norm(), 1e-12);
  }
  for (const Vec3& a : std::vector<Vec3>{{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, 1, 0}, {0.3, -0.4, 0.5}}) {
    const efc::Mat3 R = efc::rpy_to_matrix(efc::urdf::matrix_to_rpy(efc::rotation_z_to(a)));
    EXPECT_LT((em(R).col(2) - ev(a).normalized()).norm(), 1e-12);
  }
}

TEST(UrdfBackend, CompileCommandWritesUrdf) {
  const std::string efc = std::string(EFC_BINARY_DIR) + "/efc";
  if (!fs::exists(efc)) GTEST_SKIP() << "efc not built";
  const std::string dir = temp_dir("cli");
  const std::string cmd = "'" + efc + "' compile '" + std::string(EFC_SOURCE_DIR) +
                          "/examples/kitchen_faucet.json' --target urdf -o '" + dir + "/out' > '" + dir +
                          "/log' 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << read_file(dir + "/log");
  const std::string path = dir + "/out/urdf/kitchen_faucet.urdf";
  ASSERT_TRUE(fs::exists(path)) << read_file(dir + "/log");
  EXPECT_TRUE(fs::exists(dir + "/out/urdf/kitchen_faucet.functions.json"));
  EXPECT_TRUE(fs::exists(dir + "/out/urdf/meshes/spout_0.stl"));
  std::string log;
  EXPECT_EQ(check_urdf(path, &log), 0) << log;
  EXPECT_NE(read_file(dir + "/log").find("W0900"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
