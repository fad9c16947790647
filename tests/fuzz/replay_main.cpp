// The fuzz targets without libFuzzer: runs LLVMFuzzerTestOneInput over every file of the given
// files and directories (the committed corpus and every finding kept as a regression), so
// `make test` replays them with the ordinary build, and `make asan` under the sanitizers.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace fs = std::filesystem;

namespace {

void replay(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    const std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(in),
                                     std::istreambuf_iterator<char>()};
    std::fprintf(stderr, "replaying %s (%zu bytes)\n", file.c_str(), bytes.size());
    LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
}

}  // namespace

int main(int argc, char** argv) {
    size_t inputs = 0;
    for (int i = 1; i < argc; ++i) {
        if (!fs::exists(argv[i])) continue;  // a target without regressions yet
        if (!fs::is_directory(argv[i])) {
            replay(argv[i]);
            ++inputs;
            continue;
        }
        std::vector<fs::path> files;
        for (const auto& entry : fs::recursive_directory_iterator(argv[i]))
            if (entry.is_regular_file()) files.push_back(entry.path());
        std::sort(files.begin(), files.end());
        for (const fs::path& file : files)
            replay(file);
        inputs += files.size();
    }
    std::fprintf(stderr, "%zu inputs replayed\n", inputs);
    return inputs > 0 ? 0 : 1;
}
