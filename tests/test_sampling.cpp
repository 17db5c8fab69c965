// Every sampling routine against the density MIS uses for it: chi-square goodness-of-fit tests
// (as pbrt, Nori and Mitsuba ship them) of BSDF, light-point, light-choice, emission and camera
// sampling, and per sample: the density it reports equals the density evaluated for its result,
// and its weight equals f cos / pdf. A deliberately wrong density must fail the same test.
#include "helpers.h"

// -- Chi-square machinery -----------------------------------------------------------------
// Q(a, x) = Gamma(a, x) / Gamma(a), the regularized upper incomplete gamma function: a series for
// x < a + 1, else a continued fraction (modified Lentz), each to double precision.
static double gammaQ(double a, double x) {
    if (x <= 0) return 1;
    double logPrefix = a * std::log(x) - x - std::lgamma(a);
    if (x < a + 1) {
        double term = 1 / a, sum = term;
        for (int n = 1; n < 10000 && std::fabs(term) > 1e-16 * std::fabs(sum); ++n) sum += term *= x / (a + n);
        return 1 - sum * std::exp(logPrefix);
    }
    double b = x + 1 - a, c = 1e300, d = 1 / b, h = d;
    for (int i = 1; i < 10000; ++i) {
        double an = -i * (i - a);
        b += 2;
        d = an * d + b;
        if (std::fabs(d) < 1e-300) d = 1e-300;
        c = b + an / c;
        if (std::fabs(c) < 1e-300) c = 1e-300;
        d = 1 / d;
        double step = d * c;
        h *= step;
        if (std::fabs(step - 1) < 1e-16) break;
    }
    return std::exp(logPrefix) * h;
}

struct ChiSquare {
    double pValue = 0, chi2 = 0;
    int cells = 0;
};

// Observed against expected counts; cells expecting fewer than 5 are pooled into one (and left
// out if the pool still expects fewer than 5). Degrees of freedom: cells - 1.
static ChiSquare chiSquare(const std::vector<double>& observed, const std::vector<double>& expected) {
    ChiSquare r;
    double pooledObserved = 0, pooledExpected = 0;
    for (size_t i = 0; i < observed.size(); ++i) {
        if (expected[i] < 5) {
            pooledObserved += observed[i];
            pooledExpected += expected[i];
            continue;
        }
        r.chi2 += sqr(float(observed[i] - expected[i])) / expected[i];
        ++r.cells;
    }
    if (pooledExpected >= 5) {
        r.chi2 += (pooledObserved - pooledExpected) * (pooledObserved - pooledExpected) / pooledExpected;
        ++r.cells;
    } else if (pooledObserved > 5 * std::max(1.0, pooledExpected) + 10) {
        r.chi2 = 1e30;  // samples where the density says there are almost none
    }
    r.pValue = r.cells > 1 ? gammaQ((r.cells - 1) / 2.0, r.chi2 / 2.0) : 1;
    return r;
}

// Reject at 1% for the file as a whole: with about 25 fits, each at 1 - 0.99^(1/25) (Sidak, as
// Nori and Mitsuba correct for many tests). A wrong density fails by far more (p < 1e-6).
const double kAlpha = 1 - std::pow(0.99, 1.0 / 25);
constexpr int kThetaBins = 20, kPhiBins = 40, kSamples = 400000;

