// ============================================================================================
// classroom/classroom.cpp: ./bdpt as a class uses it. The lecture's renderer, ../bdpt.cpp, with
// the classroom's tools around it, each room one job:
//   lecture.h      the lecture, its profile hook filled (profile.h: --profile's clock)
//   options.h      the command line: the lecture's options with the tools' rows, did-you-mean
//   run.h          durations, the progress bar, Ctrl-C, whole files, the log and the live image
//   checks.h       before a long render: outputs, memory, the scene, the duration
//   metrics.h      the error against a reference;  figures.h  labels, the ratio, the pyramid
//   side_by_side.h several methods in one titled figure
// and here the main flow: one render, the failure table and the image tools (--compare,
// --average, --ratio). One translation unit: make builds ./bdpt from this file. Beside it, not
// in ./bdpt: physics.h (the densities and weights from their definitions, for every judge of the
// renderer), definitions.h (where each function is defined), workshop/ (the figures), web/ (the
// page) and homework/ (the cutter and the grader).
// ============================================================================================
#ifndef BDPT_NO_MAIN  // this program's main, not the lecture's
#define BDPT_NO_MAIN
#define CLASSROOM_MAIN
#endif
#include "lecture.h"
#include "options.h"
#include "run.h"
#include "checks.h"
#include "figures.h"
#include "side_by_side.h"
#include <iomanip>

// The failure table from --log files: for each run, the slope of log(rmse) against log(seconds)
// (least squares over the passes after the first tenth of the time; -0.5 for an unbiased method
// that converges, about 0 for one that is biased or lacks the technique), and the last pass's
// relative bias of the mean, firefly measure and NaN count.
inline int printFailureTable(const std::vector<std::string>& logs, std::ostream& out, std::ostream& err) {
    out << "| scene | method | slope | bias | fireflies | NaN |\n|---|---|---|---|---|---|\n";
    for (const std::string& path : logs) {
        std::ifstream in(path);
        if (!in) { err << path << ":0: cannot open log\n"; return 2; }
        std::string line, scene, method, options;
        std::vector<std::string> last;
        double lastSeconds = 0;
        std::vector<std::pair<double, double>> rows;
        std::getline(in, line);  // header
        while (std::getline(in, line)) {
            std::vector<std::string> f;
            std::stringstream ss(line);
            for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
            if (f.size() < 12 || f[6].empty()) continue;
            scene = f[0]; method = f[1]; options = f[2];
            // the error the charts draw: without the lamp's pixels where the log has it (a point
            // light's own pixel in lt's image would hold lt's RMSE flat at its value)
            const std::string& error = f.size() > 12 && !f[12].empty() ? f[12] : f[6];
            rows.push_back({std::atof(f[5].c_str()), std::atof(error.c_str())});
            lastSeconds = rows.back().first;
            last = f;
        }
        if (rows.empty()) { err << path << ":0: no rows with an error (was --ref given?)\n"; return 2; }
        double sx = 0, sy = 0, sxx = 0, sxy = 0;
        int n = 0;
        for (auto [t, e] : rows)
            if (t >= 0.1 * lastSeconds && t > 0 && e > 0) {
                double x = std::log(t), y = std::log(e);
                sx += x; sy += y; sxx += x * x; sxy += x * y; ++n;
            }
        double slope = n > 1 && n * sxx - sx * sx > 0 ? (n * sxy - sx * sy) / (n * sxx - sx * sx) : 0;
        // A slope over a few passes is noise (a single pass's error spreads by tens of per cent), and
        // so is a bias measured on them: such a row is marked, and said so.
        constexpr int kFewPasses = 8;
        if (n < kFewPasses)
            err << path << ":0: warning: only " << n << " passes after the first tenth of the time: its slope and bias are "
                << "noise, not the method's (render longer: --time for ./bdpt, FULL=1 for make charts; or a quieter machine)\n";
        char row[512];
        std::snprintf(row, sizeof row, "| %s | %s%s%s | %.2f%s | %+.1f%%%s | %.0f | %s |\n", scene.c_str(), method.c_str(),
                      options.empty() ? "" : " ", options.c_str(), slope, n < kFewPasses ? " (few passes)" : "",
                      100 * std::atof(last[9].c_str()), n < kFewPasses ? " (few passes)" : "", std::atof(last[10].c_str()),
                      last[11].c_str());
        out << row;
    }
    return 0;
}

