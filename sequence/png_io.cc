// PNG frames through libpng. libpng reports errors by longjmp: every function
// that calls into it with a setjmp below keeps C++ objects with destructors
// out of its frame (they would be skipped), and the error text reaches the
// caller through a plain struct. Reading converts no pixel format: a frame of
// the wrong kind is reported, never silently reinterpreted.
#include <png.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <new>

#include "sequence/sequence.h"

namespace efc::seq {
namespace {

// A frame claiming more pixels than this is refused before allocating:
// a corrupt header must not ask for gigabytes.
constexpr unsigned long long kMaxPixels = 1ull << 28;

struct ErrorText {
  char text[200];
};

void on_error(png_structp png, png_const_charp msg) {
  auto* e = static_cast<ErrorText*>(png_get_error_ptr(png));
  std::snprintf(e->text, sizeof e->text, "%s", msg);
  png_longjmp(png, 1);
}
// Warnings (a bad ancillary chunk, an odd sRGB profile) do not affect the
// pixels; printing them would garble a progress line.
void on_warning(png_structp, png_const_charp) {}

std::string kind_name(int bit_depth, int color_type) {
  const char* kind = "unknown colour type";
  switch (color_type) {
    case PNG_COLOR_TYPE_GRAY: kind = "grey"; break;
    case PNG_COLOR_TYPE_GRAY_ALPHA: kind = "grey+alpha"; break;
    case PNG_COLOR_TYPE_RGB: kind = "RGB"; break;
    case PNG_COLOR_TYPE_RGBA: kind = "RGBA"; break;
    case PNG_COLOR_TYPE_PALETTE: kind = "palette"; break;
  }
  return std::to_string(bit_depth) + "-bit " + kind;
}

bool little_endian() {
  const uint16_t one = 1;
  unsigned char first = 0;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

struct Header {
  png_uint_32 width = 0, height = 0;
  int bit_depth = 0, color_type = 0;
};

// Only PODs in the frames below setjmp.
bool read_header(png_structp png, png_infop info, FILE* fp, Header* h) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_init_io(png, fp);
  png_set_sig_bytes(png, 8);
  png_read_info(png, info);
  h->width = png_get_image_width(png, info);
  h->height = png_get_image_height(png, info);
  h->bit_depth = png_get_bit_depth(png, info);
  h->color_type = png_get_color_type(png, info);
  return true;
}

bool read_rows(png_structp png, png_infop info, png_bytep* rows, bool swap16) {
  if (setjmp(png_jmpbuf(png))) return false;
  if (swap16) png_set_swap(png);  // PNG stores 16-bit samples big-endian
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  png_read_image(png, rows);
  png_read_end(png, nullptr);  // a truncated file fails here, not silently
  return true;
}

// Reads a PNG of exactly (bit_depth, color_type) into `pixels` (T: uint8_t or
// uint16_t, `channels` samples per pixel).
template <typename T>
bool read_png(const std::string& path, int bit_depth, int color_type, int channels, int* width,
              int* height, std::vector<T>* pixels, std::string* error) {
  FILE* fp = std::fopen(path.c_str(), "rb");
  if (!fp) {
    *error = errno == ENOENT ? "does not exist" : std::string("cannot be opened (") + std::strerror(errno) + ")";
    return false;
  }
  unsigned char sig[8];
  if (std::fread(sig, 1, 8, fp) != 8 || png_sig_cmp(sig, 0, 8) != 0) {
    std::fclose(fp);
    *error = "is not a PNG file";
    return false;
  }
  ErrorText err{};
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &err, on_error, on_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  bool ok = png && info;
  if (!ok) *error = "cannot be read (out of memory)";
  Header h;
  if (ok && !(ok = read_header(png, info, fp, &h))) *error = std::string("is corrupt (") + err.text + ")";
  if (ok && (h.bit_depth != bit_depth || h.color_type != color_type)) {
    *error = "is " + kind_name(h.bit_depth, h.color_type) + ", expected " + kind_name(bit_depth, color_type);
    ok = false;
  }
  if (ok && static_cast<unsigned long long>(h.width) * h.height > kMaxPixels) {
    *error = "is " + std::to_string(h.width) + "x" + std::to_string(h.height) + ", too large to read";
    ok = false;
  }
  std::vector<png_bytep> rows;
  if (ok) {
    try {
      const size_t stride = static_cast<size_t>(h.width) * channels;
      pixels->assign(stride * h.height, 0);
      rows.resize(h.height);
      for (png_uint_32 y = 0; y < h.height; ++y)
        rows[y] = reinterpret_cast<png_bytep>(pixels->data() + stride * y);
    } catch (const std::bad_alloc&) {
      *error = "cannot be read (out of memory)";
      ok = false;
    }
  }
  if (ok && !(ok = read_rows(png, info, rows.data(), bit_depth == 16 && little_endian())))
    *error = std::string("is corrupt (") + err.text + ")";
  if (png) png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
  std::fclose(fp);
  if (!ok) {
    pixels->clear();
    return false;
  }
  *width = static_cast<int>(h.width);
  *height = static_cast<int>(h.height);
  return true;
}

// Low levels are for speed (synth writes several PNGs per frame): a single
// cheap filter there; the adaptive choice only where size matters more.
int filters_for(int level) {
  if (level == 0) return PNG_FILTER_NONE;
  if (level <= 5) return PNG_FILTER_SUB;
  return PNG_ALL_FILTERS;
}

bool write_rows(FILE* fp, png_bytep* rows, int width, int height, int bit_depth, int color_type,
                int level, bool swap16, ErrorText* err) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, err, on_error, on_warning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, fp);
  png_set_compression_level(png, level);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, filters_for(level));
  png_set_IHDR(png, info, width, height, bit_depth, color_type, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  if (swap16) png_set_swap(png);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

template <typename T>
bool write_png(const std::string& path, const T* pixels, size_t count, int width, int height,
               int channels, int bit_depth, int color_type, int compression, std::string* error) {
  if (width < 1 || height < 1) {
    *error = "cannot write an empty image (" + std::to_string(width) + "x" + std::to_string(height) + ")";
    return false;
  }
  if (count != static_cast<size_t>(width) * height * channels) {
    *error = "image of " + std::to_string(width) + "x" + std::to_string(height) + "x" +
             std::to_string(channels) + " has " + std::to_string(count) + " samples";
    return false;
  }
  if (compression < 0 || compression > 9) {
    *error = "PNG compression level " + std::to_string(compression) + " is not 0-9";
    return false;
  }
  FILE* fp = std::fopen(path.c_str(), "wb");
  if (!fp) {
    *error = "cannot write " + path + " (" + std::strerror(errno) + ")";
    return false;
  }
  const size_t stride = static_cast<size_t>(width) * channels;
  std::vector<png_bytep> rows(height);
  for (int y = 0; y < height; ++y)
    rows[y] = reinterpret_cast<png_bytep>(const_cast<T*>(pixels + stride * y));
  ErrorText err{};
  bool ok = write_rows(fp, rows.data(), width, height, bit_depth, color_type, compression,
                       bit_depth == 16 && little_endian(), &err);
  ok = std::fclose(fp) == 0 && ok;
  if (!ok) {
    *error = "cannot write " + path + (err.text[0] ? std::string(" (") + err.text + ")" : " (disk full?)");
    std::remove(path.c_str());  // no half-written frame left behind
  }
  return ok;
}

}  // namespace

