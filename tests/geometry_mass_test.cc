// Geometry library: rotations, mesh I/O, hulls, mass properties, bounds, OBB.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "compiler/geometry/geometry.h"

namespace efc {
namespace {

const std::string kMeshDir = std::string(EFC_SOURCE_DIR) + "/tests/data/meshes/";

// The fixture box (tests/data/meshes/box.*): dyadic numbers, exact in the
// single precision Assimp reads.
const Vec3 kBoxSize{0.5, 0.25, 0.125};
const Vec3 kBoxCenter{0.125, 0.25, 0.3125};

Mat3 mul(const Mat3& a, const Mat3& b) {
  Mat3 r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) r[i][j] += a[i][k] * b[k][j];
  return r;
}
Mat3 tr(const Mat3& a) {
  Mat3 r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r[i][j] = a[j][i];
  return r;
}
Vec3 mv(const Mat3& m, const Vec3& v) {
  Vec3 r{0, 0, 0};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) r[i] += m[i][k] * v[k];
  return r;
}
double det(const Mat3& m) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

void expect_vec(const Vec3& a, const Vec3& b, double tol) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], tol) << "component " << i;
}
void expect_mat(const Mat3& a, const Mat3& b, double tol) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(a[i][j], b[i][j], tol) << "entry " << i << "," << j;
}
void expect_rotation(const Mat3& r) {
  Mat3 id{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  expect_mat(mul(r, tr(r)), id, 1e-12);
  EXPECT_NEAR(det(r), 1.0, 1e-12);
}
// Mass properties agree to a relative tolerance (scaled by the largest entry).
void expect_same(const MassProperties& a, const MassProperties& b, double rel) {
  EXPECT_NEAR(a.volume, b.volume, rel * std::fabs(b.volume));
  EXPECT_NEAR(a.mass, b.mass, rel * std::fabs(b.mass));
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a.com[i], b.com[i], rel * (std::fabs(b.com[i]) + 1e-3));
  double scale = 0;
  for (const auto& row : b.inertia)
    for (double x : row) scale = std::max(scale, std::fabs(x));
  expect_mat(a.inertia, b.inertia, rel * scale);
}

Geometry box_geom(const Vec3& size, const Vec3& center, const Vec3& rpy = {0, 0, 0}) {
  Geometry g;
  g.kind = GeomKind::Box;
  g.size = size;
  g.center = center;
  g.rpy = rpy;
  return g;
}
Geometry mesh_geom(const MeshData& m) {
  Geometry g;
  g.kind = GeomKind::Mesh;
  g.mesh = m;
  return g;
}
MeshData load_ok(const std::string& path, const Vec3& scale = {1, 1, 1}) {
  MeshData m;
  std::string err;
  EXPECT_TRUE(load_mesh(path, scale, &m, &err)) << err;
  return m;
}
std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("efc_geometry_test_" + name)).string();
}

// ---------------------------------------------------------------- rotations
TEST(Rotation, RpyIsUrdfConvention) {
  const Vec3 rpy{0.3, -0.7, 1.9};
  const double r = rpy[0], p = rpy[1], y = rpy[2];
  const Mat3 rx{{{1, 0, 0}, {0, std::cos(r), -std::sin(r)}, {0, std::sin(r), std::cos(r)}}};
  const Mat3 ry{{{std::cos(p), 0, std::sin(p)}, {0, 1, 0}, {-std::sin(p), 0, std::cos(p)}}};
  const Mat3 rz{{{std::cos(y), -std::sin(y), 0}, {std::sin(y), std::cos(y), 0}, {0, 0, 1}}};
  expect_mat(rpy_to_matrix(rpy), mul(rz, mul(ry, rx)), 1e-15);
  expect_rotation(rpy_to_matrix(rpy));
  // yaw a quarter turn takes x to y
  expect_vec(mv(rpy_to_matrix({0, 0, M_PI / 2}), {1, 0, 0}), {0, 1, 0}, 1e-15);
}

