// classroom/physics.h: what the renderer's densities and weights *must be*, from their
// definitions, written once for every judge of the renderer: the tests, the homework's grader, the
// page's path view and the notes' worked path. Nothing here calls the code it judges for the
// quantity judged: a path's densities come from positions, materials and the samplers' own
// densities; a heuristic's weights from those densities. The file that includes it has included
// bdpt.cpp. `make homework` copies it beside the grader: it holds no line of a task's solution.
#pragma once
#include <map>
#include <vector>

// ---- the heuristics (notes, page 10)

// A heuristic's weight of strategy s by its definition, from the densities p of all the strategies
// able to make the path: balance p_s / sum p, power p_s^2 / sum p^2, max 1 for the largest (the
// strategies within a factor 1 + 1e-4 of the largest share it), uniform 1 / count.
inline double definitionWeight(Heuristic h, const std::map<int, double>& p, int s) {
    double ps = p.at(s), sum = 0, largest = 0;
    for (auto [i, pi] : p) {
        sum += h == Heuristic::Power ? pi * pi : h == Heuristic::Uniform ? 1 : pi;
        largest = std::max(largest, pi);
    }
    if (h == Heuristic::Max) {
        int sharing = 0;
        for (auto [i, pi] : p) sharing += pi * (1 + 1e-4) >= largest;
        return ps * (1 + 1e-4) >= largest ? 1.0 / sharing : 0;
    }
    return (h == Heuristic::Power ? ps * ps : h == Heuristic::Uniform ? 1 : ps) / sum;
}

// ---- a path's densities from their definition (notes, pages 7 and 10M)
// A full path x_0 (light) .. x_{n-1} (pinhole), and the subpaths each strategy (s, n-s) would have
// made of it: s vertices from the light, n-s from the pinhole.

inline bool specularAt(const Scene& scene, const PathVertex& v) {
    return v.type == PathVertex::Surface && isSpecular(scene.materials[size_t(scene.shapes[size_t(v.sp.shape)].material)]);
}

// The path of strategy (s,t): light[0..s-1], then camera[t-1..0].
inline std::vector<PathVertex> joinPath(const std::vector<PathVertex>& light, int s, const std::vector<PathVertex>& camera, int t) {
    std::vector<PathVertex> x(light.begin(), light.begin() + s);
    for (int j = t - 1; j >= 0; --j) x.push_back(camera[size_t(j)]);
    return x;
}

inline Vec3 unitTo(const PathVertex& from, const PathVertex& to) { return normalize(to.sp.p - from.sp.p); }

// The solid-angle density with which `cur`, reached from direction wo, samples direction w.
inline float pdfDirection(const Scene& scene, const PathVertex& cur, Vec3 wo, Vec3 w) {
    if (cur.type == PathVertex::Camera) return pdfCameraDirection(scene.camera, w);
    if (cur.type == PathVertex::Light) return pdfEmissionDirection(cur, w);
    float pdf, pdfReverse;
    evalBsdf(scene, cur.sp, wo, w, Transport::Radiance, pdf, pdfReverse);
    return pdf;
}

