// Core renderer: intersector, BSDF energy, furnace, pt = nee, bad input.
#include "helpers.h"
#include <regex>

TEST_CASE("ray-sphere: outside, inside, miss, and the far side only when the near one is behind") {
    Shape s;
    s.type = Shape::Sphere;
    s.p = Vec3(0, 0, 0);
    s.radius = 1;
    CHECK(intersectSphere(s.p, s.radius, {Vec3(0, 0, -5), Vec3(0, 0, 1), kInf}) == doctest::Approx(4.0f));
    CHECK(intersectSphere(s.p, s.radius, {Vec3(0, 0, 0), Vec3(0, 0, 1), kInf}) == doctest::Approx(1.0f));  // from inside
    CHECK(intersectSphere(s.p, s.radius, {Vec3(0, 1.01f, -5), Vec3(0, 0, 1), kInf}) == kInf);
    CHECK(intersectSphere(s.p, s.radius, {Vec3(0, 0, 5), Vec3(0, 0, 1), kInf}) == kInf);                  // behind
    CHECK(intersectSphere(s.p, s.radius, {Vec3(0, 0, -5), Vec3(0, 0, 1), 3.9f}) == kInf);                 // tmax
    // Far away and small: the precision fix keeps the hit within float rounding of the truth.
    s.p = Vec3(0, 0, 1e4f);
    s.radius = 0.5f;
    CHECK(intersectSphere(s.p, s.radius, {Vec3(0, 0, 0), Vec3(0, 0, 1), kInf}) == doctest::Approx(9999.5f).epsilon(1e-6));
    // A ray leaving a surface point, pushed off by offsetPoint, does not hit its own sphere.
    s.p = Vec3(0, 0, 0);
    s.radius = 300;
    Rng rng = makeRng(7, 0, 0);
    int selfHits = 0;
    for (int i = 0; i < 10000; ++i) {
        Vec3 n = sampleUniformSphere(rng.uniform(), rng.uniform());
        SurfacePoint sp = makeSurfacePoint(s, 0, s.p + s.radius * n, false);
        Vec3 d = Frame(sp.ng).toWorld(sampleCosineHemisphere(rng.uniform(), rng.uniform()));
        selfHits += intersectSphere(s.p, s.radius, spawnRay(sp, d)) < kInf;
    }
    CHECK(selfHits == 0);
}

TEST_CASE("ray-quad: inside, edges, outside, parallel, back side") {
    Shape q;
    q.type = Shape::Quad;
    q.p = Vec3(0, 0, 0);
    q.u = Vec3(2, 0, 0);
    q.v = Vec3(0, 1, 0);
    CHECK(intersectQuad(q, {Vec3(1, 0.5f, -3), Vec3(0, 0, 1), kInf}) == doctest::Approx(3.0f));
    CHECK(intersectQuad(q, {Vec3(1, 0.5f, 3), Vec3(0, 0, -1), kInf}) == doctest::Approx(3.0f));  // back side
    CHECK(intersectQuad(q, {Vec3(2.01f, 0.5f, -3), Vec3(0, 0, 1), kInf}) == kInf);
    CHECK(intersectQuad(q, {Vec3(1, -0.01f, -3), Vec3(0, 0, 1), kInf}) == kInf);
    CHECK(intersectQuad(q, {Vec3(1, 0.5f, -3), Vec3(1, 0, 0), kInf}) == kInf);                   // parallel
    Vec3 d = normalize(Vec3(1, 1, 2));
    float t = intersectQuad(q, {Vec3(0, 0, -2), d, kInf});
    CHECK(t == doctest::Approx(2 / d.z));
}