// --compare, --average and --ratio: two PFM images in, numbers or an image out. Returns the exit status.
inline int runImageTool(const ClassroomLine& cl, std::ostream& out, std::ostream& err) {
    std::string problem = cl.average || cl.ratio ? checkOutputs(cl, replaceExtension(cl.out, ".pfm")) : "";
    if (!problem.empty()) {
        err << "bdpt: " << problem << "\n";
        return 1;
    }
    Image a, b;
    const char* verb = cl.average ? "average" : cl.ratio ? "divide" : "compare";
    for (auto [path, img] : {std::make_pair(&cl.pfmA, &a), std::make_pair(&cl.pfmB, &b)}) {
        struct stat st;
        const char* why = stat(path->c_str(), &st) != 0 ? "does not exist" : !readPFM(*path, *img) ? "is not a PFM image (as bdpt writes)" : nullptr;
        if (why) {
            err << "bdpt: cannot " << verb << ": " << *path << " " << why << "\n";
            return 2;
        }
    }
    if (a.width != b.width || a.height != b.height) {
        err << "bdpt: cannot " << verb << ": " << cl.pfmA << " is " << a.width << "x" << a.height << ", " << cl.pfmB << " is " << b.width
            << "x" << b.height << "\n";
        return 2;
    }
    if (cl.ratio) return writeRatio(a, b, cl.pfmA, cl.pfmB, cl.out, out, err);
    if (!cl.average) {
        ErrorMetrics m = compareToReference(a, b);
        out << "rmse " << m.rmse << " relmse " << m.relMse << " bias " << m.bias << " mean " << m.mean << " rmse_without_lamp "
            << m.rmseWithoutLamp << "\n";
        return 0;
    }
    for (size_t i = 0; i < a.pixels.size(); ++i) a.pixels[i] = (a.pixels[i] + b.pixels[i]) * 0.5f;
    std::string pfm = replaceExtension(cl.out, ".pfm");
    if (savePNG(a, cl.out, cl.exposure) && savePFM(a, pfm)) {
        out << "wrote " << cl.out << " and " << pfm << "\n";
        return 0;
    }
    err << "bdpt: cannot write " << cl.out << " or " << pfm << "\n";
    return 1;
}

// What a method adds to the summary line: vcm's radius and light vertices (counted over the passes
// by the classroom), then the lecture's methodSummary (the chains' b and acceptance, the clamp).
inline void printMethodSummary(const ClassroomLine& cl, const Scene& scene, const RenderResult& r, const VcmTotals& vcm, std::ostream& out) {
    if (cl.opt.method == Method::VCM) out << vcmSummary(scene, r.passes, vcm);
    out << methodSummary(cl.opt, r.method.metropolis, r.clampRemoved());
}

// Writes the render's files: the PNG, its PFM and (--strategies) the strategy images and pyramids.
inline int writeOutputs(const ClassroomLine& cl, const RenderResult& r, const std::string& pfm, std::ostream& out, std::ostream& err) {
    if (!savePNG(r.image, cl.out, cl.exposure) || !savePFM(r.image, pfm)) {
        err << "bdpt: cannot write " << cl.out << " or " << pfm << "\n";
        std::remove(cl.out.c_str());
        return 1;
    }
    if (!cl.quiet) out << summaryLine(cl, r, pfm);
    if (!cl.strategiesDir.empty() &&
        (!writeStrategyImages(r.strategies, cl.strategiesDir, cl.exposure) || !writePyramids(r.strategies, cl.strategiesDir, cl.exposure, out))) {
        err << "bdpt: cannot write the strategy images into " << cl.strategiesDir << "/\n";
        return 1;
    }
    return 0;
}

