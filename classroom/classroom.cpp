// ============================================================================================
// classroom/classroom.cpp: ./bdpt as a class uses it. The lecture's renderer, ../bdpt.cpp, with
// the classroom's tools around it: several methods side by side in one labelled image, a live
// image and a log of the error against a reference after every pass, the failure table, the
// comparison and ratio of two images, bdpt's strategies as the slides' labelled pyramid, checks
// before a long render (outputs, memory, the scene), a progress bar, Ctrl-C, --profile, and
// "did you mean". One translation unit (make builds ./bdpt from it); figures.h and checks.h are
// parts of it. Every option of ../bdpt.cpp's table is here too, with the tools' rows among them.
// ============================================================================================
#ifndef BDPT_NO_MAIN  // this program's main, not the lecture's
#define BDPT_NO_MAIN
#define CLASSROOM_MAIN
#endif
#include <chrono>
#include <cstdint>

// --profile: where a sample's time goes, by part of the work. The clock charges the time since its
// last reading to the part running then; a CostScope enters a part and, when it ends, hands the
// clock back to the part it interrupted (tracing inside a merge is tracing). Off, a scope costs a
// test of a flag. --profile renders on one thread, so one clock serves.
enum class Cost { Other, Tracing, Mis, Merging, Count };  // Other: shading, sampling, camera, film
struct CostClock {
    bool on = false;
    Cost current = Cost::Other;
    uint64_t last = 0, ticks[int(Cost::Count)] = {};
    static uint64_t timeStampCounter() {
#if defined(__x86_64__) || defined(__i386__)
        return __builtin_ia32_rdtsc();  // a few cycles where a clock call is tens
#else
        return uint64_t(std::chrono::steady_clock::now().time_since_epoch().count());
#endif
    }
    uint64_t (*now)() = &timeStampCounter;  // a test gives it a clock of its own, advanced by hand
    void switchTo(Cost next) {
        uint64_t t = now();
        ticks[int(current)] += t - last;
        last = t, current = next;
    }
};
inline CostClock gCostClock;
struct CostScope {
    Cost outer = gCostClock.current;
    explicit CostScope(Cost part) {
        if (gCostClock.on) gCostClock.switchTo(part);
    }
    ~CostScope() {
        if (gCostClock.on) gCostClock.switchTo(outer);
    }
};
#define PROFILE_PART(part) CostScope profiledPart(Cost::part)

#include "../bdpt.cpp"
#include <climits>
#include <csignal>
#include <ctime>
#include <iomanip>
#include <mutex>
#include <sys/resource.h>

// 13 h 20 min, 4 min 05 s, 12.3 s: what a person reads at a glance.
inline std::string duration(double seconds) {
    char text[32];
    long s = long(seconds + 0.5);
    if (seconds >= 3600) std::snprintf(text, sizeof text, "%ld h %02ld min", s / 3600, s / 60 % 60);
    else if (seconds >= 60) std::snprintf(text, sizeof text, "%ld min %02ld s", s / 60, s % 60);
    else std::snprintf(text, sizeof text, "%.1f s", seconds);
    return text;
}

struct ProgressBar {
    std::chrono::steady_clock::time_point last;
    void show(double fraction, int passes, double etaSeconds) {
        auto now = std::chrono::steady_clock::now();
        if (fraction < 1 && now - last < std::chrono::milliseconds(200)) return;
        last = now;
        int width = 30, filled = int(std::min(1.0, fraction) * width);
        std::fprintf(stderr, "\r[%s%s] %3d%%  pass %d  ETA %s   ", std::string(filled, '#').c_str(),
                     std::string(width - filled, '.').c_str(), int(100 * std::min(1.0, fraction)), passes,
                     duration(std::max(0.0, etaSeconds)).c_str());
        if (fraction >= 1) std::fprintf(stderr, "\n");
    }
};

// Ctrl-C: the first interrupt lets the pass in flight finish, then the render stops and the
// completed passes are written as usual (status 130). A second one removes the file being
// written, if any, and exits at once (status 3, "abandoned"); but a second signal within a second
// of the first is the same key press: `timeout -s INT` and some terminals signal the process and
// then its whole group. Only async-signal-safe calls in the handler.
constexpr int kExitInterrupted = 130, kExitAbandoned = 3;
inline std::atomic<int> gInterrupts{0};
inline std::atomic<long long> gFirstInterruptNs{0};
inline char gFileBeingWritten[4096] = {0};
inline void writeToStderr(const char* text) {
    ssize_t written = write(2, text, std::strlen(text));
    (void)written;  // nothing more to do if stderr is gone
}
extern "C" inline void onInterrupt(int) {
    timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    long long now = ts.tv_sec * 1000000000LL + ts.tv_nsec;
    if (gInterrupts.fetch_add(1) == 0) {
        gFirstInterruptNs = now;
        writeToStderr("\nbdpt: interrupted: finishing the pass in flight, then writing the image (Ctrl-C again to abandon it)\n");
        return;
    }
    if (now - gFirstInterruptNs.load() < 1000000000LL) return;
    if (gFileBeingWritten[0]) unlink(gFileBeingWritten);
    writeToStderr("bdpt: abandoned: no image written\n");
    _exit(kExitAbandoned);
}


// The classroom's files, each remembered while it is written, so that a second Ctrl-C removes it.
inline bool savePNG(const Image& img, const std::string& path, float exposure) {
    std::snprintf(gFileBeingWritten, sizeof gFileBeingWritten, "%s", tempName(path).c_str());
    bool ok = writePNG(img, path, exposure);
    gFileBeingWritten[0] = 0;
    return ok;
}
inline bool savePFM(const Image& img, const std::string& path) {
    std::snprintf(gFileBeingWritten, sizeof gFileBeingWritten, "%s", tempName(path).c_str());
    bool ok = writePFM(img, path);
    gFileBeingWritten[0] = 0;
    return ok;
}