// Directional albedo two ways: the mean sampling weight E[f cos / pdf], and (for non-delta lobes)
// an independent uniform-sphere integral of evalBsdfCos. They must agree, and stay <= 1.
TEST_CASE("BSDF albedo <= 1 and sampling consistent with evaluation") {
    Material diffuse = makeMaterial(Material::Diffuse, 0.8f), glossy = makeMaterial(Material::Glossy, 1.0f, 20),
             mirror = makeMaterial(Material::Mirror, 0.9f), glass = makeMaterial(Material::Glass, 1.0f, 1.5f);
    const int N = 200000;
    for (Material m : {diffuse, glossy, mirror, glass}) {
        Scene scene = singleQuadScene(m);
        SurfacePoint sp = surfaceAtOrigin();
        for (float theta : {0.0f, 0.5f, 1.0f, 1.4f}) {
            CAPTURE(m.type);
            CAPTURE(theta);
            Vec3 wo(std::sin(theta), 0, std::cos(theta));
            Rng rng = makeRng(3, m.type, uint64_t(theta * 100));
            double sampled = 0, uniform = 0;
            for (int i = 0; i < N; ++i) {
                BsdfSample bs;
                if (sampleBsdf(scene, sp, wo, Transport::Importance, rng, bs)) sampled += bs.weight.x;
                Vec3 wi = sampleUniformSphere(rng.uniform(), rng.uniform());
                uniform += evalBsdfCos(scene, sp, wo, wi, Transport::Importance).x * 4 * kPi;
            }
            sampled /= N;
            uniform /= N;
            CHECK(sampled <= 1.0 + 1e-3);
            if (m.type == Material::Diffuse) CHECK(sampled == doctest::Approx(0.8).epsilon(1e-6));
            if (m.type == Material::Mirror) CHECK(sampled == doctest::Approx(0.9).epsilon(1e-6));
            if (m.type == Material::Glass) CHECK(sampled == doctest::Approx(1.0).epsilon(1e-6));  // power: R + T = 1
            if (!isSpecular(m)) CHECK(sampled == doctest::Approx(uniform).epsilon(0.03));
            if (m.type == Material::Glossy && theta == 0) CHECK(sampled == doctest::Approx(1.0).epsilon(0.01));
        }
    }
}

TEST_CASE("Fresnel of a dielectric (eta 1.5): normal, 45 degrees, Brewster, total internal reflection") {
    CHECK(fresnelDielectric(1.0f, 1 / 1.5f) == doctest::Approx(0.04f).epsilon(1e-4));
    CHECK(fresnelDielectric(std::cos(45 * kPi / 180), 1 / 1.5f) == doctest::Approx(0.05024f).epsilon(1e-3));
    CHECK(fresnelDielectric(std::cos(56.31f * kPi / 180), 1 / 1.5f) == doctest::Approx(0.07396f).epsilon(1e-3));
    CHECK(fresnelDielectric(std::cos(41.0f * kPi / 180), 1.5f) < 1.0f);   // just inside the critical angle
    CHECK(fresnelDielectric(std::cos(42.0f * kPi / 180), 1.5f) == 1.0f);  // beyond 41.81 degrees
}

TEST_CASE("furnace: L = Le / (1 - a) = 2 within 1% for every method; truncated at D bounces") {
    Scene scene = sceneAt("scenes/furnace.scene", 32, 32);
    struct Run { Method m; bool mis; };
    for (Run run : {Run{Method::PT, false}, Run{Method::NEE, false}, Run{Method::NEE, true}, Run{Method::LT, false},
                    Run{Method::IR, false}, Run{Method::BDPT, false}, Run{Method::VCM, false}, Run{Method::PSSMLT, false},
                    Run{Method::MMLT, false}, Run{Method::MLT, false}}) {
        RenderOptions o = quietOptions(run.m, 64);
        o.mis = run.mis;  // nee --mis: a light density without the light's cosine gave 2.19
        o.metropolis.bootstrap = run.m == Method::MMLT ? 200000 : 20000;  // pssmlt's image mean is its b: the bootstrap's and the large steps'
        RenderResult r = render(scene, o);
        CAPTURE(int(run.m));
        CAPTURE(run.mis);
        CHECK(imageMean(r.image) == doctest::Approx(2.0).epsilon(0.01));
        CHECK(r.nonFinite == 0);
        for (int depth : {0, 1, 2, 3}) {  // Le (1 + a + ... + a^D): 1, 1.5, 1.75, 1.875; a length limit off by one fails
            CAPTURE(depth);
            o.maxDepth = depth;
            CHECK(imageMean(render(scene, o).image) == doctest::Approx(2 - std::pow(0.5, depth)).epsilon(0.01));
        }
    }
}

