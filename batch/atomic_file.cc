#include "batch/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace efc::batch {

namespace fs = std::filesystem;

namespace {

std::string host_name() {
  char buf[256] = {0};
  if (gethostname(buf, sizeof buf - 1) != 0) return "host";
  std::string h;
  for (const char* p = buf; *p; ++p) h += std::isalnum(static_cast<unsigned char>(*p)) ? *p : '_';
  return h.empty() ? "host" : h;
}

}  // namespace

bool write_file_atomically(const std::string& path, const std::string& bytes, std::string* error) {
  static std::atomic<unsigned> counter{0};
  const fs::path target(path);
  // Shards on several nodes may write into one shared folder: the host name
  // keeps two processes with the same pid apart.
  const fs::path tmp = target.parent_path() / (std::string(kTempPrefix) + host_name() + "-" + std::to_string(getpid()) +
                                               "-" + std::to_string(counter++) + "-" + target.filename().string());
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    *error = "cannot create " + tmp.string() + ": " + std::strerror(errno);
    return false;
  }
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      *error = "cannot write " + tmp.string() + ": " + std::strerror(errno);
      ::close(fd);
      ::unlink(tmp.c_str());
      return false;
    }
    done += static_cast<size_t>(n);
  }
  // fsync before rename: after a power cut the name points at whole data or
  // at the previous file, never at an empty one.
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    *error = "cannot write " + tmp.string() + ": " + std::strerror(errno);
    ::unlink(tmp.c_str());
    return false;
  }
  if (::rename(tmp.c_str(), target.c_str()) != 0) {
    *error = "cannot rename " + tmp.string() + " to " + path + ": " + std::strerror(errno);
    ::unlink(tmp.c_str());
    return false;
  }
  return true;
}

bool read_whole_file(const std::string& path, std::string* out) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) return false;
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream ss;
  ss << in.rdbuf();
  *out = ss.str();
  return !in.bad();
}

}  // namespace efc::batch
