// The lecture's file alone: bdpt.cpp compiled without classroom/ renders every method as ./bdpt
// does, bit for bit, and every method's image at a fixed seed is what it was.
#include "helpers.h"
#include "homework/mistakes.h"
#include <regex>

// FNV-1a 64 of an image's floats, rows from the top: the fingerprint tests/fixed-seed-images.txt keeps.
static uint64_t pixelHash(const Image& img) {
    uint64_t h = 0xcbf29ce484222325ULL;
    const unsigned char* p = reinterpret_cast<const unsigned char*>(img.pixels.data());
    for (size_t i = 0; i < img.pixels.size() * sizeof(Vec3); ++i) h = (h ^ p[i]) * 0x100000001b3ULL;
    return h;
}

static std::vector<std::string> words(const std::string& text) {
    std::istringstream in(text);
    std::vector<std::string> w;
    for (std::string x; in >> x;) w.push_back(x);
    return w;
}

// ./bdpt's image (this program's runCommandLine) of scene and options at 16x16, 2 spp, seed 3.
static Image fixedSeedImage(const std::string& scene, const std::string& options, const std::string& out) {
    std::vector<std::string> args = {scene, "--res", "16x16", "--spp", "2", "--seed", "3", "--quiet", "--out", out};
    for (const std::string& w : words(options)) args.push_back(w);
    std::ostringstream so, se;
    CAPTURE(se.str());
    REQUIRE(runCommandLine(args, so, se) == 0);
    Image img;
    REQUIRE(readPFM(replaceExtension(out, ".pfm"), img));
    return img;
}

TEST_CASE("every method's image at a fixed seed is the one tests/fixed-seed-images.txt keeps, bit for bit") {
    std::ifstream in("tests/fixed-seed-images.txt");
    REQUIRE(in);
    const bool rewrite = std::getenv("REWRITE_FIXED_SEED_IMAGES") != nullptr;
    std::ostringstream rewritten;
    int checked = 0, methods = 0;
    std::set<std::string> seen;
    const std::string out = "build/tmp/fixed-seed-" + std::to_string(getpid()) + ".png";  // two suites at once: two files
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') { rewritten << line << "\n"; continue; }
        size_t a = line.find(" | "), b = line.rfind(" | ");
        REQUIRE(a != std::string::npos);
        std::string scene = line.substr(0, a), options = line.substr(a + 3, b - a - 3), expected = line.substr(b + 3);
        char got[17];
        std::snprintf(got, sizeof got, "%016llx", (unsigned long long)pixelHash(fixedSeedImage(scene, options, out)));
        rewritten << scene << " | " << options << " | " << got << "\n";
        CAPTURE(scene);
        CAPTURE(options);
        if (!rewrite) CHECK(expected == got);
        methods += seen.insert(words(options)[1]).second;
        ++checked;
    }
    std::remove(out.c_str());
    std::remove(replaceExtension(out, ".pfm").c_str());
    if (rewrite) std::ofstream("tests/fixed-seed-images.txt") << rewritten.str();
    CHECK(checked >= 250);
    CHECK(methods == 9);  // every method, on every committed scene
}

// A broken image must change the fingerprint: one float's last bit.
TEST_CASE("the fingerprint sees one bit of one pixel") {
    Image a(4, 4);
    Image b = a;
    b.pixels[7].y = std::nextafter(0.0f, 1.0f);
    CHECK(pixelHash(a) != pixelHash(b));
}