TEST_CASE("rays are counted per method; Russian roulette: throughput after 3 bounces, or the albedo at every vertex") {
    // The furnace is closed and every surface is diffuse and emits: no ray escapes, every vertex
    // samples a light point, so at --maxdepth 1 (camera ray, one bounce) the counts are exact.
    Scene scene = sceneAt("scenes/furnace.scene", 8, 8);
    RenderOptions o = quietOptions(Method::PT, 2);
    o.maxDepth = 1;
    RenderResult r = render(scene, o);
    CHECK(r.rays.closest == 256);
    CHECK(r.rays.shadow == 0);
    o.method = Method::NEE;  // next event at the first vertex only: the second ends the path
    r = render(scene, o);
    CHECK(r.rays.closest == 256);
    CHECK(r.rays.shadow == 128);
    CHECK(raysPerSample(r) == "3.00 rays per sample (2.00 closest-hit, 1.00 shadow)");
    // The shortest paths over many samples: rrStart + 1 surface vertices for nee's camera path
    // and, under --roulette throughput, for both of bdpt's subpaths (which add the pinhole or
    // the light point).
    RenderOptions one = quietOptions(Method::NEE, 1);
    one.threads = 1;
    one.roulette = Roulette::Throughput;
    Scene pixel = sceneAt("scenes/furnace.scene", 1, 1);
    long long shortestNee = 1 << 30;
    size_t shortestCamera = 1 << 30, shortestLight = 1 << 30;
    std::vector<PathVertex> camera, light;
    for (uint64_t seed = 1; seed <= 64; ++seed) {
        one.seed = seed;
        shortestNee = std::min(shortestNee, render(pixel, one).rays.closest);
        Rng rng = makeRng(seed, 0, 0);
        cameraSubpath(pixel, one, 0.5f, 0.5f, rng, camera);
        lightSubpath(pixel, one, rng, light);
        shortestCamera = std::min(shortestCamera, camera.size());
        shortestLight = std::min(shortestLight, light.size());
    }
    CHECK(one.rrStart == 3);
    CHECK(shortestNee == 4);
    CHECK(shortestCamera == 5);
    CHECK(shortestLight == 5);
    // The default for subpaths, --roulette albedo: q = 0.5 (the furnace's albedo) from the first
    // vertex on, so the number of surface vertices is geometric: half the subpaths have one,
    // and the mean is 1 / (1 - 0.5) = 2 (the depth limit of 32 is never reached in practice).
    one.roulette = Roulette::Albedo;
    const int n = 20000;
    double single = 0, total = 0;
    for (int i = 0; i < n; ++i) {
        Rng rng = makeRng(7, uint64_t(i), 0);
        cameraSubpath(pixel, one, 0.5f, 0.5f, rng, camera);
        lightSubpath(pixel, one, rng, light);
        for (size_t surfaceVertices : {camera.size() - 1, light.size() - 1}) {
            single += surfaceVertices == 1;
            total += surfaceVertices;
        }
    }
    CHECK(single / (2 * n) == doctest::Approx(0.5).epsilon(0.03));
    CHECK(total / (2 * n) == doctest::Approx(2.0).epsilon(0.03));
}

TEST_CASE("Russian roulette is the furnace's only noise: pt without it (--rr-start > --maxdepth) is exact") {
    // Cosine sampling of a diffuse albedo a gives every bounce the weight a: without roulette
    // every camera path carries exactly Le (1 - a^(D+1)) / (1 - a), and all noise is roulette's.
    Scene scene = sceneAt("scenes/furnace.scene", 16, 16);
    RenderOptions o = quietOptions(Method::PT, 16, 94);
    o.maxDepth = 32;
    auto spread = [&](int rrStart) {
        o.rrStart = rrStart;
        RenderResult r = render(scene, o);
        double worst = 0;
        for (const Vec3& p : r.image.pixels) worst = std::max(worst, std::abs(double(p.x) - 2.0));
        return worst;
    };
    CHECK(spread(33) < 1e-5);
    CHECK(spread(3) > 0.05);
    CHECK(spread(0) > spread(8));  // an earlier start: fewer rays, more noise
    std::ostringstream so, se;
    CHECK(runCommandLine({"scenes/furnace.scene", "--method", "bdpt", "--rr-start", "5"}, so, se) == 2);
    CHECK(se.str().find("--rr-start applies to pt, nee and --roulette throughput") != std::string::npos);
}