// Directions sampled by `sample` (false: no direction, e.g. absorbed below the surface),
// binned in theta x phi around the frame's n, theta in [0, thetaMax]; the expected count of a
// cell is N times the integral of `pdf` (solid angle) over it, by the midpoint rule on sub x sub
// points with the element sin(theta) dtheta dphi (a density with an edge inside cells, like the
// camera's, needs a finer rule). The cells' complement (no direction) is one more cell.
// Sampler::Sobol: sample i draws point i of one scrambled Sobol sequence, as pass i of a pixel.
template <class Sample, class Pdf>
static ChiSquare chiSquareDirections(const Frame& frame, Sample sample, Pdf pdf, uint64_t seed, float thetaMax = kPi, int sub = 8,
                                     Sampler sampler = Sampler::Random) {
    Rng rng = makeRng(seed, 1, 2);
    RenderOptions sobol;
    sobol.seed = seed;
    const int cells = kThetaBins * kPhiBins;
    std::vector<double> observed(cells + 1, 0), expected(cells + 1, 0);
    for (int i = 0; i < kSamples; ++i) {
        if (sampler == Sampler::Sobol) rng = sampleRng(sobol, 0, 0, uint64_t(i));
        Vec3 w;
        if (!sample(rng, w)) { observed[cells] += 1; continue; }
        Vec3 local(dot(w, frame.s), dot(w, frame.t), dot(w, frame.n));
        float theta = std::acos(std::min(1.0f, std::max(-1.0f, local.z)));
        float phi = std::atan2(local.y, local.x);
        if (phi < 0) phi += 2 * kPi;
        if (theta >= thetaMax) { observed[cells] += 1; continue; }
        int ti = std::min(kThetaBins - 1, int(theta / thetaMax * kThetaBins)), pi = std::min(kPhiBins - 1, int(phi / (2 * kPi) * kPhiBins));
        observed[ti * kPhiBins + pi] += 1;
    }
    double total = 0;
    for (int ti = 0; ti < kThetaBins; ++ti)
        for (int pi = 0; pi < kPhiBins; ++pi) {
            double sum = 0, dTheta = thetaMax / kThetaBins / sub, dPhi = 2 * kPi / kPhiBins / sub;
            for (int a = 0; a < sub; ++a)
                for (int b = 0; b < sub; ++b) {
                    double theta = (ti * sub + a + 0.5) * dTheta, phi = (pi * sub + b + 0.5) * dPhi;
                    Vec3 local(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)));
                    sum += pdf(frame.toWorld(local)) * std::sin(theta) * dTheta * dPhi;
                }
            expected[ti * kPhiBins + pi] = sum * kSamples;
            total += sum;
        }
    expected[cells] = std::max(0.0, 1 - total) * kSamples;
    return chiSquare(observed, expected);
}

// wo at angle theta from the normal (0, 0, 1), in the x-z plane.
static Vec3 incoming(float degrees) {
    float t = degrees * kPi / 180;
    return {std::sin(t), 0, std::cos(t)};
}

// A BSDF's sampler against evalBsdf's density, and per sample pdf and weight against evalBsdf.
struct BsdfCheck {
    ChiSquare fit;
    double worstPdf = 0, worstWeight = 0;
};

static BsdfCheck checkBsdf(const Material& m, Vec3 wo, uint64_t seed, bool wrongPdf = false, Sampler sampler = Sampler::Random) {
    Scene scene = singleQuadScene(m);
    SurfacePoint sp = surfaceAtOrigin();
    BsdfCheck c;
    auto sample = [&](Rng& rng, Vec3& w) {
        BsdfSample bs;
        if (!sampleBsdf(scene, sp, wo, Transport::Radiance, rng, bs)) return false;
        float pdf, pdfReverse;
        Vec3 f = evalBsdf(scene, sp, wo, bs.wi, Transport::Radiance, pdf, pdfReverse);
        c.worstPdf = std::max(c.worstPdf, std::fabs(double(bs.pdf) - pdf) / pdf);
        c.worstWeight = std::max(c.worstWeight, double(maxComponent(absVec(bs.weight - f / pdf)) / maxComponent(f / pdf)));
        w = bs.wi;
        return true;
    };
    auto pdf = [&](Vec3 w) { return wrongPdf ? (w.z > 0 ? 1 / (2 * kPi) : 0.0f) : pdfBsdf(scene, sp, wo, w); };
    c.fit = chiSquareDirections(Frame(Vec3(0, 0, 1)), sample, pdf, seed, kPi, 8, sampler);
    return c;
}

TEST_CASE("chi-square: diffuse and glossy BSDF sampling fit their densities at several incident angles") {
    uint64_t seed = 1;
    for (float angle : {0.0f, 45.0f, 80.0f}) {
        CAPTURE(angle);
        BsdfCheck diffuse = checkBsdf(makeMaterial(Material::Diffuse, 0.8f), incoming(angle), seed++);
        CHECK(diffuse.fit.pValue > kAlpha);
        CHECK(diffuse.fit.cells > 100);
        CHECK(diffuse.worstPdf < 1e-4);
        CHECK(diffuse.worstWeight < 1e-4);
        for (float exponent : {5.0f, 50.0f, 300.0f}) {
            CAPTURE(exponent);
            BsdfCheck glossy = checkBsdf(makeMaterial(Material::Glossy, 0.8f, exponent), incoming(angle), seed++);
            CHECK(glossy.fit.pValue > kAlpha);
            CHECK(glossy.worstPdf < 1e-3);
            CHECK(glossy.worstWeight < 1e-3);
        }
    }
}

