// What the fuzz targets share (tests/fuzz/README.md). Every target ends in a 1×1 render through
// the render command's own code path, so an input is judged by what a user would see: a
// rendered image whose pixels are finite and non-negative, or a bad-input rejection (status 2)
// that wrote nothing. Anything else (another status, a NaN, a sanitizer report, a crash) aborts
// the process: a finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>

namespace rr::fuzz {

// A directory private to this process, created on first use (under /dev/shm when it exists:
// the readers take file names, and every input is written there first).
const std::filesystem::path& scratchDirectory();

// Writes `data` to `name` in the scratch directory and returns its path.
std::filesystem::path writeInput(std::string_view name, const uint8_t* data, size_t size);

// Writes `text` to `name` in the scratch directory (once per process) and returns its path.
std::filesystem::path writeFixedFile(std::string_view name, std::string_view text);

// Renders the scene file at 1×1, 1 spp, one thread, and aborts unless the outcome is one of
// those above; exits on an interrupt (Ctrl-C).
void renderOnePixel(const std::filesystem::path& scene);

}  // namespace rr::fuzz
