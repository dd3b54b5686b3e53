// Turns rendered frames into sequence files on worker threads while the main
// thread simulates and renders the next ones: depth noise and quantisation,
// masks from the segmentation (with mask noise), and the PNGs. Every random
// decision comes from (seed, frame), so the bytes do not depend on which
// thread took which frame.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "harness/render.h"
#include "sequence/sequence.h"
#include "synth/image/noise.h"

namespace efc::synth {

struct FrameWriterConfig {
  std::string dir;                      // the sequence folder being written
  seq::Intrinsics intrinsics;
  double depth_scale = 0.001;
  NoiseParams noise;
  uint64_t seed = 0;
  std::vector<std::string> mask_names;  // masks/<name>/
  std::vector<int> geom_mask;           // model geom id -> index into mask_names, -1 none
  std::vector<std::pair<int, int>> swap_pairs;  // masks that may swap (receptor, effector)
  int png_compression = 2;
  int threads = 1;
  int preview_frame = -1;               // also keep this frame's images for the preview
};

class FrameWriter {
 public:
  explicit FrameWriter(FrameWriterConfig config);
  ~FrameWriter();  // finishes the queue
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  // Queues frame `index` (blocks while too many frames wait, bounding memory).
  void push(int index, OffscreenRenderer::Views&& views);
  // Waits for every queued frame. False with the first error.
  bool finish(std::string* error);

  const std::vector<MaskNoiseLog>& mask_noise() const { return mask_noise_; }  // by frame, after finish
  // The preview frame's RGB, depth and masks (after finish).
  const seq::Image8& preview_rgb() const { return preview_rgb_; }
  const seq::Image16& preview_depth() const { return preview_depth_; }
  const std::vector<seq::Image8>& preview_masks() const { return preview_masks_; }

 private:
  void work();
  bool write_frame(int index, OffscreenRenderer::Views& views, std::string* error);

  FrameWriterConfig config_;
  std::mutex mutex_;
  std::condition_variable ready_, space_;
  std::deque<std::pair<int, OffscreenRenderer::Views>> queue_;
  bool closing_ = false;
  std::string error_;
  std::vector<MaskNoiseLog> mask_noise_;
  seq::Image8 preview_rgb_;
  seq::Image16 preview_depth_;
  std::vector<seq::Image8> preview_masks_;
  std::vector<std::thread> workers_;
};

}  // namespace efc::synth
