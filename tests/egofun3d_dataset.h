// Writes a small dataset in exactly the EgoFun3D layout (the real one is
// gated): real video files encoded with libavcodec (FFV1, lossless RGB), a
// byte-exact .npy, an HDF5 mask file written with the HDF5 API, PLY files
// (ascii mesh, binary point cloud) and the JSON annotations. Two videos:
//   kitchen_01  original 32x24, a knob (revolute) drives a drawer (prismatic):
//               geometry / linear; ascii PLY with faces; uint8 masks
//   lamp 02     an EgoExo4D crop [4, 2] .. [28, 20) of a 32x24 frame, a push
//               button (translation) lights a bulb (no articulation: fixed):
//               illumination / binary; binary PLY without faces; bool masks
#pragma once

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}
#include <hdf5.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace egofun3d_test {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kOrigW = 32, kOrigH = 24, kFrames = 6;
constexpr int kCropX0 = 4, kCropY0 = 2, kCropX1 = 28, kCropY1 = 20;

// The RGB the test encodes at frame t (and expects back).
inline std::array<uint8_t, 3> pixel(int video, int x, int y, int t) {
  return {static_cast<uint8_t>(x * 7 + t * 13 + video * 50), static_cast<uint8_t>(y * 11 + t * 3),
          static_cast<uint8_t>((x + y) * 5 + video * 90)};
}
// Mask of a part at frame t in the ORIGINAL frame: a small moving rectangle.
inline bool mask_at(int part, int x, int y, int t) {
  const int x0 = 3 + part * 8 + t, y0 = 4 + part * 3;
  return x >= x0 && x < x0 + 6 && y >= y0 && y < y0 + 5;
}

// Camera-to-world of frame t: a rotation about an axis tilted off z (so all
// quaternion components are non-zero) and a moving position.
inline std::array<double, 16> camera(int t) {
  const double angle = 0.3 + 0.2 * t;
  double ax = 0.3, ay = -0.5, az = 0.8;
  const double n = std::sqrt(ax * ax + ay * ay + az * az);
  ax /= n, ay /= n, az /= n;
  const double c = std::cos(angle), s = std::sin(angle), C = 1 - c;
  return {c + ax * ax * C,      ax * ay * C - az * s, ax * az * C + ay * s, 0.1 * t,
          ay * ax * C + az * s, c + ay * ay * C,      ay * az * C - ax * s, 1.0 - 0.05 * t,
          az * ax * C - ay * s, az * ay * C + ax * s, c + az * az * C,      1.5,
          0,                    0,                    0,                    1};
}

inline void write_text(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

// FFV1 in Matroska/AVI, pixels stored as 0RGB32: lossless, so the decoded
// frames must equal these bytes.
inline bool write_video(const fs::path& path, int video, int width, int height, int x0, int y0, int frames,
                        int fps) {
  fs::create_directories(path.parent_path());
  const AVCodec* codec = avcodec_find_encoder(AV_CODEC_ID_FFV1);
  if (!codec) return false;
  AVFormatContext* fmt = nullptr;
  if (avformat_alloc_output_context2(&fmt, nullptr, nullptr, path.c_str()) < 0) return false;
  AVStream* st = avformat_new_stream(fmt, nullptr);
  AVCodecContext* ctx = avcodec_alloc_context3(codec);
  ctx->width = width;
  ctx->height = height;
  ctx->pix_fmt = AV_PIX_FMT_0RGB32;
  ctx->time_base = {1, fps};
  ctx->framerate = {fps, 1};
  if (fmt->oformat->flags & AVFMT_GLOBALHEADER) ctx->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  if (avcodec_open2(ctx, codec, nullptr) < 0) return false;
  avcodec_parameters_from_context(st->codecpar, ctx);
  st->time_base = ctx->time_base;
  st->avg_frame_rate = {fps, 1};
  if (avio_open(&fmt->pb, path.c_str(), AVIO_FLAG_WRITE) < 0) return false;
  if (avformat_write_header(fmt, nullptr) < 0) return false;
  SwsContext* sws = sws_getContext(width, height, AV_PIX_FMT_RGB24, width, height, AV_PIX_FMT_0RGB32, SWS_POINT,
                                   nullptr, nullptr, nullptr);
  AVFrame* frame = av_frame_alloc();
  frame->format = ctx->pix_fmt;
  frame->width = width;
  frame->height = height;
  av_frame_get_buffer(frame, 0);
  AVPacket* pkt = av_packet_alloc();
  auto drain = [&] {
    while (avcodec_receive_packet(ctx, pkt) == 0) {
      av_packet_rescale_ts(pkt, ctx->time_base, st->time_base);
      pkt->stream_index = st->index;
      av_interleaved_write_frame(fmt, pkt);
    }
  };
  std::vector<uint8_t> rgb(static_cast<size_t>(width) * height * 3);
  for (int t = 0; t < frames; ++t) {
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const auto p = pixel(video, x + x0, y + y0, t);
        std::memcpy(&rgb[(static_cast<size_t>(y) * width + x) * 3], p.data(), 3);
      }
    av_frame_make_writable(frame);
    const uint8_t* src[1] = {rgb.data()};
    const int src_stride[1] = {width * 3};
    sws_scale(sws, src, src_stride, 0, height, frame->data, frame->linesize);
    frame->pts = t;
    avcodec_send_frame(ctx, frame);
    drain();
  }
  avcodec_send_frame(ctx, nullptr);
  drain();
  av_write_trailer(fmt);
  av_packet_free(&pkt);
  av_frame_free(&frame);
  sws_freeContext(sws);
  avcodec_free_context(&ctx);
  avio_closep(&fmt->pb);
  avformat_free_context(fmt);
  return true;
}