TEST_CASE("bdpt.cpp alone (build/bdpt-lecture) renders every method as ./bdpt does, bit for bit") {
    REQUIRE(fileExists("build/bdpt-lecture"));  // make test builds it: g++ ... bdpt.cpp -lstb, nothing else
    const std::string scene = "scenes/cornell-glass.scene";
    for (const char* options : {"--method pt", "--method nee --mis", "--method lt", "--method ir --clamp 1e-3", "--method bdpt --heuristic power",
                                "--method vcm", "--method pssmlt --bootstrap 2000", "--method mmlt --bootstrap 2000",
                                "--method mlt --bootstrap 2000", "--method bdpt --symmetric-refraction --no-adjoint-correction"}) {
        CAPTURE(options);
        Image full = fixedSeedImage(scene, options, "build/tmp/full.png");
        std::string command = "build/bdpt-lecture " + scene + " --res 16x16 --spp 2 --seed 3 --quiet --out build/tmp/lecture.png " + options;
        REQUIRE(std::system(command.c_str()) == 0);
        Image lecture;
        REQUIRE(readPFM("build/tmp/lecture.pfm", lecture));
        CHECK(imageMean(full) > 0);
        CHECK(std::memcmp(full.pixels.data(), lecture.pixels.data(), full.pixels.size() * sizeof(Vec3)) == 0);
    }
    // The per-strategy images too: the lecture writes the files, ./bdpt adds its pyramids.
    REQUIRE(std::system("build/bdpt-lecture scenes/cornell.scene --res 16x16 --spp 2 --quiet --strategies build/tmp/lecture-strategies "
                        "--strategy-length 3 --out build/tmp/lecture.png") == 0);
    std::ostringstream so, se;
    REQUIRE(runCommandLine({"scenes/cornell.scene", "--res", "16x16", "--spp", "2", "--quiet", "--strategies", "build/tmp/full-strategies",
                            "--strategy-length", "3", "--out", "build/tmp/full.png"}, so, se) == 0);
    int compared = 0;
    for (const char* name : {"s0_t2", "s1_t2", "s2_t1", "s0_t4", "s2_t2", "s3_t1"})
        for (const char* kind : {"_weighted", "_unweighted"}) {
            Image a, b;
            REQUIRE(readPFM(std::string("build/tmp/lecture-strategies/") + name + kind + ".pfm", a));
            REQUIRE(readPFM(std::string("build/tmp/full-strategies/") + name + kind + ".pfm", b));
            CHECK(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Vec3)) == 0);
            ++compared;
        }
    CHECK(compared == 12);
    CHECK(fileExists("build/tmp/full-strategies/pyramid-weighted.png"));
    CHECK(!fileExists("build/tmp/lecture-strategies/pyramid-weighted.png"));
}

// The lecture's file reads as the slides: no tool's hook in its transport code (sections 1-8), and
// its banners in the slides' order.
TEST_CASE("bdpt.cpp carries only the lecture: no tool hooks before its film, sections in order") {
    std::ifstream in("bdpt.cpp");
    std::vector<std::string> banners;
    int hooks = 0, lines = 0;
    bool transport = true;
    for (std::string line; std::getline(in, line); ++lines) {
        if (line.rfind("// == ", 0) == 0) banners.push_back(line.substr(6, 3));
        if (line.rfind("// == 9.", 0) == 0) transport = false;
        std::string code = line.substr(0, line.find("//"));
        for (const char* hook : {"RayCount&", "CostScope", "onPass", "strategyIndex(", "std::function", "gCostClock"})
            hooks += transport && code.find(hook) != std::string::npos;
    }
    CHECK(hooks == 0);
    CHECK(lines <= 4210);  // the lecture (Veach's four mutations among its later methods), its film (a pass also in three steps, for the page), scene file, command line (its methods' captions one table, read by --help, the figures and the page) and three appendices of machinery; tools live in classroom/
    std::vector<std::string> expected = {"1. ", "2. ", "3. ", "4. ", "5. ", "6. ", "7. ", "8. ", "9. ", "10.", "11.", "App", "App", "App"};
    CHECK(banners == expected);
}

