// Bidirectional path tracing: MIS weights, agreement with the other methods, the per-strategy
// images. (Issue: bidirectional path tracing.)
#include "helpers.h"

// -- MIS weights sum to 1 ------------------------------------------------------------------
// A full path x_0 (light) .. x_{n-1} (pinhole) made by a real bdpt connection is split again at
// every s' and its two subpaths rebuilt with the densities the generators would have stored;
// the weights of all strategies able to make the path must sum to 1.
static bool specularAt(const Scene& scene, const PathVertex& v) {
    return v.type == PathVertex::Surface && isSpecular(scene.materials[scene.shapes[v.sp.shape].material]);
}

static std::vector<PathVertex> joinPath(const std::vector<PathVertex>& light, int s, const std::vector<PathVertex>& camera, int t) {
    std::vector<PathVertex> x(light.begin(), light.begin() + s);
    for (int j = t - 1; j >= 0; --j) x.push_back(camera[j]);
    return x;
}

// The solid-angle density with which `cur`, reached from direction wo, samples direction w.
static float pdfDirection(const Scene& scene, const PathVertex& cur, Vec3 wo, Vec3 w) {
    if (cur.type == PathVertex::Camera) return pdfCameraDirection(scene.camera, w);
    if (cur.type == PathVertex::Light) return pdfEmissionDirection(cur, w);
    return pdfBsdf(scene, cur.sp, wo, w);
}

static void rebuild(const Scene& scene, const std::vector<PathVertex>& x, int s, Heuristic h, std::vector<PathVertex>& y,
                    std::vector<PathVertex>& z, double mergeEta = 0) {
    const int n = int(x.size()), t = n - s;
    y.assign(x.begin(), x.begin() + s);
    z.clear();
    for (int j = 0; j < t; ++j) z.push_back(x[n - 1 - j]);
    auto link = [](PathVertex& v, const PathVertex& prev) {  // direction and distance to the predecessor
        Vec3 d = prev.sp.p - v.sp.p;
        v.prevDist2 = dot(d, d);
        v.wo = d / std::sqrt(v.prevDist2);
    };
    for (int i = 0; i < s; ++i) {  // light subpath, y_0 on the light
        PathVertex& v = y[i];
        v.type = i == 0 ? PathVertex::Light : PathVertex::Surface;
        v.deltaPosition = i == 0 && v.sp.shape < 0;
        if (i == 0) v.continuation = 1;  // a light subpath always leaves y_0 (emission sampling)
        if (i == 0) v.sp.ng = v.deltaPosition ? Vec3(0) : geometricNormal(scene.shapes[v.sp.shape], v.sp.p);
        if (i > 0) link(v, y[i - 1]);
        v.delta = i > 0 && specularAt(scene, v);
    }
    for (int i = 0; i < s; ++i) {
        PathVertex& v = y[i];
        if (i == 0) v.pdfFwd = v.deltaPosition ? lightChoiceProbability(scene, v.light) : pdfLightPoint(scene, v.sp.shape);
        else v.pdfFwd = y[i - 1].continuation * (y[i - 1].delta ? 1 : toArea(pdfDirection(scene, y[i - 1], y[i - 1].wo, -v.wo), v, v.wo, v.prevDist2));
        v.pdfRev = i + 2 < s ? y[i + 1].continuation * (y[i + 1].delta ? 1 : toArea(pdfDirection(scene, y[i + 1], -y[i + 2].wo, y[i + 1].wo), v, y[i + 1].wo, y[i + 1].prevDist2)) : 0;
    }
    for (int j = 0; j < t; ++j) {  // camera subpath, z_0 the pinhole
        PathVertex& v = z[j];
        v.type = j == 0 ? PathVertex::Camera : PathVertex::Surface;
        v.deltaPosition = j == 0;
        if (j > 0) {
            link(v, z[j - 1]);
            v.sp.ng = geometricNormal(scene.shapes[v.sp.shape], v.sp.p);
            v.sp.ns = shadingNormal(scene.shapes[v.sp.shape], v.sp.p, v.sp.ng);
        }
        v.delta = j > 0 && specularAt(scene, v);
    }
    for (int j = 0; j < t; ++j) {
        PathVertex& v = z[j];
        v.pdfFwd = j == 0 ? 1 : z[j - 1].continuation * (z[j - 1].delta ? 1 : toArea(pdfDirection(scene, z[j - 1], z[j - 1].wo, -v.wo), v, v.wo, v.prevDist2));
        v.pdfRev = j + 2 < t ? z[j + 1].continuation * (z[j + 1].delta ? 1 : toArea(pdfDirection(scene, z[j + 1], -z[j + 2].wo, z[j + 1].wo), v, z[j + 1].wo, z[j + 1].prevDist2)) : 0;
    }
    cacheMisSums(h, y, mergeEta);
    cacheMisSums(h, z, mergeEta);
}

