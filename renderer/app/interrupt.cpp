#include "app/interrupt.h"

#include <unistd.h>

#include <csignal>

namespace rr {

namespace {

std::atomic<bool> interrupted{false};

extern "C" void onInterrupt(int) {
    if (interrupted.exchange(true)) {
        std::signal(SIGINT, SIG_DFL);
        std::raise(SIGINT);
        return;
    }
    static const char message[] =
        "\ninterrupt: finishing the current pass, then saving (Ctrl-C again to abort)\n";
    [[maybe_unused]] auto n = ::write(STDERR_FILENO, message, sizeof message - 1);
}

}  // namespace

const std::atomic<bool>& installInterruptHandler() {
    std::signal(SIGINT, onInterrupt);
    return interrupted;
}

}  // namespace rr
