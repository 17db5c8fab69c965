// The mistakes of a first hour with the program, each answered by a clear message before any work
// is done: output paths, options that do not apply, scene files from other editors and systems,
// scenes that render but not as meant, Ctrl-C.
#include "helpers.h"
#include <poll.h>
#include <pty.h>

struct Run {
    int status;
    std::string out, err;
};

static Run run(const std::vector<std::string>& args) {
    std::ostringstream so, se;
    int status = runCommandLine(args, so, se);
    return {status, so.str(), se.str()};
}

static bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Each run asks for 100,000 passes of a 256x256 image, hours of work: a check made after the
// render would hang the suite rather than pass it. Before any work, a refused run prints no
// summary line.
TEST_CASE("output paths are checked before rendering: the path and the reason, status 1, nothing rendered") {
    // A missing folder is made (a page's command into build/notes/ from a fresh clone); one that
    // cannot be, because part of its path is a file, is named.
    writeTempFile("fh_a_file", "not a folder");
    Run r = run({"scenes/cornell.scene", "--spp", "100000", "--out", "build/tmp/fh_a_file/dir/x.png"});
    CHECK(r.status == 1);
    CHECK(r.err == "bdpt: cannot write build/tmp/fh_a_file/dir/x.png: the folder build/tmp/fh_a_file/dir cannot be made "
                   "(build/tmp/fh_a_file is a file) (nothing rendered)\n");
    r = run({"scenes/cornell.scene", "--spp", "100000", "--out", "build/tmp/fh.png", "--log", "build/tmp/fh_a_file/log.csv"});
    CHECK(r.status == 1);
    CHECK(contains(r.err, "cannot write build/tmp/fh_a_file/log.csv: the folder build/tmp/fh_a_file cannot be made (build/tmp/fh_a_file is a file)"));
    CHECK(!fileExists("build/tmp/fh.png"));  // a bad --log no longer costs the image: nothing is done at all
    r = run({"scenes/cornell.scene", "--spp", "100000", "--out", "build/tmp/fh.png", "--log", "build"});
    CHECK(r.status == 2);  // not a .csv name
    mkdir("build/tmp/fh_folder.png", 0777);
    r = run({"scenes/cornell.scene", "--spp", "100000", "--out", "build/tmp/fh_folder.png"});
    CHECK(r.status == 1);
    CHECK(contains(r.err, "cannot write build/tmp/fh_folder.png: it is a folder"));
    // /proc lets root pass the permission check and refuses the file only when it is made.
    r = run({"scenes/cornell.scene", "--spp", "100000", "--out", "/proc/tmp_fh.png"});
    CHECK(r.status == 1);
    CHECK(contains(r.err, "cannot write /proc/tmp_fh.png: "));
    r = run({"scenes/cornell.scene", "--spp", "100000", "--out", "build/tmp/fh_log.png", "--log", "/dev/null"});
    CHECK(r.status == 2);  // not a .csv name, before anything else
    symlink("/dev/null", "build/tmp/fh_device.csv");
    r = run({"scenes/cornell.scene", "--spp", "100000", "--out", "build/tmp/fh_dev.png", "--log", "build/tmp/fh_device.csv"});
    CHECK(r.status == 1);
    CHECK(contains(r.err, "cannot write build/tmp/fh_device.csv: it is not a regular file"));
    CHECK(r.out.empty());  // no summary line: nothing was rendered
}

// The memory a render needs is estimated before it starts and compared with what the process may
// use (here a 2 GB `ulimit -v`): 8000x8000 (5.6 GB) is refused at once, with the estimate; a
// small render under the same limit runs.
static std::pair<int, std::string> shellRun(const std::string& command) {
    std::string text;
    FILE* p = popen(("bash -c '" + command + "' 2>&1").c_str(), "r");
    REQUIRE(p);
    char buffer[512];
    for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, p)) > 0;) text.append(buffer, n);
    int status = pclose(p);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text};
}

TEST_CASE("memory is estimated before work: a render beyond the process's limit is refused with the estimate") {
    std::remove("build/tmp/fh_mem.png");  // the small render below makes it, in every run of the suite
    auto [status, text] = shellRun("ulimit -v 2000000; " + bdptProgram() + " scenes/cornell.scene --res 8000x8000 --out build/tmp/fh_mem.png");
    CHECK(status == 1);
    CHECK(contains(text, "this render needs about 5."));
    CHECK(contains(text, "GB for 8000x8000 pixels, more than the 2.05 GB this process may use"));
    CHECK(!fileExists("build/tmp/fh_mem.png"));
    CHECK(!contains(text, "samples per pixel in"));  // refused before any work: no summary line
    auto [small, smallText] = shellRun("ulimit -v 2000000; " + bdptProgram() + " scenes/cornell.scene --res 32x32 --spp 1 --quiet --out build/tmp/fh_mem.png");
    CHECK(small == 0);
    CHECK(fileExists("build/tmp/fh_mem.png"));
    // vcm holds every light vertex of a pass: at 1024x1024 about 2 GB more.
    auto [vcm, vcmText] = shellRun("ulimit -v 2000000; " + bdptProgram() + " scenes/cornell.scene --method vcm --res 1024x1024 --out build/tmp/fh_vcm.png");
    CHECK(vcm == 1);
    CHECK(contains(vcmText, "GB for 1024x1024 pixels"));
}

TEST_CASE("--out takes a .png name only, and no run writes over one of its inputs") {
    Run r = run({"scenes/cornell.scene", "--out", "build/x.jpg"});
    CHECK(r.status == 2);
    CHECK(contains(r.err, "--out must name a .png file (the PFM goes beside it), got 'build/x.jpg'"));
    CHECK(run({"scenes/cornell.scene", "--out", "scenes/cornell.scene"}).status == 2);
    CHECK(run({"scenes/cornell.scene", "--out", "build/x.pfm"}).status == 2);
    // A scene file that happens to end in .png (or .csv) is still not overwritten.
    std::string scene = readFile("scenes/furnace.scene");
    std::string path = writeTempFile("scene.png", scene);
    r = run({path, "--spp", "1", "--res", "8x8", "--out", path});
    CHECK(r.status == 1);
    CHECK(contains(r.err, "will not write " + path + ": it is an input of this run"));
    CHECK(readFile(path) == scene);
    std::string csv = writeTempFile("scene.csv", scene);
    r = run({csv, "--spp", "1", "--res", "8x8", "--out", "build/tmp/fh2.png", "--log", csv});
    CHECK(r.status == 1);
    CHECK(readFile(csv) == scene);
    CHECK(run({"scenes/furnace.scene", "--spp", "1", "--res", "8x8", "--quiet", "--out", "build/tmp/fh2.PNG"}).status == 0);
}

TEST_CASE("--out's, --log's and --strategies' folders are made alike, with their parents, by both programs") {
    std::system("rm -rf build/tmp/fh_strategies");
    Run r = run({"scenes/cornell.scene", "--res", "8x8", "--spp", "1", "--strategy-length", "2", "--strategies",
                 "build/tmp/fh_strategies/a/b", "--out", "build/tmp/fh3.png", "--quiet"});
    CHECK(r.status == 0);
    CHECK(fileExists("build/tmp/fh_strategies/a/b/pyramid-weighted.png"));
    CHECK(fileExists("build/tmp/fh_strategies/a/b/s1_t2_unweighted.pfm"));
    std::ofstream("build/tmp/fh_file") << "x";
    r = run({"scenes/cornell.scene", "--res", "8x8", "--spp", "1", "--strategies", "build/tmp/fh_file/sub", "--out", "build/tmp/fh3.png"});
    CHECK(r.status == 1);
    CHECK(contains(r.err, "cannot write into build/tmp/fh_file/sub: the folder cannot be made (build/tmp/fh_file is a file)"));
    // --out and --log into missing folders, in ./bdpt and in the lecture's program alike.
    std::system("rm -rf build/tmp/fh_made");
    r = run({"scenes/cornell.scene", "--res", "8x8", "--spp", "1", "--log", "build/tmp/fh_made/log/a.csv", "--out", "build/tmp/fh_made/out/a.png", "--quiet"});
    CHECK(r.status == 0);
    CHECK(fileExists("build/tmp/fh_made/out/a.png"));
    CHECK(fileExists("build/tmp/fh_made/log/a.csv"));
    CHECK(std::system("build/bdpt-lecture scenes/cornell.scene --res 8x8 --spp 1 --quiet --strategy-length 2 --strategies build/tmp/fh_made/lean/s "
                      "--out build/tmp/fh_made/lean/out/a.png") == 0);
    CHECK(fileExists("build/tmp/fh_made/lean/out/a.pfm"));
    CHECK(fileExists("build/tmp/fh_made/lean/s/s1_t2_weighted.pfm"));
}