TEST(Rotation, ZToAxis) {
  for (Vec3 a : {Vec3{0, 0, 1}, Vec3{0, 0, -1}, Vec3{1, 0, 0}, Vec3{0, -1, 0}, Vec3{1, 2, -3},
                 Vec3{1e-9, 0, -1}}) {
    const double n = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    const Vec3 u{a[0] / n, a[1] / n, a[2] / n};
    const Mat3 r = rotation_z_to(u);
    expect_rotation(r);
    expect_vec(mv(r, {0, 0, 1}), u, 1e-12);
  }
}

// ---------------------------------------------------------------- primitives
TEST(MassPrimitives, Box) {
  const MassProperties mp = unit_density_mass_properties(box_geom({0.4, 0.2, 0.1}, {1, 2, 3}));
  const double v = 0.4 * 0.2 * 0.1;
  EXPECT_NEAR(mp.volume, v, 1e-15);
  EXPECT_NEAR(mp.mass, v, 1e-15);
  expect_vec(mp.com, {1, 2, 3}, 0);
  expect_mat(mp.inertia, Mat3{{{v * (0.04 + 0.01) / 12, 0, 0}, {0, v * (0.16 + 0.01) / 12, 0}, {0, 0, v * (0.16 + 0.04) / 12}}},
             1e-18);
}

TEST(MassPrimitives, CylinderAndSphere) {
  Geometry c;
  c.kind = GeomKind::Cylinder;
  c.radius = 0.05;
  c.length = 0.3;
  c.center = {0, 0, 1};
  MassProperties mp = unit_density_mass_properties(c);
  const double v = M_PI * 0.05 * 0.05 * 0.3;
  EXPECT_NEAR(mp.volume, v, 1e-15);
  const double side = v * (3 * 0.0025 + 0.09) / 12;
  expect_mat(mp.inertia, Mat3{{{side, 0, 0}, {0, side, 0}, {0, 0, v * 0.0025 / 2}}}, 1e-18);
  expect_vec(mp.com, {0, 0, 1}, 0);

  Geometry s;
  s.kind = GeomKind::Sphere;
  s.radius = 0.1;
  s.center = {1, -1, 0.5};
  mp = unit_density_mass_properties(s);
  const double vs = 4.0 / 3.0 * M_PI * 1e-3;
  EXPECT_NEAR(mp.volume, vs, 1e-15);
  const double i = 0.4 * vs * 0.01;
  expect_mat(mp.inertia, Mat3{{{i, 0, 0}, {0, i, 0}, {0, 0, i}}}, 1e-18);
  expect_vec(mp.com, {1, -1, 0.5}, 0);
}

TEST(MassPrimitives, RotatedBox) {
  // About z by theta: Ixx = c^2 Ia + s^2 Ib, Ixy = s c (Ia - Ib).
  const Vec3 size{0.4, 0.2, 0.1};
  const double th = 0.6, c = std::cos(th), s = std::sin(th);
  const MassProperties a = unit_density_mass_properties(box_geom(size, {0, 0, 0}));
  const MassProperties b = unit_density_mass_properties(box_geom(size, {0, 0, 0}, {0, 0, th}));
  const double ia = a.inertia[0][0], ib = a.inertia[1][1];
  EXPECT_NEAR(b.inertia[0][0], c * c * ia + s * s * ib, 1e-15);
  EXPECT_NEAR(b.inertia[1][1], s * s * ia + c * c * ib, 1e-15);
  EXPECT_NEAR(b.inertia[0][1], s * c * (ia - ib), 1e-15);
  EXPECT_NEAR(b.inertia[1][0], b.inertia[0][1], 1e-18);
  EXPECT_NEAR(b.inertia[2][2], a.inertia[2][2], 1e-15);
  // A general rpy: R^T I R is the body-frame diagonal tensor.
  const Vec3 rpy{0.4, -1.1, 2.5};
  const MassProperties g = unit_density_mass_properties(box_geom(size, {0, 0, 0}, rpy));
  const Mat3 r = rpy_to_matrix(rpy);
  expect_mat(mul(tr(r), mul(g.inertia, r)), a.inertia, 1e-15);
  EXPECT_NEAR(g.volume, a.volume, 1e-15);
}