// The command line with the tools' options besides the lecture's.
struct ClassroomLine : CommandLine {
    double liveSeconds = 0;      // --live: rewrite the PNG at most this often while rendering
    std::string refPath, logPath;
    std::vector<std::string> failureLogs;
    std::string pfmA, pfmB;      // --compare, --average or --ratio: the two images
    bool average = false;        // --average: write their mean to out
    bool ratio = false;          // --ratio: write their block ratio to out
    bool overwrite = false;      // --overwrite: --out may replace a file the project ships
    bool profile = false;        // --profile: one thread, the time per sample by part
    std::vector<std::string> sideBySide;  // --side-by-side: one method and its options per entry
    std::string title;           // --title: the side by side's first line
    std::string ratioPanel;      // --ratio-panel mean|error: the second entry over the first
};

// The tools' rows, each placed after the lecture's row it follows in --help.
using CR = ClassroomLine;
inline std::map<std::string, std::vector<OptionRow<CR>>> toolRows() {
    return {
        {"--threads", {{"--profile", "", {}, "",
           "render on one thread and print the time per sample split into tracing,\n"
           "MIS weights, merging (vcm) and the rest (shading, sampling, camera, film),\n"
           "from the CPU's time stamp counter; the clock adds a few per cent",
           [](CR& cl, A&) { cl.profile = true; }}}},
        {"--exposure", {{"--overwrite", "", {}, "",
           "let --out replace a file the project ships (a scene's reference, a figure of\n"
           "the notes: anything under scenes/ or lecture_notes/); refused without it",
           [](CR& cl, A&) { cl.overwrite = true; }}}},
        {"--quiet", {{"--live", "SECONDS", {}, "",
           "while rendering, rewrite the PNG from the passes so far at most every\n"
           "SECONDS (whole, by rename): an image viewer that reloads it shows the image\n"
           "converging (on a projector, say); --log is written as the passes finish",
           [](CR& cl, A& a) { cl.liveSeconds = a.number(1e-3, 1e6); }},
          {"--side-by-side", "\"M1,M2 OPTIONS,...\"", {}, "",
           "render several methods at once into one titled 16:9 image (1920x1080 where\n"
           "the images fit): each entry a method and its own options (\"nee,nee --mis,\n"
           "ir --clamp 1e-5\"), every other option shared; all run together, --spp N\n"
           "gives each N samples per pixel, --time T each T seconds of CPU time on one\n"
           "thread of its own (equal CPU time however the cores are shared). Under each\n"
           "image: the slides' caption where the entry is one of their six methods, its\n"
           "samples, seconds and, with --ref, RMSE; with --live a first frame at once.\n"
           "Each method's PFM goes beside the PNG (FILE-1-pt.pfm, ...). An entry may\n"
           "name its own scene (\"bdpt,bdpt scenes/sds-point.scene\"): one method on\n"
           "two scenes",
           [](CR& cl, A& a) {
               std::stringstream list(a.value());
               for (std::string entry; std::getline(list, entry, ',');) cl.sideBySide.push_back(entry);
               if (cl.sideBySide.size() < 2 || cl.sideBySide.size() > 8) a.fail("--side-by-side needs 2 to 8 methods, separated by commas");
           }},
          {"--title", "TEXT", {}, "",
           "--side-by-side's first title line (the second always names the scene, its\n"
           "size and the samples or CPU time each panel had)",
           [](CR& cl, A& a) { cl.title = a.value(); }},
          {"--ratio-panel", "mean|error", {}, "",
           "--side-by-side of two entries (right, then a deliberate mistake): a third\n"
           "panel, the second over the first in blocks; mean: the ratio of their means,\n"
           "grey where within the noise; error: of their squared errors against\n"
           "--ref (a mistake that adds noise, not bias); the overall ratio in the title",
           [](CR& cl, A& a) {
               cl.ratioPanel = a.value();
               if (cl.ratioPanel != "mean" && cl.ratioPanel != "error") a.fail("--ratio-panel is mean or error");
           }}}},
        {"--help", {{nullptr, "", {}, "",
           "Ctrl-C finishes the pass in flight, writes the completed passes and exits with status 130;\n"
           "a second Ctrl-C (a second or more after the first) abandons the render: no file, status 3.\n"
           "A render of a million pixels or more first says how long a pass will take (from a\n"
           "64x64 pass of the same scene and options).\n"
           "Speed against accuracy", nullptr},
          {"--ref", "FILE.pfm", {}, "",
           "reference image (same resolution): after every pass compute RMSE, relMSE,\n"
           "the relative bias of the mean and the firefly measure against it",
           [](CR& cl, A& a) { cl.refPath = a.value(); }},
          {"--log", "FILE.csv", {}, "",
           "one row per pass: scene, method, options, pass, spp, seconds, rmse, relmse,\n"
           "mean, bias, firefly, nan_count, rmse_without_lamp (the lamp's pixels and their\n"
           "neighbours left out); error columns empty without --ref; written as the\n"
           "passes finish, flushed after each (tail -f follows the run)",
           [](CR& cl, A& a) { cl.logPath = a.value(); }},
          {"--compare", "A.pfm B.pfm", {}, "", "print rmse, relmse and bias of A against B (e.g. two seeds of a reference)",
           [](CR& cl, A& a) { cl.pfmA = a.value(), cl.pfmB = a.value(); }},
          {"--average", "A.pfm B.pfm", {}, "",
           "write the mean of A and B to --out (required; and its PFM): a reference\nfrom two seeds",
           [](CR& cl, A& a) { cl.average = true, cl.pfmA = a.value(), cl.pfmB = a.value(); }},
          {"--ratio", "A.pfm B.pfm", {}, "",
           "write A/B over 4x4-pixel blocks to --out (required) in false colour\n"
           "(white: equal, red: A brighter, blue: A darker, full colour at one stop; the\n"
           "PFM holds the ratios), enlarged to at least 560 pixels under the files' names,\n"
           "the ratio of the means and the colour key; print its percentiles: where two\n"
           "methods differ",
           [](CR& cl, A& a) { cl.ratio = true, cl.pfmA = a.value(), cl.pfmB = a.value(); }},
          {"--failure-table", "LOG.csv...", {}, "",
           "print the failure table (markdown, as Appendix A of the notes has it) from\n"
           "such logs: slope of log(rmse) against log(seconds) (rmse without the lamp's\n"
           "pixels where the log has it), bias, fireflies, NaN count",
           [](CR& cl, A& a) {
               cl.failureLogs.assign(a.args.begin() + a.i + 1, a.args.end());
               if (cl.failureLogs.empty()) a.fail("--failure-table needs log files");
               a.i = a.args.size();
           }}}},
    };
}


