// Veach's Metropolis light transport (mlt): each mutation's acceptance against transition
// densities computed here from scratch, and the chains' images against references region by region.
#include "helpers.h"

// Paths drawn as the chains' starts are: a bootstrap sample's strategies, one in proportion to
// its MIS-weighted luminance.
std::vector<MutatedPath> startPaths(const Scene& scene, const RenderOptions& opt, int count) {
    std::vector<MutatedPath> paths;
    Rng rng = makeRng(77, 0, 0);
    for (int i = 0; int(paths.size()) < count && i < 100 * count; ++i) {
        double sum = pathBootstrapSample(scene, opt, i, 0, nullptr);
        if (!(sum > 0)) continue;
        MutatedPath x;
        pathBootstrapSample(scene, opt, i, rng.uniform() * sum, &x);
        if (x.f > 0) paths.push_back(x);
    }
    return paths;
}

// f(x) = C_{s,t}(x) p_{s,t}(x) is the path's, not the strategy's: every strategy able to make x
// gives the same f (bdpt's unweighted contributions and MIS densities agree through mirrors and
// glass), and the same densities of its vertices, which T reads.
TEST_CASE("a path's f and densities are the same from every strategy that can make it, through mirrors and glass") {
    for (std::string name : {"cornell-glass", "glass-box", "cornell-point"}) {
        Scene scene = sceneAt("scenes/" + name + ".scene", 32, 32);
        RenderOptions opt = quietOptions(Method::MLT, 1);
        opt.metropolis.chainShortPaths = true;
        std::vector<MutatedPath> starts = startPaths(scene, opt, 300);
        std::vector<PathVertex> light, camera;
        int compared = 0, agree = 0, specular = 0;
        for (const MutatedPath& x : starts) {
            bool hasSpecular = false;
            for (const PathVertex& v : x.x) hasSpecular |= !connectable(scene, v);
            for (int s = 0; s <= x.k(); ++s) {
                int t = x.k() + 1 - s;
                if ((s > 0 && !connectable(scene, x.x[s - 1])) || !connectable(scene, x.x[s])) continue;
                if (s == 0 && x.x[0].deltaPosition) continue;
                subpathThrough(scene, x.x, s, Transport::Importance, light);
                subpathThrough(scene, x.x, t, Transport::Radiance, camera);
                MutatedPath y;
                if (!joinPath(scene, light, s, camera, t, y)) continue;  // a cosine of 0 at a connection
                bool same = std::fabs(y.f / x.f - 1) < 1e-3;
                for (int i = 0; i <= x.k(); ++i)
                    same = same && std::fabs(y.pL[i] - x.pL[i]) <= 1e-3 * x.pL[i] && std::fabs(y.pE[i] - x.pE[i]) <= 1e-3 * x.pE[i];
                ++compared;
                agree += same;
                specular += hasSpecular;
            }
        }
        MESSAGE(name << ": " << agree << " of " << compared << " (path, strategy) pairs give the path's f and densities within 1e-3; "
                     << specular << " of the pairs through a mirror or glass");
        CHECK(compared > 500);
        CHECK(agree >= 0.99 * compared);
    }
}

// mlt's options for the mutation tests: the chains make every path length (one segment up) to D bounces.
struct MutationOptions {
    RenderOptions opt;
    SampleOptions walk;
    LengthRange range;
};
static MutationOptions mutationOptions(int maxDepth) {
    RenderOptions opt = quietOptions(Method::MLT, 1);
    opt.metropolis.chainShortPaths = true;
    opt.maxDepth = maxDepth;
    return {opt, chainOptions(opt), LengthRange{1, maxDepth + 1}};
}

