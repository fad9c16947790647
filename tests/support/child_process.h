// Spawning the project's binaries from tests: arguments as given, stdout and stderr captured
// in files, exit status (or 128 + signal) returned.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

namespace rr::test {

struct ChildProcess {
    pid_t pid = -1;
    std::filesystem::path stdoutFile, stderrFile;
};

struct ProcessResult {
    int status = -1;  // exit status, or 128 + the signal that ended the process
    std::string out, errors;
};

// Starts `binary` with `args`; stdout and stderr go to stdout.txt and stderr.txt in `dir`.
ChildProcess startProcess(const std::string& binary, const std::vector<std::string>& args,
                          const std::filesystem::path& dir);
ProcessResult waitProcess(const ChildProcess& process);
ProcessResult runProcess(const std::string& binary, const std::vector<std::string>& args,
                         const std::filesystem::path& dir);

std::string readText(const std::filesystem::path& file);

}  // namespace rr::test