TEST_CASE("pt and nee (with and without MIS) agree on cornell within statistical error") {
    Scene scene = sceneAt("scenes/cornell.scene", 32, 32);
    RegionEstimate pt = renderRegions(scene, quietOptions(Method::PT, 2048, 11), 4);
    RegionEstimate nee = renderRegions(scene, quietOptions(Method::NEE, 1024, 12), 4);
    RenderOptions misOpt = quietOptions(Method::NEE, 1024, 13);
    misOpt.mis = true;
    RegionEstimate mis = renderRegions(scene, misOpt, 4);
    CHECK(maxZ(pt, nee) < 4.5);
    CHECK(maxZ(nee, mis) < 4.5);
    // And the comparison has teeth: 3% less light is detected.
    RegionEstimate darker = nee;
    for (double& m : darker.mean) m *= 0.97;
    CHECK(maxZ(pt, darker) > 4.5);
}

TEST_CASE("pt leaves the point-lit box black; nee does not") {
    Scene scene = sceneAt("scenes/cornell-point.scene", 16, 16);
    CHECK(imageMean(render(scene, quietOptions(Method::PT, 4)).image) == 0.0);
    CHECK(imageMean(render(scene, quietOptions(Method::NEE, 4)).image) > 0.05);
}

TEST_CASE("the image is the same bit for bit with 1 and 2 threads") {
    Scene scene = sceneAt("scenes/cornell-glass.scene", 24, 24);
    CHECK(sameWithOneAndTwoThreads(scene, quietOptions(Method::NEE, 3)));
    RenderResult a = render(scene, quietOptions(Method::NEE, 3, 1)), b = render(scene, quietOptions(Method::NEE, 3, 2));
    CHECK(std::memcmp(a.image.pixels.data(), b.image.pixels.data(), a.image.pixels.size() * sizeof(Vec3)) != 0);  // seeds matter
}

TEST_CASE("PFM round trip and atomic output files") {
    Scene scene = sceneAt("scenes/cornell.scene", 8, 6);
    RenderResult r = render(scene, quietOptions(Method::NEE, 1));
    REQUIRE(writePFM(r.image, "build/tmp/roundtrip.pfm"));
    Image back;
    REQUIRE(readPFM("build/tmp/roundtrip.pfm", back));
    CHECK(back.width == 8);
    CHECK(back.height == 6);
    CHECK(std::memcmp(back.pixels.data(), r.image.pixels.data(), back.pixels.size() * sizeof(Vec3)) == 0);
    CHECK(!fileExists(tempName("build/tmp/roundtrip.pfm")));
    CHECK(!writePFM(r.image, "build/no-such-dir/x.pfm"));
    CHECK(!fileExists("build/no-such-dir/x.pfm"));
}

// Every kind of bad input: its message, exit status 2, and no output file.
static void expectBadInput(const std::string& sceneText, const std::vector<std::string>& extraArgs, const std::string& message) {
    std::string scene = writeTempFile("bad.scene", sceneText), out = "build/tmp/bad_out.png";
    std::remove(out.c_str());
    std::vector<std::string> args = {scene, "--out", out, "--quiet"};
    args.insert(args.end(), extraArgs.begin(), extraArgs.end());
    if (std::find(extraArgs.begin(), extraArgs.end(), "--spp") == extraArgs.end()) args.insert(args.end(), {"--spp", "1"});
    std::ostringstream so, se;
    int status = runCommandLine(args, so, se);
    CAPTURE(sceneText);
    CAPTURE(se.str());
    CHECK(status == 2);
    CHECK(se.str().find(message) != std::string::npos);
    CHECK(!fileExists(out));
    CHECK(!fileExists("build/tmp/bad_out.pfm"));
}