// The lecture's table (its help texts as they are) with the tools' rows among its own, and the exit
// statuses with the tools'.
inline std::vector<OptionRow<CR>> classroomOptions() {
    const std::map<std::string, std::vector<OptionRow<CR>>> tools = toolRows();
    std::vector<OptionRow<CR>> table;
    for (const OptionRow<CommandLine>& o : kOptions) {
        OptionRow<CR> row{o.name, o.value, o.methods, o.whose, o.help, nullptr};
        if (o.apply) row.apply = [lecture = o.apply](CR& cl, A& a) { lecture(cl, a); };
        if (!o.name && std::string(o.help).rfind("Exit status", 0) == 0)
            row.help = "Exit status: 0 done, 1 an output file cannot be written (checked before rendering), 2 bad scene\n"
                       "file or option, 3 abandoned by a second Ctrl-C (nothing written), 4 out of memory (nothing\n"
                       "written), 130 interrupted by Ctrl-C (the completed passes written).\n"
                       "The make targets (charts, efficiency, bench, panels, ...): make help. All write into build/ but\n"
                       "make figures and make refs, which rewrite the committed figures, tables and references.";
        table.push_back(row);
        auto extra = o.name ? tools.find(o.name) : tools.end();
        if (extra != tools.end()) table.insert(table.end(), extra->second.begin(), extra->second.end());
    }
    return table;
}
inline const std::vector<OptionRow<CR>>& classroomTable() {
    static const std::vector<OptionRow<CR>> table = classroomOptions();
    return table;
}

// The option a misspelt one probably meant: the closest name, or what other programs call it.
inline std::string suggestedOption(const std::string& word) {
    static const std::map<std::string, std::string> otherNames = {
        {"--samples", "--spp"}, {"--output", "--out"}, {"--resolution", "--res"}, {"--depth", "--maxdepth"},
        {"--integrator", "--method"}, {"--mis-heuristic", "--heuristic"}, {"--reference", "--ref"}};
    if (otherNames.count(word)) return otherNames.at(word);
    std::vector<std::string> names;
    for (const OptionRow<CR>& o : classroomTable())
        if (o.name) names.push_back(o.name);
    return closestWord(word, names);
}


// The classroom's combinations, then the lecture's.
inline void checkClassroomCombinations(ClassroomLine& cl) {
    auto given = [&](const char* o) { return cl.given.count(o) > 0; };
    if (!hasExtension(cl.out, ".png")) ArgReader::fail("--out must name a .png file (the PFM goes beside it), got '" + printable(cl.out) + "'");
    if (!cl.logPath.empty() && !hasExtension(cl.logPath, ".csv")) ArgReader::fail("--log must name a .csv file, got '" + printable(cl.logPath) + "'");
    if ((cl.average || cl.ratio) && !given("--out"))
        ArgReader::fail(std::string(cl.average ? "--average" : "--ratio") + " writes an image: name it with --out FILE.png");
    if (!cl.pfmA.empty()) return;
    for (const char* figure : {"--title", "--ratio-panel"})
        if (cl.sideBySide.empty() && given(figure)) ArgReader::fail(std::string(figure) + " is for --side-by-side's figure: give --side-by-side");
    for (const char* alone : {"--method", "--log", "--strategies", "--profile"})
        if (!cl.sideBySide.empty() && given(alone))
            ArgReader::fail(std::string(alone) + " does not go with --side-by-side" +
                            (std::string(alone) == "--method" ? ": name the methods in its list" : ": render that method alone"));
    checkCombinations(cl, classroomTable(), cl.sideBySide.empty());  // side by side: each entry's own line is checked
}

inline ClassroomLine parseCommandLine(const std::vector<std::string>& args) {
    ClassroomLine cl = parseOptions(args, classroomTable(), suggestedOption);
    if (cl.help || !cl.failureLogs.empty()) return cl;
    if (cl.pfmA.empty() && cl.scenePath.empty()) ArgReader::fail("no scene file given");
    checkClassroomCombinations(cl);
    return cl;
}

#include "figures.h"
#include "checks.h"

inline std::string optionsLabel(const RenderOptions& o) {  // what distinguishes a run in the charts
    std::ostringstream s;
    if (o.method == Method::NEE && o.mis) s << "--mis ";
    if (o.method == Method::IR) s << "--vpls " << o.vplPaths << (o.clamp > 0 ? " --clamp " : "") << (o.clamp > 0 ? std::to_string(o.clamp) : "") << " ";
    if (o.method == Method::BDPT || o.method == Method::VCM) s << "--heuristic " << kHeuristicNames[int(o.heuristic)] << " ";
    if (o.method == Method::VCM) s << "--alpha " << o.alpha << " ";
    if (isMetropolis(o.method) && o.fixedStart) s << "--fixed-start ";
    if (o.sampler != Sampler::Sobol) s << "--sampler " << kSamplerNames[int(o.sampler)] << " ";
    if (o.noScramble) s << "--no-scramble ";
    if (o.maxDepth != 32) s << "--maxdepth " << o.maxDepth;
    std::string r = s.str();
    while (!r.empty() && r.back() == ' ') r.pop_back();
    return r;
}


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

