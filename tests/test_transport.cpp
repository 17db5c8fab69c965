// Light tracing, instant radiosity, and where transport is not symmetric: refraction (eta^2) and
// shading normals (the adjoint BSDF).
#include "helpers.h"
#include "classroom/physics.h"

static Vec3 randomUpper(Rng& rng) {
    Vec3 w = sampleUniformSphere(rng.uniform(), rng.uniform());
    return w.z < 0 ? Vec3(w.x, w.y, -w.z) : w;
}

TEST_CASE("reciprocity: f(wo,wi) = f(wi,wo) for diffuse, glossy and mirror") {
    Material diffuse = makeMaterial(Material::Diffuse, 0.7f), glossy = makeMaterial(Material::Glossy, 0.9f, 12),
             mirror = makeMaterial(Material::Mirror, 0.8f);
    SurfacePoint sp = surfaceAtOrigin();
    Rng rng = makeRng(5, 0, 0);
    double worst = 0;
    int nonzero = 0;
    for (Material m : {diffuse, glossy}) {
        Scene scene = singleQuadScene(m);
        for (int i = 0; i < 20000; ++i) {
            Vec3 a = randomUpper(rng), b = randomUpper(rng);
            float fab = evalBsdfCos(scene, sp, a, b, Transport::Radiance).x / b.z;  // f without its cosine
            float fba = evalBsdfCos(scene, sp, b, a, Transport::Radiance).x / a.z;
            worst = std::max(worst, double(std::fabs(fab - fba)) / std::max(1e-6f, std::max(fab, fba)));
            nonzero += fab > 0;
        }
    }
    CHECK(worst < 1e-4);
    CHECK(nonzero > 20000);
    // The mirror: reflecting the reflection returns the first direction, with the same weight.
    Scene scene = singleQuadScene(mirror);
    for (int i = 0; i < 1000; ++i) {
        Vec3 wo = randomUpper(rng);
        BsdfSample s1, s2;
        REQUIRE(sampleBsdf(scene, sp, wo, Transport::Radiance, rng, s1));
        REQUIRE(sampleBsdf(scene, sp, s1.wi, Transport::Radiance, rng, s2));
        CHECK(length(s2.wi - wo) < 1e-5f);
        CHECK(s1.weight.x == s2.weight.x);
    }
}

// Generalized reciprocity f(wi->wo)/eta_o^2 = f(wo->wi)/eta_i^2 has two checkable faces here:
// the radiance weight of a refraction is (eta_o/eta_i)^2 times the importance weight, and the
// hemispherical Fresnel reflectance inside is 1 - (1 - outside)/eta^2.
TEST_CASE("refraction: radiance scales by (eta_o/eta_i)^2, importance does not; Fresnel inside/outside") {
    Scene scene = singleQuadScene(makeMaterial(Material::Glass, 1.0f, 1.5f));
    SurfacePoint sp = surfaceAtOrigin();
    Rng rng = makeRng(6, 0, 0);
    int refracted = 0;
    for (int i = 0; i < 4000; ++i) {
        Vec3 wo = randomUpper(rng);
        if (i % 2) wo.z = -wo.z;  // from inside the glass too
        float etaO = wo.z > 0 ? 1.0f : 1.5f, etaI = wo.z > 0 ? 1.5f : 1.0f;
        Rng r1 = rng, r2 = rng;    // the same random numbers: the same lobe is chosen
        BsdfSample rad, imp;
        bool ok1 = sampleBsdf(scene, sp, wo, Transport::Radiance, r1, rad);
        bool ok2 = sampleBsdf(scene, sp, wo, Transport::Importance, r2, imp);
        rng = r1;
        REQUIRE(ok1 == ok2);
        if (!ok1 || rad.wi.z * wo.z > 0) continue;  // reflection: no eta factor
        ++refracted;
        CHECK(rad.weight.x == doctest::Approx(imp.weight.x * sqr(etaO / etaI)).epsilon(1e-5));
        CHECK(imp.weight.x == doctest::Approx(1.0f).epsilon(1e-5));
    }
    CHECK(refracted > 1000);
    double outside = 0, inside = 0;
    const int N = 200000;
    for (int i = 0; i < N; ++i) {  // cosine-weighted hemispherical average of F
        float cosT = std::sqrt(rng.uniform());
        outside += fresnelDielectric(cosT, 1 / 1.5f);
        inside += fresnelDielectric(cosT, 1.5f);
    }
    outside /= N;
    inside /= N;
    CHECK(outside == doctest::Approx(0.0918).epsilon(0.01));
    CHECK(inside == doctest::Approx(0.5964).epsilon(0.01));
    CHECK(inside == doctest::Approx(1 - (1 - outside) / (1.5 * 1.5)).epsilon(0.01));
}

