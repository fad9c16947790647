// A fresh, empty temporary directory private to the running test (and process), so tests can
// run in parallel under ctest -j and across build trees without touching each other's files.
#pragma once

#include <filesystem>
#include <string>

namespace rr::test {

std::filesystem::path scratchDirectory(const std::string& tag = "");

}  // namespace rr::test
