#include "support/scratch.h"

#include <gtest/gtest.h>
#include <unistd.h>

namespace rr::test {

namespace {

std::filesystem::path processDirectory() {
    return std::filesystem::temp_directory_path() / ("rr_test_" + std::to_string(::getpid()));
}

// Removes this process's scratch directories when the test program ends.
class ScratchCleanup : public ::testing::Environment {
  public:
    void TearDown() override {
        std::error_code ignored;
        std::filesystem::remove_all(processDirectory(), ignored);
    }
};
const auto* const kCleanup = ::testing::AddGlobalTestEnvironment(new ScratchCleanup);

}  // namespace

std::filesystem::path scratchDirectory(const std::string& tag) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "." + info->name() + "." + tag;
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.') c = '_';
    const std::filesystem::path dir = processDirectory() / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace rr::test
