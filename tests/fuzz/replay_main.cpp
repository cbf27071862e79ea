// Replays fuzz inputs through a target's LLVMFuzzerTestOneInput without libFuzzer, so the normal
// (gcc) build and the ASan build check the seed corpus and every kept crash input on each CTest
// run. Arguments are files or directories (read recursively). Exits 1 when no input was found, so
// a mistyped path cannot pass by replaying nothing; a crash or an escaping exception fails the run.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include "tools/command_line.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

void Replay(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(file)),
                                std::istreambuf_iterator<char>());
  // An empty vector's data() may be null; libFuzzer hands targets a valid pointer even for size 0.
  static const std::uint8_t kEmpty = 0;
  const auto* data = bytes.empty() ? &kEmpty : reinterpret_cast<const std::uint8_t*>(bytes.data());
  LLVMFuzzerTestOneInput(data, bytes.size());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Replays fuzz inputs through the target's loader without libFuzzer."};
  std::vector<std::string> paths;
  app.add_option("paths", paths, "input files or folders (read recursively)")->required();
  if (const int code = sas::kiosk::ParseProgramCommandLine(app, argc, argv); code >= 0) return code;
  std::size_t count = 0;
  for (const std::string& path : paths) {
    const std::filesystem::path root(path);
    std::vector<std::filesystem::path> files;
    if (std::filesystem::is_directory(root)) {
      for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
        if (entry.is_regular_file()) files.push_back(entry.path());
      }
    } else if (std::filesystem::is_regular_file(root)) {
      files.push_back(root);
    }
    for (const auto& file : files) {
      Replay(file);
      ++count;
    }
  }
  std::cout << "replayed " << count << " inputs\n";
  if (count == 0) {
    std::cerr << "no fuzz inputs found in the given paths\n";
    return 1;
  }
  return 0;
}
