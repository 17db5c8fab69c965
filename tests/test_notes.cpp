// The lecture notes cannot rot: every function they cite exists in bdpt.cpp, every command they
// show runs (at 1 sample per pixel and 8x8 pixels) and writes into build/, every make target
// exists, every figure they show is in lecture_notes/figures/, and the formulas they state are
// the ones the code computes.
#include "helpers.h"
#include "classroom/physics.h"
#include "classroom/definitions.h"
#include "classroom/workshop/densities.h"
#include "classroom/workshop/worked_path.h"
#include <dirent.h>
#include <regex>

static std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// The rows of a generated markdown table, each as its trimmed cells (the first, empty one dropped).
static std::vector<std::vector<std::string>> tableRows(const std::string& path) {
    std::vector<std::vector<std::string>> rows;
    std::istringstream table(slurp(path));
    for (std::string line; std::getline(table, line);) {
        if (line.rfind("| ", 0) != 0) continue;
        std::vector<std::string> cells;
        std::istringstream row(line.substr(1));
        for (std::string cell; std::getline(row, cell, '|');) {
            size_t first = cell.find_first_not_of(' '), last = cell.find_last_not_of(' ');
            cells.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
        }
        rows.push_back(cells);
    }
    return rows;
}

// A page's text with line breaks and runs of spaces as one space, so quotes may wrap.
// Appendix A is read in two files, its reading and its record (the generated tables and their
// discussion): its quotes may stand in either, so the record counts as part of it.
static const char* const kAppendixA = "appendix-a-speed-and-accuracy.md";
static const char* const kAppendixARecord = "appendix-a-record.md";

static std::string flatPage(const std::string& name) {
    std::string out, text = slurp("lecture_notes/" + name);
    if (name == kAppendixA) text += "\n" + slurp(std::string("lecture_notes/") + kAppendixARecord);
    for (char c : text) {
        if (c == '\n') c = ' ';
        if (!(c == ' ' && !out.empty() && out.back() == ' ')) out += c;
    }
    return out;
}

static std::vector<std::string> notePages() {
    std::vector<std::string> pages;
    DIR* dir = opendir("lecture_notes");
    for (dirent* e; dir && (e = readdir(dir));) {
        std::string n = e->d_name;
        if (n.size() > 3 && n.substr(n.size() - 3) == ".md") pages.push_back("lecture_notes/" + n);
    }
    if (dir) closedir(dir);
    std::sort(pages.begin(), pages.end());
    return pages;
}

// A number a page quotes from a run, and the page (its file name under lecture_notes/): the text
// is rebuilt from what backs it (a generated table, a command the page shows, a test's bound)
// and must stand in the page as built.
struct Quote {
    std::string page, text;
};

// Each quote stands in its page as built.
static void checkQuotesStand(const std::vector<Quote>& quotes) {
    for (const Quote& q : quotes) {
        CAPTURE(q.page);
        CAPTURE(q.text);
        CHECK(flatPage(q.page).find(q.text) != std::string::npos);
    }
}

// The renderer's source: the lecture's file and the classroom's rooms, which the notes cite too.
static const std::vector<std::string> kRendererFiles = {"bdpt.cpp", "classroom/classroom.cpp", "classroom/profile.h", "classroom/lecture.h",
                                                        "classroom/options.h", "classroom/run.h", "classroom/checks.h", "classroom/metrics.h",
                                                        "classroom/figures.h", "classroom/side_by_side.h"};
static std::string rendererSource() {
    std::string all;
    for (const std::string& f : kRendererFiles) all += slurp(f);
    return all;
}

// The names bdpt.cpp and classroom/ define (functions and structs), from the one index of
// definitions that the homework's cutter and the page's code view read too.
static std::set<std::string> definedNames(const std::vector<std::string>& files, bool functionsOnly) {
    std::set<std::string> names;
    for (const std::string& f : files)
        for (const definitions::Definition& d : definitions::index(slurp(f)))
            if (!functionsOnly || !d.isStruct) names.insert(d.name.substr(d.name.rfind(':') == std::string::npos ? 0 : d.name.rfind(':') + 1));
    return names;
}

// Where a page says a name of the renderer lives ("`nearLamp()` in `classroom/metrics.h`"), that
// file defines it: a function, a struct, or a shell function of a workshop script.
TEST_CASE("the notes' 'NAME in FILE' citations name the file that defines NAME") {
    std::regex cited("`([A-Za-z_][A-Za-z0-9_]*)(?:\\(\\))?` in `(bdpt\\.cpp|classroom/[A-Za-z_/.]+\\.(?:cpp|h|sh|py))`");
    int checked = 0;
    std::vector<std::string> pages = notePages();
    pages.push_back("README.md");
    for (const std::string& page : pages) {
        std::string text = slurp(page);
        for (std::sregex_iterator it(text.begin(), text.end(), cited), end; it != end; ++it) {
            const std::string name = (*it)[1], file = (*it)[2], source = slurp(file);
            const bool cpp = file.size() > 2 && (file.substr(file.size() - 2) == ".h" || file.substr(file.size() - 4) == ".cpp");
            std::regex script("(\\n" + name + "\\(\\) *\\{)|(\\ndef " + name + "\\()");  // a shell function, a Python one
            CAPTURE(page);
            CAPTURE(name);
            CAPTURE(file);
            CHECK(!source.empty());
            CHECK((cpp ? definedNames({file}, false).count(name) > 0 : std::regex_search(source, script)));
            ++checked;
        }
    }
    CHECK(checked >= 5);
}

TEST_CASE("the notes cite only functions that bdpt.cpp or classroom/ defines") {
    const std::set<std::string> defined = definedNames(kRendererFiles, true);
    CHECK(defined.count("misWeight") == 1);
    CHECK(defined.count("drawCoordinates") == 1);  // Rng::drawCoordinates, defined outside its struct
    CHECK(defined.count("Vec3") == 0);             // a struct, not a function
    std::vector<std::string> pages = notePages();
    CHECK(pages.size() >= 16);  // 15 pages and the index
    int cited = 0;
    std::regex call("`([A-Za-z_][A-Za-z0-9_]*)\\(\\)`");
    for (const std::string& page : pages) {
        std::string text = slurp(page);
        for (std::sregex_iterator it(text.begin(), text.end(), call), end; it != end; ++it) {
            std::string name = (*it)[1];
            CAPTURE(page);
            CAPTURE(name);
            CHECK(defined.count(name) == 1);
            ++cited;
        }
    }
    CHECK(cited > 40);
}

// A command line's words as the shell splits them: "a b" is one word (--side-by-side's list).
static std::vector<std::string> shellWords(const std::string& line) {
    std::vector<std::string> words;
    std::string w;
    bool quoted = false, any = false;
    for (char c : line) {
        if (c == '"') { quoted = !quoted; any = true; continue; }
        if (c == ' ' && !quoted) {
            if (any) words.push_back(w);
            w.clear(), any = false;
            continue;
        }
        w += c, any = true;
    }
    if (any) words.push_back(w);
    return words;
}

// A shown command made quick: its samples, time and resolution (its side-by-side entries' too)
// replaced by 1 sample at 8x8, its outputs sent to build/tmp/notes/.
static std::vector<std::string> quickArgs(const std::string& line) {
    std::vector<std::string> words = shellWords(line), args;
    auto intoBuild = [](const std::string& path) { return "build/tmp/notes/" + path.substr(path.find_last_of('/') + 1); };
    bool hasRef = std::find(words.begin(), words.end(), "--ref") != words.end();  // its size is the reference's
    auto isBudget = [&](const std::string& w) { return w == "--spp" || w == "--time" || (w == "--res" && !hasRef); };
    for (size_t i = 1; i < words.size(); ++i) {
        const std::string& w = words[i];
        bool hasValue = i + 1 < words.size();
        if (isBudget(w) && hasValue) { ++i; continue; }
        if (w == "--side-by-side" && hasValue) {
            std::string list, entry;
            std::stringstream entries(words[++i]);
            while (std::getline(entries, entry, ',')) {
                std::stringstream entryWords(entry);
                list += list.empty() ? "" : ",";
                for (std::string e, sep; entryWords >> e; sep = " ")
                    if (isBudget(e)) entryWords >> e;
                    else list += sep + e;
            }
            args.insert(args.end(), {w, list});
            continue;
        }
        if ((w == "--out" || w == "--strategies") && hasValue) { args.push_back(w); args.push_back(intoBuild(words[++i])); continue; }
        args.push_back(w.rfind("build/", 0) == 0 ? intoBuild(w) : w);  // an earlier command's output, as an input
    }
    args.insert(args.end(), {"--spp", "1", "--quiet"});
    if (!hasRef) args.insert(args.end(), {"--res", "8x8"});
    return args;
}

TEST_CASE("the code the notes show is bdpt.cpp's, line for line") {
    // An excerpt typed from memory drifts from the code (a second edition showed a loop that had
    // moved to another function, with a call missing an argument). Every line of a ```cpp block
    // but "..." must be a line of bdpt.cpp, indentation aside.
    std::set<std::string> code;
    std::istringstream source(rendererSource());
    auto trim = [](const std::string& line) {
        size_t first = line.find_first_not_of(' '), last = line.find_last_not_of(' ');
        return first == std::string::npos ? std::string() : line.substr(first, last - first + 1);
    };
    for (std::string line; std::getline(source, line);) code.insert(trim(line));
    int lines = 0;
    for (const std::string& page : notePages()) {
        std::istringstream text(slurp(page));
        bool inCode = false;
        for (std::string line; std::getline(text, line);) {
            if (line.rfind("```", 0) == 0) { inCode = line == "```cpp"; continue; }
            if (!inCode || trim(line).empty() || trim(line) == "...") continue;
            CAPTURE(page);
            CAPTURE(line);
            CHECK(code.count(trim(line)) == 1);
            ++lines;
        }
    }
    CHECK(lines >= 8);
}

TEST_CASE("every command the notes show runs") {
    std::system("mkdir -p build/tmp/notes");
    int commands = 0;
    for (const std::string& page : notePages()) {
        std::istringstream in(slurp(page));
        for (std::string line; std::getline(in, line);) {
            if (line.rfind("./bdpt ", 0) != 0) continue;
            std::vector<std::string> args = quickArgs(line);
            for (size_t i = 0; i + 1 < args.size(); ++i)
                if (args[i] == "--strategies") std::system(("mkdir -p " + args[i + 1]).c_str());
            std::ostringstream so, se;
            CAPTURE(page);
            CAPTURE(line);
            CAPTURE(se.str());
            CHECK(runCommandLine(args, so, se) == 0);
            ++commands;
        }
    }
    CHECK(commands >= 20);
}

TEST_CASE("the commands the notes show write into build/, never over the committed figures") {
    int outputs = 0;
    for (const std::string& page : notePages()) {
        std::istringstream in(slurp(page));
        for (std::string line; std::getline(in, line);) {
            if (line.rfind("./bdpt ", 0) != 0) continue;
            std::vector<std::string> w = shellWords(line);
            for (size_t i = 0; i + 1 < w.size(); ++i)
                if (w[i] == "--out" || w[i] == "--strategies") {
                    CAPTURE(page);
                    CAPTURE(line);
                    CHECK(w[i + 1].rfind("build/", 0) == 0);
                    ++outputs;
                }
        }
    }
    CHECK(outputs >= 30);
}

TEST_CASE("every page's exercises have answers, and every figure a caption") {
    int pages = 0, figures = 0;
    for (const std::string& page : notePages()) {
        std::string text = slurp(page);
        CAPTURE(page);
        if (text.find("## Exercises") != std::string::npos) {
            CHECK(text.find("### Answers (for the instructor)") != std::string::npos);
            ++pages;
        }
        // A figure line is followed, after one blank line, by its caption in italics (or by the
        // other half of a pair of figure lines).
        std::istringstream in(text);
        std::vector<std::string> lines;
        for (std::string line; std::getline(in, line);) lines.push_back(line);
        for (size_t i = 0; i < lines.size(); ++i) {
            if (lines[i].rfind("![", 0) != 0) continue;
            CAPTURE(lines[i]);
            REQUIRE(i + 2 < lines.size());
            CHECK((lines[i + 2].rfind("*", 0) == 0 || lines[i + 2].rfind("![", 0) == 0));
            ++figures;
        }
    }
    CHECK(pages >= 16);
    CHECK(figures >= 30);
}

// -- The formulas the pages state, checked against the code -----------------------------------
// Each check finds the formula on its page, as written, and evaluates it beside the code: a page
// edited to a wrong formula fails the first half, a code change that breaks it the second.
static bool pageSays(const std::string& page, const std::string& formula) {
    return slurp("lecture_notes/" + page).find(formula) != std::string::npos;
}

