// The fuzz targets outside the fuzz build: each runs its input on every file of the
// folders (or files) named, so CI replays the seed corpora and every reproducer found so
// far with the plain compiler (fuzz/CMakeLists.txt registers one test per target); then,
// with `--mutants N`, on N inputs made from them by libFuzzer's kinds of mutation, drawn
// from a fixed stream: a short fuzzing slice that gives the same inputs on every run, so a
// finding in CI is found again by running the same command. Each mutant is written to
// `last-mutant` in the temporary folder before it runs: after a crash it holds the input.
// libFuzzer's own main takes the place of this one in the fuzz build.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <string_view>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

std::string read(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void run(const std::string& bytes) {
  LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
}

// Values that break parsers and geometry when they land in a number or a name.
constexpr std::array<std::string_view, 14> kInteresting = {
    "0", "-1", "1e308", "-1e308", "1e-308", "nan", "inf", "4294967296", "9007199254740993", "\"\"", "[]", "{}", "\xff", "\n"};

// One to four of libFuzzer's mutations: change, insert, erase, copy a range, put an
// interesting value, cut the end.
std::string mutate(std::string bytes, std::mt19937_64& random) {
  auto below = [&](std::size_t n) { return n == 0 ? std::size_t{0} : static_cast<std::size_t>(random() % n); };
  const std::size_t steps = 1 + below(4);
  for (std::size_t step = 0; step < steps; ++step) {
    const std::size_t at = below(bytes.size() + 1);
    switch (below(6)) {
      case 0:
        if (at < bytes.size()) bytes[at] = static_cast<char>(random());
        break;
      case 1: bytes.insert(at, 1, static_cast<char>(random())); break;
      case 2: bytes.erase(at, 1 + below(16)); break;
      case 3:
        if (!bytes.empty()) {
          const std::size_t from = below(bytes.size()), length = 1 + below(std::min<std::size_t>(64, bytes.size() - from));
          bytes.insert(at, bytes.substr(from, length));
        }
        break;
      case 4: {
        // Over a number if one starts here, else inserted.
        std::size_t end = at;
        while (end < bytes.size() && std::strchr("0123456789.-+eE", bytes[end])) ++end;
        bytes.replace(at, end - at, kInteresting[below(kInteresting.size())]);
        break;
      }
      default: bytes.resize(at);
    }
  }
  return bytes;
}

}  // namespace

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  long mutants = 0;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--mutants") == 0 && i + 1 < argc) {
      mutants = std::strtol(argv[++i], nullptr, 10);
    } else if (fs::is_directory(argv[i])) {
      for (const fs::directory_entry& e : fs::directory_iterator(argv[i]))
        if (e.is_regular_file()) files.push_back(e.path());
    } else if (fs::is_regular_file(argv[i])) {
      files.push_back(argv[i]);
    } else {
      std::fprintf(stderr, "%s: no such file or folder\n", argv[i]);
      return 2;
    }
  }
  if (files.empty() || mutants < 0) {
    std::fprintf(stderr, "usage: %s FOLDER_OR_FILE... [--mutants N]: no input to replay\n", argv[0]);
    return 2;
  }
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) {
    std::fprintf(stderr, "%s\n", file.c_str());  // the last line names the input that failed
    run(read(file));
  }
  const fs::path last = fs::temp_directory_path() / "last-mutant";
  std::mt19937_64 random(20261127);
  for (long i = 0; i < mutants; ++i) {
    const fs::path& file = files[static_cast<std::size_t>(i) % files.size()];
    const std::string bytes = mutate(read(file), random);
    std::ofstream(last, std::ios::binary) << bytes;
    std::fprintf(stderr, "mutant %ld of %s\n", i, file.c_str());
    run(bytes);
  }
  std::fprintf(stderr, "%zu inputs and %ld mutants replayed\n", files.size(), mutants);
  return 0;
}