// The subpaths the generators would have made of x for strategy s: x_0..x_{s-1} from the light
// and x_{n-1}..x_s from the pinhole, each vertex added by the walkers' own appendVertex (the
// stored densities, which a judge compares with subpathDensity's), so that misWeight sees what a
// sample of (s, n-s) would have stored.
inline void rebuild(const Scene& scene, const std::vector<PathVertex>& x, int s, std::vector<PathVertex>& y, std::vector<PathVertex>& z) {
    const int n = int(x.size()), t = n - s;
    auto grow = [&](std::vector<PathVertex>& path, PathVertex v, Transport mode) {
        Vec3 d = path.back().sp.p - v.sp.p;
        v.prevDist2 = dot(d, d);
        v.wo = d / std::sqrt(v.prevDist2);
        v.type = PathVertex::Surface;
        v.deltaPosition = false;
        v.sp.ng = geometricNormal(scene.shapes[size_t(v.sp.shape)], v.sp.p);
        v.sp.ns = shadingNormal(scene.shapes[size_t(v.sp.shape)], v.sp.p, v.sp.ng);
        v.delta = specularAt(scene, v);
        v.pdfRev = 0;
        appendVertex(scene, path, v, mode);
    };
    y.clear();
    z.clear();
    if (s > 0) {  // y_0 on the light
        PathVertex v = x[0];
        v.type = PathVertex::Light;
        v.deltaPosition = v.sp.shape < 0;
        v.continuation = 1;  // a light subpath always leaves y_0 (emission sampling)
        v.sp.ng = v.deltaPosition ? Vec3(0) : geometricNormal(scene.shapes[size_t(v.sp.shape)], v.sp.p);
        v.delta = false;
        v.pdfFwd = v.deltaPosition ? lightChoiceProbability(scene, v.light) : pdfLightPoint(scene, v.sp.shape);
        v.pdfRev = 0;
        y.push_back(v);
        for (int i = 1; i < s; ++i) grow(y, x[size_t(i)], Transport::Importance);
    }
    PathVertex z0 = x[size_t(n - 1)];  // the pinhole
    z0.type = PathVertex::Camera;
    z0.deltaPosition = true;
    z0.delta = false;
    z0.pdfFwd = 1;
    z0.pdfRev = 0;
    z.push_back(z0);
    for (int j = 1; j < t; ++j) grow(z, x[size_t(n - 1 - j)], Transport::Radiance);
}

// The density with which one subpath samples x[from], then x[from + dir], ..., x[to], computed
// from positions, materials and the samplers' own densities alone, with none of the stored
// pdfFwd/pdfRev. A step from a non-specular vertex a to the next non-specular vertex b has
//   p_omega(a) q(a) [q of the specular vertices between] x |cos_b| / d^2      (b next to a)
//                                                       x G(a,b) / (eta_a^2 |cos_a|) (through a chain)
// where the chain's geometry term G(a,b) = eta_a^2 |cos_a| d omega_a / dA_b is the same read from
// either end (etendue: eta^2 cos dA d omega is kept by mirrors and Snell's law; test_bdpt's
// "specular chains" checks it by finite differences), so every strategy able to make the path,
// which crosses each chain whole, in one direction or the other, has the same G(a,b): it is left
// out here (through mirrors and glass only the densities' ratios are defined). eta_a is the index
// where the chain's first segment runs.
inline double subpathDensity(const Scene& scene, const std::vector<PathVertex>& x, int from, int to, Roulette roulette) {
    const int n = int(x.size()), dir = to >= from ? 1 : -1;
    auto at = [&](int i) -> const PathVertex& { return x[size_t(i)]; };
    auto q = [&](int i) { return roulette == Roulette::Albedo && i > 0 && i < n - 1 ? albedoContinuation(scene, at(i).sp) : 1.0; };
    auto isPoint = [&](int i) { return i == n - 1 || at(i).sp.shape < 0; };  // the pinhole, a point light
    double p = from == n - 1 ? 1 : at(0).sp.shape < 0 ? lightChoiceProbability(scene, at(0).light) : pdfLightPoint(scene, at(0).sp.shape);
    for (int a = from; a != to;) {
        Vec3 w = unitTo(at(a), at(a + dir));
        PathVertex va = at(a);
        va.type = a == n - 1 ? PathVertex::Camera : a == 0 ? PathVertex::Light : PathVertex::Surface;
        double step = a == from ? pdfDirection(scene, va, Vec3(0), w) : pdfDirection(scene, va, unitTo(at(a), at(a - dir)), w);
        step *= q(a);
        int b = a + dir;
        while (b != to && specularAt(scene, at(b))) step *= q(b), b += dir;
        if (b == a + dir) {
            Vec3 d = at(b).sp.p - at(a).sp.p;
            step *= absDot(at(b).sp.ng, w) / dot(d, d);
        } else {
            const Shape& first = scene.shapes[size_t(at(a + dir).sp.shape)];
            const Material& m = scene.materials[size_t(first.material)];
            double eta = m.type == Material::Glass && dot(w, at(a + dir).sp.ng) > 0 ? m.ior : 1;  // the segment runs inside
            step /= sqr(eta) * (isPoint(a) ? 1.0 : absDot(at(a).sp.ng, w));
        }
        p *= step;
        a = b;
    }
    return p;
}