// --log and --live, after every pass: the running mean against the reference, with the time spent
// measuring taken out of the clock. The log is flushed after each pass (tail -f follows a run);
// --live rewrites the PNG from the running mean (whole, by rename).
struct PassLog {
    const ClassroomLine& cl;
    const Image& ref;
    std::ofstream log;
    std::vector<double> running;
    std::chrono::steady_clock::time_point lastLive = std::chrono::steady_clock::now();
    PassLog(const ClassroomLine& c, const Scene& scene, const Image& reference)
        : cl(c), ref(reference), running(3 * size_t(scene.camera.width) * scene.camera.height, 0.0) {}
    bool open() {
        log.open(cl.logPath);
        log << "scene,method,options,pass,spp,cpu_seconds,rmse,relmse,mean,bias,firefly,nan_count,rmse_without_lamp\n";
        return bool(log.flush());
    }
    void add(const Rendering& r) {
        const int p = r.result.passes - 1;
        const double seconds = r.result.cpuSeconds;  // the render's own: the log's metrics are not in it
        Image mean(r.scene.camera.width, r.scene.camera.height);
        for (size_t i = 0; i < r.pass.size(); ++i)
            for (int c = 0; c < 3; ++c) mean.pixels[i][c] = float((running[3 * i + c] += r.pass[i][c]) / (p + 1));
        if (cl.liveSeconds > 0 && secondsSince(lastLive) >= cl.liveSeconds) {
            savePNG(mean, cl.out, cl.exposure);  // a failure here shows again at the end
            lastLive = std::chrono::steady_clock::now();
        }
        if (!cl.logPath.empty()) {
            log << fileStem(cl.scenePath) << "," << methodName(cl.opt.method) << "," << optionsLabel(cl.opt) << "," << p + 1 << "," << p + 1
                << "," << seconds << ",";
            if (ref.width > 0) {
                ErrorMetrics m = compareToReference(mean, ref, &r.scene);
                log << m.rmse << "," << m.relMse << "," << m.mean << "," << m.bias << "," << m.firefly << "," << r.result.nonFinite << ","
                    << m.rmseWithoutLamp << "\n";
            } else {
                log << ",," << imageMean(mean) << ",,," << r.result.nonFinite << ",\n";
            }
            log.flush();
        }
    }
};


// --profile's line: the render's CPU time per sample, split as the clock's ticks split.
inline void printProfile(const CostClock& clock, double cpuSeconds, double samples, std::ostream& out) {
    double ticks = 0;
    for (uint64_t t : clock.ticks) ticks += double(t);
    const double perSample = 1e6 * cpuSeconds / std::max(1.0, samples), share = 1 / std::max(1.0, ticks);
    const char* names[] = {"shading and sampling", "tracing", "MIS", "merging"};
    char text[128];
    std::snprintf(text, sizeof text, "profile (one thread): %.3g us per sample:", perSample);
    out << text;
    for (Cost part : {Cost::Tracing, Cost::Mis, Cost::Merging, Cost::Other}) {
        double f = double(clock.ticks[int(part)]) * share;
        std::snprintf(text, sizeof text, "%s %s %.3g (%.0f%%)", part == Cost::Tracing ? "" : ",", names[int(part)], f * perSample, 100 * f);
        out << text;
    }
    out << "\n";
}

// vcm's light vertices over the passes: the most one pass held, and how many in all.
struct VcmTotals {
    size_t mostBytes = 0;
    long long lightVertices = 0, mergeable = 0;
    void add(const VcmPass& vp) {
        size_t bytes = vp.paths.capacity() * sizeof(Subpath) + vp.stored.capacity() * sizeof(VcmPass::Stored) +
                       vp.grid.bucketStart.capacity() * sizeof(uint32_t);
        for (const std::vector<PathVertex>& row : vp.rowVertices) {
            bytes += row.capacity() * sizeof(PathVertex);
            lightVertices += (long long)row.size();
        }
        mostBytes = std::max(mostBytes, bytes);
        mergeable += (long long)vp.stored.size();
    }
};

// The classroom's render loop: the lecture's passes (Rendering), with after each one the pass
// handed to `watch` (the log, the live image, a side-by-side panel), a Ctrl-C honoured between
// passes, and the progress bar drawn by a thread of its own from the rows done in the pass.
// --time counts the render's CPU seconds (the bar reads the process's, as a single render is all it runs).
template <class Watch>
inline RenderResult renderWatched(const Scene& scene, const RenderOptions& opt, bool progressBar, bool& interrupted, const Watch& watch) {
    Rendering r(scene, opt);
    auto processCpuSeconds = [] {
        timespec t{};
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
        return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
    };
    const double cpuStart = processCpuSeconds();
    std::atomic<int> passesDone{0};
    std::atomic<bool> finished{false};
    std::thread bar;
    if (progressBar && isatty(2))
        bar = std::thread([&] {
            ProgressBar shown;
            for (; !finished; std::this_thread::sleep_for(std::chrono::milliseconds(100))) {
                double passes = passesDone + double(r.rowsDone) / scene.camera.height;
                double spent = opt.wallTime ? secondsSince(r.start) : processCpuSeconds() - cpuStart;
                double f = opt.seconds > 0 ? spent / opt.seconds : passes / std::max(1, opt.spp);
                shown.show(std::min(0.999, f), passesDone, secondsSince(r.start) * (1 / std::max(1e-9, f) - 1));
            }
            shown.show(1, passesDone, 0);
        });
    do {
        if (r.result.passes > 0 && gInterrupts.load() > 0) {
            interrupted = true;
            break;
        }
        r.addPass();
        passesDone = r.result.passes;
        watch(r);
    } while (morePasses(r));
    finished = true;
    if (bar.joinable()) bar.join();
    return r.finish();
}

// --side-by-side: several methods on one scene at once, each in a thread of its own (with its
// share of the cores), and one titled image of their running means, rewritten every --live
// seconds from the first moment on. With --time each panel renders on one thread until that
// thread's own CPU clock reaches the time: equal CPU time, however the cores are shared.
struct SideBySidePanel {
    std::string label;  // the entry as written: "ir --clamp 1e-5"
    ClassroomLine cl;
    Scene scene;        // its own copy (sharing the BVH): the deliberate mistakes are the scene's
    std::mutex lock;    // guards what follows, which the render's thread writes and the frames read
    std::vector<double> sum, sumSquares;  // per pixel and channel, over passes
    int passes = 0;
    double seconds = 0;  // CPU seconds, the panel's threads together
    bool done = false, outOfMemory = false;
    RenderResult result;
};

