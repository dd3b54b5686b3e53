// efc-degrade-masks: a copy of a sequence whose part masks are much worse than
// a realistic segmenter's, for bench/infer_suite_eval (bench/README.md).
//
//   efc-degrade-masks SEQ OUT [--seed S] [--radius R] [--miss P] [--swap P] [--copy]
//
// OUT gets the same files as SEQ, hard-linked (symlinked where the file system
// refuses a hard link; copied with --copy), except masks/<part>/*.png, which
// are written anew: each frame's masks pass through synth's add_mask_noise
// (synth/image/noise.h) with a stronger NoiseParams: erosion or dilation by
// 0..R pixels (default 6), a mask emptied for a frame with probability P
// (default 0.15), and the receptor's and effector's masks of one function
// exchanged for a frame with probability P (default 0.08). The hand mask
// (role "hand") is left as it is. Seeded: the same SEQ and seed give the same
// masks. Exit 0 ok, 1 the sequence cannot be read, 2 usage or a file error.
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "compiler/diagnostics.h"
#include "sequence/sequence.h"
#include "synth/image/noise.h"

namespace fs = std::filesystem;

namespace {

int usage() {
  std::fprintf(stderr,
               "usage: efc-degrade-masks SEQ OUT [--seed S] [--radius R] [--miss P] [--swap P] [--copy]\n"
               "  a copy of SEQ (hard links) whose part masks are degraded: erosion/dilation by\n"
               "  0..R px (default 6), dropped frames (P default 0.15), identity swaps (default 0.08)\n");
  return 2;
}

// Hard link, else symlink, else copy (or copy when asked).
bool link_file(const fs::path& from, const fs::path& to, bool copy, std::string* error) {
  std::error_code ec;
  if (!copy) {
    fs::create_hard_link(from, to, ec);
    if (!ec) return true;
    fs::create_symlink(fs::absolute(from), to, ec);
    if (!ec) return true;
  }
  fs::copy_file(from, to, fs::copy_options::overwrite_existing, ec);
  if (ec) *error = to.string() + ": " + ec.message();
  return !ec;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> positional;
  uint64_t seed = 0;
  bool copy = false;
  efc::synth::NoiseParams params;
  params.level = efc::synth::NoiseLevel::Realistic;
  params.mask_radius_px = 6;
  params.mask_miss_prob = 0.15;
  params.mask_swap_prob = 0.08;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const char* name) -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "efc-degrade-masks: %s needs a value\n", name);
        std::exit(usage());
      }
      return argv[++i];
    };
    if (a == "--seed") seed = std::strtoull(value("--seed"), nullptr, 10);
    else if (a == "--radius") params.mask_radius_px = std::atoi(value("--radius"));
    else if (a == "--miss") params.mask_miss_prob = std::atof(value("--miss"));
    else if (a == "--swap") params.mask_swap_prob = std::atof(value("--swap"));
    else if (a == "--copy") copy = true;
    else if (a == "-h" || a == "--help") return usage();
    else if (!a.empty() && a[0] == '-') return usage();
    else positional.push_back(a);
  }
  if (positional.size() != 2) return usage();
  const fs::path src = positional[0], dst = positional[1];

  efc::Diagnostics diags;
  efc::seq::Sequence sequence;
  if (!sequence.open(src.string(), diags)) {
    for (const efc::Diagnostic& d : diags.items()) std::fprintf(stderr, "%s\n", efc::format_text(d).c_str());
    return 1;
  }
  const efc::seq::Meta& meta = sequence.meta();
  std::error_code ec;
  if (fs::exists(dst)) {
    std::fprintf(stderr, "efc-degrade-masks: %s exists; remove it first\n", dst.c_str());
    return 2;
  }
  // Built beside OUT and renamed: all or nothing (a resumed run sees either a
  // whole copy or none).
  const fs::path tmp = dst.string() + ".partial";
  fs::remove_all(tmp, ec);
  fs::create_directories(tmp, ec);
  if (ec) {
    std::fprintf(stderr, "efc-degrade-masks: cannot create %s: %s\n", tmp.c_str(), ec.message().c_str());
    return 2;
  }

  // The masks to degrade: every mask folder but the hand's.
  std::vector<std::string> names;
  for (const std::string& m : sequence.mask_names()) {
    std::string role;
    for (const auto& [part, r] : meta.parts)
      if (part == m) role = r;
    if (m != "hand" && role != "hand") names.push_back(m);
  }
  std::vector<std::pair<int, int>> swap_pairs;
  auto index_of = [&](const std::string& n) {
    auto it = std::find(names.begin(), names.end(), n);
    return it == names.end() ? -1 : static_cast<int>(it - names.begin());
  };
  for (const efc::seq::FunctionRef& f : meta.functions) {
    const int r = index_of(f.receptor), e = index_of(f.effector);
    if (r >= 0 && e >= 0 && r != e) swap_pairs.push_back({r, e});
  }

  // Every file but the degraded masks: linked.
  std::string error;
  for (auto it = fs::recursive_directory_iterator(src); it != fs::recursive_directory_iterator(); ++it) {
    const fs::path rel = fs::relative(it->path(), src);
    auto first = rel.begin();
    const bool degraded_dir = first != rel.end() && *first == "masks" && std::next(first) != rel.end() &&
                              index_of(std::next(first)->string()) >= 0;
    const fs::path out = tmp / rel;
    if (it->is_directory()) {
      fs::create_directories(out, ec);
      continue;
    }
    if (degraded_dir) continue;
    if (!link_file(it->path(), out, copy, &error)) {
      std::fprintf(stderr, "efc-degrade-masks: %s\n", error.c_str());
      fs::remove_all(tmp, ec);
      return 2;
    }
  }

  // The masks, frame by frame on every core.
  std::atomic<int> next{0}, failed{0};
  std::atomic<long> swapped{0}, missed{0};
  auto worker = [&]() {
    efc::Diagnostics local;
    for (int f = next++; f < meta.frames && !failed; f = next++) {
      efc::synth::MaskSet set;
      set.names = names;
      set.masks.resize(names.size());
      for (size_t k = 0; k < names.size(); ++k)
        if (!sequence.read_mask(names[k], f, local, &set.masks[k])) {
          ++failed;
          return;
        }
      const efc::synth::MaskNoiseLog log = efc::synth::add_mask_noise(params, f, &set, swap_pairs, seed);
      swapped += static_cast<long>(log.swapped.size());
      missed += static_cast<long>(log.missed.size());
      for (size_t k = 0; k < names.size(); ++k) {
        std::string err;
        const fs::path out = tmp / "masks" / names[k] / efc::seq::frame_file(f);
        if (!efc::seq::write_png_gray8(out.string(), set.masks[k], &err, 1)) {
          std::fprintf(stderr, "efc-degrade-masks: %s: %s\n", out.c_str(), err.c_str());
          ++failed;
          return;
        }
      }
    }
  };
  const unsigned cores = std::max(1u, std::min(4u, std::thread::hardware_concurrency()));
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < cores; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (failed) {
    std::fprintf(stderr, "efc-degrade-masks: could not read or write the masks of %s\n", src.c_str());
    fs::remove_all(tmp, ec);
    return 2;
  }
  fs::rename(tmp, dst, ec);
  if (ec) {
    std::fprintf(stderr, "efc-degrade-masks: cannot rename %s: %s\n", tmp.c_str(), ec.message().c_str());
    return 2;
  }
  std::printf("%s: %zu masks x %d frames degraded (radius %d, miss %.3f: %ld, swap %.3f: %ld)\n", dst.c_str(),
              names.size(), meta.frames, params.mask_radius_px, params.mask_miss_prob, missed.load(),
              params.mask_swap_prob, swapped.load());
  return 0;
}
