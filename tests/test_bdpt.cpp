// Bidirectional path tracing: MIS weights, agreement with the other methods, the per-strategy
// images.
#include "helpers.h"
#include "classroom/physics.h"

// -- MIS weights sum to 1 ------------------------------------------------------------------
// A full path x_0 (light) .. x_{n-1} (pinhole) made by a real bdpt connection is split again at
// every s' and its two subpaths rebuilt with the densities the generators would have stored;
// the weights of all strategies able to make the path must sum to 1.
// The path kit (joinPath, able, rebuild, pathDensity, subpathDensity) is classroom/physics.h's.
struct WeightCheck {
    int paths = 0;
    double worstSum = 0, worstRebuild = 0, worstDefinition = 0, worstMergeWalk = 0, mergeShare = 0;
    int merges = 0, mergesUnderflowed = 0;
    std::map<int, int> lengths;
};

// The weight that vcm's own merging code (mergeCameraVertices) gives the merge of the camera
// subpath z's last vertex with vertex i of the light subpath y, both ending at one point: a pass of
// that one light subpath, its record alone in the grid, and the weight read back from the
// strategy images' splats (c and c w). So the densities are passed as the code that makes merges
// passes them, not as this test would.
static float mergeWeightInPath(const Scene& scene, Heuristic h, double mergeEta, std::vector<PathVertex> y, int i,
                               std::vector<PathVertex> z) {
    y[i].beta = z.back().beta = Vec3(1);  // w does not depend on them; c, a float, then underflows less
    VcmPass vp;
    vp.mergeEta = mergeEta;
    vp.radius = 1e-4f * (1 + maxComponent(absVec(y[i].sp.p)));
    vp.paths = {Subpath(y)};
    vp.stored = {{y[i].sp.p, uint32_t(i), y.data()}};
    buildHashGrid(vp.grid, {y[i].sp.p}, vp.radius);
    RenderOptions opt;
    opt.heuristic = h;
    opt.maxDepth = 1000;
    RowOutput out;
    out.strategyMaxLength = 64;
    mergeCameraVertices(scene, opt, vp, z, 0, out);
    Vec3 c(0), cw(0);
    for (const StrategySplat& sp : out.strategySplats)
        if (sp.merge && sp.s == i && sp.t == int(z.size())) c += sp.value, cw += sp.value * sp.weight;
    float largest = maxComponent(c);
    return largest > 0 ? (c.x == largest ? cw.x : c.y == largest ? cw.y : cw.z) / largest : -1;  // -1: c underflowed
}

// fn(light, s, camera, t, connection, C) for every strategy of at least minVertices vertices that
// connects, over `samples` random pairs of subpaths (random stream `stream` of `seed`).
template <class Fn>
static void forEachConnectedStrategy(const Scene& scene, const RenderOptions& opt, int samples, uint64_t seed, uint64_t stream, int minVertices,
                                     Fn fn) {
    std::vector<PathVertex> camera, light;
    for (int i = 0; i < samples; ++i) {
        Rng rng = makeRng(seed, uint64_t(i), stream);
        cameraSubpath(scene, opt, rng.uniform() * scene.camera.width, rng.uniform() * scene.camera.height, rng, camera);
        lightSubpath(scene, opt, rng, light);
        for (int t = 1; t <= int(camera.size()); ++t)
            for (int s = 0; s <= int(light.size()); ++s) {
                if (s + t < minVertices || s + t - 2 > opt.maxDepth) continue;
                int pixel = 0;
                Connection connection;
                Vec3 c = connectStrategy(scene, light, s, camera, t, connection, pixel);
                if (!isBlack(c)) fn(light, s, camera, t, connection, c);
            }
    }
}

