#include "shard/io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace shard::io {
namespace {

// The temporary file: closed when it goes out of scope, and removed unless it was renamed.
class TemporaryFile {
 public:
  explicit TemporaryFile(std::filesystem::path path)
      : path_(std::move(path)), fd_(::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666)) {}
  ~TemporaryFile() {
    close();
    if (!renamed_) ::unlink(path_.c_str());
  }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;

  bool is_open() const { return fd_ >= 0; }
  bool write(std::string_view content) {
    while (!content.empty()) {
      const ssize_t n = ::write(fd_, content.data(), content.size());
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return false;
      content.remove_prefix(static_cast<std::size_t>(n));
    }
    return true;
  }
  bool sync_and_close() { return ::fsync(fd_) == 0 && close() == 0; }
  bool rename_to(const std::filesystem::path& target) {
    renamed_ = ::rename(path_.c_str(), target.c_str()) == 0;
    return renamed_;
  }

 private:
  int close() {
    const int rc = fd_ >= 0 ? ::close(fd_) : 0;
    fd_ = -1;
    return rc;
  }
  std::filesystem::path path_;
  int fd_;
  bool renamed_ = false;
};

[[noreturn]] void fail(const std::filesystem::path& file, const char* step) {
  throw std::runtime_error(fmt::format("{}: cannot be written ({}: {}); check that its folder exists and is "
                                       "writable and that the disk is not full",
                                       file.string(), step, std::strerror(errno)));
}

}  // namespace

void write_file_atomically(const std::filesystem::path& file, std::string_view content) {
  auto temporary_name = file;
  temporary_name += fmt::format(".tmp.{}", ::getpid());
  TemporaryFile temporary(temporary_name);
  if (!temporary.is_open()) fail(file, "creating a temporary file beside it");
  if (!temporary.write(content)) fail(file, "writing");
  if (!temporary.sync_and_close()) fail(file, "flushing to disk");
  if (!temporary.rename_to(file)) fail(file, "renaming the temporary file over it");
}

}  // namespace shard::io