TEST_CASE("notes, page 5: the pinhole's p_omega = 1/(A cos^3), W_e cos / p_omega = 1, W_j = width height/(A cos^4)") {
    CHECK(pageSays("05-generating-paths.md", "p_omega = 1/(A cos^3 theta)"));
    CHECK(pageSays("05-generating-paths.md", "W_e = 1/(A cos^4 theta) makes W_e cos/p_omega = 1"));
    CHECK(pageSays("05-generating-paths.md", "W_j = width height/(A cos^4 theta)"));
    Scene scene = sceneAt("scenes/cornell.scene", 48, 32);
    const Camera& cam = scene.camera;
    Rng rng = makeRng(3, 0, 0);
    double worst = 0;
    for (int i = 0; i < 1000; ++i) {
        Vec3 d = cameraRay(cam, rng.uniform() * cam.width, rng.uniform() * cam.height).d;
        double c = dot(d, cam.forward), A = cam.imageArea;
        double pOmega = pdfCameraDirection(cam, d), Wj = pixelImportance(cam, d), We = Wj / (cam.width * cam.height);
        worst = std::max({worst, std::fabs(pOmega * A * c * c * c - 1), std::fabs(We * c / pOmega - 1),
                          std::fabs(Wj * A * c * c * c * c / (cam.width * cam.height) - 1)});
    }
    CHECK(worst < 1e-4);
}

TEST_CASE("notes, page 5: a light path starts at Phi_light / P(light) = Phi") {
    CHECK(pageSays("05-generating-paths.md", "= Phi_light / P(light) = Phi, the total power"));
    for (const char* file : {"scenes/cornell.scene", "tests/two-lights.scene"}) {
        Scene scene = sceneAt(file, 8, 8);
        Rng rng = makeRng(4, 0, 0);
        for (int i = 0; i < 200; ++i) {
            EmissionSample es = sampleEmission(scene, rng);
            CAPTURE(file);
            CHECK(average(es.weight) == doctest::Approx(scene.totalPower).epsilon(1e-4));
        }
    }
}

TEST_CASE("notes, pages 7 and 10: p_{k,s+1}/p_{k,s} = pdfRev/pdfFwd of the vertex changing sides, and the heuristics' table") {
    CHECK(pageSays("07-probabilities.md", "\\frac{p_{k,s+1}}{p_{k,s}} = \\frac{\\mathrm{pdfRev}(x_s)}{\\mathrm{pdfFwd}(x_s)}"));
    CHECK(pageSays("10-combining-estimators.md", "| `balance` | 1/(1 + sum r_i) |"));
    CHECK(pageSays("10-combining-estimators.md", "| `power` | 1/(1 + sum r_i^2) |"));
    // Paths of k = 2 on cornell: x_0 on the lamp, x_1 what a pixel sees, x_2 the pinhole. The
    // three strategies' densities as page 7 writes them, each vertex's from scratch
    // (tests/densities.h), and misWeight's weight of next event (s = 1) and of light tracing
    // (s = 2) against them.
    Scene scene = sceneAt("scenes/cornell.scene", 32, 32);
    int lamp = scene.lights[0].shape;
    RenderOptions opt = quietOptions(Method::BDPT, 1, 5);
    std::vector<PathVertex> camera, light;
    int checked = 0;
    double worst = 0;
    for (int i = 0; i < 400; ++i) {
        Rng rng = makeRng(5, uint64_t(i), 0);
        cameraSubpath(scene, opt, rng.uniform() * 32, rng.uniform() * 32, rng, camera);
        lightSubpath(scene, opt, rng, light);
        if (camera.size() < 2 || light.empty() || camera[1].delta) continue;
        TwoSegmentPath path = twoSegmentPath(scene, lamp, light[0].sp, camera[1].sp);
        if (!path.valid) continue;
        const double* p = path.p;
        for (Heuristic h : {Heuristic::Balance, Heuristic::Power}) {
            auto pw = [&](double x) { return h == Heuristic::Power ? x * x : x; };
            double sum = pw(p[0]) + pw(p[1]) + pw(p[2]);
            Connection c;
            int pixel = 0;
            if (isBlack(connectStrategy(scene, light, 1, camera, 2, c, pixel))) continue;
            double w1 = misWeight(scene, light, 1, camera, 2, h, c, 0);
            worst = std::max(worst, std::fabs(w1 - pw(p[1]) / sum));
            std::vector<PathVertex> lightPath = {light[0], camera[1]}, eye = {camera[0]};  // s = 2, t = 1
            lightPath[1].type = PathVertex::Surface;
            lightPath[1].wo = path.w;  // toward x_0, its predecessor on the light subpath
            lightPath[1].prevDist2 = float(path.dist2);
            lightPath[1].pdfFwd = p[2] / path.pLight;
            lightPath[1].pdfRev = 0;
            lightPath[1].continuation = albedoContinuation(scene, camera[1].sp);
            lightPath[0].pdfRev = 0;
            Connection c2;
            if (isBlack(connectStrategy(scene, lightPath, 2, eye, 1, c2, pixel))) continue;
            double w2 = misWeight(scene, lightPath, 2, eye, 1, h, c2, 0);
            worst = std::max(worst, std::fabs(w2 - pw(p[2]) / sum));
            ++checked;
        }
    }
    CHECK(checked > 100);
    CHECK(worst < 1e-3);
}

TEST_CASE("notes, pages 6 and 14: refraction scales radiance by (eta_o/eta_i)^2, importance by 1") {
    CHECK(pageSays("06-extending-paths.md", "scales radiance by (eta_o/eta_i)^2 and importance not at all"));
    CHECK(pageSays("14-power-versus-radiance.md", "L_o = (eta_o/eta_i)^2 L_i"));
    Scene scene = singleQuadScene(makeMaterial(Material::Glass, 1, 1.5f));
    SurfacePoint sp = surfaceAtOrigin();
    Rng rng = makeRng(6, 0, 0);
    int refractions = 0;
    for (Vec3 wo : {normalize(Vec3(0.3f, 0, 1)), normalize(Vec3(0.3f, 0, -1))}) {  // from air, from glass
        double etaO = wo.z > 0 ? 1 : 1.5, etaI = wo.z > 0 ? 1.5 : 1;
        for (int i = 0; i < 200; ++i)
            for (Transport mode : {Transport::Radiance, Transport::Importance}) {
                BsdfSample bs;
                if (!sampleBsdf(scene, sp, wo, mode, rng, bs) || bs.wi.z * wo.z > 0) continue;  // reflections
                double expected = mode == Transport::Radiance ? (etaO / etaI) * (etaO / etaI) : 1;
                CHECK(bs.weight.x == doctest::Approx(expected).epsilon(1e-5));
                ++refractions;
            }
    }
    CHECK(refractions > 500);
}

TEST_CASE("notes, page 13: the adjoint f*(wo,wi) = f(wi,wo) |wo.ns| |wi.ng| / (|wo.ng| |wi.ns|)") {
    CHECK(pageSays("13-shading-normals.md", "f^*(w_o, w_i) = f(w_i, w_o)\\, \\frac{|w_o \\cdot n_s|\\, |w_i \\cdot n_g|}{|w_o \\cdot n_g|\\, |w_i \\cdot n_s|}"));
    Scene scene = singleQuadScene(makeMaterial(Material::Diffuse, 0.8f));
    SurfacePoint sp = surfaceAtOrigin(normalize(Vec3(0.4f, 0.1f, 1)));
    Rng rng = makeRng(7, 0, 0);
    int pairs = 0;
    for (int i = 0; i < 2000; ++i) {
        Vec3 wo = sampleUniformSphere(rng.uniform(), rng.uniform()), wi = sampleUniformSphere(rng.uniform(), rng.uniform());
        float pdf, pdfRev;
        Vec3 radiance = evalBsdf(scene, sp, wo, wi, Transport::Radiance, pdf, pdfRev);   // f(wo,wi) |wi.ns|
        Vec3 importance = evalBsdf(scene, sp, wo, wi, Transport::Importance, pdf, pdfRev);
        if (radiance.x <= 0) continue;
        // Lambert's f is symmetric, so f(wi,wo) |wi.ns| is the radiance value itself.
        double factor = absDot(wo, sp.ns) * absDot(wi, sp.ng) / (absDot(wo, sp.ng) * absDot(wi, sp.ns));
        CHECK(importance.x == doctest::Approx(radiance.x * factor).epsilon(1e-4));
        ++pairs;
    }
    CHECK(pairs > 300);
}

TEST_CASE("notes, pages 4 and 9: the furnace's partial sums, and roulette's q = min(0.95, max channel of beta / beta at the start)") {
    CHECK(pageSays("04-measurement-equation.md", "Le (1 - a^(D+1))/(1-a)"));
    CHECK(pageSays("09-russian-roulette-and-sampling.md", "q = min(0.95, max channel of beta / beta at the start)"));
    Scene furnace = sceneAt("scenes/furnace.scene", 4, 4);
    for (int D : {0, 1, 3, 6}) {
        RenderOptions o = quietOptions(Method::PT, 2, 8);
        o.maxDepth = D;
        o.rrStart = 99;
        CHECK(imageMean(render(furnace, o).image) == doctest::Approx((1 - std::pow(0.5, D + 1)) / 0.5).epsilon(1e-5));
    }
    RenderOptions o;
    Rng rng = makeRng(9, 0, 0);
    int survived = 0, trials = 20000;
    for (int i = 0; i < trials; ++i) {
        Vec3 beta(0.2f, 0.4f, 0.1f);
        if (!russianRoulette(beta, 0.5f, o.rrStart, o, rng)) continue;
        ++survived;
        CHECK(beta.y == doctest::Approx(0.4 / 0.8));  // q = min(0.95, 0.4 / 0.5) = 0.8
    }
    CHECK(double(survived) / trials == doctest::Approx(0.8).epsilon(0.02));
}

// The pages that speak of vertices and strategies show a path with its vertices labelled as the
// slides label them (classroom/workshop/diagrams.py draws them): bdpt's idea, the densities, the path
// formulation, the combination of strategies, merging and Metropolis.
TEST_CASE("the pages on paths and strategies each show a path diagram") {
    int pages = 0;
    for (const char* page : {"03-bidirectional-path-tracing.md", "07-probabilities.md", "08-path-formulation.md",
                             "10-combining-estimators.md", "15-vertex-merging.md", "16-metropolis-sampling.md"}) {
        std::smatch m;
        std::string text = flatPage(page);
        CAPTURE(page);
        REQUIRE(std::regex_search(text, m, std::regex("\\(figures/(path-[a-z-]+\\.svg)\\)")));
        std::string svg = slurp("lecture_notes/figures/" + m[1].str());
        CHECK(svg.rfind("<svg", 0) == 0);
        int vertices = 0;
        for (size_t at = svg.find("<circle"); at != std::string::npos; at = svg.find("<circle", at + 1)) ++vertices;
        CHECK(vertices >= 4);  // a path: its vertices drawn, each labelled
        pages += svg.find("<title>") != std::string::npos && svg.find("</svg>") != std::string::npos;
    }
    CHECK(pages >= 6);
}

// A page's image is a figure to show in class: at least 560 pixels across (two fill a slide), as
// --side-by-side, --ratio, the pyramids and the charts draw them, each with its labels burned in.
TEST_CASE("every make target and every figure the notes mention exists, each image at least 560 pixels wide") {
    std::string makefile = slurp("Makefile");
    std::regex target("`make ([a-z-]+)`"), image("\\]\\((figures/[^)]+)\\)");
    std::regex program("`(?:make )?(build/[A-Za-z_-]+)[ `]");  // a program the notes build or run: build/all_tests, build/worked-path
    int targets = 0, images = 0, programs = 0;
    for (const std::string& page : notePages()) {
        std::string text = slurp(page);
        for (std::sregex_iterator it(text.begin(), text.end(), program), end; it != end; ++it) {
            CAPTURE(page);
            CAPTURE((*it)[1].str());
            const std::string name = (*it)[1].str();  // a rule of its own, or one test file's program (the pattern rule build/test_%)
            CHECK((makefile.find("\n" + name + ":") != std::string::npos || (name.rfind("build/test_", 0) == 0 && fileExists("tests/" + name.substr(6) + ".cpp"))));
            ++programs;
        }
        for (std::sregex_iterator it(text.begin(), text.end(), target), end; it != end; ++it) {
            CAPTURE((*it)[1].str());
            CHECK(makefile.find("\n" + (*it)[1].str() + ":") != std::string::npos);
            ++targets;
        }
        for (std::sregex_iterator it(text.begin(), text.end(), image), end; it != end; ++it) {
            CAPTURE(page);
            CAPTURE((*it)[1].str());
            const std::string path = "lecture_notes/" + (*it)[1].str();
            CHECK(fileExists(path));
            int w = 0, h = 0, channels = 0;
            if (hasExtension(path, "png") && stbi_info(path.c_str(), &w, &h, &channels) == 1) CHECK(w >= 560);
            ++images;
        }
    }
    CHECK(targets >= 3);
    CHECK(images >= 20);
    CHECK(programs >= 4);
}

