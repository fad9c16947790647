#include "app/metrics_command.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <variant>

#include "metrics/merge.h"
#include "metrics/metrics_error.h"
#include "metrics/regression.h"

namespace rr {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

void printError(std::string message) {
    std::replace(message.begin(), message.end(), '\n', ' ');  // always exactly one line
    std::fprintf(stderr, "error: %s\n", message.c_str());
}

// Runs a subcommand, which prints its output only once everything has succeeded, and turns what
// it throws into the exit status.
int reportingErrors(const std::function<void()>& command) {
    try {
        command();
        return 0;
    } catch (const MetricsError& e) {
        printError(e.what());
        return 2;
    } catch (const std::exception& e) {
        printError(e.what());
        return 1;
    } catch (...) {
        printError("unexpected failure");
        return 1;
    }
}

Json numberOrNull(const std::optional<double>& v) {
    return v ? Json(*v) : Json(nullptr);
}

// A JSON number, or "n/a" for null, as the summaries show it.
std::string shortNumber(const Json& v) {
    if (!v.is_number()) return "n/a";
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", v.get<double>());
    return text;
}

void addLine(std::string& out, const std::string& label, const std::string& value) {
    char text[256];
    std::snprintf(text, sizeof text, "%-14s %s\n", label.c_str(), value.c_str());
    out += text;
}

// ---- compare ----

Json statsJson(const ErrorStats& s) {
    return {{"rmse", s.rmse},
            {"mse", s.mse},
            {"sigma_over_mu", numberOrNull(s.sigmaOverMu)},
            {"relmse", s.relmse},
            {"tvi_err", s.tviErr},
            {"reference_mean", s.referenceMean},
            {"mean", s.mean},
            {"relative_bias", numberOrNull(s.relativeBias)}};
}

// IMAGE's render time: --time, else its renderer.renderTime when that is positive.
std::optional<double> renderTime(const CompareCommandOptions& o, const ExrImage& image) {
    if (o.time) return o.time;
    const std::optional<double> t = numericAttribute(image, "renderer.renderTime");
    return t && std::isfinite(*t) && *t > 0 ? t : std::nullopt;
}

void addEfficiencies(Json& j, double time, const ErrorStats& rgb) {
    j["time"] = time;
    const std::optional<double> pEff = efficiency(rgb.tviErr, time);
    const std::optional<double> mseEff = efficiency(rgb.mse, time);
    j["p_eff"] = numberOrNull(pEff);
    j["mse_eff"] = numberOrNull(mseEff);
    std::string note;
    if (!pEff) note = "p_eff is null: tvi_err is 0";
    if (!mseEff) note += (note.empty() ? "" : "; ") + std::string("mse_eff is null: mse is 0");
    if (!note.empty()) j["note"] = note;
}

Json compareJson(const CompareCommandOptions& o, const ExrImage& image, const Comparison& c) {
    // Over RGB at the top level (compareImages refuses a reference without a positive mean, so
    // σ/µ and the bias are numbers there), per channel and on luminance below.
    Json j = statsJson(c.rgb);
    j.update({{"image", o.image},
              {"reference", o.reference},
              {"width", c.width},
              {"height", c.height},
              {"cd_per_unit", o.cdPerUnit},
              {"relmse_reject_fraction", o.relmseReject},
              {"luminance", statsJson(c.luminance)}});
    for (size_t k = 0; k < 3; ++k)
        j["channels"][kRgbChannels[k]] = statsJson(c.channels[k]);
    if (const auto it = image.attributes.find("renderer.spp"); it != image.attributes.end())
        std::visit([&](const auto& spp) { j["spp"] = spp; }, it->second);
    if (const auto time = renderTime(o, image)) {
        addEfficiencies(j, *time, c.rgb);
        j["time_source"] = o.time ? "--time" : "renderer.renderTime";
    }
    return j;
}

std::string compareSummary(const Json& j) {
    std::string out;
    addLine(out, "image",
            j["image"].get<std::string>() + "  (" + j["width"].dump() + "x" + j["height"].dump() +
                (j.contains("spp") ? ", " + shortNumber(j["spp"]) + " spp)" : ")"));
    addLine(out, "reference", j["reference"].get<std::string>());
    for (const char* key : {"rmse", "mse", "sigma_over_mu"})
        addLine(out, key, shortNumber(j[key]));
    addLine(out, "relmse",
            shortNumber(j["relmse"]) +
                (j["relmse_reject_fraction"] > 0
                     ? "  (without the " + shortNumber(j["relmse_reject_fraction"]) +
                           " of pixels with the largest values)"
                     : ""));
    addLine(out, "tvi_err", shortNumber(j["tvi_err"]));
    if (j.contains("time")) {
        addLine(out, "time",
                shortNumber(j["time"]) + " s  (" + j["time_source"].get<std::string>() + ")");
        addLine(out, "p_eff", shortNumber(j["p_eff"]));
        addLine(out, "mse_eff", shortNumber(j["mse_eff"]));
        if (j.contains("note")) addLine(out, "note", j["note"].get<std::string>());
    }
    auto row = [&](const std::string& label, const std::array<std::string, 4>& cells) {
        char text[256];
        std::snprintf(text, sizeof text, "%-14s %-14s %-14s %-14s %s\n", label.c_str(),
                      cells[0].c_str(), cells[1].c_str(), cells[2].c_str(), cells[3].c_str());
        out += text;
    };
    row("", {"rmse", "sigma_over_mu", "relmse", "tvi_err"});
    auto variant = [&](const std::string& label, const Json& s) {
        row(label, {shortNumber(s["rmse"]), shortNumber(s["sigma_over_mu"]),
                    shortNumber(s["relmse"]), shortNumber(s["tvi_err"])});
    };
    for (const char* c : kRgbChannels)
        variant(c, j["channels"][c]);
    variant("luminance", j["luminance"]);
    return out;
}

void compare(const CompareCommandOptions& o) {
    if (o.time && !(std::isfinite(*o.time) && *o.time > 0))
        throw MetricsError("--time must be a positive number of seconds");
    const ExrImage image = readInputExr(o.image);
    const ExrImage reference = readInputExr(o.reference);
    const Comparison c =
        compareImages(inputFromExr(image, o.image), inputFromExr(reference, o.reference),
                      {o.relmseReject, o.cdPerUnit});
    const Json j = compareJson(o, image, c);
    std::fputs(o.json ? (j.dump(2) + "\n").c_str() : compareSummary(j).c_str(), stdout);
}

// ---- slope ----

Json readJsonFile(const std::string& file) {
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
        throw MetricsError("cannot read " + file + ": no such file");
    std::ifstream in(file);
    if (!in) throw MetricsError("cannot read " + file);
    try {
        return Json::parse(in);
    } catch (const Json::parse_error& e) {
        throw MetricsError(file + ": malformed JSON: " + e.what());
    }
}

Json fitJson(const LineFit& f) {
    return {{"slope", f.slope},
            {"slope_stderr", f.slopeStderr},
            {"intercept", f.intercept},
            {"r2", f.r2},
            {"n", f.n}};
}

std::string fitSummary(const Json& f) {
    return "slope " + shortNumber(f["slope"]) + " +- " + shortNumber(f["slope_stderr"]) +
           "  (intercept " + shortNumber(f["intercept"]) + ", natural log; R^2 " +
           shortNumber(f["r2"]) + ", n " + f["n"].dump() + ")";
}

void slope(const SlopeCommandOptions& o) {
    const Json document = readJsonFile(o.file);
    ConvergenceSlopes s;
    try {
        s = convergenceSlopes(parseConvergencePoints(document));
    } catch (const MetricsError& e) {
        throw MetricsError(o.file + ": " + e.what());
    }
    Json j = {{"vs_spp", fitJson(s.vsSpp)}};
    if (s.vsTime) j["vs_time"] = fitJson(*s.vsTime);
    std::string summary;
    addLine(summary, "vs spp", fitSummary(j["vs_spp"]));
    if (s.vsTime) addLine(summary, "vs time", fitSummary(j["vs_time"]));
    std::fputs(o.json ? (j.dump(2) + "\n").c_str() : summary.c_str(), stdout);
}

// ---- merge ----

void merge(const MergeCommandOptions& o) {
    std::error_code ec;
    if (fs::is_directory(o.out, ec)) throw MetricsError("--out names a directory: " + o.out);
    std::vector<ExrImage> inputs;
    for (const std::string& file : o.inputs)
        inputs.push_back(readInputExr(file));
    const MergedReference m = mergeImages(inputs, o.inputs);
    const fs::path out(o.out);
    if (out.has_parent_path()) fs::create_directories(out.parent_path());
    writeExr(out, m.image);

    Json j = {{"out", o.out}, {"mean", m.mean}};
    if (m.spp) j["spp"] = *m.spp;
    if (m.noise) {
        j["half_difference_rmse"] = m.noise->halfDifferenceRmse;
        j["noise_rmse"] = m.noise->noiseRmse;
        j["noise_sigma_over_mu"] = numberOrNull(m.noise->noiseSigmaOverMu);
    }
    std::string summary = "merged " + std::to_string(inputs.size()) + " images" +
                          (m.spp ? " (" + std::to_string(*m.spp) + " spp)" : "") + " into " +
                          o.out + ": mean " + shortNumber(j["mean"]);
    if (m.noise)
        summary += ", noise rmse " + shortNumber(j["noise_rmse"]) + " (sigma/mu " +
                   shortNumber(j["noise_sigma_over_mu"]) + ")";
    std::fputs(o.json ? (j.dump(2) + "\n").c_str() : (summary + "\n").c_str(), stdout);
}

}  // namespace

int runCompareCommand(const CompareCommandOptions& options) {
    return reportingErrors([&] { compare(options); });
}

int runSlopeCommand(const SlopeCommandOptions& options) {
    return reportingErrors([&] { slope(options); });
}

int runMergeCommand(const MergeCommandOptions& options) {
    return reportingErrors([&] { merge(options); });
}

}  // namespace rr