// The slides' captions of "Results from Different Techniques", for the entries that are exactly
// the methods they name.
inline std::string slideCaption(const std::string& entry) {
    static const std::map<std::string, std::string> captions = {
        {"pt", "(a) Unidirectional (eye tracing)"}, {"nee", "(b) Unidirectional + next event"},
        {"lt", "(c) Next event (light tracing)"},   {"ir", "(d) Instant radiosity"},
        {"bdpt", "(f) Bidirectional path tracing"}};
    if (entry.rfind("ir --clamp ", 0) == 0 && entry.find(' ', 11) == std::string::npos) return "(e) Instant radiosity (clamped)";
    auto it = captions.find(entry);
    return it == captions.end() ? "" : it->second;
}

// The figure for a projector: a title over the panels, each panel's caption under its own image,
// the images enlarged by the largest whole factor that fits 1920x1080, the canvas 16:9 (padded,
// content centred). Tiles are the panels and, with --ratio-panel, the ratio after them.
struct SideBySideLayout {
    int W, H, cols, rows, zoom = 1, scale, titleScale, titleLines, gap, strip, titleH, panelW, panelH, contentW, contentH,
        canvasW, canvasH, left, top;
    SideBySideLayout(int n, int width, int height, int widest, int widestTitle, int lines) : W(width), H(height), titleLines(lines) {
        cols = n <= 3 ? n : (n + 1) / 2;
        rows = (n + cols - 1) / cols;
        for (int z = 64; z >= 1; --z) {
            zoom = z;
            size(widest, widestTitle);
            if (contentW <= 1920 && contentH <= 1080) break;
        }
        canvasW = std::max({1920, contentW, (contentH * 16 + 8) / 9}), canvasH = std::max(contentH, (canvasW * 9 + 15) / 16);
        left = (canvasW - contentW) / 2, top = (canvasH - contentH) / 2;
    }
    void size(int widest, int widestTitle) {
        panelW = W * zoom, panelH = H * zoom;
        scale = std::max(1, std::min(4, (panelW - 4) / std::max(1, widest)));
        titleScale = std::max(scale, std::min(6, (cols * panelW) / std::max(1, widestTitle)));
        gap = 3 * scale;
        strip = 3 * 7 * scale + gap;  // three lines of caption under each image
        titleH = titleLines * 7 * titleScale + 2 * gap;
        contentW = cols * (panelW + gap) + gap, contentH = titleH + rows * (panelH + strip + gap) + gap;
    }
    int tileX(int i) const { return left + gap + (i % cols) * (panelW + gap); }
    int tileY(int i) const { return top + titleH + (i / cols) * (panelH + strip + gap); }
};

// A panel's running mean and the variance of that mean per pixel (from the passes' spread).
inline void panelMean(SideBySidePanel& panel, Image& mean, Image* variance, int& passes, double& seconds) {
    std::lock_guard<std::mutex> hold(panel.lock);
    passes = panel.passes, seconds = panel.seconds;
    for (size_t p = 0; passes > 0 && p < mean.pixels.size(); ++p)
        for (int c = 0; c < 3; ++c) {
            double m = panel.sum[3 * p + c] / passes;
            mean.pixels[p][c] = float(m);
            if (variance) variance->pixels[p][c] = float(std::max(0.0, panel.sumSquares[3 * p + c] / passes - m * m) / std::max(1, passes - 1));
        }
}

struct RatioPanel {
    std::string kind;  // "mean": B/A of the means; "error": B's squared error over A's, against --ref
    Image colours;
    double overall = 0;  // the ratio of the image means, or of the MSEs
};

// --ratio-panel: the second panel over the first in blocks a twelfth of the image across (large
// enough to read from the back of a room). "mean": grey where the blocks' means differ by less
// than 3 standard errors, or where either's standard error is over 15% of it (a few rare splats:
// the passes' spread is then no error bar); "error": each block's squared error against the
// reference, over two stops either way (a mistake that adds noise, not bias).
inline RatioPanel ratioPanel(std::vector<std::unique_ptr<SideBySidePanel>>& panels, const std::string& kind, const Image& ref) {
    const int W = panels[0]->scene.camera.width, H = panels[0]->scene.camera.height, block = std::max(2, std::min(W, H) / 12);
    Image a(W, H), b(W, H), va(W, H), vb(W, H);
    int passesA, passesB;
    double seconds;
    panelMean(*panels[0], a, &va, passesA, seconds);
    panelMean(*panels[1], b, &vb, passesB, seconds);
    RatioPanel r{kind, Image(W, H)};
    auto lum3 = [](const Vec3& v) { return double(v.x) + v.y + v.z; };
    auto sq = [](double d) { return d * d; };
    double errA = 0, errB = 0;
    for (int by = 0; by < H; by += block)
        for (int bx = 0; bx < W; bx += block) {
            double sa = 0, sb = 0, vsa = 0, vsb = 0;
            for (int y = by; y < std::min(H, by + block); ++y)
                for (int x = bx; x < std::min(W, bx + block); ++x) {
                    if (kind == "error") {
                        sa += sq(lum3(a.at(x, y)) - lum3(ref.at(x, y))), sb += sq(lum3(b.at(x, y)) - lum3(ref.at(x, y)));
                    } else {
                        sa += lum3(a.at(x, y)), sb += lum3(b.at(x, y)), vsa += lum3(va.at(x, y)), vsb += lum3(vb.at(x, y));
                    }
                }
            errA += sa, errB += sb;
            Vec3 colour(0.03f);  // black in both
            if (sa > 0 && sb > 0) {
                const float stops = kind == "error" ? 2 : 1, t = std::max(-1.0f, std::min(1.0f, float(std::log2(sb / sa)) / stops));
                colour = t >= 0 ? Vec3(1, 1 - t, 1 - t) : Vec3(1 + t, 1 + t, 1);
                // Within the noise: closer than 3 standard errors, or a block so noisy (a few rare
                // splats) that its spread from the passes is no error bar.
                if (kind == "mean" && (std::fabs(sb - sa) < 3 * std::sqrt(vsa + vsb) || vsa > sqr(0.15 * sa) || vsb > sqr(0.15 * sb)))
                    colour = Vec3(0.25f);
            } else if (sa > 0 || sb > 0) {
                colour = sb > 0 ? Vec3(1, 0, 0) : Vec3(0, 0, 1);
            }
            for (int y = by; y < std::min(H, by + block); ++y)
                for (int x = bx; x < std::min(W, bx + block); ++x) r.colours.at(x, y) = colour;
        }
    r.overall = kind == "error" ? errB / std::max(1e-30, errA) : imageMean(b) / std::max(1e-30, imageMean(a));
    return r;
}

