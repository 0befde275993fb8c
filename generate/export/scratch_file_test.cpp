#include "generate/export/scratch_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "tests/test_util.h"

namespace exacity {
namespace {

// Three MiB of bytes that differ from place to place, so a byte read from the wrong
// offset shows.
std::string numbered_bytes() {
  std::string bytes;
  for (int k = 0; bytes.size() < (3u << 20); ++k) bytes += std::to_string(k) + ",";
  return bytes;
}

// Bytes past what is held in memory go to the file and come back in order, read anywhere
// (across the file's end and what still waits in memory) or copied whole; the folder holds
// nothing but the output's own files meanwhile and after.
TEST(ScratchFile, GivesBackEveryByteInOrderAndLeavesNoFile) {
  const std::filesystem::path dir = testing_util::temp_dir("scratch");
  const std::string bytes = numbered_bytes();
  std::ostringstream copied;
  {
    ScratchFile file(dir / "out.bin");
    std::size_t at = 0;
    for (std::size_t n : {10u, 1000u, 1u << 20, 5u, 7u << 18})
      file.append(std::string_view(bytes).substr(at, n)), at += n;
    file.append(std::string_view(bytes).substr(at));
    file.append_zeros(3);
    ASSERT_EQ(file.size(), bytes.size() + 3);
    EXPECT_TRUE(std::filesystem::is_empty(dir));
    for (std::size_t offset : {std::size_t{0}, std::size_t{1} << 20, bytes.size() - 100}) {
      std::string part(100, ' ');
      file.read(offset, part.data(), part.size());
      EXPECT_EQ(part, bytes.substr(offset, 100)) << offset;
    }
    file.copy_to(copied);
  }
  EXPECT_TRUE(copied.str() == bytes + std::string(3, '\0'));
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

// Bytes that fit in memory make no file and are copied as they are.
TEST(ScratchFile, AFewBytesStayInMemory) {
  const std::filesystem::path dir = testing_util::temp_dir("scratch-small");
  ScratchFile file(dir / "out.bin");
  file.append("{\"a\":1}");
  std::ostringstream copied;
  file.copy_to(copied);
  EXPECT_EQ(copied.str(), "{\"a\":1}");
  char c = 0;
  file.read(5, &c, 1);
  EXPECT_EQ(c, '1');
}

}  // namespace
}  // namespace exacity