TEST(MassPrimitives, TiltedCylinder) {
  Geometry c;
  c.kind = GeomKind::Cylinder;
  c.radius = 0.05;
  c.length = 0.3;
  const double h = std::sqrt(0.5);
  c.axis = {h, 0, h};
  const MassProperties mp = unit_density_mass_properties(c);
  const double v = M_PI * 0.0025 * 0.3, ia = v * 0.0025 / 2, is = v * (3 * 0.0025 + 0.09) / 12;
  // The axis is an eigenvector with the axial moment; y keeps the side moment.
  expect_vec(mv(mp.inertia, c.axis), {ia * h, 0, ia * h}, 1e-15);
  EXPECT_NEAR(mp.inertia[1][1], is, 1e-15);
  EXPECT_NEAR(mp.inertia[0][0], 0.5 * (ia + is), 1e-15);
  EXPECT_NEAR(mp.inertia[0][2], 0.5 * (ia - is), 1e-15);  // I = is 1 + (ia - is) a a^T
  // Along x the cylinder's moment about x is the axial one.
  c.axis = {1, 0, 0};
  const MassProperties x = unit_density_mass_properties(c);
  expect_mat(x.inertia, Mat3{{{ia, 0, 0}, {0, is, 0}, {0, 0, is}}}, 1e-15);
}

TEST(MassPrimitives, CompoundParallelAxis) {
  // Two 0.25-long boxes end to end are one 0.5-long box.
  Geometry c;
  c.kind = GeomKind::Compound;
  c.children = {box_geom({0.25, 0.25, 0.125}, {0, 0.25, 0.3125}), box_geom({0.25, 0.25, 0.125}, {0.25, 0.25, 0.3125})};
  expect_same(unit_density_mass_properties(c), unit_density_mass_properties(box_geom(kBoxSize, kBoxCenter)), 1e-12);
  // A box and a sphere: the textbook sum about the joint centre of mass.
  Geometry s;
  s.kind = GeomKind::Sphere;
  s.radius = 0.1;
  s.center = {0, 0, 1};
  Geometry b = box_geom({0.2, 0.2, 0.2}, {0, 0, 0});
  c.children = {b, s};
  const MassProperties mp = unit_density_mass_properties(c);
  const double mb = 0.008, ms = 4.0 / 3.0 * M_PI * 1e-3, m = mb + ms, zc = ms / m;
  EXPECT_NEAR(mp.mass, m, 1e-15);
  expect_vec(mp.com, {0, 0, zc}, 1e-15);
  const double ixx = mb * 0.08 / 12 + mb * zc * zc + 0.4 * ms * 0.01 + ms * (1 - zc) * (1 - zc);
  EXPECT_NEAR(mp.inertia[0][0], ixx, 1e-15);
  EXPECT_NEAR(mp.inertia[2][2], mb * 0.08 / 12 + 0.4 * ms * 0.01, 1e-15);
}

TEST(MassPrimitives, WithMass) {
  const MassProperties unit = unit_density_mass_properties(box_geom({0.4, 0.2, 0.1}, {1, 0, 0}));
  const MassProperties mp = with_mass(unit, 2.0);
  EXPECT_EQ(mp.mass, 2.0);
  EXPECT_EQ(mp.volume, unit.volume);
  expect_vec(mp.com, unit.com, 0);
  EXPECT_NEAR(mp.inertia[0][0], 2.0 * (0.04 + 0.01) / 12, 1e-15);
  EXPECT_NEAR(mp.inertia[2][2], 2.0 * (0.16 + 0.04) / 12, 1e-15);
}

