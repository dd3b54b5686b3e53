#include "pipeline/egofun3d/ply.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

namespace efc::egofun3d {
namespace {

constexpr const char* kCode = "E1045";

enum class Type { I8, U8, I16, U16, I32, U32, F32, F64, Bad };

Type parse_type(const std::string& s) {
  if (s == "char" || s == "int8") return Type::I8;
  if (s == "uchar" || s == "uint8") return Type::U8;
  if (s == "short" || s == "int16") return Type::I16;
  if (s == "ushort" || s == "uint16") return Type::U16;
  if (s == "int" || s == "int32") return Type::I32;
  if (s == "uint" || s == "uint32") return Type::U32;
  if (s == "float" || s == "float32") return Type::F32;
  if (s == "double" || s == "float64") return Type::F64;
  return Type::Bad;
}

size_t type_size(Type t) {
  switch (t) {
    case Type::I8: case Type::U8: return 1;
    case Type::I16: case Type::U16: return 2;
    case Type::I32: case Type::U32: case Type::F32: return 4;
    case Type::F64: return 8;
    default: return 0;
  }
}

struct Property {
  std::string name;
  bool is_list = false;
  Type count_type = Type::Bad, type = Type::Bad;
};

struct Element {
  std::string name;
  unsigned long long count = 0;
  int line = 0;
  std::vector<Property> props;
};

// Binary little-endian values; the caller checked the bytes are there.
double load(const char* p, Type t) {
  switch (t) {
    case Type::I8: return static_cast<int8_t>(*p);
    case Type::U8: return static_cast<uint8_t>(*p);
    case Type::I16: { int16_t v; std::memcpy(&v, p, 2); return v; }
    case Type::U16: { uint16_t v; std::memcpy(&v, p, 2); return v; }
    case Type::I32: { int32_t v; std::memcpy(&v, p, 4); return v; }
    case Type::U32: { uint32_t v; std::memcpy(&v, p, 4); return v; }
    case Type::F32: { float v; std::memcpy(&v, p, 4); return v; }
    case Type::F64: { double v; std::memcpy(&v, p, 8); return v; }
    default: return 0;
  }
}

class Reader {
 public:
  Reader(const std::string& path, Diagnostics& diags) : path_(path), diags_(diags) {}

