#include "generate/export/scratch_file.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#include "generate/errors.h"

namespace exacity {

namespace {
constexpr std::size_t kHeldInMemory = 1 << 20;
}

ScratchFile::~ScratchFile() {
  if (fd_ >= 0) ::close(fd_);
}

void ScratchFile::append(std::string_view bytes) {
  pending_.append(bytes);
  if (pending_.size() >= kHeldInMemory) flush();
}

void ScratchFile::append_zeros(std::size_t n) { append(std::string(n, '\0')); }

void ScratchFile::read(std::uint64_t offset, char* to, std::size_t n) {
  if (fd_ >= 0) flush();
  if (fd_ < 0) {
    std::memcpy(to, pending_.data() + offset, n);
    return;
  }
  for (std::size_t done = 0; done < n;) {
    const ssize_t got = ::pread(fd_, to + done, n - done, static_cast<off_t>(offset + done));
    if (got <= 0) fail();
    done += static_cast<std::size_t>(got);
  }
}

void ScratchFile::copy_to(std::ostream& out) {
  if (fd_ < 0) {
    out.write(pending_.data(), static_cast<std::streamsize>(pending_.size()));
    return;
  }
  flush();
  std::vector<char> chunk(std::min<std::uint64_t>(written_, 1 << 16));
  for (std::uint64_t at = 0; at < written_; at += chunk.size()) {
    const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(chunk.size(), written_ - at));
    read(at, chunk.data(), n);
    out.write(chunk.data(), static_cast<std::streamsize>(n));
  }
}

void ScratchFile::flush() {
  if (fd_ < 0) {
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (fd_ < 0) fail();
    ::unlink(path_.c_str());
  }
  for (std::size_t done = 0; done < pending_.size();) {
    const ssize_t n = ::write(fd_, pending_.data() + done, pending_.size() - done);
    if (n <= 0) fail();
    done += static_cast<std::size_t>(n);
  }
  written_ += pending_.size();
  pending_.clear();
}

void ScratchFile::fail() const { throw UserError(path_.string() + ": scratch file failed (disk full?)"); }

}  // namespace exacity
