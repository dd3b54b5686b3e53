// The recording itself: any video FFmpeg's libraries decode (EgoFun3D ships
// .mp4), frame by frame as 8-bit RGB. Frames are handed out as they are
// decoded, so a long video never sits in memory whole.
#pragma once

#include <memory>
#include <string>

#include "sequence/sequence.h"

namespace efc::egofun3d {

class VideoReader {
 public:
  VideoReader();
  ~VideoReader();
  VideoReader(const VideoReader&) = delete;
  VideoReader& operator=(const VideoReader&) = delete;

  // Opens the file and its best video stream. False with *error (worded to
  // follow the file's name: "does not exist", "has no video stream", ...).
  bool open(const std::string& path, std::string* error);
  double fps() const;  // the stream's average frame rate (its nominal rate when unknown)
  int width() const;
  int height() const;

  // The next frame as RGB24. False at the end (*error empty) or on a
  // decoding error (*error set). Every frame must have the first's size.
  bool next(seq::Image8* out, std::string* error);

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace efc::egofun3d
