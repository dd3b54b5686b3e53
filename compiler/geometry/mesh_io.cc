// Mesh files: reading OBJ/STL/PLY through Assimp into one welded triangle
// mesh, and writing binary STL for backends.
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <unordered_map>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "compiler/geometry/geometry.h"
#include "compiler/geometry/vec.h"

namespace efc {

using namespace geom;

namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// Collects the triangles of every mesh a node (and its children) references,
// with the node transforms applied. OBJ, STL and PLY loaders produce a flat
// scene with identity transforms, but honouring them costs nothing and keeps
// this right if another loader is ever allowed.
struct Collector {
  const aiScene* scene;
  Vec3 scale;
  std::map<Vec3, int> index_of;  // welding by exact position (see load_mesh)
  MeshData* out;
  bool finite = true;

  int vertex(const Vec3& p) {
    auto it = index_of.find(p);
    if (it != index_of.end()) return it->second;
    int id = static_cast<int>(out->vertices.size());
    out->vertices.push_back(p);
    index_of.emplace(p, id);
    return id;
  }

  void visit(const aiNode* node, const aiMatrix4x4& parent, int depth) {
    if (!node || depth > 256) return;  // a malformed cyclic graph must not recurse forever
    const aiMatrix4x4 m = parent * node->mTransformation;
    // A mirroring transform (or scale) turns outward triangles inward; flip
    // them back so the mesh keeps its orientation.
    const double det = static_cast<double>(aiMatrix3x3(m).Determinant()) * scale[0] * scale[1] * scale[2];
    const bool flip = det < 0;
    for (unsigned k = 0; k < node->mNumMeshes; ++k) {
      const unsigned mi = node->mMeshes[k];
      if (mi >= scene->mNumMeshes) continue;
      const aiMesh* mesh = scene->mMeshes[mi];
      if (!mesh || !mesh->mVertices) continue;
      for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
        const aiFace& face = mesh->mFaces[f];
        if (face.mNumIndices != 3) continue;  // points and lines carry no volume
        std::array<int, 3> tri{};
        bool ok = true;
        for (int c = 0; c < 3; ++c) {
          const unsigned vi = face.mIndices[c];
          if (vi >= mesh->mNumVertices) { ok = false; break; }
          const aiVector3D q = m * mesh->mVertices[vi];
          const Vec3 p{q.x * scale[0], q.y * scale[1], q.z * scale[2]};
          if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
            finite = false;
            ok = false;
            break;
          }
          tri[c] = vertex(p);
        }
        if (!ok) continue;
        // Triangles that collapse after welding have no area and would break
        // the edge count of the closedness test.
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) continue;
        if (flip) std::swap(tri[1], tri[2]);
        out->triangles.push_back(tri);
      }
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c) visit(node->mChildren[c], m, depth + 1);
  }
};

// Closed = every edge is used exactly twice, once in each direction, i.e.
// the surface is edge-manifold, watertight and consistently wound. A mesh
// with a few flipped triangles does not bound a well-defined volume for the
// signed-volume integrals, so it counts as not closed (its hull is used).
bool is_closed(const MeshData& m) {
  if (m.triangles.empty()) return false;
  std::unordered_map<uint64_t, int> directed;
  directed.reserve(m.triangles.size() * 3);
  auto key = [](int a, int b) { return (static_cast<uint64_t>(a) << 32) | static_cast<uint32_t>(b); };
  for (const auto& t : m.triangles)
    for (int e = 0; e < 3; ++e) ++directed[key(t[e], t[(e + 1) % 3])];
  for (const auto& [k, count] : directed) {
    if (count != 1) return false;
    const int a = static_cast<int>(k >> 32), b = static_cast<int>(k & 0xffffffffu);
    auto it = directed.find(key(b, a));
    if (it == directed.end() || it->second != 1) return false;
  }
  return true;
}

void put_u32(std::string& out, uint32_t v) {
  const char b[4] = {static_cast<char>(v & 0xff), static_cast<char>((v >> 8) & 0xff),
                     static_cast<char>((v >> 16) & 0xff), static_cast<char>((v >> 24) & 0xff)};
  out.append(b, 4);
}
void put_f32(std::string& out, double d) {
  // STL is little-endian IEEE float whatever the host.
  const float x = static_cast<float>(d);
  uint32_t u;
  std::memcpy(&u, &x, 4);
  put_u32(out, u);
}

}  // namespace

