// efc batch on a real Slurm cluster (tests/slurm_cluster.h: munged,
// slurmctld and slurmd on loopback, started here and stopped by pid): the
// array job `efc batch --slurm --submit` writes and submits runs every
// shard, `efc batch --merge` joins them, and every job's output is there.
// Skipped, saying why, when Slurm is not installed (scripts/setup installs
// slurm-wlm and munge).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "tests/efc_cli.h"
#include "tests/slurm_cluster.h"

namespace {

namespace fs = std::filesystem;
using efc_test::read_file;
using efc_test::run_efc;
using json = nlohmann::json;

TEST(BatchSlurm, ArrayJobRunsEveryShardAndTheMergeHoldsEveryJob) {
  const std::vector<std::string> missing = efc_test::SlurmCluster::missing_programs();
  if (!missing.empty()) {
    std::string names;
    for (const std::string& m : missing) names += " " + m;
    GTEST_SKIP() << "Slurm is not installed (missing:" << names << "); scripts/setup installs slurm-wlm and munge";
  }
  efc_test::SlurmCluster cluster;
  std::string why;
  ASSERT_TRUE(cluster.start(&why)) << why << "\n" << cluster.logs();

  const fs::path dir = cluster.dir() / "work";
  fs::create_directories(dir);
  std::vector<std::string> names = {"desk_lamp", "toaster", "kettle", "pedal_bin", "kitchen_drawer"};
  std::string manifest = "# five examples\n";
  for (const std::string& n : names) manifest += std::string(EFC_SOURCE_DIR) + "/examples/" + n + ".json\n";
  std::ofstream(dir / "specs.txt") << manifest;

  auto r = run_efc("batch '" + (dir / "specs.txt").string() + "' -o '" + (dir / "out").string() +
                   "' --slurm --submit --tasks 3 --parallel 2 --cpus-per-task 1 --mem 100M --time 00:05:00 "
                   "-- compile --target mujoco");
  ASSERT_EQ(r.exit_code, 0) << r.err << "\n" << cluster.logs();
  std::string id = r.out;
  while (!id.empty() && (id.back() == '\n' || id.back() == ' ')) id.pop_back();
  ASSERT_TRUE(std::regex_match(id, std::regex("[0-9]+"))) << "job id: '" << r.out << "'";
  cluster.track_job(id);
  EXPECT_NE(read_file(dir / "out/batch.sbatch").find("#SBATCH --array=0-2%2"), std::string::npos);
  ASSERT_TRUE(cluster.wait_job(id, 120)) << cluster.show_job(id) << "\n" << cluster.logs();

  // Without accounting, exit codes come from scontrol: one line per task.
  const std::string shown = cluster.show_job(id);
  int tasks = 0;
  std::istringstream lines(shown);
  for (std::string line; std::getline(lines, line);) {
    if (line.find("ArrayJobId=" + id) == std::string::npos) continue;
    ++tasks;
    EXPECT_NE(line.find("JobState=COMPLETED"), std::string::npos) << line;
    EXPECT_NE(line.find(" ExitCode=0:0"), std::string::npos) << line;
  }
  EXPECT_EQ(tasks, 3) << shown;
  for (int t = 0; t < 3; ++t) {
    const fs::path log = dir / "out/logs" / (id + "_" + std::to_string(t) + ".out");
    EXPECT_TRUE(fs::exists(log)) << log;
    EXPECT_NE(read_file(log).find("in shard " + std::to_string(t) + "/3"), std::string::npos) << read_file(log);
    EXPECT_TRUE(fs::exists(dir / ("out/results-" + std::to_string(t) + "-of-3.jsonl")));
  }

  r = run_efc("batch --merge '" + (dir / "out").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream results(read_file(dir / "out/results.jsonl"));
  size_t k = 0;
  for (std::string line; std::getline(results, line); ++k) {
    const json rec = json::parse(line);
    ASSERT_LT(k, names.size());
    EXPECT_EQ(rec["exit_code"], 0) << rec;
    EXPECT_EQ(rec["line"], k + 2);
    const fs::path xml = dir / "out" / rec["output"].get<std::string>() / "mujoco" / (names[k] + ".xml");
    EXPECT_TRUE(fs::exists(xml)) << xml;
  }
  EXPECT_EQ(k, names.size());
}

}  // namespace