// The lecture first: the first method starts within the first 21% of the file, after only the
// slides' topics (random numbers, geometry and the scene, materials, lights, camera); the data
// structures no slide shows (the BVH, Sobol's construction and its fast path, vcm's hash grid) are
// appendices at the end.
TEST_CASE("bdpt.cpp: the first method within the first 21%; the BVH, Sobol points and the hash grid after the lecture") {
    std::ifstream in("bdpt.cpp");
    int lines = 0, firstMethod = 0, bvhBuilder = 0, fastSobol = 0, lastMethod = 0, sobolDefinition = 0, hashGrid = 0;
    for (std::string line; std::getline(in, line);) {
        ++lines;
        if (!firstMethod && line.rfind("inline Vec3 samplePT(", 0) == 0) firstMethod = lines;
        if (line.rfind("inline Vec3 sampleMLT(", 0) == 0) lastMethod = lines;
        if (line.rfind("struct BvhBuilder", 0) == 0) bvhBuilder = lines;
        if (line.rfind("inline void Rng::drawCoordinates(", 0) == 0 && line.find(';') == std::string::npos) fastSobol = lines;
        if (line.rfind("constexpr SobolMatrices makeSobolMatrices(", 0) == 0) sobolDefinition = lines;
        if (line.rfind("inline std::vector<uint32_t> buildHashGrid(", 0) == 0 && line.find(';') == std::string::npos) hashGrid = lines;
    }
    MESSAGE("samplePT at line " << firstMethod << " of " << lines << " (" << 100 * firstMethod / lines << "%)");
    CHECK(firstMethod > 0);
    CHECK(firstMethod <= lines * 21 / 100);
    CHECK(bvhBuilder > lastMethod);
    CHECK(fastSobol > lastMethod);
    CHECK(sobolDefinition > lastMethod);
    CHECK(hashGrid > lastMethod);
}

// One help text per option: the lecture's --help and ./bdpt's give every option they share the same
// words, ./bdpt's followed by what it does more (its tools' rows between them).
TEST_CASE("build/bdpt-lecture --help and ./bdpt --help agree on every shared option") {
    auto blocks = [](const std::string& text) {
        std::map<std::string, std::string> rows;
        std::istringstream in(text);
        std::string current;
        for (std::string line; std::getline(in, line);) {
            if (line.rfind("  --", 0) == 0) {
                current = line.substr(2, line.find(' ', 2) - 2);
                rows[current] = line;
            } else if (!current.empty() && line.rfind("    ", 0) == 0) {
                rows[current] += "\n" + line;
            } else {
                current.clear();
            }
        }
        return rows;
    };
    REQUIRE(std::system("build/bdpt-lecture --help > build/tmp/lecture-help.txt") == 0);
    std::ostringstream so, se;
    REQUIRE(runCommandLine({"--help"}, so, se) == 0);
    std::ifstream f("build/tmp/lecture-help.txt");
    std::stringstream lectureText;
    lectureText << f.rdbuf();
    auto lecture = blocks(lectureText.str()), classroom = blocks(so.str());
    CHECK(lecture.size() >= 30);
    CHECK(classroom.size() > lecture.size());
    int differ = 0;
    int extended = 0;
    for (const auto& [name, text] : lecture) {
        CAPTURE(name);
        differ += classroom.count(name) == 0 || classroom.at(name).rfind(text, 0) != 0;
        extended += classroom.count(name) && classroom.at(name) != text;
    }
    CHECK(differ == 0);
    CHECK(extended == 3);  // --radius, --strategies, --quiet: below, each program does what its own says
}