TEST_CASE("a camera inside a glass sphere in a uniform room sees eta^2 Le = 2.25; symmetric refraction sees 1") {
    Scene scene = sceneAt("tests/glass-camera.scene", 8, 8);
    CHECK(imageMean(render(scene, quietOptions(Method::PT, 256)).image) == doctest::Approx(2.25).epsilon(0.01));
    scene.conventions.symmetricRefraction = true;
    CHECK(imageMean(render(scene, quietOptions(Method::PT, 256)).image) == doctest::Approx(1.0).epsilon(0.01));
}

// Directional albedo of the BSDF light paths use, by uniform sampling of wi over the sphere.
static double adjointAlbedo(const Scene& scene, const SurfacePoint& sp, Vec3 wo, Rng& rng) {
    double sum = 0;
    const int N = 400000;
    for (int i = 0; i < N; ++i)
        sum += evalBsdfCos(scene, sp, wo, sampleUniformSphere(rng.uniform(), rng.uniform()), Transport::Importance).x;
    return sum * 4 * kPi / N;
}

TEST_CASE("shading normals: the adjoint BSDF's albedo exceeds 1 at grazing angles (the energy generator)") {
    Scene scene = singleQuadScene(makeMaterial(Material::Diffuse, 0.8f));
    Rng rng = makeRng(8, 0, 0);
    float tilt = 0.5f;  // radians
    SurfacePoint tilted = surfaceAtOrigin(Vec3(std::sin(tilt), 0, std::cos(tilt)));
    SurfacePoint plain = surfaceAtOrigin();
    Vec3 grazing = normalize(Vec3(1, 0, 0.05f));  // nearly in the geometric plane, well above ns
    double a = adjointAlbedo(scene, tilted, grazing, rng);
    CHECK(a > 1.5);   // "can be arbitrarily large": |wo.ns|/|wo.ng| = 9.6 here
    for (float theta : {0.0f, 0.7f, 1.3f, 1.55f}) {
        Vec3 wo(std::sin(theta), 0, std::cos(theta));
        CHECK(adjointAlbedo(scene, plain, wo, rng) <= 0.8 * 1.01);
    }
    scene.conventions.noAdjointCorrection = true;  // the uncorrected BSDF conserves energy but breaks reciprocity
    CHECK(adjointAlbedo(scene, tilted, grazing, rng) < 0.81);
}

TEST_CASE("energy generator: a floor with a constant tilted shading normal reflects more power than it receives") {
    Scene tilted = sceneAt("scenes/energy-generator.scene", 48, 36);
    double ratio = floorPowerRatio(tilted, 1, 200000, 12).mean;
    MESSAGE("power out / power in: " << ratio << " (albedo 0.8)");
    CHECK(ratio > 1.5);
    Scene plain = tilted;
    plain.shapes[0].shading = Shape::ShadingNormal::Geometric;
    CHECK(floorPowerRatio(plain, 1, 200000, 12).mean == doctest::Approx(0.8).epsilon(1e-4));
    Scene uncorrected = tilted;  // the shading BSDF unadjoined keeps energy, loses consistency
    uncorrected.conventions.noAdjointCorrection = true;
    CHECK(floorPowerRatio(uncorrected, 1, 200000, 12).mean <= 0.8 + 1e-4);
    // Consistency, not conservation: with the adjoint lt agrees with nee on this floor's image.
    RegionEstimate nee = renderRegions(tilted, quietOptions(Method::NEE, 256, 44), 2);
    RegionEstimate lt = renderRegions(tilted, quietOptions(Method::LT, 1024, 45), 2);
    RegionEstimate ltUncorrected = renderRegions(uncorrected, quietOptions(Method::LT, 1024, 46), 2);
    MESSAGE("image means nee " << nee.mean.back() << " lt " << lt.mean.back() << " lt unadjoined " << ltUncorrected.mean.back());
    CHECK(maxZ(nee, lt) < 4.5);
    CHECK(ltUncorrected.mean.back() < 0.5 * nee.mean.back());
    // Camera paths render the generated energy too: their weights stay bounded, but the BSDF they
    // integrate, f' |wi.ns| / |wi.ng|, is the same. Expected from the geometry alone: toward the
    // lamp's centre from the floor's, |w.ns| / |w.ng| = 7.4 (the floor's other points see the lamp
    // a little higher, so a little less). "Eye paths see nothing strange" would give 1.
    RegionEstimate neePlain = renderRegions(plain, quietOptions(Method::NEE, 256, 47), 2);
    Vec3 toLamp = normalize(Vec3(0, 0.5f, 4)), ns = tilted.shapes[0].tiltedNormal;
    double expected = std::abs(dot(toLamp, ns)) / std::abs(toLamp.y);
    double brighter = nee.mean.back() / neePlain.mean.back();
    MESSAGE("nee, tilted floor / untilted: " << nee.mean.back() << " / " << neePlain.mean.back() << " = " << brighter
            << " (|w.ns| / |w.ng| at the centre " << expected << ")");
    CHECK(brighter > 0.75 * expected);
    CHECK(brighter < 1.05 * expected);
}