TEST_CASE("options that the method would ignore are refused, naming the method they belong to") {
    struct Case { std::vector<std::string> args; std::string message; };
    for (const Case& c : std::vector<Case>{
             {{"--method", "pt", "--heuristic", "max"}, "--heuristic applies to --method bdpt, vcm, mlt, pssmlt and mmlt, not to --method pt"},
             {{"--radius", "0.1"}, "--radius applies to --method vcm, not to --method bdpt"},
             {{"--method", "vcm", "--alpha", "0"}, "option --alpha needs a number from 0.001 to 1, got '0'"},
             {{"--mis"}, "--mis applies to --method nee, not to --method bdpt"},
             {{"--method", "nee", "--clamp", "1"}, "--clamp applies to --method ir, not to --method nee"},
             {{"--method", "lt", "--vpls", "4"}, "--vpls applies to --method ir, not to --method lt"},
             {{"--method", "nee", "--roulette", "off"}, "--roulette applies to the methods that trace light paths (lt, ir, bdpt, vcm, mlt, pssmlt, mmlt)"},
             {{"--method", "bdpt", "--chains", "8"}, "--chains applies to --method mlt, pssmlt and mmlt, not to --method bdpt"},
             {{"--method", "vcm", "--fixed-start"}, "--fixed-start applies to --method mlt, pssmlt and mmlt, not to --method vcm"},
             {{"--method", "pssmlt", "--large-step", "1.5"}, "option --large-step needs a number from 0 to 1, got '1.5'"},
             {{"--method", "pt", "--no-adjoint-correction"}, "--no-adjoint-correction applies to the methods that trace light paths"},
             {{"--strategy-length", "3"}, "--strategy-length applies with --strategies DIR"},
             {{"--time", "1", "--spp", "4"}, "--time and --spp both given"},
             {{"--res", "16384x16384"}, "option --res: 16384x16384 is larger than 64 megapixels"},
             {{"--spp", "0"}, "option --spp needs a number from 1 to 1e+08, got '0'"},
         }) {
        std::vector<std::string> args = {"scenes/cornell.scene", "--out", "build/tmp/fh4.png"};
        args.insert(args.end(), c.args.begin(), c.args.end());
        Run r = run(args);
        CAPTURE(c.message);
        CHECK(r.status == 2);
        CHECK(contains(r.err, c.message));
    }
    CHECK(!fileExists("build/tmp/fh4.png"));
}

TEST_CASE("scene files from other editors and systems: a byte-order mark, CR and CRLF line endings") {
    const std::string lines[] = {"camera 0 0 -3  0 0 0  0 1 0  40  8 8", "material m diffuse 0.5 0.5 0.5",
                                 "sphere 0 0 0  1  m emit 1 1 1", "# a comment"};
    for (const std::string& newline : {std::string("\n"), std::string("\r\n"), std::string("\r")})
        for (bool bom : {false, true}) {
            std::string text = bom ? "\xEF\xBB\xBF" : "";
            for (const std::string& l : lines) text += l + newline;
            CAPTURE(int(newline.size()));
            CAPTURE(bom);
            Scene s = parseScene(text, "editors.scene");
            CHECK(s.shapes.size() == 1);
            CHECK(s.camera.width == 8);
        }
    // A mistake on line 3 is still reported on line 3 with CRLF endings.
    try {
        parseScene("camera 0 0 -3  0 0 0  0 1 0  40  8 8\r\nmaterial m diffuse 0.5 0.5 0.5\r\ncube 1\r\n", "crlf.scene");
        CHECK(false);
    } catch (const InputError& e) {
        CHECK(std::string(e.what()) == "crlf.scene:3: unknown directive 'cube' (camera, material, sphere, quad, pointlight, exposure)");
    }
}

TEST_CASE("a missing, empty or folder scene file: the real problem, not 'no camera'") {
    CHECK(run({"build/no-such.scene"}).err == "build/no-such.scene: cannot open the scene file: No such file or directory\n");
    std::string empty = writeTempFile("empty.scene", " \n\n");
    CHECK(contains(run({empty}).err, empty + ": the file is empty"));
    CHECK(run({"scenes"}).err == "scenes: is a folder, not a scene file\n");
    CHECK(run({"scenes"}).status == 2);
}

TEST_CASE("warnings before the work: one light takes nearly all of the choice; a lamp facing the wrong way; nothing the camera sees is lit") {
    // A huge dim sky sphere and a small lamp: by power the sky takes 99.99% of the light choice.
    std::string sky = writeTempFile("sky.scene", "camera 0 1 -4  0 1 0  0 1 0  50  16 16\nmaterial m diffuse 0.5 0.5 0.5\n"
                                                 "quad -2 0 -2  4 0 0  0 0 4  m\n"
                                                 "sphere 0 0 0  1000  m emit 0.05 0.05 0.05 inside\n"
                                                 "quad -0.1 2 -0.1  0 0 0.2  0.2 0 0  m emit 5 5 5\n");
    Run r = run({sky, "--spp", "1", "--out", "build/tmp/fh5.png", "--quiet"});
    CHECK(r.status == 0);
    CHECK(contains(r.err, sky + ":4: warning: this light takes 99.9"));
    // A lamp above an open floor whose front (u x v) faces up, into the empty sky: nothing is lit.
    std::string away = writeTempFile("away.scene", "camera 0 1 -4  0 0 0  0 1 0  50  16 16\nmaterial m diffuse 0.5 0.5 0.5\n"
                                                   "quad -2 0 -2  4 0 0  0 0 4  m\n"
                                                   "quad -0.1 2 -0.1  0 0 0.2  0.2 0 0  m emit 5 5 5\n");
    r = run({away, "--spp", "1", "--out", "build/tmp/fh5.png", "--quiet"});
    CHECK(r.status == 0);
    CHECK(contains(r.err, away + ": warning: a quick preview"));
    CHECK(contains(r.err, "sees no light at all"));
    // The box of the furnace and the Cornell box raise neither.
    CHECK(run({"scenes/cornell.scene", "--res", "8x8", "--spp", "1", "--out", "build/tmp/fh5.png", "--quiet"}).err.empty());
    // The Cornell box's lamp with u and v swapped faces the ceiling 0.1 mm above it: the room
    // renders almost black (mean 0.0007 against 0.12), and the warning names the line and the fix.
    std::string cornell = readFile("scenes/cornell.scene"), lamp = "quad 343 548.7 227   0 0 105   -130 0 0   lamp";
    REQUIRE(cornell.find(lamp) != std::string::npos);
    std::string swapped = writeTempFile("swapped.scene", cornell.replace(cornell.find(lamp), lamp.size(),
                                                                         "quad 343 548.7 227   -130 0 0   0 0 105   lamp"));
    r = run({swapped, "--res", "16x16", "--spp", "4", "--out", "build/tmp/fh5.png", "--quiet"});
    CHECK(r.status == 0);
    CHECK(contains(r.err, swapped + ":19: warning: this light's emitting side (u x v for a quad) faces a surface 0.0999 away: 0% of "
                          "its light gets farther, 7"));
    CHECK(contains(r.err, "swap its u and v"));
    // A lamp 0.5 mm above a floor, with nothing around it (tests/thin-gap.scene), is meant so.
    CHECK(run({"tests/thin-gap.scene", "--res", "8x8", "--spp", "1", "--out", "build/tmp/fh5.png", "--quiet"}).err.empty());
}

