// Speed against accuracy: the metrics on images with known answers, and where each method fails,
// as numbers.
#include "helpers.h"

static Image constantImage(int w, int h, float v) {
    Image img(w, h);
    for (Vec3& p : img.pixels) p = Vec3(v);
    return img;
}

TEST_CASE("metrics on synthetic images with known answers") {
    Image ref = constantImage(10, 10, 1), img = constantImage(10, 10, 1.1f);
    img.at(3, 4) = Vec3(11);  // one firefly: error 10 where the others have 0.1
    ErrorMetrics m = compareToReference(img, ref);
    CHECK(m.rmse == doctest::Approx(std::sqrt((99 * 0.01 + 100) / 100)).epsilon(1e-4));
    CHECK(m.relMse == doctest::Approx((99 * 0.01 + 100) / 1.01 / 100).epsilon(1e-4));
    CHECK(m.bias == doctest::Approx(0.199).epsilon(1e-4));
    CHECK(m.mean == doctest::Approx(1.199).epsilon(1e-4));
    CHECK(m.firefly == doctest::Approx(100).epsilon(1e-3));  // 99.9th percentile 10 over median 0.1
    ErrorMetrics same = compareToReference(ref, ref);
    CHECK(same.rmse == 0);
    CHECK(same.bias == 0);
    Image dark = constantImage(10, 10, 0.5f);
    CHECK(compareToReference(dark, ref).bias == doctest::Approx(-0.5));
    CHECK(compareToReference(dark, ref).relMse == doctest::Approx(0.25 / 1.01).epsilon(1e-4));
    // A lamp pixel (above 5) at (7, 2): it and its 8 neighbours leave rmse_without_lamp.
    Image lampRef = constantImage(10, 10, 1), lampImg = constantImage(10, 10, 1);
    lampRef.at(7, 2) = Vec3(17);
    lampImg.at(7, 2) = Vec3(15);   // error 2 on the lamp
    lampImg.at(8, 3) = Vec3(2);    // error 1 beside it
    lampImg.at(0, 9) = Vec3(1.5f); // error 0.5 far away
    ErrorMetrics lamp = compareToReference(lampImg, lampRef);
    CHECK(lamp.rmse == doctest::Approx(std::sqrt((4 + 1 + 0.25) / 100)).epsilon(1e-5));
    CHECK(lamp.rmseWithoutLamp == doctest::Approx(std::sqrt(0.25 / 91)).epsilon(1e-5));
    CHECK(nearLamp(lampRef, 6, 1));
    CHECK(!nearLamp(lampRef, 5, 2));
}

// A point light is a pixel of light tracing's image that no camera path reaches: the reference
// (bdpt's, scenes/refs/cornell-point.pfm) has the room there. With the scene, lampPixels leaves
// that pixel out, and lt's bias is the transport's: within 5%. Without it, it was +89%.
TEST_CASE("a point light's own pixel is the lamp's: lt on cornell-point agrees with the reference within 5%") {
    Scene scene = sceneAt("scenes/cornell-point.scene", 64, 64);
    Image ref;
    REQUIRE(readPFM("scenes/refs/cornell-point.pfm", ref));
    RenderResult r = render(scene, quietOptions(Method::LT, 16, 3));
    ErrorMetrics with = compareToReference(r.image, ref, &scene), without = compareToReference(r.image, ref);
    MESSAGE("lt on cornell-point: bias " << with.bias << " with the point light's pixel left out, " << without.bias << " without");
    CHECK(std::fabs(with.bias) < 0.05);
    CHECK(without.bias > 0.5);
    CHECK(with.rmseWithoutLamp < 0.1 * without.rmseWithoutLamp);
}

// `bdpt OPTION A.pfm B.pfm --out build/tmp/NAME.png` on two images written for it; the PFM it
// writes is read back into result.
static int twoImageCommand(const std::string& option, const Image& a, const Image& b, const std::string& name, Image& result,
                           std::ostringstream& so) {
    std::string pa = "build/tmp/" + name + "_a.pfm", pb = "build/tmp/" + name + "_b.pfm";
    REQUIRE(writePFM(a, pa));
    REQUIRE(writePFM(b, pb));
    std::ostringstream se;
    int status = runCommandLine({option, pa, pb, "--out", "build/tmp/" + name + ".png"}, so, se);
    if (status == 0) REQUIRE(readPFM("build/tmp/" + name + ".pfm", result));
    return status;
}