// What the lecture keeps, it prints, and each printed number is the quantity it names, checked
// from outside the program. The clamp's share: ir with and without the clamp, at one seed, make the
// same camera rays and VPLs, and pt --maxdepth 0 the same rays' emission seen directly; so the
// energy the clamp removed is (unclamped - clamped) / (unclamped - emission), from the three PFMs'
// means (printing the clamped share, or the share of the whole image, fails). The chains'
// acceptance: with the bidirectional mutation alone every proposal is one, so its line must
// repeat the chains' total, N = W x H x passes proposals; with two mutations their proposals add
// up to N and their acceptances, weighted by proposals, to the total's (a table with its columns
// swapped or a rate of the wrong count fails).
static std::string lectureRun(const std::string& args, const std::string& name) {
    const std::string command = "build/bdpt-lecture " + args + " --out build/tmp/" + name + ".png > build/tmp/" + name + ".txt";
    REQUIRE(std::system(command.c_str()) == 0);
    return readFile("build/tmp/" + name + ".txt");
}
static double pfmMean(const std::string& name) {
    Image img;
    REQUIRE(readPFM("build/tmp/" + name + ".pfm", img));
    double sum = 0;
    for (const Vec3& p : img.pixels) sum += (double(p.x) + p.y + p.z) / 3;
    return sum / double(img.pixels.size());
}
TEST_CASE("the lecture's program prints what its options promise: the clamp's energy, the chains' b and acceptance") {
    const std::string common = "scenes/cornell.scene --res 24x24 --spp 4 --seed 7 ";
    const std::string text = lectureRun(common + "--method ir --clamp 1e-5", "clamp");
    lectureRun(common + "--method ir", "unclamped");
    lectureRun(common + "--method pt --maxdepth 0", "emission");
    const size_t at = text.find("clamp 1e-05 removed ");
    REQUIRE(at != std::string::npos);
    const double printed = std::atof(text.c_str() + at + 20) / 100;
    const double clamped = pfmMean("clamp"), unclamped = pfmMean("unclamped"), emission = pfmMean("emission");
    const double removed = (unclamped - clamped) / (unclamped - emission);
    MESSAGE("the clamp removed " << 100 * printed << "% as printed, " << 100 * removed << "% from the three images");
    CHECK(removed > 0.01);
    CHECK(printed == doctest::Approx(removed).epsilon(1e-3));

    auto number = [](const std::string& t, const std::string& before) {
        const size_t p = t.find(before);
        REQUIRE(p != std::string::npos);
        return std::atof(t.c_str() + p + before.size());
    };
    const std::string pssmlt = lectureRun("scenes/cornell.scene --method pssmlt --bootstrap 2000 --res 16x16 --spp 2", "chains");
    CHECK(pssmlt.find("pssmlt: b = ") != std::string::npos);
    CHECK(number(pssmlt, "% of ") == 16 * 16 * 2);
    const std::string mlt = "scenes/door.scene --method mlt --bootstrap 20000 --res 24x24 --spp 4 --seed 5 ";
    const std::string one = lectureRun(mlt + "--mutations bidir", "mlt-bidir");
    const double N = 24 * 24 * 4;
    MESSAGE(one);
    auto rateAndCount = [&](const std::string& t, const std::string& name) {  // "NAME X% of N" in the per-mutation line
        const size_t p = t.find(name + " ", t.find("mlt: accepted"));
        REQUIRE(p != std::string::npos);
        const double rate = std::atof(t.c_str() + p + name.size() + 1);
        return std::make_pair(rate, std::atof(t.c_str() + t.find("% of ", p) + 5));
    };
    const double total = number(one, "chains accepted "), totalCount = number(one, "% of ");
    auto [bidir, bidirCount] = rateAndCount(one, "bidirectional");
    CHECK(totalCount == N);
    CHECK(bidirCount == N);
    CHECK(bidir == total);
    CHECK(one.find("lens 0.0% of 0,") != std::string::npos);
    CHECK(one.find("caustic 0.0% of 0,") != std::string::npos);
    CHECK(one.find("multi-chain 0.0% of 0 ") != std::string::npos);
    const std::string two = lectureRun(mlt + "--mutations bidir,lens", "mlt-two");
    MESSAGE(two);
    auto [bRate, bCount] = rateAndCount(two, "bidirectional");
    auto [lRate, lCount] = rateAndCount(two, "lens");
    const double all = number(two, "chains accepted ");
    CHECK(bCount + lCount == N);
    CHECK(lCount > 0);
    CHECK(std::fabs((bRate * bCount + lRate * lCount) / N - all) <= 0.1);  // each printed to 0.1%
}

