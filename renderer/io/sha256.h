#pragma once

#include <string>
#include <string_view>

namespace rr {

// Hex SHA-256 digest (OpenSSL), as `sha256sum` prints it.
std::string sha256Hex(std::string_view data);

}  // namespace rr
