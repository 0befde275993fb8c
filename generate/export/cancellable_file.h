// Files written or read in one library call (nlohmann's serializer and parser) or copied
// whole (city.glb's scratch files) that still stop once the build is cancelled (generate/cancel.h): the bytes go
// through a 64 KiB buffer, and the flag is checked each time it is passed on or refilled.
#pragma once

#include <array>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <streambuf>
#include <string>

#include "generate/cancel.h"
#include "generate/errors.h"

namespace exacity {

// The output stream lets its buffer's exceptions through (its badbit exception mask):
// Cancelled, or UserError when the file cannot be written.
class CancellableFile : public std::ostream {
 public:
  explicit CancellableFile(const std::filesystem::path& path)
      : std::ostream(&buffer_), file_(path, std::ios::binary), buffer_(*file_.rdbuf(), path) {
    if (!file_) buffer_.fail();
    exceptions(std::ios::badbit);
  }
  // Writes what is left in the buffer and closes the file.
  void close() {
    flush();
    file_.close();
    if (file_.fail()) buffer_.fail();
  }

 private:
  class Buffer : public std::streambuf {
   public:
    Buffer(std::streambuf& to, std::filesystem::path path) : to_(to), path_(std::move(path)) {
      setp(bytes_.data(), bytes_.data() + bytes_.size());
    }
    [[noreturn]] void fail() const { throw UserError(path_.string() + ": write failed (disk full?)"); }

   protected:
    int_type overflow(int_type c) override {
      pass_on();
      if (!traits_type::eq_int_type(c, traits_type::eof())) sputc(traits_type::to_char_type(c));
      return traits_type::not_eof(c);
    }
    int sync() override {
      pass_on();
      if (to_.pubsync() != 0) fail();
      return 0;
    }

   private:
    void pass_on() {
      cancel_.check();
      const std::streamsize n = pptr() - pbase();
      if (to_.sputn(pbase(), n) != n) fail();
      pbump(static_cast<int>(-n));
    }
    std::streambuf& to_;
    const std::filesystem::path path_;
    const CancelCheck cancel_;
    std::array<char, 1 << 16> bytes_;
  };

  std::ofstream file_;
  Buffer buffer_;
};

// An input stream of the file; nlohmann's parser reads its buffer directly, so Cancelled
// reaches the parser's caller. Bad when the file cannot be opened.
class CancellableInput : public std::istream {
 public:
  explicit CancellableInput(const std::filesystem::path& path) : std::istream(&buffer_) {
    if (!file_.open(path, std::ios::in | std::ios::binary)) setstate(std::ios::badbit);
  }

 private:
  class Buffer : public std::streambuf {
   public:
    explicit Buffer(std::filebuf& from) : from_(from) {}

   protected:
    int_type underflow() override {
      cancel_.check();
      const std::streamsize n = from_.sgetn(bytes_.data(), bytes_.size());
      setg(bytes_.data(), bytes_.data(), bytes_.data() + n);
      return n > 0 ? traits_type::to_int_type(bytes_[0]) : traits_type::eof();
    }

   private:
    std::filebuf& from_;
    const CancelCheck cancel_;
    std::array<char, 1 << 16> bytes_;
  };

  std::filebuf file_;
  Buffer buffer_{file_};
};

}  // namespace exacity