TEST_CASE("--average: the mean of two references, and refusal of images of different sizes") {
    Image one = constantImage(6, 4, 1), three = constantImage(6, 4, 3), small = constantImage(4, 4, 1);
    three.at(5, 3) = Vec3(7, 9, 11);  // a corner, to see the rows are not flipped
    REQUIRE(writePFM(small, "build/tmp/avg_small.pfm"));
    std::ostringstream so, se;
    Image mean;
    CHECK(twoImageCommand("--average", one, three, "avg", mean, so) == 0);
    CHECK(mean.width == 6);
    CHECK(mean.at(0, 0).y == 2.0f);
    CHECK(mean.at(5, 3).z == 6.0f);
    CHECK(fileExists("build/tmp/avg.png"));
    CHECK(so.str().find("wrote build/tmp/avg.png and build/tmp/avg.pfm") != std::string::npos);
    CHECK(runCommandLine({"--average", "build/tmp/avg_a.pfm", "build/tmp/avg_small.pfm", "--out", "build/tmp/avg2.png"}, so, se) == 2);
    CHECK(!fileExists("build/tmp/avg2.pfm"));
    // Each refusal names the input and what is wrong with it.
    CHECK(se.str().find("cannot average: build/tmp/avg_a.pfm is 6x4, build/tmp/avg_small.pfm is 4x4") != std::string::npos);
    std::ostringstream se2, se3, se4;
    CHECK(runCommandLine({"--average", "build/tmp/avg_a.pfm", "build/no_such.pfm", "--out", "build/tmp/avg2.png"}, so, se2) == 2);
    CHECK(se2.str().find("build/no_such.pfm does not exist") != std::string::npos);
    CHECK(runCommandLine({"--compare", "build/tmp/avg_a.pfm", "Makefile"}, so, se3) == 2);
    CHECK(se3.str().find("cannot compare: Makefile is not a PFM image") != std::string::npos);
    // Without --out an image-writing command refuses instead of writing over render.png.
    CHECK(runCommandLine({"--ratio", "build/tmp/avg_a.pfm", "build/tmp/avg_b.pfm"}, so, se4) == 2);
    CHECK(se4.str().find("--ratio writes an image: name it with --out FILE.png") != std::string::npos);
}

TEST_CASE("--ratio: A/B over 4x4 blocks, in false colour, with its percentiles") {
    Image b = constantImage(8, 8, 1), a = constantImage(8, 8, 1);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) a.at(x, y) = Vec3(2);  // rows 0-3 twice as bright
    a.at(0, 7) = Vec3(1 + 16);                               // one noisy pixel: its block's mean 2
    for (int y = 4; y < 8; ++y) b.at(7, y) = a.at(7, y) = Vec3(0);  // an undefined column
    std::ostringstream so;
    Image r;
    CHECK(twoImageCommand("--ratio", a, b, "ratio", r, so) == 0);
    CHECK(r.at(1, 1).x == doctest::Approx(2.0));
    CHECK(r.at(6, 2).x == doctest::Approx(2.0));
    CHECK(r.at(3, 5).x == doctest::Approx(2.0));   // the noisy pixel's block: (15 + 17) / 16
    CHECK(r.at(5, 5).x == doctest::Approx(1.0));   // 12 / 12: the black column is left out of both
    Image colours = ratioColours(blockRatio(a, b, 4));
    CHECK(colours.at(0, 0).x == 1.0f);
    CHECK(colours.at(0, 0).y == 0.0f);             // one stop brighter: full red
    CHECK(colours.at(5, 5).y == 1.0f);             // equal: white
    CHECK(so.str().find("% of the blocks more than half a stop apart") != std::string::npos);
    CHECK(so.str().find("wrote build/tmp/ratio.png and build/tmp/ratio.pfm") != std::string::npos);
    // Against an all-black image every block is undefined: said so, not "0% apart".
    std::ostringstream so2;
    Image unused;
    CHECK(twoImageCommand("--ratio", a, constantImage(8, 8, 0), "ratio_black", unused, so2) == 2);
    CHECK(!fileExists("build/tmp/ratio_black.png"));
}