// One method on one scene, as the classroom watches it: the log and live image after every pass,
// vcm's memory per pass, the profile clock around the whole.
inline int renderOne(ClassroomLine& cl, const Scene& scene, const Image& ref, std::ostream& out, std::ostream& err) {
    const std::string pfm = replaceExtension(cl.out, ".pfm");
    PassLog passLog(cl, scene, ref);
    if (!cl.logPath.empty() && !passLog.open()) { err << "bdpt: cannot write " << cl.logPath << " (nothing rendered)\n"; return 1; }
    VcmTotals vcm;
    PassSplit split;
    auto watch = [&](const Rendering& r) {
        if (cl.profile) split.endPass();
        if (!cl.logPath.empty() || cl.liveSeconds > 0) passLog.add(r);
        if (cl.opt.method == Method::VCM) vcm.add(r.storage.vcm);
        if (cl.profile) split.beginPass();
    };
    if (cl.profile) cl.opt.threads = 1, gCostClock.start(), split.beginPass();
    double cpu0 = threadCpuSeconds();
    bool interrupted = false;
    RenderResult r = renderWatched(scene, cl.opt, !cl.quiet, interrupted, watch);
    double cpu = threadCpuSeconds() - cpu0;
    if (cl.profile) gCostClock.switchTo(Cost::Other), gCostClock.on = false;
    if (!cl.logPath.empty()) {
        passLog.log.close();
        if (!passLog.log) { err << "bdpt: cannot write " << cl.logPath << "\n"; return 1; }
    }
    if (int status = writeOutputs(cl, r, pfm, out, err)) return status;
    if (interrupted) {
        err << "bdpt: interrupted: wrote the " << r.passes << " completed samples per pixel to " << cl.out << " and " << pfm << "\n";
        return kExitInterrupted;
    }
    if (!cl.quiet) printMethodSummary(cl, scene, r, vcm, out);
    if (cl.profile) printProfile(split, cpu, double(r.passes) * r.image.width * r.image.height, out);
    if (!cl.quiet && ref.width > 0) {
        ErrorMetrics m = compareToReference(r.image, ref, &scene);
        char text[256];
        std::snprintf(text, sizeof text, "against %s: rmse %.4g (%.4g without the lamp's pixels), relmse %.4g, bias %+.2f%%\n",
                      cl.refPath.c_str(), m.rmse, m.rmseWithoutLamp, m.relMse, 100 * m.bias);
        out << text;
    }
    return 0;
}

inline int runCommandLine(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    ClassroomLine cl;
    Scene scene;
    try {
        cl = parseCommandLine(args);
        if (cl.help) { out << usage(classroomTable()); return 0; }
        if (!cl.failureLogs.empty()) return printFailureTable(cl.failureLogs, out, err);
        if (!cl.pfmA.empty()) return runImageTool(cl, out, err);
        if (!cl.strategiesDir.empty() || !cl.sideBySide.empty())
            if (std::string why = fontProblem(); !why.empty()) throw InputError("bdpt: " + why + " (nothing rendered)");
        scene = loadSceneOrGuess(cl.scenePath);
        applyToScene(cl, scene);
    } catch (const InputError& e) {
        err << e.what() << "\n";
        return 2;
    }
    Image ref;
    if (int status = checkBeforeRendering(cl, scene, replaceExtension(cl.out, ".pfm"), ref, err)) return status;
    if (!cl.sideBySide.empty()) return runSideBySide(args, cl, scene, ref, out, err);
    if (cl.liveSeconds > 0)  // a first frame at once: a viewer opens it, and never shows an older run's image
        savePNG(Image(scene.camera.width, scene.camera.height), cl.out, 0);
    warnAboutScene(scene, cl.opt, err);
    warnAboutDuration(cl, scene, err);
    return renderOne(cl, scene, ref, out, err);
}

// ./bdpt's main: Ctrl-C's handler, the command line, and a render past the memory estimate said
// plainly. The test programs run it too (tests/helpers.h: a test that needs the program itself,
// its signals and its exit status, starts the test program as ./bdpt).
inline int classroomMain(int argc, char** argv) {
    std::signal(SIGINT, onInterrupt);
    try {
        return runCommandLine(std::vector<std::string>(argv + 1, argv + argc), std::cout, std::cerr);
    } catch (const std::bad_alloc&) {  // past the estimate: a scene larger than it, or a lower limit
        std::cerr << "bdpt: out of memory (a smaller --res, fewer --strategies, or another method); no file written\n";
        return 4;
    }
}

#ifdef CLASSROOM_MAIN
int main(int argc, char** argv) { return classroomMain(argc, argv); }
#endif