TEST_CASE("a scene sets the PNG's default exposure (the furnace: grey, not white); --exposure overrides it") {
    CHECK(loadScene("scenes/furnace.scene").exposure == -2);
    for (bool override : {false, true}) {
        std::vector<std::string> args = {"scenes/furnace.scene", "--res", "8x8", "--spp", "4", "--quiet", "--out", "build/tmp/fh6.png"};
        if (override) args.insert(args.end(), {"--exposure", "0"});
        REQUIRE(run(args).status == 0);
        Image img;
        REQUIRE(readPFM("build/tmp/fh6.pfm", img));
        REQUIRE(writePNG(img, "build/tmp/fh6-expected.png", override ? 0 : -2));
        CHECK(readFile("build/tmp/fh6.png") == readFile("build/tmp/fh6-expected.png"));
        int grey = toSRGBBytes(img, override ? 0 : -2)[0];  // 2 clips to white; 0.5 (within noise) is sRGB 188
        CHECK(grey >= (override ? 255 : 180));
        CHECK(grey <= (override ? 255 : 196));
    }
    CHECK(contains(run({"scenes/furnace.scene", "--exposure", "99"}).err, "--exposure needs a number from -50 to 50"));
}

TEST_CASE("Ctrl-C is said at once; twice within a second is one press (timeout signals the group)") {
    // `timeout -s INT` sends SIGINT to the process and then to its group: two signals at once.
    // Here the first once a pass is logged (the render is running), the second 0.05 s after the
    // first is answered. (A second press a second or more later abandons the render: test_robustness.)
    for (const char* f : {"build/tmp/fh_int.png", "build/tmp/fh_int.pfm", "build/tmp/fh_int.csv"}) std::remove(f);
    InterruptedRun r = interruptRun({"scenes/cornell.scene", "--res", "64x64", "--spp", "1000000", "--log", "build/tmp/fh_int.csv", "--out",
                                     "build/tmp/fh_int.png"}, "fh_int", [] { return loggedPasses("build/tmp/fh_int.csv", "cornell,bdpt") >= 1; }, 0.05);
    CHECK(r.readySeen);
    CHECK(r.firstAnswered);  // the second signal came after the first was answered, 0.05 s later: the same press
    CHECK(r.status == 130);
    CHECK(r.err.find("bdpt: interrupted: finishing the pass in flight, then writing the image (Ctrl-C again to abandon it)") != std::string::npos);
    CHECK(fileExists("build/tmp/fh_int.png"));
    CHECK(fileExists("build/tmp/fh_int.pfm"));
}

TEST_CASE("--live: the PNG is rewritten whole while rendering, and the log grows pass by pass") {
    // Killed (SIGKILL: nothing of bdpt runs after it) part-way through a long render, once its log
    // holds 10 passes: without --live there would be no PNG; with it the last one written is
    // there, whole (PNG signature first, IEND chunk last), and the log holds the passes so far.
    for (const char* f : {"build/tmp/fh_live.png", "build/tmp/fh_live.pfm", "build/tmp/fh_live.csv"}) std::remove(f);
    BackgroundRun run = startInBackground(bdptProgram() + " scenes/cornell.scene --res 96x96 --spp 1000000 --live 0.2 --threads 1 "
                                          "--log build/tmp/fh_live.csv --out build/tmp/fh_live.png", "build/tmp/fh_live.txt");
    CHECK(waitFor([] { return loggedPasses("build/tmp/fh_live.csv", "cornell,bdpt") >= 10; }));
    CHECK(run.stop(SIGKILL) != 0);  // killed
    std::string png = readFile("build/tmp/fh_live.png");
    REQUIRE(png.size() > 100);
    CHECK(png.substr(1, 3) == "PNG");
    CHECK(png.substr(png.size() - 8, 4) == "IEND");
    CHECK(!fileExists("build/tmp/fh_live.pfm"));  // the PFM is the finished image's only
    CHECK(loggedPasses("build/tmp/fh_live.csv", "cornell,bdpt") >= 10);
}

// A typo gets the word it probably meant; a file the project ships is not lost to a careless
// --out; --ref says the final error without --log; a long render's ETA reads in hours.
TEST_CASE("did you mean: a misspelt option, material or scene path gets the likely one") {
    CHECK(contains(run({"scenes/furnace.scene", "--samples", "4"}).err, "unknown option '--samples' (did you mean --spp?)"));
    CHECK(contains(run({"scenes/furnace.scene", "--heuristc", "max"}).err, "unknown option '--heuristc' (did you mean --heuristic?)"));
    CHECK(contains(run({"scenes/furnace.scene", "--method", "bpdt"}).err, "unknown method 'bpdt' (did you mean bdpt? pt, nee, lt, ir, bdpt"));
    CHECK(contains(run({"scenes/furnace.scene", "--method", "magic"}).err, "unknown method 'magic' (pt, nee, lt, ir, bdpt, vcm"));
    CHECK(run({"scenes/furnace.scene", "--zzzzzz"}).err == "bdpt: unknown option '--zzzzzz' (see --help)\n");  // nothing close: no guess
    Run r = run({"furnace.scene", "--spp", "1"});
    CHECK(r.status == 2);
    CHECK(contains(r.err, "furnace.scene: cannot open the scene file: No such file or directory (did you mean scenes/furnace.scene?)"));
    std::string scene = writeTempFile("typo.scene", "camera 0 1 -4 0 1 0 0 1 0 40 8 8\nmaterial white diffuse 0.5 0.5 0.5\n"
                                                     "quad 0 0 0 1 0 0 0 0 1 whte emit 1 1 1\n");
    CHECK(run({scene}).err == scene + ":3: unknown material 'whte' (did you mean 'white'?)\n");
    // Two edits away (two letters dropped, a transposition), and capitals: still found.
    CHECK(contains(run({"scenes/furnace.scene", "--heurstc", "max"}).err, "unknown option '--heurstc' (did you mean --heuristic?)"));
    CHECK(contains(run({"scenes/furnace.scene", "--bootsrtap", "9"}).err, "unknown option '--bootsrtap' (did you mean --bootstrap?)"));
    CHECK(contains(run({"scenes/furnace.scene", "--method", "BDPT"}).err, "unknown method 'BDPT' (did you mean bdpt?"));
    CHECK(contains(run({"scenes/furnace.scene", "--Spp", "4"}).err, "unknown option '--Spp' (did you mean --spp?)"));
    // The limit, from both sides: two edits away a word of 8 letters is found, three are too many.
    CHECK(contains(run({"scenes/furnace.scene", "--sppxy", "4"}).err, "unknown option '--sppxy' (did you mean --spp?)"));
    CHECK(run({"scenes/furnace.scene", "--sppxyz", "4"}).err == "bdpt: unknown option '--sppxyz' (see --help)\n");
    // Equally close to two: both named, not whichever comes first in the table.
    CHECK(contains(run({"scenes/furnace.scene", "--ree", "4"}).err, "unknown option '--ree' (did you mean --ref or --res?)"));
    std::string tie = writeTempFile("tie.scene", "camera 0 1 -4 0 1 0 0 1 0 40 8 8\nmaterial red diffuse 0.8 0.1 0.1\n"
                                                 "material rod diffuse 0.5 0.5 0.5\nquad 0 0 0 1 0 0 0 0 1 rad emit 1 1 1\n");
    CHECK(run({tie}).err == tie + ":4: unknown material 'rad' (did you mean 'red' or 'rod'?)\n");
    // The lecture's own program: the same guesses, and the classroom's options named as ./bdpt's.
    auto lecture = [](const std::string& options) {
        std::system(("build/bdpt-lecture scenes/furnace.scene " + options + " 2> build/tmp/fh_lecture.err").c_str());
        return readFile("build/tmp/fh_lecture.err");
    };
    CHECK(contains(lecture("--heurstc max"), "unknown option '--heurstc' (did you mean --heuristic?)"));
    CHECK(contains(lecture("--sppxyz 4"), "unknown option '--sppxyz' (see --help)"));
    CHECK(contains(lecture("--ree 4"), "unknown option '--ree' (did you mean --res?)"));  // --ref is ./bdpt's alone
    CHECK(contains(lecture("--side-by-side pt,nee"), "--side-by-side is an option of ./bdpt, the classroom's program"));
    CHECK(contains(lecture("--ref x.pfm"), "--ref is an option of ./bdpt"));  // not "did you mean --res"
}