// Can strategy (s, n-s) make this path at all? s = 0 needs x_0 on an area light; a connection
// needs both of its vertices non-specular.
inline bool able(const Scene& scene, const std::vector<PathVertex>& x, int s) {
    if (s == 0) return x[0].sp.shape >= 0 && scene.shapes[size_t(x[0].sp.shape)].light >= 0;
    PathVertex a = x[size_t(s - 1)], b = x[size_t(s)];
    a.type = s - 1 == 0 ? PathVertex::Light : PathVertex::Surface;
    b.type = s == int(x.size()) - 1 ? PathVertex::Camera : PathVertex::Surface;
    return !specularAt(scene, a) && !specularAt(scene, b);
}

// The slides' Probability(SP, estimator), computed from scratch: strategy s samples x_0..x_{s-1}
// from the light and x_{n-1}..x_s from the pinhole (the factors common to every strategy, the
// chains' G and the deltas, left out).
inline double pathDensity(const Scene& scene, const std::vector<PathVertex>& x, int s, Roulette roulette) {
    const int n = int(x.size());
    return (s > 0 ? subpathDensity(scene, x, 0, s - 1, roulette) : 1) * subpathDensity(scene, x, n - 1, s, roulette);
}

// The weight that misWeight, the code judged, gives strategy s of the path x: from the subpaths
// that strategy would have made (rebuild) and the connection connectStrategy would have evaluated.
inline double rebuiltWeight(const Scene& scene, const std::vector<PathVertex>& x, int s, Heuristic h, double mergeEta = 0) {
    thread_local std::vector<PathVertex> y, z;
    rebuild(scene, x, s, y, z);
    const int t = int(x.size()) - s;
    Connection c;
    if (s > 0) evalConnection(scene, y[size_t(s - 1)], z[size_t(t - 1)], c);
    return misWeight(scene, y, s, z, t, h, c, mergeEta);
}

// vcm's merge at x_i: the light subpath x_0..x_i and the camera subpath x_{n-1}..x_i both sampled
// up to x_i, times eta_VCM (notes, page 15).
inline double mergeDensity(const Scene& scene, const std::vector<PathVertex>& x, int i, Roulette roulette, double mergeEta) {
    return subpathDensity(scene, x, 0, i, roulette) * subpathDensity(scene, x, int(x.size()) - 1, i, roulette) * mergeEta;
}

// The densities of every strategy able to make x, by s; with vcm's mergeEta > 0 also the merge at
// every non-specular x_i (0 < i < n-1), keyed kMergeKey + i.
constexpr int kMergeKey = 1000;
inline std::map<int, double> strategyDensities(const Scene& scene, const std::vector<PathVertex>& x, Roulette roulette, double mergeEta = 0) {
    std::map<int, double> density;
    const int n = int(x.size());
    for (int s = 0; s < n; ++s)
        if (able(scene, x, s)) density[s] = pathDensity(scene, x, s, roulette);
    for (int i = 1; mergeEta > 0 && i + 1 < n; ++i)
        if (!specularAt(scene, x[size_t(i)]))
            density[kMergeKey + i] = mergeDensity(scene, x, i, roulette, mergeEta);
    return density;
}

// ---- power and radiance at a shading normal (notes, page 13)

// Power out / power in of the floor of scenes/energy-generator.scene as light paths see it: their
// throughput arriving, and after one Importance-mode bounce, in `batches` batches of light paths
// (batch b draws from makeRng(seed, b, 0)): the mean of the batches' ratios and its standard error
// (the adjoint's weights are large where |wo.ng| is small).
struct PowerRatio {
    double mean = 0, se = 0;
};
inline PowerRatio floorPowerRatio(const Scene& scene, int batches, int paths, uint64_t seed) {
    std::vector<double> r;
    for (int b = 0; b < batches; ++b) {
        Rng rng = makeRng(seed, uint64_t(b), 0);
        double in = 0, out = 0;
        for (int i = 0; i < paths; ++i) {
            EmissionSample es = sampleEmission(scene, rng);
            Ray ray = spawnRay(es.point.sp, es.dir);
            Hit hit = intersect(scene, ray);
            if (!hit.found() || scene.shapes[size_t(hit.shape)].emission.x > 0) continue;
            SurfacePoint sp = surfaceAt(scene, ray, hit);
            in += es.weight.x;
            BsdfSample bs;
            if (sampleBsdf(scene, sp, -ray.d, Transport::Importance, rng, bs)) out += es.weight.x * bs.weight.x;
        }
        r.push_back(out / in);
    }
    PowerRatio q;
    for (double x : r) q.mean += x / double(r.size());
    for (double x : r) q.se += r.size() > 1 ? sqr(float(x - q.mean)) / double(r.size() - 1) : 0;
    q.se = std::sqrt(q.se / double(r.size()));
    return q;
}