TEST_CASE("every method has its own line style, the same in every chart; a chart has at most six, each its own colour") {
    std::system("bash classroom/workshop/charts.sh styles > build/tmp/styles.txt");
    std::istringstream in(slurp("build/tmp/styles.txt"));
    std::set<std::string> styles, labels, charted;
    std::map<std::string, std::string> colourOf;
    std::vector<std::vector<std::string>> charts;
    for (std::string line; std::getline(in, line);) {
        std::string first = line.substr(0, line.find(' ')), rest = line.substr(line.find(' ') + 1);
        if (first.rfind("chart", 0) == 0) {  // "chart-SUFFIX method method ...": one chart's curves
            std::istringstream words(rest);
            charts.emplace_back();
            for (std::string w; words >> w;) charts.back().push_back(w);
            continue;
        }
        labels.insert(first);
        styles.insert(rest);
        colourOf[first] = rest.substr(0, rest.find(" dt"));
        CHECK(line.find("#999999") == std::string::npos);  // the fallback: a method without its own style
    }
    CHECK(labels.size() == 14);
    CHECK(styles.size() == labels.size());
    CHECK(charts.size() >= 2);
    for (const std::vector<std::string>& chart : charts) {  // at most six curves, each its own colour
        CAPTURE(chart.size());
        CHECK(chart.size() <= 6);
        std::set<std::string> colours;
        for (const std::string& method : chart) {
            CHECK(labels.count(method) == 1);
            colours.insert(colourOf[method]);
            charted.insert(method);
        }
        CHECK(colours.size() == chart.size());
    }
    CHECK(charted == labels);  // every method is in some chart
}

static std::vector<Quote> referenceQuotes();

TEST_CASE("Appendix A quotes the reference check's range of ratios as the generated table has it") {
    std::vector<double> ratios;  // the last column, where it is a number ("exact" for the furnace)
    for (const auto& cells : tableRows("lecture_notes/figures/reference-check.md"))
        if (!cells.empty() && cells.back().find_first_of("0123456789") == 0) ratios.push_back(std::stod(cells.back()));
    REQUIRE(ratios.size() >= 10);
    // every chart's lowest curve ends well above its reference's noise (a reference then adds
    // under 8% to a charted RMSE): below that a chart measures the reference, not the method
    CHECK(*std::min_element(ratios.begin(), ratios.end()) >= 2.5);
    checkQuotesStand(referenceQuotes());
}


// What a render prints, by name, in the order printed (a --side-by-side run prints one of each
// per panel): samples per pixel, mean, rays per sample, and against --ref its errors.
static std::map<std::string, std::vector<double>> summaryNumbers(const std::string& output) {
    std::map<std::string, std::vector<double>> found;
    auto collect = [&](const char* pattern, std::vector<const char*> names) {
        std::regex re(pattern);
        for (std::sregex_iterator it(output.begin(), output.end(), re), end; it != end; ++it)
            for (size_t i = 0; i < names.size(); ++i)
                if ((*it)[i + 1].matched) found[names[i]].push_back(std::stod((*it)[i + 1]));
    };
    collect("(\\d+) samples per pixel in", {"spp"});
    collect(", mean ([-+0-9.e]+),", {"mean"});
    collect("([0-9.]+) rays per sample \\(([0-9.]+) closest-hit, ([0-9.]+) shadow\\)", {"rays", "closest", "shadow"});
    collect("rmse ([-+0-9.e]+) \\(([-+0-9.e]+) without the lamp's pixels\\)(?:, relmse ([-+0-9.e]+))?, bias ([-+0-9.]+)%",
            {"rmse", "rmse_without_lamp", "relmse", "bias"});
    collect("([0-9.]+) light vertices per pixel and pass, ([0-9.]+) of them mergeable; light subpaths and grid ([0-9.]+) MB \\(([0-9]+) bytes",
            {"light_vertices", "mergeable", "vcm_mb", "vcm_bytes"});
    collect("profile \\(one thread\\): ([0-9.e+-]+) us per sample: tracing ([0-9.e+-]+) \\(([0-9]+)%\\), MIS ([0-9.e+-]+) \\(([0-9]+)%\\), "
            "merging ([0-9.e+-]+) \\(([0-9]+)%\\), shading and sampling ([0-9.e+-]+) \\(([0-9]+)%\\)",
            {"us", "tracing", "tracing_pct", "mis", "mis_pct", "merging", "merging_pct", "rest", "rest_pct"});
    collect("ratio of means ([0-9.e+-]+); A/B over 4x4 blocks: 5% ([0-9.e+-]+), median ([0-9.e+-]+), 95% ([0-9.e+-]+); ([0-9.e+-]+)% of the blocks",
            {"ratio", "ratio_p5", "ratio_median", "ratio_p95", "ratio_apart"});
    for (size_t i = 0; i < found["rmse"].size() && i < found["rays"].size(); ++i)  // the table's 1/(MSE x rays)
        found["efficiency"].push_back(1 / (sqr(found["rmse"][i]) * found["rays"][i]));
    return found;
}

// Run quotes: each command as the page prints it (it must stand there), run as printed but for
// its outputs (into build/tmp/notes-runs/), once for each value of `vary` (an option whose value
// each run replaces or adds; none: one run). The quote's {C.NAME:FORMAT:WHICH} is command C's
// number NAME (NAME#K: the K-th printed) formatted, of run WHICH: a value's index (default 0),
// min or max over the runs; {C.NAME/D.NAME2:FORMAT} is a quotient of two.
// A command may add "|| OPTIONS" (not part of what the page prints): options that replace or are
// added to the printed ones, "!--name" removing one ("the same without --mis").
struct RunQuote {
    std::string page;
    std::vector<std::string> commands;
    std::string vary;
    std::vector<std::string> values;
    std::vector<std::string> quotes;
    bool fromFigures = false;  // not rerun: what the command printed when make figures ran it
};

// make figures' log of the pages' commands: each command as the page shows it, and its output.
static const std::map<std::string, std::string>& figureRuns() {
    static std::map<std::string, std::string> runs = [] {
        std::map<std::string, std::string> m;
        std::istringstream log(slurp("lecture_notes/figures/figure-commands.txt"));
        std::string command;
        for (std::string line; std::getline(log, line);)
            if (line.rfind("$ ", 0) == 0) command = line.substr(2);
            else if (!command.empty()) m[command] += line + "\n";
        return m;
    }();
    return runs;
}

static std::string printedPart(const std::string& command) { return command.substr(0, command.find(" ||")); }

// An option's place in words (the scene and values are not options), or words.size().
static size_t optionAt(const std::vector<std::string>& words, const std::string& name) {
    return size_t(std::find(words.begin(), words.end(), name) - words.begin());
}
static bool takesValue(const std::vector<std::string>& words, size_t i) { return i + 1 < words.size() && words[i + 1].rfind("--", 0) != 0; }

static void setOption(std::vector<std::string>& words, const std::string& name, const std::string* value) {
    size_t i = optionAt(words, name);
    if (i == words.size()) {
        words.push_back(name);
        if (value) words.push_back(*value);
    } else if (value) {
        words[i + 1] = *value;
    }
}

// The words of a run: the printed command with its overrides and `vary` set to value, every
// path under build/ (an output, or an earlier run's output as an input) in build/tmp/notes-runs/.
static std::vector<std::string> runArgs(const std::string& command, const std::string& vary, const std::string& value) {
    std::vector<std::string> words = shellWords(printedPart(command)), overrides;
    words.erase(words.begin());  // ./bdpt
    if (command.find(" ||") != std::string::npos) overrides = shellWords(command.substr(command.find(" ||") + 3));
    for (size_t i = 0; i < overrides.size(); ++i) {
        if (overrides[i][0] == '!') {
            size_t at = optionAt(words, overrides[i].substr(1));
            REQUIRE(at < words.size());
            words.erase(words.begin() + long(at), words.begin() + long(at + (takesValue(words, at) ? 2 : 1)));
        } else {
            bool hasValue = takesValue(overrides, i);
            setOption(words, overrides[i], hasValue ? &overrides[i + 1] : nullptr);
            i += hasValue;
        }
    }
    if (!vary.empty()) setOption(words, vary, &value);
    for (std::string& w : words)
        if (w.rfind("build/", 0) == 0) w = "build/tmp/notes-runs/" + w.substr(w.find_last_of('/') + 1);
    return words;
}

static std::string fillQuote(const RunQuote& q, const std::string& quote,
                             const std::vector<std::vector<std::map<std::string, std::vector<double>>>>& runs) {
    std::regex field("\\{([0-9])\\.([a-z0-9_]+)(?:#([0-9]))?(?:/([0-9])\\.([a-z0-9_]+)(?:#([0-9]))?)?:([^:}]+)(?::([a-z0-9]+))?\\}");
    std::string out, rest = quote;
    std::smatch m;
    while (std::regex_search(rest, m, field)) {
        auto number = [&](int c, const std::string& name, const std::string& k, size_t run) {
            const std::vector<double>& v = runs.at(size_t(c)).at(run).at(name);
            return v.at(k.empty() ? 0 : size_t(std::stoi(k)) - 1);
        };
        auto value = [&](size_t run) {
            double x = number(std::stoi(m[1]), m[2], m[3], run);
            return m[4].matched ? x / number(std::stoi(m[4]), m[5], m[6], run) : x;
        };
        std::string which = m[8].matched ? m[8].str() : "0";
        double x = value(0);
        if (which == "min" || which == "max")
            for (size_t r = 1; r < q.values.size(); ++r) x = which == "min" ? std::min(x, value(r)) : std::max(x, value(r));
        else
            x = value(size_t(std::stoi(which)));
        char text[64];
        std::snprintf(text, sizeof text, m[7].str().c_str(), x);
        out += m.prefix().str() + text;
        rest = m.suffix();
    }
    return out + rest;
}

static std::vector<RunQuote> runQuoteTable();

// A --strategies run's weighted images: each one's mean, as the number s2_t1 (s = 2, t = 1).
static void addStrategyMeans(const std::vector<std::string>& args, std::map<std::string, std::vector<double>>& numbers) {
    size_t at = optionAt(args, "--strategies");
    if (at + 1 >= args.size()) return;
    for (int s = 0; s <= 6; ++s)
        for (int t = 1; s + t <= 7; ++t) {
            Image img;
            std::string name = "s" + std::to_string(s) + "_t" + std::to_string(t);
            if (readPFM(args[at + 1] + "/" + name + "_weighted.pfm", img)) numbers[name].push_back(imageMean(img));
        }
}

// The run quotes, rendered once per test program.
static const std::vector<Quote>& runQuotes() {
    static std::vector<Quote> quotes = [] {
        std::system("mkdir -p build/tmp/notes-runs");
        std::vector<Quote> built;
        for (const RunQuote& q : runQuoteTable()) {
            std::vector<std::vector<std::map<std::string, std::vector<double>>>> runs;
            for (const std::string& command : q.commands) {
                runs.emplace_back();
                if (q.fromFigures) {
                    auto run = figureRuns().find(printedPart(command));
                    CAPTURE(command);
                    REQUIRE(run != figureRuns().end());
                    runs.back().push_back(summaryNumbers(run->second));
                    continue;
                }
                for (const std::string& value : q.values.empty() ? std::vector<std::string>{""} : q.values) {
                    std::ostringstream so, se;
                    int status = runCommandLine(runArgs(command, q.vary, value), so, se);
                    CAPTURE(command);
                    CAPTURE(se.str());
                    CHECK(status == 0);
                    runs.back().push_back(summaryNumbers(so.str()));
                    addStrategyMeans(runArgs(command, q.vary, value), runs.back().back());
                }
            }
            for (const std::string& quote : q.quotes) built.push_back({q.page, fillQuote(q, quote, runs)});
        }
        return built;
    }();
    return quotes;
}

