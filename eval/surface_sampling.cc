#include "eval/surface_sampling.h"

#include <algorithm>
#include <cmath>

#include "compiler/geometry/geometry.h"
#include "compiler/geometry/vec.h"

namespace efc::eval {

using namespace geom;

namespace {

constexpr double kTwoPi = 6.28318530717958647692;

// splitmix64: tiny, well mixed, and its output is fixed by its definition.
class Random {
 public:
  explicit Random(uint64_t seed) : state_(seed) {}
  double uniform() {  // [0, 1) with 53 random bits
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }

 private:
  uint64_t state_;
};

// One piece of surface with a uniform sampler: a triangle, a sphere, a
// cylinder's side or a disc (a cylinder's cap).
struct Piece {
  enum Kind { Triangle, Sphere, Tube, Disc } kind = Triangle;
  Vec3 a{}, b{}, c{};  // triangle corners; else a = centre
  Mat3 frame{};        // tube, disc: columns x, y, axis
  double radius = 0, length = 0;
  double area = 0;
};

void add_triangle(std::vector<Piece>* out, const Vec3& a, const Vec3& b, const Vec3& c) {
  Piece p;
  p.a = a, p.b = b, p.c = c;
  p.area = 0.5 * norm(cross(sub(b, a), sub(c, a)));
  if (p.area > 0) out->push_back(p);
}

void add_box(std::vector<Piece>* out, const Geometry& g) {
  const Mat3 r = rpy_to_matrix(g.rpy);
  auto corner = [&](int i) {
    const Vec3 local{(i & 1 ? 0.5 : -0.5) * g.size[0], (i & 2 ? 0.5 : -0.5) * g.size[1],
                     (i & 4 ? 0.5 : -0.5) * g.size[2]};
    return add(g.center, apply(r, local));
  };
  // Each face as two triangles over corner indices (bit k = +half along k).
  static const int faces[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                  {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};
  for (const auto& f : faces) {
    add_triangle(out, corner(f[0]), corner(f[1]), corner(f[2]));
    add_triangle(out, corner(f[0]), corner(f[2]), corner(f[3]));
  }
}

void add_cylinder(std::vector<Piece>* out, const Geometry& g) {
  Piece p;
  p.frame = rotation_z_to(normalized(g.axis));
  p.radius = g.radius, p.length = g.length;
  p.kind = Piece::Tube;
  p.a = g.center;
  p.area = kTwoPi * g.radius * g.length;
  if (p.area > 0) out->push_back(p);
  p.kind = Piece::Disc;
  p.area = 0.5 * kTwoPi * g.radius * g.radius;
  for (double side : {-0.5, 0.5}) {
    p.a = add(g.center, mul(column(p.frame, 2), side * g.length));
    if (p.area > 0) out->push_back(p);
  }
}

void collect(const Geometry& g, std::vector<Piece>* out) {
  switch (g.kind) {
    case GeomKind::Mesh:
      if (!g.mesh) return;
      for (const auto& t : g.mesh->triangles)
        add_triangle(out, g.mesh->vertices[t[0]], g.mesh->vertices[t[1]], g.mesh->vertices[t[2]]);
      return;
    case GeomKind::Box: add_box(out, g); return;
    case GeomKind::Cylinder: add_cylinder(out, g); return;
    case GeomKind::Sphere: {
      Piece p;
      p.kind = Piece::Sphere;
      p.a = g.center;
      p.radius = g.radius;
      p.area = 2 * kTwoPi * g.radius * g.radius;
      if (p.area > 0) out->push_back(p);
      return;
    }
    case GeomKind::Compound:
      for (const Geometry& c : g.children) collect(c, out);
      return;
  }
}

Vec3 sample(const Piece& p, Random& rng) {
  const double u = rng.uniform(), v = rng.uniform();
  switch (p.kind) {
    case Piece::Triangle: {  // sqrt warps the square onto the triangle uniformly
      const double s = std::sqrt(u);
      return add(add(mul(p.a, 1 - s), mul(p.b, s * (1 - v))), mul(p.c, s * v));
    }
    case Piece::Sphere: {  // Archimedes: z uniform on [-1, 1]
      const double z = 1 - 2 * u, r = std::sqrt(std::max(0.0, 1 - z * z)), phi = kTwoPi * v;
      return add(p.a, mul(Vec3{r * std::cos(phi), r * std::sin(phi), z}, p.radius));
    }
    case Piece::Tube: {
      const double phi = kTwoPi * u;
      const Vec3 local{p.radius * std::cos(phi), p.radius * std::sin(phi), (v - 0.5) * p.length};
      return add(p.a, apply(p.frame, local));
    }
    case Piece::Disc: {
      const double r = p.radius * std::sqrt(u), phi = kTwoPi * v;
      const Vec3 local{r * std::cos(phi), r * std::sin(phi), 0};  // named: an rvalue would pick std::apply
      return add(p.a, apply(p.frame, local));
    }
  }
  return p.a;
}

}  // namespace

std::vector<Vec3> sample_surface(const Geometry& g, int count, uint64_t seed) {
  std::vector<Piece> pieces;
  collect(g, &pieces);
  std::vector<double> cumulative;
  double total = 0;
  for (const Piece& p : pieces) cumulative.push_back(total += p.area);
  std::vector<Vec3> out;
  if (pieces.empty() || !(total > 0) || count <= 0) return out;
  Random rng(seed);
  out.reserve(count);
  for (int i = 0; i < count; ++i) {
    const double pick = rng.uniform() * total;
    const size_t k = std::min<size_t>(
        std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin(), pieces.size() - 1);
    out.push_back(sample(pieces[k], rng));
  }
  return out;
}

}  // namespace efc::eval