// Can strategy (s, n-s) make this path at all? s = 0 needs x_0 on an area light; a connection
// needs both of its vertices non-specular.
static bool able(const Scene& scene, const std::vector<PathVertex>& x, int s) {
    if (s == 0) return x[0].sp.shape >= 0 && scene.shapes[x[0].sp.shape].light >= 0;
    PathVertex a = x[s - 1], b = x[s];
    a.type = s - 1 == 0 ? PathVertex::Light : PathVertex::Surface;
    b.type = s == int(x.size()) - 1 ? PathVertex::Camera : PathVertex::Surface;
    return !specularAt(scene, a) && !specularAt(scene, b);
}

struct WeightCheck {
    int paths = 0;
    double worstSum = 0, worstRebuild = 0, worstDefinition = 0, worstMergeWalk = 0, mergeShare = 0;
    std::map<int, int> lengths;
};

// The slides' Probability(SP, estimator), computed from scratch: the density with which strategy
// s makes the path is the product of every vertex's pdfFwd in the two rebuilt subpaths (the
// pinhole's and the deltas' factors appear in every strategy alike).
static double pathDensity(const std::vector<PathVertex>& y, const std::vector<PathVertex>& z) {
    double p = 1;
    for (const PathVertex& v : y) p *= v.pdfFwd;
    for (const PathVertex& v : z) p *= v.pdfFwd;
    return p;
}

// Each heuristic's weight of strategy s by its definition, from the densities p of all the
// strategies able to make the path: balance p_s / sum p, power p_s^2 / sum p^2, max 1 for the
// largest (ties within 1e-4 share), uniform 1 / count.
static double definitionWeight(Heuristic h, const std::map<int, double>& p, int s) {
    double ps = p.at(s), sum = 0;
    int larger = 0, equal = 0;
    for (auto [i, pi] : p) {
        sum += h == Heuristic::Power ? pi * pi : h == Heuristic::Uniform ? 1 : pi;
        if (i == s) continue;
        larger += pi / ps > 1 + 1e-4;
        equal += std::fabs(pi / ps - 1) <= 1e-4;
    }
    if (h == Heuristic::Max) return larger ? 0 : 1.0 / (1 + equal);
    return (h == Heuristic::Power ? ps * ps : h == Heuristic::Uniform ? 1 : ps) / sum;
}

