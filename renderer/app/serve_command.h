// `renderer serve`: renders requests read from stdin, one per line, each a JSON array of the
// arguments `renderer render` takes (["scene.json", "--seed", "3", "--out", "x.exr", ...]), and
// answers each with one line on stdout: {"status": the exit status `renderer render` would
// give, "messages": the lines it would print}. Scenes it built are kept (SceneCache), so a
// harness running many renders of a few scenes pays process start-up, asset loading and
// acceleration-structure builds once per scene rather than once per render; every render's
// integrator is built afresh, and its outputs are those of `renderer render` with the same
// arguments (tests/test_serve.py). Every line gets a reply (an empty one is a bad request).
// Ends at the end of its input (status 0), or after the request during which Ctrl-C came
// (status 130).
#pragma once

#include <cstddef>

namespace rr {

struct ServeOptions {
    size_t cachedScenes = 4;
};

int runServeCommand(const ServeOptions& options);

}  // namespace rr