  bool run(Ply* out) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path_, ec)) return fail(0, "the geometry file does not exist");
    std::ifstream in(path_, std::ios::binary);
    data_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (!header()) return false;
    return binary_ ? binary_body(out) : ascii_body(out);
  }

 private:
  bool fail(int line, const std::string& message) {
    diags_.error(kCode, path_, line, line > 0 ? 1 : 0, "", message,
                 "the importer reads PLY (ascii or binary_little_endian) with vertex x y z and optional "
                 "face vertex_indices");
    return false;
  }

  bool next_line(std::string* line) {
    if (pos_ >= data_.size()) return false;
    size_t nl = data_.find('\n', pos_);
    if (nl == std::string::npos) nl = data_.size();
    *line = data_.substr(pos_, nl - pos_);
    if (!line->empty() && line->back() == '\r') line->pop_back();
    pos_ = nl + 1;
    ++line_;
    return true;
  }

  bool header() {
    std::string line;
    if (!next_line(&line) || line != "ply") return fail(1, "is not a PLY file (the first line is not 'ply')");
    bool have_format = false;
    for (;;) {
      if (!next_line(&line)) return fail(line_, "the PLY header has no end_header line");
      std::istringstream ss(line);
      std::string word;
      ss >> word;
      if (word == "end_header") break;
      if (word == "comment" || word == "obj_info" || word.empty()) continue;
      if (word == "format") {
        std::string kind;
        ss >> kind;
        if (kind == "ascii") binary_ = false;
        else if (kind == "binary_little_endian") binary_ = true;
        else return fail(line_, "PLY format '" + kind + "' is not supported (ascii, binary_little_endian)");
        have_format = true;
      } else if (word == "element") {
        Element e;
        e.line = line_;
        if (!(ss >> e.name >> e.count)) return fail(line_, "malformed element line");
        elements_.push_back(e);
      } else if (word == "property") {
        if (elements_.empty()) return fail(line_, "property before any element");
        Property p;
        std::string t;
        ss >> t;
        if (t == "list") {
          std::string ct, vt;
          ss >> ct >> vt >> p.name;
          p.is_list = true;
          p.count_type = parse_type(ct);
          p.type = parse_type(vt);
          if (p.count_type == Type::Bad || p.count_type == Type::F32 || p.count_type == Type::F64 ||
              p.type == Type::Bad)
            return fail(line_, "unknown list property types '" + ct + " " + vt + "'");
        } else {
          p.type = parse_type(t);
          ss >> p.name;
          if (p.type == Type::Bad) return fail(line_, "unknown property type '" + t + "'");
        }
        elements_.back().props.push_back(p);
      } else {
        return fail(line_, "unexpected PLY header line '" + line + "'");
      }
    }
    if (!have_format) return fail(1, "the PLY header has no format line");
    bool have_vertex = false;
    for (const Element& e : elements_) {
      if (e.name != "vertex") continue;
      have_vertex = true;
      int found = 0;
      for (const Property& p : e.props)
        if (!p.is_list && (p.name == "x" || p.name == "y" || p.name == "z")) ++found;
      if (found != 3) return fail(e.line, "the vertex element lacks x, y and z");
      if (e.count > 100000000ULL) return fail(e.line, "more than 100 million vertices");
    }
    if (!have_vertex) return fail(line_, "the PLY file has no vertex element");
    return true;
  }

  static bool is_face_list(const Element& e, const Property& p) {
    return e.name == "face" && p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index");
  }

  // Stores one item's values (vertex coordinates, a face's polygon).
  bool store(const Element& e, const Property& p, const std::vector<double>& values, Ply* out,
             const std::string& where) {
    if (e.name == "vertex" && !p.is_list) {
      if (!std::isfinite(values[0])) return fail(ascii_line(), where + ": coordinate is not finite");
      auto& v = out->vertices.back();
      if (p.name == "x") v[0] = values[0];
      if (p.name == "y") v[1] = values[0];
      if (p.name == "z") v[2] = values[0];
    } else if (is_face_list(e, p)) {
      std::vector<int> poly;
      for (double x : values) poly.push_back(static_cast<int>(x));
      out->faces.push_back(std::move(poly));
    }
    return true;
  }

  int ascii_line() const { return binary_ ? 0 : line_; }

  bool ascii_body(Ply* out) {
    std::string line;
    for (const Element& e : elements_) {
      for (unsigned long long i = 0; i < e.count; ++i) {
        do {
          if (!next_line(&line))
            return fail(line_, "ends early: element '" + e.name + "' item " + std::to_string(i) + " of " +
                                   std::to_string(e.count) + " is missing");
        } while (line.find_first_not_of(" \t") == std::string::npos);
        if (e.name == "vertex") out->vertices.push_back({0, 0, 0});
        std::istringstream ss(line);
        for (const Property& p : e.props) {
          std::vector<double> values;
          size_t n = 1;
          if (p.is_list) {
            double count;
            if (!(ss >> count) || count < 0 || count > 1000)
              return fail(line_, "bad list length for '" + p.name + "'");
            n = static_cast<size_t>(count);
          }
          for (size_t k = 0; k < n; ++k) {
            std::string tok;
            double v = 0;
            if (!(ss >> tok)) return fail(line_, "too few values for element '" + e.name + "'");
            const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
            if (ec != std::errc() || end != tok.data() + tok.size())
              return fail(line_, "'" + tok + "' is not a number");
            values.push_back(v);
          }
          if (!store(e, p, values, out, e.name + " " + std::to_string(i))) return false;
        }
      }
    }
    return check_faces(out);
  }

  bool binary_body(Ply* out) {
    for (const Element& e : elements_) {
      for (unsigned long long i = 0; i < e.count; ++i) {
        const std::string where = "element '" + e.name + "' item " + std::to_string(i);
        if (e.name == "vertex") out->vertices.push_back({0, 0, 0});
        for (const Property& p : e.props) {
          size_t n = 1;
          if (p.is_list) {
            const size_t cs = type_size(p.count_type);
            if (pos_ + cs > data_.size()) return fail(0, "ends early, in " + where);
            const double count = load(data_.data() + pos_, p.count_type);
            pos_ += cs;
            if (count < 0 || count > 1000) return fail(0, "bad list length in " + where);
            n = static_cast<size_t>(count);
          }
          const size_t es = type_size(p.type);
          if (pos_ + n * es > data_.size()) return fail(0, "ends early, in " + where);
          std::vector<double> values(n);
          for (size_t k = 0; k < n; ++k, pos_ += es) values[k] = load(data_.data() + pos_, p.type);
          if (!store(e, p, values, out, where)) return false;
        }
      }
    }
    return check_faces(out);
  }

  bool check_faces(Ply* out) {
    for (size_t f = 0; f < out->faces.size(); ++f) {
      const auto& poly = out->faces[f];
      if (poly.size() < 3) return fail(0, "face " + std::to_string(f) + " has fewer than 3 vertices");
      for (int v : poly)
        if (v < 0 || static_cast<size_t>(v) >= out->vertices.size())
          return fail(0, "face " + std::to_string(f) + " names vertex " + std::to_string(v) + ", the file has " +
                             std::to_string(out->vertices.size()));
    }
    return true;
  }

  const std::string& path_;
  Diagnostics& diags_;
  std::string data_;
  size_t pos_ = 0;
  int line_ = 0;
  bool binary_ = false;
  std::vector<Element> elements_;
};

}  // namespace

bool read_ply(const std::string& path, Diagnostics& diags, Ply* out) {
  *out = Ply{};
  Reader r(path, diags);
  if (r.run(out)) return true;
  *out = Ply{};
  return false;
}

}  // namespace efc::egofun3d