// mergeEta > 0: vcm's weights, where a merge at every non-specular vertex x_i (0 < i < n-1) is
// one more strategy, of density p_i * mergeEta * p_light(x_i) (the keys 1000 + i below).
static WeightCheck checkWeights(const Scene& scene, Heuristic h, int samples, uint64_t seed, Roulette roulette = RenderOptions().roulette,
                                double mergeEta = 0) {
    RenderOptions opt = quietOptions(Method::BDPT, 1, seed);
    opt.maxDepth = 6;
    opt.heuristic = h;
    opt.roulette = roulette;
    WeightCheck wc;
    std::vector<PathVertex> camera, light, y, z;
    for (int i = 0; i < samples; ++i) {
        Rng rng = makeRng(seed, uint64_t(i), 7);
        cameraSubpath(scene, opt, rng.uniform() * scene.camera.width, rng.uniform() * scene.camera.height, rng, camera);
        lightSubpath(scene, opt, rng, light);
        cacheMisSums(h, camera, mergeEta);
        cacheMisSums(h, light, mergeEta);
        for (int t = 1; t <= int(camera.size()); ++t)
            for (int s = 0; s <= int(light.size()); ++s) {
                if (s + t < 3 || s + t - 2 > opt.maxDepth) continue;  // k >= 2: more than one strategy
                int pixel = 0;
                Connection connection;
                if (isBlack(connectStrategy(scene, light, s, camera, t, connection, pixel))) continue;
                std::vector<PathVertex> x = joinPath(light, s, camera, t);
                double sum = 0;
                std::map<int, double> density, weight;
                for (int s2 = 0; s2 < int(x.size()); ++s2) {
                    if (!able(scene, x, s2)) continue;
                    rebuild(scene, x, s2, h, y, z, mergeEta);
                    int t2 = int(x.size()) - s2;
                    Connection c2;  // what connectStrategy would have evaluated for (s2, t2)
                    if (s2 > 0) evalConnection(scene, y[s2 - 1], z[t2 - 1], c2);
                    float w = misWeight(scene, y, s2, z, t2, h, c2, mergeEta);
                    density[s2] = pathDensity(y, z);
                    weight[s2] = w;
                    sum += w;
                    if (s2 == s) {  // the rebuilt subpaths give the weight the sample got
                        float w0 = misWeight(scene, light, s, camera, t, h, connection, mergeEta);
                        wc.worstRebuild = std::max(wc.worstRebuild, double(std::fabs(w - w0)));
                    }
                }
                for (int i = 1; mergeEta > 0 && i + 1 < int(x.size()); ++i) {
                    if (specularAt(scene, x[i])) continue;
                    std::vector<PathVertex> yMerge, zMerge, unused;
                    rebuild(scene, x, i + 1, h, yMerge, unused, mergeEta);  // the light subpath x_0..x_i
                    rebuild(scene, x, i, h, unused, zMerge, mergeEta);      // the camera subpath x_{n-1}..x_i
                    int t2 = int(x.size()) - i;
                    const PathVertex& xi = zMerge[t2 - 1];
                    float pdf, pdfReverse;
                    if (isBlack(evalBsdf(scene, xi.sp, xi.wo, yMerge[i].wo, Transport::Radiance, pdf, pdfReverse))) continue;
                    VcmPass::Stored record = storedVertex(h, yMerge, i, mergeEta, 0);
                    float w = mergeWeight(yMerge, record, zMerge, t2, h, mergeEta, pdf, pdfReverse);
                    float wWalked = mergeWeight(yMerge, record, zMerge, t2, h, mergeEta, pdf, pdfReverse, true);
                    wc.worstMergeWalk = std::max(wc.worstMergeWalk, double(std::fabs(w - wWalked)));
                    density[1000 + i] = pathDensity(yMerge, zMerge) * mergeEta;  // x_i's two densities: p_i p_light(x_i)
                    weight[1000 + i] = w;
                    sum += w;
                    wc.mergeShare += w;
                }
                wc.worstSum = std::max(wc.worstSum, std::fabs(sum - 1));
                for (auto [s2, w] : weight) wc.worstDefinition = std::max(wc.worstDefinition, std::fabs(w - definitionWeight(h, density, s2)));
                ++wc.paths;
                ++wc.lengths[int(x.size()) - 1];
            }
    }
    if (wc.paths > 0) wc.mergeShare /= wc.paths;
    return wc;
}

static Scene smallScene(const std::string& file) { return sceneAt(file, 16, 16); }

// The slides' "Implementation: Example: Maximums Heuristics" as a reference implementation: every
// strategy's sample SP adds SP.f / p with p = max over estimators of Probability(SP, estimator),
// computed from scratch. Literally, every strategy adds it; corrected (lecture notes, page 10),
// only the strategy whose own density is that maximum does (ties share, as misWeight's max).
// Returns the estimate of the image mean: camera contributions and splats alike, per sample.
static double slideMaxEstimate(const Scene& scene, int samples, bool literal) {
    RenderOptions opt = quietOptions(Method::BDPT, 1, 31);
    opt.maxDepth = 12;
    std::vector<PathVertex> camera, light, y, z;
    double total = 0;
    for (int i = 0; i < samples; ++i) {
        Rng rng = makeRng(31, uint64_t(i), 7);
        cameraSubpath(scene, opt, rng.uniform() * scene.camera.width, rng.uniform() * scene.camera.height, rng, camera);
        lightSubpath(scene, opt, rng, light);
        for (int t = 1; t <= int(camera.size()); ++t)
            for (int s = 0; s <= int(light.size()); ++s) {
                if (s + t < 2 || s + t - 2 > opt.maxDepth) continue;
                int pixel = 0;
                Connection connection;
                Vec3 c = connectStrategy(scene, light, s, camera, t, connection, pixel);  // SP.f / p_s
                if (isBlack(c)) continue;
                std::vector<PathVertex> x = joinPath(light, s, camera, t);
                std::map<int, double> density;
                for (int s2 = 0; s2 < int(x.size()); ++s2) {
                    if (!able(scene, x, s2)) continue;
                    rebuild(scene, x, s2, Heuristic::Max, y, z);
                    density[s2] = pathDensity(y, z);  // Probability(SP, estimator s2)
                }
                double pMax = 0;
                for (auto [s2, p] : density) pMax = std::max(pMax, p);
                double share = literal ? density.at(s) / pMax : definitionWeight(Heuristic::Max, density, s);
                total += (c.x + c.y + c.z) / 3 * share;  // SP.f / p_max = (SP.f / p_s) (p_s / p_max)
            }
    }
    return total / samples;
}