inline std::string threeDigits(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", x);
    return text;
}

inline std::vector<unsigned char> sideBySideFrame(std::vector<std::unique_ptr<SideBySidePanel>>& panels, const Image& ref,
                                                  const SideBySideLayout& L, const std::vector<std::string>& title, const std::string& ratioKind) {
    std::vector<unsigned char> canvas(size_t(L.canvasW) * L.canvasH * 3, 24);
    auto caption = [&](int tile, int line, const std::string& text) {
        drawLabel(canvas, L.canvasW, L.canvasH, L.tileX(tile), L.tileY(tile) + L.panelH + L.gap / 2 + line * 7 * L.scale, text, L.scale);
    };
    for (size_t i = 0; i < panels.size(); ++i) {
        SideBySidePanel& panel = *panels[i];
        Image mean(L.W, L.H);
        int passes;
        double seconds;
        panelMean(panel, mean, nullptr, passes, seconds);
        blitZoomed(canvas, L.canvasW, toSRGBBytes(mean, panel.cl.exposure), L.W, L.H, L.zoom, L.tileX(int(i)), L.tileY(int(i)));
        const std::string slide = !ratioKind.empty() ? (i == 0 ? "right" : "deliberate mistake") : slideCaption(panel.label);
        std::string counts = passes > 0 ? std::to_string(passes) + " spp, " + threeDigits(seconds) + " CPU s" : "starting";
        caption(int(i), 0, slide.empty() ? panel.label : slide);
        caption(int(i), 1, slide.empty() ? counts : panel.label + ": " + counts);
        if (ref.width > 0 && passes > 0) caption(int(i), 2, "RMSE " + threeDigits(compareToReference(mean, ref, &panel.scene).rmse));
    }
    std::vector<std::string> lines = title;
    if (!ratioKind.empty() && panels[0]->passes > 0 && panels[1]->passes > 0) {
        RatioPanel r = ratioPanel(panels, ratioKind, ref);
        const int t = int(panels.size());
        blitZoomed(canvas, L.canvasW, toSRGBBytes(r.colours, 0), L.W, L.H, L.zoom, L.tileX(t), L.tileY(t));
        const std::string division = "'" + panels[1]->label + "' / '" + panels[0]->label + "'";
        if (ratioKind == "error") {
            caption(t, 0, "squared error: " + division);
            caption(t, 1, "blue 1/4 - white 1 - red 4");
            lines.push_back("squared error " + division + " = " + threeDigits(r.overall));
        } else {
            caption(t, 0, "mean: " + division);
            caption(t, 1, "blue 1/2 - white 1 - red 2");
            caption(t, 2, "grey: within the noise");
            lines.push_back(division + " = " + threeDigits(r.overall) + " on average");
        }
    }
    for (size_t k = 0; k < lines.size(); ++k)
        drawLabel(canvas, L.canvasW, L.canvasH, (L.canvasW - labelWidth(lines[k], L.titleScale)) / 2, L.top + L.gap + int(k) * 7 * L.titleScale,
                  lines[k], L.titleScale);
    return canvas;
}

// The panels' own command lines: the scene, the entry's method and options, and every option of
// the whole line but those of the one figure (--out, --live, --title, --ratio-panel) and
// --side-by-side itself.
inline std::vector<std::unique_ptr<SideBySidePanel>> sideBySidePanels(const std::vector<std::string>& args, const ClassroomLine& cl) {
    std::vector<std::string> shared;
    for (size_t i = 0; i < args.size(); ++i) {
        if (args[i] == "--side-by-side" || args[i] == "--out" || args[i] == "--live" || args[i] == "--title" || args[i] == "--ratio-panel") {
            ++i;
            continue;
        }
        if (args[i] != "--overwrite" && args[i] != cl.scenePath) shared.push_back(args[i]);
    }
    std::vector<std::unique_ptr<SideBySidePanel>> panels;
    for (const std::string& entry : cl.sideBySide) {
        auto panel = std::make_unique<SideBySidePanel>();
        std::vector<std::string> line = {cl.scenePath, "--method"};
        std::stringstream words(entry);
        for (std::string w; words >> w;) {
            if (hasExtension(w, "scene") && line.back().rfind("--", 0) != 0) line[0] = w;  // the entry's own scene
            else line.push_back(w);
            panel->label += (panel->label.empty() ? "" : " ") + w;
        }
        if (line.size() == 2) ArgReader::fail("--side-by-side has an empty entry (two commas, or one at an end)");
        line.insert(line.end(), shared.begin(), shared.end());
        try {
            panel->cl = parseCommandLine(line);
        } catch (const InputError& e) {
            throw InputError(std::string(e.what()) + ", in --side-by-side's entry '" + printable(entry) +
                             "' (an option of some methods only goes in their entries)");
        }
        panels.push_back(std::move(panel));
    }
    return panels;
}