// The homework is cut from this file (make homework, classroom/homework/tasks): every cut must
// still find its function and lines here, and the file a student gets must compile with its
// stubs. make test-homework grades it; this is the quick guard for an edit of bdpt.cpp.
TEST_CASE("the homework's cuts still fit bdpt.cpp, and the file they make compiles") {
    REQUIRE(std::system("g++ -O0 -std=c++17 -o build/tmp/homework-cut classroom/homework/cut.cpp > build/tmp/homework-cut.log 2>&1") == 0);
    REQUIRE(std::system("mkdir -p build/tmp/homework/grader") == 0);
    const int cut = std::system("build/tmp/homework-cut classroom/homework/tasks bdpt.cpp build/tmp/homework 'H1 H2 H3 H4 H5 H6' "
                                "> build/tmp/homework-cut.txt 2>&1");
    CAPTURE(readFile("build/tmp/homework-cut.txt"));
    REQUIRE(cut == 0);
    const std::string handedOut = readFile("build/tmp/homework/bdpt.cpp");
    int todos = 0, cuts = 0;
    for (size_t at = handedOut.find("// TODO (H"); at != std::string::npos; at = handedOut.find("// TODO (H", at + 1)) ++todos;
    std::istringstream tasks(readFile("classroom/homework/tasks"));
    for (std::string line; std::getline(tasks, line);) cuts += line.rfind("cut ", 0) == 0 || line.rfind("cut-lines ", 0) == 0;
    CHECK(cuts >= 12);
    CHECK(todos == cuts);  // every cut of the task list, each once
    CHECK(std::system("g++ -std=c++17 -Wall -Wextra -Werror -fsyntax-only build/tmp/homework/bdpt.cpp > build/tmp/homework-syntax.log 2>&1") == 0);
    CAPTURE(readFile("build/tmp/homework-syntax.log"));
    // What a cut leaves above its TODO is code: a comment there would be the cut lines' own
    // explanation, handed out with the task (specularScatter's "Radiance flows wi -> wo: ...").
    std::vector<std::string> lines;
    std::istringstream in(handedOut);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    int commentsAbove = 0;
    for (size_t i = 1; i < lines.size(); ++i)
        if (lines[i].find("// TODO (H") != std::string::npos && lines[i - 1].find_first_not_of(' ') != std::string::npos &&
            lines[i - 1].compare(lines[i - 1].find_first_not_of(' '), 2, "//") == 0) {
            MESSAGE("a comment left above a TODO: " << lines[i - 1]);
            ++commentsAbove;
        }
    CHECK(commentsAbove == 0);
    // The texts that answer a task (tasks' `secret` lines: code, and the banners' formulas) stand in
    // the solution and nowhere in what a student gets: the file handed out, its README.
    const std::string solution = readFile("bdpt.cpp"), readme = readFile("build/tmp/homework/README.md");
    std::istringstream list(readFile("classroom/homework/tasks"));
    int secrets = 0, inSolution = 0, handed = 0;
    for (std::string line; std::getline(list, line);) {
        if (line.rfind("secret ", 0) != 0) continue;
        const std::string secret = line.substr(7);
        ++secrets;
        inSolution += solution.find(secret) != std::string::npos;
        const bool given = handedOut.find(secret) != std::string::npos || readme.find(secret) != std::string::npos;
        handed += given;
        if (given) MESSAGE("handed out with its task: " << secret);
    }
    CHECK(secrets >= 12);
    CHECK(inSolution == secrets);
    CHECK(handed == 0);
    // The README's path through a mirror: each strategy's "makes the path" is physics.h's able().
    Scene scene = parseScene("camera 0 1 -4  0 1 0  0 1 0  40  8 8\nmaterial white diffuse 0.5 0.5 0.5\nmaterial mirror mirror 0.9 0.9 0.9\n"
                             "quad -1 2 -1  2 0 0  0 0 2  white emit 1 1 1\nquad -3 0 -3  6 0 0  0 0 6  white\nquad 2 0 -1  0 2 0  0 0 2  mirror\n", "mirror path");
    std::vector<PathVertex> x(5);
    const int shapes[5] = {0, 1, 2, 1, -1};  // the lamp, diffuse, the mirror, diffuse, the pinhole
    for (int i = 0; i < 5; ++i) x[size_t(i)].sp.shape = shapes[i], x[size_t(i)].type = PathVertex::Surface;
    std::istringstream rows(readme.substr(readme.find("| s | t | joins | makes the path |")));
    int checkedRows = 0;
    for (std::string row; std::getline(rows, row) && row.rfind("|", 0) == 0;) {
        if (!std::isdigit(static_cast<unsigned char>(row[2]))) continue;
        const int s = row[2] - '0';
        CAPTURE(row);
        CHECK((row.find("| yes |") != std::string::npos) == able(scene, x, s));
        ++checkedRows;
    }
    CHECK(checkedRows == 5);
}