TEST_CASE("MIS: the weights of all strategies able to make a path sum to 1 and follow each heuristic's definition") {
    Scene glossy = parseScene("camera 0 1 -4  0 1 0  0 1 0  50  16 16\n"
                              "material white diffuse 0.8 0.8 0.8\nmaterial shiny glossy 0.9 0.9 0.9 20\n"
                              "quad -2 0 -2  4 0 0  0 0 4  white\nquad -2 0 2  4 0 0  0 3 0  shiny\n"
                              "sphere 0.5 0.6 0.5  0.6  shiny\nquad -0.5 2.9 -0.5  1 0 0  0 0 1  white emit 8 8 8\n", "glossy");
    struct Case { std::string name; Scene scene; };
    std::vector<Case> cases = {{"cornell (diffuse)", smallScene("scenes/cornell.scene")},
                               {"glossy", glossy},
                               {"cornell-glass (specular)", smallScene("scenes/cornell-glass.scene")},
                               {"cornell-point (point light)", smallScene("scenes/cornell-point.scene")},
                               {"shading-normals (bumps)", smallScene("scenes/shading-normals.scene")}};
    for (Heuristic h : {Heuristic::Balance, Heuristic::Power, Heuristic::Max, Heuristic::Uniform})
        for (Case& c : cases) {
            CAPTURE(c.name);
            CAPTURE(int(h));
            for (Roulette roulette : {Roulette::Throughput, Roulette::Albedo}) {
                CAPTURE(int(roulette));
                WeightCheck wc = checkWeights(c.scene, h, 400, 77, roulette);
                CHECK(wc.paths > 500);
                CHECK(wc.lengths.size() >= 4);     // paths of at least 4 different lengths
                CHECK(wc.worstSum < 1e-4);
                CHECK(wc.worstRebuild < 1e-3);
                // The ratio walk against the densities from scratch: an inverted ratio
                // (pdfFwd/pdfRev) still sums to 1, and power computed as balance would too.
                CHECK(wc.worstDefinition < 1e-3);
            }
        }
}

TEST_CASE("the slides' maximum-heuristic pseudo-code: literally it overcounts the furnace, corrected it gives 2") {
    Scene furnace = smallScene("scenes/furnace.scene");  // exact: 2 (1 - 0.5^13) with at most 12 bounces
    double literal = slideMaxEstimate(furnace, 3000, true), corrected = slideMaxEstimate(furnace, 3000, false);
    MESSAGE("furnace, the slide's loop: literal " << literal << ", corrected " << corrected << " (exact 2)");
    CHECK(corrected == doctest::Approx(2.0).epsilon(0.02));
    CHECK(literal > 3.0);  // 3.2 here: paths of k segments counted by up to k + 1 strategies
    // The renderer's max heuristic is the corrected loop.
    RenderOptions o = quietOptions(Method::BDPT, 64, 32);
    o.heuristic = Heuristic::Max;
    CHECK(imageMean(render(furnace, o).image) == doctest::Approx(corrected).epsilon(0.02));
}