TEST_CASE("bad input: file:line message, exit 2, no output file") {
    const std::string cam = "camera 0 0 -5  0 0 0  0 1 0  40  8 8\n";
    const std::string mat = "material m diffuse 0.5 0.5 0.5\n";
    const std::string light = "pointlight 0 2 0  1 1 1\n";
    expectBadInput(cam + mat + "cube 0 0 0 1 m\n" + light, {}, "bad.scene:3: unknown directive 'cube'");
    expectBadInput(cam + mat + "sphere 0 0 0 m\n" + light, {}, "bad.scene:3: malformed number 'm' for sphere radius");
    expectBadInput(cam + mat + "sphere 0 0 0\n" + light, {}, "bad.scene:3: missing sphere radius");
    expectBadInput(cam + mat + light + "pointlight 0 2 0 1 1 1 7\n", {}, "bad.scene:4: unexpected '7'");
    expectBadInput(cam + mat + "sphere 0 0 1e999 1 m\n" + light, {}, "bad.scene:3: number out of range");
    expectBadInput(cam + mat + "sphere 0 0 nan 1 m\n" + light, {}, "bad.scene:3: malformed number 'nan'");
    expectBadInput(cam + mat + "sphere 0 0 0 1 wood\n" + light, {}, "bad.scene:3: unknown material 'wood'");
    expectBadInput(cam + mat + mat + light, {}, "bad.scene:3: duplicate material name 'm'");
    expectBadInput(cam + mat + "sphere 0 0 0 -1 m\n" + light, {}, "bad.scene:3: sphere radius must be > 0");
    expectBadInput(cam + mat + "sphere 0 0 0 0 m\n" + light, {}, "bad.scene:3: sphere radius must be > 0");
    expectBadInput(cam + mat + "quad 0 0 0  1 0 0  2 0 0  m\n" + light, {}, "bad.scene:3: quad has zero area");
    expectBadInput(cam + "material g glass 0\n" + light, {}, "bad.scene:2: index of refraction must be > 0");
    expectBadInput(cam + "material g glass -1.5\n" + light, {}, "bad.scene:2: index of refraction must be > 0");
    expectBadInput(cam + "material d diffuse 0.5 1.2 0.5\n" + light, {}, "bad.scene:2: albedo must lie in [0,1]");
    expectBadInput(cam + "material d diffuse 0.5 -0.1 0.5\n" + light, {}, "bad.scene:2: albedo must lie in [0,1]");
    expectBadInput("camera 0 0 -5  0 0 0  0 1 0  40  0 8\n" + light, {}, "bad.scene:1: image width must be a whole number");
    expectBadInput("camera 0 0 -5  0 0 0  0 1 0  40  100000 8\n" + light, {}, "bad.scene:1: image width must be");
    expectBadInput("camera 0 0 -5  0 0 0  0 1 0  40  10000 10000\n" + light, {}, "bad.scene:1: image larger than 64 megapixels");
    expectBadInput(mat + light, {}, "bad.scene:2: no camera");
    expectBadInput(cam + mat + "sphere 0 0 0 1 m\n", {}, "bad.scene:3: no light");
    expectBadInput(cam + mat + "sphere 0 0 0 1 m emit 0 0 0\n", {}, "bad.scene:3: no light");
    expectBadInput(cam + light, {"--method", "magic"}, "bdpt: unknown method 'magic'");
    expectBadInput(cam + light, {"--fast"}, "bdpt: unknown option '--fast'");
    expectBadInput(cam + light, {"--spp", "0"}, "bdpt: option --spp needs a number from 1");
    expectBadInput(cam + light, {"--spp"}, "bdpt: option --spp needs a value");
    expectBadInput(cam + light, {"--spp", "1.5"}, "bdpt: option --spp needs a whole number, got '1.5'");
    expectBadInput(cam + light, {"--spp", "4", "--spp", "8"}, "bdpt: option --spp given twice");
    expectBadInput(cam + light, {"--out=x.png"}, "bdpt: unknown option '--out=x.png' (write '--out x.png')");
    std::ostringstream so, se;
    CHECK(runCommandLine({"build/does-not-exist.scene", "--out", "build/tmp/bad_out.png"}, so, se) == 2);
    CHECK(se.str() == "build/does-not-exist.scene: cannot open the scene file: No such file or directory\n");
    CHECK(!fileExists("build/tmp/bad_out.png"));
}