// -- T(y|x) of the bidirectional mutation, from its definition (Veach 1997, 11.4.2), for scenes of
// diffuse quads and one light: P(kd) P(ka|kd) / (#places (n+1)) sum over the splits of the new
// vertices' densities, each written out here from the geometry.
struct FromScratch {
    const Scene& scene;
    int maxSegments, minSegments;
    bool oneSplit = false;  // a careful person's mistake: the density of one split (here all from the light) alone
    static double deleteWeight(int kd) { return kd == 1 ? 0.25 : kd == 2 ? 0.5 : std::pow(0.5, kd); }
    static double addWeight(int ka, int kd) {
        int j = std::abs(ka - kd);
        return j == 0 ? 0.5 : j == 1 ? 0.15 : 0.2 * std::pow(0.5, j);
    }
    bool lengthOk(int k, int kd, int ka) const { int n = k - kd + ka; return ka >= 1 && n >= minSegments && n <= maxSegments && !(kd == 1 && ka == 1); }
    double pDelete(int kd, int k) const {
        double t = 0;
        for (int d = 1; d <= k + 1; ++d) t += deleteWeight(d);
        return deleteWeight(kd) / t;
    }
    double pAdd(int ka, int kd, int k) const {
        double t = 0;
        for (int a = 1; a <= maxSegments + 1; ++a) t += lengthOk(k, kd, a) ? addWeight(a, kd) : 0;
        return lengthOk(k, kd, ka) ? addWeight(ka, kd) / t : 0;
    }
    int places(int k, int kd, int ka) const {  // every vertex diffuse: only the light point's rule
        int n = 0;
        for (int a = 0; a + kd - 1 <= k; ++a) n += a > 0 || (kd > 1 && ka > 1);
        return n;
    }
    // Density of sampling point `to` from `from` that was reached from `before` (nullptr: from is
    // the light point or the pinhole).
    double diffuseStep(Vec3 before, Vec3 from, Vec3 fromNormal, Vec3 to, Vec3 toNormal) const {
        Vec3 d = to - from;
        double d2 = dot(d, d);
        Vec3 w = d / std::sqrt(float(d2));
        double cosFrom = dot(fromNormal, w), cosTo = std::fabs(dot(toNormal, w));
        if (dot(fromNormal, before - from) * cosFrom <= 0) return 0;  // the other side: a diffuse surface never transmits
        return std::fabs(cosFrom) / kPi * cosTo / d2;
    }
    double lightStep(const PathVertex& light, Vec3 to, Vec3 toNormal) const {
        Vec3 d = to - light.sp.p;
        double d2 = dot(d, d), cosTo = dot(toNormal, toNormal) == 0 ? 1 : std::fabs(dot(toNormal, d)) / std::sqrt(d2);
        if (light.deltaPosition) return 1 / (4 * kPi) * cosTo / d2;
        double cosLight = dot(light.sp.ng, d) / std::sqrt(d2);
        return cosLight > 0 ? cosLight / kPi * cosTo / d2 : 0;
    }
    double cameraStep(Vec3 to, Vec3 toNormal) const {
        const Camera& cam = scene.camera;
        double tanHalf = std::tan(cam.fovDegrees * kPi / 360), area = 4 * tanHalf * tanHalf * double(cam.width) / cam.height;
        Vec3 d = to - cam.eye;
        double d2 = dot(d, d), cosCam = dot(cam.forward, d) / std::sqrt(d2);
        return 1 / (area * cosCam * cosCam * cosCam) * std::fabs(dot(toNormal, d)) / std::sqrt(d2) / d2;
    }
    double lightPoint(const PathVertex& v) const {
        if (v.deltaPosition) return 1.0 / scene.lights.size();
        const Shape& s = scene.shapes[v.sp.shape];
        return 1.0 / (scene.lights.size() * length(cross(s.u, s.v)));
    }
    // Light-side density of x_i, from x_{i-1}; camera-side density of x_i, from x_{i+1}.
    double fromLight(const MutatedPath& p, int i) const {
        const auto& x = p.x;
        if (i == 0) return lightPoint(x[0]);
        Vec3 n = x[i].sp.ng;
        if (i == 1) return lightStep(x[0], x[1].sp.p, n);
        return diffuseStep(x[i - 2].sp.p, x[i - 1].sp.p, x[i - 1].sp.ng, x[i].sp.p, n);
    }
    double fromCamera(const MutatedPath& p, int i) const {
        const auto& x = p.x;
        int k = p.k();
        if (i == 0 && x[0].deltaPosition) return 0;
        if (i == k - 1) return cameraStep(x[i].sp.p, x[i].sp.ng);
        return diffuseStep(x[i + 2].sp.p, x[i + 1].sp.p, x[i + 1].sp.ng, x[i].sp.p, x[i].sp.ng);
    }
    // A point light is one point: y with x_0 kept is also y with x_0 deleted and drawn again.
    double transition(const MutatedPath& x, const MutatedPath& y, int a, int kd, int ka) const {
        return oneWay(x, y, a, kd, ka) + (a == 1 && x.x[0].deltaPosition ? oneWay(x, y, 0, kd + 1, ka + 1) : 0);
    }
    double oneWay(const MutatedPath& x, const MutatedPath& y, int a, int kd, int ka) const {
        if (!lengthOk(x.k(), kd, ka) || places(x.k(), kd, ka) == 0) return 0;
        double sum = 0;
        for (int s = oneSplit ? ka - 1 : 0; s < ka; ++s) {
            double p = 1;
            for (int i = a; i < a + ka - 1; ++i) p *= i < a + s ? fromLight(y, i) : fromCamera(y, i);
            sum += p;
        }
        return pDelete(kd, x.k()) * pAdd(ka, kd, x.k()) / (places(x.k(), kd, ka) * double(ka)) * sum;
    }
};

// The replaced range of x: the first a vertices and the last vertices from x_b on are y's too.
bool replacedRange(const MutatedPath& x, const MutatedPath& y, int& a, int& kd, int& ka) {
    auto same = [](const PathVertex& p, const PathVertex& q) { return p.sp.p.x == q.sp.p.x && p.sp.p.y == q.sp.p.y && p.sp.p.z == q.sp.p.z; };
    int prefix = 0, suffix = 0;
    while (prefix < std::min(x.k(), y.k()) && same(x.x[prefix], y.x[prefix])) ++prefix;
    if (x.k() == y.k() && prefix == x.k()) return false;  // the same path
    while (suffix < std::min(x.k(), y.k()) + 1 - prefix && same(x.x[x.k() - suffix], y.x[y.k() - suffix])) ++suffix;
    a = prefix;
    kd = x.k() + 1 - suffix - a + 1;
    ka = y.k() + 1 - suffix - a + 1;
    return suffix >= 1;
}