// The same check for vcm: connections and merges together. mergeEta = pi r^2 N_light with the
// default radius and the light subpaths of the scene's own resolution, so that merges take a real
// share; sds adds the paths L S D S E, which only s = 0 and merges make.
TEST_CASE("vcm MIS: the weights of all connections and merges able to make a path sum to 1 and follow each heuristic's definition") {
    struct Case { std::string name; Scene scene; double mergeEta; };
    std::vector<Case> cases;
    for (const char* file : {"scenes/cornell.scene", "scenes/cornell-glass.scene", "scenes/sds.scene", "scenes/shading-normals.scene"}) {
        Scene full = loadScene(file);
        double eta = kPi * sqr(double(defaultMergeRadius(full))) * full.camera.width * full.camera.height;
        cases.push_back({file, smallScene(file), eta});
    }
    for (Heuristic h : {Heuristic::Balance, Heuristic::Power, Heuristic::Max, Heuristic::Uniform})
        for (Case& c : cases) {
            CAPTURE(c.name);
            CAPTURE(int(h));
            WeightCheck wc = checkWeights(c.scene, h, 300, 78, Roulette::Albedo, c.mergeEta);
            CHECK(wc.paths > 300);
            CHECK(wc.worstSum < 1e-4);
            CHECK(wc.worstRebuild < 1e-3);
            CHECK(wc.worstDefinition < 1e-3);
            CHECK(wc.worstMergeWalk < 1e-5);  // a merge's record gives what the walk along its light subpath gives
            CHECK(wc.mergeShare > 0.01);      // the merges took part
        }
}

TEST_CASE("bdpt equals nee and lt within noise on cornell, cornell-point and indirect") {
    for (const char* file : {"scenes/cornell.scene", "scenes/cornell-point.scene", "scenes/indirect.scene"}) {
        CAPTURE(file);
        Scene scene = sceneAt(file, 32, 32);
        RegionEstimate bdpt = renderRegions(scene, quietOptions(Method::BDPT, 256, 61), 4);
        RegionEstimate nee = renderRegions(scene, quietOptions(Method::NEE, 1024, 62), 4);
        CHECK(maxZ(bdpt, nee) < 4.5);
        if (std::string(file) != "scenes/cornell-point.scene") {  // lt alone also sees the point light itself
            RegionEstimate lt = renderRegions(scene, quietOptions(Method::LT, 1024, 63), 4);
            CHECK(maxZ(bdpt, lt) < 4.5);
        }
    }
}

static double meanPixelVariance(const RenderResult& r) {
    double v = 0;
    for (const Vec3& p : r.variance.pixels) v += average(p);
    return v / r.variance.pixels.size();
}

TEST_CASE("on indirect, bdpt's error at equal samples is far below nee's") {
    // Both are unbiased, so the squared error of a pixel is its variance: compare the per-pixel
    // variances of the mean at 128 samples per pixel. Measured: 25x (5.0x in RMSE).
    Scene scene = sceneAt("scenes/indirect.scene", 32, 32);
    double nee = meanPixelVariance(render(scene, quietOptions(Method::NEE, 128, 71)));
    double bdpt = meanPixelVariance(render(scene, quietOptions(Method::BDPT, 128, 72)));
    CHECK(nee / bdpt > 8);  // RMSE ratio > 2.8
}

// Per-strategy images of several independent renders: region means and their standard errors.
struct StrategyStats {
    std::vector<std::vector<double>> mean, stdError;  // [image][region]
};

static StrategyStats strategyStats(const Scene& scene, int maxLength, int renders, int spp) {
    const int W = scene.camera.width, H = scene.camera.height;
    std::vector<std::vector<std::vector<double>>> samples;  // [image][region][render]
    for (int k = 0; k < renders; ++k) {
        RenderOptions o = quietOptions(Method::BDPT, spp, 100 + k);
        o.strategyMaxLength = maxLength;
        RenderResult r = render(scene, o);
        samples.resize(r.strategyImages.size(), std::vector<std::vector<double>>(5));
        for (size_t img = 0; img < r.strategyImages.size(); ++img) {
            double region[5] = {0};
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    double v = average(r.strategyImages[img].at(x, y));
                    region[(y * 2 / H) * 2 + x * 2 / W] += v * 4 / (W * H);
                    region[4] += v / (W * H);
                }
            for (int q = 0; q < 5; ++q) samples[img][q].push_back(region[q]);
        }
    }
    StrategyStats st;
    for (auto& image : samples) {
        st.mean.emplace_back();
        st.stdError.emplace_back();
        for (auto& v : image) {
            double m = 0, q = 0;
            for (double x : v) m += x;
            m /= v.size();
            for (double x : v) q += (x - m) * (x - m);
            st.mean.back().push_back(m);
            st.stdError.back().push_back(std::sqrt(q / (v.size() - 1) / v.size()));
        }
    }
    return st;
}