// ---------------------------------------------------------------- meshes
TEST(MeshMass, ClosedObjMatchesPrimitive) {
  const MeshData m = load_ok(kMeshDir + "box.obj");
  EXPECT_TRUE(m.closed);
  EXPECT_EQ(m.vertices.size(), 8u);  // welded across the per-face normals
  EXPECT_EQ(m.triangles.size(), 12u);  // quads triangulated
  expect_same(unit_density_mass_properties(mesh_geom(m)), unit_density_mass_properties(box_geom(kBoxSize, kBoxCenter)),
              1e-9);
}

TEST(MeshMass, OpenMeshUsesHull) {
  const MeshData m = load_ok(kMeshDir + "box_open.obj");
  EXPECT_FALSE(m.closed);
  EXPECT_EQ(m.triangles.size(), 10u);
  expect_same(unit_density_mass_properties(mesh_geom(m)), unit_density_mass_properties(box_geom(kBoxSize, kBoxCenter)),
              1e-9);
}

TEST(MeshMass, InwardWoundMeshIsFlipped) {
  const MeshData m = load_ok(kMeshDir + "box_inward.obj");
  EXPECT_TRUE(m.closed);
  expect_same(unit_density_mass_properties(mesh_geom(m)), unit_density_mass_properties(box_geom(kBoxSize, kBoxCenter)),
              1e-9);
}

TEST(MeshMass, InconsistentWindingIsNotClosed) {
  MeshData m = load_ok(kMeshDir + "box.obj");
  std::swap(m.triangles[0][1], m.triangles[0][2]);
  std::string err;
  ASSERT_TRUE(write_binary_stl(temp_path("flipped.stl"), m, {0, 0, 0}, &err)) << err;
  const MeshData back = load_ok(temp_path("flipped.stl"));
  EXPECT_FALSE(back.closed);
  std::filesystem::remove(temp_path("flipped.stl"));
}

TEST(MeshMass, FarFromOriginIsAccurate) {
  // The integrals run about the vertex mean, so a mesh 1 km away keeps its
  // inertia to many digits.
  MeshData m = load_ok(kMeshDir + "box.obj");
  for (Vec3& p : m.vertices) p[0] += 1000;
  Vec3 c = kBoxCenter;
  c[0] += 1000;
  expect_same(unit_density_mass_properties(mesh_geom(m)), unit_density_mass_properties(box_geom(kBoxSize, c)), 1e-9);
}

TEST(MeshIo, StlAndPlyLoad) {
  const MassProperties ref = unit_density_mass_properties(box_geom(kBoxSize, kBoxCenter));
  for (const char* f : {"box.stl", "box.ply"}) {
    SCOPED_TRACE(f);
    const MeshData m = load_ok(kMeshDir + f);
    EXPECT_TRUE(m.closed);
    EXPECT_EQ(m.vertices.size(), 8u);
    EXPECT_EQ(m.triangles.size(), 12u);
    expect_same(unit_density_mass_properties(mesh_geom(m)), ref, 1e-9);
  }
}

TEST(MeshIo, ScaleApplied) {
  const MeshData m = load_ok(kMeshDir + "box.obj", {2, 1, 0.5});
  const MassProperties mp = unit_density_mass_properties(mesh_geom(m));
  const Vec3 size{1.0, 0.25, 0.0625}, center{0.25, 0.25, 0.15625};
  expect_same(mp, unit_density_mass_properties(box_geom(size, center)), 1e-9);
  Vec3 lo, hi;
  bounding_box(mesh_geom(m), &lo, &hi);
  expect_vec(lo, {-0.25, 0.125, 0.125}, 1e-12);
  expect_vec(hi, {0.75, 0.375, 0.1875}, 1e-12);
  // A mirroring scale keeps the mesh closed and outward.
  const MeshData mirrored = load_ok(kMeshDir + "box.obj", {-1, 1, 1});
  EXPECT_TRUE(mirrored.closed);
  const MassProperties mm = unit_density_mass_properties(mesh_geom(mirrored));
  EXPECT_NEAR(mm.volume, 0.5 * 0.25 * 0.125, 1e-12);
  EXPECT_NEAR(mm.com[0], -0.125, 1e-12);
}