TEST_CASE("the bidirectional mutation's acceptance is f(y) T(x|y) / (f(x) T(y|x)) with T written out from its definition") {
    for (std::string name : {"cornell", "cornell-point"}) {
        Scene scene = sceneAt("scenes/" + name + ".scene", 32, 32);
        const MutationOptions m = mutationOptions(5);  // lengths reach the clamp of the length distribution
        FromScratch T{scene, m.opt.maxDepth + 1, 1};
        std::vector<MutatedPath> starts = startPaths(scene, m.opt, 300);
        REQUIRE(starts.size() == 300);
        Rng rng = makeRng(5, 0, 0);
        int compared = 0, agree = 0, oneSplitOff = 0, lengthsUnclampedOff = 0;
        double worst = 0;
        for (const MutatedPath& x : starts)
            for (int proposal = 0; proposal < 10; ++proposal) {
                MutatedPath y;
                double ratio = bidirectionalMutation(scene, m.walk, m.range, x, rng, y);
                if (!(ratio > 0)) continue;
                int a, kd, ka;
                if (!replacedRange(x, y, a, kd, ka)) {  // a point light drawn again, and nothing else changed: y = x
                    CHECK(x.x[0].deltaPosition);
                    CHECK(ratio == doctest::Approx(1).epsilon(1e-5));
                    continue;
                }
                double expected = y.f * T.transition(y, x, a, ka, kd) / (x.f * T.transition(x, y, a, kd, ka));
                double err = std::fabs(ratio / expected - 1);
                worst = std::max(worst, err);
                ++compared;
                agree += err < 1e-4;
                // Two careful people's T: the length probabilities not renormalised to the lengths
                // allowed, and the density of one split alone.
                FromScratch unclamped = T, single = T;
                unclamped.maxSegments = 1000;
                single.oneSplit = true;
                double noRenorm = y.f * unclamped.transition(y, x, a, ka, kd) / (x.f * unclamped.transition(x, y, a, kd, ka));
                double oneSplit = y.f * single.transition(y, x, a, ka, kd) / (x.f * single.transition(x, y, a, kd, ka));
                oneSplitOff += !(std::fabs(oneSplit / expected - 1) < 1e-2);
                lengthsUnclampedOff += std::fabs(noRenorm / expected - 1) > 1e-2;
            }
        MESSAGE(name << ": " << agree << " of " << compared << " proposals within 1e-4 (worst " << worst << "); "
                     << lengthsUnclampedOff << " off by > 1% if the length pmfs were not renormalised, " << oneSplitOff << " with one split's density");
        CHECK(compared > 1000);
        CHECK(agree == compared);
        CHECK(lengthsUnclampedOff > compared / 20);
        CHECK(oneSplitOff > compared / 4);
    }
}

// Where the ray from `from` along `dir` first meets the scene (a finite difference's end).
bool hitPoint(const Scene& scene, Vec3 from, Vec3 dir, Vec3& p) {
    Ray ray{from, normalize(dir), kInf};
    Hit hit = intersect(scene, ray);
    if (!hit.found()) return false;
    p = surfaceAt(scene, ray, hit).p;
    return true;
}

// Area swept on the scene per unit of a 2-D parameter of a ray, by central differences; 0 where
// steps h and h/2 disagree (the stencil crosses an edge of the scene).
template <class RayAt>
double sweptAreaOnce(const Scene& scene, double u, double v, double h, const RayAt& rayAt);
template <class RayAt>
double sweptArea(const Scene& scene, double u, double v, double h, const RayAt& rayAt) {
    double a = sweptAreaOnce(scene, u, v, h, rayAt), b = sweptAreaOnce(scene, u, v, h / 2, rayAt);
    return std::fabs(a / b - 1) < 1e-3 ? b : 0;
}
template <class RayAt>
double sweptAreaOnce(const Scene& scene, double u, double v, double h, const RayAt& rayAt) {
    Vec3 p[4];
    double du[4] = {h, -h, 0, 0}, dv[4] = {0, 0, h, -h};
    for (int i = 0; i < 4; ++i) {
        Vec3 from, dir;
        rayAt(u + du[i], v + dv[i], from, dir);
        if (!hitPoint(scene, from, dir, p[i])) return 0;
    }
    Vec3 a = (p[0] - p[1]) / float(2 * h), b = (p[2] - p[3]) / float(2 * h);
    return length(cross(a, b));
}