// The efficiency table's quotes (make figures), each rebuilt from the table; its range checks too.
static std::vector<Quote> efficiencyQuotes() {
    // Typed prose beside a regenerated table goes stale; each quote is rebuilt from the table.
    // "scene|method" -> the row's cells: MSE, CPU-s, rays/sample, efficiency ("0.89x"), share
    std::map<std::string, std::vector<std::string>> eff;
    for (const auto& cells : tableRows("lecture_notes/figures/efficiency.md"))
        if (cells.size() >= 7 && cells[5].size() > 1 && cells[5].back() == 'x') eff[cells[0] + "|" + cells[1]] = {cells.begin() + 2, cells.end()};
    REQUIRE(eff.size() >= 60);
    auto col = [&](const char* scene, const char* method, int i) { return eff.at(std::string(scene) + "|" + method).at(size_t(i)); };
    auto e = [&](const char* scene, const char* method) { return col(scene, method, 3); };
    auto quotient = [&](const char* scene, const char* a, const char* b, int i) {  // cell a / cell b
        return std::stod(col(scene, a, i)) / std::stod(col(scene, b, i));
    };
    auto ratio = [&](const char* format, const char* scene, const char* a, const char* b, int i) {  // as the page prints it
        char text[32];
        std::snprintf(text, sizeof text, format, quotient(scene, a, b, i));
        return std::string(text);
    };
    const int mse = 0, cpu = 1, rays = 2, efficiency = 3, share = 4;
    const std::string p10 = "10-combining-estimators.md", p12 = "12-comparison-with-path-tracing.md", p15 = "15-vertex-merging.md",
                      p17 = "17-veach-mutations.md", a = "appendix-a-speed-and-accuracy.md";
    std::vector<Quote> quotes = {
        {p12, "bdpt is " + e("cornell", "bdpt") + " nee --mis"},
        {p12, e("indirect", "bdpt") + " on `scenes/indirect.scene`, " + e("glass-box", "bdpt") + " (glass-box) and " + e("cornell-glass", "bdpt") + " (cornell-glass)"},
        {p12, "lt at " + e("indirect", "lt") + " and bdpt at " + e("indirect", "bdpt")},
        {p12, "costs about " + ratio("%.1f", "cornell", "bdpt", "nee", cpu) + " nee samples"},
        {p12, "table bdpt traces " + col("cornell", "bdpt", rays) + " per sample against nee's " + col("cornell", "nee", rays)},
        {p15, "cornell " + e("cornell", "vcm") + " (bdpt " + e("cornell", "bdpt") + "), indirect " + e("indirect", "vcm") + " (bdpt " + e("indirect", "bdpt") + ")"},
        {p15, "cornell-glass " + e("cornell-glass", "vcm") + " (bdpt " + e("cornell-glass", "bdpt") + "), glass-box " + e("glass-box", "vcm") + " (bdpt " + e("glass-box", "bdpt") + ";"},
        {p15, e("sds-ior1", "vcm") + " nee --mis, bdpt " + e("sds-ior1", "bdpt")},
        {a, "nee --mis wins (bdpt " + e("cornell", "bdpt") + ")"},
        {a, "lead (" + e("indirect", "lt") + " and " + e("indirect", "bdpt")},
        {a, e("cornell-glass", "bdpt") + " on cornell-glass and " + e("glass-box", "bdpt") + " on glass-box"},
        {a, "(cornell " + e("cornell", "vcm") + " against " + e("cornell", "bdpt") + ", indirect " + e("indirect", "vcm") + " against " + e("indirect", "bdpt")},
        {a, "(cornell-glass " + e("cornell-glass", "vcm") + " against " + e("cornell-glass", "bdpt") + ", glass-box " + e("glass-box", "vcm") + " against " + e("glass-box", "bdpt")},
        {a, "(mmlt " + e("sds-ior1", "mmlt") + " against bdpt's " + e("sds-ior1", "bdpt")},
        {a, "light tracing leads (" + e("door", "lt") + "), bdpt follows (" + e("door", "bdpt") + "), Veach's mlt is close behind (" + e("door", "mlt") +
                ") and pssmlt reaches " + e("door", "pssmlt")},
        {p10, col("indirect", "bdpt", mse) + " for balance, " + col("indirect", "bdpt --heuristic power", mse) + " power, " +
                   col("indirect", "bdpt --heuristic max", mse) + " max and " + col("indirect", "bdpt --heuristic uniform", mse) + " uniform"},
        {p10, "balance's MSE is " + col("indirect", "bdpt", mse) + " against power's " + col("indirect", "bdpt --heuristic power", mse) + ", max's " +
                   col("indirect", "bdpt --heuristic max", mse) + " and uniform's " + col("indirect", "bdpt --heuristic uniform", mse)},
        // numbers derived from the table: ratios of its cells
        {a, "bdpt's MSE is " + ratio("%.2fx", "cornell", "bdpt", "nee --mis", mse) + " nee's"},
        {a, "a sample costing " + ratio("%.2fx", "cornell", "vcm", "bdpt", cpu) + " and " + ratio("%.2fx", "indirect", "vcm", "bdpt", cpu) + " bdpt's here"},
        {a, "comes out ahead of bdpt (" + e("sds-ior1", "mlt") + ")"},
        {"16-metropolis-sampling.md", "light tracing wins (" + e("door", "lt") + " nee --mis; bdpt " + e("door", "bdpt") + ", mlt " + e("door", "mlt") +
                                          ", pssmlt " + e("door", "pssmlt") + ", mmlt " + e("door", "mmlt") + ")"},
        {"16-metropolis-sampling.md", "(pssmlt " + e("cornell", "pssmlt") + ", bdpt " + e("cornell", "bdpt") + ")"},
        {p15, "a vcm sample costs " + ratio("%.2fx", "cornell", "vcm", "bdpt", cpu) + " a bdpt sample on cornell and " +
                  ratio("%.2fx", "sds-ior1", "vcm", "bdpt", cpu) + " on sds-ior1"},
        {p17, "cornell-glass " + ratio("%.2fx", "cornell-glass", "mlt", "pssmlt", efficiency) + ", glass-box " + ratio("%.2fx", "glass-box", "mlt", "pssmlt", efficiency) +
                  ", indirect " + ratio("%.2fx", "indirect", "mlt", "pssmlt", efficiency) + " pssmlt's efficiency"},
        {a, "a sample costs " + ratio("%.1fx", "cornell", "bdpt", "nee", cpu) + " (CPU seconds; " + col("cornell", "bdpt", rays) +
                 " rays against " + col("cornell", "nee", rays) + ")"},
        {a, "For bdpt on glass-box that share is " + col("glass-box", "bdpt", share)},
        {a, "its MSE is " + ratio("%.0fx", "sds-ior1", "bdpt", "vcm", mse) + " below bdpt's"},
        {p15, "vcm's MSE is " + ratio("%.2fx", "glass-box", "vcm", "nee", mse) + " nee's, bdpt's " + ratio("%.2fx", "glass-box", "bdpt", "nee", mse)},
        {p15, "vcm's MSE is " + ratio("%.0fx", "sds-ior1", "bdpt", "vcm", mse) + " below bdpt's"},
        {a, "its MSE at equal mutations is " + ratio("%.1f", "cornell", "mmlt", "pssmlt", mse) + " to " +
                   ratio("%.0f", "glass-box", "mmlt", "pssmlt", mse) + " times pssmlt's"},
        {a, "its MSE is " + ratio("%.2fx", "door", "pssmlt", "bdpt", mse) + " bdpt's"},
        {a, "a mutation costs " + ratio("%.1fx", "door", "pssmlt", "bdpt", cpu) + " a bdpt sample there"},
        {a, col("door", "pssmlt", rays) + " rays per sample against " + col("door", "bdpt", rays)},
    };
    // Appendix A: cornell-glass's ratio lies between cornell's and glass-box's, the range it quotes
    double cornellGlass = quotient("cornell-glass", "mmlt", "pssmlt", mse);
    CHECK(cornellGlass >= quotient("cornell", "mmlt", "pssmlt", mse));
    CHECK(cornellGlass <= quotient("glass-box", "mmlt", "pssmlt", mse));
    // Appendix A: "The Metropolis methods lose to bdpt on these scenes", but mlt on sds-ior1, where
    // every method but vcm has one error, the bias; and mlt loses to pssmlt on glass and indirect.
    for (const char* scene : {"cornell", "cornell-glass", "indirect", "glass-box", "door"})
        for (const char* method : {"mlt", "pssmlt", "mmlt"}) {
            CAPTURE(scene);
            CAPTURE(method);
            CHECK(std::stod(e(scene, method)) < std::stod(e(scene, "bdpt")));
        }
    CHECK(std::stod(e("sds-ior1", "mlt")) > std::stod(e("sds-ior1", "bdpt")));
    for (const char* scene : {"cornell-glass", "indirect", "glass-box"}) CHECK(std::stod(e(scene, "mlt")) < std::stod(e(scene, "pssmlt")));
    // Appendix A: "mmlt's unevenness is above bdpt's (the table)", the spliced make uneven table
    std::map<std::string, double> unevenness;
    for (const auto& cells : tableRows("lecture_notes/figures/uneven-door.md"))
        if (cells.size() >= 5 && cells[4].find_first_of("0123456789") == 0) unevenness[cells[0]] = std::stod(cells[4]);
    REQUIRE(unevenness.size() == 4);
    CHECK(unevenness["mmlt"] > unevenness["bdpt"]);
    return quotes;
}

// The failure table's quotes (make figures), each rebuilt from the table.
static std::vector<Quote> failureQuotes() {
    // "scene|method" -> {slope, bias}; a method is named by its label's first word, bdpt by
    // its heuristic ("bdpt balance"), ir --clamp and nee --mis as such.
    std::map<std::string, std::pair<std::string, std::string>> cell;
    std::map<std::string, std::string> fireflies;
    for (const auto& c : tableRows("lecture_notes/figures/failure-table.md")) {
        if (c.size() < 4 || c[2] == "slope" || c[2].find("---") != std::string::npos) continue;
        std::string m = c[1];
        if (m.rfind("bdpt --heuristic ", 0) == 0) m = "bdpt " + m.substr(17);
        else if (m.rfind("ir --vpls 16 --clamp", 0) == 0) m = "ir --clamp";
        else if (m != "nee --mis") m = m.substr(0, m.find(' '));
        cell[c[0] + "|" + m] = {c[2], c[3]};
        fireflies[c[0] + "|" + m] = c[4];
        CHECK(c.at(5) == "0");  // Appendix A: no method drops a non-finite sample on any scene
    }
    REQUIRE(cell.size() == 168);  // 12 scenes x 14 methods, each row its own key
    auto slope = [&](const char* s, const char* m) { return cell.at(std::string(s) + "|" + m).first; };
    auto bias = [&](const char* s, const char* m) { return cell.at(std::string(s) + "|" + m).second; };
    auto firefly = [&](const char* m) { return fireflies.at(std::string("cornell|") + m); };
    const std::string p1 = "01-path-sampling-techniques.md", p12 = "12-comparison-with-path-tracing.md", p14 = "14-power-versus-radiance.md",
                      p15 = "15-vertex-merging.md", a = "appendix-a-speed-and-accuracy.md";
    std::vector<Quote> quotes = {
        {p1, "lt flattens at once (bias " + bias("cornell-glass", "lt")},
        {p1, "clamped ir stays high (bias " + bias("cornell-glass", "ir --clamp")},
        {p12, "pt, nee, lt (bias " + bias("sds-point", "pt") + ": black), ir (" + bias("sds-point", "ir") + ") and bdpt (" + bias("sds-point", "bdpt balance")},
        {p12, "Only vcm converges (slope " + slope("sds-point", "vcm") + ", bias " + bias("sds-point", "vcm") + ")"},
        {p12, "The Metropolis methods keep the same bias (mlt " + bias("sds-point", "mlt") + ", pssmlt " + bias("sds-point", "pssmlt") + ", mmlt " +
                  bias("sds-point", "mmlt") + ")"},
        {p12, "bdpt misses " + bias("sds-point", "bdpt balance").substr(1) + " of the image"},
        {a, "pssmlt misses the same L S D S E light as bdpt (" + bias("sds-point", "pssmlt") + " on sds-point"},
        {p12, "mmlt's curve falls (slope " + slope("sds-point", "mmlt") + ") only toward its floor"},
        {a, "keep the same bias (mlt " + bias("sds-point", "mlt") + ", pssmlt " + bias("sds-point", "pssmlt") + ", mmlt " + bias("sds-point", "mmlt") +
                "), though mmlt's slope is " + slope("sds-point", "mmlt")},
        {p14, "(bias " + bias("refraction", "lt") + "): it cannot"},
        {p14, "clamped ir levels off too (" + bias("refraction", "ir --clamp")},
        {p14, "unclamped ir's " + bias("refraction", "ir")},
        {a, "bdpt " + bias("sds-point", "bdpt balance") + " and " + bias("sds-ior1", "bdpt balance") + ", slope 0"},
        {a, "vcm on `sds-point` and `sds-ior1` (slope " + slope("sds-point", "vcm") + " and " + slope("sds-ior1", "vcm") + ", bias " +
                 bias("sds-point", "vcm") + " and " + bias("sds-ior1", "vcm") + ")"},
        {a, "from " + slope("refraction", "vcm") + ", vcm on `refraction`, to " + slope("refraction", "mmlt") + ", mmlt there"},
        {a, "still falls fast there (slope " + slope("sds", "vcm") + ")"},
        {p15, "vcm " + slope("sds-ior1", "vcm") + " on sds-ior1 and " + slope("sds-point", "vcm") + " on sds-point, while bdpt's error there stays flat at " +
                   bias("sds-ior1", "bdpt balance") + " and " + bias("sds-point", "bdpt balance") + " (slope " + slope("sds-ior1", "bdpt balance") +
                   " and " + slope("sds-point", "bdpt balance") + ")"},
        {a, "lt on `cornell-point` (" + bias("cornell-point", "lt") + ", slope " + slope("cornell-point", "lt") + ")"},
        {a, "(" + bias("cornell", "ir --clamp") + " on cornell, where at 4 s the noise still dominates, slope " + slope("cornell", "ir --clamp") +
                 "; " + bias("indirect", "ir --clamp") + " on indirect"},
        {a, "from the ceiling, slope " + slope("indirect", "ir --clamp") + ")"},
        {a, "(from " + slope("refraction", "mmlt") + " on `refraction` to " + slope("furnace", "mmlt") + " in the furnace and " + slope("sds", "mmlt") +
                   " on `sds`; mlt " + slope("cornell", "mlt") + " on cornell)"},
        {a, "on `door`, pt's " + bias("door", "pt") + " (slope " + slope("door", "pt") + ") and unclamped ir's " + bias("door", "ir") + " (slope " +
                   slope("door", "ir") + ")"},
        {a, "the slopes on cornell-glass are " + slope("cornell-glass", "pssmlt") + " (pssmlt), " + slope("cornell-glass", "mmlt") +
                   " (mmlt) and " + slope("cornell-glass", "mlt") + " (mlt)"},
        {a, "where bdpt's is " + slope("cornell-glass", "bdpt balance")},
        {a, "has one of the smallest ratios (" + firefly("pt") + "), and ir, bdpt and nee, good elsewhere, ratios " +
                 std::to_string(int(std::lround(std::stod(firefly("nee")) / std::stod(firefly("pt"))))) + " to " +
                 std::to_string(int(std::lround(std::stod(firefly("ir")) / std::stod(firefly("pt"))))) + " times as large (" + firefly("ir") + ", " +
                 firefly("bdpt balance") + " and " + firefly("nee") + ")"},
        {a, "from " + bias("cornell-glass", "ir") + ", ir on cornell-glass, to " + bias("refraction", "ir") + ", ir on refraction"},
        {a, "vcm on `door` (" + bias("door", "vcm") + " in the table, slope " + slope("door", "vcm") + " while the noise"},
    };
    return quotes;
}

