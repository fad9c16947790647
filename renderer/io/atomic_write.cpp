#include "io/atomic_write.h"

#include <unistd.h>

#include <string>

namespace rr {

namespace fs = std::filesystem;

void writeAtomically(const fs::path& destination,
                     const std::function<void(const fs::path&)>& write) {
    const fs::path dir = destination.has_parent_path() ? destination.parent_path() : fs::path(".");
    // Appended piecewise: GCC 12's -Wrestrict misfires on `"." + std::string&&`.
    std::string name = ".";
    name += destination.stem().string();
    name += ".tmp" + std::to_string(::getpid());
    name += destination.extension().string();
    const fs::path temporary = dir / name;
    try {
        write(temporary);
        fs::rename(temporary, destination);
    } catch (...) {
        std::error_code ignored;
        fs::remove(temporary, ignored);
        throw;
    }
}

}  // namespace rr