// The lens perturbation moves the film point u symmetrically, so its acceptance is
// pi(u_y)/pi(u_x) with pi(u) = f(x(u)) |dA/du|, the area the camera's vertex sweeps per film
// area: taken here by finite differences of the traced ray, not from any density of the code.
// The caustic perturbation turns the direction w at x_l by theta with the solid-angle density
// p(theta) = 1 / (2 pi ln(theta2/theta1) theta sin theta), whose range scales with the path's
// lengths (Veach 1997, p. 354): its acceptance is pi(w_y) p_y(theta) / (pi(w_x) p_x(theta)) with
// pi(w) = f |dA/dw|, dA/dw again by finite differences.
TEST_CASE("the lens and caustic perturbations' acceptance is that of their moves on the film and on the sphere of directions") {
    Scene scene = sceneAt("scenes/cornell.scene", 32, 32);
    const Camera& cam = scene.camera;
    RenderOptions opt = quietOptions(Method::MLT, 1);
    opt.metropolis.chainShortPaths = true;
    std::vector<MutatedPath> starts = startPaths(scene, opt, 400);
    REQUIRE(starts.size() == 400);
    Rng rng = makeRng(9, 0, 0);
    auto filmRay = [&](double u, double v, Vec3& from, Vec3& dir) {
        Ray r = cameraRay(cam, float(u), float(v));
        from = r.o, dir = r.d;
    };
    auto filmArea = [&](const MutatedPath& p) {
        float fx = 0, fy = 0;
        if (!projectToFilm(cam, p.x[p.k() - 1].sp.p, fx, fy)) return 0.0;
        return sweptArea(scene, fx, fy, 0.02, filmRay);
    };
    auto directionArea = [&](const MutatedPath& p, int l) {  // per steradian, about the direction to x_{l+1}
        Vec3 w = normalize(p.x[l + 1].sp.p - p.x[l].sp.p);
        Frame frame(w);
        auto turnedRay = [&](double a, double b, Vec3& from, Vec3& dir) {
            from = p.x[l].sp.p + w * 1e-3f;
            dir = frame.toWorld(Vec3(float(a), float(b), 1));  // gnomonic: d(a,b) = dw / cos^3 = dw at the centre
        };
        return sweptArea(scene, 0, 0, 2e-4, turnedRay);
    };
    auto thetaDensity = [&](const MutatedPath& p, int l, double theta) {
        double chain = 0;
        for (int i = l; i < p.k() - 1; ++i) chain += length(p.x[i + 1].sp.p - p.x[i].sp.p);
        double radiansPerPixel = cam.fovDegrees * kPi / 180 / cam.height;  // the field of view spans the height
        double scale = radiansPerPixel * length(p.x[p.k()].sp.p - p.x[p.k() - 1].sp.p) / chain;
        double t1 = 0.1 * scale, t2 = std::min(std::sqrt(0.05 * cam.width * cam.height / kPi) * scale, kPi / 2.0);
        return theta >= t1 && theta <= t2 ? 1 / (2 * kPi * std::log(t2 / t1) * theta * std::sin(theta)) : 0;
    };
    int lensCompared = 0, lensAgree = 0, lensFOnlyOff = 0, causticCompared = 0, causticAgree = 0, causticFOnlyOff = 0;
    for (const MutatedPath& x : starts)
        for (int proposal = 0; proposal < 4; ++proposal) {
            MutatedPath y;
            double ratio = lensPerturbation(scene, x, rng, y);
            if (ratio > 0 && filmArea(x) > 0 && filmArea(y) > 0) {
                double expected = y.f * filmArea(y) / (x.f * filmArea(x));
                ++lensCompared;
                lensAgree += std::fabs(ratio / expected - 1) < 1e-3;
                lensFOnlyOff += std::fabs(y.f / x.f / expected - 1) > 2e-2;
            }
            ratio = causticPerturbation(scene, x, rng, y);
            int l = causticVertex(scene, x);  // cornell has no mirrors: l = k-2
            if (ratio > 0 && directionArea(x, l) > 0 && directionArea(y, l) > 0) {  // cornell has no mirrors: l = k-2
                double theta = std::acos(std::clamp(double(dot(normalize(x.x[l + 1].sp.p - x.x[l].sp.p), normalize(y.x[l + 1].sp.p - y.x[l].sp.p))), -1.0, 1.0));
                double expected = y.f * directionArea(y, l) * thetaDensity(y, l, theta) / (x.f * directionArea(x, l) * thetaDensity(x, l, theta));
                ++causticCompared;
                causticAgree += std::fabs(ratio / expected - 1) < 3e-3;  // directions 1e-4 apart: hit points carry float noise
                causticFOnlyOff += std::fabs(y.f / x.f / expected - 1) > 2e-2;
            }
        }
    MESSAGE("lens: " << lensAgree << " of " << lensCompared << " within 1e-3 of f |dA/du|'s ratio; " << lensFOnlyOff
                     << " off by > 2% with f(y)/f(x) alone");
    MESSAGE("caustic: " << causticAgree << " of " << causticCompared << " within 3e-3; " << causticFOnlyOff
                        << " off by > 2% with f(y)/f(x) alone");
    CHECK(lensCompared > 500);
    CHECK(lensAgree >= 0.995 * lensCompared);  // finite differences of float hit points: a few fall outside
    CHECK(lensFOnlyOff > lensCompared / 10);
    CHECK(causticCompared > 500);
    CHECK(causticAgree >= 0.995 * causticCompared);
    CHECK(causticFOnlyOff > causticCompared / 10);
}