// Page 10's four paths: the numbers its text quotes are the densities' (classroom/workshop/estimators.cpp).
static std::vector<Quote> estimatorQuotes() {
    // The paths of the figure: lamp centre -> the point seen in row R of the middle column -> eye.
    Scene scene = loadScene("scenes/cornell.scene");
    std::map<int, TwoSegmentPath> paths;
    std::map<int, double> cosLamp, distance;
    for (int row : {62, 78, 94, 150}) {
        RowPath r = rowPath(scene, row);
        REQUIRE(r.path.valid);
        paths[row] = r.path;
        cosLamp[row] = r.cosLamp;
        distance[row] = r.distance;
    }
    auto text = [](const char* format, double v) { char b[32]; std::snprintf(b, sizeof b, format, v); return std::string(b); };
    auto cb = [&](int row) { return paths[row].p[2] / paths[row].p[1]; };  // p_C / p_B
    const std::string p10 = "10-combining-estimators.md";
    std::vector<std::string> texts = {
        "p_C / p_B is " + text("%.2f", cb(62)) + ", " + text("%.2f", cb(78)) + " and " + text("%.2f", cb(94)) + " at rows 62, 78 and 94",
        text("%.3f", cosLamp[62]) + " at row 62, " + text("%.3f", cosLamp[94]) + " at row 94",
        "longer distance (" + text("%.0f", distance[62]) + " to " + text("%.0f", distance[94]) + ")",
    };
    // A's width relative to the widest, and its height f/p_A relative to the widest's: the range
    double smallest = 1e30, largest = 0;
    for (auto& [row, path] : paths) {
        double relative = path.p[0] / std::max({path.p[0], path.p[1], path.p[2]});
        smallest = std::min(smallest, 1 / relative);
        largest = std::max(largest, 1 / relative);
    }
    texts.push_back(text("%.2f%%", 100 / largest) + " to " + text("%.2f%%", 100 / smallest) + " of the best width");
    texts.push_back("B and C tie within " + text("%.2f%%", 100 * std::fabs(paths[78].p[1] / paths[78].p[2] - 1)));
    texts.push_back("f/p_A is " + text("%.0f", smallest) + " to " + text("%.0f", largest) + " times the widest one's");
    std::vector<Quote> quotes;
    for (const std::string& t : texts) quotes.push_back({p10, t});
    return quotes;
}