TEST_CASE("lt equals nee on cornell, region by region") {
    Scene scene = sceneAt("scenes/cornell.scene", 32, 32);
    RegionEstimate nee = renderRegions(scene, quietOptions(Method::NEE, 1024, 21), 4);
    RegionEstimate lt = renderRegions(scene, quietOptions(Method::LT, 1024, 22), 4);
    CHECK(maxZ(nee, lt) < 4.5);
    RegionEstimate darker = lt;
    for (double& m : darker.mean) m *= 0.97;
    CHECK(maxZ(nee, darker) > 4.5);  // the comparison would see a 3% error
}

// The pool: compare the floor, the part of the image both methods can render.
static RegionEstimate poolFloor(Scene scene, Method m, int spp, uint64_t seed, bool symmetric) {
    scene.conventions.symmetricRefraction = symmetric;
    RegionEstimate all = renderRegions(scene, quietOptions(m, spp, seed), 4);
    RegionEstimate floor;  // regions 12..15: the bottom row of a 4x4 grid
    for (int r = 12; r < 16; ++r) {
        floor.mean.push_back(all.mean[r]);
        floor.stdError.push_back(all.stdError[r]);
    }
    return floor;
}

TEST_CASE("refraction scene: pt and lt agree under water; with --symmetric-refraction both are off by ~eta^2") {
    Scene scene = sceneAt("scenes/refraction.scene", 32, 24);
    RegionEstimate pt = poolFloor(scene, Method::PT, 512, 31, false), lt = poolFloor(scene, Method::LT, 2048, 32, false);
    CHECK(maxZ(pt, lt) < 4.5);
    RegionEstimate ptSym = poolFloor(scene, Method::PT, 512, 33, true), ltSym = poolFloor(scene, Method::LT, 2048, 34, true);
    CHECK(maxZ(pt, ptSym) > 6);
    CHECK(maxZ(lt, ltSym) > 6);
    double eta2 = 1.33 * 1.33;
    for (size_t r = 0; r < 4; ++r) {
        CHECK(pt.mean[r] / ptSym.mean[r] == doctest::Approx(eta2).epsilon(0.1));  // eye tracing too dark
        CHECK(ltSym.mean[r] / lt.mean[r] == doctest::Approx(eta2).epsilon(0.1));  // particles too bright
    }
}

TEST_CASE("shading normals: lt agrees with nee with the adjoint correction, not without") {
    Scene scene = sceneAt("scenes/shading-normals.scene", 32, 32);
    RegionEstimate nee = renderRegions(scene, quietOptions(Method::NEE, 512, 41), 1);
    RegionEstimate lt = renderRegions(scene, quietOptions(Method::LT, 1024, 42), 1);
    CHECK(maxZ(nee, lt) < 4.5);
    scene.conventions.noAdjointCorrection = true;
    RegionEstimate uncorrected = renderRegions(scene, quietOptions(Method::LT, 1024, 43), 1);
    CHECK(maxZ(nee, uncorrected) > 6);
}

TEST_CASE("lt renders the point-lit box, and its image is the same with 1 and 2 threads") {
    Scene scene = sceneAt("scenes/cornell-point.scene", 24, 24);
    CHECK(sameWithOneAndTwoThreads(scene, quietOptions(Method::LT, 4)));
    CHECK(imageMean(render(scene, quietOptions(Method::LT, 4)).image) > 0.05);
}