// Each entry's scene: the main one (a copy, sharing its BVH), or its own, which must be of the
// same size and goes without a reference. Returns the exit status if one cannot be rendered.
inline int loadPanelScenes(std::vector<std::unique_ptr<SideBySidePanel>>& panels, const ClassroomLine& cl, const Scene& scene,
                           const Image& ref, std::ostream& err) {
    const int W = scene.camera.width, H = scene.camera.height;
    for (auto& panel : panels) {
        panel->scene = scene;
        if (panel->cl.scenePath == cl.scenePath) continue;
        try {
            panel->scene = loadSceneOrGuess(panel->cl.scenePath);
        } catch (const InputError& e) {
            err << e.what() << ", in --side-by-side's entry '" << printable(panel->label) << "'\n";
            return 2;
        }
        if (cl.width > 0) setResolution(panel->scene.camera, cl.width, cl.height);
        if (ref.width > 0) {
            err << "bdpt: --ref is one scene's reference: leave it out when an entry names its own scene (nothing rendered)\n";
            return 2;
        }
        if (panel->scene.camera.width != W || panel->scene.camera.height != H) {
            err << "bdpt: the scenes' images differ in size (" << cl.scenePath << " " << W << "x" << H << ", " << panel->cl.scenePath
                << " " << panel->scene.camera.width << "x" << panel->scene.camera.height
                << "): give them one with --res WxH (nothing rendered)\n";
            return 2;
        }
    }
    double needed = 0;
    for (auto& panel : panels) needed += estimatedBytes(panel->scene, panel->cl.opt, false);
    if (needed + 200e6 > memoryLimitBytes()) {
        err << "bdpt: these " << panels.size() << " renders need about " << std::setprecision(2) << std::fixed << needed / 1e9
            << " GB together, more than this process may use: use a smaller --res (nothing rendered)\n";
        return 1;
    }
    std::set<std::string> warned;  // every scene an entry renders, once
    for (auto& panel : panels)
        if (warned.insert(panel->cl.scenePath).second) warnAboutScene(panel->scene, panel->cl.opt, err);
    return 0;
}

// A panel's render, on its own thread with its share of the cores, adding each pass to the
// panel's running sum for the frames.
inline std::thread startPanel(SideBySidePanel& panel, int threads) {
    panel.scene.conventions = panel.cl.conventions;
    if (!panel.cl.exposureGiven) panel.cl.exposure = panel.scene.exposure;
    panel.cl.opt.threads = threads;
    panel.sum.assign(3 * size_t(panel.scene.camera.width) * panel.scene.camera.height, 0.0);
    panel.sumSquares = panel.sum;
    return std::thread([&panel] {
        auto addPass = [&](const Rendering& r) {
            std::lock_guard<std::mutex> hold(panel.lock);
            for (size_t i = 0; i < r.pass.size(); ++i)
                for (int c = 0; c < 3; ++c) panel.sum[3 * i + c] += r.pass[i][c], panel.sumSquares[3 * i + c] += sqr(r.pass[i][c]);
            panel.passes = r.result.passes;
            panel.seconds = r.result.cpuSeconds;
        };
        bool interrupted = false;
        try {
            panel.result = renderWatched(panel.scene, panel.cl.opt, false, interrupted, addPass);
        } catch (const std::bad_alloc&) {
            panel.outOfMemory = true;
        }
        std::lock_guard<std::mutex> hold(panel.lock);
        panel.done = true;
    });
}

// Each panel's PFM beside the PNG (FILE-1-pt.pfm, ...) and its line of the summary.
inline int writePanels(const std::vector<std::unique_ptr<SideBySidePanel>>& panels, const ClassroomLine& cl, const Image& ref,
                       std::ostream& out, std::ostream& err) {
    const std::string base = replaceExtension(cl.out, "");
    for (size_t i = 0; i < panels.size(); ++i) {
        const SideBySidePanel& panel = *panels[i];
        const std::string pfm = base + "-" + std::to_string(i + 1) + "-" + methodName(panel.cl.opt.method) + ".pfm";
        if (!savePFM(panel.result.image, pfm)) {
            err << "bdpt: cannot write " << pfm << "\n";
            return 1;
        }
        if (cl.quiet) continue;
        char text[160];
        std::snprintf(text, sizeof text, "%zu. %s: %d samples per pixel in %.2f CPU s on %d thread%s, mean %g, ", i + 1, panel.label.c_str(),
                      panel.result.passes, panel.result.cpuSeconds, panel.cl.opt.threads,
                      panel.cl.opt.threads > 1 ? "s" : "",
                      imageMean(panel.result.image));
        out << text << raysPerSample(panel.result) << "; wrote " << pfm;
        if (ref.width > 0) {
            ErrorMetrics m = compareToReference(panel.result.image, ref, &panel.scene);
            std::snprintf(text, sizeof text, "; rmse %.4g (%.4g without the lamp's pixels), bias %+.2f%%", m.rmse, m.rmseWithoutLamp, 100 * m.bias);
            out << text;
        }
        out << "\n";
    }
    return 0;
}

// The figure's title: --title's line, then what is compared: the scene, its size, the budget.
inline std::vector<std::string> sideBySideTitle(const std::vector<std::unique_ptr<SideBySidePanel>>& panels, const ClassroomLine& cl,
                                                const Scene& scene) {
    std::set<std::string> scenes;
    for (auto& panel : panels) scenes.insert(fileStem(panel->cl.scenePath));
    std::string what = scenes.size() == 1 ? *scenes.begin() : std::to_string(scenes.size()) + " scenes";
    what += " (" + std::to_string(scene.camera.width) + "x" + std::to_string(scene.camera.height) + "): ";
    if (cl.opt.seconds > 0) what += "equal CPU time, " + threeDigits(cl.opt.seconds) + " s each on one thread";
    else what += std::to_string(cl.opt.spp) + (cl.opt.spp == 1 ? " sample" : " samples") + " per pixel each";
    std::vector<std::string> lines;
    if (!cl.title.empty()) lines.push_back(cl.title);
    lines.push_back(what);
    return lines;
}