// The PNG of --ratio is a figure: enlarged to at least 560 across, the division and the ratio of
// means written above it, and a key from blue (1/2) through white (1) to red (2).
TEST_CASE("--ratio's figure: enlarged, labelled, its colour key running from blue to red") {
    Image b = constantImage(16, 8, 1), a = constantImage(16, 8, 2);  // A twice as bright: all red
    std::ostringstream so;
    Image r;
    REQUIRE(twoImageCommand("--ratio", a, b, "ratio_figure", r, so) == 0);
    int w = 0, h = 0, channels = 0;
    unsigned char* png = stbi_load("build/tmp/ratio_figure.png", &w, &h, &channels, 3);
    REQUIRE(png != nullptr);
    CHECK(w >= 560);
    CHECK(w < 2 * 560);
    auto pixel = [&](int x, int y) { return Vec3(png[3 * (y * w + x)], png[3 * (y * w + x) + 1], png[3 * (y * w + x) + 2]); };
    // The key's row: its left end blue, its middle white, its right end red; the map below all red.
    int keyRow = -1;
    for (int y = 0; y < h && keyRow < 0; ++y)
        if (pixel(w / 2, y).x > 250 && pixel(w / 2, y).z > 250 && pixel(w / 20, y).z > 250 && pixel(w / 20, y).x < 80) keyRow = y;
    REQUIRE(keyRow >= 0);
    CHECK(pixel(w - w / 20, keyRow).x > 250);
    CHECK(pixel(w - w / 20, keyRow).z < 80);
    Vec3 bottom = pixel(w / 2, h - h / 20);
    CHECK(bottom.x > 250);
    CHECK(bottom.y < 10);
    // Text above the key: white pixels where the title is, on a dark strip.
    int white = 0;
    for (int y = 0; y < keyRow; ++y)
        for (int x = 0; x < w; ++x) white += pixel(x, y).y == 255 && pixel(x, y).x == 255;
    CHECK(white > 500);
    stbi_image_free(png);
}

TEST_CASE("the failure table: slope of log(rmse) against log(time), last bias, fireflies and NaNs") {
    std::ofstream a("build/tmp/converges.csv"), b("build/tmp/biased.csv");
    a << "scene,method,options,pass,spp,seconds,rmse,relmse,mean,bias,firefly,nan_count\n";
    b << "scene,method,options,pass,spp,seconds,rmse,relmse,mean,bias,firefly,nan_count\n";
    for (int p = 1; p <= 100; ++p) {
        a << "x,nee,,"<< p << "," << p << "," << 0.01 * p << "," << 0.3 / std::sqrt(p) << ",0,1,0.001,7,0\n";
        b << "x,ir,--clamp 1," << p << "," << p << "," << 0.01 * p << ",0.05,0,1,-0.042,3,2\n";
    }
    a.close();
    b.close();
    std::ostringstream out, err;
    CHECK(printFailureTable({"build/tmp/converges.csv", "build/tmp/biased.csv"}, out, err) == 0);
    CHECK(out.str().find("| x | nee | -0.50 | +0.1% | 7 | 0 |") != std::string::npos);
    CHECK(out.str().find("| x | ir --clamp 1 | 0.00 | -4.2% | 3 | 2 |") != std::string::npos);
    CHECK(printFailureTable({"build/no-such.csv"}, out, err) == 2);
    CHECK(err.str().find("warning") == std::string::npos);  // 90 passes in the fit: no warning
    // A run of 5 passes: its slope and bias are marked and said to be noise.
    std::ofstream c("build/tmp/short.csv");
    c << "scene,method,options,pass,spp,seconds,rmse,relmse,mean,bias,firefly,nan_count\n";
    for (int p = 1; p <= 5; ++p) c << "x,mmlt,," << p << "," << p << "," << p << "," << 0.3 / p << ",0,1,0.1,7,0\n";
    c.close();
    std::ostringstream out2, err2;
    CHECK(printFailureTable({"build/tmp/short.csv"}, out2, err2) == 0);
    CHECK(out2.str().find("(few passes)") != std::string::npos);
    CHECK(err2.str().find("build/tmp/short.csv:0: warning: only 5 passes") != std::string::npos);
    // lt on a point light: its own pixel holds the whole image's RMSE flat; the error without the
    // lamp's pixels (the last column) falls as 1/sqrt(N), the slope the table must give.
    std::ofstream d("build/tmp/point.csv");
    d << "scene,method,options,pass,spp,seconds,rmse,relmse,mean,bias,firefly,nan_count,rmse_without_lamp\n";
    for (int p = 1; p <= 100; ++p) d << "x,lt,," << p << "," << p << "," << 0.01 * p << ",9.18,0,1,0.001,7,0," << 0.3 / std::sqrt(p) << "\n";
    d.close();
    std::ostringstream out3, err3;
    CHECK(printFailureTable({"build/tmp/point.csv"}, out3, err3) == 0);
    CHECK(out3.str().find("| x | lt | -0.50 | +0.1% | 7 | 0 |") != std::string::npos);
}