// The lecture's list of the classroom's options is the classroom's: the rows ./bdpt adds.
TEST_CASE("kClassroomOptions are exactly the options ./bdpt adds to the lecture's") {
    std::set<std::string> lecture, added, listed(std::begin(kClassroomOptions), std::end(kClassroomOptions));
    for (const OptionRow<CommandLine>& o : kOptions)
        if (o.name) lecture.insert(o.name);
    for (const OptionRow<ClassroomLine>& o : classroomTable())
        if (o.name && !lecture.count(o.name)) added.insert(o.name);
    CHECK(added.size() >= 10);
    CHECK(added == listed);
}

TEST_CASE("--out replaces a file the project ships (under scenes/ or lecture_notes/) only with --overwrite") {
    mkdir("build/tmp/scenes", 0777);
    std::string shipped = writeTempFile("scenes/shipped.png", "a committed figure");
    Run r = run({"scenes/furnace.scene", "--res", "8x8", "--spp", "1", "--out", shipped});
    CHECK(r.status == 1);
    CHECK(contains(r.err, "will not overwrite build/tmp/scenes/shipped.png: the project ships it"));
    CHECK(readFile(shipped) == "a committed figure");
    CHECK(run({"--average", "scenes/refs/furnace.pfm", "scenes/refs/furnace.pfm", "--out", shipped}).status == 1);
    CHECK(readFile(shipped) == "a committed figure");
    CHECK(run({"scenes/furnace.scene", "--res", "8x8", "--spp", "1", "--out", shipped, "--overwrite"}).status == 0);
    CHECK(readFile(shipped) != "a committed figure");
    CHECK(run({"scenes/furnace.scene", "--res", "8x8", "--spp", "1", "--out", "build/tmp/fresh.png"}).status == 0);  // elsewhere: as always
}

TEST_CASE("--ref without --log: the summary says the final error; ETAs in hours and minutes") {
    Image ref;
    REQUIRE(readPFM("scenes/refs/furnace.pfm", ref));
    std::string size = std::to_string(ref.width) + "x" + std::to_string(ref.height);
    Run r = run({"scenes/furnace.scene", "--res", size, "--spp", "2", "--ref", "scenes/refs/furnace.pfm", "--out", "build/tmp/ref.png"});
    CHECK(r.status == 0);
    CHECK(contains(r.out, "against scenes/refs/furnace.pfm: rmse "));
    CHECK(contains(r.out, "bias "));
    CHECK(duration(48028.9) == "13 h 20 min");  // not a timing threshold: how seconds are written, nothing timed
    CHECK(duration(245) == "4 min 05 s");       // not a timing threshold: as above
    CHECK(duration(12.34) == "12.3 s");         // not a timing threshold: as above
}

// A projector's viewer opens the file as soon as the command starts: mlt's bootstrap (10 million
// samples here, a long while) must not leave it showing an older run's image or nothing at all.
// Each run is watched until the PNG is a picture, and killed then: its log has no pass yet.
TEST_CASE("--live writes a first frame at once, before mlt's bootstrap ends") {
    writeTempFile("fh_first.png", "an older run's image");
    std::remove("build/tmp/fh_first.csv");
    BackgroundRun run = startInBackground(bdptProgram() + " scenes/door.scene --method mlt --bootstrap 10000000 --res 64x48 --time 600 --live 1 "
                                          "--threads 1 --log build/tmp/fh_first.csv --out build/tmp/fh_first.png", "build/tmp/fh_first.txt");
    int w = 0, h = 0, channels = 0;
    CHECK(waitFor([&] { return stbi_info("build/tmp/fh_first.png", &w, &h, &channels) == 1; }));
    CHECK(loggedPasses("build/tmp/fh_first.csv", "door,mlt") == 0);  // still in the bootstrap
    CHECK(run.stop(SIGKILL) != 0);
    CHECK(w == 64);
    CHECK(h == 48);
    // Side by side too: the labelled frame of every panel at once, mlt's saying it is starting.
    writeTempFile("fh_first_sbs.png", "an older run's image");
    BackgroundRun sbs = startInBackground(bdptProgram() + " scenes/door.scene --side-by-side \"bdpt,mlt --bootstrap 10000000\" --res 64x48 --time 600 "
                                          "--live 1 --threads 1 --out build/tmp/fh_first_sbs.png", "build/tmp/fh_first_sbs.txt");
    CHECK(waitFor([&] { return stbi_info("build/tmp/fh_first_sbs.png", &w, &h, &channels) == 1; }));
    CHECK(sbs.running());  // the first frame came long before the end of mlt's bootstrap
    CHECK(sbs.stop(SIGKILL) != 0);
    CHECK(w >= 1280);
}

// --side-by-side renders each method as it would alone: at equal samples every panel's PFM is the
// method's own image bit for bit (the image does not depend on the threads a panel gets), the
// labelled PNG is projector-sized, and an entry's mistake is named with the entry.
TEST_CASE("--side-by-side: each panel is the method's own render, the image at least 1280 wide, errors name the entry") {
    Run r = run({"scenes/cornell-glass.scene", "--res", "48x40", "--spp", "3", "--side-by-side", "nee --mis, ir --clamp 1e-3,bdpt",
                 "--ref", "build/tmp/fh_sbs_ref.pfm", "--out", "build/tmp/fh_sbs.png"});
    CHECK(r.status == 2);  // the reference does not exist yet: checked before rendering
    CHECK(run({"scenes/cornell-glass.scene", "--res", "48x40", "--spp", "64", "--method", "pt", "--quiet", "--out", "build/tmp/fh_sbs_ref.png"})
              .status == 0);
    std::rename("build/tmp/fh_sbs_ref.pfm", "build/tmp/fh_sbs_reference.pfm");
    r = run({"scenes/cornell-glass.scene", "--res", "48x40", "--spp", "3", "--side-by-side", "nee --mis, ir --clamp 1e-3,bdpt",
             "--ref", "build/tmp/fh_sbs_reference.pfm", "--out", "build/tmp/fh_sbs.png"});
    REQUIRE(r.status == 0);
    CHECK(contains(r.out, "2. ir --clamp 1e-3: 3 samples per pixel"));
    CHECK(contains(r.out, "rmse "));
    const char* alone[3][2] = {{"nee", "--mis"}, {"ir", "--clamp"}, {"bdpt", nullptr}};
    for (int i = 0; i < 3; ++i) {
        std::vector<std::string> args = {"scenes/cornell-glass.scene", "--res", "48x40", "--spp", "3", "--quiet", "--threads", "2",
                                         "--method", alone[i][0], "--out", "build/tmp/fh_sbs_alone.png"};
        if (alone[i][1]) args.push_back(alone[i][1]);
        if (i == 1) args.push_back("1e-3");
        REQUIRE(run(args).status == 0);
        CAPTURE(i);
        CHECK(readFile("build/tmp/fh_sbs-" + std::to_string(i + 1) + "-" + alone[i][0] + ".pfm") == readFile("build/tmp/fh_sbs_alone.pfm"));
    }
    // An entry's deliberate mistake is its own: lt and lt without the adjoint differ where the
    // shading normals are bumped, and each panel is that entry rendered alone.
    REQUIRE(run({"scenes/shading-normals.scene", "--res", "32x32", "--spp", "2", "--side-by-side", "lt,lt --no-adjoint-correction",
                 "--quiet", "--out", "build/tmp/fh_sbs_mistake.png"}).status == 0);
    for (const char* mistake : {"", "--no-adjoint-correction"}) {
        std::vector<std::string> args = {"scenes/shading-normals.scene", "--res", "32x32", "--spp", "2", "--quiet", "--method", "lt",
                                         "--out", "build/tmp/fh_sbs_alone.png"};
        if (*mistake) args.push_back(mistake);
        REQUIRE(run(args).status == 0);
        CAPTURE(mistake);
        CHECK(readFile(std::string("build/tmp/fh_sbs_mistake-") + (*mistake ? "2" : "1") + "-lt.pfm") == readFile("build/tmp/fh_sbs_alone.pfm"));
    }
    CHECK(readFile("build/tmp/fh_sbs_mistake-1-lt.pfm") != readFile("build/tmp/fh_sbs_mistake-2-lt.pfm"));
    int w = 0, h = 0, channels = 0;
    CHECK(stbi_info("build/tmp/fh_sbs.png", &w, &h, &channels) == 1);
    CHECK(w >= 1280);
    CHECK(h >= 600);
    r = run({"scenes/cornell.scene", "--side-by-side", "pt,nee --clamp 1", "--out", "build/tmp/fh_sbs.png"});
    CHECK(r.status == 2);
    CHECK(contains(r.err, "--clamp applies to --method ir, not to --method nee (see --help), in --side-by-side's entry 'nee --clamp 1'"));
    r = run({"scenes/cornell.scene", "--side-by-side", "pt,ir", "--clamp", "1", "--out", "build/tmp/fh_sbs.png"});  // shared, but ir's only
    CHECK(r.status == 2);
    CHECK(contains(r.err, "in --side-by-side's entry 'pt' (an option of some methods only goes in their entries)"));
    r = run({"scenes/cornell.scene", "--side-by-side", "pt,nee", "--method", "bdpt", "--out", "build/tmp/fh_sbs.png"});
    CHECK(r.status == 2);
    CHECK(contains(r.err, "--method does not go with --side-by-side: name the methods in its list"));
    CHECK(run({"scenes/cornell.scene", "--side-by-side", "pt", "--out", "build/tmp/fh_sbs.png"}).status == 2);
}

