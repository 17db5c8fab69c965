// classroom/options.h: the classroom's command line: the lecture's table with the tools' rows
// among its own, did-you-mean, the combinations it refuses, and a run's label in the charts.
#pragma once
#include <deque>
#include "lecture.h"

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


// The rows after --quiet: the live image and the side-by-side figure.
inline std::vector<OptionRow<ClassroomLine>> liveRows() {
    return {{"--live", "SECONDS", {}, "",
         "while rendering, rewrite the PNG from the passes so far at most every\n"
         "SECONDS (whole, by rename): an image viewer that reloads it shows the image\n"
         "converging (on a projector, say); --log is written as the passes finish",
         [](ClassroomLine& cl, ArgReader& a) { cl.liveSeconds = a.number(1e-3, 1e6); }},
        {"--side-by-side", "\"M1,M2 OPTIONS,...\"", {}, "",
         "render several methods at once into one titled 16:9 image (1920x1080 where\n"
         "the images fit): each entry a method and its own options (\"nee,nee --mis,\n"
         "ir --clamp 1e-5\"), every other option shared; all run together, --spp N\n"
         "gives each N samples per pixel, --time T each T seconds of CPU time on one\n"
         "thread of its own (equal CPU time however the cores are shared). Under each\n"
         "image: the slides' caption where the entry is one of their six methods, its\n"
         "samples, CPU seconds and, with --ref, RMSE; with --live a first frame at once.\n"
         "Each method's PFM goes beside the PNG (FILE-1-pt.pfm, ...). An entry may\n"
         "name its own scene (\"bdpt,bdpt scenes/sds-point.scene\"): one method on\n"
         "two scenes",
         [](ClassroomLine& cl, ArgReader& a) {
             std::stringstream list(a.value());
             for (std::string entry; std::getline(list, entry, ',');) cl.sideBySide.push_back(entry);
             if (cl.sideBySide.size() < 2 || cl.sideBySide.size() > 8) a.fail("--side-by-side needs 2 to 8 methods, separated by commas");
         }},
        {"--title", "TEXT", {}, "",
         "--side-by-side's first title line (the second always names the scene, its\n"
         "size and the samples or CPU time each panel had)",
         [](ClassroomLine& cl, ArgReader& a) { cl.title = a.value(); }},
        {"--ratio-panel", "mean|error", {}, "",
         "--side-by-side of two entries (right, then a deliberate mistake): a third\n"
         "panel, the second over the first in blocks; mean: the ratio of their means,\n"
         "grey where within the noise; error: of their squared errors against\n"
         "--ref (a mistake that adds noise, not bias); the overall ratio in the title",
         [](ClassroomLine& cl, ArgReader& a) {
             cl.ratioPanel = a.value();
             if (cl.ratioPanel != "mean" && cl.ratioPanel != "error") a.fail("--ratio-panel is mean or error");
         }}};
}

// The rows after --help: a reference's error, the log, the tools that read images and logs.
inline std::vector<OptionRow<ClassroomLine>> referenceRows() {
    return {{nullptr, "", {}, "",
         "Ctrl-C finishes the pass in flight, writes the completed passes and exits with status 130;\n"
         "a second Ctrl-C (a second or more after the first) abandons the render: no file, status 3.\n"
         "A render of a million pixels or more first says how long a pass will take (from a\n"
         "64x64 pass of the same scene and options).\n"
         "Speed against accuracy", nullptr},
        {"--ref", "FILE.pfm", {}, "",
         "reference image (same resolution): after every pass compute RMSE, relMSE,\n"
         "the relative bias of the mean and the firefly measure against it",
         [](ClassroomLine& cl, ArgReader& a) { cl.refPath = a.value(); }},
        {"--log", "FILE.csv", {}, "",
         "one row per pass: scene, method, options, pass, spp, cpu_seconds, rmse, relmse,\n"
         "mean, bias, firefly, nan_count, rmse_without_lamp (the lamp's pixels and their\n"
         "neighbours left out); error columns empty without --ref; written as the\n"
         "passes finish, flushed after each (tail -f follows the run)",
         [](ClassroomLine& cl, ArgReader& a) { cl.logPath = a.value(); }},
        {"--compare", "A.pfm B.pfm", {}, "", "print rmse, relmse and bias of A against B (e.g. two seeds of a reference)",
         [](ClassroomLine& cl, ArgReader& a) { cl.pfmA = a.value(), cl.pfmB = a.value(); }},
        {"--average", "A.pfm B.pfm", {}, "",
         "write the mean of A and B to --out (required; and its PFM): a reference\nfrom two seeds",
         [](ClassroomLine& cl, ArgReader& a) { cl.average = true, cl.pfmA = a.value(), cl.pfmB = a.value(); }},
        {"--ratio", "A.pfm B.pfm", {}, "",
         "write A/B over 4x4-pixel blocks to --out (required) in false colour\n"
         "(white: equal, red: A brighter, blue: A darker, full colour at one stop; the\n"
         "PFM holds the ratios), enlarged to at least 560 pixels under the files' names,\n"
         "the ratio of the means and the colour key; print its percentiles: where two\n"
         "methods differ",
         [](ClassroomLine& cl, ArgReader& a) { cl.ratio = true, cl.pfmA = a.value(), cl.pfmB = a.value(); }},
        {"--failure-table", "LOG.csv...", {}, "",
         "print the failure table (markdown, as Appendix A of the notes has it) from\n"
         "such logs: slope of log(rmse) against log(CPU seconds) (rmse without the lamp's\n"
         "pixels where the log has it), bias, fireflies, NaN count",
         [](ClassroomLine& cl, ArgReader& a) {
             cl.failureLogs.assign(a.args.begin() + a.i + 1, a.args.end());
             if (cl.failureLogs.empty()) a.fail("--failure-table needs log files");
             a.i = a.args.size();
         }}};
}

