#include "pipeline/templates/vlm_images.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

namespace efc::pipeline {
namespace {

void tint(seq::Image8& img, const seq::Image8& mask, const int rgb[3]) {
  if (mask.width != img.width || mask.height != img.height) return;
  for (size_t i = 0; i < mask.pixels.size(); ++i)
    if (mask.pixels[i])
      for (int c = 0; c < 3; ++c)
        img.pixels[3 * i + c] = static_cast<uint8_t>((img.pixels[3 * i + c] + rgb[c]) / 2);
}

// PNG bytes by way of a private temporary file (the sequence library writes files).
std::string png_bytes(const seq::Image8& img) {
  static std::atomic<int> serial{0};
  const std::filesystem::path p = std::filesystem::temp_directory_path() /
                                  ("efc_vlm_" + std::to_string(::getpid()) + "_" + std::to_string(serial++) + ".png");
  std::string error, out;
  if (seq::write_png_rgb(p.string(), img, &error, 6)) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    out = ss.str();
  }
  std::error_code ec;
  std::filesystem::remove(p, ec);
  return out;
}

}  // namespace

std::vector<std::string> vlm_frames(const TemplateInput& input, const std::string& receptor,
                                    const std::string& effector, const std::vector<double>& s_R) {
  std::vector<std::string> out;
  if (!input.sequence) return out;
  const int N = input.sequence->meta().frames;
  if (N <= 0) return out;
  int lo = 0, hi = 0;
  for (int i = 0; i < std::min<int>(N, static_cast<int>(s_R.size())); ++i) {
    if (!std::isfinite(s_R[i])) continue;
    if (!std::isfinite(s_R[lo]) || s_R[i] < s_R[lo]) lo = i;
    if (!std::isfinite(s_R[hi]) || s_R[i] > s_R[hi]) hi = i;
  }
  std::vector<int> frames = {lo, hi, N - 1};
  if (frames[0] == frames[1]) frames = {0, N / 2, N - 1};
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  const int green[3] = {0, 255, 0}, magenta[3] = {255, 0, 255};
  for (int f : frames) {
    Diagnostics quiet;
    seq::Image8 img, m;
    if (!input.sequence->read_rgb(f, quiet, &img)) continue;
    const auto& names = input.sequence->mask_names();
    if (std::binary_search(names.begin(), names.end(), receptor) && input.sequence->read_mask(receptor, f, quiet, &m))
      tint(img, m, green);
    if (std::binary_search(names.begin(), names.end(), effector) && input.sequence->read_mask(effector, f, quiet, &m))
      tint(img, m, magenta);
    std::string png = png_bytes(img);
    if (!png.empty()) out.push_back(std::move(png));
  }
  return out;
}

}  // namespace efc::pipeline