// With quasi-random numbers the counts are closer to their expectations than chance allows (chi^2
// far below its degrees of freedom), which the test passes; a wrong density is still far off.
TEST_CASE("chi-square with --sampler sobol: BSDF sampling fits, more evenly than chance; a wrong density still fails") {
    for (float angle : {0.0f, 60.0f}) {
        CAPTURE(angle);
        BsdfCheck diffuse = checkBsdf(makeMaterial(Material::Diffuse, 0.8f), incoming(angle), 7, false, Sampler::Sobol);
        BsdfCheck glossy = checkBsdf(makeMaterial(Material::Glossy, 0.8f, 50), incoming(angle), 8, false, Sampler::Sobol);
        CHECK(diffuse.fit.pValue > kAlpha);
        CHECK(glossy.fit.pValue > kAlpha);
        CHECK(diffuse.fit.chi2 < 0.5 * diffuse.fit.cells);  // independent numbers give about `cells`
        CHECK(glossy.fit.chi2 < 0.5 * glossy.fit.cells);
    }
    BsdfCheck uniform = checkBsdf(makeMaterial(Material::Diffuse, 0.8f), incoming(30), 9, true, Sampler::Sobol);
    CHECK(uniform.fit.pValue < 1e-6);
}

TEST_CASE("chi-square: a deliberately wrong density fails (cosine sampling evaluated as uniform; Phong's n+2 for n+1)") {
    BsdfCheck uniform = checkBsdf(makeMaterial(Material::Diffuse, 0.8f), incoming(30), 50, true);
    CHECK(uniform.fit.pValue < 1e-6);
    // The glossy sampler against a density normalized with (n+2)/(2 pi), f's factor, not (n+1)/(2 pi).
    Scene scene = singleQuadScene(makeMaterial(Material::Glossy, 0.8f, 20));
    SurfacePoint sp = surfaceAtOrigin();
    Vec3 wo = incoming(30);
    auto sample = [&](Rng& rng, Vec3& w) {
        BsdfSample bs;
        if (!sampleBsdf(scene, sp, wo, Transport::Radiance, rng, bs)) return false;
        w = bs.wi;
        return true;
    };
    ChiSquare wrong = chiSquareDirections(Frame(Vec3(0, 0, 1)), sample, [&](Vec3 w) { return pdfBsdf(scene, sp, wo, w) * 22.0f / 21.0f; }, 51);
    CHECK(wrong.pValue < 1e-6);
}

TEST_CASE("chi-square: glass chooses reflection with probability F and refraction otherwise, in both directions") {
    Material glass = makeMaterial(Material::Glass, 1, 1.5f);
    Scene scene = singleQuadScene(glass);
    SurfacePoint sp = surfaceAtOrigin();
    Rng rng = makeRng(9, 0, 0);
    for (float angle : {0.0f, 30.0f, 60.0f, 85.0f})
        for (bool inside : {false, true}) {
            CAPTURE(angle);
            CAPTURE(inside);
            Vec3 wo = incoming(angle);
            if (inside) wo.z = -wo.z;
            float etaO = inside ? 1.5f : 1, etaT = inside ? 1 : 1.5f;
            float F = fresnelDielectric(std::fabs(wo.z), etaO / etaT);
            // Tabulated (Fresnel's equations, eta 1.5, computed independently): the sampler must
            // choose with these in both directions of the interface (an inverted eta swaps them).
            if (angle == 30) CHECK(F == doctest::Approx(inside ? 0.055190 : 0.041523).epsilon(1e-4));
            if (angle == 60) CHECK(F == doctest::Approx(inside ? 1.0 : 0.089187).epsilon(1e-4));
            std::vector<double> observed(2, 0);
            const int n = 100000;
            double worstSnell = 0;
            for (int i = 0; i < n; ++i) {
                BsdfSample bs;
                bool ok = sampleBsdf(scene, sp, wo, Transport::Radiance, rng, bs);
                REQUIRE(ok);
                CHECK(bs.delta);
                bool reflected = bs.wi.z * wo.z > 0;
                observed[reflected ? 0 : 1] += 1;
                CHECK(bs.pdf == doctest::Approx(reflected ? F : 1 - F));
                if (reflected) {
                    worstSnell = std::max(worstSnell, double(length(bs.wi - reflect(wo, Vec3(0, 0, wo.z > 0 ? 1.0f : -1.0f)))));
                } else {  // Snell: eta_o sin_o = eta_t sin_t, in the plane of incidence, opposite side
                    float sinO = std::sqrt(1 - wo.z * wo.z), sinT = std::sqrt(std::max(0.0f, 1 - bs.wi.z * bs.wi.z));
                    worstSnell = std::max(worstSnell, double(std::fabs(etaO * sinO - etaT * sinT)));
                    CHECK(bs.wi.x * wo.x <= 0);
                }
            }
            CHECK(worstSnell < 1e-5);
            if (F >= 1) {
                CHECK(observed[1] == 0);  // total internal reflection
            } else {
                ChiSquare fit = chiSquare(observed, {n * double(F), n * (1 - double(F))});
                CHECK(fit.pValue > kAlpha);
            }
        }
}