// --time in a side by side is CPU time: each panel renders on one thread until that thread's
// clock says T, however many panels share the cores. The process's CPU time (getrusage, the
// kernel's count, not the program's) is then about panels x T; stopped by the wall clock instead,
// more panels than cores would share them and use about cores x T.
TEST_CASE("--side-by-side --time T gives every panel T seconds of CPU time") {
    const int cores = int(std::max(1u, std::thread::hardware_concurrency())), panels = std::min(8, cores + 1);
    std::string entries = "pt";
    for (int i = 1; i < panels; ++i) entries += i % 2 ? ",nee" : ",pt";
    auto cpuNow = [] { return cpuSeconds(RUSAGE_SELF); };
    const double T = 0.3, before = cpuNow();
    Run r = run({"scenes/cornell.scene", "--res", "32x32", "--side-by-side", entries, "--time", "0.3", "--out", "build/tmp/fh_cpu.png"});
    const double cpuUsed = cpuNow() - before;
    REQUIRE(r.status == 0);
    MESSAGE(panels << " panels at --time 0.3: " << cpuUsed << " CPU s in all");
    // not a timing threshold: the budget each panel was given, T, against the CPU the kernel counted;
    // a busy machine stretches the wall clock, not the CPU seconds a budget spends
    CHECK(cpuUsed > 0.9 * panels * T);
    CHECK(cpuUsed < 1.3 * panels * T + 0.2);  // not a timing threshold: the budget again, and a pass's overshoot
    CHECK(contains(r.out, "CPU s on 1 thread"));
    // Fewer panels than cores (8 given, 2 panels): still one thread each, each with T of CPU.
    const double before2 = cpuNow();
    r = run({"scenes/cornell.scene", "--res", "32x32", "--side-by-side", "pt,nee", "--threads", "8", "--time", "0.3", "--out", "build/tmp/fh_cpu2.png"});
    const double cpuUsed2 = cpuNow() - before2;
    REQUIRE(r.status == 0);
    CHECK(contains(r.out, "1. pt: "));
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') >= 2);
    size_t onOne = 0;
    for (size_t at = 0; (at = r.out.find(" CPU s on 1 thread,", at)) != std::string::npos; ++at) ++onOne;
    CHECK(onOne == 2);
    CHECK(cpuUsed2 > 0.9 * 2 * T);        // not a timing threshold: the budget, as above
    CHECK(cpuUsed2 < 1.3 * 2 * T + 0.2);  // not a timing threshold: the budget, as above
}

// --time is CPU time everywhere: a render on two threads at --time T spends T CPU seconds in all
// (the kernel's count, getrusage), not T on each thread as a wall-clock budget on an idle 2-core
// machine would; --wall-time T is the wall clock's. Both print which clock they mean.
TEST_CASE("--time T: T CPU seconds for a render on two threads; --wall-time names the wall clock") {
    auto cpuNow = [] { return cpuSeconds(RUSAGE_SELF); };
    const double before = cpuNow();
    Run r = run({"scenes/cornell.scene", "--res", "48x48", "--threads", "2", "--time", "0.6", "--out", "build/tmp/fh_time.png"});
    const double cpuUsed = cpuNow() - before;
    REQUIRE(r.status == 0);
    MESSAGE("--time 0.6 on 2 threads: " << cpuUsed << " CPU s");
    CHECK(cpuUsed > 0.55);  // not a timing threshold: the budget, 0.6 CPU s, against the kernel's count
    CHECK(cpuUsed < 0.85);  // not a timing threshold: the budget and a pass's overshoot; a wall budget on 2 idle cores would spend 1.2
    const size_t at = r.out.find(" s (");
    REQUIRE(at != std::string::npos);
    CHECK(std::atof(r.out.c_str() + at + 4) >= 0.6);  // not a timing threshold: "... in W s (C CPU s)", C reached the budget T
    CHECK(contains(r.out, " CPU s), mean "));
    CHECK(contains(run({"scenes/cornell.scene", "--time", "1", "--wall-time", "1"}).err, "--time and --wall-time both given"));
}

// --wall-time T counts the wall clock, not the CPU's: a render held still (SIGSTOP) after its first
// pass while more than T of wall time passes ends as soon as it may run again, after at most the
// pass in flight, having spent a small part of T in CPU time; counting CPU seconds it would run on
// until it had spent all of T. The sleep makes the condition (wall time passing while the render
// cannot run), it measures nothing; a busy machine only lengthens the wall time more.
TEST_CASE("--wall-time T ends at T seconds of the wall clock, whatever CPU time they held") {
    for (const char* f : {"build/tmp/fh_wall.png", "build/tmp/fh_wall.pfm", "build/tmp/fh_wall.csv"}) std::remove(f);
    const double childrenBefore = cpuSeconds(RUSAGE_CHILDREN);
    BackgroundRun r = startInBackground(bdptProgram() + " scenes/cornell.scene --res 16x16 --threads 1 --wall-time 1 --log build/tmp/fh_wall.csv "
                                        "--out build/tmp/fh_wall.png", "build/tmp/fh_wall.txt");
    REQUIRE(waitFor([] { return loggedPasses("build/tmp/fh_wall.csv", "cornell,bdpt") >= 1; }));
    kill(r.pid, SIGSTOP);
    usleep(1500000);
    kill(r.pid, SIGCONT);
    REQUIRE(r.wait() == 0);
    const double cpuUsed = cpuSeconds(RUSAGE_CHILDREN) - childrenBefore;
    const std::string out = r.output();
    MESSAGE(out);
    const size_t at = out.find(" samples per pixel in ");
    REQUIRE(at != std::string::npos);
    const double wall = std::atof(out.c_str() + at + 22);
    CHECK(wall >= 1);        // not a timing threshold: the budget, 1 s of the wall clock, reached
    CHECK(cpuUsed < 0.5);    // not a timing threshold: the budget, 1 s, of which CPU seconds would have spent all
}

