// Robustness: malformed scene files, Ctrl-C, numerical edge cases.
#include "helpers.h"
#include <dirent.h>


// Runs the command line on a bad scene: status 2, exactly the expected message, no file.
static void expectRejected(const std::string& scene, const std::string& expected) {
    const std::string out = "build/tmp/rejected.png";
    std::remove(out.c_str());
    std::ostringstream so, se;
    int status = runCommandLine({scene, "--out", out, "--spp", "1", "--quiet"}, so, se);
    CAPTURE(scene);
    CHECK(status == 2);
    CHECK(se.str() == expected);
    CHECK(!fileExists(out));
    CHECK(!fileExists("build/tmp/rejected.pfm"));
}

TEST_CASE("every file in tests/bad_scenes is rejected with its exact message, status 2 and no output") {
    DIR* dir = opendir("tests/bad_scenes");
    REQUIRE(dir);
    std::vector<std::string> scenes;
    for (dirent* e; (e = readdir(dir));) {
        std::string name = e->d_name;
        if (name.size() > 6 && name.substr(name.size() - 6) == ".scene") scenes.push_back("tests/bad_scenes/" + name);
    }
    closedir(dir);
    CHECK(scenes.size() >= 30);
    for (const std::string& scene : scenes) {
        std::string expected = readFile(scene.substr(0, scene.size() - 6) + ".expected");
        REQUIRE(!expected.empty());
        CHECK(expected.rfind(scene + ":", 0) == 0);  // it starts with file:line
        expectRejected(scene, expected);
    }
}

TEST_CASE("a 1 MB line is rejected like any other") {
    std::string big = "camera 0 1 -5  0 1 0  0 1 0  40  32 32\nmaterial m diffuse 0.5 0.5 0.5\nsphere 0 0 0 1 m";
    while (big.size() < (1 << 20)) big += " emit 1 1 1";
    std::string path = writeTempFile("long-line.scene", big + " 7\n");
    expectRejected(path, path + ":3: unknown option '7' (emit, bump, inside)\n");
}

TEST_CASE("Ctrl-C finishes the pass, writes the completed passes and exits 130; a second press leaves nothing") {
    for (const char* f : {"build/tmp/int.png", "build/tmp/int.pfm", "build/tmp/int.csv"}) std::remove(f);
    InterruptedRun once = interruptRun({"scenes/cornell.scene", "--res", "64x64", "--spp", "1000000", "--threads", "1", "--log", "build/tmp/int.csv",
                                        "--out", "build/tmp/int.png"}, "int", [] { return loggedPasses("build/tmp/int.csv", "cornell,bdpt") >= 1; }, 0);
    CHECK(once.readySeen);      // the render was running (a pass logged) when Ctrl-C came
    CHECK(once.firstAnswered);  // and said so at once
    CHECK(once.status == 130);
    Image img;
    REQUIRE(readPFM("build/tmp/int.pfm", img));
    CHECK(img.width == 64);
    CHECK(imageMean(img) == doctest::Approx(0.123).epsilon(0.1));  // a real image of the completed passes
    CHECK(fileExists("build/tmp/int.png"));
    // A pass of a 2048x2048 image takes about 9 s on the one thread these runs use: the first
    // Ctrl-C once the render has said how long a pass takes (it is about to start one), the second
    // 1.2 s after the first was answered (sooner is the same press), inside the first pass.
    std::remove("build/tmp/int2.png");
    std::remove("build/tmp/int2.pfm");
    InterruptedRun abandoned = interruptRun({"scenes/cornell.scene", "--res", "2048x2048", "--spp", "1000000", "--threads", "1", "--out", "build/tmp/int2.png"},
                                            "int2", [] { return readFile("build/tmp/int2.err").find("a pass (one sample per pixel) takes about") != std::string::npos; }, 1.2);
    CHECK(abandoned.readySeen);
    CHECK(abandoned.firstAnswered);  // the second press came after the first was answered
    CHECK(abandoned.status == kExitAbandoned);
    CHECK(abandoned.err.find("bdpt: abandoned: no image written") != std::string::npos);
    CHECK(!fileExists("build/tmp/int2.png"));
    CHECK(!fileExists("build/tmp/int2.pfm"));
    DIR* dir = opendir("build");
    int temps = 0;
    for (dirent* e; (e = readdir(dir));) temps += std::string(e->d_name).find("tmp_int2.png.tmp") == 0;
    closedir(dir);
    CHECK(temps == 0);
}