inline int runSideBySide(const std::vector<std::string>& args, ClassroomLine& cl, const Scene& scene, const Image& ref, std::ostream& out,
                         std::ostream& err) {
    std::vector<std::unique_ptr<SideBySidePanel>> panels;
    try {
        panels = sideBySidePanels(args, cl);
    } catch (const InputError& e) {
        err << e.what() << "\n";
        return 2;
    }
    if (int status = loadPanelScenes(panels, cl, scene, ref, err)) return status;
    if (!cl.ratioPanel.empty() && panels.size() != 2) {
        err << "bdpt: --ratio-panel divides the second entry by the first: give --side-by-side two entries (nothing rendered)\n";
        return 2;
    }
    if (cl.ratioPanel == "error" && ref.width == 0) {
        err << "bdpt: --ratio-panel error compares each entry's squared error against the reference: give --ref (nothing rendered)\n";
        return 2;
    }
    const int n = int(panels.size()), cores = cl.opt.threads > 0 ? cl.opt.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    const std::vector<std::string> title = sideBySideTitle(panels, cl, scene);
    int widest = labelWidth("(b) Unidirectional + next event", 1), widestTitle = 1;
    for (auto& panel : panels) widest = std::max(widest, labelWidth(panel->label + ": 999 spp, 99.9 CPU s", 1));
    if (!cl.ratioPanel.empty()) widest = std::max(widest, labelWidth("squared error: '" + panels[1]->label + "' / '" + panels[0]->label + "'", 1));
    for (const std::string& line : title) widestTitle = std::max(widestTitle, labelWidth(line, 1));
    const SideBySideLayout layout(n + !cl.ratioPanel.empty(), scene.camera.width, scene.camera.height, widest, widestTitle,
                                  int(title.size()) + !cl.ratioPanel.empty());
    auto writeFrame = [&] {
        std::snprintf(gFileBeingWritten, sizeof gFileBeingWritten, "%s", tempName(cl.out).c_str());
        bool ok = writePNGBytes(sideBySideFrame(panels, ref, layout, title, cl.ratioPanel), layout.canvasW, layout.canvasH, cl.out);
        gFileBeingWritten[0] = 0;
        return ok;
    };
    if (cl.liveSeconds > 0) writeFrame();  // at once: a viewer opens it, and never shows an older run's image
    std::vector<std::thread> running;
    for (auto& panel : panels) running.push_back(startPanel(*panel, cl.opt.seconds > 0 ? 1 : std::max(1, cores / n)));
    auto lastFrame = std::chrono::steady_clock::now();
    for (bool all = false; !all;) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        all = true;
        for (auto& panel : panels) {
            std::lock_guard<std::mutex> hold(panel->lock);
            all = all && panel->done;
        }
        if (!all && cl.liveSeconds > 0 && secondsSince(lastFrame) >= cl.liveSeconds) writeFrame(), lastFrame = std::chrono::steady_clock::now();
    }
    for (std::thread& t : running) t.join();
    for (auto& panel : panels)
        if (panel->outOfMemory) throw std::bad_alloc();
    if (!writeFrame()) {
        err << "bdpt: cannot write " << cl.out << "\n";
        return 1;
    }
    if (int status = writePanels(panels, cl, ref, out, err)) return status;
    if (!cl.quiet && !cl.ratioPanel.empty())
        out << "ratio panel: '" << panels[1]->label << "' / '" << panels[0]->label << "' = " << ratioPanel(panels, cl.ratioPanel, ref).overall
            << (cl.ratioPanel == "error" ? " (of the squared errors)" : " (of the means)") << "\n";
    if (!cl.quiet) out << "wrote " << cl.out << " (" << layout.canvasW << "x" << layout.canvasH << ")\n";
    if (gInterrupts.load() > 0) {
        err << "bdpt: interrupted: wrote the completed samples per pixel of every panel\n";
        return kExitInterrupted;
    }
    return 0;
}

// What a method adds to the summary line: vcm's radius and light vertices (counted over the passes
// by the classroom), then the lecture's methodSummary (the chains' b and acceptance, the clamp).
inline void printMethodSummary(const ClassroomLine& cl, const Scene& scene, const RenderResult& r, const VcmTotals& vcm, std::ostream& out) {
    char text[256];
    if (cl.opt.method == Method::VCM) {
        double pixelPasses = double(r.passes) * r.image.width * r.image.height;
        std::snprintf(text, sizeof text, "vcm: radius %g in pass 1, %g in pass %d; %.1f light vertices per pixel and pass, %.1f of them "
                      "mergeable; light subpaths and grid %.1f MB (%.0f bytes per light vertex)\n", mergeRadius(scene, cl.opt, 0),
                      mergeRadius(scene, cl.opt, r.passes - 1), r.passes, vcm.lightVertices / pixelPasses, vcm.mergeable / pixelPasses,
                      vcm.mostBytes / 1e6, vcm.mostBytes * double(r.passes) / std::max(1.0, double(vcm.lightVertices)));
        out << text;
    }
    out << methodSummary(cl.opt, r);
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
        (!writeStrategyImages(r, cl.opt.strategyMaxLength, cl.strategiesDir, cl.exposure) ||
         !writePyramids(r, cl.opt.strategyMaxLength, cl.strategiesDir, cl.exposure, out))) {
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
    auto watch = [&](const Rendering& r) {
        if (!cl.logPath.empty() || cl.liveSeconds > 0) passLog.add(r);
        if (cl.opt.method == Method::VCM) vcm.add(r.storage.vcm);
    };
    if (cl.profile) cl.opt.threads = 1, gCostClock = CostClock(), gCostClock.on = true, gCostClock.last = gCostClock.now();
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
    if (cl.profile) printProfile(gCostClock, cpu, double(r.passes) * r.image.width * r.image.height, out);
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

#ifdef CLASSROOM_MAIN
int main(int argc, char** argv) {
    std::signal(SIGINT, onInterrupt);
    try {
        return runCommandLine(std::vector<std::string>(argv + 1, argv + argc), std::cout, std::cerr);
    } catch (const std::bad_alloc&) {  // past the estimate: a scene larger than it, or a lower limit
        std::cerr << "bdpt: out of memory (a smaller --res, fewer --strategies, or another method); no file written\n";
        return 4;
    }
}
#endif