TEST(MeshIo, ErrorsNotCrashes) {
  MeshData m;
  std::string err;
  EXPECT_FALSE(load_mesh(kMeshDir + "does_not_exist.obj", {1, 1, 1}, &m, &err));
  EXPECT_NE(err.find("does not exist"), std::string::npos) << err;
  err.clear();
  EXPECT_FALSE(load_mesh(kMeshDir + "not_a_mesh.obj", {1, 1, 1}, &m, &err));
  EXPECT_FALSE(err.empty());
  err.clear();
  EXPECT_FALSE(load_mesh(kMeshDir, {1, 1, 1}, &m, &err));  // a directory
  EXPECT_FALSE(err.empty());
  err.clear();
  EXPECT_FALSE(load_mesh(kMeshDir + "box.obj", {1, 0, 1}, &m, &err));
  EXPECT_FALSE(err.empty());

  // Binary junk, an empty file, and a truncated binary STL, under every extension.
  std::string junk(777, '\0');
  for (size_t i = 0; i < junk.size(); ++i) junk[i] = static_cast<char>((i * 2654435761u) >> 13);
  std::string truncated(80, 'x');
  truncated += std::string("\xe8\x03\x00\x00", 4);  // claims 1000 triangles
  truncated += std::string(100, '\x01');
  const std::string bodies[] = {junk, "", truncated, "solid x\nfacet normal 0 0 1\nouter loop\nvertex 1 2\n"};
  for (const char* ext : {".obj", ".stl", ".ply"}) {
    for (size_t b = 0; b < 4; ++b) {
      const std::string path = temp_path("junk" + std::to_string(b) + ext);
      std::ofstream(path, std::ios::binary) << bodies[b];
      err.clear();
      EXPECT_FALSE(load_mesh(path, {1, 1, 1}, &m, &err)) << path;
      EXPECT_FALSE(err.empty()) << path;
      std::filesystem::remove(path);
    }
  }
  // Other formats are not mesh inputs of the spec.
  const std::string dae = temp_path("x.dae");
  std::ofstream(dae) << "<COLLADA/>";
  err.clear();
  EXPECT_FALSE(load_mesh(dae, {1, 1, 1}, &m, &err));
  EXPECT_NE(err.find("extension"), std::string::npos) << err;
  std::filesystem::remove(dae);
}

TEST(MeshIo, BinaryStlRoundTrip) {
  const MeshData m = load_ok(kMeshDir + "box.obj");
  const Vec3 offset{-0.125, 0.5, 1.0};
  const std::string path = temp_path("roundtrip.stl");
  std::string err;
  ASSERT_TRUE(write_binary_stl(path, m, offset, &err)) << err;
  EXPECT_EQ(std::filesystem::file_size(path), 84u + 50u * m.triangles.size());
  const MeshData back = load_ok(path);
  EXPECT_TRUE(back.closed);
  EXPECT_EQ(back.vertices.size(), 8u);
  EXPECT_EQ(back.triangles.size(), 12u);
  const MassProperties a = unit_density_mass_properties(mesh_geom(m));
  MassProperties b = unit_density_mass_properties(mesh_geom(back));
  for (int k = 0; k < 3; ++k) b.com[k] -= offset[k];
  expect_same(b, a, 1e-9);
  std::filesystem::remove(path);
  EXPECT_FALSE(write_binary_stl("/nonexistent_dir/x.stl", m, offset, &err));
  EXPECT_FALSE(err.empty());
}