// Two lights of different kinds and powers, for the light choice and the light points.
static Scene twoLightScene() {
    return parseScene("camera 0 1 -4  0 1 0  0 1 0  50  16 16\nmaterial white diffuse 0.8 0.8 0.8\n"
                      "quad -2 0 -2  4 0 0  0 0 4  white\n"
                      "quad -0.5 2.9 -0.5  1 0 0  0 0 1.5  white emit 8 6 4\n"
                      "sphere 1 1 1  0.3  white emit 2 2 2\n"
                      "pointlight -1 2 0  10 10 10\n", "two-lights");
}

TEST_CASE("chi-square: lights are chosen by power (Phi = pi Le A, 4 pi I), and each point's density is pdfLightPoint") {
    Scene scene = twoLightScene();
    REQUIRE(scene.lights.size() == 3);
    std::vector<double> power;
    for (const Light& l : scene.lights) power.push_back(lightPower(l, scene.shapes));
    CHECK(power[0] == doctest::Approx(4 * kPi * 10));              // the point light, I = 10
    CHECK(power[1] == doctest::Approx(kPi * 1.5 * 6));             // the quad: A = 1.5, mean Le = 6
    CHECK(power[2] == doctest::Approx(kPi * 4 * kPi * 0.09 * 2));  // the sphere: A = 4 pi r^2
    Rng rng = makeRng(4, 0, 0);
    const int n = 300000;
    std::vector<double> observed(3, 0), expected;
    double worstPdf = 0;
    for (int i = 0; i < n; ++i) {
        LightPoint lp = sampleLightPoint(scene, rng);
        observed[lp.light] += 1;
        double p = lp.deltaPosition ? lightChoiceProbability(scene, lp.light) : pdfLightPoint(scene, lp.sp.shape);
        worstPdf = std::max(worstPdf, std::fabs(p - lp.pdfArea) / p);
    }
    double total = power[0] + power[1] + power[2];
    for (double p : power) expected.push_back(n * p / total);
    CHECK(chiSquare(observed, expected).pValue > kAlpha);
    CHECK(worstPdf < 1e-6);
    for (int l = 0; l < 3; ++l) CHECK(lightChoiceProbability(scene, l) == doctest::Approx(power[l] / total));
    // A uniform choice instead of one by power fails.
    CHECK(chiSquare(observed, {n / 3.0, n / 3.0, n / 3.0}).pValue < 1e-6);
}

TEST_CASE("chi-square: points on quads are uniform in (a, b); points on spheres uniform in direction") {
    Scene scene = twoLightScene();
    const int quad = 1, sphere = 2, bins = 20;
    Rng rng = makeRng(5, 0, 0);
    const Shape& q = scene.shapes[quad];
    Vec3 w = quadW(q.u, q.v);
    std::vector<double> observed(bins * bins, 0), expected(bins * bins, double(kSamples) / (bins * bins));
    for (int i = 0; i < kSamples; ++i) {
        SurfacePoint sp = sampleShapePoint(scene, quad, rng.uniform(), rng.uniform());
        Vec3 rel = sp.p - q.p;
        float a = dot(w, cross(rel, q.v)), b = dot(w, cross(q.u, rel));
        observed[std::min(bins - 1, std::max(0, int(b * bins))) * bins + std::min(bins - 1, std::max(0, int(a * bins)))] += 1;
    }
    CHECK(chiSquare(observed, expected).pValue > kAlpha);
    const Shape& s = scene.shapes[sphere];
    auto sample = [&](Rng& r, Vec3& d) {
        SurfacePoint sp = sampleShapePoint(scene, sphere, r.uniform(), r.uniform());
        d = normalize(sp.p - s.p);
        return true;
    };
    CHECK(chiSquareDirections(Frame(Vec3(0, 0, 1)), sample, [](Vec3) { return 1 / (4 * kPi); }, 6).pValue > kAlpha);
}

