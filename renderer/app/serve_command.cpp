#include "app/serve_command.h"

#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "app/command_line.h"
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
    std::string line;
    while (std::getline(std::cin, line)) {
        if (line.empty()) continue;
        std::vector<std::string> messages;
        const int status = serveRequest(line, scenes, messages);
        const Json reply = {{"status", status}, {"messages", messages}};
        std::fprintf(replies, "%s\n",
                     reply.dump(-1, ' ', false, Json::error_handler_t::replace).c_str());
        std::fflush(replies);
        if (status == 130) break;  // interrupted: whoever sent the requests is stopping
    }
    std::fclose(replies);
    return 0;
}

}  // namespace rr
