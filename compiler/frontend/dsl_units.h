// Units of the DSL: which unit fits which spec field, conversion to the
// spec's SI values, and the choice of unit when printing (the shortest
// spelling that converts back to exactly the same double).
#pragma once

#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <nlohmann/json.hpp>

namespace efc::dsl {

enum class Dim {
  None,              // unitless: axis, direction, colours, scale, gain, stiffness, ...
  Length, Angle, Mass, Time,
  Temperature,       // an absolute temperature (K -> C subtracts 273.15)
  TemperatureDelta,  // a temperature difference (cumulative delta)
  Luminous, Flow, Speed,
  Unknown,           // not a spec field, or depends on a part that is missing
};

struct Unit {
  const char* name;  // as written: "mm", "L/min"
  Dim dim;
};

// nullptr when `name` is not a unit.
const Unit* find_unit(std::string_view name);
// "m, cm, mm, rad, deg, ..." for messages.
std::string unit_list();
// "a length (m, cm, mm)", "unitless" for messages.
std::string describe_dim(Dim d);
// True when a number written in `u` may stand in a field of dimension `d`.
bool unit_fits(const Unit& u, Dim d);

// The value in the spec's unit of `value` written in `u`, for a field of
// dimension `field` (which decides whether K is absolute or a difference).
double to_si(const Unit& u, double value, Dim field);

// The dimension of the field at `path` (JSON pointer tokens of the number, or
// of the array holding a range or vector) in the document. Built once per
// document: a joint position's dimension needs its part, found by name.
class FieldDimensions {
 public:
  explicit FieldDimensions(const nlohmann::json& doc);
  Dim of(const std::vector<std::string>& path) const;

 private:
  Dim joint_dim(const std::string& part) const;
  Dim effect_dim(const nlohmann::json* function, bool difference) const;
  const nlohmann::json& doc_;
  std::unordered_map<std::string, Dim> joints_;  // part name -> its joint position's dimension
};

// The shortest decimal text that reads back as exactly `v` ("0.1", "1e-07").
std::string shortest(double v);

// Spells SI values that share one unit (a scalar, a range, a vector) in the
// unit of `d` that reads back exactly and takes the fewest characters (the SI
// unit on ties). `unit` is empty for unitless and unknown fields.
struct Spelled {
  std::vector<std::string> numbers;
  std::string unit;
};
Spelled spell(const std::vector<double>& si_values, Dim d);

}  // namespace efc::dsl