// ---------------------------------------------------------------- hulls
TEST(Hull, CubeWithInteriorPoints) {
  std::vector<Vec3> pts;
  for (int i = 0; i < 8; ++i) pts.push_back({double(i & 1), double(i >> 1 & 1), double(i >> 2 & 1)});
  for (int i = 1; i < 10; ++i) pts.push_back({0.1 * i, 0.5, 0.3});  // inside
  pts.push_back({0.5, 0.5, 1.0});  // on a face
  MeshData h;
  std::string err;
  ASSERT_TRUE(convex_hull(pts, &h, &err)) << err;
  EXPECT_TRUE(h.closed);
  EXPECT_EQ(h.vertices.size(), 8u);
  EXPECT_EQ(h.triangles.size(), 12u);
  const MassProperties mp = unit_density_mass_properties(mesh_geom(h));  // positive: outward
  EXPECT_NEAR(mp.volume, 1.0, 1e-12);
  expect_vec(mp.com, {0.5, 0.5, 0.5}, 1e-12);
  // Every triangle faces away from the centre.
  for (const auto& t : h.triangles) {
    const Vec3 &a = h.vertices[t[0]], &b = h.vertices[t[1]], &c = h.vertices[t[2]];
    const Vec3 e1{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const Vec3 n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    EXPECT_GT(n[0] * (a[0] - 0.5) + n[1] * (a[1] - 0.5) + n[2] * (a[2] - 0.5), 0);
  }
}

TEST(Hull, DegenerateInputsFail) {
  MeshData h;
  std::string err;
  EXPECT_FALSE(convex_hull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, &h, &err));
  EXPECT_FALSE(err.empty());
  err.clear();
  EXPECT_FALSE(convex_hull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.5, 0.2, 0}}, &h, &err));
  EXPECT_FALSE(err.empty());
  EXPECT_TRUE(h.triangles.empty());
  // Repeated hulls do not leak or corrupt Qhull state.
  for (int i = 0; i < 200; ++i) {
    ASSERT_TRUE(convex_hull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.1, 0.1, 0.1}}, &h, &err)) << err;
    ASSERT_EQ(h.triangles.size(), 4u);
  }
}

// ---------------------------------------------------------------- bounds
TEST(Bounds, AxisAlignedBoxes) {
  Vec3 lo, hi;
  bounding_box(box_geom({2, 4, 6}, {1, 1, 1}, {0, 0, M_PI / 2}), &lo, &hi);
  expect_vec(lo, {-1, 0, -2}, 1e-12);
  expect_vec(hi, {3, 2, 4}, 1e-12);
  Geometry c;
  c.kind = GeomKind::Cylinder;
  c.radius = 0.1;
  c.length = 1;
  c.axis = {1, 0, 0};
  bounding_box(c, &lo, &hi);
  expect_vec(lo, {-0.5, -0.1, -0.1}, 1e-12);
  expect_vec(hi, {0.5, 0.1, 0.1}, 1e-12);
  Geometry s;
  s.kind = GeomKind::Sphere;
  s.radius = 0.5;
  s.center = {0, 0, 3};
  Geometry comp;
  comp.kind = GeomKind::Compound;
  comp.children = {c, s};
  bounding_box(comp, &lo, &hi);
  expect_vec(lo, {-0.5, -0.5, -0.1}, 1e-12);
  expect_vec(hi, {0.5, 0.5, 3.5}, 1e-12);
  // The bounding box of the sample points is the exact one for these shapes.
  const auto pts = sample_points(comp);
  EXPECT_EQ(pts.size(), 64u + 26u);
  Vec3 plo = pts[0], phi = pts[0];
  for (const Vec3& p : pts)
    for (int k = 0; k < 3; ++k) plo[k] = std::min(plo[k], p[k]), phi[k] = std::max(phi[k], p[k]);
  expect_vec(plo, lo, 1e-12);
  expect_vec(phi, hi, 1e-12);
  EXPECT_EQ(sample_points(box_geom({1, 1, 1}, {0, 0, 0})).size(), 8u);
}

