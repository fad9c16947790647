#include "app/serve_command.h"

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "app/command_line.h"
#include "app/interrupt.h"
#include "app/render_command.h"
#include "config/json_reader.h"

namespace rr {

namespace {

// Replies go to the process's stdout as it was; stdout itself is pointed at stderr, so that
// nothing a library prints can come between the replies.
std::FILE* takeStdoutForReplies() {
    std::fflush(stdout);
    const int replies = ::dup(STDOUT_FILENO);
    if (replies < 0 || ::dup2(STDERR_FILENO, STDOUT_FILENO) < 0) return nullptr;
    return ::fdopen(replies, "w");
}

// Resets the process's peak resident memory (VmHWM) to its current size, so that each served
// render's renderer.peakMemoryMiB is the peak during that render (cached scenes included, as
// they stay resident), not the peak over the renders served before it.
void resetPeakMemory() {
    std::ofstream("/proc/self/clear_refs") << "5";
}

// The request's arguments, or a message saying why it is not a request.
bool readArguments(const std::string& line, std::vector<std::string>* args, std::string* problem) {
    const Json request = Json::parse(line, nullptr, /*allow_exceptions=*/false);
    if (request.is_discarded()) {
        *problem = "error: a request is one line of JSON; got \"" + line + "\"";
        return false;
    }
    if (!request.is_array()) {
        *problem = "error: a request is a JSON array of the arguments of `renderer render`";
        return false;
    }
    for (const Json& arg : request) {
        if (!arg.is_string()) {
            *problem = "error: every argument of a request is a string; got " + arg.dump();
            return false;
        }
        args->push_back(arg.get<std::string>());
    }
    return true;
}

int serveRequest(const std::string& line, SceneCache& scenes, std::vector<std::string>& messages) {
    std::vector<std::string> args;
    std::string problem;
    if (!readArguments(line, &args, &problem)) {
        messages.push_back(problem);
        return 2;
    }
    CLI::App command{"renderer render (served)"};
    command.set_help_flag();  // --help is an unknown option here, not a request for text
    RenderCommandOptions options;
    addRenderOptions(&command, options);
    try {
        command.parse(std::vector<std::string>(args.rbegin(), args.rend()));  // CLI11: reversed
    } catch (const CLI::ParseError& e) {
        messages.push_back(std::string("error: ") + e.what());
        return 2;
    }
    RenderEnvironment environment;
    environment.scenes = &scenes;
    environment.report = [&](const std::string& message) { messages.push_back(message); };
    environment.progressBar = false;
    resetPeakMemory();
    return runRenderCommand(options, environment);
}

}  // namespace

int runServeCommand(const ServeOptions& options) {
    std::FILE* replies = takeStdoutForReplies();
    if (!replies) {
        std::perror("renderer serve: cannot set up its replies");
        return 1;
    }
    SceneCache scenes(options.cachedScenes);
    const std::atomic<bool>& interrupted = installInterruptHandler();
    std::string line;
    while (!interrupted && std::getline(std::cin, line)) {
        std::vector<std::string> messages;
        const int status = serveRequest(line, scenes, messages);
        const Json reply = {{"status", status}, {"messages", messages}};
        std::fprintf(
            replies, "%s\n",
            reply.dump(-1, ' ', /*ensure_ascii=*/true, Json::error_handler_t::replace).c_str());
        std::fflush(replies);
    }
    const bool written = !std::ferror(replies);
    if (std::fclose(replies) != 0 || !written) {
        std::perror("renderer serve: cannot write its replies");
        return 1;
    }
    return interrupted ? 130 : 0;  // Ctrl-C: whoever sent the requests is stopping
}

}  // namespace rr
