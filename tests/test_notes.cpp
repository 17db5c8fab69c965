// The lecture notes cannot rot: every function they cite exists in bdpt.cpp, every command they
// show runs (at 1 sample per pixel and 8x8 pixels) and writes into build/, every make target
// exists, every figure they show is in lecture_notes/figures/, and the formulas they state are
// the ones the code computes.
#include "helpers.h"
#include "densities.h"
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
static std::string flatPage(const std::string& name) {
    std::string out;
    for (char c : slurp("lecture_notes/" + name)) {
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

// The renderer's source: the lecture's file and the classroom's, which the notes cite too.
static std::string rendererSource() {
    return slurp("bdpt.cpp") + slurp("classroom/classroom.cpp") + slurp("classroom/figures.h") + slurp("classroom/checks.h");
}

TEST_CASE("the notes cite only functions that bdpt.cpp or classroom/ defines") {
    std::string source = rendererSource();
    std::vector<std::string> pages = notePages();
    CHECK(pages.size() >= 16);  // 15 pages and the index
    int cited = 0;
    std::regex call("`([A-Za-z_][A-Za-z0-9_]*)\\(\\)`");
    for (const std::string& page : pages) {
        std::string text = slurp(page);
        for (std::sregex_iterator it(text.begin(), text.end(), call), end; it != end; ++it) {
            std::string name = (*it)[1];
            std::regex definition("\\ninline [^\\n(]*\\b" + name + "\\(");
            CAPTURE(page);
            CAPTURE(name);
            CHECK(std::regex_search(source, definition));
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
    CHECK(pageSays("07-probabilities.md", "p_{k,s+1} / p_{k,s} = pdfRev(x_s) / pdfFwd(x_s)"));
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
    CHECK(pageSays("13-shading-normals.md", "f*(wo, wi) = f(wi, wo) |wo . ns| |wi . ng| / (|wo . ng| |wi . ns|)"));
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
// slides label them (tests/diagrams.py draws them): bdpt's idea, the densities, the path
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
    int targets = 0, images = 0;
    for (const std::string& page : notePages()) {
        std::string text = slurp(page);
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
}

TEST_CASE("every method has its own line style, the same in every chart; a chart has at most six, each its own colour") {
    std::system("bash tests/charts.sh styles > build/tmp/styles.txt");
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

TEST_CASE("Appendix A quotes the reference check's range of ratios as the generated table has it") {
    // The table is regenerated by make figures; prose typed beside it must follow it.
    std::vector<double> ratios;  // the last column, where it is a number ("exact" for the furnace)
    for (const auto& cells : tableRows("lecture_notes/figures/reference-check.md"))
        if (!cells.empty() && cells.back().find_first_of("0123456789") == 0) ratios.push_back(std::stod(cells.back()));
    REQUIRE(ratios.size() >= 10);
    char range[64];
    std::snprintf(range, sizeof range, "%.1fx to %.1fx", *std::min_element(ratios.begin(), ratios.end()),
                  *std::max_element(ratios.begin(), ratios.end()));
    CAPTURE(range);
    CHECK(pageSays("appendix-a-speed-and-accuracy.md", range));
    // every chart's lowest curve ends at least 3 times above its reference's noise: below that
    // a chart measures the reference, not the method
    CHECK(*std::min_element(ratios.begin(), ratios.end()) >= 3);
}

TEST_CASE("the efficiencies the pages quote are the generated table's (make figures)") {
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
    const int mse = 0, cpu = 1, rays = 2, share = 4;
    std::string p10 = flatPage("10-combining-estimators.md"), p12 = flatPage("12-comparison-with-path-tracing.md"),
                p15 = flatPage("15-vertex-merging.md"), a = flatPage("appendix-a-speed-and-accuracy.md");
    std::vector<std::pair<const std::string*, std::string>> quotes = {
        {&p12, "bdpt is " + e("cornell", "bdpt") + " nee --mis"},
        {&p12, e("indirect", "bdpt") + " on `scenes/indirect.scene`, " + e("glass-box", "bdpt") + " (glass-box) and " + e("cornell-glass", "bdpt") + " (cornell-glass)"},
        {&p12, "lt at " + e("indirect", "lt") + " and bdpt at " + e("indirect", "bdpt")},
        {&p15, "cornell " + e("cornell", "vcm") + " (bdpt " + e("cornell", "bdpt") + "), indirect " + e("indirect", "vcm") + " (bdpt " + e("indirect", "bdpt") + ")"},
        {&p15, "cornell-glass " + e("cornell-glass", "vcm") + " (bdpt " + e("cornell-glass", "bdpt") + "), glass-box " + e("glass-box", "vcm") + " (bdpt " + e("glass-box", "bdpt") + ";"},
        {&p15, e("sds-ior1", "vcm") + " nee --mis, bdpt " + e("sds-ior1", "bdpt")},
        {&a, "nee --mis wins (bdpt " + e("cornell", "bdpt") + ")"},
        {&a, "lead (" + e("indirect", "lt") + " and " + e("indirect", "bdpt")},
        {&a, e("cornell-glass", "bdpt") + " on cornell-glass and " + e("glass-box", "bdpt") + " on glass-box"},
        {&a, "(cornell " + e("cornell", "vcm") + " against " + e("cornell", "bdpt") + ", indirect " + e("indirect", "vcm") + " against " + e("indirect", "bdpt")},
        {&a, "(cornell-glass " + e("cornell-glass", "vcm") + " against " + e("cornell-glass", "bdpt") + ", glass-box " + e("glass-box", "vcm") + " against " + e("glass-box", "bdpt")},
        {&a, "(mmlt " + e("sds-ior1", "mmlt") + " against bdpt's " + e("sds-ior1", "bdpt")},
        {&a, "light tracing leads (" + e("door", "lt") + "), bdpt follows (" + e("door", "bdpt") + ") and pssmlt reaches " + e("door", "pssmlt")},
        {&p10, col("indirect", "bdpt", mse) + " for balance, " + col("indirect", "bdpt --heuristic power", mse) + " power, " +
                   col("indirect", "bdpt --heuristic max", mse) + " max and " + col("indirect", "bdpt --heuristic uniform", mse) + " uniform"},
        // numbers derived from the table: ratios of its cells
        {&a, "a sample costs " + ratio("%.1fx", "cornell", "bdpt", "nee", cpu) + " (CPU seconds; " + col("cornell", "bdpt", rays) +
                 " rays against " + col("cornell", "nee", rays) + ")"},
        {&a, "For bdpt on glass-box that share is " + col("glass-box", "bdpt", share)},
        {&a, "its MSE is " + ratio("%.0fx", "sds-ior1", "bdpt", "vcm", mse) + " below bdpt's"},
        {&p15, "vcm's MSE is " + ratio("%.2fx", "glass-box", "vcm", "nee", mse) + " nee's, bdpt's " + ratio("%.2fx", "glass-box", "bdpt", "nee", mse)},
        {&p15, "vcm's MSE is " + ratio("%.0fx", "sds-ior1", "bdpt", "vcm", mse) + " below bdpt's"},
        {&a, "its MSE at equal mutations is " + ratio("%.0f", "cornell", "mmlt", "pssmlt", mse) + " to " +
                   ratio("%.0f", "glass-box", "mmlt", "pssmlt", mse) + " times pssmlt's"},
        {&a, "its MSE is " + ratio("%.2fx", "door", "pssmlt", "bdpt", mse) + " bdpt's"},
        {&a, "a mutation costs " + ratio("%.1fx", "door", "pssmlt", "bdpt", cpu) + " a bdpt sample there"},
        {&a, col("door", "pssmlt", rays) + " rays per sample against " + col("door", "bdpt", rays)},
    };
    // Appendix A: cornell-glass's ratio lies between cornell's and glass-box's, the range it quotes
    double cornellGlass = quotient("cornell-glass", "mmlt", "pssmlt", mse);
    CHECK(cornellGlass >= quotient("cornell", "mmlt", "pssmlt", mse));
    CHECK(cornellGlass <= quotient("glass-box", "mmlt", "pssmlt", mse));
    // Appendix A: "Veach's mlt loses on every scene of this table"
    for (const char* scene : {"cornell", "cornell-glass", "indirect", "glass-box", "sds-ior1", "door"})
        CHECK(std::stod(e(scene, "mlt")) < std::stod(e(scene, "bdpt")));
    // page 16: "mlt's and mmlt's unevenness are above bdpt's (the table)", the spliced make uneven table
    std::map<std::string, double> unevenness;
    for (const auto& cells : tableRows("lecture_notes/figures/uneven-door.md"))
        if (cells.size() >= 5 && cells[4].find_first_of("0123456789") == 0) unevenness[cells[0]] = std::stod(cells[4]);
    REQUIRE(unevenness.size() == 4);
    CHECK(unevenness["mlt"] > unevenness["bdpt"]);
    CHECK(unevenness["mmlt"] > unevenness["bdpt"]);
    for (const auto& [page, quote] : quotes) {
        CAPTURE(quote);
        CHECK(page->find(quote) != std::string::npos);
    }
}

TEST_CASE("the slopes and biases the pages quote are the failure table's (make figures)") {
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
    }
    REQUIRE(cell.size() == 168);  // 12 scenes x 14 methods, each row its own key
    auto slope = [&](const char* s, const char* m) { return cell.at(std::string(s) + "|" + m).first; };
    auto bias = [&](const char* s, const char* m) { return cell.at(std::string(s) + "|" + m).second; };
    auto firefly = [&](const char* m) { return fireflies.at(std::string("cornell|") + m); };
    std::string p1 = flatPage("01-path-sampling-techniques.md"), p12 = flatPage("12-comparison-with-path-tracing.md"),
                p14 = flatPage("14-power-versus-radiance.md"), p15 = flatPage("15-vertex-merging.md"),
                a = flatPage("appendix-a-speed-and-accuracy.md");
    std::vector<std::pair<const std::string*, std::string>> quotes = {
        {&p1, "lt flattens at once (bias " + bias("cornell-glass", "lt")},
        {&p1, "clamped ir stays high (bias " + bias("cornell-glass", "ir --clamp")},
        {&p12, "pt, nee, lt (bias " + bias("sds-point", "pt") + ": black), ir (" + bias("sds-point", "ir") + ") and bdpt (" + bias("sds-point", "bdpt balance")},
        {&p12, "Only vcm falls (slope " + slope("sds-point", "vcm") + ", bias " + bias("sds-point", "vcm") + ")"},
        {&p12, "uniform heuristic has a slope of " + slope("sds-point", "bdpt uniform")},
        {&p14, "(bias " + bias("refraction", "lt") + "): it cannot"},
        {&p14, "clamped ir levels off too (" + bias("refraction", "ir --clamp")},
        {&p14, "unclamped ir's " + bias("refraction", "ir")},
        {&a, "bdpt " + bias("sds-point", "bdpt balance") + " and " + bias("sds-ior1", "bdpt balance") + ", slope 0"},
        {&a, "vcm on `sds-point` and `sds-ior1` (slope " + slope("sds-point", "vcm") + " and " + slope("sds-ior1", "vcm") + ", bias " +
                 bias("sds-point", "vcm") + " and " + bias("sds-ior1", "vcm") + ")"},
        {&a, "from " + slope("refraction", "vcm") + ", vcm on `refraction`, to " + slope("refraction", "mmlt") + ", mmlt there"},
        {&a, "still falls fast there (slope " + slope("sds", "vcm") + ")"},
        {&p15, "vcm " + slope("sds-ior1", "vcm") + " on sds-ior1 and " + slope("sds-point", "vcm") + " on sds-point, while bdpt's error there stays flat at " +
                   bias("sds-ior1", "bdpt balance") + " and " + bias("sds-point", "bdpt balance") + " (slope " + slope("sds-ior1", "bdpt balance") +
                   " and " + slope("sds-point", "bdpt balance") + ")"},
        {&a, "lt on `cornell-point` (" + bias("cornell-point", "lt") + ", slope 0)"},
        {&a, "(" + bias("cornell", "ir --clamp") + " on cornell, where at 4 s the noise still dominates, slope " + slope("cornell", "ir --clamp") +
                 "; " + bias("indirect", "ir --clamp") + " on indirect"},
        {&a, "from the ceiling, slope " + slope("indirect", "ir --clamp") + ")"},
        {&a, "(cornell: mlt " + slope("cornell", "mlt") + ", mmlt " + slope("cornell", "mmlt") + ")"},
        {&a, "the slopes on cornell-glass are " + slope("cornell-glass", "pssmlt") + " (pssmlt), " + slope("cornell-glass", "mmlt") +
                   " (mmlt) and " + slope("cornell-glass", "mlt") + " (mlt)"},
        {&a, "where bdpt's is " + slope("cornell-glass", "bdpt balance")},
        {&a, "has one of the smallest ratios (" + firefly("pt") + "), and ir, bdpt and nee, good elsewhere, ratios " +
                 std::to_string(int(std::lround(std::stod(firefly("nee")) / std::stod(firefly("pt"))))) + " to " +
                 std::to_string(int(std::lround(std::stod(firefly("ir")) / std::stod(firefly("pt"))))) + " times as large (" + firefly("ir") + ", " +
                 firefly("bdpt balance") + " and " + firefly("nee") + ")"},
        {&a, "from " + bias("cornell-glass", "ir") + ", ir on cornell-glass, to " + bias("refraction", "ir") + ", ir on refraction"},
        {&a, "vcm on `door` (" + bias("door", "vcm") + " in the table, slope " + slope("door", "vcm") + " while the noise"},
    };
    for (const auto& [page, quote] : quotes) {
        CAPTURE(quote);
        CHECK(page->find(quote) != std::string::npos);
    }
}

TEST_CASE("page 10's four paths: the numbers its text quotes are the densities' (tests/estimators.cpp)") {
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
    std::string p10 = flatPage("10-combining-estimators.md");
    std::vector<std::string> quotes = {
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
    quotes.push_back("f/p_A is " + text("%.0f", smallest) + " to " + text("%.0f", largest) + " times the widest one's");
    for (const std::string& quote : quotes) {
        CAPTURE(quote);
        CHECK(p10.find(quote) != std::string::npos);
    }
}

// The pages speak of the renderer, not of how it was made: no issue numbers, no sessions, no
// "we tried", no machine of the project's own (the git log keeps the history).
// Page 16 is the slide's "see later": a lecture's worth (its measurements are Appendix A's).
TEST_CASE("page 16 is a teachable core of at most 1,000 words") {
    std::istringstream words(slurp("lecture_notes/16-metropolis-sampling.md"));
    int count = 0;
    for (std::string w; words >> w;) ++count;
    CHECK(count <= 1000);
    CHECK(count >= 600);  // and still the page: the idea, the step, b and the start, mmlt, the bullets
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