// The tools' rows, each placed after the lecture's row it follows in --help.
inline std::map<std::string, std::vector<OptionRow<ClassroomLine>>> toolRows() {
    return {
        {"--threads", {{"--profile", "", {}, "",
           "render on one thread and print the time per sample split into tracing,\n"
           "MIS weights, merging (vcm) and the rest (shading, sampling, camera, film),\n"
           "from the CPU's time stamp counter; the clock adds a few per cent",
           [](ClassroomLine& cl, ArgReader&) { cl.profile = true; }}}},
        {"--exposure", {{"--overwrite", "", {}, "",
           "let --out replace a file the project ships (a scene's reference, a figure of\n"
           "the notes: anything under scenes/ or lecture_notes/); refused without it",
           [](ClassroomLine& cl, ArgReader&) { cl.overwrite = true; }}}},
        {"--quiet", liveRows()},
        {"--help", referenceRows()},
    };
}


// What an option does more in ./bdpt than in the lecture's program: said after the lecture's words.
inline const std::map<std::string, std::string>& classroomAdditions() {
    static const std::map<std::string, std::string> more = {
        {"--radius", ": the summary line reports both"},
        {"--strategies", ",\nand two pyramid montages (each row brightened by the stops in its tiles'\nlabels)"},
        {"--quiet", ", and no progress bar"}};
    return more;
}

// The lecture's table (its help texts, with ./bdpt's additions) with the tools' rows among its own,
// and the exit statuses with the tools'.
inline std::vector<OptionRow<ClassroomLine>> classroomOptions() {
    const std::map<std::string, std::vector<OptionRow<ClassroomLine>>> tools = toolRows();
    static std::deque<std::string> helps;  // the texts the rows point to (a deque does not move them)
    std::vector<OptionRow<ClassroomLine>> table;
    for (const OptionRow<CommandLine>& o : kOptions) {
        OptionRow<ClassroomLine> row{o.name, o.value, o.methods, o.whose, o.help, nullptr};
        if (o.name && classroomAdditions().count(o.name)) row.help = helps.emplace_back(std::string(o.help) + classroomAdditions().at(o.name)).c_str();
        if (o.apply) row.apply = [lecture = o.apply](ClassroomLine& cl, ArgReader& a) { lecture(cl, a); };
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
inline const std::vector<OptionRow<ClassroomLine>>& classroomTable() {
    static const std::vector<OptionRow<ClassroomLine>> table = classroomOptions();
    return table;
}

// The options a misspelt one probably meant: the closest names, or what other programs call it.
inline std::string suggestedOption(const std::string& word) {
    static const std::map<std::string, std::string> otherNames = {
        {"--samples", "--spp"}, {"--output", "--out"}, {"--resolution", "--res"}, {"--depth", "--maxdepth"},
        {"--integrator", "--method"}, {"--mis-heuristic", "--heuristic"}, {"--reference", "--ref"}};
    if (otherNames.count(word)) return otherNames.at(word);
    std::vector<std::string> names;
    for (const OptionRow<ClassroomLine>& o : classroomTable())
        if (o.name) names.push_back(o.name);
    return closestWords(word, names);
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

inline std::string optionsLabel(const RenderOptions& o) {  // what distinguishes a run in the charts
    std::ostringstream s;
    if (o.method == Method::NEE && o.mis) s << "--mis ";
    if (o.method == Method::IR) s << "--vpls " << o.ir.vplPaths << (o.ir.clamp > 0 ? " --clamp " : "") << (o.ir.clamp > 0 ? std::to_string(o.ir.clamp) : "") << " ";
    if (o.method == Method::BDPT || o.method == Method::VCM) s << "--heuristic " << kHeuristicNames[int(o.heuristic)] << " ";
    if (o.method == Method::VCM) s << "--alpha " << o.vcm.alpha << " ";
    if (isMetropolis(o.method) && o.metropolis.fixedStart) s << "--fixed-start ";
    if (o.sampler != Sampler::Sobol) s << "--sampler " << kSamplerNames[int(o.sampler)] << " ";
    if (o.noScramble) s << "--no-scramble ";
    if (o.maxDepth != 32) s << "--maxdepth " << o.maxDepth;
    std::string r = s.str();
    while (!r.empty() && r.back() == ' ') r.pop_back();
    return r;
}