// --profile's split. What its design guarantees, whatever else the machine runs: the parts add up
// to the whole, and a part with no scope in a method's code gets nothing (pt has no MIS weights,
// neither pt nor bdpt merges). Where each part's time goes is checked on a clock preemption cannot
// move, a count: with a clock that advances by one at every reading, tracing is charged once per
// ray, so its ticks are the rays the render counts (a ray function without its scope, or a scope
// around a call that traces none, breaks the equality); bdpt's weights and vcm's merges are charged, pt's and
// bdpt's merges are not. How long each part takes on this machine is make bench's, not a test's.
static uint64_t gCountingClock = 0;
TEST_CASE("--profile splits a sample's time into tracing, MIS, merging and the rest") {
    struct Profile {
        std::map<std::string, double> share;
    };
    auto profile = [](const char* method) {
        std::ostringstream so, se;
        REQUIRE(runCommandLine({"scenes/cornell.scene", "--method", method, "--res", "48x48", "--spp", "8", "--profile", "--out",
                                "build/tmp/profile.png"}, so, se) == 0);
        std::string text = so.str();
        size_t at = text.find("profile (one thread): ");
        REQUIRE(at != std::string::npos);
        Profile p;
        double total = std::atof(text.c_str() + at + 22), sum = 0;
        for (const char* part : {"tracing", "MIS", "merging", "shading and sampling"}) {
            size_t q = text.find(std::string(part) + " ", at);
            REQUIRE(q != std::string::npos);
            double value = std::atof(text.c_str() + q + std::strlen(part) + 1);
            p.share[part] = value / total;
            sum += value;
        }
        CHECK(sum == doctest::Approx(total).epsilon(0.02));
        return p;
    };
    SUBCASE("the real clock: the parts add up, and a part a method lacks is 0") {
        Profile pt = profile("pt"), bdpt = profile("bdpt");
        CHECK(pt.share["MIS"] == 0);
        CHECK(pt.share["merging"] == 0);
        CHECK(bdpt.share["merging"] == 0);
    }
    SUBCASE("a counting clock: tracing's ticks are the rays, MIS and merging where they run") {
        // Every reading advances the clock by one, so each switch charges one tick to the part it
        // leaves: tracing gets one per ray traced, exactly; a part never entered gets none.
        gCostClock.now = [] { return ++gCountingClock; };
        Scene scene = sceneAt("scenes/cornell.scene", 24, 24);
        std::map<Method, std::array<uint64_t, int(Cost::Count)>> ticks;
        std::map<Method, long long> rays;
        for (Method m : {Method::PT, Method::BDPT, Method::VCM}) {
            gCostClock.start();
            RenderResult r = render(scene, quietOptions(m, 4));
            gCostClock.switchTo(Cost::Other);
            std::copy(std::begin(gCostClock.ticks), std::end(gCostClock.ticks), ticks[m].begin());
            rays[m] = r.rays.closest + r.rays.shadow;
            MESSAGE(std::string(methodName(m)) << ": " << rays[m] << " rays; ticks: tracing " << ticks[m][int(Cost::Tracing)] << ", MIS "
                                  << ticks[m][int(Cost::Mis)] << ", merging " << ticks[m][int(Cost::Merging)]);
            CHECK(ticks[m][int(Cost::Tracing)] == uint64_t(rays[m]));
        }
        gCostClock = CostClock();
        CHECK(ticks[Method::PT][int(Cost::Mis)] == 0);
        CHECK(ticks[Method::BDPT][int(Cost::Mis)] > 0);
        CHECK(ticks[Method::BDPT][int(Cost::Merging)] == 0);
        CHECK(ticks[Method::VCM][int(Cost::Merging)] > 0);
    }
}