TEST(Bounds, ObbOfRotatedBox) {
  const Vec3 size{0.3, 0.12, 0.05}, center{0.2, -0.1, 0.25}, rpy{0.5, -0.3, 1.2};
  const Geometry g = box_geom(size, center, rpy);
  const OrientedBox b = oriented_bounding_box(g);
  std::vector<double> half(b.half.begin(), b.half.end());
  std::sort(half.begin(), half.end());
  EXPECT_NEAR(half[0], 0.025, 1e-9);
  EXPECT_NEAR(half[1], 0.06, 1e-9);
  EXPECT_NEAR(half[2], 0.15, 1e-9);
  expect_vec(b.center, center, 1e-9);
  expect_rotation(b.axes);
  // Its corners are the box's corners.
  const auto pts = sample_points(g);
  for (const Vec3& c : b.corners()) {
    double best = 1e9;
    for (const Vec3& p : pts) best = std::min(best, std::hypot(c[0] - p[0], c[1] - p[1], c[2] - p[2]));
    EXPECT_LT(best, 1e-9);
  }
}

TEST(Bounds, ObbOfAxisAlignedShapesKeepsWorldAxes) {
  const OrientedBox b = oriented_bounding_box(box_geom({0.3, 0.1, 0.2}, {0, 0, 1}));
  expect_mat(b.axes, Mat3{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}, 1e-12);
  expect_vec(b.half, {0.15, 0.05, 0.1}, 1e-12);
  expect_vec(b.center, {0, 0, 1}, 1e-12);
  const auto c = b.corners();
  ASSERT_EQ(c.size(), 8u);
  expect_vec(c[0], {-0.15, -0.05, 0.9}, 1e-12);
  expect_vec(c[7], {0.15, 0.05, 1.1}, 1e-12);
  // A cube is ambiguous for PCA; the answer must still be the cube.
  const OrientedBox cube = oriented_bounding_box(box_geom({1, 1, 1}, {0, 0, 0}, {0.2, 0.1, 0.3}));
  for (double h : cube.half) EXPECT_NEAR(h, 0.5, 1e-9);
}

TEST(Bounds, ObbOfFlatMesh) {
  MeshData m;
  m.vertices = {{0, 0, 0}, {1, 1, 0}, {0, 2, 0}};
  m.triangles = {{0, 1, 2}};
  m.closed = false;
  const OrientedBox b = oriented_bounding_box(mesh_geom(m));
  expect_rotation(b.axes);
  EXPECT_NEAR(b.half[0] * b.half[1] * b.half[2], 0, 1e-12);
  EXPECT_EQ(unit_density_mass_properties(mesh_geom(m)).volume, 0);  // no hull, no volume
}

// ---------------------------------------------------------------- example meshes
TEST(ExampleMeshes, FaucetMeshesAreClosedAndOutward) {
  const std::string dir = std::string(EFC_SOURCE_DIR) + "/examples/meshes/";
  struct Want {
    const char* file;
    Vec3 lo, hi;
  };
  for (const Want& w : {Want{"faucet_spout.obj", {-0.012, -0.012, 0.20}, {0.212, 0.012, 0.312}},
                        Want{"faucet_handle.obj", {-0.132, -0.015, 0.209}, {-0.020, 0.015, 0.221}}}) {
    SCOPED_TRACE(w.file);
    const MeshData m = load_ok(dir + w.file);
    EXPECT_TRUE(m.closed);
    EXPECT_LT(m.vertices.size(), 2000u);
    // Outward: the signed volume is positive before any flipping.
    double v = 0;
    for (const auto& t : m.triangles) {
      const Vec3 &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
      v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6;
    }
    EXPECT_GT(v, 0);
    EXPECT_NEAR(unit_density_mass_properties(mesh_geom(m)).volume, v, 1e-9);
    Vec3 lo, hi;
    bounding_box(mesh_geom(m), &lo, &hi);
    expect_vec(lo, w.lo, 1e-4);
    expect_vec(hi, w.hi, 1e-4);
  }
  // The handle is modelled axis-aligned: its OBB keeps the world axes.
  const OrientedBox b = oriented_bounding_box(mesh_geom(load_ok(dir + "faucet_handle.obj")));
  expect_mat(b.axes, Mat3{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}, 1e-12);
  expect_vec(b.half, {0.056, 0.015, 0.006}, 1e-4);
}

}  // namespace
}  // namespace efc
