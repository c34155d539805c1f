// A fuzz target without libFuzzer: runs LLVMFuzzerTestOneInput once on each file named on the
// command line, or on every file under a folder named there. Linked with each harness by every
// preset but fuzz, so the harnesses compile with the project's own compiler and warnings, and
// CTest replays each seed corpus through its harness (docs/architecture.md, "Fuzzing").
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

namespace fs = std::filesystem;

bool replay(const char* program, const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "%s: cannot open %s\n", program, file.c_str());
    return false;
  }
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::fprintf(stderr, "%s\n", file.c_str());
  LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string program = fs::path(argv[0]).filename().string();
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s FILE_OR_FOLDER...\n", program.c_str());
    return 2;
  }
  std::vector<fs::path> files;
  for (int i = 1; i < argc; ++i) {
    const fs::path arg = argv[i];
    std::error_code error;
    if (fs::is_directory(arg, error)) {
      for (const auto& entry : fs::recursive_directory_iterator(arg)) {
        if (entry.is_regular_file()) files.push_back(entry.path());
      }
    } else {
      files.push_back(arg);
    }
  }
  std::sort(files.begin(), files.end());  // the same order on every machine
  int failed = 0;
  for (const fs::path& file : files) failed += replay(program.c_str(), file) ? 0 : 1;
  std::fprintf(stderr, "%s: %zu inputs, %d unreadable\n", program.c_str(), files.size(), failed);
  if (files.empty()) return 1;  // a corpus that is not there is no replay
  return failed == 0 ? 0 : 1;
}