TEST_CASE("numerical edge cases render with no NaN or infinity, for every method") {
    for (std::string file : {"tests/edge-camera-inside.scene", "tests/edge-grazing.scene", "tests/edge-scales.scene",
                             "tests/edge-light-touching.scene", "tests/edge-ior-one.scene", "tests/edge-tir.scene",
                             "tests/glass-camera.scene"})
        for (Method m : {Method::PT, Method::NEE, Method::LT, Method::IR, Method::BDPT}) {
            CAPTURE(file);
            CAPTURE(int(m));
            RenderOptions o = quietOptions(m, 8);
            o.mis = true;
            RenderResult r = render(sceneAt(file, 16, 16), o);
            CHECK(r.nonFinite == 0);
            bool finite = true;
            for (const Vec3& p : r.image.pixels) finite = finite && isFinite(p);
            CHECK(finite);
            if (m == Method::BDPT) CHECK(imageMean(r.image) > 0);  // something is lit in each
        }
}

// The Metropolis methods splat a path's colour over its luminance f times a/f. On shading-normals'
// grazing paths f falls to 1e-42, below float's normal range, where 1/f overflows a float: computed
// through a float reciprocal, mlt's splats were infinite (1 to 3 of them in each of these four
// 32x32 renders). mlt on every committed scene, pssmlt and mmlt on shading-normals: not one dropped.
TEST_CASE("mlt gives no non-finite sample on any committed scene, shading-normals' grazing paths included") {
    long long dropped = 0;
    for (int seed = 1; seed <= 4; ++seed) {
        RenderOptions o = quietOptions(Method::MLT, 16, seed);
        o.metropolis.bootstrap = 20000;
        dropped += render(sceneAt("scenes/shading-normals.scene", 32, 32), o).nonFinite;
    }
    CHECK(dropped == 0);
    DIR* dir = opendir("scenes");
    std::vector<std::string> files;
    for (dirent* e; (e = readdir(dir));)
        if (std::string(e->d_name).size() > 6 && std::string(e->d_name).rfind(".scene") == std::string(e->d_name).size() - 6)
            files.push_back(std::string("scenes/") + e->d_name);
    closedir(dir);
    CHECK(files.size() >= 14);
    for (const std::string& file : files)
        for (Method m : {Method::MLT, Method::PSSMLT, Method::MMLT}) {
            if (m != Method::MLT && file != "scenes/shading-normals.scene") continue;  // their splats' weight: the same scaled()
            CAPTURE(file);
            CAPTURE(int(m));
            RenderOptions o = quietOptions(m, 8, 3);
            o.metropolis.bootstrap = 20000;
            RenderResult r = render(sceneAt(file, 32, 32), o);
            CHECK(r.nonFinite == 0);
            bool finite = true;
            for (const Vec3& p : r.image.pixels) finite = finite && isFinite(p);
            CHECK(finite);
        }
}

TEST_CASE("glass of index 1 is invisible: the same image as without it, within noise") {
    Scene with = sceneAt("tests/edge-ior-one.scene", 16, 16);
    std::string text = readFile("tests/edge-ior-one.scene");
    Scene without = parseScene(text.substr(0, text.find("sphere 0 0.6 0")), "without");
    setResolution(without.camera, 16, 16);
    CHECK(maxZ(renderRegions(with, quietOptions(Method::NEE, 256, 1), 2), renderRegions(without, quietOptions(Method::NEE, 256, 2), 2)) < 4.5);
}