bool load_mesh(const std::string& path, const Vec3& scale, MeshData* out, std::string* error) {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  *out = MeshData{};
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return fail("mesh file '" + path + "' does not exist");
  if (!std::filesystem::is_regular_file(path, ec)) return fail("mesh file '" + path + "' is not a regular file");
  const std::string ext = lower_extension(path);
  if (ext != ".obj" && ext != ".stl" && ext != ".ply")
    return fail("mesh file '" + path + "' has extension '" + ext + "'; expected .obj, .stl or .ply");
  for (double s : scale)
    if (!std::isfinite(s) || s == 0) return fail("mesh scale must be finite and non-zero");
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) return fail("mesh file '" + path + "' cannot be opened for reading");
  }

  Assimp::Importer importer;
  // JoinIdenticalVertices only joins vertices whose normals and texture
  // coordinates also agree; welding by position happens below.
  const aiScene* scene = nullptr;
  try {
    scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
  } catch (...) {  // Assimp catches its own, but a garbage file must never escape
    scene = nullptr;
  }
  if (!scene) {
    std::string why = importer.GetErrorString();
    if (why.empty()) why = "unknown error";
    return fail("cannot read mesh '" + path + "': " + why);
  }
  if (!scene->mRootNode && scene->mNumMeshes == 0) return fail("mesh file '" + path + "' holds no mesh");

  // Weld vertices by exact position: STL repeats every vertex per triangle
  // and OBJ splits them at normal/texture seams, yet the closedness test and
  // the hull need shared vertices. Exact equality (not a tolerance) keeps
  // distinct-but-close vertices of fine meshes apart.
  Collector c{scene, scale, {}, out};
  if (scene->mRootNode) {
    c.visit(scene->mRootNode, aiMatrix4x4(), 0);
  } else {
    aiNode flat;  // no node graph: take every mesh once, untransformed
    std::vector<unsigned> all(scene->mNumMeshes);
    for (unsigned i = 0; i < scene->mNumMeshes; ++i) all[i] = i;
    flat.mNumMeshes = scene->mNumMeshes;
    flat.mMeshes = all.data();
    c.visit(&flat, aiMatrix4x4(), 0);
    flat.mMeshes = nullptr;  // owned by `all`, not by the node
    flat.mNumMeshes = 0;
  }
  if (!c.finite) return fail("mesh '" + path + "' has non-finite vertex coordinates");
  if (out->triangles.empty()) return fail("mesh '" + path + "' has no triangles");
  out->closed = is_closed(*out);
  return true;
}

std::string binary_stl(const MeshData& mesh, const Vec3& offset) {
  std::string out;
  out.reserve(84 + 50 * mesh.triangles.size());
  // The header must not start with "solid", or readers take it for ASCII.
  char header[80] = {};
  std::snprintf(header, sizeof header, "binary STL written by efc");
  out.append(header, sizeof header);
  put_u32(out, static_cast<uint32_t>(mesh.triangles.size()));
  const int nv = static_cast<int>(mesh.vertices.size());
  for (const auto& t : mesh.triangles) {
    Vec3 p[3];
    for (int c = 0; c < 3; ++c)
      p[c] = (t[c] >= 0 && t[c] < nv) ? add(mesh.vertices[t[c]], offset) : offset;
    const Vec3 n = normalized(cross(sub(p[1], p[0]), sub(p[2], p[0])));
    for (int k = 0; k < 3; ++k) put_f32(out, n[k]);
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) put_f32(out, p[c][k]);
    out.append(2, '\0');  // attribute byte count
  }
  return out;
}

bool write_binary_stl(const std::string& path, const MeshData& mesh, const Vec3& offset,
                      std::string* error) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) {
    if (error) *error = "cannot open '" + path + "' for writing";
    return false;
  }
  const std::string bytes = binary_stl(mesh, offset);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  f.close();
  if (!f) {
    if (error) *error = "failed writing '" + path + "'";
    return false;
  }
  return true;
}

}  // namespace efc