// NumPy .npy version 1.0, '<f8', C order; `shape` as Python writes it.
inline void write_npy(const fs::path& path, const std::vector<double>& values, const std::string& shape) {
  std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': " + shape + ", }";
  while ((10 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string out = "\x93NUMPY";
  out += '\x01';
  out += '\x00';
  out += static_cast<char>(header.size() & 0xff);
  out += static_cast<char>(header.size() >> 8);
  out += header;
  out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(double));
  write_text(path, out);
}

struct MaskSpec {
  std::string label;
  int mask_idx;
  int part;      // which rectangle (mask_at)
  bool as_bool;  // h5py's bool (an int8 enum FALSE/TRUE) rather than uint8
};

inline void write_h5(const fs::path& path, const std::vector<MaskSpec>& groups, int frames, int height, int width) {
  fs::create_directories(path.parent_path());
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  for (const MaskSpec& g : groups) {
    const hid_t grp = H5Gcreate2(file, g.label.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const hid_t scalar = H5Screate(H5S_SCALAR);
    const hid_t attr = H5Acreate2(grp, "mask_idx", H5T_STD_I64LE, scalar, H5P_DEFAULT, H5P_DEFAULT);
    const long long idx = g.mask_idx;
    H5Awrite(attr, H5T_NATIVE_LLONG, &idx);
    H5Aclose(attr);
    H5Sclose(scalar);
    const hsize_t dims[3] = {static_cast<hsize_t>(frames), static_cast<hsize_t>(height), static_cast<hsize_t>(width)};
    const hid_t space = H5Screate_simple(3, dims, nullptr);
    hid_t type = H5T_STD_U8LE;
    if (g.as_bool) {
      type = H5Tenum_create(H5T_NATIVE_INT8);
      int8_t v = 0;
      H5Tenum_insert(type, "FALSE", &v);
      v = 1;
      H5Tenum_insert(type, "TRUE", &v);
    }
    // Chunked and compressed, as h5py writes large arrays.
    const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    const hsize_t chunk[3] = {2, static_cast<hsize_t>(height), static_cast<hsize_t>(width)};
    H5Pset_chunk(dcpl, 3, chunk);
    H5Pset_deflate(dcpl, 4);
    const hid_t dset = H5Dcreate2(grp, "masks", type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    std::vector<uint8_t> data(static_cast<size_t>(frames) * height * width);
    for (int t = 0; t < frames; ++t)
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
          data[(static_cast<size_t>(t) * height + y) * width + x] = mask_at(g.part, x, y, t) ? 1 : 0;
    H5Dwrite(dset, g.as_bool ? type : H5T_NATIVE_UCHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data());
    H5Dclose(dset);
    H5Pclose(dcpl);
    if (g.as_bool) H5Tclose(type);
    H5Sclose(space);
    H5Gclose(grp);
  }
  H5Fclose(file);
}

// Three boxes: base (vertices 0-7), receptor (8-15), effector (16-23).
inline std::vector<std::array<double, 3>> box_vertices(std::array<double, 3> lo, std::array<double, 3> hi) {
  std::vector<std::array<double, 3>> v;
  for (int i = 0; i < 8; ++i) v.push_back({i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]});
  return v;
}
inline std::vector<std::array<int, 3>> box_faces(int o) {
  // Outward-facing triangles of the box whose corner i has bits (x, y, z).
  const int f[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                        {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  std::vector<std::array<int, 3>> out;
  for (const auto& t : f) out.push_back({t[0] + o, t[1] + o, t[2] + o});
  return out;
}
inline std::vector<std::array<double, 3>> scene_vertices() {
  auto v = box_vertices({0, 0, 0}, {0.6, 0.4, 0.5});
  for (const auto& p : box_vertices({0.25, 0.4, 0.35}, {0.3, 0.43, 0.4})) v.push_back(p);
  for (const auto& p : box_vertices({0.05, 0.4, 0.05}, {0.55, 0.42, 0.3})) v.push_back(p);
  return v;
}

inline void write_ply_ascii(const fs::path& path) {
  const auto v = scene_vertices();
  std::string s = "ply\nformat ascii 1.0\ncomment written by egofun3d_import_test\nelement vertex " +
                  std::to_string(v.size()) +
                  "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\n"
                  "property uchar blue\nelement face 36\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : v) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "%g %g %g 200 100 50\n", p[0], p[1], p[2]);
    s += buf;
  }
  for (int b = 0; b < 3; ++b)
    for (const auto& t : box_faces(b * 8))
      s += "3 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + "\n";
  write_text(path, s);
}

inline void write_ply_binary_points(const fs::path& path) {
  const auto v = scene_vertices();
  std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(v.size()) +
                  "\nproperty double x\nproperty double y\nproperty double z\nproperty float nx\nend_header\n";
  for (const auto& p : v) {
    s.append(reinterpret_cast<const char*>(p.data()), 24);
    const float nx = 1.0f;
    s.append(reinterpret_cast<const char*>(&nx), 4);
  }
  write_text(path, s);
}

inline std::vector<int> range_of(int a, int b) {
  std::vector<int> out;
  for (int i = a; i < b; ++i) out.push_back(i);
  return out;
}

// Knobs for the bad-input tests.
struct Faults {
  bool npy_wrong_shape = false;      // kitchen_01: (N, 3, 4)
  bool h5_t_mismatch = false;        // kitchen_01: masks with one frame too few
  bool missing_video = false;        // lamp 02: no video file
  bool bad_function_json = false;    // functions.json is not JSON (both videos fail)
  bool receptor_unarticulated = false;  // kitchen_01: no articulation for the knob
};

inline json metadata_entry(const std::string& name, const std::string& source, json id, const std::string& stem,
                           const std::string& cropped_video, const std::string& original_video,
                           const std::string& geometry_type, const std::string& ply, const std::string& articulation) {
  return {{"video_name", name},
          {"source", source},
          {"function_instance_id", id},
          {"cropped_video_path", cropped_video},
          {"original_video_path", original_video},
          {"camera_extrinsics_path", "cameras/" + stem + "/extrinsics.npy"},
          {"camera_intrinsics_path", "cameras/" + stem + "/intrinsics.json"},
          {"video_mask_path", "masks/" + stem + ".h5"},
          {"geometry_type", geometry_type},
          {"geometry_path", ply},
          {"part_annotation_path", "annotations/parts.json"},
          {"articulation_path", articulation},
          {"function_annotation_path", "annotations/functions.json"}};
}

inline bool write_dataset(const fs::path& ds, const Faults& faults = {}) {
  const int fps = 10;
  // Videos.
  if (!write_video(ds / "videos/kitchen_01.mkv", 0, kOrigW, kOrigH, 0, 0, kFrames, fps)) return false;
  if (!faults.missing_video &&
      !write_video(ds / "videos/lamp_02_cropped.avi", 1, kCropX1 - kCropX0, kCropY1 - kCropY0, kCropX0, kCropY0,
                   kFrames, fps))
    return false;
  // Cameras.
  std::vector<double> m;
  for (int t = 0; t < kFrames; ++t)
    for (double x : camera(t)) m.push_back(x);
  if (faults.npy_wrong_shape) {
    std::vector<double> m34;
    for (int t = 0; t < kFrames; ++t)
      for (int k = 0; k < 12; ++k) m34.push_back(camera(t)[k]);
    write_npy(ds / "cameras/kitchen_01/extrinsics.npy", m34, "(" + std::to_string(kFrames) + ", 3, 4)");
  } else {
    write_npy(ds / "cameras/kitchen_01/extrinsics.npy", m, "(" + std::to_string(kFrames) + ", 4, 4)");
  }
  write_npy(ds / "cameras/lamp_02/extrinsics.npy", m, "(" + std::to_string(kFrames) + ", 4, 4)");
  const json k_full = {{20.0, 0.0, 15.5}, {0.0, 21.0, 11.5}, {0.0, 0.0, 1.0}};
  write_text(ds / "cameras/kitchen_01/intrinsics.json",
             json{{"undistorted_intrinsics", k_full}, {"original_frame_size", {kOrigW, kOrigH}}}.dump(2));
  write_text(ds / "cameras/lamp_02/intrinsics.json",
             json{{"undistorted_intrinsics", k_full},
                  {"original_frame_size", {kOrigW, kOrigH}},
                  {"cropped_intrinsics", {{20.0, 0.0, 11.5}, {0.0, 21.0, 9.5}, {0.0, 0.0, 1.0}}},
                  {"cropped_top_left", {kCropX0, kCropY0}},
                  {"cropped_bottom_right", {kCropX1, kCropY1}}}
                 .dump(2));
  // Masks (full original frames).
  write_h5(ds / "masks/kitchen_01.h5",
           {{"stove knob", 3, 0, false}, {"drawer", 4, 1, false}, {"kitchen cabinet", 5, 2, false}},
           faults.h5_t_mismatch ? kFrames - 1 : kFrames, kOrigH, kOrigW);
  write_h5(ds / "masks/lamp_02.h5", {{"button", 3, 0, true}, {"bulb", 4, 1, true}}, kFrames, kOrigH, kOrigW);
  // Geometry.
  write_ply_ascii(ds / "geometry/kitchen_01.ply");
  write_ply_binary_points(ds / "geometry/lamp_02.ply");
  // Annotations.
  write_text(ds / "annotations/parts.json",
             json::array({{{"function_instance_id", 7},
                           {"receptor", {{"label", "stove knob"}, {"indices", range_of(8, 16)}, {"pid", 1}}},
                           {"effector", {{"label", "drawer"}, {"indices", range_of(16, 24)}, {"pid", 2}}},
                           {"description", "turning the knob opens the drawer"}},
                          {{"function_instance_id", 12},
                           {"receptor", {{"label", "button"}, {"indices", range_of(8, 16)}, {"pid", 3}}},
                           {"effector", {{"label", "bulb"}, {"indices", range_of(16, 24)}, {"pid", 4}}},
                           {"description", "the button lights the bulb"}}})
                 .dump(2));
  json kitchen_joints = json::array();
  if (!faults.receptor_unarticulated)
    kitchen_joints.push_back({{"pid", 1}, {"type", "revolute"}, {"axis", {0, 1, 0}}, {"origin", {0.275, 0.42, 0.375}},
                              {"rangeMin", 0}, {"rangeMax", 1.5}});
  kitchen_joints.push_back(
      {{"pid", 2}, {"type", "prismatic"}, {"axis", {0, 2, 0}}, {"origin", {0, 0, 0}}, {"rangeMin", 0}, {"rangeMax", 0.3}});
  write_text(ds / "annotations/articulation_kitchen_01.json", kitchen_joints.dump(2));
  write_text(ds / "annotations/articulation_lamp_02.json",
             json::array({{{"pid", 3}, {"type", "translation"}, {"axis", {0, -1, 0}}, {"origin", {0.27, 0.4, 0.37}},
                           {"rangeMin", 0}, {"rangeMax", 0.005}}})
                 .dump(2));
  if (faults.bad_function_json)
    write_text(ds / "annotations/functions.json", "[\n  {\"function_instance_id\": 7, \"physics\": \"geometry\",\n");
  else
    write_text(ds / "annotations/functions.json",
               json::array({{{"function_instance_id", 7}, {"physics", "geometry"}, {"func", "linear"}},
                            {{"function_instance_id", "12"}, {"physics", "Illumination"}, {"func", "binary"}}})
                   .dump(2));
  write_text(ds / "dataset_metadata.json",
             json::array({metadata_entry("kitchen_01", "hoi4d", 7, "kitchen_01", "", "videos/kitchen_01.mkv", "mesh",
                                         "geometry/kitchen_01.ply", "annotations/articulation_kitchen_01.json"),
                          metadata_entry("lamp 02", "egoexo4d", "12", "lamp_02", "videos/lamp_02_cropped.avi",
                                         "videos/lamp_02_original.mp4", "point cloud", "geometry/lamp_02.ply",
                                         "annotations/articulation_lamp_02.json")})
                 .dump(2));
  return true;
}

}  // namespace egofun3d_test