// The error of a render against a reference, after each of several pass counts.
static std::vector<ErrorMetrics> errorsAt(const Scene& scene, RenderOptions o, const Image& ref, const std::vector<int>& passes) {
    std::vector<ErrorMetrics> out;
    std::vector<double> sum(3 * ref.pixels.size(), 0.0);
    o.spp = passes.back();
    renderEachPass(scene, o, [&](const Rendering& r) {
        const std::vector<Vec3>& pass = r.pass;
        const int p = r.result.passes - 1;
        for (size_t i = 0; i < pass.size(); ++i)
            for (int c = 0; c < 3; ++c) sum[3 * i + c] += pass[i][c];
        if (std::find(passes.begin(), passes.end(), p + 1) == passes.end()) return;
        Image mean(ref.width, ref.height);
        for (size_t i = 0; i < mean.pixels.size(); ++i)
            for (int c = 0; c < 3; ++c) mean.pixels[i][c] = float(sum[3 * i + c] / (p + 1));
        out.push_back(compareToReference(mean, ref));
    });
    return out;
}

TEST_CASE("pt on cornell-point is black, and more samples do not help") {
    Scene scene = sceneAt("scenes/cornell-point.scene", 16, 16);
    Image ref = render(scene, quietOptions(Method::NEE, 256, 3)).image;
    std::vector<ErrorMetrics> e = errorsAt(scene, quietOptions(Method::PT, 1, 4), ref, {4, 64});
    CHECK(e[0].mean == 0);
    CHECK(e[1].rmse == e[0].rmse);
    CHECK(e[1].bias == doctest::Approx(-1.0));
}

TEST_CASE("indirect: nee's error falls like N^-1/2 but stays above bdpt's at equal samples") {
    Scene scene = sceneAt("scenes/indirect.scene", 16, 16);
    Image ref = referenceImage("scenes/refs/indirect.pfm", 4);  // lt, 75,000 passes at 64x64
    std::vector<int> passes = {16, 64, 256};
    std::vector<ErrorMetrics> nee = errorsAt(scene, quietOptions(Method::NEE, 1, 6), ref, passes);
    std::vector<ErrorMetrics> bdpt = errorsAt(scene, quietOptions(Method::BDPT, 1, 7), ref, passes);
    double slope = std::log(nee[2].rmse / nee[0].rmse) / std::log(16.0);
    CHECK(slope == doctest::Approx(-0.5).epsilon(0.3));  // -0.35 .. -0.65
    for (size_t i = 0; i < passes.size(); ++i) {
        CAPTURE(passes[i]);
        CHECK(nee[i].rmse > 2 * bdpt[i].rmse);
    }
}

TEST_CASE("ir: the clamp's bias does not shrink with passes; unclamped ir has more fireflies") {
    Scene scene = sceneAt("scenes/cornell.scene", 24, 24);
    Image ref = render(scene, quietOptions(Method::BDPT, 1024, 8)).image;
    RenderOptions clamped = quietOptions(Method::IR, 1, 9), unclamped = clamped;
    clamped.ir.clamp = 1e-5f;
    std::vector<ErrorMetrics> c = errorsAt(scene, clamped, ref, {64, 512});
    std::vector<ErrorMetrics> u = errorsAt(scene, unclamped, ref, {64, 512});
    CHECK(c[0].bias < -0.015);
    CHECK(c[1].bias == doctest::Approx(c[0].bias).epsilon(0.3));  // 8x the passes, the same bias
    CHECK(std::fabs(u[1].bias) < std::fabs(c[1].bias) / 2);
    CHECK(u[0].firefly > 1.5 * c[0].firefly);
}

TEST_CASE("no method produces a NaN or an infinity on any scene") {
    for (const char* file : {"scenes/cornell.scene", "scenes/cornell-point.scene", "scenes/cornell-glass.scene",
                             "scenes/indirect.scene", "scenes/furnace.scene", "scenes/refraction.scene",
                             "scenes/shading-normals.scene", "scenes/sds.scene", "scenes/sds-point.scene"})
        for (Method m : {Method::PT, Method::NEE, Method::LT, Method::IR, Method::BDPT}) {
            CAPTURE(file);
            CAPTURE(int(m));
            RenderResult r = render(sceneAt(file, 16, 16), quietOptions(m, 4));
            CHECK(r.nonFinite == 0);
            bool finite = true;
            for (const Vec3& p : r.image.pixels) finite = finite && isFinite(p);
            CHECK(finite);
        }
}

