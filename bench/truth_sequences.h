// Helpers of the programs that score efc infer's stages against synthetic
// truth (ego_motion_eval, part_motion_eval): finding the sequences an
// argument names, and percentiles.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace efc::bench {

// `arg` itself when it is a sequence folder holding `truth_file` (relative,
// e.g. "truth/poses.txt"); else every <entry>/seq of the suite folder `arg`
// that holds it, sorted. Empty when there is none.
inline std::vector<std::filesystem::path> sequences_in(const std::filesystem::path& arg,
                                                       const std::string& truth_file) {
  if (std::filesystem::exists(arg / truth_file)) return {arg};
  std::vector<std::filesystem::path> out;
  if (std::filesystem::is_directory(arg))
    for (const auto& e : std::filesystem::directory_iterator(arg))
      if (std::filesystem::exists(e.path() / "seq" / truth_file)) out.push_back(e.path() / "seq");
  std::sort(out.begin(), out.end());
  return out;
}

// The p-quantile (0..1) of v, nearest rank; 0 for an empty v.
inline double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(p * (v.size() - 1) + 0.5)];
}

}  // namespace efc::bench