// What the homework tells a student (the TODOs and the README, from classroom/homework/tasks)
// states no formula of its own: it says what to compute and where to read it. A formula it does
// show is quoted from the notes, in backticks, as a page the task names writes it; so an
// acceptance or a scale factor written upside down in a TODO is found here, not by a student.
static std::vector<std::string> unquotedFormulas(const std::string& text) {
    static const std::regex formula("\\b(min|max|sqrt|exp|log|abs|pow)\\s*\\(|[A-Za-z0-9_)\\]}|]\\s*/\\s*[A-Za-z0-9_(\\[{|]|\\^\\s*[0-9{(]|"
                                    "\\|[A-Za-z_][A-Za-z0-9_.]*\\|");
    std::vector<std::string> found;
    const std::string bare = std::regex_replace(text, std::regex("`[^`]*`"), "``");
    for (std::sregex_iterator it(bare.begin(), bare.end(), formula), end; it != end; ++it) found.push_back(it->str());
    return found;
}
TEST_CASE("the homework's words state no formula but quotes from the notes pages of their task") {
    CHECK(unquotedFormulas("accept with a = min(1, f(u)/f(v))").size() == 2);  // the rule bites
    CHECK(unquotedFormulas("scale by (eta_o/eta_i)^2").size() == 2);
    CHECK(unquotedFormulas("the factor |wo.ns| over |wo.ng|").size() == 2);
    CHECK(unquotedFormulas("the acceptance `min(1, f(v)/f(u))` of page 16; Transport::Radiance, (s,t)").empty());
    std::istringstream tasks(readFile("classroom/homework/tasks"));
    std::string task, notes;
    int lines = 0, quotes = 0;
    for (std::string line; std::getline(tasks, line);) {
        if (line.rfind("task ", 0) == 0) task = line;
        if (line.rfind("notes ", 0) == 0) notes = line.substr(6);
        const bool words = line.rfind("teaches ", 0) == 0 || line.rfind("told ", 0) == 0 || line.rfind("  todo ", 0) == 0;
        if (!words) continue;
        ++lines;
        CAPTURE(task);
        CAPTURE(line);
        CHECK(unquotedFormulas(line).empty());
        static const std::regex quoted("`([^`]*)`");
        for (std::sregex_iterator it(line.begin(), line.end(), quoted), end; it != end; ++it) {
            const std::string quote = (*it)[1];
            bool onPage = false;
            std::istringstream pages(notes);
            for (std::string page; pages >> page;)
                onPage = onPage || readFile("lecture_notes/" + page).find(quote) != std::string::npos;
            CAPTURE(quote);
            CHECK((onPage || !std::regex_search(quote, std::regex("[/^|(]"))));  // a formula quoted is the notes'
            ++quotes;
        }
    }
    MESSAGE(lines << " lines of the homework's words, " << quotes << " quotes");
    CHECK(lines > 40);
}