TEST_CASE("per-strategy images: for one path length every strategy alone converges to the same image, and the MIS-weighted ones add up to it") {
    Scene scene = sceneAt("scenes/cornell.scene", 16, 16);
    const int L = 3, renders = 8;
    StrategyStats st = strategyStats(scene, L, renders, 128);
    REQUIRE(st.mean.size() == size_t(L * (L + 3)));
    for (int k = 2; k <= L; ++k) {
        CAPTURE(k);
        // The MIS-weighted strategies of length k, summed: bdpt's length-k term.
        std::vector<double> sumMean(5, 0), sumVar(5, 0);
        for (int s = 0; s <= k; ++s) {
            int img = 2 * strategyIndex(s, k + 1 - s) + 1;
            for (int q = 0; q < 5; ++q) { sumMean[q] += st.mean[img][q]; sumVar[q] += sqr(float(st.stdError[img][q])); }
        }
        CHECK(sumMean[4] > 0.005);  // there is light in it
        for (int s = 0; s <= k; ++s) {
            CAPTURE(s);
            int img = 2 * strategyIndex(s, k + 1 - s);
            double worst = 0;
            for (int q = 0; q < 5; ++q)  // weighted images are correlated; the variances are a rough bound
                worst = std::max(worst, std::fabs(st.mean[img][q] - sumMean[q]) / std::sqrt(sqr(float(st.stdError[img][q])) + 2 * sumVar[q]));
            CHECK(worst < 4.5);
        }
    }
}

TEST_CASE("the MIS-weighted strategy images add up to the rendered image exactly, when they cover every path length") {
    Scene scene = sceneAt("scenes/cornell.scene", 12, 12);
    RenderOptions o = quietOptions(Method::BDPT, 4, 5);
    o.maxDepth = 2;          // paths of at most 3 segments ...
    o.strategyMaxLength = 3; // ... all of them in the strategy images
    RenderResult r = render(scene, o);
    double worst = 0, total = 0;
    for (int y = 0; y < 12; ++y)
        for (int x = 0; x < 12; ++x) {
            Vec3 sum(0);
            for (int k = 1; k <= 3; ++k)
                for (int s = 0; s <= k; ++s) sum += r.strategyImages[2 * strategyIndex(s, k + 1 - s) + 1].at(x, y);
            worst = std::max(worst, double(maxComponent(Vec3(std::fabs(sum.x - r.image.at(x, y).x), std::fabs(sum.y - r.image.at(x, y).y),
                                                              std::fabs(sum.z - r.image.at(x, y).z)))));
            total += average(r.image.at(x, y));
        }
    CHECK(total > 1);
    CHECK(worst < 1e-4 * (1 + total / 144));
}

TEST_CASE("bdpt: the image is the same with 1 and 2 threads, and each heuristic agrees with nee") {
    CHECK(sameWithOneAndTwoThreads(sceneAt("scenes/cornell-glass.scene", 16, 16), quietOptions(Method::BDPT, 4)));
    Scene cornell = sceneAt("scenes/cornell.scene", 24, 24);
    RegionEstimate nee = renderRegions(cornell, quietOptions(Method::NEE, 1024, 81), 2);
    for (Heuristic h : {Heuristic::Power, Heuristic::Max, Heuristic::Uniform}) {
        RenderOptions o = quietOptions(Method::BDPT, 256, 82);
        o.heuristic = h;
        CAPTURE(int(h));
        CHECK(maxZ(nee, renderRegions(cornell, o, 2)) < 4.5);
    }
}

TEST_CASE("SDS: with a point light no method makes L S D S E; with an area light only s = 0 does") {
    // Camera and light sit inside solid glass balls: at most 3 bounces leaves exactly the paths
    // light -> glass surface -> room -> glass surface -> eye.
    Scene point = sceneAt("scenes/sds-point.scene", 16, 12);
    for (Method m : {Method::PT, Method::NEE, Method::LT, Method::IR, Method::BDPT}) {
        RenderOptions o = quietOptions(m, 8);
        o.maxDepth = 3;
        CAPTURE(int(m));
        CHECK(imageMean(render(point, o).image) == 0.0);
    }
    RenderOptions more = quietOptions(Method::BDPT, 8);  // two diffuse vertices: a connection exists
    CHECK(imageMean(render(point, more).image) > 0.05);
    Scene area = sceneAt("scenes/sds.scene", 16, 12);
    RenderOptions o = quietOptions(Method::BDPT, 64);
    o.maxDepth = 3;
    o.strategyMaxLength = 4;
    RenderResult r = render(area, o);
    CHECK(imageMean(r.image) > 0.05);
    for (int s = 0; s <= 4; ++s) {
        CAPTURE(s);
        double m = imageMean(r.strategyImages[2 * strategyIndex(s, 5 - s)]);  // k = 4, unweighted
        if (s == 0) CHECK(m > 0.05);
        else CHECK(m == 0.0);
    }
}