static std::vector<RunQuote> runQuoteTable() {
    const std::string p1 = "01-path-sampling-techniques.md", p2 = "02-light-and-path-tracing.md", p3 = "03-bidirectional-path-tracing.md", p4 = "04-measurement-equation.md", p6 = "06-extending-paths.md", p11 = "11-contributions-of-paths.md", p12 = "12-comparison-with-path-tracing.md", p15 = "15-vertex-merging.md", p9 = "09-russian-roulette-and-sampling.md",
                      p13 = "13-shading-normals.md", p14 = "14-power-versus-radiance.md", a = "appendix-a-speed-and-accuracy.md", p17 = "17-veach-mutations.md", c = "appendix-c-quasi-random-numbers.md";
    const std::vector<std::string> seeds = {"1", "2", "3", "4"};
    auto rrRow = [](const char* label, int i) {
        std::string k = std::to_string(i);
        return std::string("| ") + label + " | {0.rays:%.2f:" + k + "} | {0.mean:%g:" + k + "} | {0.rmse:%.4g:" + k + "} | {0.efficiency:%.0f:" + k + "} |";
    };
    const std::string direct = "./bdpt scenes/cornell.scene --method bdpt --maxdepth 1 --res 24x24 --spp 16 --seed 1 --ref tests/refs/cornell-direct.pfm --out build/notes/direct-bdpt.png";
    const std::string glossy = "./bdpt build/glossy.scene --method nee --res 64x64 --spp 16 --seed 1 --ref build/glossy-ref.pfm --out build/notes/glossy.png";
    const std::string bidir = "./bdpt scenes/cornell-glass.scene --method mlt --mutations bidir --res 64x64 --spp 128 --bootstrap 100000 --threads 1 --ref scenes/refs/cornell-glass.pfm --out build/notes/bidir-only.png";
    const std::string random = "./bdpt scenes/cornell.scene --method nee --mis --sampler random --spp 16 --res 64x64 --ref scenes/refs/cornell.pfm --out build/notes/random.png";
    auto profile = [](const std::string& method, const std::string& name) {
        return "./bdpt scenes/cornell.scene --method " + method + " --res 128x128 --spp 8 --profile --out build/notes/profile-" + name + ".png";
    };
    auto profileRow = [](const std::string& label, int i) {
        std::string c = std::to_string(i);
        return "| " + label + " | {" + c + ".rays:%.2f} | {" + c + ".us:%g} | {" + c + ".tracing:%g} ({" + c + ".tracing_pct:%g}%) | {" + c +
               ".mis:%g} ({" + c + ".mis_pct:%g}%) | {" + c + ".merging:%g} ({" + c + ".merging_pct:%g}%) | {" + c + ".rest:%g} ({" + c +
               ".rest_pct:%g}%) |";
    };
    const std::string radius = "./bdpt scenes/sds-ior1.scene --method vcm --res 64x64 --spp 32 --radius 0.07 --ref scenes/refs/sds-ior1.pfm --out build/notes/radius.png";
    const std::string door = "./bdpt scenes/door.scene --method vcm --res 64x64 --spp 64 --radius 3 --ref scenes/refs/door.pfm --out build/notes/door-vcm.png";
    const std::string example = "./bdpt scenes/cornell.scene --method pt --spp 64 --res 64x64 --seed 1 --ref scenes/refs/cornell.pfm --out build/notes/example-pt.png";
    const std::string ptDirect = "./bdpt scenes/cornell.scene --method pt --maxdepth 1 --res 24x24 --spp 4 --ref tests/refs/cornell-direct.pfm --out build/notes/pt-direct.png";
    return {
        {p1, {"./bdpt scenes/cornell-glass.scene --side-by-side \"pt,nee,lt,ir,ir --clamp 1e-5,bdpt\" --spp 40 --res 200x200 --title \"Results from different "
              "techniques: 40 paths per pixel\" --out build/notes/six-panels-40.png"}, "", {},
         {"pt's sample costs {0.rays#1:%.2f} rays and bdpt's {0.rays#6:%.2f}"}, true},
        {p1, {"./bdpt scenes/cornell-glass.scene --side-by-side \"lt,ir --clamp 1e-5,bdpt\" --spp 64 --res 64x64 --ref scenes/refs/cornell-glass.pfm --out build/notes/bias.png"},
         "", {}, {"prints bias {0.bias#1:%+.2f}% for lt", "{0.bias#2:%+.2f}% for clamped ir", "and {0.bias#3:%+.2f}% for bdpt"}},
        {p2, {"./bdpt scenes/cornell.scene --side-by-side lt,pt --maxdepth 1 --spp 4 --res 192x192 --out build/notes/direct.png"}, "", {},
         {"(means {0.mean#1:%.4f} and {0.mean#2:%.4f} in the figure's run"}},
        {p2, {ptDirect, ptDirect + " || --method lt"}, "--spp", {"4", "16", "64", "128", "256"},
         {"lt at 4 paths has RMSE {1.rmse:%.4g:0}, pt {0.rmse:%.4g:0} at 4, {0.rmse:%.4g:1} at 16, {0.rmse:%.4g:2} at 64, {0.rmse:%.4g:3} at 128 "
          "and {0.rmse:%.4g:4} at 256. lt traces more rays per path ({1.rays:%.2f:0} against pt's {0.rays:%.2f:0})"}},
        {p4, {"./bdpt build/furnace-08.scene --method pt --maxdepth 3 --spp 16 --out build/notes/furnace-08.png"}, "--maxdepth", {"3", "32"},
         {"2.952 with `--maxdepth 3` (the renderer: {0.mean:%.3f:0})", "the renderer gives {0.mean:%.3f:1}"}},
        {p6, {"./bdpt build/pool-ior1.scene --side-by-side pt,lt --spp 64 --res 64x48 --out build/notes/pool-ior1.png"}, "", {},
         {"(image means pt {0.mean#1:%.3f}, lt {0.mean#2:%.3f})"}},
        {p11, {"./bdpt scenes/cornell.scene --method bdpt --res 64x64 --spp 16 --maxdepth 4 --out build/notes/cornell-k5.png"}, "--maxdepth",
         {"4", "32"}, {"has mean {0.mean:%.4f:0} with `--maxdepth 4` and {0.mean:%.4f:1} without"}},
        {p11, {"./bdpt scenes/indirect.scene --method bdpt --spp 64 --res 64x64 --strategies build/notes/pyramid-indirect --out build/notes/indirect-pyramid.png"},
         "", {}, {"s2_t1 (mean {0.s2_t1:%.3f} of its weighted image, half of the whole image's {0.mean:%.3f}). Then row 3, the ceiling's light on "
                  "the floor and walls, mostly s2_t2 ({0.s2_t2:%.3f}) and s3_t1 ({0.s3_t1:%.3f})"}},
        {p12, {example, example + " || --method bdpt --spp 16"}, "--seed", seeds,
         {"relMSE {0.relmse:%.2f:min}-{0.relmse:%.2f:max} for pt against {1.relmse:%.4f:min}-{1.relmse:%.4f:max} for bdpt, about 50 times "
          "lower. The RMSE differs less ({0.rmse:%.3f:min}-{0.rmse:%.3f:max} against {1.rmse:%.3f:min}-{1.rmse:%.3f:max})",
          "(`rmse_without_lamp`, the figure the page's panels show first) pt's is {0.rmse_without_lamp:%.4f:min}-{0.rmse_without_lamp:%.4f:max} "
          "and bdpt's is {1.rmse_without_lamp:%.4f:min}-{1.rmse_without_lamp:%.4f:max}"}},
        {p12, {"./bdpt scenes/sds.scene --method pt --res 64x64 --spp 64 --out build/notes/sds-pt.png"}, "--method", {"pt", "bdpt"},
         {"bdpt's rays ({0.rays:%.2f:0} against {0.rays:%.2f:1} per sample)"}},
        {p12, {"./bdpt scenes/cornell.scene --method pt --spp 4 --res 256x256 --out build/notes/rays.png"}, "--method", {"pt", "nee", "lt", "bdpt"},
         {"pt {0.rays:%.2f:0} rays per sample (all closest-hit), nee {0.rays:%.2f:1}, lt {0.rays:%.2f:2}, bdpt {0.rays:%.2f:3} ({0.closest:%.2f:3} "
          "closest-hit, {0.shadow:%.2f:3} shadow)"}},
        {p3, {direct, direct + " || --method nee"}, "--seed", seeds,
         {"`rmse_without_lamp` {0.rmse_without_lamp:%.4f:min}-{0.rmse_without_lamp:%.4f:max} for bdpt, {1.rmse_without_lamp:%.4f:min}-"
          "{1.rmse_without_lamp:%.4f:max} for nee. The RMSE over every pixel hides it ({0.rmse:%.4f:min}-{0.rmse:%.4f:max} against "
          "{1.rmse:%.4f:min}-{1.rmse:%.4f:max})"}},
        {p9, {"./bdpt scenes/furnace.scene --method pt --res 64x64 --spp 16 --rr-start 3 --ref scenes/refs/furnace.pfm --out build/notes/rr.png"},
         "--rr-start", {"0", "1", "2", "3", "5", "8"},
         {rrRow("0", 0), rrRow("1", 1), rrRow("2", 2), rrRow("3 (default)", 3), rrRow("5", 4), rrRow("8", 5),
          "from {0.rays:%.2f:0} to {0.rays:%.2f:5} rays per sample, RMSE from {0.rmse:%.4g:0} to {0.rmse:%.4g:5}"}},
        {p9, {"./bdpt scenes/glass-box.scene --method bdpt --roulette throughput --res 64x64 --spp 16 --out build/notes/rr-throughput.png"},
         "--roulette", {"throughput", "albedo", "off"},
         {"Rays per sample: throughput {0.rays:%.2f:0}, albedo {0.rays:%.2f:1}, off {0.rays:%.2f:2}, and the time follows the rays; "
          "the means agree ({0.mean:%g:0}, {0.mean:%g:1}, {0.mean:%g:2})"}},
        {p9, {"./bdpt build/glossy.scene --method bdpt --res 64x64 --spp 512 --out build/glossy-ref.png"}, "", {}, {}},
        {p9, {glossy, glossy + " || --mis"}, "--seed", seeds,
         {"RMSE {0.rmse:%.3f:min}-{0.rmse:%.3f:max} without `--mis`, {1.rmse:%.4f:min}-{1.rmse:%.4f:max} with it (seeds 1 to 4, "
          "64x64 as in the page), at the same {0.rays:%.2f:0} rays per sample"}},
        {p13, {"./bdpt scenes/energy-generator.scene --side-by-side \"nee,lt,lt --no-adjoint-correction,nee tests/energy-generator-flat.scene\" "
               "--spp 256 --title \"The energy generator: a shading normal tilted 60 degrees\" --out build/notes/energy.png"}, "", {},
         {"(means {0.mean#1:%.4g} and {0.mean#2:%.4g} in the figure's run)",
          "{0.mean#1/0.mean#4:%.1f} times as bright as the same floor without the tilt ({0.mean#1:%.4g} against {0.mean#4:%.4g}, the figure's",
          "its floor is {0.mean#1/0.mean#3:%.0f} times darker than nee's ({0.mean#3:%.4g})"}, true},
        {p13, {"./bdpt --ratio build/notes/shading-2-lt.pfm build/notes/shading-1-nee.pfm --out build/notes/shading-ratio-correct.png",
               "./bdpt --ratio build/notes/shading-3-lt.pfm build/notes/shading-1-nee.pfm --out build/notes/shading-ratio-wrong.png"}, "", {},
         {"in the figure's run the ratio of the means is {0.ratio:%.3f}, 90% of the blocks lie within {0.ratio_p5:%.2f}-{0.ratio_p95:%.2f} and "
          "{0.ratio_apart:%.1f}% are more than half a stop off",
          "the image mean is only {1.ratio:%.3f} times nee's, but locally the error is far larger: {1.ratio_apart:%.0f}% of the blocks are more "
          "than half a stop off, and the 95th percentile of the ratio is {1.ratio_p95:%.2f}"}, true},
        {p17, {bidir, bidir + " || !--mutations"}, "", {},
         // three digits: in the page a chain may take another turn in the last bits of cosf
         {"(`rmse_without_lamp` {0.rmse_without_lamp:%.3g} with `bidir` alone against {1.rmse_without_lamp:%.3g} with all four, seed 1)"}},
        {p13, {"./bdpt scenes/energy-generator.scene --method nee --spp 64 --out build/notes/energy-60.png",
               "./bdpt build/energy-20.scene --method nee --spp 64 --out build/notes/energy-20.png"}, "", {},
         {"the image mean halves ({0.mean:%.4g} -> {1.mean:%.4g})"}},
        {p15, {"./bdpt scenes/cornell.scene --method vcm --spp 1 --res 256x256 --out build/notes/vcm-memory.png"}, "", {},
         {"256x256, {0.light_vertices:%.1f} light vertices per pixel, {0.vcm_bytes:%.0f} bytes each", "{0.vcm_mb:%.1f} MB; bdpt keeps"}},
        {p15, {radius, radius + " || --alpha 1"}, "--radius", {"0.07", "0.14", "0.28"},
         // three digits: the page's vcm sums its merges in another order, and its last digit may differ
         {"(RMSE {0.rmse:%.3g:0}, {0.rmse:%.3g:1}, {0.rmse:%.3g:2} at the default alpha; {1.rmse:%.3g:0}, {1.rmse:%.3g:1}, {1.rmse:%.3g:2} at `--alpha 1`)"}},
        {p15, {door}, "--radius", {"3", "15", "30"},
         {"(the image mean {0.bias:%+.2f:0}% at r = 3, {0.bias:%+.2f:1}% at 15, {0.bias:%+.2f:2}% at 30)"}},
        {p14, {"./bdpt --ratio build/notes/pool-mistake-4-lt.pfm build/notes/pool-mistake-3-lt.pfm --out build/notes/pool-lt-ratio.png"}, "", {},
         {"(in the figure's run the command printed \"ratio of means {0.ratio:%.5g}\")"}, true},
        {a, {profile("pt", "pt"), profile("nee --mis", "nee"), profile("bdpt", "bdpt"), profile("vcm", "vcm")}, "", {},
         {profileRow("pt", 0), profileRow("nee --mis", 1), profileRow("bdpt", 2), profileRow("vcm", 3)}, true},
        {a, {"./bdpt scenes/cornell.scene --method vcm --spp 1 --out build/notes/vcm-cornell.png",
             "./bdpt scenes/sds-point.scene --method vcm --spp 1 --out build/notes/vcm-sds-point.png"}, "", {},
         {"cornell (256x256) has {0.light_vertices:%.1f} light vertices per pixel and pass, {0.mergeable:%.1f} of them mergeable, "
          "{0.vcm_bytes:%.0f} bytes per light vertex and {0.vcm_mb:%.1f} MB in all; sds-point (192x128) {1.light_vertices:%.1f} and "
          "{1.mergeable:%.1f}, {1.vcm_bytes:%.0f} bytes and {1.vcm_mb:%.1f} MB"}},
        {c, {random, random + " || !--sampler", random + " || !--sampler --no-scramble"}, "", {},
         {"`rmse_without_lamp` {1.rmse_without_lamp:%.4g}, against {0.rmse_without_lamp:%.4g} with independent numbers and "
          "{2.rmse_without_lamp:%.4g} unscrambled, whose mean is {2.bias:%.2f}% too bright"}},
    };
}

TEST_CASE("the numbers the pages quote from runs are what the commands they print give") {
    // page 9's exercise 3: the glossy floor, as the page tells the student to make it
    std::system("mkdir -p build/tmp/notes-runs");
    std::ofstream glossy("build/tmp/notes-runs/glossy.scene");
    std::istringstream cornell(slurp("scenes/cornell.scene"));
    for (std::string line; std::getline(cornell, line);) {
        if (line.rfind("quad 0 0 0 ", 0) == 0 && line.find("# floor") != std::string::npos) line.replace(line.find("white"), 5, "polished");
        glossy << line << "\n";
        if (line.rfind("material lamp", 0) == 0) glossy << "material polished glossy 0.8 0.8 0.8 2000\n";
    }
    glossy.close();
    std::ofstream furnace("build/tmp/notes-runs/furnace-08.scene");  // page 4's exercise 1
    furnace << std::regex_replace(slurp("scenes/furnace.scene"), std::regex("diffuse 0.5 0.5 0.5"), "diffuse 0.8 0.8 0.8");
    furnace.close();
    std::ofstream energy("build/tmp/notes-runs/energy-20.scene");  // page 13's exercise 3
    energy << std::regex_replace(slurp("scenes/energy-generator.scene"), std::regex("tilt 60"), "tilt 20");
    energy.close();
    std::ofstream pool("build/tmp/notes-runs/pool-ior1.scene");  // page 6's exercise 2
    pool << std::regex_replace(slurp("scenes/refraction.scene"), std::regex("material water glass 1.33"), "material water glass 1.0");
    pool.close();
    for (const RunQuote& q : runQuoteTable())
        for (const std::string& command : q.commands) {
            CAPTURE(command);
            CHECK(flatPage(q.page).find(printedPart(command)) != std::string::npos);
        }
    checkQuotesStand(runQuotes());
}

TEST_CASE("the efficiencies the pages quote are the generated table's (make figures)") {
    checkQuotesStand(efficiencyQuotes());
}

TEST_CASE("the slopes and biases the pages quote are the failure table's (make figures)") {
    checkQuotesStand(failureQuotes());
}

static std::vector<Quote> measuredQuotes();
static std::vector<Quote> metropolisQuotes();

TEST_CASE("Appendix A's roulette table: albedo roulette, bdpt's, is the most efficient of the three rules on every scene") {
    std::map<std::string, std::map<std::string, double>> efficiency;  // scene -> rule -> efficiency
    for (const auto& c : tableRows("lecture_notes/figures/roulette.md"))
        if (c.size() >= 7 && c[1].rfind("bdpt --roulette ", 0) == 0) efficiency[c[0]][c[1].substr(16, c[1].find(' ', 16) - 16)] = std::stod(c[5]);
    REQUIRE(efficiency.size() == 4);
    for (auto& [scene, rules] : efficiency) {
        CAPTURE(scene);
        REQUIRE(rules.size() == 3);
        CHECK(rules["albedo"] > rules["throughput"]);
        CHECK(rules["albedo"] > rules["off"]);
    }
}

TEST_CASE("the numbers the pages quote from make metropolis's tables are the tables'") {
    checkQuotesStand(metropolisQuotes());
}

TEST_CASE("the numbers the pages quote from the tests' measurements are what they measure") {
    checkQuotesStand(measuredQuotes());
}

TEST_CASE("page 10's four paths: the numbers its text quotes are the densities' (classroom/workshop/estimators.cpp)") {
    checkQuotesStand(estimatorQuotes());
}

// A page's flat text with all but its prose blanked, length kept: code blocks and spans,
// spliced (generated) tables, comments, image and link addresses.
// A machine's benchmark record (<!-- record: what ran, where --> ... <!-- record:end -->, Appendix
// B's Embree tables) is not prose either: no run of make figures can regenerate it.
static std::string proseOnly(std::string flat) {
    // found by plain search, not std::regex: its recursive matcher overflows the stack on a
    // spliced table's length (under the sanitizers)
    auto blank = [&](size_t from, size_t to) { std::fill(flat.begin() + long(from), flat.begin() + long(std::min(to, flat.size())), '\x01'); };
    auto spans = [&](const std::string& open, auto close) {  // close(text after open) -> the end's position
        for (size_t at = flat.find(open); at != std::string::npos; at = flat.find(open, at + 1)) {
            size_t to = close(at + open.size());
            if (to == std::string::npos) break;
            blank(at, to);
        }
    };
    auto until = [&](const std::string& end) { return [&, end](size_t from) { size_t e = flat.find(end, from); return e == std::string::npos ? e : e + end.size(); }; };
    spans("```", until("```"));
    spans("<!-- record: ", until("<!-- record:end -->"));
    spans("<!-- ", [&](size_t from) {  // a splice's start runs to its end; any other comment to its -->
        size_t close = flat.find(" -->", from);
        if (close == std::string::npos) return close;
        std::string name = flat.substr(from, close - from);
        if (name.size() > 6 && name.compare(name.size() - 6, 6, ":start") == 0) return until("<!-- " + name.substr(0, name.size() - 6) + ":end -->")(close);
        return close + 4;
    });
    spans("`", until("`"));
    spans("](", until(")"));
    return flat;
}

