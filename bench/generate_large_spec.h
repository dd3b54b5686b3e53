// A generated spec for the benchmarks: `parts` parts (200 by default) in
// columns of ten standing on one long base, with mixed primitive geometry
// (box, cylinder, sphere, compound), revolute / prismatic / continuous joints,
// and about one function per two parts over every mapping and the non-particle
// effects (geometry, illumination, temperature, airflow), including chains (a
// geometry effector that is the receptor of the next function).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace efc_bench {

// The spec as JSON. `parts` >= 2; functions = 5 per full column of 10 parts.
nlohmann::json generate_large_spec(int parts = 200, const std::string& name = "large_200");

// Writes it to <dir>/<name>.json (creating dir) and returns the path; throws
// std::runtime_error when the file cannot be written.
std::string write_large_spec(const std::string& dir, int parts = 200,
                             const std::string& name = "large_200");

}  // namespace efc_bench