// The progress bar as a terminal shows it (it is drawn only on one: the program runs on a pseudo-
// terminal here). Its percentage is the budget's clock: --time counts CPU seconds, --wall-time the
// wall clock's. A render held still (SIGSTOP) for half its budget shows, once it runs again, the
// same percentage as before under --time (no CPU was spent) and half the bar more under
// --wall-time. The hold makes the condition; the bar's own frames are what is read.
struct TerminalRun {
    pid_t pid = -1;
    int fd = -1;
    std::string screen;  // everything the program wrote to its terminal
    // Reads what the program writes for `seconds` (a hold's length; it ends early if it exits).
    void readFor(double seconds) {
        for (double waited = 0; waited < seconds; waited += 0.05) {
            pollfd p{fd, POLLIN, 0};
            if (poll(&p, 1, 50) > 0) {
                char b[4096];
                ssize_t n = read(fd, b, sizeof b);
                if (n <= 0) return;
                screen.append(b, size_t(n));
            }
        }
    }
    int lastPercent() const {  // the newest frame's "NN%" ("[####....]  NN%  pass P  ETA ...")
        size_t at = screen.rfind("%  pass ");
        if (at == std::string::npos || at < 3) return -1;
        return std::atoi(screen.c_str() + at - 3);
    }
};
inline TerminalRun startInTerminal(const std::string& command) {
    TerminalRun t;
    t.pid = forkpty(&t.fd, nullptr, nullptr, nullptr);
    if (t.pid == 0) {
        execl("/bin/bash", "bash", "-c", ("exec " + command).c_str(), (char*)nullptr);
        _exit(127);
    }
    return t;
}
TEST_CASE("the progress bar on a terminal counts --time's CPU seconds and --wall-time's wall clock") {
    for (const char* budget : {"--time", "--wall-time"}) {
        CAPTURE(budget);
        TerminalRun t = startInTerminal(bdptProgram() + " scenes/cornell.scene --res 48x48 --threads 1 " + budget +
                                        " 6 --out build/tmp/fh_bar.png");
        REQUIRE(t.pid > 0);
        REQUIRE(waitFor([&] { t.readFor(0.1); return t.lastPercent() >= 3; }));
        const int before = t.lastPercent();
        kill(t.pid, SIGSTOP);
        usleep(3000000);  // half the budget
        kill(t.pid, SIGCONT);
        t.screen.clear();
        REQUIRE(waitFor([&] { t.readFor(0.1); return t.lastPercent() >= 0; }));
        t.readFor(0.3);
        const int after = t.lastPercent();
        MESSAGE(std::string(budget) << ": " << before << "% before the hold, " << after << "% after it");
        if (std::string(budget) == "--time") CHECK(after - before < 25);
        else CHECK(after - before >= 40);
        int status = 0;
        kill(t.pid, SIGINT);
        t.readFor(0.2);
        waitpid(t.pid, &status, 0);
        close(t.fd);
    }
}

// A folder that mkdir itself refuses: the reason is the file system's, as `mkdir` prints it
// (/sys refuses new folders even to root; elsewhere, a folder without write permission).
TEST_CASE("an output folder the file system refuses: its own reason, nothing rendered") {
    std::string parent = "build/tmp/fh_locked";
    if (geteuid() == 0) {
        parent = "/sys";
    } else {
        mkdir(parent.c_str(), 0555);
        chmod(parent.c_str(), 0555);
    }
    const std::string folder = parent + "/bdpt-test-folder";
    auto [status, said] = shellRun("mkdir " + folder);
    REQUIRE(status != 0);  // the file system refuses it
    const std::string reason = said.substr(said.rfind(": ") + 2, said.find_last_not_of("\n") - said.rfind(": ") - 1);
    MESSAGE("mkdir says: " << reason);
    Run r = run({"scenes/cornell.scene", "--spp", "100000", "--out", folder + "/x.png"});
    CHECK(r.status == 1);
    CHECK(r.err == "bdpt: cannot write " + folder + "/x.png: the folder " + folder + " cannot be made (" + reason + ") (nothing rendered)\n");
    r = run({"scenes/cornell.scene", "--spp", "100000", "--strategies", folder + "/s", "--out", "build/tmp/fh_locked.png"});
    CHECK(r.status == 1);
    CHECK(contains(r.err, "cannot write into " + folder + "/s: the folder cannot be made (" + reason + ")"));
    if (parent != "/sys") chmod(parent.c_str(), 0755);
}

// The ratio panel as drawn, read back from the PNG: the rightmost tile is found on the canvas's
// middle row (the background is (24,24,24); every pixel of a panel differs from it), its blocks
// (a twelfth of the image across) read at their centres. Blocks: {R, G, B} per block, row by row.
struct DrawnRatioPanel {
    int blocksX = 0, blocksY = 0, block = 0;
    std::vector<std::array<int, 3>> colours;
};
static DrawnRatioPanel drawnRatioPanel(const std::string& png, int W, int H) {
    int cw = 0, ch = 0, n = 0;
    unsigned char* rgb = stbi_load(png.c_str(), &cw, &ch, &n, 3);
    DrawnRatioPanel d;
    if (!rgb) return d;
    auto background = [&](int x, int y) {
        const unsigned char* p = rgb + 3 * (size_t(y) * cw + x);
        return p[0] == 24 && p[1] == 24 && p[2] == 24;
    };
    int y = ch / 2, right = cw - 1;
    while (right > 0 && background(right, y)) --right;
    int left = right;
    while (left > 0 && !background(left - 1, y)) --left;
    const int zoom = (right - left + 1) / W;
    int top = y;
    while (top > 0 && !background(left, top - 1)) --top;
    d.block = std::max(2, std::min(W, H) / 12);
    d.blocksX = (W + d.block - 1) / d.block, d.blocksY = (H + d.block - 1) / d.block;
    for (int by = 0; by < H; by += d.block)
        for (int bx = 0; bx < W; bx += d.block) {
            int cx = left + zoom * (bx + std::min(d.block, W - bx) / 2), cy = top + zoom * (by + std::min(d.block, H - by) / 2);
            const unsigned char* p = rgb + 3 * (size_t(cy) * cw + cx);
            d.colours.push_back({p[0], p[1], p[2]});
        }
    stbi_image_free(rgb);
    return d;
}
// Each block of two PFMs: the sums of their pixels' channels, as the panel compares them.
static std::vector<std::pair<double, double>> blockSums(const std::string& a, const std::string& b, int block) {
    Image A, B;
    std::vector<std::pair<double, double>> sums;
    if (!readPFM(a, A) || !readPFM(b, B)) return sums;
    for (int by = 0; by < A.height; by += block)
        for (int bx = 0; bx < A.width; bx += block) {
            double sa = 0, sb = 0;
            for (int y = by; y < std::min(A.height, by + block); ++y)
                for (int x = bx; x < std::min(A.width, bx + block); ++x)
                    sa += double(A.at(x, y).x) + A.at(x, y).y + A.at(x, y).z, sb += double(B.at(x, y).x) + B.at(x, y).y + B.at(x, y).z;
            sums.push_back({sa, sb});
        }
    return sums;
}