// The image regions of mlt's chains, run here so that a test may give them mutations the command
// line refuses (a perturbation alone): 8 seeds' region means, scaled as mlt's passes are.
RegionEstimate chainRegions(const Scene& scene, RenderOptions opt, int grid, int seeds) {
    const int W = scene.camera.width, H = scene.camera.height, R = grid * grid;
    const long long N = (long long)W * H;
    std::vector<std::vector<double>> perSeed(R);
    for (int seed = 0; seed < seeds; ++seed) {
        opt.seed = 2000 + seed;
        MetropolisPass mp;
        startPathChains(scene, opt, 1, mp);
        const SampleOptions walk = chainOptions(opt);
        const LengthRange lengths{shortestChainPath(opt), opt.maxDepth + 1};
        const long long steps = N * opt.spp / (long long)mp.paths.size();
        std::vector<double> sum(R, 0);
        for (PathChain& chain : mp.paths) {
            auto splat = [&](const MutatedPath& x, double weight) {
                sum[(x.pixel / W * grid / H) * grid + (x.pixel % W) * grid / W] += average(x.colour) * x.f * weight;
            };
            for (long long i = 0; i < steps; ++i) splatAndAccept(chain, mutate(scene, walk, lengths, chain.current, chain.rng, chain.proposal), splat);
            splat(chain.current, chain.currentWeight);
        }
        for (int r = 0; r < R; ++r) perSeed[r].push_back(sum[r] * mp.b / double(steps * mp.paths.size()) * R);
    }
    return regionsOverSeeds(perSeed);
}


// Through mirrors and glass a perturbation follows the path's lobes, and its densities are the
// chain's (bdpt's banner). Each perturbation runs alone here: chains that start as f is
// distributed (the bootstrap's starts) stay so under any move that keeps f stationary, even one
// that never leaves a path's neighbourhood, so their image is unbiased region by region. (The
// finite-difference test above is the one that tells a wrong acceptance apart: accepting by
// f(y)/f(x) alone moves these regions by only a few standard errors.)
TEST_CASE("the lens and caustic perturbations alone keep f stationary through mirrors and glass") {
    Scene scene = sceneAt("scenes/cornell-glass.scene", 32, 32);
    RegionEstimate ref = referenceRegions("cornell-glass", 4);
    for (int bit : {int(kLens), int(kCaustic)}) {
        RenderOptions opt = quietOptions(Method::MLT, 256);
        opt.metropolis.mutations = bit;
        opt.metropolis.chainShortPaths = true;
        opt.metropolis.bootstrap = 20000;
        opt.metropolis.chains = 64;
        double chi = chiSquare(chainRegions(scene, opt, 4, 8), ref);
        MESSAGE(std::string(bit == kLens ? "lens" : "caustic") << " alone: chi-square over 16 regions " << chi);
        CHECK(chi < 100);  // about 22 +- 11 when unbiased (8 seeds)
    }
}

// The probability of the lobe a path takes at vertex i if it is glass (1 elsewhere), from Fresnel's
// equations written out here: F where the path reflects, 1 - F where it refracts.
static double glassLobe(const Scene& scene, const MutatedPath& x, int i) {
    const Material& m = scene.materials[scene.shapes[x.x[i].sp.shape].material];
    if (i == 0 || i == x.k() || m.type != Material::Glass) return 1;
    Vec3 n = x.x[i].sp.ng, toNext = normalize(x.x[i + 1].sp.p - x.x[i].sp.p), toPrev = normalize(x.x[i - 1].sp.p - x.x[i].sp.p);
    bool reflects = dot(toNext, n) * dot(toPrev, n) > 0, outside = dot(toNext, n) > 0;
    double etaI = outside ? 1.0 : m.ior, etaT = outside ? m.ior : 1.0, cosI = std::fabs(dot(toNext, n));
    double sinT = etaI / etaT * std::sqrt(std::max(0.0, 1 - cosI * cosI)), F = 1;
    if (sinT < 1) {
        double cosT = std::sqrt(1 - sinT * sinT);
        double rs = (etaI * cosI - etaT * cosT) / (etaI * cosI + etaT * cosT), rp = (etaT * cosI - etaI * cosT) / (etaT * cosI + etaI * cosT);
        F = (rs * rs + rp * rp) / 2;
    }
    return reflects ? F : 1 - F;
}

// The multi-chain perturbation moves the film point u as the lens perturbation does and turns the
// direction at each diffuse vertex c_j whose light came through a mirror or glass by a symmetric
// angle, so its acceptance is pi(y)/pi(x), pi = f |d(diffuse vertices)/d(u, w_1..w_m)|. Through a
// specular chain from a to b, f's generalized geometric term is |cos_a| |dw_a/dA_b|: it cancels the
// Jacobian's |dA_b/dw_a|, and at the film the pinhole's importance cancels |dA/du|. Left, written
// out here: Le and the BSDF values (albedo/pi, the mirror's reflectance, glass's F or 1 - F), the cosine
// at each turned vertex toward its light, and the geometric term of the final connection.
static double multiChainTarget(const Scene& scene, const MutatedPath& p, int end) {
    Vec3 colour = scene.shapes[p.x[0].sp.shape].emission;  // a colour: f's luminance is taken of the product
    double scalar = 1;
    for (int i = 1; i < p.k(); ++i) {
        const Material& m = scene.materials[scene.shapes[p.x[i].sp.shape].material];
        colour = colour * (m.type == Material::Diffuse ? m.albedo / float(kPi) : m.type == Material::Mirror ? m.albedo : Vec3(1));
        scalar *= glassLobe(scene, p, i);
        bool turned = i > end && m.type == Material::Diffuse &&
                      scene.materials[scene.shapes[p.x[i - 1].sp.shape].material].type != Material::Diffuse;
        if (turned) scalar *= std::fabs(dot(p.x[i].sp.ng, normalize(p.x[i - 1].sp.p - p.x[i].sp.p)));
    }
    if (end > 0) {
        Vec3 d = p.x[end - 1].sp.p - p.x[end].sp.p;
        double cosA = std::fabs(dot(p.x[end].sp.ng, normalize(d)));
        double cosB = p.x[end - 1].deltaPosition ? 1 : std::fabs(dot(p.x[end - 1].sp.ng, normalize(d)));
        scalar *= cosA * cosB / dot(d, d);
    }
    return luminance(colour) * scalar;
}