TEST_CASE("ir: unclamped converges to nee; clamped loses energy, and more passes do not win it back") {
    Scene scene = sceneAt("scenes/cornell.scene", 32, 32);
    RegionEstimate nee = renderRegions(scene, quietOptions(Method::NEE, 512, 51), 2);
    RenderOptions o = quietOptions(Method::IR, 1024, 52);
    RegionEstimate ir = renderRegions(scene, o, 2);
    CHECK(maxZ(nee, ir) < 4.5);
    o.ir.clamp = 1e-5f;  // G in mm^-2: clamps VPLs closer than about 30 cm
    RenderResult clamped;
    RegionEstimate irc = renderRegions(scene, o, 2, &clamped);
    double bias1024 = (nee.mean.back() - irc.mean.back()) / nee.mean.back();
    CHECK(bias1024 > 0.015);  // of the whole image, whose visible lamp the clamp does not touch
    CHECK((nee.mean.back() - irc.mean.back()) / std::hypot(nee.stdError.back(), irc.stdError.back()) > 5);
    CHECK(clamped.clampRemoved() > 0.05);
    o.spp = 128;
    o.seed = 53;
    RegionEstimate irc128 = renderRegions(scene, o, 2);
    double bias128 = (nee.mean.back() - irc128.mean.back()) / nee.mean.back();
    CHECK(bias128 == doctest::Approx(bias1024).epsilon(0.35));  // 8x the passes, the same bias
}

// What --clamp removes, recomputed here for the same VPLs and camera vertices: G(x,y) = cos_x cos_y
// / d^2 from the two points and their normals, each VPL's gathered energy scaled by min(1, C/G).
// A G with one cosine left out clamps other VPLs (cornell at 1e-5: a share of 13.6% instead of 9%).
TEST_CASE("ir --clamp removes exactly the energy above min(G, C), G with both cosines") {
    Scene scene = sceneAt("scenes/cornell.scene", 24, 24);
    const int W = scene.camera.width, H = scene.camera.height;
    RenderOptions o = quietOptions(Method::IR, 1, 9);
    o.ir.clamp = 1e-5f;
    o.threads = 1;
    RenderResult r = render(scene, o);
    std::vector<Vpl> vpls = traceVpls(scene, o, 0);
    double before = 0, after = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            Rng rng = sampleRng(o, 0, uint64_t(y) * W + x, 0);  // the render's own numbers for this pixel
            Ray ray = pixelRay(scene.camera, x, y, rng);
            Hit hit = intersect(scene, ray);
            if (!hit.found()) continue;
            PathVertex z;  // cornell has no mirror: the first hit gathers
            z.sp = surfaceAt(scene, ray, hit);
            z.wo = -ray.d;
            z.beta = Vec3(1);
            for (const Vpl& v : vpls) {
                Connection k;
                evalConnection(scene, v.y, z, k);
                Vec3 c = connectVertices(v.y, z, k);
                if (isBlack(c) || !mutuallyVisible(scene, v.y, z)) continue;
                Vec3 d = z.sp.p - v.y.sp.p;
                double dist2 = dot(d, d), cosX = std::fabs(dot(z.sp.ng, d)) / std::sqrt(dist2);
                double cosY = v.y.type == PathVertex::Light && v.y.deltaPosition ? 1 : std::fabs(dot(v.y.sp.ng, d)) / std::sqrt(dist2);
                double G = cosX * cosY / dist2;
                before += average(c);
                after += average(c) * std::min(1.0, o.ir.clamp / G);
            }
        }
    double share = 1 - after / before;
    MESSAGE("clamp 1e-5 on cornell: removed " << 100 * r.clampRemoved() << "% (recomputed " << 100 * share << "%)");
    CHECK(share > 0.05);
    CHECK(r.clampRemoved() == doctest::Approx(share).epsilon(1e-3));
}

// nee --mis weights the light sample and the BSDF sample that find the same light with one
// heuristic: the two weights of a path then sum to 1. With two heuristics they do not: at a ratio
// r = p_bsdf / p_light the sum is 1/(1+r^2) + r/(1+r) (power for the light sample, balance for
// the BSDF's), 1 only at r = 1. Here a lamp 1 above the floor subtends about 1.6 sr, so that r
// lies between 0.26 and 0.51 for every point the pinhole (between lamp and floor, looking down)
// sees: one heuristic mixed with the other moves the image by +-14%. Plain nee, without MIS, is
// the reference.
TEST_CASE("nee --mis equals plain nee under a lamp where the two heuristics differ everywhere") {
    Scene scene = parseScene("camera 0 0.5 0  0 0 0  0 0 1  60  24 24\n"
                             "material white diffuse 0.7 0.7 0.7\n"
                             "quad -3 0 -3  0 0 6  6 0 0  white\n"
                             "quad -0.63 1 -0.63  1.26 0 0  0 0 1.26  white emit 1 1 1\n",  // facing down
                             "lamp-over-floor");
    RenderOptions plain = quietOptions(Method::NEE, 256, 21), mis = quietOptions(Method::NEE, 256, 22);
    plain.maxDepth = mis.maxDepth = 1;  // direct light: where the two strategies meet
    mis.mis = true;
    RegionEstimate a = renderRegions(scene, plain, 4), b = renderRegions(scene, mis, 4);
    double z = maxZ(a, b), relative = b.mean.back() / a.mean.back() - 1;
    MESSAGE("nee --mis against nee: max z over 16 regions " << z << ", image mean " << 100 * relative << "%");
    CHECK(z < 4.5);
    CHECK(std::fabs(relative) < 0.02);
}