TEST_CASE("--strategies writes every (s,t) image, weighted and not, and the two pyramids") {
    std::string dir = "build/tmp_strategies";
    std::system(("rm -rf " + dir + " && mkdir -p " + dir).c_str());
    std::ostringstream so, se;
    CHECK(runCommandLine({"scenes/cornell.scene", "--method", "bdpt", "--res", "16x16", "--spp", "2", "--strategies", dir,
                          "--strategy-length", "3", "--out", dir + "/main.png"}, so, se) == 0);
    for (int k = 1; k <= 3; ++k)
        for (int s = 0; s <= k; ++s)
            for (const char* kind : {"_unweighted.png", "_weighted.pfm"}) {
                std::string f = dir + "/s" + std::to_string(s) + "_t" + std::to_string(k + 1 - s) + kind;
                CAPTURE(f);
                CHECK(fileExists(f));
            }
    CHECK(fileExists(dir + "/pyramid-unweighted.png"));
    CHECK(fileExists(dir + "/pyramid-weighted.png"));
    CHECK(!fileExists(dir + "/s0_t5_unweighted.png"));  // k = 4 > --strategy-length
    std::ostringstream so2, se2;
    CHECK(runCommandLine({"scenes/cornell.scene", "--method", "nee", "--strategies", dir}, so2, se2) == 2);
    CHECK(se2.str().find("--strategies applies to --method bdpt and vcm, not to --method nee") != std::string::npos);
    CHECK(runCommandLine({"scenes/cornell.scene", "--heuristic", "best"}, so2, se2) == 2);
    CHECK(se2.str().find("unknown heuristic 'best'") != std::string::npos);
}

TEST_CASE("the pyramid's rows are brightened to within half a stop of the brightest row") {
    Scene scene = sceneAt("scenes/cornell.scene", 16, 16);
    RenderOptions o = quietOptions(Method::BDPT, 16, 93);
    o.strategyMaxLength = 5;
    RenderResult r = render(scene, o);
    std::vector<int> stops = pyramidRowStops(r, 5);
    std::vector<double> row(6, 0);
    for (int k = 1; k <= 5; ++k)
        for (int s = 0; s <= k; ++s) row[k] += imageMean(r.strategyImages[2 * strategyIndex(s, k + 1 - s) + 1]);
    double brightest = *std::max_element(row.begin(), row.end());
    for (int k = 1; k <= 5; ++k) {
        CAPTURE(k);
        CHECK(stops[k] >= 0);
        CHECK(std::abs(std::log2(brightest / (row[k] * std::exp2(stops[k])))) <= 0.5 + 1e-9);
    }
    CHECK(stops[5] >= 3);  // cornell keeps about half the light per bounce
}

TEST_CASE("every heuristic gives Le/(1-a) = 2 in the furnace (ties between equal densities are shared)") {
    Scene scene = sceneAt("scenes/furnace.scene", 16, 16);
    for (Heuristic h : {Heuristic::Balance, Heuristic::Power, Heuristic::Max, Heuristic::Uniform}) {
        RenderOptions o = quietOptions(Method::BDPT, 128, 90);
        o.heuristic = h;
        CAPTURE(int(h));
        CHECK(imageMean(render(scene, o).image) == doctest::Approx(2.0).epsilon(0.005));
    }
}

TEST_CASE("bdpt equals nee --mis region by region where both have the technique: mirror and glass, two scales") {
    // The caustics reach nee only by s = 0 (noisy), so the regions are large: 2 x 2.
    for (std::string file : {"scenes/cornell-glass.scene", "scenes/glass-box.scene"}) {
        CAPTURE(file);
        Scene scene = sceneAt(file, 24, 24);
        RenderOptions mis = quietOptions(Method::NEE, 2048, 91);
        mis.mis = true;
        RegionEstimate nee = renderRegions(scene, mis, 2);
        RegionEstimate bdpt = renderRegions(scene, quietOptions(Method::BDPT, 512, 92), 2);
        MESSAGE(file << ": z " << maxZ(nee, bdpt) << " means " << nee.mean.back() << " " << bdpt.mean.back());
        CHECK(maxZ(nee, bdpt) < 4.5);
    }
}