// --ratio-panel mean, by what it shows: a block is red where the second entry is the brighter, blue
// where it is the darker (the sign read from the two panels' own PFMs here), grey where the two
// differ by no more than their noise. The eta^2 mistake is a bias of 1.77 under the water, far
// above 16 passes' noise: most lit blocks are coloured, each the right way. The same method at two
// seeds differs by noise alone: nearly every block is grey. (A mask from one pass's variance, 16
// times the mean's, would grey the eta^2 figure; colours swapped would paint it blue.)
TEST_CASE("--ratio-panel mean: red where the mistake is brighter, grey only within the noise, read from the figure") {
    struct Figure { const char* entries; const char* out; int coloured = 0, grey = 0, wrongSign = 0, lit = 0; };
    Figure figures[] = {{"lt,lt --symmetric-refraction", "build/tmp/fh_rp_eta"}, {"lt,lt --seed 2", "build/tmp/fh_rp_seeds"}};
    for (Figure& f : figures) {
        CAPTURE(std::string(f.entries));
        Run r = run({"scenes/refraction.scene", "--res", "64x48", "--spp", "256", "--side-by-side", f.entries, "--ratio-panel", "mean",
                     "--quiet", "--out", std::string(f.out) + ".png"});
        REQUIRE(r.status == 0);
        DrawnRatioPanel d = drawnRatioPanel(std::string(f.out) + ".png", 64, 48);
        REQUIRE(d.colours.size() == size_t(d.blocksX * d.blocksY));
        auto sums = blockSums(std::string(f.out) + "-1-lt.pfm", std::string(f.out) + "-2-lt.pfm", d.block);
        REQUIRE(sums.size() == d.colours.size());
        for (size_t i = 0; i < sums.size(); ++i) {
            const auto& c = d.colours[i];
            if (!(sums[i].first > 0 && sums[i].second > 0)) continue;
            ++f.lit;
            const bool grey = std::abs(c[0] - c[1]) < 8 && std::abs(c[1] - c[2]) < 8;
            if (grey) { ++f.grey; continue; }
            ++f.coloured;
            const bool red = c[0] > c[2];
            f.wrongSign += red != (sums[i].second > sums[i].first);
        }
        MESSAGE(std::string(f.entries) << ": " << f.lit << " lit blocks, " << f.coloured << " coloured (" << f.wrongSign << " the wrong way), " << f.grey << " grey");
        CHECK(f.lit >= 60);
        CHECK(f.wrongSign == 0);
    }
    CHECK(figures[0].coloured >= figures[0].lit / 2);  // the bias shows
    CHECK(figures[1].grey >= 0.9 * figures[1].lit);    // noise alone does not
}

// The slides' captions of the six panels, as the slide "Results from different techniques" words
// them (../shared/seeds: "a) Unidirectional (eye tracing)" ...), and those of the later methods.
// Each must be drawn under its own image: found in the figure's pixels, right under a panel and
// starting at its left edge, by drawing the expected words the same way and matching them there.
static int captionsFound(const std::string& png, const std::vector<std::string>& captions) {
    int cw = 0, ch = 0, n = 0;
    unsigned char* rgb = stbi_load(png.c_str(), &cw, &ch, &n, 3);
    if (!rgb) return -1;
    auto bg = [&](int x, int y) { const unsigned char* p = rgb + 3 * (size_t(y) * cw + x); return p[0] == 24 && p[1] == 24 && p[2] == 24; };
    // Panels: runs of 64 or more pixels off the background; a panel's bottom-left corner is where
    // such a run starts in a row and not in the row below.
    std::vector<std::pair<int, int>> corners;
    auto runStarts = [&](int y) {
        std::set<int> starts;
        for (int x = 0, run = 0; x < cw; ++x) {
            run = bg(x, y) ? 0 : run + 1;
            if (run == 64) starts.insert(x - 63);
        }
        return starts;
    };
    std::set<int> above = runStarts(0);
    for (int y = 1; y < ch; ++y) {
        std::set<int> here = runStarts(y);
        for (int x : above)
            if (!here.count(x)) corners.push_back({x, y});
        above = here;
    }
    int found = 0;
    for (const std::string& caption : captions) {
        bool seen = false;
        for (int scale = 1; scale <= 6 && !seen; ++scale) {
            // A line of labels is 7 scale pixels high; the words drawn 4 pixels in (a glyph may start left of its pen).
            const int w = labelWidth(caption, scale) + 8, h = 7 * scale;
            std::vector<unsigned char> ink(size_t(w) * h * 3, 24);
            drawLabel(ink, w, h, 4, 0, caption, scale);
            for (const auto& [x0, bottom] : corners)
                for (int y0 = bottom; y0 < bottom + 12 * scale && y0 + h <= ch && !seen; ++y0) {
                    if (x0 < 4 || x0 - 4 + w > cw) break;
                    bool same = true;
                    for (int y = 0; y < h && same; ++y)
                        same = std::memcmp(&ink[3 * size_t(y) * w], rgb + 3 * (size_t(y0 + y) * cw + x0 - 4), 3 * size_t(w)) == 0;
                    seen = same;
                }
        }
        found += seen;
    }
    stbi_image_free(rgb);
    return found;
}

// Whether text is drawn anywhere in the figure, at any of the label scales (a title line).
static bool textFound(const std::string& png, const std::string& text) {
    int cw = 0, ch = 0, n = 0;
    unsigned char* rgb = stbi_load(png.c_str(), &cw, &ch, &n, 3);
    if (!rgb) return false;
    bool seen = false;
    for (int scale = 1; scale <= 8 && !seen; ++scale) {
        const int w = labelWidth(text, scale) + 8, h = 7 * scale;
        std::vector<unsigned char> ink(size_t(w) * h * 3, 24);
        drawLabel(ink, w, h, 4, 0, text, scale);
        for (int y0 = 0; y0 + h <= ch && !seen; ++y0)
            for (int x0 = 0; x0 + w <= cw && !seen; ++x0) {
                bool same = true;
                for (int y = 0; y < h && same; ++y)
                    same = std::memcmp(&ink[3 * size_t(y) * w], rgb + 3 * (size_t(y0 + y) * cw + x0), 3 * size_t(w)) == 0;
                seen = same;
            }
    }
    stbi_image_free(rgb);
    return seen;
}

// The title says what each panel had: an entry's own --spp, not the shared one.
TEST_CASE("--side-by-side's title gives each entry's own samples per pixel, read from the figure") {
    Run r = run({"scenes/cornell.scene", "--res", "16x16", "--side-by-side", "pt --spp 4,nee --spp 8", "--quiet", "--out", "build/tmp/fh_title.png"});
    REQUIRE(r.status == 0);
    CHECK(textFound("build/tmp/fh_title.png", "cornell (16x16): 4, 8 samples per pixel"));
    CHECK(!textFound("build/tmp/fh_title.png", "cornell (16x16): 16 samples per pixel each"));  // the default --spp: none had it
    r = run({"scenes/cornell.scene", "--res", "16x16", "--spp", "16", "--side-by-side", "pt,nee", "--quiet", "--out", "build/tmp/fh_title.png"});
    REQUIRE(r.status == 0);
    CHECK(textFound("build/tmp/fh_title.png", "cornell (16x16): 16 samples per pixel each"));
}

TEST_CASE("--side-by-side: the slides' captions are drawn under their panels, read from the figure") {
    REQUIRE(fontProblem().empty());
    const std::vector<std::string> six = {"(a) Unidirectional (eye tracing)", "(b) Unidirectional + next event", "(c) Next event (light tracing)",
                                          "(d) Instant radiosity", "(e) Instant radiosity (clamped)", "(f) Bidirectional path tracing"};
    Run r = run({"scenes/cornell-glass.scene", "--res", "48x48", "--spp", "1", "--side-by-side", "pt,nee,lt,ir,ir --clamp 1e-5,bdpt", "--quiet",
                 "--out", "build/tmp/fh_captions.png"});
    REQUIRE(r.status == 0);
    CHECK(captionsFound("build/tmp/fh_captions.png", six) == 6);
    CHECK(captionsFound("build/tmp/fh_captions.png", {"(e) Unidirectional (eye tracing)", "(a) Instant radiosity"}) == 0);  // the search bites
    // The later methods are named as the slides name them too, not by a bare method name; nee's
    // MIS variant beside them keeps its entry: one letter (b) would point to a comparison the
    // figure is not (and so would (a) and (f) beside vcm on sds-point).
    const std::vector<std::string> later = {"Vertex Connection and Merging (VCM, later)", "Metropolis-Sampling (see later): Veach's mlt"};
    r = run({"scenes/cornell.scene", "--res", "32x32", "--spp", "1", "--side-by-side", "vcm,mlt --bootstrap 1000,nee --mis", "--quiet",
             "--out", "build/tmp/fh_captions_later.png"});
    REQUIRE(r.status == 0);
    CHECK(captionsFound("build/tmp/fh_captions_later.png", later) == 2);
    CHECK(captionsFound("build/tmp/fh_captions_later.png", {"(b) Unidirectional + next event, with MIS"}) == 0);
    r = run({"scenes/cornell.scene", "--res", "32x32", "--spp", "1", "--side-by-side", "pt,bdpt,vcm", "--quiet", "--out", "build/tmp/fh_captions_vcm.png"});
    REQUIRE(r.status == 0);
    CHECK(captionsFound("build/tmp/fh_captions_vcm.png", {"Vertex Connection and Merging (VCM, later)"}) == 1);
    CHECK(captionsFound("build/tmp/fh_captions_vcm.png", {"(a) Unidirectional (eye tracing)", "(f) Bidirectional path tracing"}) == 0);
    // A figure of two methods is not the slides' comparison: no letter points to a panel it lacks.
    r = run({"scenes/cornell.scene", "--res", "32x32", "--spp", "1", "--side-by-side", "lt,pt", "--quiet", "--out", "build/tmp/fh_captions_two.png"});
    REQUIRE(r.status == 0);
    CHECK(captionsFound("build/tmp/fh_captions_two.png", {"(c) Next event (light tracing)", "(a) Unidirectional (eye tracing)"}) == 0);
}