// The numbers a page states as a run could print them: decimals, percentages and factors
// (0.0940, 23%, 1.77x), each with its place in the flat page.
static std::vector<std::pair<size_t, std::string>> statedNumbers(const std::string& prose) {
    std::vector<std::pair<size_t, std::string>> numbers;
    std::regex number("(^|[^A-Za-z0-9_.^])([0-9]+(?:,[0-9]{3})*(\\.[0-9]+)?)(%|x(?![A-Za-z0-9]))?");
    for (std::sregex_iterator it(prose.begin(), prose.end(), number), end; it != end; ++it)
        if ((*it)[3].matched || (*it)[4].matched) numbers.push_back({size_t(it->position(2)), (*it)[2].str() + (*it)[4].str()});
    return numbers;
}

// Numbers a page states that no run measures: constants, parameters, closed forms, the slides'
// and papers' own numbers, each with enough of its sentence to find it.
static std::vector<Quote> notMeasured();
static std::vector<Quote> testBounds();

// Pages 7 and 10M's paths worked with numbers: build/worked-path's tables, every line of them.
static std::vector<Quote> workedQuotes() {
    std::vector<Quote> quotes;
    for (const auto& [page, table] : {std::pair<std::string, std::string>{"07-probabilities.md", worked::cornellTable()},
                                      {"10m-mirrors-and-glass.md", worked::causticTable()}}) {
        std::istringstream lines(table);
        for (std::string line; std::getline(lines, line);)
            if (!line.empty()) quotes.push_back({page, line});
    }
    return quotes;
}

TEST_CASE("pages 7 and 10M show build/worked-path's tables, line for line, and the tables add up") {
    std::vector<Quote> quotes = workedQuotes();
    CHECK(quotes.size() >= 20);
    for (const Quote& q : quotes) {
        CAPTURE(q.page);
        CAPTURE(q.text);
        CHECK(slurp("lecture_notes/" + q.page).find(q.text) != std::string::npos);
    }
    // The cornell path's balance weights sum to 1, and p_{3,s+1}/p_{3,s} is x_s's light/camera
    // column (page 7's walk), read back from the printed table.
    std::vector<std::vector<double>> vertices, strategies;
    for (const Quote& q : quotes) {
        if (q.page != "07-probabilities.md" || (q.text.rfind("| x_", 0) != 0 && !std::isdigit(static_cast<unsigned char>(q.text[2])))) continue;
        std::vector<double> cells;
        std::istringstream in(q.text);
        for (std::string cell; std::getline(in, cell, '|');) {
            char* end = nullptr;
            double v = std::strtod(cell.c_str(), &end);
            if (end != cell.c_str()) cells.push_back(v);
        }
        (q.text.rfind("| x_", 0) == 0 ? vertices : strategies).push_back(cells);
    }
    REQUIRE(vertices.size() == 4);
    REQUIRE(strategies.size() == 5);
    double balance = 0;
    for (const auto& row : strategies) balance += row.at(4);
    CHECK(balance == doctest::Approx(1).epsilon(1e-3));
    for (int s = 0; s < 3; ++s) CHECK(strategies[s + 1].at(3) / strategies[s].at(3) == doctest::Approx(vertices[s].back()).epsilon(2e-3));
}

TEST_CASE("every number the pages quote from a run is backed by a generated table, a command the page prints or a test's bound") {
    std::vector<Quote> backed = notMeasured();
    std::map<std::string, int> bySource;
    auto add = [&](const std::vector<Quote>& quotes, const char* source) {
        backed.insert(backed.end(), quotes.begin(), quotes.end());
        bySource[source] += int(quotes.size());
    };
    add(efficiencyQuotes(), "efficiency table");
    add(failureQuotes(), "failure table");
    add(estimatorQuotes(), "page 10's densities");
    add(runQuotes(), "commands the pages print");
    add(measuredQuotes(), "the tests' measurements");
    add(metropolisQuotes(), "make metropolis's tables");
    add(referenceQuotes(), "the reference check");
    add(workedQuotes(), "the worked paths");
    int stated = 0, unbacked = 0, constants = 0;
    for (const std::string& path : notePages()) {
        std::string page = path.substr(14), flat = flatPage(page);
        if (page == kAppendixARecord) continue;  // read as part of Appendix A
        std::vector<bool> covered(flat.size(), false), constant(flat.size(), false);
        for (const Quote& q : backed)
            if (q.page == page)
                for (size_t at = flat.find(q.text); at != std::string::npos; at = flat.find(q.text, at + 1))
                    std::fill(covered.begin() + long(at), covered.begin() + long(at + q.text.size()), true);
        std::vector<Quote> given = notMeasured(), bounds = testBounds();
        given.insert(given.end(), bounds.begin(), bounds.end());
        for (const Quote& q : given)
            if (q.page == page)
                for (size_t at = flat.find(q.text); at != std::string::npos; at = flat.find(q.text, at + 1))
                    std::fill(constant.begin() + long(at), constant.begin() + long(at + q.text.size()), true);
        for (const auto& [at, number] : statedNumbers(proseOnly(flat))) {
            ++stated;
            if (constant[at]) { ++constants; continue; }
            if (covered[at]) continue;
            ++unbacked;
            CAPTURE(page);
            CAPTURE(number);
            std::string context = flat.substr(at < 60 ? 0 : at - 60, 120);
            CAPTURE(context);
            CHECK(covered[at]);
        }
    }
    MESSAGE("numbers the pages state: " << stated << ", of them not measured (constants, parameters, closed forms): " << constants
            << ", unbacked: " << unbacked << "; quotes checked: " << bySource["efficiency table"] << " from the efficiency table, "
            << bySource["failure table"] << " from the failure table, " << bySource["page 10's densities"] << " from page 10's densities, "
            << bySource["commands the pages print"] << " from commands the pages print, " << bySource["the tests' measurements"]
            << " from the tests' measurements, " << bySource["make metropolis's tables"] << " from make metropolis's tables, "
            << bySource["the reference check"] << " from the reference check");
}

static std::vector<Quote> notMeasured() {
    const std::string n = "04n-notation.md";
    return {
        // closed forms, each checked by a test of its own where a run could contradict it
        {"04-measurement-equation.md", "1, 1.5, 1.75, 1.875, ..., the partial sums Le (1 - a^(D+1))/(1-a) with a = 0.5"},
        {"04-measurement-equation.md", "(1 - 0.8^4)/(1 - 0.8) = 2.952"},
        {"04-measurement-equation.md", "(1 - 0.8^33)/0.2 = 4.997"},
        {"04-measurement-equation.md", "albedo to 0.8"},
        {"09-russian-roulette-and-sampling.md", "0.8 x 2002 / (2 pi) = 255"},
        {"10m-mirrors-and-glass.md", "eta_b^2 / eta_a^2 = 1.33^2 = 1.77"},
        {"10m-mirrors-and-glass.md", "eta_D = 1.33 in the water, so the ratio gains 1/1.33^2"},
        {"10m-mirrors-and-glass.md", "the factor 1.33^2 cos_water"},
        {"06-extending-paths.md", "pt's 1.77x darker, lt's 1.77x brighter"},
        {"06-extending-paths.md", "to 1.0 and render"},
        {"06-extending-paths.md", "hangs 0.5 mm above a floor"},  // the scene's own coordinates
        // page 7's exercise 4: arithmetic on the worked path's printed table
        {"07-probabilities.md", "(the lamp's centre is (278, 548.7, 279.5))"},
        {"07-probabilities.md", "by x_1's ratio 1.237, s = 3 further by x_2's 1.076 (1.331), s = 0 divides by x_0's 122.6 (0.008157)"},
        {"07-probabilities.md", "1 / (1 + 0.008157^2 + 1.237^2 + 1.331^2) = 1 / 4.302 = 0.2325: the table's 0.2324"},
        {"13-shading-normals.md", "albedo 0.8"},
        {"13-shading-normals.md", "ratio at most 0.8"},
        {"13-shading-normals.md", "the albedo, 0.80"},
        {"13-shading-normals.md", "predicts about 7.4"},
        {"13-shading-normals.md", "|w . ng| = 0.124"},
        {"13-shading-normals.md", "0.124 cos 20 + 0.992 sin 20 = 0.46 instead of 0.92"},
        {"13-shading-normals.md", "falls from 7.4 to 3.7"},
        {"14-power-versus-radiance.md", "eta^2 = 1.77 times"},
        {"14-power-versus-radiance.md", "theta_c = 48.8 degrees"},
        {"14-power-versus-radiance.md", "2.9 times smaller (2 pi (1 - cos theta_c) = 2.14 sr)"},
        {"14-power-versus-radiance.md", "the floor 1.77x darker"},
        {"14-power-versus-radiance.md", "eta^2 = 1.33^2 = 1.7689"},
        {"14-power-versus-radiance.md", "pt's floor is 1.77x too dark and lt's 1.77x too bright"},
        {"14-power-versus-radiance.md", "eta^2 Le = 2.25 Le"},
        {"14-power-versus-radiance.md", "2.25 (correct: eta^2 Le with eta = 1.5)"},
        {"14-power-versus-radiance.md", "(1.5^2)(1/1.5)^2 = 1"},
        {"15-vertex-merging.md", "n^-0.375"},
        {"15-vertex-merging.md", "tell -0.375 from"},
        {"15-vertex-merging.md", "pi 0.07^2 x 24576 = 378"},
        {"15-vertex-merging.md", "at 192x128, r = 0.14 (two pixels there) makes it 8"},
        {"15-vertex-merging.md", "where 0.14 is about one pixel, it is 1.4"},
        {"13-shading-normals.md", "0.75 at 60 degrees, 0.97 at 20"},  // (1 + cos alpha) / 2
        // parameters: the renderer's defaults, Veach's and the exercises' settings
        {"09-russian-roulette-and-sampling.md", "q = min(0.95,"},
        {"15-vertex-merging.md", "default 0.75;"},
        {"15-vertex-merging.md", "glass of index 1.0"},
        {"15-vertex-merging.md", "and `--radius` 0.14 and 0.28"},
        {"15-vertex-merging.md", "radius, r = 0.07 (about one"},
        {"15-vertex-merging.md", "by vcm at r = 0.07, 0.14 and 0.28"},
        {"15-vertex-merging.md", "as r = 0.07's"},
        {"16-metropolis-sampling.md", "(probability `--large-step`, 0.3)"},
        {"16-metropolis-sampling.md", "`--sigma` (0.01,"},
        {"17-veach-mutations.md", "kd +- 1 with 0.15 each, kd +- j with 0.2 x 2^-j"},
        {"17-veach-mutations.md", "from 0.1 pixel to the radius of a disc of 5% of the image"},
        {"17-veach-mutations.md", "the 5% disc's radius"},
        {"17-veach-mutations.md", "(1e-4 to 0.1 degrees"},
        {n, "the 99.9th percentile"},
        {n, "plus 0.01"},
        {"appendix-a-speed-and-accuracy.md", "full colour at 2x"},
        {"appendix-a-speed-and-accuracy.md", "weighted 0.5, 2 or 3"},
        {"appendix-a-speed-and-accuracy.md", "(ref^2 + 0.01)"},
        {"appendix-a-speed-and-accuracy.md", "the 99.9th percentile"},
        {"appendix-a-speed-and-accuracy.md", "(99.9th percentile"},
        {"appendix-a-speed-and-accuracy.md", "at 1.5 s a run"},
        {"appendix-a-speed-and-accuracy.md", "(about -0.5 where"},
        {"appendix-a-speed-and-accuracy.md", "(slope near -0.5,"},
        {"appendix-a-speed-and-accuracy.md", "A bias beside a slope near -0.5 is noise"},
        {"appendix-a-speed-and-accuracy.md", "a slope far from -0.5"},
        {"appendix-a-speed-and-accuracy.md", "(slope 0, bias -100.0%)"},
        {"appendix-a-speed-and-accuracy.md", "predicts n^-0.375"},
        // sections of books and papers
        {n, "pbrt (v3, 8.2)"},
        {"09-russian-roulette-and-sampling.md", "Veach's thesis, 10.3"},
        {"10-combining-estimators.md", "theorem 9.2"},
        {"10-combining-estimators.md", "Theorem 9.2: the balance"},
        // the optional sheet's example, the densities the test `MIS: the max heuristic's near-ties` takes
        {"10-combining-estimators.md", "densities 1, 1.00008 and 1.00016 would get 0, 1/3 and 1/2"},
        {"14-power-versus-radiance.md", "section 5.2"},
        {"16-metropolis-sampling.md", "Veach 1997, 11.5"},
    };
}