// tests/homework/mistakes.txt pins texts of bdpt.cpp (the lines each plausible mistake changes):
// each must be there exactly once, or make test-homework, minutes later, cannot apply it.
TEST_CASE("every text tests/homework/mistakes.txt changes is in bdpt.cpp exactly once") {
    const std::string source = readFile("bdpt.cpp");
    std::vector<Mistake> mistakes = readMistakes();
    int texts = 0, once = 0;
    for (const Mistake& m : mistakes)
        for (const auto& edit : m.edits) {
            ++texts;
            size_t at = source.find(edit.first);
            bool found = at != std::string::npos && source.find(edit.first, at + 1) == std::string::npos;
            once += found;
            if (!found) MESSAGE(m.task << " \"" << m.what << "\": " << (at == std::string::npos ? "not found" : "found twice") << ": " << edit.first);
        }
    CHECK(mistakes.size() >= 30);
    CHECK(texts >= 32);
    CHECK(once == texts);
}

// Each program's --help promises what that program does: the pyramid montages, vcm's memory line
// and the progress bar are ./bdpt's; the lecture's help names none of them, and its runs make none.
TEST_CASE("each program's --help is true of it: --strategies' montages, --radius's summary, --quiet's progress bar") {
    auto helpOf = [](const std::string& text, const std::string& option) {
        size_t at = text.find("\n  " + option + " ");
        REQUIRE(at != std::string::npos);
        size_t end = text.find("\n  --", at + 1);
        return text.substr(at, end - at);
    };
    REQUIRE(std::system("build/bdpt-lecture --help > build/tmp/lecture-help.txt") == 0);
    const std::string lecture = readFile("build/tmp/lecture-help.txt");
    std::ostringstream so, se;
    REQUIRE(runCommandLine({"--help"}, so, se) == 0);
    const std::string classroom = so.str();
    // --strategies: the montages only where the help says so.
    CHECK(helpOf(lecture, "--strategies").find("pyramid") == std::string::npos);
    CHECK(helpOf(classroom, "--strategies").find("pyramid montages") != std::string::npos);
    std::remove("build/tmp/help-lecture/pyramid-weighted.png");
    lectureRun("scenes/cornell.scene --res 16x16 --spp 1 --strategies build/tmp/help-lecture", "help-lecture");
    CHECK(fileExists("build/tmp/help-lecture/s1_t2_weighted.pfm"));
    CHECK_FALSE(fileExists("build/tmp/help-lecture/pyramid-weighted.png"));
    std::ostringstream out, err;
    REQUIRE(runCommandLine({"scenes/cornell.scene", "--res", "16x16", "--spp", "1", "--quiet", "--strategies", "build/tmp/help-classroom",
                            "--out", "build/tmp/help-classroom.png"}, out, err) == 0);
    CHECK(fileExists("build/tmp/help-classroom/pyramid-weighted.png"));
    CHECK(fileExists("build/tmp/help-classroom/pyramid-unweighted.png"));
    // --radius: the memory in the summary where the help says so.
    CHECK(helpOf(lecture, "--radius").find("summary") == std::string::npos);
    CHECK(helpOf(classroom, "--radius").find("the summary line reports both") != std::string::npos);
    CHECK(lectureRun("scenes/cornell.scene --method vcm --res 16x16 --spp 1", "help-vcm").find(" MB") == std::string::npos);
    std::ostringstream vcm, vcmErr;
    REQUIRE(runCommandLine({"scenes/cornell.scene", "--method", "vcm", "--res", "16x16", "--spp", "1", "--out", "build/tmp/help-vcm.png"}, vcm, vcmErr) == 0);
    CHECK(vcm.str().find("light vertices per pixel and pass") != std::string::npos);
    CHECK(vcm.str().find(" MB (") != std::string::npos);
    // --quiet: a progress bar only where the help names one (the lecture draws none).
    CHECK(helpOf(lecture, "--quiet").find("progress") == std::string::npos);
    CHECK(helpOf(classroom, "--quiet").find("progress bar") != std::string::npos);
    CHECK(lecture.find("progress") == std::string::npos);
}