// --ratio-panel mean: the mistaken entry over the right one. Light tracing through water with the
// refraction rules swapped carries eta^2 = 1.33^2 = 1.769 too much under the water (the scene's
// floor is all under it), the closed form; the reverse division would give 0.565.
TEST_CASE("--ratio-panel: the symmetric-refraction mistake is eta^2 too bright") {
    Run r = run({"scenes/refraction.scene", "--res", "64x48", "--spp", "16", "--side-by-side", "lt,lt --symmetric-refraction",
                 "--ratio-panel", "mean", "--title", "eta^2", "--out", "build/tmp/fh_ratio_panel.png"});
    REQUIRE(r.status == 0);
    const size_t at = r.out.find("ratio panel: 'lt --symmetric-refraction' / 'lt' = ");
    REQUIRE(at != std::string::npos);
    const double ratio = std::atof(r.out.c_str() + r.out.find(" = ", at) + 3);
    CHECK(ratio == doctest::Approx(1.33 * 1.33).epsilon(0.03));
    CHECK(run({"scenes/refraction.scene", "--side-by-side", "lt,pt,nee", "--ratio-panel", "mean", "--out", "build/tmp/fh_rp.png"}).status == 2);
    CHECK(run({"scenes/refraction.scene", "--method", "lt", "--ratio-panel", "mean", "--out", "build/tmp/fh_rp.png"}).status == 2);
    CHECK(run({"scenes/refraction.scene", "--side-by-side", "lt,pt", "--ratio-panel", "error", "--out", "build/tmp/fh_rp.png"}).status == 2);
    int w = 0, h = 0, channels = 0;
    CHECK(stbi_info("build/tmp/fh_ratio_panel.png", &w, &h, &channels) == 1);
    CHECK(w * 9 == h * 16);  // 16:9 for the projector
}

// An entry that names a scene renders that scene: one method on two scenes (the point light
// against the area light), its panel the scene's own render alone.
TEST_CASE("--side-by-side: an entry's own scene") {
    Run r = run({"scenes/cornell.scene", "--res", "40x40", "--spp", "2", "--side-by-side", "nee,nee scenes/cornell-point.scene",
                 "--out", "build/tmp/fh_sbs_scenes.png"});
    REQUIRE(r.status == 0);
    REQUIRE(run({"scenes/cornell-point.scene", "--res", "40x40", "--spp", "2", "--method", "nee", "--threads", "1", "--quiet",
                 "--out", "build/tmp/fh_sbs_point.png"}).status == 0);
    REQUIRE(run({"scenes/cornell.scene", "--res", "40x40", "--spp", "2", "--method", "nee", "--threads", "1", "--quiet",
                 "--out", "build/tmp/fh_sbs_area.png"}).status == 0);
    CHECK(readFile("build/tmp/fh_sbs_scenes-2-nee.pfm") == readFile("build/tmp/fh_sbs_point.pfm"));
    CHECK(readFile("build/tmp/fh_sbs_scenes-1-nee.pfm") == readFile("build/tmp/fh_sbs_area.pfm"));
    CHECK(readFile("build/tmp/fh_sbs_scenes-1-nee.pfm") != readFile("build/tmp/fh_sbs_scenes-2-nee.pfm"));
    // Scenes of different image sizes need one --res; one scene's reference cannot judge another's.
    r = run({"scenes/cornell.scene", "--spp", "1", "--side-by-side", "nee,nee scenes/sds.scene", "--out", "build/tmp/fh_sbs_scenes.png"});
    CHECK(r.status == 2);
    CHECK(contains(r.err, "the scenes' images differ in size (scenes/cornell.scene 256x256, scenes/sds.scene 192x128): give them one with --res WxH"));
    r = run({"scenes/cornell.scene", "--res", "40x40", "--spp", "1", "--side-by-side", "nee,nee scenes/cornell-point.scene", "--ref",
             "build/tmp/fh_sbs_area.pfm", "--out", "build/tmp/fh_sbs_scenes.png"});
    CHECK(r.status == 2);
    CHECK(contains(r.err, "--ref is one scene's reference"));
    r = run({"scenes/cornell.scene", "--side-by-side", "nee,nee scenes/no-such.scene", "--out", "build/tmp/fh_sbs_scenes.png"});
    CHECK(r.status == 2);
    CHECK(contains(r.err, "in --side-by-side's entry 'nee scenes/no-such.scene'"));
}

// A render of millions of pixels says up front how long it will take, before its first pass of
// many seconds (estimated from a 64x64 pass of the same scene and options): the first hour's
// --res 8000x8000 ran twenty minutes without a word. Killed once it has said it, one thread. Its
// numbers are checked against the trial pass it prints, not against a clock: one pass is the
// trial's CPU seconds times the ratio of pixels, the whole render its passes times one pass (an
// estimate off by the number of passes, or by the pixels' ratio, fails).
TEST_CASE("a render of millions of pixels says how long it will take before it starts, and the estimate holds") {
    std::remove("build/tmp/fh_big.png");
    BackgroundRun big = startInBackground(bdptProgram() + " scenes/cornell.scene --res 1500x1500 --spp 4 --threads 1 --out build/tmp/fh_big.png",
                                          "build/tmp/fh_big.txt");
    REQUIRE(waitFor([&] { return big.output().find("passes about ") != std::string::npos; }));
    CHECK(big.stop(SIGKILL) != 0);  // killed in its first pass
    const std::string text = big.output();
    const std::string pass = "bdpt: 1500x1500 pixels: a pass (one sample per pixel) takes about ", passes = "its 4 passes about ",
                      trial = "(from a 64x64 pass of ";
    REQUIRE(text.find(pass) != std::string::npos);
    REQUIRE(text.find(passes) != std::string::npos);
    REQUIRE(text.find(trial) != std::string::npos);
    CHECK(!fileExists("build/tmp/fh_big.png"));
    auto seconds = [&](const std::string& after) {  // "12.3 s", "4 min 05 s" or "1 h 20 min", as duration() writes them
        const char* at = text.c_str() + text.find(after) + after.size();
        double a = 0, b = 0;
        char unit[8] = {0};
        int n = std::sscanf(at, "%lf %7s %lf", &a, unit, &b);
        if (n >= 2 && std::string(unit) == "min") return 60 * a + b;
        if (n >= 2 && std::string(unit) == "h") return 3600 * a + 60 * b;
        return a;
    };
    const double onePass = seconds(pass), fourPasses = seconds(passes), trialPass = seconds(trial);
    MESSAGE("a 64x64 trial pass of " << trialPass << " CPU s: one 1500x1500 pass " << onePass << " s, four " << fourPasses << " s");
    // each figure printed to 3 digits, or to 0.1 s (1 s past a minute)
    const double expected = trialPass * 1500.0 * 1500 / (64 * 64);
    CHECK(std::fabs(onePass - expected) <= 0.005 * expected + (expected < 60 ? 0.05 : 0.5));
    CHECK(std::fabs(fourPasses - 4 * onePass) <= 0.01 * fourPasses + (fourPasses < 60 ? 0.25 : 2.5));
}