TEST_CASE("the multi-chain perturbation's acceptance is that of its moves on the film and the spheres of directions") {
    Scene scene = sceneAt("scenes/cornell-glass.scene", 32, 32);
    RenderOptions opt = quietOptions(Method::MLT, 1);
    opt.metropolis.chainShortPaths = true;
    std::vector<MutatedPath> starts;
    for (const MutatedPath& x : startPaths(scene, opt, 4000))
        if (multiChainEnd(scene, x) >= 0) starts.push_back(x);
    Rng rng = makeRng(11, 0, 0);
    int compared = 0, agree = 0, fOnlyOff = 0, lightHit = 0, turns = 0;
    for (const MutatedPath& x : starts)
        for (int proposal = 0; proposal < 8; ++proposal) {
            MutatedPath y;
            double ratio = multiChainPerturbation(scene, x, rng, y);
            if (!(ratio > 0)) continue;
            const int end = multiChainEnd(scene, x);
            double expected = multiChainTarget(scene, y, end) / multiChainTarget(scene, x, end);
            ++compared;
            agree += std::fabs(ratio / expected - 1) < 2e-5;
            fOnlyOff += std::fabs(y.f / x.f / expected - 1) > 1e-2;
            lightHit += end == 0;
            for (int i = end + 1; i < x.k(); ++i) turns += connectable(scene, x.x[i]);
        }
    MESSAGE("multi-chain: " << starts.size() << " paths, " << compared << " proposals (" << lightHit << " ending on the light, "
                            << turns << " turned vertices); " << agree << " within 2e-5 of the written-out ratio; " << fOnlyOff
                            << " off by > 1% with f(y)/f(x) alone");
    CHECK(compared > 300);
    CHECK(lightHit > 30);
    CHECK(turns > 100);
    CHECK(agree >= 0.99 * compared);  // the walk's pE at a turned vertex (its BSDF's density of the angle): 544 of 1,076
    CHECK(fOnlyOff > compared / 10);
}

// The multi-chain perturbation turns the direction toward the next vertex by an angle of density
// 1/theta on Veach's fixed range, 1e-4 to 0.1 degrees (Veach 1997, p. 357): log10 of the angle in
// degrees is uniform on [-4, -1], a third in each decade. Measured here from the paths themselves:
// the angle at the first turned vertex c between x's direction toward x_{c-1} and y's. (Radians
// taken for degrees would turn up to 5.7 degrees.)
TEST_CASE("the multi-chain perturbation's turns follow Veach's range: 1e-4 to 0.1 degrees, density 1/theta") {
    Scene scene = sceneAt("scenes/cornell-glass.scene", 32, 32);
    RenderOptions opt = quietOptions(Method::MLT, 1);
    opt.metropolis.chainShortPaths = true;
    Rng rng = makeRng(12, 0, 0);
    std::vector<double> log10Degrees;
    for (const MutatedPath& x : startPaths(scene, opt, 4000)) {
        const int end = multiChainEnd(scene, x);
        int c = x.k() - 1;
        while (c > end && !connectable(scene, x.x[c])) --c;
        if (end < 0 || c <= end) continue;  // no turned vertex
        for (int proposal = 0; proposal < 8; ++proposal) {
            MutatedPath y;
            if (!(multiChainPerturbation(scene, x, rng, y) > 0) || y.k() != x.k()) continue;
            auto direction = [&](const MutatedPath& p) {
                Vec3 d = p.x[c - 1].sp.p - p.x[c].sp.p;
                return std::array<double, 3>{d.x, d.y, d.z};
            };
            auto a = direction(x), b = direction(y);
            double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2], cz = a[0] * b[1] - a[1] * b[0];
            double dotAB = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            double theta = std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), dotAB);  // exact for small angles, unlike acos
            log10Degrees.push_back(std::log10(theta * 180 / kPi));
        }
    }
    REQUIRE(log10Degrees.size() > 200);
    double lowest = *std::min_element(log10Degrees.begin(), log10Degrees.end());
    double highest = *std::max_element(log10Degrees.begin(), log10Degrees.end());
    int decade[3] = {0, 0, 0};
    for (double l : log10Degrees) ++decade[std::clamp(int(std::floor(l + 4)), 0, 2)];
    const double n = double(log10Degrees.size());
    MESSAGE(log10Degrees.size() << " turns: 10^" << lowest << " to 10^" << highest << " degrees; per decade from 1e-4: "
            << decade[0] / n << ", " << decade[1] / n << ", " << decade[2] / n);
    CHECK(lowest > -4.2);  // float vertices blur the smallest turns a little
    CHECK(highest < -0.98);
    for (int d : decade) CHECK(std::fabs(d / n - 1.0 / 3) < 0.1);
}