// mergeEta > 0: vcm's weights, where a merge at every non-specular vertex x_i (0 < i < n-1) is
// one more strategy, of density p_i * mergeEta * p_light(x_i) (the keys kMergeKey + i below).
static WeightCheck checkWeights(const Scene& scene, Heuristic h, int samples, uint64_t seed, Roulette roulette = RenderOptions().roulette,
                                double mergeEta = 0) {
    RenderOptions opt = quietOptions(Method::BDPT, 1, seed);
    opt.maxDepth = 6;
    opt.heuristic = h;
    opt.roulette = roulette;
    WeightCheck wc;
    // k >= 2: more than one strategy
    forEachConnectedStrategy(scene, opt, samples, seed, 7, 3, [&](const std::vector<PathVertex>& light, int s, const std::vector<PathVertex>& camera,
                                                                  int t, const Connection& connection, Vec3) {
        std::vector<PathVertex> x = joinPath(light, s, camera, t);
        double sum = 0;
        std::map<int, double> density, weight;
        for (int s2 = 0; s2 < int(x.size()); ++s2) {
            if (!able(scene, x, s2)) continue;
            float w = float(rebuiltWeight(scene, x, s2, h, mergeEta));
            density[s2] = pathDensity(scene, x, s2, roulette);
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
            rebuild(scene, x, i + 1, yMerge, unused);  // the light subpath x_0..x_i
            rebuild(scene, x, i, unused, zMerge);      // the camera subpath x_{n-1}..x_i
            int t2 = int(x.size()) - i;
            const PathVertex& xi = zMerge[t2 - 1];
            float pdf, pdfReverse;
            if (isBlack(evalBsdf(scene, xi.sp, xi.wo, yMerge[i].wo, Transport::Radiance, pdf, pdfReverse))) continue;
            float w = mergeWeightInPath(scene, h, mergeEta, yMerge, i, zMerge);
            float wWalked = mergeWeight(scene, yMerge, i, zMerge, t2, h, mergeEta, pdf, pdfReverse);
            if (w < 0) w = wWalked, ++wc.mergesUnderflowed;  // a glossy lobe's f of 1e-30: nothing to splat
            wc.worstMergeWalk = std::max(wc.worstMergeWalk, double(std::fabs(w - wWalked)));
            density[kMergeKey + i] = mergeDensity(scene, x, i, roulette, mergeEta);
            weight[kMergeKey + i] = w;
            sum += w;
            wc.mergeShare += w;
            ++wc.merges;
        }
        wc.worstSum = std::max(wc.worstSum, std::fabs(sum - 1));
        for (auto [s2, w] : weight) wc.worstDefinition = std::max(wc.worstDefinition, std::fabs(w - definitionWeight(h, density, s2)));
        ++wc.paths;
        ++wc.lengths[int(x.size()) - 1];
    });
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
    double total = 0;
    forEachConnectedStrategy(scene, opt, samples, 31, 7, 2, [&](const std::vector<PathVertex>& light, int s, const std::vector<PathVertex>& camera,
                                                                 int t, const Connection&, Vec3 c) {  // c = SP.f / p_s
        std::vector<PathVertex> x = joinPath(light, s, camera, t);
        std::map<int, double> density = strategyDensities(scene, x, opt.roulette);  // Probability(SP, estimator)
        double pMax = 0;
        for (auto [s2, p] : density) pMax = std::max(pMax, p);
        double share = literal ? density.at(s) / pMax : definitionWeight(Heuristic::Max, density, s);
        total += (c.x + c.y + c.z) / 3 * share;  // SP.f / p_max = (SP.f / p_s) (p_s / p_max)
    });
    return total / samples;
}