// A pass during which the render could not run is left out of --profile's split: its wall time
// went to no part of the sample. The render is held still (SIGSTOP) three times while its passes
// run; each hold lies inside a pass (they take all but a sliver of the time), which its thread then
// did not run undisturbed, so the line must say fewer passes were kept than run. The holds make
// the condition; nothing here is measured against a clock.
TEST_CASE("--profile leaves out of its split the passes during which the render was held still") {
    std::remove("build/tmp/profile-held.csv");
    BackgroundRun r = startInBackground(bdptProgram() + " scenes/cornell.scene --res 64x64 --spp 300 --profile --log build/tmp/profile-held.csv "
                                        "--out build/tmp/profile-held.png", "build/tmp/profile-held.txt");
    for (int passes : {2, 40, 80}) {
        REQUIRE(waitFor([passes] { return loggedPasses("build/tmp/profile-held.csv", "cornell,bdpt") >= passes; }));
        kill(r.pid, SIGSTOP);
        usleep(300000);
        kill(r.pid, SIGCONT);
    }
    REQUIRE(r.wait() == 0);
    const std::string out = r.output();
    MESSAGE(out);
    int kept = 0, passes = 0;
    const size_t at = out.find("; split over the ");
    REQUIRE(at != std::string::npos);  // "split over all N passes" would mean a held pass was kept
    REQUIRE(std::sscanf(out.c_str() + at, "; split over the %d of %d passes", &kept, &passes) == 2);
    CHECK(passes == 300);
    CHECK(kept < passes);
}

// The profile clock charges time to the part running: a part that interrupts another (MIS weights
// inside a merge, tracing inside either) hands the clock back to it when it ends. Handed to "the
// rest" instead, the merge's time after the weights would be charged there. The clock is one the
// test advances by hand (spin adds milliseconds), so a busy machine cannot move the shares.
static uint64_t gHandClock = 0;
TEST_CASE("--profile's clock hands an interrupted part's time back to it") {
    auto spin = [](double seconds) { gHandClock += uint64_t(seconds * 1000); };
    gCostClock = CostClock();
    gCostClock.now = [] { return gHandClock; };
    gCostClock.on = true;
    gCostClock.last = gCostClock.now();
    {
        CostScope merging(Cost::Merging);
        spin(0.01);
        {
            CostScope mis(Cost::Mis);
            spin(0.01);
            {
                CostScope tracing(Cost::Tracing);
                spin(0.01);
            }
            spin(0.01);
        }
        spin(0.04);
    }
    gCostClock.switchTo(Cost::Other);
    gCostClock.on = false;
    const uint64_t* t = gCostClock.ticks;
    double total = double(t[int(Cost::Merging)] + t[int(Cost::Mis)] + t[int(Cost::Tracing)] + t[int(Cost::Other)]);
    double merging = t[int(Cost::Merging)] / total, mis = t[int(Cost::Mis)] / total, other = t[int(Cost::Other)] / total;
    MESSAGE("merging " << merging << ", MIS " << mis << ", tracing " << t[int(Cost::Tracing)] / total << ", the rest " << other);
    // 50 of 80 ms exactly; the weights' 20 and tracing's 10 apart. Handed to "the rest" after
    // the weights, the merge would keep 10 (0.125) and the rest get 40.
    CHECK(merging == doctest::Approx(50.0 / 80));
    CHECK(mis == doctest::Approx(20.0 / 80));
    CHECK(t[int(Cost::Tracing)] / total == doctest::Approx(10.0 / 80));
    CHECK(other == 0);    // nothing ran outside the parts
    gCostClock = CostClock();
}

// --ratio's title names the two files; where their names are the same (two folders of strategy
// images) it names their folders too, or the title would read "A / A".
TEST_CASE("--ratio's title tells two files of one name apart by their folders") {
    CHECK(ratioTitle("build/notes/pool-lt.pfm", "build/notes/pool.pfm") == "pool-lt / pool");
    CHECK(ratioTitle("build/bdpt/s4_t1_weighted.pfm", "build/lt/s4_t1_weighted.pfm") == "bdpt/s4_t1_weighted / lt/s4_t1_weighted");
    CHECK(ratioTitle("a.pfm", "a.pfm") == "a / a");
}
