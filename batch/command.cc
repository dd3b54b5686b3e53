#include "batch/command.h"

#include <map>

namespace efc::batch {

namespace {

// The efc commands (cli/cli.cc) and how each takes its output.
const std::map<std::string, OutputKind>& commands() {
  static const std::map<std::string, OutputKind> table = {
      {"check", OutputKind::None},         {"compile", OutputKind::Folder},
      {"play", OutputKind::None},          {"parity", OutputKind::None},
      {"replay", OutputKind::None},        {"synth", OutputKind::Folder},
      {"synth-suite", OutputKind::Folder}, {"articulate", OutputKind::None},
      {"infer", OutputKind::Folder},       {"fmt", OutputKind::None},
      {"convert", OutputKind::None},       {"check-sequence", OutputKind::None},
      {"eval", OutputKind::None},          {"import-egofun3d", OutputKind::Folder},
  };
  return table;
}

}  // namespace

bool is_output_flag(const std::string& arg) {
  if (arg == "-o" || arg == "--output" || arg.rfind("--output=", 0) == 0) return true;
  return arg.size() > 2 && arg.rfind("-o", 0) == 0 && arg[2] != '-';
}

bool check_command(const std::vector<std::string>& command, OutputKind* kind, std::string* why) {
  if (command.empty()) {
    *why = "no command to run: give it after '--', e.g. efc batch list.txt -o out -- compile --target all";
    return false;
  }
  if (command[0] == "batch") {
    *why = "a batch cannot run efc batch";
    return false;
  }
  const auto it = commands().find(command[0]);
  if (it == commands().end()) {
    std::string names;
    for (const auto& [name, k] : commands()) names += (names.empty() ? "" : ", ") + name;
    *why = "'" + command[0] + "' is not an efc command batch can run (" + names + ")";
    return false;
  }
  *kind = it->second;
  if (*kind == OutputKind::Folder)
    for (const std::string& a : command)
      if (is_output_flag(a)) {
        *why = "the command may not give '" + a + "': efc batch sets each job's output folder (DIR/jobs/<id>/)";
        return false;
      }
  return true;
}

bool check_line_args(const std::vector<Job>& jobs, OutputKind kind, const std::string& manifest, Diagnostics& diags) {
  if (kind != OutputKind::Folder) return true;
  bool ok = true;
  for (const Job& job : jobs)
    for (size_t k = 0; k < job.args.size(); ++k)
      if (is_output_flag(job.args[k])) {
        diags.error("E1100", manifest, job.line, job.arg_cols[k], "",
                    "a line may not give '" + job.args[k] + "': efc batch sets each job's output folder",
                    "remove it; the job writes into DIR/jobs/<id>/");
        ok = false;
      }
  return ok;
}

std::vector<std::string> job_argv(const std::string& efc_exe, const std::vector<std::string>& command, const Job& job,
                                  OutputKind kind, const std::string& job_dir) {
  std::vector<std::string> argv{efc_exe, command.at(0), job.path};
  argv.insert(argv.end(), command.begin() + 1, command.end());
  argv.insert(argv.end(), job.args.begin(), job.args.end());
  if (kind == OutputKind::Folder) {
    argv.push_back("-o");
    argv.push_back(job_dir);
  }
  return argv;
}

}  // namespace efc::batch
