// The importer's JSON files (dataset_metadata.json, intrinsics, annotations)
// read with the compiler's positioned reader, so every problem points at the
// line:col of the value that is wrong (nlohmann::json keeps no positions).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "compiler/diagnostics.h"
#include "compiler/frontend/positioned_json.h"

namespace efc::egofun3d {

class JsonDoc {
 public:
  // Reads and parses `path`. A missing or unreadable file is `code` at the
  // file itself; syntax errors are the compiler's E0002-E0007. False after
  // any error.
  bool read(const std::string& path, const std::string& code, Diagnostics& diags);

  const std::string& file() const { return file_; }
  const nlohmann::json& root() const { return doc_.value; }
  // line:col of the value at `pointer` (of its nearest located ancestor).
  std::pair<int, int> at(const std::string& pointer) const;
  void error(Diagnostics& diags, const std::string& code, const std::string& pointer,
             const std::string& message, const std::string& hint = "") const;
  void warning(Diagnostics& diags, const std::string& code, const std::string& pointer,
               const std::string& message) const;

  // Typed access to a key of the object at `pointer`; an absent key or a
  // value of another type is a located `code` error. nullopt then.
  const nlohmann::json* member(Diagnostics& diags, const std::string& code, const std::string& pointer,
                               const std::string& key, bool required = true) const;
  std::optional<std::string> string(Diagnostics& diags, const std::string& code, const std::string& pointer,
                                    const std::string& key) const;
  std::optional<double> number(Diagnostics& diags, const std::string& code, const std::string& pointer,
                               const std::string& key) const;
  // `n` finite numbers.
  std::optional<std::vector<double>> numbers(Diagnostics& diags, const std::string& code,
                                             const std::string& pointer, const std::string& key, size_t n) const;
  // A 3x3 matrix (3 rows of 3 finite numbers), row-major.
  std::optional<std::array<double, 9>> matrix3(Diagnostics& diags, const std::string& code,
                                               const std::string& pointer, const std::string& key) const;

 private:
  std::string file_, text_;
  frontend::PositionedJson doc_;
};

std::string pointer_join(const std::string& base, const std::string& key);
std::string pointer_join(const std::string& base, size_t index);

}  // namespace efc::egofun3d