// ---- Metropolis (notes, page 17)

// A known target on [0,1)^2, read through the chain's replayed numbers as the renderer's walkers
// read theirs: 60 times brighter in one corner than in the dimmest part.
inline float knownTarget(float x, float y) { return std::exp(3 * x) * (1 + 8 * sqr(y - 0.5f)); }
inline double knownTargetIntegral(double x0, double x1, double y0, double y1) {  // closed form over a box
    auto X = [](double x) { return std::exp(3 * x) / 3; };
    auto Y = [](double y) { return y + 8 * std::pow(y - 0.5, 3) / 3; };
    return (X(x1) - X(x0)) * (Y(y1) - Y(y0));
}

struct TargetRun {
    double visitedChiSquare = 0, splattedChiSquare = 0;
    double acceptance = 0;
};

// A chain on the target (opt's large-step probability and sigma, the acceptance rule given): the
// chi-square of the visited states (every 10th, nearly independent) and of the expected-value
// splats' weights, over 8 x 8 bins against the closed form (63 degrees of freedom: about 63 +- 11
// when they fit). A chain that splats nothing gets 1e9.
inline TargetRun runOnKnownTarget(const RenderOptions& opt, Rng rng, float (*accept)(float, float) = symmetricAcceptance) {
    constexpr int kBins = 8, kSteps = 200000, kThin = 10;
    PrimarySampleChain chain;
    chain.rng = rng;
    auto evaluate = [&](PrimarySampleState& u) {
        Rng numbers;
        numbers.replay = &u.camera;
        u.camera.used = 0;
        u.camera.fresh = &chain.rng;
        float x = numbers.uniform(), y = numbers.uniform();
        u.f = knownTarget(x, y);
        u.contributions.assign(1, {std::min(kBins - 1, int(x * kBins)) + kBins * std::min(kBins - 1, int(y * kBins)), Vec3(1)});
    };
    evaluate(chain.current);
    std::vector<double> visited(kBins * kBins, 0), splatted(kBins * kBins, 0);
    auto splat = [&](const PrimarySampleState& u, double weight) {
        if (!u.contributions.empty()) splatted[size_t(u.contributions[0].pixel)] += weight * u.f;
    };
    for (int i = 0; i < kSteps; ++i) {
        metropolisStep(opt, chain, evaluate, splat, accept);
        if (i % kThin == 0 && !chain.current.contributions.empty()) visited[size_t(chain.current.contributions[0].pixel)] += 1;
    }
    splat(chain.current, chain.currentWeight);
    TargetRun run;
    double total = knownTargetIntegral(0, 1, 0, 1), samples = kSteps / kThin, splatTotal = 0;
    for (double w : splatted) splatTotal += w;
    for (int b = 0; b < kBins * kBins; ++b) {
        double x0 = double(b % kBins) / kBins, y0 = double(b / kBins) / kBins;
        double p = knownTargetIntegral(x0, x0 + 1.0 / kBins, y0, y0 + 1.0 / kBins) / total;
        run.visitedChiSquare += sqr(visited[size_t(b)] - samples * p) / (samples * p);
        run.splattedChiSquare += splatTotal > 0 ? sqr(splatted[size_t(b)] / splatTotal * samples - samples * p) / (samples * p) : 1e9;
    }
    run.acceptance = chain.proposed > 0 ? double(chain.accepted) / double(chain.proposed) : 0;
    return run;
}
