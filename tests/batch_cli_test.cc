// `efc batch` as a user meets it: a manifest of jobs run in parallel gives
// the same outputs as each job run alone (compile over every example, infer
// over the committed synthetic suite), results.jsonl holds one complete
// record per job, a failing job stops nothing, a re-run skips what is done,
// a batch killed mid-run (SIGKILL) or stopped (SIGTERM) finishes on the next
// run without redoing or corrupting anything, shards merge, the Slurm
// script runs as it is (without Slurm: tests/batch_slurm_test.cc has the
// cluster), and efc eval reads the results.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "tests/efc_cli.h"

namespace {

namespace fs = std::filesystem;
using efc_test::read_file;
using efc_test::run_efc;
using json = nlohmann::json;

const fs::path kSource = EFC_SOURCE_DIR;
const fs::path kExamples = kSource / "examples";
const fs::path kSuite = kSource / "tests/data/synth-suite";

fs::path fresh_dir(const std::string& stem) {
  fs::path p = fs::temp_directory_path() / ("efc-batch-" + std::to_string(getpid()) + "-" + stem);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

// Quoted for the shell run_efc goes through.
std::string q(const fs::path& p) {
  std::string out = "'";
  for (char c : p.string()) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

// The results file as records, by id (and their order).
std::vector<json> read_results(const fs::path& file) {
  std::vector<json> out;
  std::istringstream in(read_file(file));
  std::string line;
  while (std::getline(in, line)) out.push_back(json::parse(line));  // throws on a corrupt line
  return out;
}

// Every regular file under `dir`, relative path -> bytes.
std::map<std::string, std::string> tree(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out[fs::relative(e.path(), dir).string()] = read_file(e.path());
  return out;
}

void expect_same_tree(const fs::path& a, const fs::path& b) {
  const auto ta = tree(a), tb = tree(b);
  ASSERT_FALSE(ta.empty()) << a;
  EXPECT_EQ(ta.size(), tb.size()) << a << " vs " << b;
  for (const auto& [rel, bytes] : ta) {
    const auto it = tb.find(rel);
    ASSERT_NE(it, tb.end()) << rel << " only in " << a;
    EXPECT_TRUE(bytes == it->second) << rel << " differs between " << a << " and " << b;
  }
}

std::vector<fs::path> example_specs() {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(kExamples))
    if (e.path().extension() == ".json") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// efc started in the background (to be signalled), stderr into a file.
struct Background {
  pid_t pid = -1;
  fs::path err;
  Background(const std::vector<std::string>& args, const fs::path& err_file) : err(err_file) {
    std::vector<std::string> argv{std::string(EFC_BINARY_DIR) + "/efc"};
    argv.insert(argv.end(), args.begin(), args.end());
    pid = fork();
    if (pid == 0) {
      const int fd = open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      dup2(fd, 2);
      const int null = open("/dev/null", O_RDWR);
      dup2(null, 0);
      dup2(null, 1);
      std::vector<char*> a;
      for (auto& s : argv) a.push_back(s.data());
      a.push_back(nullptr);
      execv(a[0], a.data());
      _exit(127);
    }
  }
  // The exit code, or -signal.
  int wait() {
    int status = 0;
    waitpid(pid, &status, 0);
    pid = -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
  }
  ~Background() {
    if (pid > 0) {
      kill(pid, SIGKILL);
      waitpid(pid, nullptr, 0);
    }
  }
};

size_t count_records(const fs::path& dir) {
  size_t n = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir / "records", ec))
    if (e.path().extension() == ".json" && e.path().filename().string()[0] != '.') ++n;
  return n;
}

// Waits until `dir` holds at least `n` records (or 60 s).
bool wait_for_records(const fs::path& dir, size_t n) {
  for (int i = 0; i < 6000; ++i) {
    if (count_records(dir) >= n) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

// Processes whose command line or working folder names `needle` (this
// test's unique folder): what a batch left running.
std::vector<pid_t> processes_naming(const std::string& needle) {
  std::vector<pid_t> out;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string cmd = read_file(e.path() / "cmdline");
    for (char& c : cmd)
      if (c == '\0') c = ' ';
    // A job runs in its folder DIR/jobs/ID, whatever its command line says.
    std::error_code ec;
    const std::string cwd = fs::read_symlink(e.path() / "cwd", ec).string();
    const bool ours = cmd.find(needle) != std::string::npos || cwd.find(needle) != std::string::npos;
    if (ours && std::stoi(name) != getpid()) out.push_back(std::stoi(name));
  }
  return out;
}

bool no_process_left(const std::string& needle) {
  for (int i = 0; i < 300; ++i) {
    if (processes_naming(needle).empty()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

// A manifest of slow jobs: each plays the desk lamp's templates for long
// enough (replay, no simulator) to be caught running.
std::string slow_manifest(int n) {
  std::string text = "# replays, each a fraction of a second\n";
  for (int i = 0; i < n; ++i)
    text += (kExamples / "desk_lamp.json").string() + " --csv r" + std::to_string(i) + ".csv\n";
  return text;
}
const std::string kSlowCommand = "replay --profile press:3 --duration 150 --dt 0.0005";

TEST(BatchCli, CompileEveryExampleSameAsAlone) {
  const fs::path dir = fresh_dir("compile");
  const std::vector<fs::path> specs = example_specs();
  ASSERT_GE(specs.size(), 19u);
  // Paths relative to the manifest's folder.
  fs::create_directories(dir / "m/a/b/c");
  std::string manifest;
  for (const fs::path& s : specs) manifest += fs::relative(s, dir / "m/a/b/c").string() + "\n";
  write(dir / "m/a/b/c/list.txt", "# every example\n" + manifest);
  auto r = run_efc("batch " + q(dir / "m/a/b/c/list.txt") + " -o " + q(dir / "out") + " -j 2 -- compile --target all");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("[" + std::to_string(specs.size()) + "/" + std::to_string(specs.size()) + "]"),
            std::string::npos)
      << r.err;
  const std::vector<json> results = read_results(dir / "out/results.jsonl");
  ASSERT_EQ(results.size(), specs.size());
  for (size_t i = 0; i < specs.size(); ++i) {
    const json& rec = results[i];
    EXPECT_EQ(rec["exit_code"], 0) << rec;
    EXPECT_EQ(rec["path"], specs[i].string());
    EXPECT_EQ(rec["line"], i + 2);
    EXPECT_GT(rec["seconds"].get<double>(), 0.0);
    EXPECT_GT(rec["peak_rss_mb"].get<double>(), 1.0);
    EXPECT_TRUE(rec["diagnostics"].is_string());
    EXPECT_EQ(rec["job"], fs::relative(specs[i], dir / "m/a/b/c").string());
    const std::string id = rec["id"];
    EXPECT_EQ(rec["output"], "jobs/" + id);
    // The same job alone, into a folder of the same name.
    const fs::path alone = dir / "alone" / id;
    fs::create_directories(alone.parent_path());
    auto a = run_efc("compile " + q(specs[i]) + " --target all -o " + q(alone));
    ASSERT_EQ(a.exit_code, 0) << a.err;
    expect_same_tree(dir / "out/jobs" / id, alone);
  }
  fs::remove_all(dir);
}

TEST(BatchCli, InferOverASuiteSameAsAloneAndEvalReadsTheResults) {
  const fs::path dir = fresh_dir("infer");
  // Three committed sequences, and one without depth (its infer fails).
  std::vector<fs::path> seqs;
  for (const auto& e : fs::directory_iterator(kSuite))
    if (fs::is_directory(e.path() / "seq")) seqs.push_back(e.path() / "seq");
  std::sort(seqs.begin(), seqs.end());
  ASSERT_GE(seqs.size(), 3u);
  seqs.resize(3);
  fs::create_directories(dir / "broken");
  fs::copy(seqs[0], dir / "broken/seq", fs::copy_options::recursive);
  fs::remove_all(dir / "broken/seq/depth");
  std::string manifest;
  for (const fs::path& s : seqs) manifest += s.string() + "\n";
  manifest += "broken/seq\n";
  write(dir / "seqs.txt", manifest);
  auto r = run_efc("batch " + q(dir / "seqs.txt") + " -o " + q(dir / "pred") + " -j 2 -- infer --threads 1");
  EXPECT_EQ(r.exit_code, 1) << r.err;  // the broken one
  EXPECT_NE(r.err.find("seqs.txt:4: error[E1110]: job 00004-seq failed (exit 1)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("E1050"), std::string::npos) << r.err;  // its own first error
  const std::vector<json> results = read_results(dir / "pred/results.jsonl");
  ASSERT_EQ(results.size(), 4u);
  EXPECT_EQ(results[3]["exit_code"], 1);
  EXPECT_NE(results[3]["diagnostics"].get<std::string>().find("error[E1050]"), std::string::npos);
  for (size_t i = 0; i < 3; ++i) {
    ASSERT_EQ(results[i]["exit_code"], 0) << results[i];
    const fs::path job = dir / "pred" / results[i]["output"].get<std::string>();
    const fs::path alone = dir / "alone" / std::to_string(i);
    fs::create_directories(alone.parent_path());
    auto a = run_efc("infer " + q(seqs[i]) + " --threads 1 -o " + q(alone));
    ASSERT_EQ(a.exit_code, 0) << a.err;
    // report.json holds timings; the spec and the meshes are the output.
    EXPECT_EQ(read_file(job / "spec.json"), read_file(alone / "spec.json")) << seqs[i];
    fs::remove(job / "report.json");
    fs::remove(alone / "report.json");
    expect_same_tree(job, alone);
  }

  // The data set's tables from the results: the failed job is a failure.
  r = run_efc("eval --list " + q(dir / "pred/results.jsonl") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json ev = json::parse(r.out);
  ASSERT_EQ(ev["pairs"].size(), 4u);
  EXPECT_TRUE(ev["pairs"][0]["prediction_loaded"].get<bool>());
  EXPECT_FALSE(ev["pairs"][3]["prediction_loaded"].get<bool>());
  EXPECT_NE(ev["pairs"][3]["prediction_problem"].get<std::string>().find("failed (exit 1)"), std::string::npos);
  EXPECT_GT(ev["aggregate"]["articulation"]["failed_joints"].get<int>(), 0);
  r = run_efc("eval --list " + q(dir / "pred"));  // the folder works too: tables
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(r.out.empty());
  // A compile batch has no truth: located errors, no table.
  write(dir / "specs.txt", (kExamples / "desk_lamp.json").string() + "\n");
  ASSERT_EQ(run_efc("batch " + q(dir / "specs.txt") + " -o " + q(dir / "c") + " -- check").exit_code, 0);
  r = run_efc("eval --list " + q(dir / "c/results.jsonl"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("results.jsonl:1:1: error[E1118]"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
  fs::remove_all(dir);
}

TEST(BatchCli, BadManifestsAndFoldersAreRefusedBeforeAnythingRuns) {
  const fs::path dir = fresh_dir("bad");
  const std::string lamp = (kExamples / "desk_lamp.json").string();
  write(dir / "list.txt", lamp + "\n" + lamp + " --target \"all\n# fine\n" + lamp + " 'x\n");
  auto r = run_efc("batch " + q(dir / "list.txt") + " -o " + q(dir / "out") + " -- compile --target mujoco");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("list.txt:2:" + std::to_string(lamp.size() + 11) + ": error[E1100]: unterminated double quote"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("list.txt:4:"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));

  write(dir / "o.txt", lamp + " -o /tmp/elsewhere\n");
  r = run_efc("batch " + q(dir / "o.txt") + " -o " + q(dir / "out") + " -- compile --target mujoco");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("o.txt:1:" + std::to_string(lamp.size() + 2) + ": error[E1100]"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));

  write(dir / "ok.txt", lamp + "\n");
  for (const std::string& cmd : {std::string(""), std::string(" --"), std::string(" -- frobnicate"),
                                 std::string(" -- compile -o x"), std::string(" -- batch")}) {
    r = run_efc("batch " + q(dir / "ok.txt") + " -o " + q(dir / "out") + cmd);
    EXPECT_EQ(r.exit_code, 2) << cmd << r.err;
    EXPECT_NE(r.err.find("error[E1103]"), std::string::npos) << cmd << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "out"));
  r = run_efc("batch " + q(dir / "absent.txt") + " -o " + q(dir / "out") + " -- check");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("error[E1101]"), std::string::npos) << r.err;
  r = run_efc("batch " + q(dir / "ok.txt") + " -- check");
  EXPECT_EQ(r.exit_code, 2);
  r = run_efc("batch " + q(dir / "ok.txt") + " -o " + q(dir / "out") + " --shard 2/2 -- check");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("error[E1104]"), std::string::npos) << r.err;
  r = run_efc("batch " + q(dir / "ok.txt") + " -o " + q(dir / "out") + " --tasks 3 -- check");
  EXPECT_EQ(r.exit_code, 2);  // --tasks without --slurm

  // Never into a folder of other files, nor one of another command.
  fs::create_directories(dir / "mine");
  write(dir / "mine/notes.txt", "keep\n");
  r = run_efc("batch " + q(dir / "ok.txt") + " -o " + q(dir / "mine") + " -- check");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("error[E1106]"), std::string::npos) << r.err;
  EXPECT_EQ(fs::directory_iterator(dir / "mine")->path().filename(), "notes.txt");
  ASSERT_EQ(run_efc("batch " + q(dir / "ok.txt") + " -o " + q(dir / "out") + " -- check").exit_code, 0);
  r = run_efc("batch " + q(dir / "ok.txt") + " -o " + q(dir / "out") + " -- check --dump-ir");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("another command"), std::string::npos) << r.err;
  r = run_efc("batch --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("--shard"), std::string::npos);
  EXPECT_NE(r.out.find("results.jsonl"), std::string::npos);
  fs::remove_all(dir);
}

TEST(BatchCli, AFailingJobStopsNothingAndARerunSkipsWhatIsDone) {
  const fs::path dir = fresh_dir("fail");
  write(dir / "list.txt",
        (kExamples / "desk_lamp.json").string() + "\nmissing.json\n" + (kExamples / "toaster.json").string() + "\n");
  const std::string cmd = "batch " + q(dir / "list.txt") + " -o " + q(dir / "out") + " -j 1 -- check";
  auto r = run_efc(cmd);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("list.txt:2: error[E1110]: job 00002-missing failed (exit 2)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("[3/3] 00003-toaster exit 0"), std::string::npos) << r.err;
  std::vector<json> results = read_results(dir / "out/results.jsonl");
  ASSERT_EQ(results.size(), 3u);
  EXPECT_EQ(results[0]["exit_code"], 0);
  EXPECT_EQ(results[1]["exit_code"], 2);
  EXPECT_NE(results[1]["diagnostics"].get<std::string>().find("error[E0001]"), std::string::npos);
  EXPECT_EQ(results[2]["exit_code"], 0);
  const std::string rec1 = read_file(dir / "out/records/00001-desk_lamp.json");
  const auto mtime1 = fs::last_write_time(dir / "out/records/00001-desk_lamp.json");

  // Again: nothing runs.
  r = run_efc(cmd);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("0 ran ok, 0 failed, 3 done before"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(dir / "out/records/00001-desk_lamp.json"), rec1);
  EXPECT_EQ(fs::last_write_time(dir / "out/records/00001-desk_lamp.json"), mtime1);
  // The missing spec appears; --retry-failed runs it and only it.
  fs::copy_file(kExamples / "kettle.json", dir / "missing.json");
  r = run_efc("batch " + q(dir / "list.txt") + " -o " + q(dir / "out") + " --retry-failed -- check");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("1 ran ok, 0 failed, 2 done before"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(dir / "out/records/00001-desk_lamp.json"), rec1);
  results = read_results(dir / "out/results.jsonl");
  ASSERT_EQ(results.size(), 3u);
  EXPECT_EQ(results[1]["exit_code"], 0);
  // A changed line is a new job.
  write(dir / "list.txt", (kExamples / "desk_lamp.json").string() + " --dump-ir\nmissing.json\n" +
                              (kExamples / "toaster.json").string() + "\n");
  r = run_efc(cmd);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("1 ran ok, 0 failed, 2 done before"), std::string::npos) << r.err;
  EXPECT_NE(read_file(dir / "out/logs/00001-desk_lamp.stdout").find("\"parts\""), std::string::npos);
  fs::remove_all(dir);
}

TEST(BatchCli, KilledMidRunTheRerunFinishesTheRest) {
  const fs::path dir = fresh_dir("kill");
  const int n = 6;
  write(dir / "list.txt", slow_manifest(n));
  std::vector<std::string> args{"batch", (dir / "list.txt").string(), "-o", (dir / "out").string(), "-j", "1", "--"};
  std::istringstream words(kSlowCommand);
  for (std::string w; words >> w;) args.push_back(w);
  std::map<std::string, std::string> before;
  std::map<std::string, fs::file_time_type> before_time;
  {
    Background batch(args, dir / "err1.txt");
    ASSERT_TRUE(wait_for_records(dir / "out", 1)) << read_file(dir / "err1.txt");
    ASSERT_EQ(kill(batch.pid, SIGKILL), 0);
    EXPECT_EQ(batch.wait(), -SIGKILL);
    // The job that was running dies with the batch (PR_SET_PDEATHSIG).
    EXPECT_TRUE(no_process_left((dir / "out").string()));
  }
  for (const auto& e : fs::directory_iterator(dir / "out/records")) {
    if (e.path().filename().string()[0] == '.') continue;
    before[e.path().filename().string()] = read_file(e.path());
    before_time[e.path().filename().string()] = fs::last_write_time(e.path());
  }
  ASSERT_GE(before.size(), 1u);
  ASSERT_LT(before.size(), static_cast<size_t>(n)) << "every job ended before the kill: make them slower";
  // What the killed run left is valid JSON lines (possibly a job behind).
  EXPECT_LE(read_results(dir / "out/results.jsonl").size(), before.size());

  std::string rerun = "batch " + q(dir / "list.txt") + " -o " + q(dir / "out") + " -j 2 -- " + kSlowCommand;
  auto r = run_efc(rerun);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find(std::to_string(before.size()) + " done before"), std::string::npos) << r.err;
  const std::vector<json> results = read_results(dir / "out/results.jsonl");
  ASSERT_EQ(results.size(), static_cast<size_t>(n));
  std::set<std::string> ids;
  for (const json& rec : results) {
    EXPECT_EQ(rec["exit_code"], 0) << rec;
    EXPECT_TRUE(ids.insert(rec["id"].get<std::string>()).second) << rec["id"];
    EXPECT_TRUE(fs::exists(dir / "out" / rec["output"].get<std::string>() /
                           ("r" + std::to_string(rec["line"].get<int>() - 2) + ".csv")))
        << rec;
  }
  // The first run's records, untouched.
  for (const auto& [name, text] : before) {
    EXPECT_EQ(read_file(dir / "out/records" / name), text) << name;
    EXPECT_EQ(fs::last_write_time(dir / "out/records" / name), before_time[name]) << name;
  }
  // No temporary file left behind.
  for (const auto& e : fs::recursive_directory_iterator(dir / "out"))
    EXPECT_EQ(e.path().filename().string().find(".efc-batch-tmp-"), std::string::npos) << e.path();
  fs::remove_all(dir);
}

TEST(BatchCli, SigtermIsPassedOnAndNothingPartialIsRecorded) {
  const fs::path dir = fresh_dir("term");
  const int n = 8;
  write(dir / "list.txt", slow_manifest(n));
  std::vector<std::string> args{"batch", (dir / "list.txt").string(), "-o", (dir / "out").string(), "-j", "2", "--"};
  std::istringstream words(kSlowCommand);
  for (std::string w; words >> w;) args.push_back(w);
  Background batch(args, dir / "err.txt");
  ASSERT_TRUE(wait_for_records(dir / "out", 1)) << read_file(dir / "err.txt");
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_EQ(kill(batch.pid, SIGTERM), 0);
  EXPECT_EQ(batch.wait(), 2);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 10.0);
  const std::string err = read_file(dir / "err.txt");
  EXPECT_NE(err.find("error[E1111]: interrupted by SIGTERM"), std::string::npos) << err;
  EXPECT_TRUE(no_process_left((dir / "out").string()));
  const size_t done = count_records(dir / "out");
  EXPECT_LT(done, static_cast<size_t>(n));
  const std::vector<json> results = read_results(dir / "out/results.jsonl");
  EXPECT_EQ(results.size(), done);
  for (const json& rec : results) EXPECT_EQ(rec["exit_code"], 0) << rec;  // no job killed by the TERM is recorded
  fs::remove_all(dir);
}

TEST(BatchCli, ShardsMergeIntoOneResultsFile) {
  const fs::path dir = fresh_dir("shards");
  std::string manifest;
  const std::vector<fs::path> specs = example_specs();
  for (int i = 0; i < 5; ++i) manifest += specs[i].string() + "\n";
  write(dir / "list.txt", manifest);
  const std::string base = "batch " + q(dir / "list.txt") + " -o " + q(dir / "out");
  auto r = run_efc(base + " --shard 0/2 -- check");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_results(dir / "out/results-0-of-2.jsonl").size(), 3u);  // jobs 0, 2, 4
  EXPECT_FALSE(fs::exists(dir / "out/results.jsonl"));
  r = run_efc("batch --merge " + q(dir / "out"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("results-1-of-2.jsonl: error[E1112]: shard 1 of 2 has no results"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--shard 1/2 -- check"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out/results.jsonl"));
  // Shard 1 as a Slurm array task would run it: from the environment.
  setenv("SLURM_ARRAY_TASK_ID", "1", 1);
  setenv("SLURM_ARRAY_TASK_COUNT", "2", 1);
  r = run_efc(base + " -- check");
  unsetenv("SLURM_ARRAY_TASK_ID");
  unsetenv("SLURM_ARRAY_TASK_COUNT");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_results(dir / "out/results-1-of-2.jsonl").size(), 2u);
  r = run_efc("batch --merge " + q(dir / "out"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<json> merged = read_results(dir / "out/results.jsonl");
  ASSERT_EQ(merged.size(), 5u);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(merged[i]["path"], specs[i].string());
  EXPECT_EQ(run_efc("batch --merge " + q(dir / "out") + " -o x").exit_code, 2);
  EXPECT_EQ(run_efc("batch --merge " + q(dir / "nothing")).exit_code, 2);
  fs::remove_all(dir);
}

// The script --slurm writes, run by bash as Slurm would run each task (the
// real cluster is tests/batch_slurm_test.cc): paths with quotes, blanks and
// $(...) stay single words.
TEST(BatchCli, SlurmScriptRunsAsWrittenAndQuotesEverything) {
  const fs::path dir = fresh_dir("slurm-script");
  const fs::path odd = dir / "it's a $(touch pwned) list";
  fs::create_directories(odd);
  write(odd / "list $x.txt", (kExamples / "desk_lamp.json").string() + "\n" + (kExamples / "toaster.json").string() +
                                 "\n" + (kExamples / "kettle.json").string() + "\n");
  const fs::path out = dir / "out dir";
  auto r = run_efc("batch " + q(odd / "list $x.txt") + " -o " + q(out) +
                   " --slurm --tasks 2 --parallel 1 --cpus-per-task 2 --mem 1G --time 00:05:00 -- compile --target "
                   "'mujoco'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string script = read_file(out / "batch.sbatch");
  EXPECT_NE(script.find("#SBATCH --array=0-1%1\n"), std::string::npos) << script;
  EXPECT_NE(script.find("#SBATCH --cpus-per-task=2\n"), std::string::npos) << script;
  EXPECT_NE(script.find("#SBATCH --output=\"" + out.string() + "/logs/%A_%a.out\""), std::string::npos) << script;
  EXPECT_NE(script.find("'" + std::string(EFC_BINARY_DIR) + "/efc' batch"), std::string::npos) << script;
  EXPECT_TRUE(fs::exists(out / "batch.json"));
  EXPECT_TRUE(fs::is_directory(out / "logs"));
  for (int task = 0; task < 2; ++task) {
    const std::string env =
        "SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " SLURM_ARRAY_TASK_COUNT=2 SLURM_CPUS_PER_TASK=2";
    const int rc =
        std::system(("cd " + q(dir) + " && " + env + " bash " + q(out / "batch.sbatch") + " 2>/dev/null").c_str());
    EXPECT_EQ(WEXITSTATUS(rc), 0) << task;
  }
  EXPECT_FALSE(fs::exists(dir / "pwned"));
  EXPECT_FALSE(fs::exists(odd / "pwned"));
  r = run_efc("batch --merge " + q(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<json> merged = read_results(out / "results.jsonl");
  ASSERT_EQ(merged.size(), 3u);
  for (const json& rec : merged) {
    EXPECT_EQ(rec["exit_code"], 0) << rec;
    EXPECT_TRUE(fs::is_directory(out / rec["output"].get<std::string>() / "mujoco")) << rec;
  }
  // A folder sbatch cannot be told about safely; sbatch not to be found.
  r = run_efc("batch " + q(odd / "list $x.txt") + " -o " + q(dir / "100%") + " --slurm -- check");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("error[E1117]"), std::string::npos) << r.err;
  const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
  setenv("PATH", (dir / "empty-bin").c_str(), 1);
  r = run_efc("batch " + q(odd / "list $x.txt") + " -o " + q(dir / "sub") + " --slurm --submit -- check");
  setenv("PATH", path.c_str(), 1);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("error[E1116]"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(dir / "sub/batch.sbatch"));  // kept, to submit by hand
  fs::remove_all(dir);
}

}  // namespace