bool read_png_rgb(const std::string& path, Image8* out, std::string* error) {
  out->channels = 3;
  return read_png(path, 8, PNG_COLOR_TYPE_RGB, 3, &out->width, &out->height, &out->pixels, error);
}

bool read_png_gray8(const std::string& path, Image8* out, std::string* error) {
  out->channels = 1;
  return read_png(path, 8, PNG_COLOR_TYPE_GRAY, 1, &out->width, &out->height, &out->pixels, error);
}

bool read_png_gray16(const std::string& path, Image16* out, std::string* error) {
  return read_png(path, 16, PNG_COLOR_TYPE_GRAY, 1, &out->width, &out->height, &out->pixels, error);
}

bool write_png_rgb(const std::string& path, const Image8& img, std::string* error, int compression) {
  if (img.channels != 3) {
    *error = "write_png_rgb: the image has " + std::to_string(img.channels) + " channels, not 3";
    return false;
  }
  return write_png(path, img.pixels.data(), img.pixels.size(), img.width, img.height, 3, 8,
                   PNG_COLOR_TYPE_RGB, compression, error);
}

bool write_png_gray8(const std::string& path, const Image8& img, std::string* error, int compression) {
  if (img.channels != 1) {
    *error = "write_png_gray8: the image has " + std::to_string(img.channels) + " channels, not 1";
    return false;
  }
  return write_png(path, img.pixels.data(), img.pixels.size(), img.width, img.height, 1, 8,
                   PNG_COLOR_TYPE_GRAY, compression, error);
}

bool write_png_gray16(const std::string& path, const Image16& img, std::string* error, int compression) {
  return write_png(path, img.pixels.data(), img.pixels.size(), img.width, img.height, 1, 16,
                   PNG_COLOR_TYPE_GRAY, compression, error);
}

}  // namespace efc::seq
