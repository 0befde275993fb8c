// Bytes an export makes before it can write them (a document's parts made in another order
// than the file holds them, a GLB's binary chunk that follows its JSON), kept aside in an
// unlinked file instead of memory: held in memory they were most of the 3D export's peak
// on a large city. Up to 1 MiB waits in memory; the file is made (beside the output, and
// unlinked at once, so nothing is left behind however the export ends) only once more
// comes, so a small output never touches the disk for it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <string_view>

namespace exacity {

class ScratchFile {
 public:
  // `beside`: the output the bytes are for; the scratch file is named after it.
  explicit ScratchFile(std::filesystem::path beside) : path_(beside.string() + ".scratch") {}
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;
  ~ScratchFile();

  void append(std::string_view bytes);
  void append_zeros(std::size_t n);
  // Bytes appended so far.
  std::uint64_t size() const { return written_ + pending_.size(); }
  // `n` bytes from `offset` (within size()) into `to`.
  void read(std::uint64_t offset, char* to, std::size_t n);
  // Every byte appended, in order.
  void copy_to(std::ostream& out);

 private:
  void flush();
  [[noreturn]] void fail() const;

  std::filesystem::path path_;
  int fd_ = -1;
  std::uint64_t written_ = 0;  // bytes in the file
  std::string pending_;        // bytes not yet in it
};

}  // namespace exacity