// The target f at a glass vertex carries the probability of the lobe the path took there: F where
// the path reflects, 1 - F where it refracts, F the dielectric's Fresnel reflectance for the angle
// the path makes with the normal (written out here from Fresnel's equations). With F for both
// lobes, the caustic under the glass ball falls to about half.
TEST_CASE("mlt's f through glass carries F where the path reflects and 1 - F where it refracts") {
    Scene scene = sceneAt("scenes/cornell-glass.scene", 32, 32);
    RenderOptions opt = quietOptions(Method::MLT, 1);
    opt.metropolis.chainShortPaths = true;
    int glass = 0, refracted = 0, agree = 0;
    for (const MutatedPath& x : startPaths(scene, opt, 400))
        for (int i = 1; i < x.k(); ++i) {
            if (scene.materials[scene.shapes[x.x[i].sp.shape].material].type != Material::Glass) continue;
            Vec3 n = x.x[i].sp.ng;
            refracted += dot(x.x[i + 1].sp.p - x.x[i].sp.p, n) * dot(x.x[i - 1].sp.p - x.x[i].sp.p, n) < 0;
            ++glass;
            agree += std::fabs(x.lobe[i] - glassLobe(scene, x, i)) < 1e-4;
        }
    MESSAGE((glass - refracted) << " reflections and " << refracted << " refractions at glass vertices of the chains' starts");
    CHECK(refracted > 100);
    CHECK(glass - refracted > 5);
    CHECK(agree == glass);
}

// Detailed balance with the choice of the mutation: a proposal y of x is made with probability
// T(y|x) / count(x), count the number of mutations that apply to x, so the acceptance is
// min(1, f(y) T(x|y) count(x) / (f(x) T(y|x) count(y))). On cornell (every vertex diffuse) a
// path of one segment admits the bidirectional mutation alone and a longer one all three (the
// lens perturbation needs a vertex behind the one seen, the caustic one two segments): from two
// segments to one the factor is 3. Without it, those moves break detailed balance by 3x (where the
// acceptance is below 1 either way).
TEST_CASE("mlt's acceptance counts the choice of the mutation where x and y admit different ones") {
    Scene scene = sceneAt("scenes/cornell.scene", 32, 32);
    const MutationOptions m = mutationOptions(5);
    FromScratch T{scene, m.opt.maxDepth + 1, 1};
    auto count = [](const MutatedPath& p) { return p.k() >= 2 ? 3 : 1; };
    Rng rng = makeRng(11, 0, 0);
    int compared = 0, agree = 0, countsDiffer = 0, withoutCountsOff = 0;
    for (const MutatedPath& x : startPaths(scene, m.opt, 300))
        for (int proposal = 0; proposal < 30; ++proposal) {
            MutatedPath y;
            double a = mutate(scene, m.walk, m.range, x, rng, y);
            int from, kd, ka;
            if (y.mutation != kBidirectional || !(a > 0) || !replacedRange(x, y, from, kd, ka)) continue;
            double ratio = y.f * T.transition(y, x, from, ka, kd) / (x.f * T.transition(x, y, from, kd, ka));
            double expected = std::min(1.0, ratio * count(x) / count(y));
            ++compared;
            agree += std::fabs(a / expected - 1) < 1e-4;
            if (count(x) == count(y)) continue;
            ++countsDiffer;
            withoutCountsOff += std::fabs(std::min(1.0, ratio) / expected - 1) > 0.01;
        }
    MESSAGE(agree << " of " << compared << " acceptances as written out; " << countsDiffer << " between paths admitting 1 and 3 mutations, "
                  << withoutCountsOff << " of them off by > 1% without count(x)/count(y)");
    CHECK(compared > 1000);
    CHECK(agree == compared);
    CHECK(countsDiffer > 50);
    CHECK(withoutCountsOff > 20);  // where min(1, .) does not hide the factor
}