TEST_CASE("--help lists every option the parser accepts, and the README's table too") {
    std::ostringstream so, se;
    CHECK(runCommandLine({"--help"}, so, se) == 0);
    std::stringstream readme;
    readme << std::ifstream("README.md").rdbuf();
    int listed = 0;
    for (const OptionRow<ClassroomLine>& o : classroomTable()) {
        if (!o.name) continue;
        CAPTURE(o.name);
        CHECK(so.str().find(std::string("  ") + o.name) != std::string::npos);  // at the start of its help line
        CHECK(readme.str().find(std::string("`") + o.name) != std::string::npos);
        ++listed;
    }
    CHECK(listed >= 35);
}

TEST_CASE("a good run writes both files and reports them") {
    std::remove("build/tmp/good.png");
    std::remove("build/tmp/good.pfm");
    std::ostringstream so, se;
    CHECK(runCommandLine({"scenes/furnace.scene", "--res", "8x8", "--spp", "2", "--out", "build/tmp/good.png"}, so, se) == 0);
    CHECK(fileExists("build/tmp/good.png"));
    Image img;
    REQUIRE(readPFM("build/tmp/good.pfm", img));
    CHECK(img.width == 8);
    CHECK(imageMean(img) == doctest::Approx(2.0).epsilon(0.1));
    CHECK(so.str().find("0 non-finite samples dropped") != std::string::npos);
}

TEST_CASE("PFM bytes: header, little-endian floats, rows from the bottom up (written by hand here)") {
    Image img(2, 2);
    img.at(0, 0) = Vec3(1, 2, 3);      // top row
    img.at(1, 0) = Vec3(4, 5, 6);
    img.at(0, 1) = Vec3(0.5f, -1, 0);  // bottom row: written first
    img.at(1, 1) = Vec3(7, 8, 9);
    std::string path = "build/tmp/bytes.pfm";
    REQUIRE(writePFM(img, path));
    std::string bytes = readFile(path);
    std::string expected = "PF\n2 2\n-1.0\n";
    for (float v : {0.5f, -1.0f, 0.0f, 7.0f, 8.0f, 9.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f}) {
        uint32_t u;
        std::memcpy(&u, &v, 4);
        for (int b = 0; b < 4; ++b) expected += char((u >> (8 * b)) & 0xff);  // little-endian by construction
    }
    CHECK(bytes == expected);
}

// The PNG's bytes follow the sRGB curve (IEC 61966-2-1), written here from the standard: linear
// below 0.0031308, a 2.4 power above. A plain gamma 2.2 passes the furnace's grey window but
// lifts dark values most: 0.001 becomes 11 instead of 3. Read back from the file, so the whole
// path (exposure, rounding, the writer) is checked.
TEST_CASE("the PNG's transfer curve is sRGB's, not a plain gamma, from the value to the file's bytes") {
    auto srgb = [](double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055; };
    const std::vector<double> values = {0, 0.0002, 0.001, 0.0025, 0.004, 0.01, 0.05, 0.18, 0.5, 0.8, 1, 3};
    Image img(int(values.size()), 1);
    for (size_t i = 0; i < values.size(); ++i) img.pixels[i] = Vec3(float(values[i]) * 0.5f);  // exposure +1 stop below
    REQUIRE(writePNG(img, "build/tmp/srgb.png", 1.0f));
    int w = 0, h = 0, channels = 0;
    unsigned char* bytes = stbi_load("build/tmp/srgb.png", &w, &h, &channels, 3);
    REQUIRE(bytes);
    CHECK(w == int(values.size()));
    for (size_t i = 0; i < values.size(); ++i) {
        CAPTURE(values[i]);
        int expected = int(std::lround(std::min(1.0, srgb(values[i])) * 255));
        for (int c = 0; c < 3; ++c) CHECK(int(bytes[3 * i + c]) == expected);
    }
    CHECK(int(bytes[3 * 2]) == 3);                                          // 0.001: 3, not gamma 2.2's 11
    CHECK(std::lround(std::pow(0.001, 1 / 2.2) * 255) == 11);
    stbi_image_free(bytes);
    std::remove("build/tmp/srgb.png");
}