TEST_CASE("shading normals: ir and bdpt agree with nee with the adjoint correction, and differ without it") {
    // Every method that walks light paths needs the adjoint BSDF, on its sampled bounces and in
    // its connections alike; 4 x 4 regions, since the error is regional (the floor near the camera
    // is brightened, the back wall darkened).
    Scene scene = sceneAt("scenes/shading-normals.scene", 32, 32);
    RegionEstimate nee = referenceRegions("shading-normals", 4);  // nee, 84,000 passes (scenes/refs)
    // lt and bdpt differ far past 6 standard errors without the adjoint (97 and 51 measured at 4x
    // these passes): 256 and 64 passes; ir's 8.5 needs its 1,024.
    struct Run { Method m; int spp; };
    for (Run run : {Run{Method::LT, 256}, Run{Method::IR, 1024}, Run{Method::BDPT, 64}}) {
        CAPTURE(int(run.m));
        scene.conventions.noAdjointCorrection = false;
        double z = maxZ(nee, renderRegions(scene, quietOptions(run.m, run.spp, 45), 4));
        scene.conventions.noAdjointCorrection = true;
        double zWithout = maxZ(nee, renderRegions(scene, quietOptions(run.m, run.spp, 46), 4));
        MESSAGE(std::string(methodName(run.m)) << ": z " << z << ", without the adjoint " << zWithout);
        CHECK(z < 4.5);
        CHECK(zWithout > 6);
    }
}

TEST_CASE("three lights of three kinds: nee --mis, lt and bdpt agree region by region, and in the mean") {
    Scene scene = sceneAt("tests/two-lights.scene", 32, 32);
    REQUIRE(scene.lights.size() == 3);
    RenderOptions mis = quietOptions(Method::NEE, 1024, 47);
    mis.mis = true;
    RegionEstimate nee = renderRegions(scene, mis, 4);
    for (Method m : {Method::LT, Method::BDPT}) {
        CAPTURE(int(m));
        RegionEstimate other = renderRegions(scene, quietOptions(m, m == Method::LT ? 1024 : 256, 48), 4);
        double z = maxZ(nee, other);
        MESSAGE(std::string(methodName(m)) << ": z " << z << " means " << nee.mean.back() << " " << other.mean.back());
        CHECK(z < 4.5);
    }
}

TEST_CASE("a connection evaluates its light end with the adjoint BSDF and its camera end with the BSDF") {
    // What bdpt's and ir's connections multiply (evalConnection); losing the adjoint there biases
    // bdpt by only about 1% on shading-normals.scene, below what a render test resolves cheaply.
    Material m = makeMaterial(Material::Diffuse, 0.8f);
    Scene scene = singleQuadScene(m);
    Rng rng = makeRng(8, 0, 0);
    int compared = 0, differing = 0;
    double worst = 0;
    for (int i = 0; i < 2000; ++i) {
        PathVertex y, x;
        y.sp = surfaceAtOrigin(normalize(Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, 1)));  // a bumped light-side vertex
        y.wo = sampleUniformSphere(rng.uniform(), rng.uniform());
        y.wo.z = std::fabs(y.wo.z);
        x.sp = surfaceAtOrigin(normalize(Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, 1)));
        x.sp.p = Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, 0.2f + rng.uniform());
        x.sp.ng = Vec3(0, 0, -1);  // facing the quad
        x.sp.ns = normalize(Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, -1));
        x.wo = normalize(Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, -1));
        Connection c;
        evalConnection(scene, y, x, c);
        if (isBlack(c.fy) || isBlack(c.fx)) continue;
        ++compared;
        Vec3 importance = evalBsdfCos(scene, y.sp, y.wo, c.w, Transport::Importance);
        Vec3 radiance = evalBsdfCos(scene, x.sp, x.wo, -c.w, Transport::Radiance);
        worst = std::max(worst, double(maxComponent(absVec(c.fy - importance)) + maxComponent(absVec(c.fx - radiance))));
        differing += std::fabs(average(importance) / average(evalBsdfCos(scene, y.sp, y.wo, c.w, Transport::Radiance)) - 1) > 0.01f;
    }
    CHECK(compared > 500);
    CHECK(worst < 1e-6);
    CHECK(differing > compared / 4);  // the adjoint differs from the BSDF here: the check can fail
}
