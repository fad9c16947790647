#include "support/child_process.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

extern char** environ;

namespace rr::test {

namespace fs = std::filesystem;

ChildProcess startProcess(const std::string& binary, const std::vector<std::string>& args,
                          const fs::path& dir) {
    ChildProcess p;
    p.stdoutFile = dir / "stdout.txt";
    p.stderrFile = dir / "stderr.txt";
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, p.stdoutFile.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, p.stderrFile.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<std::string> all{binary};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all)
        argv.push_back(a.data());
    argv.push_back(nullptr);
    EXPECT_EQ(posix_spawn(&p.pid, binary.c_str(), &actions, nullptr, argv.data(), environ), 0);
    posix_spawn_file_actions_destroy(&actions);
    return p;
}

ProcessResult waitProcess(const ChildProcess& process) {
    int status = 0;
    waitpid(process.pid, &status, 0);
    ProcessResult r;
    r.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = readText(process.stdoutFile);
    r.errors = readText(process.stderrFile);
    return r;
}

ProcessResult runProcess(const std::string& binary, const std::vector<std::string>& args,
                         const fs::path& dir) {
    return waitProcess(startProcess(binary, args, dir));
}

std::string readText(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace rr::test
