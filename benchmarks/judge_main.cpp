// exacity_judge OUT...: the robustness benchmark's judge on output folders; exit 0 when
// every folder passes, 1 otherwise.
#include <iostream>

#include "benchmarks/judge.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: exacity_judge OUT...\n";
    return 2;
  }
  int status = 0;
  for (int i = 1; i < argc; ++i) {
    exacity::bench::Verdict v = exacity::bench::judge(argv[i]);
    for (const std::string& p : v.problems) std::cout << argv[i] << ": " << p << "\n";
    std::cout << argv[i] << ": " << (v.passed() ? "passed" : "rejected") << "\n";
    if (!v.passed()) status = 1;
  }
  return status;
}
