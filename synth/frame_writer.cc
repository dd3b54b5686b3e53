#include "synth/frame_writer.h"

#include <algorithm>

namespace efc::synth {

FrameWriter::FrameWriter(FrameWriterConfig config) : config_(std::move(config)) {
  const int n = std::max(1, config_.threads);
  for (int i = 0; i < n; ++i) workers_.emplace_back([this] { work(); });
}

FrameWriter::~FrameWriter() {
  std::string ignored;
  finish(&ignored);
}

void FrameWriter::push(int index, OffscreenRenderer::Views&& views) {
  std::unique_lock<std::mutex> lock(mutex_);
  // A few frames in flight per thread keep every core busy; more only costs memory.
  space_.wait(lock, [&] { return queue_.size() < 2 * workers_.size() + 2; });
  queue_.emplace_back(index, std::move(views));
  ready_.notify_one();
}

bool FrameWriter::finish(std::string* error) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closing_ = true;
    ready_.notify_all();
  }
  for (std::thread& t : workers_)
    if (t.joinable()) t.join();
  workers_.clear();
  std::sort(mask_noise_.begin(), mask_noise_.end(),
            [](const MaskNoiseLog& a, const MaskNoiseLog& b) { return a.frame < b.frame; });
  if (!error_.empty()) *error = error_;
  return error_.empty();
}

void FrameWriter::work() {
  for (;;) {
    std::pair<int, OffscreenRenderer::Views> job;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      ready_.wait(lock, [&] { return closing_ || !queue_.empty(); });
      if (queue_.empty()) return;
      job = std::move(queue_.front());
      queue_.pop_front();
      space_.notify_one();
    }
    std::string error;
    if (!write_frame(job.first, job.second, &error)) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (error_.empty()) error_ = error;
    }
  }
}

bool FrameWriter::write_frame(int index, OffscreenRenderer::Views& v, std::string* error) {
  const FrameWriterConfig& c = config_;
  const std::string name = seq::frame_file(index);
  const size_t n = static_cast<size_t>(v.width) * v.height;

  seq::Image8 rgb;
  rgb.width = v.width, rgb.height = v.height, rgb.channels = 3;
  rgb.pixels = std::move(v.rgb);
  if (!seq::write_png_rgb(c.dir + "/rgb/" + name, rgb, error, c.png_compression)) return false;

  Rng depth_rng(stream_seed(c.seed, static_cast<uint64_t>(index), kDepthStream));
  add_depth_noise(c.noise, c.intrinsics, v.width, v.height, rgb.pixels.data(), &v.depth, depth_rng);
  seq::Image16 depth = quantize_depth(v.depth, v.width, v.height, c.depth_scale);
  if (!seq::write_png_gray16(c.dir + "/depth/" + name, depth, error, c.png_compression)) return false;

  MaskSet masks;
  masks.names = c.mask_names;
  masks.masks.resize(c.mask_names.size());
  for (seq::Image8& m : masks.masks) {
    m.width = v.width, m.height = v.height, m.channels = 1;
    m.pixels.assign(n, 0);
  }
  for (size_t i = 0; i < n; ++i) {
    const int g = v.geom[i];
    if (g < 0 || g >= static_cast<int>(c.geom_mask.size())) continue;
    const int k = c.geom_mask[g];
    if (k >= 0) masks.masks[k].pixels[i] = 255;
  }
  MaskNoiseLog log = add_mask_noise(c.noise, index, &masks, c.swap_pairs, c.seed);
  for (size_t k = 0; k < masks.names.size(); ++k)
    if (!seq::write_png_gray8(c.dir + "/masks/" + masks.names[k] + "/" + name, masks.masks[k], error,
                              c.png_compression))
      return false;

  std::lock_guard<std::mutex> lock(mutex_);
  if (!log.empty()) mask_noise_.push_back(std::move(log));
  if (index == c.preview_frame) {
    preview_rgb_ = std::move(rgb);
    preview_depth_ = std::move(depth);
    preview_masks_ = std::move(masks.masks);
  }
  return true;
}

}  // namespace efc::synth