// The bidirectional mutation draws the split s of its n new vertices (s from the light side, n - s
// from the camera's) uniformly from 0..n, T's sum over splits assumes it. With n = 1 (one vertex
// replaced by one), s = 1 makes the new vertex by the light walk from x_0 and s = 0 by the camera
// walk from x_2. The mutation's numbers are replayed: kd = ka = 2 and a = 1 chosen, then the
// split's number u, then a direction number 0, which sends either walk along its vertex's normal:
// which of the two hit points the new vertex is tells the split. It must be s = 1 for u >= 1/2.
TEST_CASE("the bidirectional mutation's split of the new vertices is uniform over 0..n") {
    Scene scene = sceneAt("scenes/cornell.scene", 32, 32);
    const MutationOptions m = mutationOptions(5);
    auto hitAlong = [&](const SurfacePoint& from, Vec3 dir) {
        Hit hit = intersect(scene, spawnRay(from, dir));
        return hit.found() ? surfaceAt(scene, spawnRay(from, dir), hit).p : Vec3(kInf);
    };
    int fromLight = 0, fromCamera = 0, wrong = 0;
    for (const MutatedPath& x : startPaths(scene, m.opt, 60)) {
        const int k = x.k();
        if (k < 3) continue;  // x_0, x_1 replaced, x_2 and the pinhole kept, x_2 not the pinhole's neighbour only
        double deleteTotal = 0, addBefore = 0, addTotal = 0, places = 0;
        for (int d = 1; d <= k + 1; ++d) deleteTotal += deletionWeight(d);
        for (int e = 1; e <= m.range.max + 1; ++e) {
            double w = additionAllowed(e, 2, k, m.range) ? additionWeight(e, 2) : 0;
            addTotal += w;
            if (e < 2) addBefore += w;
        }
        for (int i = 0; i + 1 <= k; ++i) places += deletionAllowed(scene, x, i, 2, 2);
        Vec3 lightHit = hitAlong(x.x[0].sp, x.x[0].sp.ng);
        Vec3 wo = normalize(x.x[3].sp.p - x.x[2].sp.p);
        Vec3 cameraHit = hitAlong(x.x[2].sp, facingShadingNormal(x.x[2].sp, wo));
        for (int i = 0; i < 16; ++i) {
            double u = (i + 0.5) / 16;
            PrimaryStream numbers;
            numbers.values = {float(0.5 / deleteTotal), float((addBefore + 0.25) / addTotal), float(1.5 / places), float(u), 0.0f, 0.3f};
            Rng fresh = makeRng(3, uint64_t(i), 0);
            numbers.fresh = &fresh;
            Rng rng;
            rng.replay = &numbers;
            MutatedPath y;
            if (!(bidirectionalMutation(scene, m.walk, m.range, x, rng, y) > 0) || y.k() != k) continue;
            Vec3 p = y.x[1].sp.p;
            bool light = length(p - lightHit) < 1e-4f, camera = length(p - cameraHit) < 1e-4f;
            fromLight += light, fromCamera += camera;
            wrong += light != (u >= 0.5) || light == camera;
        }
    }
    MESSAGE(fromLight << " new vertices made by the light walk, " << fromCamera << " by the camera walk, " << wrong << " by the wrong one");
    CHECK(fromLight > 30);
    CHECK(fromCamera > 30);
    CHECK(wrong == 0);
}

// T(y|x) of the bidirectional mutation counts the lobes the walks took at new glass vertices (F or
// 1 - F), as f does. Written out here, T's lobes from Fresnel's equations (glassLobe), its split
// densities from the path's pL and pE (which the first test checks against every strategy), its
// length and place probabilities from the code (checked on diffuse paths above): on cornell-glass,
// proposals whose new vertices include glass must match the code's ratio. Without the lobes in T,
// a refraction's 1 - F (about 0.96) and a reflection's F (about 0.04) stay in f alone.
TEST_CASE("the bidirectional mutation's T counts the glass lobes of its new vertices") {
    Scene scene = sceneAt("scenes/cornell-glass.scene", 32, 32);
    const MutationOptions m = mutationOptions(6);
    auto T = [&](const MutatedPath& from, const MutatedPath& to, int a, int kd, int ka, bool& throughGlass) {
        double sum = 0, lobes = 1;
        for (int s = 0; s < ka; ++s) {  // s of the ka - 1 new vertices from the light side
            int lightEnd = a + s - 1, cameraEnd = a + s;
            if ((lightEnd >= 0 && !connectable(scene, to.x[lightEnd])) || !connectable(scene, to.x[cameraEnd])) continue;
            double p = 1;
            for (int i = a; i < a + ka - 1; ++i) p *= i < a + s ? to.pL[i] : to.pE[i];
            sum += p;
        }
        for (int i = a; i < a + ka - 1; ++i) lobes *= glassLobe(scene, to, i), throughGlass |= !connectable(scene, to.x[i]);
        int places = deletionPlaces(scene, from, kd, ka);
        return places ? deletionProbability(kd, from.k()) * additionProbability(ka, kd, from.k(), m.range) / (double(places) * ka) * sum * lobes : 0;
    };
    Rng rng = makeRng(13, 0, 0);
    int compared = 0, agree = 0;
    for (const MutatedPath& x : startPaths(scene, m.opt, 300))
        for (int proposal = 0; proposal < 40; ++proposal) {
            MutatedPath y;
            double ratio = bidirectionalMutation(scene, m.walk, m.range, x, rng, y);
            int a, kd, ka;
            if (!(ratio > 0) || !replacedRange(x, y, a, kd, ka)) continue;
            bool glass = false;
            double forward = T(x, y, a, kd, ka, glass), backward = T(y, x, a, ka, kd, glass);
            if (!glass) continue;
            ++compared;
            agree += std::fabs(ratio / (y.f * backward / (x.f * forward)) - 1) < 1e-4;
        }
    MESSAGE(agree << " of " << compared << " proposals replacing or making glass vertices as written out");
    CHECK(compared > 100);
    CHECK(agree == compared);
}