TEST_CASE("chi-square: emission directions are cosine around the normal (area) and uniform (point); weight = Le cos / (p_A p_omega)") {
    Scene scene = twoLightScene();
    for (int light : {0, 1, 2}) {
        CAPTURE(light);
        Vec3 normal;
        double worstPdf = 0, worstWeight = 0;
        bool sawNormal = false;
        auto sample = [&](Rng& rng, Vec3& d) {
            EmissionSample es = sampleEmission(scene, rng);
            if (es.point.light != light) return false;
            PathVertex y0 = lightVertex(es.point);
            float p = pdfEmissionDirection(y0, es.dir);
            worstPdf = std::max(worstPdf, std::fabs(double(p) - es.pdfDir) / p);
            float cosLight = es.point.deltaPosition ? 1 : dot(es.dir, es.point.sp.ng);
            Vec3 expectedWeight = es.point.emission * (cosLight / (es.point.pdfArea * p));
            worstWeight = std::max(worstWeight, double(maxComponent(absVec(es.weight - expectedWeight)) / maxComponent(expectedWeight)));
            if (!es.point.deltaPosition && !sawNormal) { normal = es.point.sp.ng; sawNormal = true; }
            d = es.dir;
            if (!es.point.deltaPosition) {  // rotate into the frame of (0,0,1): one frame for every point of a sphere
                Frame f(es.point.sp.ng);
                d = Vec3(dot(d, f.s), dot(d, f.t), dot(d, f.n));
            }
            return true;
        };
        // Samples of the other lights count as "no direction": the expected share of this light
        // is its choice probability, so the test also checks the choice.
        float choice = lightChoiceProbability(scene, light);
        bool point = scene.lights[light].type == Light::Point;
        auto pdf = [&](Vec3 d) { return choice * (point ? 1 / (4 * kPi) : std::max(0.0f, d.z) / kPi); };
        ChiSquare fit = chiSquareDirections(Frame(Vec3(0, 0, 1)), sample, pdf, 20 + light);
        CHECK(fit.pValue > kAlpha);
        CHECK(worstPdf < 1e-4);  // a 1e-7 error in the cosine of a grazing direction (sphere)
        CHECK(worstWeight < 1e-4);
    }
}

TEST_CASE("chi-square: the pinhole's directions have density 1/(A cos^3), and W_e cos / p = 1") {
    Scene scene = sceneAt("scenes/cornell.scene", 32, 24);
    const Camera& cam = scene.camera;
    double worstImportance = 0;
    auto sample = [&](Rng& rng, Vec3& d) {
        int x = int(rng.uniform() * cam.width), y = int(rng.uniform() * cam.height);
        float fx = filmCoordinate(x, rng.uniform()), fy = filmCoordinate(y, rng.uniform());
        d = cameraRay(cam, fx, fy).d;
        double pixelShare = pixelImportance(cam, d) * dot(d, cam.forward) / (double(cam.width) * cam.height);
        worstImportance = std::max(worstImportance, std::fabs(pixelShare / pdfCameraDirection(cam, d) - 1));
        return true;
    };
    // Cells around the axis out to the image's corner; the image's edges cut through cells.
    float corner = std::atan(cam.tanHalfFov * std::sqrt(1 + sqr(cam.aspect))) * 1.001f;
    ChiSquare fit = chiSquareDirections(Frame(cam.forward), sample, [&](Vec3 d) { return pdfCameraDirection(cam, d); }, 30, corner, 48);
    CHECK(fit.pValue > kAlpha);
    CHECK(fit.cells > 50);
    CHECK(worstImportance < 1e-4);
    // cos^2 instead of cos^3 fails.
    ChiSquare wrong = chiSquareDirections(Frame(cam.forward), sample, [&](Vec3 d) { return pdfCameraDirection(cam, d) * dot(d, cam.forward); }, 31, corner, 48);
    CHECK(wrong.pValue < 1e-6);
}

TEST_CASE("the incomplete gamma function: chi-square tail probabilities of known values") {
    CHECK(gammaQ(0.5, 3.841 / 2) == doctest::Approx(0.05).epsilon(1e-3));   // 1 degree of freedom, 95%
    CHECK(gammaQ(5, 23.209 / 2) == doctest::Approx(0.01).epsilon(1e-3));    // 10 degrees of freedom, 99%
    CHECK(gammaQ(50, 124.342 / 2) == doctest::Approx(0.05).epsilon(2e-3));  // 100 degrees of freedom, 95%
    CHECK(gammaQ(2, 0) == 1);
}