TEST_CASE("MIS: the weights of all strategies able to make a path sum to 1 and follow each heuristic's definition") {
    Scene glossy = parseScene("camera 0 1 -4  0 1 0  0 1 0  50  16 16\n"
                              "material white diffuse 0.8 0.8 0.8\nmaterial shiny glossy 0.9 0.9 0.9 20\n"
                              "quad -2 0 -2  4 0 0  0 0 4  white\nquad -2 0 2  4 0 0  0 3 0  shiny\n"
                              "sphere 0.5 0.6 0.5  0.6  shiny\nquad -0.5 2.9 -0.5  1 0 0  0 0 1  white emit 8 8 8\n", "glossy");
    struct Case { std::string name; Scene scene; int samples = 400; };
    std::vector<Case> cases = {{"cornell (diffuse)", smallScene("scenes/cornell.scene")},
                               {"glossy", glossy},
                               {"cornell-glass (specular)", smallScene("scenes/cornell-glass.scene")},
                               {"refraction (one interface: camera and floor under water)", smallScene("scenes/refraction.scene"), 1000},
                               {"cornell-point (point light)", smallScene("scenes/cornell-point.scene")},
                               // A point light in a box of 1 m: densities of order one, where a point light counted as
                               // a strategy (s = 0 hitting it) takes visible weight; at cornell-point's millimetres it hides.
                               {"point light in metres", parseScene("camera 0.5 0.5 -1.2  0.5 0.5 0.5  0 1 0  50  16 16\n"
                                                                    "material white diffuse 0.7 0.7 0.7\nmaterial red diffuse 0.6 0.1 0.1\n"
                                                                    "quad 0 0 0  0 0 1  1 0 0  white\nquad 0 1 0  1 0 0  0 0 1  white\n"
                                                                    "quad 0 0 1  1 0 0  0 1 0  white\nquad 0 0 0  0 1 0  0 0 1  red\n"
                                                                    "quad 1 0 0  0 0 1  0 1 0  white\npointlight 0.5 0.9 0.5  1 1 1\n",
                                                                    "point-metres")},
                               {"shading-normals (bumps)", smallScene("scenes/shading-normals.scene")}};
    for (Heuristic h : {Heuristic::Balance, Heuristic::Power, Heuristic::Max, Heuristic::Uniform})
        for (Case& c : cases) {
            CAPTURE(c.name);
            CAPTURE(int(h));
            for (Roulette roulette : {Roulette::Throughput, Roulette::Albedo}) {
                CAPTURE(int(roulette));
                WeightCheck wc = checkWeights(c.scene, h, c.samples, 77, roulette);
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

// -- SmallVCM's recursion (notes, page 10's exercise) --------------------------------------
// Beyond the two vertices next to the connection the walk is the same for every connection to a
// vertex, so each subpath can sum it once per vertex (Georgiev's report, eq. 34-36, in pbrt's
// densities):  S_i = ratio_i^e ([strategy i able] + [merge at i] (mergeEta pdfFwd_i)^e + S_{i-1}),
// ratio_i = pdfRev_i / pdfFwd_i, e = 1 balance, 2 power, 0 uniform, and a connection's weight
// needs the junction's four densities and S of the vertex beyond: O(1) instead of O(k). Written
// here from the formula, apart from misWalk, it must give the walk's weights. The broken variant
// counts a strategy at every vertex, delta or not (the fireflies of Mitsuba #132).
static double misPowerOf(Heuristic h, double r) { return h == Heuristic::Power ? r * r : h == Heuristic::Uniform ? 1 : r; }

static std::vector<double> recursiveSums(Heuristic h, const std::vector<PathVertex>& path, double mergeEta, bool countDeltas) {
    std::vector<double> S(path.size());
    for (size_t i = 0; i < path.size(); ++i) {
        const PathVertex& v = path[i];
        bool able = i == 0 ? v.type == PathVertex::Light && !v.deltaPosition : countDeltas || (!v.delta && !path[i - 1].delta);
        bool mergeable = mergeEta > 0 && v.type == PathVertex::Surface && !v.delta;
        double terms = able + (mergeable ? misPowerOf(h, mergeEta * v.pdfFwd) : 0) + (i > 0 ? S[i - 1] : 0);
        double ratio = misPowerOf(h, v.pdfFwd > 0 ? v.pdfRev / v.pdfFwd : 0);
        S[i] = ratio == 0 || terms == 0 ? 0 : ratio * terms;
    }
    return S;
}

// w_{s,t} from the sums: the junction's vertices (the last two of each subpath) walked, the rest
// read from S.
static double recursiveWeight(const Scene& scene, const std::vector<PathVertex>& light, int s, const std::vector<PathVertex>& camera, int t,
                              Heuristic h, const Connection& c, double mergeEta, bool countDeltas) {
    std::vector<double> SL = recursiveSums(h, light, mergeEta, countDeltas), SC = recursiveSums(h, camera, mergeEta, countDeltas);
    Junction j = connectionJunction(scene, light, s, camera, t, c);
    double sum = 1;
    auto side = [&](const std::vector<PathVertex>& v, int n, const std::vector<double>& S, double endRev, double beforeRev, bool camSide) {
        double r = 1;
        for (int i = n - 1; i >= 0 && i >= n - 2; --i) {
            if (camSide && i == 0) return;  // the pinhole is never sampled by a light subpath
            r *= (i == n - 1 ? endRev : beforeRev) / v[i].pdfFwd;
            bool deltaHere = i != n - 1 && v[i].delta, deltaBefore = i > 0 ? (i - 1 != n - 1 && v[i - 1].delta) : v[0].deltaPosition;
            if (camSide) deltaBefore = i - 1 != n - 1 && v[i - 1].delta;
            if (countDeltas || (!deltaHere && !deltaBefore)) sum += misPowerOf(h, r);
            bool mergeable = mergeEta > 0 && !deltaHere && (camSide ? !(s == 0 && i == n - 1) : i > 0);
            if (mergeable) sum += misPowerOf(h, r * mergeEta * v[i].pdfFwd);
        }
        int beyond = n - 3;
        if (beyond >= (camSide ? 1 : 0)) sum += misPowerOf(h, r) * S[beyond];
    };
    side(camera, t, SC, j.ptRev, j.ptMinusRev, true);
    side(light, s, SL, j.qsRev, j.qsMinusRev, false);
    return 1 / sum;
}

static double worstRecursionError(const Scene& scene, Heuristic h, double mergeEta, bool countDeltas, int* compared) {
    RenderOptions opt = quietOptions(Method::BDPT, 1, 5);
    opt.maxDepth = 8;
    double worst = 0;
    forEachConnectedStrategy(scene, opt, 300, 5, 9, 3, [&](const std::vector<PathVertex>& light, int s, const std::vector<PathVertex>& camera,
                                                           int t, const Connection& c, Vec3) {
        double walk = misWeight(scene, light, s, camera, t, h, c, mergeEta);
        double recursive = recursiveWeight(scene, light, s, camera, t, h, c, mergeEta, countDeltas);
        worst = std::max(worst, std::fabs(walk - recursive) / std::max(1e-3, walk));
        ++*compared;
    });
    return worst;
}

TEST_CASE("SmallVCM's recursion (page 10's exercise) gives the walk's weights on every scene; counting deltas does not") {
    for (const char* file : {"scenes/cornell.scene", "scenes/cornell-glass.scene", "scenes/cornell-point.scene", "scenes/glass-box.scene",
                             "scenes/indirect.scene", "scenes/refraction.scene", "scenes/sds.scene", "scenes/shading-normals.scene",
                             "scenes/door.scene", "scenes/energy-generator.scene", "scenes/furnace.scene"}) {
        Scene scene = smallScene(file);
        Scene full = loadScene(file);
        double eta = kPi * sqr(double(defaultMergeRadius(full))) * full.camera.width * full.camera.height;
        std::string name = file;
        for (Heuristic h : {Heuristic::Balance, Heuristic::Power, Heuristic::Uniform})
            for (double mergeEta : {0.0, eta}) {
                CAPTURE(name);
                CAPTURE(int(h));
                CAPTURE(mergeEta);
                int compared = 0;
                CHECK(worstRecursionError(scene, h, mergeEta, false, &compared) < 1e-4);
                CHECK(compared > 30);  // sds and door: few random subpaths connect
            }
    }
    int compared = 0;
    for (const char* file : {"scenes/cornell-glass.scene", "scenes/glass-box.scene"}) {  // mirrors and glass: deltas on the paths
        double error = worstRecursionError(smallScene(file), Heuristic::Balance, 0, true, &compared);
        MESSAGE(std::string(file) << ": counting deltas moves a weight by up to " << 100 * error << "%");
        CHECK(error > 0.1);
    }
}

// -- Specular chains: the weights against the true densities -------------------------------
// A path L S..S D E (lamp, specular chain, diffuse point, pinhole) is made by two strategies
// only: s = 0 (the camera path through D and the chain hits the lamp) and t = 1 (the light path
// through the chain lands on D, which is connected to the pinhole). Their true area densities,
//   p_{t=1} = p_A(L) (cos_L / pi) |d omega_L / dA_D|       p_{s=0} = p_cam(D) q_D (cos_D / pi) |d omega_D / dA_L|,
// come here from outside the renderer: the chain's Jacobians from unfolding a planar mirror
// (|d omega / dA| = cos / (unfolded length)^2) or by central finite differences of this test's
// own Snell tracer, and p_cam(D) from the pinhole's 1/(A cos^3) (test_sampling checks it).

// The test's tracer works in double: a finite difference of float positions loses half its digits.
struct D3 {
    double x = 0, y = 0, z = 0;
    D3() = default;
    D3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
    explicit D3(Vec3 v) : x(v.x), y(v.y), z(v.z) {}
    D3 operator+(D3 b) const { return {x + b.x, y + b.y, z + b.z}; }
    D3 operator-(D3 b) const { return {x - b.x, y - b.y, z - b.z}; }
    D3 operator*(double s) const { return {x * s, y * s, z * s}; }
    Vec3 f() const { return Vec3(float(x), float(y), float(z)); }
};
static double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
static double length(D3 a) { return std::sqrt(dot(a, a)); }
static D3 normalize(D3 a) { return a * (1 / length(a)); }

static D3 refractThrough(D3 d, D3 n, double etaFrom, double etaTo, bool& ok) {  // d travelling, n either side
    if (dot(d, n) > 0) n = n * -1;  // n against d
    double eta = etaFrom / etaTo, c = -dot(d, n), k = 1 - eta * eta * (1 - c * c);
    ok = k > 0;
    return ok ? normalize(d * eta + n * (eta * c - std::sqrt(k))) : D3();
}

struct Chain {  // one of the test scenes' specular chains, traced by the test alone
    virtual ~Chain() = default;
    virtual bool trace(D3 o, D3 d, std::vector<D3>& points) const = 0;  // o, the chain's points, the end
};

// A planar interface y = h between air above (eta 1) and eta below, then the plane y = end.
struct FlatInterface : Chain {
    double h, eta, end;
    FlatInterface(double h_, double eta_, double end_) : h(h_), eta(eta_), end(end_) {}
    bool trace(D3 o, D3 d, std::vector<D3>& pts) const override {
        pts = {o};
        double t = (h - o.y) / d.y;
        if (!(t > 0)) return false;
        D3 s = o + d * t;
        bool ok, fromAbove = o.y > h;
        D3 d2 = refractThrough(d, D3(0, 1, 0), fromAbove ? 1 : eta, fromAbove ? eta : 1, ok);
        double t2 = (end - s.y) / d2.y;
        if (!ok || !(t2 > 0)) return false;
        pts.push_back(s);
        pts.push_back(s + d2 * t2);
        return true;
    }
};

// A glass ball (centre c, radius r, index eta) crossed once, then the plane y = end.
struct Ball : Chain {
    D3 c;
    double r, eta, end;
    Ball(D3 c_, double r_, double eta_, double end_) : c(c_), r(r_), eta(eta_), end(end_) {}
    double hit(D3 o, D3 d, bool nearest) const {
        D3 oc = o - c;
        double b = dot(oc, d), disc = b * b - (dot(oc, oc) - r * r);
        if (disc < 0) return -1;
        return nearest ? -b - std::sqrt(disc) : -b + std::sqrt(disc);
    }
    bool trace(D3 o, D3 d, std::vector<D3>& pts) const override {
        pts = {o};
        double t = hit(o, d, true);
        if (!(t > 0)) return false;
        D3 p1 = o + d * t;
        bool ok;
        D3 d1 = refractThrough(d, normalize(p1 - c), 1, eta, ok);
        if (!ok) return false;
        D3 p2 = p1 + d1 * hit(p1, d1, false);
        D3 d2 = refractThrough(d1, normalize(p2 - c), eta, 1, ok);
        double t3 = (end - p2.y) / d2.y;
        if (!ok || !(t3 > 0)) return false;
        pts.push_back(p1);
        pts.push_back(p2);
        pts.push_back(p2 + d2 * t3);
        return true;
    }
};

// |dA_end / d omega| at the chain's start along d: central differences in two tangent directions
// (the end plane is horizontal, so the area is the cross product's length).
static double areaPerSolidAngle(const Chain& chain, D3 o, D3 d, double eps = 1e-5) {
    D3 t1 = normalize(std::fabs(d.x) > 0.5 ? cross(d, D3(0, 1, 0)) : cross(d, D3(1, 0, 0))), t2 = cross(d, t1);
    auto end = [&](double u, double v) {
        std::vector<D3> pts;
        REQUIRE(chain.trace(o, normalize(d + t1 * u + t2 * v), pts));
        return pts.back();
    };
    D3 du = (end(eps, 0) - end(-eps, 0)) * (0.5 / eps), dv = (end(0, eps) - end(0, -eps)) * (0.5 / eps);
    return length(cross(du, dv));
}

static int shapeAt(const Scene& scene, Vec3 p) {  // the shape whose surface holds p
    for (size_t i = 0; i < scene.shapes.size(); ++i) {
        const Shape& s = scene.shapes[i];
        if (s.type == Shape::Sphere && std::fabs(length(p - s.p) - s.radius) < 1e-4f * s.radius) return int(i);
        if (s.type == Shape::Quad) {
            Vec3 rel = p - s.p, w = quadW(s.u, s.v);
            float a = dot(w, cross(rel, s.v)), b = dot(w, cross(s.u, rel));
            if (std::fabs(dot(rel, s.normal)) < 1e-4f * (1 + length(s.u)) && a >= 0 && a <= 1 && b >= 0 && b <= 1) return int(i);
        }
    }
    return -1;
}

// The path lamp -> chain -> D -> pinhole as bdpt's joined vertices x_0..x_{n-1}.
// Each surface vertex continues with the albedo roulette's q, as the walkers store it.
static std::vector<PathVertex> chainPath(const Scene& scene, const std::vector<D3>& points) {
    std::vector<PathVertex> x;
    for (D3 p : points) {
        PathVertex v;
        int shape = shapeAt(scene, p.f());
        REQUIRE(shape >= 0);
        v.sp = makeSurfacePoint(scene.shapes[shape], shape, p.f(), false);
        v.light = scene.shapes[shape].light;
        v.continuation = albedoContinuation(scene, v.sp);
        x.push_back(v);
    }
    x[0].type = PathVertex::Light;
    PathVertex eye;
    eye.type = PathVertex::Camera;
    eye.sp.p = scene.camera.eye;
    x.push_back(eye);
    return x;
}

static double pinholeAreaDensity(const Camera& cam, D3 p, D3 n) {  // 1/(A cos^3) |cos_p| / d^2
    D3 d = p - D3(cam.eye);
    double dist2 = dot(d, d), cosCam = dot(normalize(d), D3(cam.forward));
    double filmArea = sqr(2 * double(cam.tanHalfFov)) * cam.aspect;
    return 1 / (filmArea * cosCam * cosCam * cosCam) * std::fabs(dot(n, normalize(d))) / dist2;
}

// The weights of s = 0 and t = 1 on the path `points` (lamp, chain, D), against the heuristic of
// the true densities pS0 and pT1.
static void checkChainWeights(const Scene& scene, const std::vector<D3>& points, double pS0, double pT1) {
    std::vector<PathVertex> x = chainPath(scene, points);
    const int n = int(x.size());
    std::map<int, double> density = {{0, pS0}, {n - 1, pT1}};
    for (Heuristic h : {Heuristic::Balance, Heuristic::Power, Heuristic::Max, Heuristic::Uniform})
        for (int s : {0, n - 1}) {
            CAPTURE(int(h));
            CAPTURE(s);
            CHECK(rebuiltWeight(scene, x, s, h) == doctest::Approx(definitionWeight(h, density, s)).epsilon(1e-4));
        }
}

TEST_CASE("specular chains: the weights of s = 0 and t = 1 follow the true densities (mirror unfolded, one interface, a glass ball)") {
    // The default roulette (albedo) puts D's q into s = 0 alone: the chain's q appear in both.
    REQUIRE(RenderOptions().roulette == Roulette::Albedo);
    SUBCASE("a planar mirror: unfolded, the chain's geometry is cos cos / (unfolded length)^2") {
        Scene scene = parseScene("camera 0 1.2 -3  0 0.4 0  0 1 0  50  32 32\n"
                                 "material white diffuse 0.7 0.7 0.7\nmaterial mirror mirror 0.9 0.9 0.9\n"
                                 "quad -1 0 -1  2 0 0  0 0 2  white\n"             // floor y = 0, up
                                 "quad -1 0 1  0 2 0  2 0 0  mirror\n"             // back wall z = 1, a mirror
                                 "quad -0.3 1.5 -0.2  0.6 0 0  0 0 0.4  white emit 5 5 5\n", "mirror");  // lamp, facing down
        D3 L(0.05, 1.5, 0.05), D(-0.2, 0, 0.3);
        D3 image(L.x, L.y, 2 - L.z);  // L mirrored in z = 1
        D3 M = D + (image - D) * ((1 - D.z) / (image.z - D.z));
        double unfolded2 = dot(image - D, image - D);
        D3 wL = normalize(M - L), wD = normalize(M - D);  // leaving L, leaving D
        double cosL = std::fabs(wL.y), cosD = std::fabs(wD.y), pLamp = 1 / (0.6 * 0.4), q = 0.7;
        double pT1 = pLamp * cosL / kPi * cosD / unfolded2;
        double pS0 = pinholeAreaDensity(scene.camera, D, D3(0, 1, 0)) * q * cosD / kPi * cosL / unfolded2;
        MESSAGE("mirror: p_{s=0} / p_{t=1} = " << pS0 / pT1);
        checkChainWeights(scene, {L, M, D}, pS0, pT1);
    }
    // The pool: the sky (eta 1) over water (1.33), the floor and the camera under water. Etendue
    // eta^2 cos dA d omega makes p_{s=0}/p_{t=1} = p_cam(D) q_D / (p_A(L) 1.33^2): from one
    // interface the chain's geometry does not cancel, and the ratio differs from what a delta of
    // 1 per steradian gives by eta^2 cos_water / cos_air.
    SUBCASE("one interface (the pool), by finite differences") {
        Scene scene = sceneAt("scenes/refraction.scene", 64, 48);
        const double eta = 1.33, pLamp = 1 / (120.0 * 120.0), q = 0.7;
        for (D3 start : {D3(1, 6, 4), D3(-3, 6, 2)}) {
            CAPTURE(start.x);
            D3 wL = normalize(D3(0.3, 0, 1) - start);
            std::vector<D3> pts;
            REQUIRE(FlatInterface(0, eta, -3).trace(start, wL, pts));
            D3 D = pts.back(), wD = normalize(pts[1] - D);
            double pCam = pinholeAreaDensity(scene.camera, D, D3(0, 1, 0));
            double pT1 = pLamp * std::fabs(wL.y) / kPi / areaPerSolidAngle(FlatInterface(0, eta, -3), start, wL);
            double pS0 = pCam * q * std::fabs(wD.y) / kPi / areaPerSolidAngle(FlatInterface(0, eta, 6), D, wD);
            REQUIRE(pS0 > 0);
            CHECK(pS0 / pT1 == doctest::Approx(pCam * q / (pLamp * eta * eta)).epsilon(1e-5));  // etendue, checked
            checkChainWeights(scene, pts, pS0, pT1);
        }
    }
    SUBCASE("a glass ball crossed once (glass-box's caustic), by finite differences") {
        Scene scene = sceneAt("scenes/glass-box.scene", 64, 64);
        Ball ball(D3(-0.55, 0.5, -0.35), 0.5, 1.6, 0), back(D3(-0.55, 0.5, -0.35), 0.5, 1.6, 2.55);
        const double pLamp = 1 / (0.5 * 0.5), q = 0.73;
        for (D3 target : {D3(-0.45, 0.5, -0.3), D3(-0.7, 0.6, -0.4)}) {
            CAPTURE(target.x);
            D3 L(0.1, 2.55, -0.05), wL = normalize(target - L);
            std::vector<D3> pts;
            REQUIRE(ball.trace(L, wL, pts));
            D3 D = pts.back(), wD = normalize(pts[2] - D);
            double pCam = pinholeAreaDensity(scene.camera, D, D3(0, 1, 0));
            double pT1 = pLamp * std::fabs(wL.y) / kPi / areaPerSolidAngle(ball, L, wL);
            double pS0 = pCam * q * std::fabs(wD.y) / kPi / areaPerSolidAngle(back, D, wD);
            REQUIRE(pS0 > 0);
            // Both ends in air: the ratio of the issue, p_cam(D) q_D / p_A(L), about 0.005 here.
            CHECK(pS0 / pT1 == doctest::Approx(pCam * q / pLamp).epsilon(1e-5));
            checkChainWeights(scene, pts, pS0, pT1);
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
            // The merging code's own weight (its densities passed as it passes them) is the walk
            // along the light subpath with the densities this test computes; passing the camera
            // BSDF's forward and reverse densities swapped moved cornell by -0.26%, regions by
            // up to -2.6%, which no image comparison caught.
            CHECK(wc.worstMergeWalk < 1e-5);
            CHECK(wc.mergesUnderflowed < wc.merges / 10);
            CHECK(wc.mergeShare > 0.01);      // the merges took part
        }
}

TEST_CASE("bdpt equals nee and lt within noise on cornell, cornell-point and indirect") {
    for (const char* file : {"scenes/cornell.scene", "scenes/cornell-point.scene", "scenes/indirect.scene"}) {
        CAPTURE(file);
        Scene scene = sceneAt(file, 32, 32);
        // nee and lt at twice bdpt's passes (each side's own standard error enters maxZ)
        RegionEstimate bdpt = renderRegions(scene, quietOptions(Method::BDPT, 256, 61), 4);
        RegionEstimate nee = renderRegions(scene, quietOptions(Method::NEE, 512, 62), 4);
        CHECK(maxZ(bdpt, nee) < 4.5);
        if (std::string(file) != "scenes/cornell-point.scene") {  // lt alone also sees the point light itself
            RegionEstimate lt = renderRegions(scene, quietOptions(Method::LT, 512, 63), 4);
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
        samples.resize(r.strategies.images.size(), std::vector<std::vector<double>>(5));
        for (size_t img = 0; img < r.strategies.images.size(); ++img) {
            double region[5] = {0};
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    double v = average(r.strategies.images[img].at(x, y));
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
            int img = 2 * StrategyImages::index(s, k + 1 - s) + 1;
            for (int q = 0; q < 5; ++q) { sumMean[q] += st.mean[img][q]; sumVar[q] += sqr(float(st.stdError[img][q])); }
        }
        CHECK(sumMean[4] > 0.005);  // there is light in it
        for (int s = 0; s <= k; ++s) {
            CAPTURE(s);
            int img = 2 * StrategyImages::index(s, k + 1 - s);
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
                for (int s = 0; s <= k; ++s) sum += r.strategies.at(s, k + 1 - s, true).at(x, y);
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
        double m = imageMean(r.strategies.at(s, 5 - s, false));  // k = 4, unweighted
        if (s == 0) CHECK(m > 0.05);
        else CHECK(m == 0.0);
    }
}

TEST_CASE("--strategies writes every (s,t) image, weighted and not, and the two pyramids") {
    std::string dir = "build/tmp/strategies";
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
    std::vector<int> stops = pyramidRowStops(r.strategies);
    std::vector<double> row(6, 0);
    for (int k = 1; k <= 5; ++k)
        for (int s = 0; s <= k; ++s) row[k] += imageMean(r.strategies.at(s, k + 1 - s, true));
    double brightest = *std::max_element(row.begin(), row.end());
    for (int k = 1; k <= 5; ++k) {
        CAPTURE(k);
        CHECK(stops[k] >= 0);
        CHECK(std::abs(std::log2(brightest / (row[k] * std::exp2(stops[k])))) <= 0.5 + 1e-9);
    }
    CHECK(stops[5] >= 3);  // cornell keeps about half the light per bounce
}

TEST_CASE("the pyramid's labels never cover a tile: every tile in the montage is its image, pixel for pixel") {
    // Labels drawn on the tiles hid row 1, the lamp at the top of the frame (second teacher's read).
    for (Method m : {Method::BDPT, Method::VCM}) {
        CAPTURE(methodName(m));
        Scene scene = sceneAt("scenes/cornell.scene", 96, 64);  // labels at scale 2
        RenderOptions o = quietOptions(m, 1, 95);
        o.strategyMaxLength = 3;
        RenderResult r = render(scene, o);
        const bool merges = r.strategies.merges;
        CHECK(merges == (m == Method::VCM));
        PyramidLayout layout(96, 64, 3, merges);
        std::vector<int> stops = pyramidRowStops(r.strategies);
        for (int weighted = 0; weighted < 2; ++weighted) {
            std::vector<unsigned char> canvas = pyramidCanvas(r.strategies, 0, weighted, layout, stops);
            int tiles = 0, labelPixels = 0;
            for (int k = 1; k <= 3; ++k)
                for (int s = 0; s <= k; ++s) {
                    std::vector<unsigned char> tile = toSRGBBytes(r.strategies.at(s, k + 1 - s, weighted), float(stops[k]));
                    int x0 = layout.tileX(k, s, 3), y0 = layout.tileY(k), differ = 0;
                    for (int y = 0; y < 64; ++y)
                        for (int x = 0; x < 3 * 96; ++x) differ += canvas[3 * (size_t(y0 + y) * layout.canvasW + x0) + x] != tile[3 * size_t(y) * 96 + x];
                    CHECK(differ == 0);
                    for (int y = y0 - layout.strip; y < y0; ++y)  // the label is there, above the tile
                        for (int x = x0; x < x0 + 20; ++x) labelPixels += canvas[3 * (size_t(y) * layout.canvasW + x)] > 160;  // white text on grey 40
                    ++tiles;
                }
            CHECK(tiles == 9);
            CHECK(labelPixels > 9 * 20);
        }
    }
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

// The caustic under glass-box's glass ball, seen directly (L S S D E): only s = 0 and t = 1 make
// it, and with the true densities t = 1 (light tracing) takes nearly all of it, so bdpt's error
// there is lt's alone at equal samples. With pbrt's densities through specular vertices
// (--delta-density-one: the delta as an area density of 1) s = 0 keeps most of that light, and
// bdpt's error in the block is about 100x lt's. Both are unbiased: the squared error of a pixel
// is the variance of its mean, here over the spread of independent seeds. Six seeds estimate a
// variance this spiky to about +-30% (bdpt/lt over four sets of seeds and both samplers:
// 0.88-1.35), so "equal" is checked as below 1.6x, which the mistake exceeds 60-fold.
TEST_CASE("a caustic seen directly: bdpt's error there is light tracing's at equal samples") {
    Scene scene = sceneAt("scenes/glass-box.scene", 128, 128);
    const int seeds = 6;
    // The pixels of the caustic's block (x 80-99, y 114-116) that see the floor alone: at its
    // edge the ball's silhouette shows the caustic through glass (L S S D S E), which only s = 0
    // makes, and its noise is not the question here.
    std::vector<std::pair<int, int>> block;
    for (int y = 114; y < 117; ++y)
        for (int x = 80; x < 100; ++x) {
            bool floorOnly = true;
            for (float u : {0.0f, 0.5f, 0.999f})
                for (float v : {0.0f, 0.5f, 0.999f}) floorOnly = floorOnly && intersect(scene, cameraRay(scene.camera, x + u, y + v)).shape == 0;
            if (floorOnly) block.push_back({x, y});
        }
    REQUIRE(block.size() >= 30);
    auto blockError = [&](Method m, bool deltaDensityOne) {
        Scene variant = scene;
        variant.conventions.deltaDensityOne = deltaDensityOne;
        std::vector<Image> images;
        for (int k = 0; k < seeds; ++k) images.push_back(render(variant, quietOptions(m, 8, 500 + k)).image);
        SpreadOverSeeds s = spreadOverSeeds(images, block);
        return std::make_pair(s.varianceSum, s.mean);
    };
    auto [bdpt, bdptMean] = blockError(Method::BDPT, false);
    auto [lt, ltMean] = blockError(Method::LT, false);
    auto [mistake, mistakeMean] = blockError(Method::BDPT, true);
    MESSAGE("caustic block (" << block.size() << " pixels): squared error bdpt " << bdpt << ", lt " << lt << ", bdpt --delta-density-one "
            << mistake << " (means " << bdptMean << ", " << ltMean << ", " << mistakeMean << ")");
    CHECK(ltMean > 0.5);  // the block is in the caustic
    CHECK(bdpt < 1.6 * lt);
    CHECK(mistake > 10 * lt);
    // Who carries the caustic: the MIS-weighted images of s = 0 and t = 1 for k = 4 (L S S D E).
    for (bool deltaDensityOne : {false, true}) {
        Scene variant = scene;
        variant.conventions.deltaDensityOne = deltaDensityOne;
        RenderOptions o = quietOptions(Method::BDPT, 16, 510);
        o.strategyMaxLength = 4;
        RenderResult r = render(variant, o);
        double s0 = 0, t1 = 0;
        for (auto [x, y] : block) {
            s0 += average(r.strategies.at(0, 5, true).at(x, y));
            t1 += average(r.strategies.at(4, 1, true).at(x, y));
        }
        double share = s0 / (s0 + t1);
        MESSAGE(std::string(deltaDensityOne ? "--delta-density-one" : "true densities") << ": s = 0 carries " << 100 * share << "% of L S S D E in the block, t = 1 "
                << 100 * (1 - share) << "%");
        if (deltaDensityOne) CHECK(share > 0.5);
        else CHECK(share < 0.05);
    }
}
