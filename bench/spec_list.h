// Shared by the sequence benchmarks (synth_bench, infer_bench): which
// example specs to run, and reading a spec's text. Header-only, so
// infer_bench need not link the other benchmarks' common library.
#pragma once

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace efc_bench {

// The stems in $EFC_BENCH_SPECS (comma-separated), else `defaults`;
// "large_200" (the generated spec of the other benchmarks) is skipped.
inline std::vector<std::string> example_stems(const std::string& defaults) {
  const char* env = std::getenv("EFC_BENCH_SPECS");
  std::string list = env && *env ? env : defaults;
  std::vector<std::string> out;
  std::stringstream ss(list);
  for (std::string s; std::getline(ss, s, ',');)
    if (!s.empty() && s != "large_200") out.push_back(s);
  return out;
}

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace efc_bench