// Bounds a test asserts, quoted as the test states them (the test fails beyond them).
static std::vector<Quote> testBounds() {
    return {
        {"06-extending-paths.md", "within 10% of 1.33^2"},
        {"09-russian-roulette-and-sampling.md", "= 2 within 1%"},
        {"10-combining-estimators.md", "2 within 2%"},
        {"10m-mirrors-and-glass.md", "s = 0 carries under 5% of the caustic"},
        {"10m-mirrors-and-glass.md", "within 1.6 times light tracing's"},
        {"14-power-versus-radiance.md", "within 10% of eta^2"},
        {"appendix-c-quasi-random-numbers.md", "falls by more than 32x with Sobol points (16x is 1/N), and ends below 0.2x"},
        {"15-vertex-merging.md", "reports 131 bytes and 24.6 MB"},  // make test-web reads it from the page's panel
    };
}

// The reference check (make figures): the range of its ratios, and what the smallest means for a chart.
static std::vector<Quote> referenceQuotes() {
    std::vector<double> ratios;
    for (const auto& cells : tableRows("lecture_notes/figures/reference-check.md"))
        if (!cells.empty() && cells.back().find_first_of("0123456789") == 0) ratios.push_back(std::stod(cells.back()));
    REQUIRE(!ratios.empty());
    double low = *std::min_element(ratios.begin(), ratios.end()), high = *std::max_element(ratios.begin(), ratios.end());
    auto text = [](const char* format, double v) { char b[32]; std::snprintf(b, sizeof b, format, v); return std::string(b); };
    const std::string a = "appendix-a-speed-and-accuracy.md";
    double added = std::sqrt(1 + 1 / (low * low));
    std::string sds;  // page 12's caption: vcm's curve on sds ends this many times above the reference's noise
    for (const auto& cells : tableRows("lecture_notes/figures/reference-check.md"))
        if (cells.size() > 1 && cells.front().find("sds") == 0 && cells.front().size() == 3) sds = cells.back();
    REQUIRE(!sds.empty());
    return {
        {"12-comparison-with-path-tracing.md", "vcm's ends " + sds + " times above it"},
        {a, text("%.1fx", low) + " to " + text("%.1fx", high)},
        {a, "adds at most " + text("%.1f%%", 100 * (added - 1)) + " to a charted RMSE (errors add in squares: sqrt(1 + 1/" + text("%.1f", low) + "^2) = " +
                text("%.3f", added) + ")"},
    };
}

// make metropolis's tables (Appendix A): the Markov chains against bdpt, and mlt's mutations.
static std::vector<Quote> metropolisQuotes() {
    std::map<std::string, std::vector<std::string>> met, rate;  // "scene|size|method" -> cells; scene -> mutations per second's cells
    for (const auto& c : tableRows("lecture_notes/figures/metropolis.md"))
        if (c.size() >= 7 && c[5].size() > 1 && c[5].back() == 'x') met[c[0] + "|" + c[1] + "|" + c[2]] = c;
    for (const auto& c : tableRows("lecture_notes/figures/mutations.md"))
        if (c.size() == 6 && c[3].size() > 1 && c[3].back() == 'x') rate[c[0]] = c;
    REQUIRE(met.size() >= 12);
    REQUIRE(rate.size() >= 3);
    auto e = [&](const char* scene, const char* size, const char* method) { return met.at(std::string(scene) + "|" + size + "|" + method).at(5); };
    double leastAccepted = 100, mostAccepted = 0;  // the bidirectional mutation's acceptance, in percent
    for (const auto& c : tableRows("lecture_notes/figures/mutations.md"))
        if (c.size() == 6 && c[1] == "bidirectional") {
            leastAccepted = std::min(leastAccepted, std::stod(c[3])), mostAccepted = std::max(mostAccepted, std::stod(c[3]));
        }
    double fewest = 1e9, most = 0;
    for (const auto& [scene, cells] : rate) {
        double r = std::stod(cells.at(3));
        fewest = std::min(fewest, r), most = std::max(most, r);
    }
    auto text = [](const char* format, double v) { char b[32]; std::snprintf(b, sizeof b, format, v); return std::string(b); };
    const char *small = "64x64, 1024", *large = "128x128, 256";
    const std::string p17 = "17-veach-mutations.md";
    return {
        {p17, "mlt is " + e("door-hidden", small, "mlt") + " as efficient as bdpt at 64x64 and " + e("door-hidden", large, "mlt") + " at 128x128; pssmlt " +
                  e("door-hidden", small, "pssmlt") + " and " + e("door-hidden", large, "pssmlt")},
        {p17, "mlt only matches bdpt (" + e("door-side", small, "mlt") + ")"},
        {"16-metropolis-sampling.md", "mlt is " + e("door-hidden", small, "mlt") + " as efficient as bdpt, pssmlt " + e("door-hidden", small, "pssmlt") +
                                          ", mmlt " + e("door-hidden", small, "mmlt")},
        {p17, "it loses (" + e("cornell", small, "mlt") + " bdpt)"},
        {p17, "cheaper (" + text("%.1f", fewest) + " to " + text("%.1f", most) + " times as many per CPU-second)"},
        {p17, "about four splats to mlt's " + text("%.1f", std::stod(rate.at("cornell-glass").at(4)))},
        {"appendix-a-speed-and-accuracy.md", "is accepted " + text("%.0f", leastAccepted) + "-" + text("%.0f", mostAccepted) + "% of the time"},
    };
}

// Numbers the pages quote from the tests' measurements, measured again here as the tests do.
static std::vector<Quote> measuredQuotes() {
    auto text = [](const char* format, double v) { char b[32]; std::snprintf(b, sizeof b, format, v); return std::string(b); };
    Scene tilted = sceneAt("scenes/energy-generator.scene", 48, 36);
    Scene tilt20 = tilted;
    Vec3 u = normalize(tilt20.shapes[0].u), n = tilt20.shapes[0].normal;
    tilt20.shapes[0].tiltedNormal = normalize(std::cos(20 * kPi / 180) * n + std::sin(20 * kPi / 180) * u);
    double at60 = floorPowerRatio(tilted, 1, 200000, 12).mean, at20 = floorPowerRatio(tilt20, 1, 200000, 12).mean;
    const std::string p13 = "13-shading-normals.md";
    return {
        {p13, "The floor sends out **" + text("%.1f", at60) + " times the power it receives**"},
        {p13, "the power ratio falls from " + text("%.2f", at60) + " to " + text("%.2f", at20)},
        {p13, text("%.2f", at60) + " / (0.8 x 7.4) = " + text("%.2f", at60 / (0.8 * 7.4)) + " at 60 degrees, " + text("%.2f", at20) +
                  " / (0.8 x 3.7) = " + text("%.2f", at20 / (0.8 * 3.7))},
        {p13, "lowers these to the measured " + text("%.2f", at60 / (0.8 * 7.4)) + " and " + text("%.2f", at20 / (0.8 * 3.7))},
    };
}

// The pages speak of the renderer, not of how it was made: no issue numbers, no sessions, no
// "we tried", no machine of the project's own (the git log keeps the history).
// Where students stop reading: each page a lecture's worth (the measured record is Appendix A's
// record, the quasi-random points Appendix C's), and still the page (the lower bounds). A page
// may end in an optional sheet for after class ("## Optional sheet"): the limit is the class's
// part. Formulas ($$...$$, $...$) count as one word each: TeX's markup is not read.
static int classWords(const std::string& page) {
    std::string text = slurp("lecture_notes/" + page);
    text = text.substr(0, text.find("## Optional sheet"));
    text = std::regex_replace(text, std::regex("\\$\\$[^$]*\\$\\$"), "F");
    text = std::regex_replace(text, std::regex("\\$[^$\n]+\\$"), "F");
    std::istringstream words(text);
    int count = 0;
    for (std::string w; words >> w;) ++count;
    return count;
}

TEST_CASE("each page is an hour's: pages 9, 15, 16 and 17, page 10 with 10M in class, and Appendix A's reading") {
    struct Limit {
        const char* page;
        int most, least;
    };
    for (const Limit& l : {Limit{"09-russian-roulette-and-sampling.md", 1300, 800}, Limit{"15-vertex-merging.md", 1400, 900},
                           Limit{"16-metropolis-sampling.md", 1000, 600}, Limit{"17-veach-mutations.md", 1200, 800},
                           Limit{kAppendixA, 3000, 1000}}) {
        CAPTURE(l.page);
        CHECK(classWords(l.page) <= l.most);
        CHECK(classWords(l.page) >= l.least);
    }
    int pages10 = classWords("10-combining-estimators.md") + classWords("10m-mirrors-and-glass.md");
    MESSAGE("page 10 and 10M in class: " << pages10 << " words; page 15: " << classWords("15-vertex-merging.md") << "; Appendix A's reading: "
            << classWords(kAppendixA));
    CHECK(pages10 <= 1400);
    CHECK(pages10 >= 900);
    for (const char* sheet : {"10-combining-estimators.md", "10m-mirrors-and-glass.md", "15-vertex-merging.md"})
        CHECK(slurp(std::string("lecture_notes/") + sheet).find("## Optional sheet, after class") != std::string::npos);
}

// Every command the READMEs and the pages print writes under build/ (which make clean removes),
// so that running them leaves the repository as it was (git status clean): --out, --strategies,
// --log and a compiler's -o. Upper-case names (FILE.png, DIR) are the option tables' placeholders.
TEST_CASE("every command the READMEs and the notes print writes under build/") {
    std::vector<std::string> files = notePages();
    files.push_back("README.md");
    files.push_back("tests/README.md");
    std::regex output("(?:--out|--strategies|--log|-o) ([^ `\"|)]+)");
    int outputs = 0, outside = 0;
    for (const std::string& file : files) {
        std::string text = slurp(file);
        for (std::sregex_iterator it(text.begin(), text.end(), output), end; it != end; ++it) {
            const std::string path = (*it)[1];
            const std::string stem = path.substr(0, path.find('.'));
            if (std::none_of(stem.begin(), stem.end(), [](char c) { return std::islower((unsigned char)c); })) continue;  // FILE.png
            CAPTURE(file);
            CAPTURE(path);
            ++outputs;
            outside += path.rfind("build/", 0) != 0;
            CHECK(path.rfind("build/", 0) == 0);
        }
    }
    MESSAGE(outputs << " outputs of printed commands, " << outside << " outside build/");
    CHECK(outputs > 50);
}

// The README is a first hour's guide: set-up, the tour, the command line, the scene format; the
// depth is in the notes (its table of topics points there).
TEST_CASE("the README is at most 400 lines") {
    std::istringstream readme(slurp("README.md"));
    int lines = 0;
    for (std::string line; std::getline(readme, line);) ++lines;
    CHECK(lines > 200);
    CHECK(lines <= 400);
}

TEST_CASE("no development history in the pages or the READMEs") {
    std::vector<std::string> files = notePages();
    files.push_back("README.md");
    files.push_back("tests/README.md");
    // What the git log says, not a page: issue numbers, the work's own steps, what was true before.
    std::regex history("\\b[Ii]ssues? #?[0-9]+|\\bsessions?\\b|\\b[Ww]e (tried|have not|did)\\b|\\(Issues?:|this project's [0-9]-core|"
                       "\\b(were|was) (corrected|fixed|changed)\\b|\\bearlier (runs?|versions?|editions?|numbers|builds?)\\b|"
                       "\\bas before\\b|\\bused to be\\b|\\bpreviously\\b|\\bit now\\b|\\b(step|commit|change) that added\\b|"
                       "\\bin the first (charts|version)\\b|\\bbefore the (fix|change)\\b");
    for (const std::string& file : files) {
        std::string text = flatPage(file.rfind("lecture_notes/", 0) == 0 ? file.substr(14) : "../" + file);
        std::smatch m;
        std::string found = std::regex_search(text, m, history) ? m.str() : "";
        CAPTURE(file);
        CAPTURE(found);
        CHECK(found.empty());
    }
    for (const char* line : {"fixed in issue 24", "1.5x before the densities were corrected", "as the earlier runs had it",
                             "the labels, as before", "in the step that added mlt", "it now reads one byte"})
        CHECK(std::regex_search(std::string(line), history));  // the pattern catches what it should
    CHECK(!std::regex_search(std::string("the acceptance rule no longer gives detailed balance, now that T is not symmetric"), history));
}
