#include "crowdbake/runtime/byte_source.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace crowdbake::runtime {
namespace {

class FileSource final : public ByteSource {
 public:
  FileSource(int fd, uint64_t size, std::string path)
      : fd_(fd), size_(size), path_(std::move(path)) {}
  ~FileSource() override { ::close(fd_); }
  FileSource(const FileSource&) = delete;
  FileSource& operator=(const FileSource&) = delete;

  uint64_t size() const override { return size_; }
  const std::string& name() const override { return path_; }

  Status read(uint64_t offset, size_t count, uint8_t* out) override {
    size_t done = 0;
    while (done < count) {
      const ssize_t got = ::pread(fd_, out + done, count - done, static_cast<off_t>(offset + done));
      if (got < 0 && errno == EINTR) continue;
      if (got < 0)
        return {StatusCode::kIoError, path_ + ": read of " + std::to_string(count) +
                                          " bytes at offset " + std::to_string(offset) +
                                          " failed: " + std::strerror(errno)};
      if (got == 0)
        return {StatusCode::kIoError, path_ + ": file ended at " + std::to_string(offset + done) +
                                          " bytes while reading " + std::to_string(count) +
                                          " bytes at offset " + std::to_string(offset) +
                                          " (was it truncated while open?)"};
      done += static_cast<size_t>(got);
    }
    return {};
  }

 private:
  int fd_;
  uint64_t size_;
  std::string path_;
};

class MemorySource final : public ByteSource {
 public:
  MemorySource(std::vector<uint8_t> bytes, std::string name)
      : bytes_(std::move(bytes)), name_(std::move(name)) {}
  uint64_t size() const override { return bytes_.size(); }
  const std::string& name() const override { return name_; }
  Status read(uint64_t offset, size_t count, uint8_t* out) override {
    if (offset > bytes_.size() || count > bytes_.size() - offset)
      return {StatusCode::kIoError, name_ + ": read past the end"};
    if (count) std::memcpy(out, bytes_.data() + offset, count);
    return {};
  }

 private:
  std::vector<uint8_t> bytes_;
  std::string name_;
};

}  // namespace

Status open_file_source(const std::string& path, std::unique_ptr<ByteSource>& out) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return {StatusCode::kIoError, path + ": cannot open: " + std::strerror(errno)};
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int e = errno;
    ::close(fd);
    return {StatusCode::kIoError, path + ": cannot stat: " + std::strerror(e)};
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    return {StatusCode::kIoError, path + ": not a regular file"};
  }
  out = std::make_unique<FileSource>(fd, static_cast<uint64_t>(st.st_size), path);
  return {};
}

std::unique_ptr<ByteSource> make_memory_source(std::vector<uint8_t> bytes, std::string name) {
  return std::make_unique<MemorySource>(std::move(bytes), std::move(name));
}

}  // namespace crowdbake::runtime
