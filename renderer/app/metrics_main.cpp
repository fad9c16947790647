// The metrics tool: error of renders against a reference, convergence slopes, and merging
// renders into a reference. Subcommands: compare, slope, merge.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "app/metrics_command.h"

int main(int argc, char** argv) {
    CLI::App app{"Error metrics, convergence slopes and reference merging for rendered EXR images"};
    app.require_subcommand(1);

    rr::CompareCommandOptions c;
    CLI::App* compare = app.add_subcommand(
        "compare", "error of IMAGE against REFERENCE: MSE, RMSE, sigma/mu, relMSE, tvi error");
    compare->add_option("image", c.image, "rendered EXR (channels R, G, B)")->required();
    compare->add_option("reference", c.reference, "reference EXR of the same size")->required();
    compare->add_option("--time", c.time,
                        "render time in seconds for p_eff and mse_eff (default: IMAGE's "
                        "renderer.renderTime)");
    compare->add_flag("--json", c.json, "print one JSON object");
    compare->add_option("--relmse-reject", c.relmseReject,
                        "leave the FRACTION of pixels with the largest relMSE out of relmse, "
                        "in [0, 0.5) (default 0)");
    compare->add_option("--cd-per-unit", c.cdPerUnit,
                        "display luminance of pixel value 1 in cd/m^2 for the tvi error (default "
                        "100: pixel value 1 is displayed as a 100 cd/m^2 white)");

    rr::SlopeCommandOptions s;
    CLI::App* slope = app.add_subcommand(
        "slope",
        "least-squares slope of log(error) against log(spp) and log(time), natural logarithms");
    slope
        ->add_option("file", s.file,
                     "JSON: [{\"spp\": N, \"error\": E, \"time\": T}, ...] or {\"points\": [...]}; "
                     "time is optional")
        ->required();
    slope->add_flag("--json", s.json, "print one JSON object");

    rr::MergeCommandOptions m;
    CLI::App* merge = app.add_subcommand(
        "merge", "average renders into a reference, weighted by their renderer.spp");
    merge->add_option("inputs", m.inputs, "input EXRs of equal size")->required()->expected(2, -1);
    merge->add_option("--out", m.out, "output EXR")->required();
    merge->add_flag("--json", m.json, "print one JSON object");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    }
    if (*compare) return rr::runCompareCommand(c);
    if (*slope) return rr::runSlopeCommand(s);
    return rr::runMergeCommand(m);
}
