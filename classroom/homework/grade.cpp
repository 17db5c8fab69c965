// classroom/homework/grade.cpp: the homework's grader. Compiled with a student's bdpt.cpp (the one
// beside it in their folder, or make grade HOMEWORK=FILE in the repository), it checks each task
// of grader/tasks.txt by the physics, never by the code's shape, and knows no solution: closed
// forms (a square lamp's irradiance, the pinhole's importance, the furnace's sums, Fresnel and
// Snell's eta^2, the adjoint's ratio), one method or strategy against another, weights that sum
// to 1, and images the complete renderer made when the homework was handed out (grader/data/).
// Each task runs in a child process with a CPU-seconds and a memory limit: a crash, an endless
// loop or a huge allocation costs that task its points and says so; the others go on.
//   grade [--task ID] [--data DIR] [--tasks FILE] [--cpu-limit S] [--seed N] [--json FILE]   grade the tasks
//     (--json: Gradescope's results.json; compiled with -DBDPT_HIDDEN_CHECKS, hidden.h's checks too)
//   grade --write-data DIR                          make the data (run with the complete bdpt.cpp)
// A mistake is named where its fingerprint is recognised: each check measures at several points
// and compares the measurements with the physics and with what each classic mistake would give
// there (the mistake's formula, integrated the same way), and names the one that fits.
#define BDPT_NO_MAIN
#include "bdpt.cpp"
#include "physics.h"
#include "harness.h"  // a check, its process with limits, the report and Gradescope's results.json

namespace grade {

std::string dataDir = "grader/data";

std::string num(double x, int digits = 4) {
    char t[64];
    std::snprintf(t, sizeof t, "%.*g", digits, x);
    return t;
}
std::string list(const std::vector<double>& v, int digits = 4) {
    std::string s;
    for (double x : v) s += (s.empty() ? "" : ", ") + num(x, digits);
    return s;
}

// ---- images and statistics
Image dataImage(const std::string& name) {
    Image img;
    if (!readPFM(dataDir + "/" + name + ".pfm", img)) throw std::runtime_error("the grader's data " + dataDir + "/" + name + ".pfm is missing");
    return img;
}
// Each region's mean (grid x grid, all channels) of an image.
std::vector<double> regionMeans(const Image& img, int grid) {
    std::vector<double> sum(size_t(grid * grid), 0.0);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) sum[size_t((y * grid / img.height) * grid + x * grid / img.width)] += average(img.at(x, y));
    for (double& s : sum) s /= double(img.width) * img.height / (grid * grid);
    return sum;
}

// A render's region means with their standard errors from the spread of the passes' (independent).
struct Estimate {
    std::vector<double> mean, se;
    double imageMean = 0, imageSe = 0;
    long long nonFinite = 0;
    RenderResult result;
};
Estimate summarize(const std::vector<std::vector<double>>& perPass) {  // [pass][region]; the last region the whole
    Estimate e;
    const size_t R = perPass[0].size(), n = perPass.size();
    for (size_t r = 0; r < R; ++r) {
        double m = 0, q = 0;
        for (const auto& p : perPass) m += p[r] / double(n);
        for (const auto& p : perPass) q += sqr(float(p[r] - m));
        e.mean.push_back(m);
        e.se.push_back(n > 1 ? std::sqrt(q / double(n - 1) / double(n)) : 0);
    }
    e.imageMean = e.mean.back(), e.imageSe = e.se.back();
    e.mean.pop_back(), e.se.pop_back();
    return e;
}
// value(rendering, pixel) of each pass, per region.
template <class Value>
Estimate estimate(const Scene& scene, RenderOptions opt, int grid, const Value& value) {
    const int W = scene.camera.width, H = scene.camera.height;
    opt.threads = 1;
    Rendering r(scene, opt);
    std::vector<std::vector<double>> perPass;
    do {
        r.addPass();
        std::vector<double> s(size_t(grid * grid + 1), 0.0);
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                double v = value(r, y * W + x);
                s[size_t((y * grid / H) * grid + x * grid / W)] += v / (double(W) * H / (grid * grid));
                s.back() += v / (double(W) * H);
            }
        perPass.push_back(s);
    } while (morePasses(r));
    Estimate e = summarize(perPass);
    e.result = r.finish();
    e.nonFinite = e.result.nonFinite;
    return e;
}
Estimate estimate(const Scene& scene, const RenderOptions& opt, int grid) {
    return estimate(scene, opt, grid, [](const Rendering& r, int i) { return double(average(r.pass[size_t(i)])); });
}

std::string regionName(int r, int grid) {
    static const char* rows[] = {"top", "upper middle", "lower middle", "bottom"};
    static const char* cols[] = {"left", "left of centre", "right of centre", "right"};
    if (grid != 4) return "region " + std::to_string(r);
    return std::string(rows[r / 4]) + " " + cols[r % 4];
}

// An estimate against a reference, region by region: it fails where a region is both more than 5
// standard errors and more than `tolerance` (relative) away. Its words: the image's ratio, and the
// region most off.
struct Comparison {
    bool pass = true;
    double ratio = 1, worstZ = 0, worstRatio = 1;
    int worst = -1;
    std::vector<double> ratios;
    std::string text;
};
Comparison compare(const Estimate& e, const std::vector<double>& ref, int grid, double tolerance = 0.03) {
    Comparison c;
    double sum = 0, refSum = 0;
    for (size_t r = 0; r < ref.size(); ++r) {
        sum += e.mean[r], refSum += ref[r];
        double rel = ref[r] > 0 ? e.mean[r] / ref[r] : (e.mean[r] > 0 ? 1e9 : 1);
        c.ratios.push_back(rel);
        double z = std::fabs(e.mean[r] - ref[r]) / std::max(e.se[r], 1e-12);
        bool off = z > 5 && std::fabs(e.mean[r] - ref[r]) > tolerance * std::max(ref[r], 1e-3 * refSum / ref.size());
        if (off && (c.worst < 0 || std::fabs(std::log(std::max(rel, 1e-9))) > std::fabs(std::log(std::max(c.worstRatio, 1e-9))))) c.worst = int(r), c.worstRatio = rel, c.worstZ = z;
        c.pass = c.pass && !off;
    }
    c.ratio = refSum > 0 ? sum / refSum : 0;
    if (!std::isfinite(c.ratio) || sum == 0 || e.nonFinite > 0) c.pass = false;
    if (sum == 0) c.text = "the image is black";
    else if (!c.pass)
        c.text = "the image mean is " + num(c.ratio, 3) + "x the reference's" +
                 (c.worst >= 0 ? "; most off, the " + regionName(c.worst, grid) + " region: " + num(c.worstRatio, 3) + "x" +
                                     (c.worstZ < 1e4 ? " (" + num(c.worstZ, 3) + " standard errors)" : "") : "");
    if (e.nonFinite > 0) c.text += (c.text.empty() ? "" : "; ") + std::to_string(e.nonFinite) + " samples were NaN or infinite and dropped (a division by 0?)";
    return c;
}

// ---- fingerprints: measurements at several points against the physics and each classic mistake
struct Model {
    std::string name, diagnosis;       // name "right": the physics
    std::vector<double> predicted;
};
struct Fit {
    bool pass = false;
    std::string text, mistake;
};
// A diagnosis's first clause (up to its first colon, semicolon or bracket): how a class's report
// names the mistake.
std::string firstClause(const std::string& diagnosis) {
    std::string c = diagnosis.substr(0, diagnosis.find_first_of(":;("));
    while (!c.empty() && (c.back() == ' ' || c.back() == ',')) c.pop_back();
    return c;
}
// measured[i] with standard error se[i] (0 for an exact computation) against the models; the
// physics is models[0]. Passes where every point is within 4 standard errors and `tolerance` of it.
Fit fitModels(const std::vector<double>& measured, const std::vector<double>& se, const std::vector<Model>& models, const std::string& what,
              double tolerance = 0.01) {
    auto misfit = [&](const Model& m) {
        double worst = 0;
        for (size_t i = 0; i < measured.size(); ++i) {
            if (!std::isfinite(measured[i])) return 1e30;
            double scale = std::max(4 * se[i], tolerance * std::fabs(m.predicted[i]) + 1e-9);
            worst = std::max(worst, std::fabs(measured[i] - m.predicted[i]) / scale);
        }
        return std::isfinite(worst) ? worst : 1e30;
    };
    Fit f;
    f.pass = misfit(models[0]) <= 1;
    if (f.pass) return f;
    bool black = true;
    for (double m : measured) black = black && m == 0;
    if (measured.size() <= 6) {
        f.text = what + ": expected " + list(models[0].predicted) + ", measured " + list(measured);
    } else {  // many points: the first, and the range of measured / expected
        double lo = 1e300, hi = -1e300;
        for (size_t i = 0; i < measured.size(); ++i) {
            double r = models[0].predicted[i] != 0 ? measured[i] / models[0].predicted[i] : 0;
            lo = std::min(lo, r), hi = std::max(hi, r);
        }
        f.text = what + ": at the first, expected " + num(models[0].predicted[0]) + ", measured " + num(measured[0]) +
                 "; measured / expected from " + num(lo, 3) + " to " + num(hi, 3);
    }
    size_t best = 0;
    for (size_t k = 1; k < models.size(); ++k)
        if (misfit(models[k]) < misfit(models[best])) best = k;
    const bool named = best > 0 && misfit(models[best]) <= 1;  // a mistake that gives 0 (a limit off by one) is named too
    if (black && !named) return f.text += " (all 0)", f;
    for (double m : measured)
        if (!std::isfinite(m)) return f.text += " (NaN or infinite: a 0/0, or a division by a density of 0, somewhere; the renderer drops such samples)", f;
    if (named) f.text += ": " + models[best].diagnosis, f.mistake = firstClause(models[best].diagnosis);
    else if (models.size() > 1) f.text += ": no classic mistake fits these numbers (read the formula again on the notes' page)";
    return f;
}

// ---- scenes the checks build for themselves
Scene scene(const std::string& file, int w, int h) {
    Scene s = loadScene(file);
    setResolution(s.camera, w, h);
    return s;
}
// Every check's random numbers start from its own seed, plus --seed's (the grader's own tests run
// a correct renderer at many seeds: no check may fail it by chance).
uint64_t gSeed = 0;
Rng checkRng(uint64_t seed, uint64_t a, uint64_t b) { return makeRng(seed + 1000 * gSeed, a, b); }
RenderOptions options(Method m, int spp, uint64_t seed = 1) {
    RenderOptions o;
    o.method = m;
    o.spp = spp;
    o.seed = seed + 1000 * gSeed;
    o.threads = 1;
    return o;
}
// A floor of albedo 0.5 under a square lamp (0.8 x 0.8, radiance 4, facing down at height 2), and a
// plate at height 1 that hides the lamp from the floor around x = 3; or a point light there.
const char* kLampScene = "camera 0 1 -6  0 0.5 0  0 1 0  40  32 32\n"
                         "material floor diffuse 0.5 0.5 0.5\nmaterial black diffuse 0 0 0\n"
                         "quad -6 0 6  12 0 0  0 0 -12  floor\n"
                         "quad -0.4 2 -0.4  0.8 0 0  0 0 0.8  black emit 4 4 4\n"
                         "quad 1 1 -1  0 0 2  1 0 0  floor\n";
const char* kPointScene = "camera 0 1 -6  0 0.5 0  0 1 0  40  32 32\n"
                          "material floor diffuse 0.5 0.5 0.5\n"
                          "quad -6 0 6  12 0 0  0 0 -12  floor\n"
                          "pointlight 0 2 0  5 5 5\n";
SurfacePoint floorPoint(const Scene& s, Vec3 p) {  // the floor is shape 0
    SurfacePoint sp = makeSurfacePoint(s.shapes[0], 0, p, false);
    return sp;
}

}  // namespace grade

// ============================================================================================
// H1 path tracing: samplePT in the furnace (its partial sums are closed forms) and on cornell;
// estimateDirect at points under a square lamp (Lambert's closed form for a polygon's irradiance),
// behind a plate, under a point light, and with the power heuristic (the weighted integral).
namespace grade {

// The furnace: a closed sphere of albedo a = 0.5 emitting Le = 1; paths of at most D bounces
// give Le (1 + a + ... + a^D). Without roulette every sample is exact.
double furnaceMean(int maxDepth, int rrStart, int size, int spp) {
    Scene s = scene("scenes/furnace.scene", size, size);
    RenderOptions o = options(Method::PT, spp, 3);
    o.maxDepth = maxDepth;
    o.rrStart = rrStart;
    return imageMean(render(s, o).image);
}

// Every path of the furnace, without roulette, carries the same value: Le (1 + a) at --maxdepth 1.
// A pixel of one sample at exactly Le is a path that ended at its bounce, where nothing can end it.
double shareEndedAtFirstBounce() {
    Scene s = scene("scenes/furnace.scene", 16, 16);
    RenderOptions o = options(Method::PT, 1, 5);
    o.maxDepth = 1;
    o.rrStart = 1000;
    Image img = render(s, o).image;
    int ended = 0;
    for (const Vec3& v : img.pixels) ended += std::fabs(v.x - 1) < 1e-4;
    return double(ended) / img.pixels.size();
}
// A furnace that no fingerprint fits, and paths that end where none can: the diagnosis says why.
void nameLostPaths(Fit& f) {
    if (f.pass || !f.mistake.empty()) return;
    double lost = shareEndedAtFirstBounce();
    if (lost <= 0.02) return;
    const std::string selfHit = "the next ray starts exactly on its surface and hits that surface again (rounding puts its origin "
                                "behind it about half the time): start it with spawnRay, which pushes it off along the normal";
    const std::string none = ": no classic mistake fits these numbers (read the formula again on the notes' page)";
    if (f.text.size() >= none.size() && f.text.compare(f.text.size() - none.size(), none.size(), none) == 0)
        f.text.resize(f.text.size() - none.size());
    f.text += "; at --maxdepth 1, " + num(100 * lost, 2) + "% of the paths end at their first bounce (their pixel is exactly Le, "
              "where every path of the furnace gives Le (1 + a)): " + selfHit;
    f.mistake = firstClause(selfHit);
}

Outcome ptFurnaceDepths() {
    std::vector<double> measured, zero(4, 0.0);
    for (int d = 0; d <= 3; ++d) measured.push_back(furnaceMean(d, 1000, 8, 4));
    auto series = [](int from, int to) {  // a^from + ... + a^to per depth
        return [from, to](int d) { double s = 0; for (int k = from; k <= d + to; ++k) s += std::pow(0.5, k); return s; };
    };
    auto each = [](const std::function<double(int)>& f) { std::vector<double> v; for (int d = 0; d <= 3; ++d) v.push_back(f(d)); return v; };
    std::vector<Model> models = {
        {"right", "", each(series(0, 0))},
        {"first hit", "emission is counted only where the camera ray first hits: the light a surface sends after a bounce is lost; "
                      "add the emitted radiance at every hit, weighted by the path's throughput (page 1)", each([](int) { return 1.0; })},
        {"no throughput", "the throughput is never multiplied by the BSDF sample's weight (f |cos| / p): every bounce adds the whole "
                          "emission (page 8, T(pi))", each([](int d) { return d + 1.0; })},
        {"one bounce more", "--maxdepth off by one: D bounces keep paths of at most D + 1 segments, yours keep one more (page 4's partial "
                            "sums)", each(series(0, 1))},
        {"one bounce less", "--maxdepth off by one: D bounces keep paths of at most D + 1 segments, yours stop one short (page 4's partial "
                            "sums)", each([](int d) { double s = 0; for (int k = 0; k < d; ++k) s += std::pow(0.5, k); return s; })},
        {"late throughput", "a hit's emission is weighted by the throughput after that hit's own bounce, not the one that reached it",
         each(series(1, 1))},
    };
    Fit f = fitModels(measured, std::vector<double>(4, 0.0), models, "pt in the furnace (albedo 0.5, Le 1) at --maxdepth 0, 1, 2, 3, no roulette", 1e-3);
    nameLostPaths(f);
    return {f.pass, f.text, f.mistake};
}

Outcome ptFurnaceRoulette() {
    Scene s = scene("scenes/furnace.scene", 16, 16);
    Estimate e = estimate(s, options(Method::PT, 32, 5), 1);
    // Without dividing by q, a path that survives roulette keeps the throughput it had: the mean
    // is sum_k a^k times the chance of surviving to bounce k, q_b = min(0.95, a^(b+1)) from bounce 3.
    double unweighted = 0, survive = 1;
    for (int k = 0; k <= 32; ++k) {
        unweighted += std::pow(0.5, k) * survive;
        if (k >= 3) survive *= std::min(0.95, std::pow(0.5, k + 1));
    }
    std::vector<Model> models = {
        {"right", "", {2 - std::pow(0.5, 32)}},
        {"no 1/q", "Russian roulette without dividing the surviving path's throughput by its probability q (russianRoulette "
                   "divides the beta it is given: keep the beta it changes; page 9)", {unweighted}},
    };
    Fit f = fitModels({e.imageMean}, {e.imageSe}, models, "pt in the furnace with Russian roulette (2 expected)", 0.004);
    nameLostPaths(f);
    return {f.pass, f.text, f.mistake};
}

Outcome ptCornell() {
    Scene s = scene("scenes/cornell.scene", 32, 32);
    Estimate e = estimate(s, options(Method::PT, 64, 7), 4);
    Comparison c = compare(e, regionMeans(dataImage("cornell-32"), 4), 4, 0.05);
    return {c.pass, "pt on cornell (32x32, 64 samples) against the reference: " + c.text};
}

// The square lamp's irradiance at p (normal n), by Lambert's formula for a polygon: E = Le/2
// sum_i beta_i n.(v_i x v_i+1)/|v_i x v_i+1|, v_i unit vectors to its corners in order.
double polygonIrradiance(Vec3 p, Vec3 n, const std::vector<Vec3>& corners, double Le) {
    double sum = 0;
    for (size_t i = 0; i < corners.size(); ++i) {
        Vec3 a = normalize(corners[i] - p), b = normalize(corners[(i + 1) % corners.size()] - p), c = cross(a, b);
        double angle = std::acos(std::max(-1.0f, std::min(1.0f, dot(a, b))));
        sum += angle * dot(n, c) / length(c);
    }
    return Le / 2 * std::fabs(sum);
}
// integral over the lamp of integrand(cos_x, cos_y, d, A), by the midpoint rule on 96 x 96 cells.
template <class F>
double overLamp(const Shape& lamp, Vec3 p, Vec3 n, const F& integrand) {
    const int N = 96;
    double sum = 0;
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) {
            Vec3 y = lamp.p + ((i + 0.5f) / N) * lamp.u + ((j + 0.5f) / N) * lamp.v, w = y - p;
            double d = length(w);
            Vec3 u = w / float(d);
            sum += integrand(std::max(0.0f, dot(n, u)), std::max(0.0f, -dot(lamp.normal, u)), d, double(lamp.area)) * lamp.area / (N * N);
        }
    return sum;
}

struct DirectSample {
    std::vector<double> mean, se;
};
DirectSample directAt(const Scene& s, const std::vector<Vec3>& points, bool mis, int n) {
    DirectSample r;
    for (size_t k = 0; k < points.size(); ++k) {
        SurfacePoint sp = floorPoint(s, points[k]);
        double sum = 0, sum2 = 0;
        for (int i = 0; i < n; ++i) {
            Rng rng = checkRng(17, uint64_t(i), k);
            double v = average(estimateDirect(s, sp, Vec3(0, 1, 0), rng, mis));
            sum += v, sum2 += v * v;
        }
        double m = sum / n;
        r.mean.push_back(m);
        r.se.push_back(std::isfinite(m) ? std::sqrt(std::max(0.0, sum2 / n - m * m) / (n - 1)) : 0);
    }
    return r;
}

const std::vector<Vec3> kLampPoints = {Vec3(0, 0, 0), Vec3(-1.5f, 0, 1), Vec3(-4, 0, -1), Vec3(0.8f, 0, 0.8f)};

Outcome directUnderLamp() {
    Scene s = parseScene(kLampScene, "lamp");
    const Shape& lamp = s.shapes[1];
    const double rho = 0.5, Le = 4;
    std::vector<Vec3> corners = {lamp.p, lamp.p + lamp.u, lamp.p + lamp.u + lamp.v, lamp.p + lamp.v};
    auto model = [&](auto integrand) {
        std::vector<double> v;
        for (Vec3 p : kLampPoints) v.push_back(rho / kPi * Le * overLamp(lamp, p, Vec3(0, 1, 0), integrand));
        return v;
    };
    std::vector<double> right;
    for (Vec3 p : kLampPoints) right.push_back(rho / kPi * polygonIrradiance(p, Vec3(0, 1, 0), corners, Le));
    std::vector<Model> models = {
        {"right", "", right},
        {"no light cosine", "the light's cosine |cos theta_y| at the lamp is missing (G has two cosines: evalBsdf gives the one at x, "
                            "the lamp's is yours; page 8)", model([](double cx, double, double d, double) { return cx / (d * d); })},
        {"two receiver cosines", "the cosine at x counted twice: evalBsdf's value is f |cos theta_x| already (section 4's banner)",
         model([](double cx, double cy, double d, double) { return cx * cx * cy / (d * d); })},
        {"1/d", "divided by the distance, not its square: G = cos cos / |x - y|^2 (the slides' G(x,y))",
         model([](double cx, double cy, double d, double) { return cx * cy / d; })},
        {"no density", "not divided by the light point's density p_A = 1 / area (lp.pdfArea): next event is a Monte Carlo estimate "
                       "over the lamp's area (page 5)", model([](double cx, double cy, double d, double A) { return cx * cy / (d * d) / A; })},
        {"solid angle", "divided by the density in solid angle, p_A d^2 / cos_y, where the area density belongs: the estimate is over "
                        "points of the lamp (dA), not directions", model([](double cx, double cy, double d, double) { return cx * cy * cy / (d * d * d * d); })},
    };
    DirectSample d = directAt(s, kLampPoints, false, 20000);
    Fit f = fitModels(d.mean, d.se, models, "estimateDirect under a square lamp (4 points of the floor, 20000 samples each)", 0.01);
    return {f.pass, f.text, f.mistake};
}

Outcome directBehindPlate() {
    Scene s = parseScene(kLampScene, "lamp");
    DirectSample d = directAt(s, {Vec3(3, 0, 0), Vec3(0, 0, 0)}, false, 2000);
    if (d.mean[1] <= 0) return {false, "estimateDirect gives nothing even under the lamp: a point the plate hides cannot be told from one it does not"};
    bool pass = d.mean[0] == 0;
    return {pass, pass ? "" : "estimateDirect at a point the plate hides from the lamp: expected 0, measured " + num(d.mean[0]) +
                                  ": the shadow ray is missing (occluded(scene, shadowRay(sp, lp.sp)): V(x,y) of G; page 2)"};
}

Outcome directPointLight() {
    Scene s = parseScene(kPointScene, "point");
    const double rho = 0.5, I = 5;
    std::vector<double> right;
    for (Vec3 p : kLampPoints) {
        Vec3 w = Vec3(0, 2, 0) - p;
        double d2 = dot(w, w), cx = w.y / std::sqrt(d2);
        right.push_back(rho / kPi * I * cx / d2);
    }
    std::vector<Model> models = {{"right", "", right}};
    DirectSample plain = directAt(s, kLampPoints, false, 16), mis = directAt(s, kLampPoints, true, 16);
    Fit f = fitModels(plain.mean, plain.se, models, "estimateDirect under a point light (I = 5 at height 2)", 1e-3);
    if (!f.pass) {
        bool black = true;
        for (double m : plain.mean) black = black && m == 0;
        if (black) f.text += ": a point light has no surface and no area: its cosine is 1 and its density the chance of choosing it "
                             "(lp.deltaPosition, lp.pdfArea; page 5)";
        return {false, f.text, f.mistake};
    }
    Fit g = fitModels(mis.mean, mis.se, models, "estimateDirect with mis under a point light", 1e-3);
    if (!g.pass) g.text += ": no BSDF sample can hit a point light, so its light sample keeps the whole weight (weight 1)";
    return {g.pass, g.text, g.mistake};
}

Outcome directWithMis() {
    Scene s = parseScene(kLampScene, "lamp");
    const Shape& lamp = s.shapes[1];
    const double rho = 0.5, Le = 4;
    // The light sample's share of a point y under the power heuristic: its density in solid angle,
    // p_L = d^2 / (A cos_y), against the BSDF's, p_B = cos_x / pi (Lambert's cosine sampling).
    auto model = [&](auto weight) {
        std::vector<double> v;
        for (Vec3 p : kLampPoints)
            v.push_back(rho / kPi * Le * overLamp(lamp, p, Vec3(0, 1, 0), [&](double cx, double cy, double d, double A) {
                if (cy <= 0 || cx <= 0) return 0.0;
                double pL = d * d / (A * cy), pB = cx / kPi;
                return cx * cy / (d * d) * weight(pL, pB, 1 / A);
            }));
        return v;
    };
    std::vector<Model> models = {
        {"right", "", model([](double pL, double pB, double) { return pL * pL / (pL * pL + pB * pB); })},
        {"area density", "the power heuristic compares the light's area density (1/A) with the BSDF's solid-angle density: put the "
                         "light's in solid angle, p_A d^2 / |cos_y| (page 10: one measure for every strategy)",
         model([](double, double pB, double pA) { return pA * pA / (pA * pA + pB * pB); })},
        {"balance", "the balance heuristic where nee --mis uses the power heuristic (sampleNEE weights the BSDF's hits by "
                    "powerHeuristic): the two weights of a path no longer sum to 1", model([](double pL, double pB, double) { return pL / (pL + pB); })},
        {"no weight", "with mis the light sample is not weighted: the paths both techniques find are counted twice (\"make sure no path "
                      "is counted multiple times\")", model([](double, double, double) { return 1.0; })},
        {"the BSDF's weight", "the light sample weighted by the BSDF's share, p_B^2 / (p_L^2 + p_B^2), not its own",
         model([](double pL, double pB, double) { return pB * pB / (pL * pL + pB * pB); })},
    };
    DirectSample d = directAt(s, kLampPoints, true, 20000);
    Fit f = fitModels(d.mean, d.se, models, "estimateDirect with mis (the power heuristic) under a square lamp, 4 points", 0.01);
    return {f.pass, f.text, f.mistake};
}

// nee (sampleNEE with the student's estimateDirect), plain and with --mis, against the reference.
Outcome neeCornell() {
    Scene s = scene("scenes/cornell.scene", 32, 32);
    const std::vector<double> ref = regionMeans(dataImage("cornell-32"), 4);
    for (bool mis : {false, true}) {
        RenderOptions o = options(Method::NEE, 32, mis ? 14 : 13);
        o.mis = mis;
        Comparison c = compare(estimate(s, o, 4), ref, 4, 0.05);
        if (c.pass) continue;
        std::string text = std::string("nee") + (mis ? " --mis" : "") + " on cornell (32x32, 32 samples) against the reference: " + c.text;
        if (c.ratio > 1.3 && !mis) text += ": the lamp's light counted twice, by next event and by the BSDF sample that hits it (page 9: count every path once)";
        return {false, text};
    }
    return {true, ""};
}

std::vector<Check> checksH1() {
    return {{"pt in the furnace, depth by depth", 1, ptFurnaceDepths},
            {"nee and nee --mis on cornell against the reference", 1, neeCornell},
            {"pt in the furnace with Russian roulette", 1, ptFurnaceRoulette},
            {"pt on cornell against the reference", 1, ptCornell},
            {"next event under a square lamp", 2, directUnderLamp},
            {"next event behind a plate", 1, directBehindPlate},
            {"next event from a point light", 1, directPointLight},
            {"next event with the power heuristic", 2, directWithMis}};
}

}  // namespace grade

// ============================================================================================
// H2 light tracing: connectToCamera at points the camera sees and one it does not, against the
// pinhole's closed form (W_j cos / d^2 over the W H light paths of a pass = 1 / (A cos^3 d^2));
// lt's image on cornell and cornell-point against the references.
namespace grade {

struct SeenPoint {
    SurfacePoint sp;
    int pixel;
    Vec3 fromEye;  // unit, the camera ray's direction
    float dist;
};
// Points of cornell that the camera sees through film positions spread over the image, corners too.
std::vector<SeenPoint> seenPoints(const Scene& s) {
    std::vector<SeenPoint> points;
    const float W = float(s.camera.width), H = float(s.camera.height);
    for (float fy : {0.3f, 0.27f * H, 0.5f * H + 0.4f, 0.74f * H, H - 0.3f})
        for (float fx : {0.3f, 0.26f * W + 0.1f, 0.5f * W + 0.3f, 0.77f * W, W - 0.3f}) {
            Ray ray = cameraRay(s.camera, fx, fy);
            Hit hit = intersect(s, ray);
            if (!hit.found()) continue;
            points.push_back({surfaceAt(s, ray, hit), int(fy) * s.camera.width + int(fx), ray.d, hit.t});
        }
    return points;
}

Outcome cameraPixels() {
    Scene s = scene("scenes/cornell.scene", 32, 32);
    const int W = 32, H = 32;
    int right = 0, unseen = 0, flippedY = 0, flippedX = 0, swapped = 0, backwards = 0, n = 0;
    for (const SeenPoint& p : seenPoints(s)) {
        CameraConnection c = connectToCamera(s, p.sp);
        int x = p.pixel % W, y = p.pixel / W;
        ++n;
        right += c.pixel == p.pixel;
        unseen += c.pixel < 0;
        flippedY += c.pixel == (H - 1 - y) * W + x && y != H - 1 - y;
        flippedX += c.pixel == y * W + (W - 1 - x) && x != W - 1 - x;
        swapped += c.pixel == x * W + y && x != y;
        backwards += c.pixel == p.pixel && dot(c.toCamera, p.fromEye) > -0.999f;
    }
    if (right == n && backwards == 0) return {true, ""};
    std::string text = "connectToCamera at " + std::to_string(n) + " points the camera sees: " + std::to_string(right - backwards) + " right";
    if (unseen == n) text += "; every one reported unseen (pixel -1): pixelOf gives the pixel, and -1 only outside the image; the shadow ray's end at the eye is a SurfacePoint with only p set (no surface to push off)";
    else if (flippedY > n / 2) text += "; the image upside down: film rows grow downward (projectToFilm, pixelOf)";
    else if (flippedX > n / 2) text += "; the image mirrored left to right: the camera's right is forward x up (the Cornell box's convention)";
    else if (swapped > n / 2) text += "; x and y swapped: a pixel's index is y W + x";
    else if (backwards > 0) text += "; toCamera does not point from x to the eye (unit length)";
    return {false, text};
}

Outcome cameraHidden() {
    Scene s = scene("scenes/cornell.scene", 32, 32);
    SurfacePoint eye;
    eye.p = s.camera.eye;
    int hidden = 0, reported = 0;
    for (int i = 0; i < 40 && hidden < 8; ++i)
        for (int j = 0; j < 40 && hidden < 8; ++j) {  // floor points (shape 3 of cornell's file: y = 0) behind the blocks
            Ray down{Vec3(20 + 13 * i, 500, 20 + 13 * j), Vec3(0, -1, 0), kInf};
            Hit hit = intersect(s, down);
            if (!hit.found()) continue;
            SurfacePoint sp = surfaceAt(s, down, hit);
            if (sp.p.y > 1 || pixelOf(s.camera, sp.p) < 0 || !occluded(s, shadowRay(sp, eye))) continue;
            ++hidden;
            reported += connectToCamera(s, sp).pixel >= 0;
        }
    if (hidden == 0) return {false, "the grader found no hidden point of the floor (its scene changed?)"};
    int seen = 0;
    for (const SeenPoint& p : seenPoints(s)) seen += connectToCamera(s, p.sp).pixel >= 0;
    if (seen == 0) return {false, "connectToCamera gives no pixel even to points the camera sees: a hidden point cannot be told from a seen one"};
    if (reported == 0) return {true, ""};
    return {false, "connectToCamera at " + std::to_string(hidden) + " floor points the blocks hide from the eye: " + std::to_string(reported) +
                       " given a pixel: no visibility test toward the eye (a shadow ray from x to the pinhole): light tracing lights what the camera cannot see"};
}

Outcome cameraImportanceAt(int width, int height) {
    Scene s = scene("scenes/cornell.scene", width, height);
    const double A = s.camera.imageArea, N = double(width) * height;
    std::vector<double> measured, zero, cosines, right, noCos, extraCos, notPerPath, twice, overD, noD;
    for (const SeenPoint& p : seenPoints(s)) {
        CameraConnection c = connectToCamera(s, p.sp);
        double cosT = dot(p.fromEye, s.camera.forward), d = p.dist * length(p.fromEye), r = 1 / (A * cosT * cosT * cosT * d * d);
        measured.push_back(c.pixel >= 0 ? c.importance : 0);
        zero.push_back(0), cosines.push_back(cosT), right.push_back(r), noCos.push_back(r / cosT), extraCos.push_back(r * cosT);
        notPerPath.push_back(r * N), twice.push_back(r / N), overD.push_back(r * d), noD.push_back(r * d * d);
    }
    double corner = 1 / *std::min_element(cosines.begin(), cosines.end());
    std::vector<Model> models = {
        {"right", "", right},
        {"no cosine", "light tracing is " + num(corner, 3) + "x too bright at the image's corners and right at its centre: the camera's "
                      "importance lacks the cosine at the camera (W_j cos theta / d^2); page 5", noCos},
        {"extra cosine", "light tracing is " + num(corner, 3) + "x too dark at the image's corners and right at its centre: one cosine at "
                         "the camera too many (pixelImportance's W_j holds 1/cos^4, the connection one cos); page 5", extraCos},
        {"not per light path", "light tracing is " + num(N, 4) + "x too bright everywhere: a pass traces one light path per pixel, W H of "
                               "them, and each splat must be divided by their number (pbrt-v4 #347); page 5", notPerPath},
        {"per light path twice", "light tracing is " + num(N, 4) + "x too dark: divided by the number of light paths twice", twice},
        {"1/d", "divided by the distance to the eye, not its square (G's 1/d^2)", overD},
        {"no 1/d^2", "the 1/d^2 of G between x and the eye is missing", noD},
    };
    Fit f = fitModels(measured, zero, models, "connectToCamera's importance at " + std::to_string(measured.size()) + " points of a " + std::to_string(width) +
                                                  "x" + std::to_string(height) + " image, against 1 / (A cos^3 d^2)", 2e-3);
    bool none = !f.pass;
    for (double m : measured) none = none && m <= 0;
    if (none) f.text += ": no point of the image gets a positive importance: the direction whose W_j and cosine the camera gives is the one leaving "
                        "the pinhole toward x (-toCamera), cos theta = forward . (x - eye) / d";
    return {f.pass, f.text, f.mistake};
}

// The pixels where the camera sees a lamp's front side, with the radiance it sees there (32 x 32
// rays a pixel: the lamp's edge rows are a few percent of a pixel): what lt's light vertices y_0
// alone put in the image.
Image lampSeen(const Scene& s) {
    constexpr int n = 32;
    Image img(s.camera.width, s.camera.height);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int k = 0; k < n * n; ++k) {
                Ray ray = cameraRay(s.camera, x + (k % n + 0.5f) / n, y + (k / n + 0.5f) / n);
                Hit hit = intersect(s, ray);
                if (hit.found()) img.at(x, y) += emittedRadiance(s, surfaceAt(s, ray, hit), -ray.d) / float(n * n);
            }
    return img;
}

Outcome ltCornell() {
    Scene s = scene("scenes/cornell.scene", 32, 32);
    Estimate e = estimate(s, options(Method::LT, 128, 9), 4);
    Image ref = dataImage("cornell-32");
    Comparison c = compare(e, regionMeans(ref, 4), 4, 0.03);
    if (c.pass) return {true, ""};
    Image lamp = lampSeen(s);
    std::string text = "lt on cornell (32x32, 128 light paths a pixel) against the reference: " + c.text;
    // y_0 left out: the reference less the lamp as the camera sees it
    std::vector<double> noLamp = regionMeans(ref, 4), lampRegions = regionMeans(lamp, 4);
    bool fits = true;
    for (size_t r = 0; r < noLamp.size(); ++r) fits = fits && std::fabs(e.mean[r] - (noLamp[r] - lampRegions[r])) <= 5 * e.se[r] + 0.03 * noLamp[r];
    if (fits) text += ": the lamp itself is black: its own vertex y_0 must be joined to the camera too (s = 1, t = 1: light tracing sees the lamp)";
    else if (c.ratio > 0 && std::fabs(c.ratio - kPi) < 0.05 * kPi) text += ": pi times too bright: the splat's factor at the vertex is f |cos| (evalVertex toward the camera), not its BSDF sample's weight";
    return {false, text};
}

Outcome ltCornellPoint() {
    Scene s = scene("scenes/cornell-point.scene", 32, 32);
    const int lightPixel = pixelOf(s.camera, s.lights[0].position);
    auto masked = [&](const Image& img) {  // the point light's own pixel is lt's alone: left out of both
        Image m = img;
        if (lightPixel >= 0) m.pixels[size_t(lightPixel)] = Vec3(0);
        return m;
    };
    Estimate e = estimate(s, options(Method::LT, 128, 11), 4, [&](const Rendering& r, int i) { return i == lightPixel ? 0.0 : double(average(r.pass[size_t(i)])); });
    Comparison c = compare(e, regionMeans(masked(dataImage("cornell-point-32")), 4), 4, 0.03);
    return {c.pass, "lt on cornell-point (a point light) against the reference: " + c.text};
}

std::vector<Check> checksH2() {
    return {{"connectToCamera: the pixel that sees a point", 2, cameraPixels},
            {"connectToCamera: a point hidden from the eye", 1, cameraHidden},
            {"connectToCamera: the importance", 3, [] { return cameraImportanceAt(32, 32); }},
            {"lt on cornell against the reference", 3, ltCornell},
            {"lt on cornell-point against the reference", 1, ltCornellPoint}};
}

}  // namespace grade

// ============================================================================================
// H3 non-symmetric scattering: a glass interface's refraction weights by transport mode against
// (eta_o/eta_i)^2 and 1 (power is conserved, radiance is not); the adjoint BSDF with shading
// normals against Veach's ratio; and the energy generator, where light paths must see the extra
// light that eye paths see.
namespace grade {

// A glass quad at y = 0, its front side (up) outside, ior 1.5 inside; a diffuse quad with bumped
// shading normals. Each has a light only because a scene needs one.
const char* kGlassScene = "camera 0 1 -4  0 0 0  0 1 0  40  8 8\nmaterial glass glass 1.5\n"
                          "quad -1 0 -1  0 0 2  2 0 0  glass\npointlight 0 3 0  1 1 1\n";
const char* kBumpScene = "camera 0 1 -4  0 0 0  0 1 0  40  8 8\nmaterial white diffuse 0.8 0.8 0.8\n"
                         "quad -1 0 -1  0 0 2  2 0 0  white bump 0.7 5\npointlight 0 3 0  1 1 1\n";

Outcome refractionWeightsAt(float ior) {
    std::string text = kGlassScene;
    text.replace(text.find("glass 1.5"), 9, "glass " + num(ior, 6));
    Scene s = parseScene(text, "glass");
    SurfacePoint sp = makeSurfacePoint(s.shapes[0], 0, Vec3(0.1f, 0, 0.2f), false);
    std::vector<double> measured, zero, right, swapped, none, notSquared, inverted, both;
    std::vector<std::string> where;
    struct Case { float degrees; bool fromOutside; };
    for (Case c : {Case{0, true}, Case{30, true}, Case{60, true}, Case{10, false}, Case{25, false}, Case{35, false}}) {
        float a = c.degrees * kPi / 180;
        Vec3 wo = normalize(Vec3(std::sin(a), c.fromOutside ? std::cos(a) : -std::cos(a), 0.1f * std::sin(a)));
        const double etaO = c.fromOutside ? 1 : ior, etaI = c.fromOutside ? ior : 1, r = sqr(float(etaO / etaI));
        for (Transport mode : {Transport::Radiance, Transport::Importance}) {
            BsdfSample bs;
            bool ok = specularScatter(s, sp, wo, mode, true, bs);
            const bool rad = mode == Transport::Radiance;
            measured.push_back(ok ? double(bs.weight.x) : 0), zero.push_back(0);
            right.push_back(rad ? r : 1), swapped.push_back(rad ? 1 : 1 / r), none.push_back(1);
            notSquared.push_back(rad ? etaO / etaI : 1), inverted.push_back(rad ? 1 / r : 1), both.push_back(r);
        }
    }
    std::vector<Model> models = {
        {"right", "", right},
        {"swapped", "glass is too bright seen through from the light's side (importance scaled by eta^2) and right from the eye's in "
                    "one case, wrong in the other: the two rules swapped, --symmetric-refraction's mistake; eta^2 belongs to radiance, power "
                    "carries none; page 14", swapped},
        {"none", "no eta^2 for radiance: radiance crossing into glass is compressed into a smaller solid angle, L_t = (eta_t/eta_i)^2 "
                 "L_i (the slides' \"Power versus Radiance\"); smallpt's rule; page 14", none},
        {"not squared", "eta where the rule has eta^2: L_t = (eta_t/eta_i)^2 L_i; page 14", notSquared},
        {"inverted", "the ratio upside down: radiance flows from wi to wo, L(wo) = (eta_o/eta_i)^2 L(wi), eta_o on wo's side; page 14", inverted},
        {"both", "eta^2 for importance too: power does not change when a photon is refracted (the slides' \"Power versus Radiance\"); "
                 "page 14", both},
    };
    Fit f = fitModels(measured, zero, models,
                      "refraction's weight through glass of index " + num(ior) + " (radiance, then importance, at 0, 30, 60 degrees from outside and 10, 25, 35 from inside)", 1e-4);
    return {f.pass, f.text, f.mistake};
}

Outcome adjointRatio() {
    Scene s = parseScene(kBumpScene, "bump");
    Rng rng = checkRng(23, 0, 0);
    std::vector<double> measured, radiance, zero, right, none, inverted, woOnly, wiOnly, radianceRight;
    for (int i = 0; measured.size() < 60 && i < 20000; ++i) {
        SurfacePoint sp = makeSurfacePoint(s.shapes[0], 0, Vec3(2 * rng.uniform() - 1, 0, 2 * rng.uniform() - 1), false);
        Vec3 wo = sampleUniformSphere(rng.uniform(), rng.uniform()), wi = sampleUniformSphere(rng.uniform(), rng.uniform());
        wo.y = std::fabs(wo.y), wi.y = std::fabs(wi.y);
        if (dot(wo, sp.ns) < 0.05f || dot(wi, sp.ns) < 0.05f || wo.y < 0.05f || wi.y < 0.05f) continue;
        float pdf, pdfReverse;
        double fr = average(evalBsdf(s, sp, wo, wi, Transport::Radiance, pdf, pdfReverse));
        double fi = average(evalBsdf(s, sp, wo, wi, Transport::Importance, pdf, pdfReverse));
        double plain = 0.8 / kPi * dot(wi, sp.ns);  // Lambert's f |wi.ns|
        double ratio = absDot(wo, sp.ns) * absDot(wi, sp.ng) / (absDot(wo, sp.ng) * absDot(wi, sp.ns));
        measured.push_back(fi), radiance.push_back(fr), zero.push_back(0), radianceRight.push_back(plain);
        right.push_back(plain * ratio), none.push_back(plain), inverted.push_back(plain / ratio);
        woOnly.push_back(plain * absDot(wo, sp.ns) / absDot(wo, sp.ng)), wiOnly.push_back(plain * absDot(wi, sp.ng) / absDot(wi, sp.ns));
    }
    Fit r = fitModels(radiance, zero, {{"right", "", radianceRight}}, "the BSDF for radiance with shading normals", 1e-4);
    if (!r.pass) return {false, r.text + ": radiance needs no correction (the adjoint is the light paths' alone; Transport::Radiance: 1)"};
    std::vector<Model> models = {
        {"right", "", right},
        {"none", "light paths use the shading-normal BSDF unchanged: the adjoint factor |wo.ns| |wi.ng| / (|wo.ng| |wi.ns|) is missing, "
                 "--no-adjoint-correction's mistake; light tracing then disagrees with eye tracing wherever shading normals tilt (page 13)", none},
        {"inverted", "the adjoint factor upside down: |wo.ns| |wi.ng| / (|wo.ng| |wi.ns|), wo toward the light on a light path (page 13)", inverted},
        {"half", "half of the adjoint factor: |wo.ns| / |wo.ng| alone; the other half, |wi.ng| / |wi.ns|, belongs too (page 13)", woOnly},
        {"other half", "half of the adjoint factor: |wi.ng| / |wi.ns| alone; the other half, |wo.ns| / |wo.ng|, belongs too (page 13)", wiOnly},
    };
    Fit f = fitModels(measured, zero, models, "the BSDF for importance (light paths) with shading normals, at 60 pairs of directions", 1e-4);
    return {f.pass, f.text, f.mistake};
}

double dataNumber(const std::string& name) {
    std::ifstream in(dataDir + "/numbers.txt");
    for (std::string key; in >> key;) {
        double v;
        in >> v;
        if (key == name) return v;
    }
    throw std::runtime_error("the grader's data " + dataDir + "/numbers.txt has no " + name);
}

Outcome energyGenerator() {
    Scene s = scene("scenes/energy-generator.scene", 48, 36);
    PowerRatio measured = floorPowerRatio(s, 40, 2500, 12 + 1000 * gSeed);  // physics.h
    double expected = dataNumber("energy-generator-power-ratio");
    if (std::isfinite(measured.mean) && std::fabs(measured.mean - expected) <= std::max(4 * measured.se, 0.01 * expected)) return {true, ""};
    std::string text = "the energy generator's floor (a shading normal tilted 60 degrees, albedo 0.8) as light paths see it: power out / power in "
                       "expected " + num(expected, 3) + " (the renderer's, with the adjoint), measured " + num(measured.mean, 3) + " +- " + num(measured.se, 2);
    if (measured.mean <= 0.81) text += ": at most the albedo (0.8): light paths see no energy generator, where eye paths see the tilted floor 7 times brighter; the adjoint factor is missing (page 13)";
    return {false, text};
}

std::vector<Check> checksH3() {
    return {{"refraction by transport mode", 4, [] { return refractionWeightsAt(1.5f); }},
            {"the adjoint BSDF", 4, adjointRatio},
            {"the energy generator seen from the light", 2, energyGenerator}};
}

}  // namespace grade

// ============================================================================================
// H4 instant radiosity: gatherVpls with VPLs placed by hand, against the closed form of each
// connection (Lambert's f = rho/pi at both ends, G = cos cos / d^2); with the clamp and its
// report; ir's image on cornell, all lengths and direct light alone, against the references.
namespace grade {

// A floor, a wall at x = -2, a lamp under the ceiling and a plate at x = 0 that stands between
// the camera vertex x = (1, 0, 2) and the wall's low part.
const char* kRoomScene = "camera 0 1.5 -5  0 1 0  0 1 0  40  16 16\n"
                         "material white diffuse 0.5 0.5 0.5\nmaterial black diffuse 0 0 0\n"
                         "quad -3 0 3  6 0 0  0 0 -6  white\n"
                         "quad -2 0 -3  0 3 0  0 0 6  white\n"
                         "quad -0.5 2.9 -0.5  1 0 0  0 0 1  black emit 5 5 5\n"
                         "quad 0 0 1.5  0 0.8 0  0 0 1  white\n";
constexpr double kRoomAlbedo = 0.5;

PathVertex vertexAt(const Scene& s, int shape, Vec3 p, Vec3 wo, double beta, PathVertex::Type type = PathVertex::Surface) {
    PathVertex v;
    v.type = type;
    v.sp = makeSurfacePoint(s.shapes[size_t(shape)], shape, p, false);
    v.wo = normalize(wo);
    v.beta = Vec3(float(beta));
    if (type == PathVertex::Light) v.light = s.shapes[size_t(shape)].light;
    return v;
}
// The connection y -> x by its closed form: beta_y f_y |cos_y| f_x |cos_x| beta_x / d^2, with
// Lambert's f = rho / pi at a surface and the emitter's cosine alone at a light's vertex; and G.
double closedConnection(const PathVertex& y, const PathVertex& x, double* G = nullptr) {
    Vec3 d = x.sp.p - y.sp.p;
    double d2 = dot(d, d);
    Vec3 w = d / float(std::sqrt(d2));
    double cy = absDot(y.sp.ng, w), cx = absDot(x.sp.ng, w);
    double fy = y.type == PathVertex::Light ? cy : kRoomAlbedo / kPi * cy, fx = kRoomAlbedo / kPi * cx;
    if (G) *G = cx * cy / d2;
    return average(y.beta) * fy * fx * average(x.beta) / d2;
}

struct Room {
    Scene s = parseScene(kRoomScene, "room");
    PathVertex x = vertexAt(s, 0, Vec3(1, 0, 2), Vec3(-1, 1.5f, -7), 1);           // the camera vertex on the floor
    PathVertex wall = vertexAt(s, 1, Vec3(-2, 1, 0), Vec3(0.6f, 0.8f, 0), 0.3);       // seen from x
    PathVertex lamp = vertexAt(s, 2, Vec3(0, 2.9f, 0.2f), Vec3(0, -1, 0), 4, PathVertex::Light);
    PathVertex hidden = vertexAt(s, 1, Vec3(-2, 0.3f, 2), Vec3(0.6f, 0.8f, 0), 0.3);  // behind the plate
    PathVertex near = vertexAt(s, 3, Vec3(0, 0.3f, 2.2f), Vec3(0.7f, 0.7f, 0), 0.2);  // on the plate, close to x
};
double gather(const Room& r, const std::vector<Vpl>& vpls, int maxDepth, int cameraBounces, float clamp, RowOutput* report = nullptr) {
    RenderOptions o = options(Method::IR, 1);
    o.maxDepth = maxDepth;
    o.ir.clamp = clamp;
    RowOutput out;
    double v = average(gatherVpls(r.s, o, vpls, r.x, cameraBounces, out));
    if (report) *report = out;
    return v;
}

Outcome gatherVisible() {
    Room r;
    double wall = closedConnection(r.wall, r.x), lamp = closedConnection(r.lamp, r.x);
    double measured = gather(r, {{r.wall, 1}, {r.lamp, 0}}, 32, 0, 0);
    std::vector<Model> models = {
        {"right", "", {wall + lamp}},
        {"twice", "every VPL gathered twice", {2 * (wall + lamp)}},
        {"last only", "only the last VPL's light kept: add each VPL's connection to the sum", {lamp}},
    };
    Fit f = fitModels({measured}, {0}, models, "gatherVpls from a VPL on a wall and one on the lamp, at a floor point that sees both", 1e-4);
    return {f.pass, f.text, f.mistake};
}

Outcome gatherHidden() {
    Room r;
    double measured = gather(r, {{r.hidden, 1}}, 32, 0, 0), open = closedConnection(r.hidden, r.x);
    if (gather(r, {{r.wall, 1}}, 32, 0, 0) <= 0) return {false, "gatherVpls gives nothing even from a VPL x sees: a hidden one cannot be told from it"};
    if (measured == 0) return {true, ""};
    return {false, "gatherVpls from a VPL a plate hides from x: expected 0, measured " + num(measured) +
                       (std::fabs(measured / open - 1) < 1e-3 ? ": no visibility test between the VPL and x (mutuallyVisible: G's V(x,y))" : "")};
}

Outcome gatherLength() {
    Room r;
    // --maxdepth 3, x one bounce from the camera: a VPL after b bounces makes a path of b + 1 + 1
    // bounces; b = 1 is at the limit, b = 2 past it.
    double atLimit = closedConnection(r.wall, r.x), measured = gather(r, {{r.wall, 2}, {r.wall, 1}}, 3, 1, 0);
    std::vector<Model> models = {
        {"right", "", {atLimit}},
        {"no limit", "VPLs gathered whatever the path's length: a VPL after b bounces and x after c make a path of b + c + 1 bounces, "
                     "at most --maxdepth (ir --maxdepth 1 must give direct light only)", {2 * atLimit}},
        {"one short", "the length limit off by one: a path of exactly --maxdepth bounces is kept (b + c + 1 <= maxDepth)", {0}},
    };
    Fit f = fitModels({measured}, {0}, models, "gatherVpls at --maxdepth 3 from x one bounce from the camera, VPLs after 2 and 1 bounces", 1e-4);
    return {f.pass, f.text, f.mistake};
}

Outcome gatherClampAt(float C) {
    Room r;
    double Gwall = 0, Gnear = 0, wall = closedConnection(r.wall, r.x, &Gwall), near = closedConnection(r.near, r.x, &Gnear);
    RowOutput report;
    double measured = gather(r, {{r.wall, 1}, {r.near, 1}}, 32, 0, C, &report);
    auto distance2 = [&](const PathVertex& y) { Vec3 d = r.x.sp.p - y.sp.p; return double(dot(d, d)); };
    auto clampedBy = [&](double c, double G) { return G > C ? c * C / G : c; };
    std::vector<Model> models = {
        {"right", "", {wall + near * C / Gnear}},
        {"G without 1/d^2", "the clamp compares cos cos alone with C: the geometry term G(x,y) = |cos_x| |cos_y| / d^2 keeps its 1/d^2 "
                            "(page 4; panel (e))", {clampedBy(wall, Gwall * distance2(r.wall)) + clampedBy(near, Gnear * distance2(r.near))}},
        {"no clamp", "--clamp changes nothing: replace G by min(G, C), i.e. scale a connection whose G exceeds C by C / G (panel (e))", {wall + near}},
        {"clamped always", "every connection scaled by C / G, also those whose G is below C: min(G, C) leaves them alone", {wall * C / Gwall + near * C / Gnear}},
        {"contribution clamped", "the contribution bounded by C instead of G: min(G, C) bounds the geometry term", {std::min(wall, double(C)) + std::min(near, double(C))}},
    };
    Fit f = fitModels({measured}, {0}, models, "gatherVpls with --clamp " + num(C) + " from a far VPL (G " + num(Gwall, 3) + ") and a near one (G " + num(Gnear, 3) + ")", 1e-4);
    return {f.pass, f.text, f.mistake};
}

Outcome clampReport() {
    Room r;
    const float C = 0.1f;
    double Gnear = 0, wall = closedConnection(r.wall, r.x), near = closedConnection(r.near, r.x, &Gnear);
    RowOutput report;
    gather(r, {{r.wall, 1}, {r.near, 1}}, 32, 0, C, &report);
    const double before = wall + near, after = wall + near * C / Gnear;
    bool pass = std::fabs(report.energyUnclamped - before) <= 1e-4 * before && std::fabs(report.energyClamped - after) <= 1e-4 * after;
    if (pass) return {true, ""};
    std::string text = "the clamp's report (out.energyUnclamped, out.energyClamped): expected " + num(before) + " and " + num(after) + ", measured " +
                       num(report.energyUnclamped) + " and " + num(report.energyClamped);
    if (report.energyUnclamped == 0 && report.energyClamped == 0) text += ": nothing reported (ir --clamp prints the share of the energy its clamp removed: panel (e)'s bias)";
    else if (std::fabs(report.energyUnclamped - after) <= 1e-4 * after && std::fabs(report.energyClamped - before) <= 1e-4 * before) text += ": the two swapped";
    return {false, text};
}

Outcome irCornell() {
    Scene s = scene("scenes/cornell.scene", 32, 32);
    Estimate e = estimate(s, options(Method::IR, 48, 13), 4);
    Comparison c = compare(e, regionMeans(dataImage("cornell-32"), 4), 4, 0.03);
    return {c.pass, "ir on cornell (32x32, 48 passes) against the reference: " + c.text};
}

Outcome irDirect() {
    Scene s = scene("scenes/cornell.scene", 24, 24);
    RenderOptions o = options(Method::IR, 32, 15);
    o.maxDepth = 1;
    Estimate e = estimate(s, o, 4);
    Comparison c = compare(e, regionMeans(dataImage("cornell-direct-24"), 4), 4, 0.03);
    return {c.pass, "ir --maxdepth 1 on cornell against the reference of direct light alone: " + c.text +
                        (!c.pass && c.ratio > 1.05 ? ": too bright: paths longer than --maxdepth gathered" : "")};
}

std::vector<Check> checksH4() {
    return {{"gathering visible VPLs", 2, gatherVisible},
            {"a VPL hidden from x", 1, gatherHidden},
            {"the path-length limit", 1, gatherLength},
            {"the clamp", 2, [] { return gatherClampAt(0.1f); }},
            {"the clamp's energy report", 1, clampReport},
            {"ir on cornell against the reference", 2, irCornell},
            {"ir --maxdepth 1 against direct light", 1, irDirect}};
}

}  // namespace grade

// ============================================================================================
// H5 bidirectional path tracing: misWeight on paths of real subpaths, split again at every s and
// rebuilt, against the heuristics' definitions from densities computed from scratch (the weights
// of every strategy able to make a path sum to 1); connectStrategy by the agreement of the
// strategies (t >= 2: t = 1 is H2's), alone and weighted, against the complete renderer's.
namespace grade {

// The path kit (joinPath, able, rebuild, pathDensity) is physics.h's.

// The paths light[0..s-1] + camera[t-1..0] of samples' subpaths that carry light, found without
// connectStrategy: s = 0 ends on an emitter's front; otherwise two connectable vertices whose
// connection carries something and sees through.
template <class Fn>
void forEachLitPath(const Scene& sc, int samples, uint64_t seed, Fn fn) {
    RenderOptions opt = options(Method::BDPT, 1, seed);
    opt.maxDepth = 5;
    std::vector<PathVertex> camera, light;
    for (int i = 0; i < samples; ++i) {
        Rng rng = checkRng(seed, uint64_t(i), 7);
        cameraSubpath(sc, opt, rng.uniform() * sc.camera.width, rng.uniform() * sc.camera.height, rng, camera);
        lightSubpath(sc, opt, rng, light);
        for (int t = 1; t <= int(camera.size()); ++t)
            for (int s = 0; s <= int(light.size()); ++s) {
                if (s + t < 3 || s + t - 2 > opt.maxDepth) continue;
                const PathVertex& pt = camera[size_t(t - 1)];
                if (s == 0) {
                    if (t > 1 && pt.type == PathVertex::Surface && !isBlack(emittedRadiance(sc, pt.sp, pt.wo))) fn(light, s, camera, t);
                    continue;
                }
                const PathVertex& qs = light[size_t(s - 1)];
                if (!connectable(sc, qs) || !connectable(sc, pt)) continue;
                Connection c;
                evalConnection(sc, qs, pt, c);
                if (isBlack(c.fy) || isBlack(c.fx) || (t > 1 && !mutuallyVisible(sc, qs, pt))) continue;
                fn(light, s, camera, t);
            }
    }
}

struct WeightCheck {
    int paths = 0;
    bool anyWeight = false;  // a weight other than 0 seen
    double worstSum = 0, sumOfWorst = 0, worstDefinition = 0;
    std::map<int, double> worstAsHeuristic;  // the weights against each heuristic's definition
    // the weights against two mistakes' (balance, power, uniform): (s,t) left out of its own sum,
    // and every ratio upside down (p_{s,t} / p_i for p_i / p_{s,t})
    double worstWithoutSelf = 0, worstInverted = 0;
};
// A heuristic's weight of strategy s from the densities, with the ratios r_i given by `ratio`
// (p_i / p_s by the definition) and (s,t) itself counted or not: two mistakes' fingerprints.
double weightFrom(Heuristic h, const std::map<int, double>& p, int s, bool self, bool inverted) {
    double sum = 0;
    for (auto [i, pi] : p)
        if (i != s || self) sum += misPower(h, inverted ? p.at(s) / pi : pi / p.at(s));
    return sum > 0 ? 1 / sum : 0;
}
WeightCheck checkWeights(const Scene& sc, Heuristic h, int samples) {
    WeightCheck wc;
    forEachLitPath(sc, samples, 77, [&](const std::vector<PathVertex>& light, int s, const std::vector<PathVertex>& camera, int t) {
        std::vector<PathVertex> x = joinPath(light, s, camera, t);
        double sum = 0;
        std::map<int, double> density, weight;
        for (int s2 = 0; s2 < int(x.size()); ++s2) {
            if (!able(sc, x, s2)) continue;
            double w = rebuiltWeight(sc, x, s2, h);
            if (!std::isfinite(w)) w = 1e9;
            density[s2] = pathDensity(sc, x, s2, RenderOptions().roulette);
            weight[s2] = w;
            sum += w;
            wc.anyWeight = wc.anyWeight || w != 0;
        }
        if (std::fabs(sum - 1) > wc.worstSum) wc.worstSum = std::fabs(sum - 1), wc.sumOfWorst = sum;
        for (auto [s2, w] : weight) {
            wc.worstDefinition = std::max(wc.worstDefinition, std::fabs(w - definitionWeight(h, density, s2)));
            for (Heuristic other : {Heuristic::Balance, Heuristic::Power, Heuristic::Max, Heuristic::Uniform})
                wc.worstAsHeuristic[int(other)] = std::max(wc.worstAsHeuristic[int(other)], std::fabs(w - definitionWeight(other, density, s2)));
            if (h == Heuristic::Max) continue;
            const double without = weightFrom(h, density, s2, false, false), upsideDown = weightFrom(h, density, s2, true, true);
            wc.worstWithoutSelf = std::max(wc.worstWithoutSelf, std::fabs(w - without) / std::max(1.0, without));
            wc.worstInverted = std::max(wc.worstInverted, std::fabs(w - upsideDown) / std::max(1.0, upsideDown));
        }
        ++wc.paths;
    });
    return wc;
}

const char* heuristicName(Heuristic h) {
    return h == Heuristic::Balance ? "balance" : h == Heuristic::Power ? "power" : h == Heuristic::Max ? "max" : "uniform";
}
struct MisScene {
    std::string name;
    Scene scene;
};
std::vector<MisScene> misScenes() {
    return {{"cornell", scene("scenes/cornell.scene", 16, 16)},
            {"cornell-point (a point light)", scene("scenes/cornell-point.scene", 16, 16)},
            {"glass-box (a mirror and a glass ball)", scene("scenes/glass-box.scene", 16, 16)}};
}

Outcome weightsSum() {
    std::string text;
    bool allZero = true, withoutSelf = true;
    std::vector<std::string> failing;
    for (const MisScene& m : misScenes())
        for (Heuristic h : {Heuristic::Balance, Heuristic::Power, Heuristic::Max, Heuristic::Uniform}) {
            WeightCheck wc = checkWeights(m.scene, h, 150);
            allZero = allZero && std::fabs(wc.sumOfWorst) < 1e-9 && wc.worstSum > 0.99;
            if (h != Heuristic::Max) withoutSelf = withoutSelf && wc.worstWithoutSelf <= 1e-3;
            if (wc.paths < 50) return {false, "the grader found only " + std::to_string(wc.paths) + " paths on " + m.name};
            if (wc.worstSum > 1e-3) failing.push_back(m.name + " (" + heuristicName(h) + "): a path whose weights sum to " + num(wc.sumOfWorst, 4));
        }
    if (failing.empty()) return {true, ""};
    text = "the MIS weights of all strategies able to make a path must sum to 1 (page 10); ";
    for (size_t i = 0; i < failing.size() && i < 3; ++i) text += (i ? "; " : "") + failing[i];
    if (failing.size() > 3) text += " (and " + std::to_string(failing.size() - 3) + " more)";
    if (allZero) text += ": every weight is 0 (misWeight returns 0?)";
    else {
        bool onlySpecular = true, onlyPoint = true;
        for (const std::string& f : failing) onlySpecular = onlySpecular && f.find("glass-box") == 0, onlyPoint = onlyPoint && f.find("cornell-point") == 0;
        if (onlySpecular) text += ": only where mirrors and glass are: a strategy that would connect at a mirror or glass vertex is counted; it "
                                  "cannot make the path (no connection passes a delta BSDF; page 10M)";
        else if (onlyPoint) text += ": only with the point light: a strategy that would hit a point light (s = 0) cannot make the path (deltaPosition)";
        else if (withoutSelf) return {false, text + ": (s,t) itself is left out of its own sum: every weight is 1 / sum over the others; (s,t) counts with "
                                                    "r = 1 (page 10)", "(s,t) itself is left out of its own sum"};

        else text += ": a strategy counted twice, or one missing (the walk adds each other strategy once, r_i relative to (s,t))";
    }
    return {false, text};
}

Outcome weightsDefinition() {
    std::vector<std::string> failing;
    std::string likeOther;
    bool anyWeight = false, withoutSelf = true, inverted = true;
    for (const MisScene& m : misScenes())
        for (Heuristic h : {Heuristic::Balance, Heuristic::Power, Heuristic::Max, Heuristic::Uniform}) {
            WeightCheck wc = checkWeights(m.scene, h, 150);
            anyWeight = anyWeight || wc.anyWeight;
            if (h != Heuristic::Max) withoutSelf = withoutSelf && wc.worstWithoutSelf <= 1e-3, inverted = inverted && wc.worstInverted <= 1e-3;
            if (wc.worstDefinition <= 1e-3) continue;
            failing.push_back(m.name + " (" + heuristicName(h) + "): a weight " + num(wc.worstDefinition, 3) + " from the definition");
            for (Heuristic other : {Heuristic::Balance, Heuristic::Power, Heuristic::Max, Heuristic::Uniform})
                if (other != h && wc.worstAsHeuristic[int(other)] <= 1e-3 && likeOther.empty())
                    likeOther = std::string(": --heuristic ") + heuristicName(h) + " gives the " + heuristicName(other) + " heuristic's weights";
        }
    if (failing.empty()) return {true, ""};
    std::string text = "each weight must be its heuristic's, from the densities of the strategies able to make the path (p_s^2 / sum p_i^2 for "
                       "power; page 10): " + failing[0] + (failing.size() > 1 ? " (and " + std::to_string(failing.size() - 1) + " more)" : "");
    if (!anyWeight) return {false, text + ": every weight is 0 (misWeight returns 0?)"};
    if (likeOther.empty() && withoutSelf)
        return {false, text + ": (s,t) itself is left out of its own sum: every weight is 1 / sum over the others; (s,t) counts with r = 1 (page 10)",
                "(s,t) itself is left out of its own sum"};
    if (likeOther.empty() && inverted)
        return {false, text + ": each ratio upside down: the walk multiplies by pdfRev(x) / pdfFwd(x) of the vertex changing sides, r_i = p_i / p_{s,t} "
                              "(page 7)", "each ratio upside down"};
    text += likeOther.empty() ? ": the ratios walked from (s,t) are wrong: pdfRev(x)/pdfFwd(x) of the vertex changing sides, the junction's four "
                                "reverse densities (connectionJunction), not the stored ones (page 7)"
                              : likeOther + " (MisSum{heuristic})";
    return {false, text};
}

// The strategies' images of lengths k = 1..3 that have a camera subpath of at least two vertices
// (t >= 2: light tracing's t = 1 is H2's), region by region over passes.
struct StrategyEstimates {
    std::map<std::pair<int, int>, Estimate> unweighted;  // (s, t)
    std::map<int, Estimate> weightedByLength;             // k: the sum over s of the weighted images, t >= 2
};
StrategyEstimates strategyEstimates(int spp) {
    // bdpt's samples as the renderer draws them (its camera and light streams), every connection
    // with t >= 2 made by connectStrategy and weighted by misWeight; t = 1 (connectToCamera, H2's)
    // is left out, so that this task's grade does not depend on that one.
    Scene sc = scene("scenes/cornell.scene", 32, 32);
    RenderOptions o = options(Method::BDPT, spp, 19);
    const int W = 32, H = 32, grid = 4;
    std::map<std::pair<int, int>, std::vector<std::vector<double>>> perPass;
    std::map<int, std::vector<std::vector<double>>> weightedPass;
    std::vector<PathVertex> camera, light;
    for (int pass = 0; pass < spp; ++pass) {
        std::map<std::pair<int, int>, std::vector<double>> sums;
        std::map<int, std::vector<double>> weighted;
        for (int k = 1; k <= 3; ++k) {
            weighted[k].assign(size_t(grid * grid + 1), 0.0);
            for (int s = 0; s + 2 <= k + 1; ++s) sums[{s, k + 1 - s}].assign(size_t(grid * grid + 1), 0.0);
        }
        for (int pixel = 0; pixel < W * H; ++pixel) {
            Rng rng = sampleRng(o, kCameraStream, uint64_t(pixel), uint64_t(pass)), lightRng = lightPathRng(o, pixel, pass);
            FilmPoint f = jitteredFilmPoint(pixel % W, pixel / W, rng);
            cameraSubpath(sc, o, f.x, f.y, rng, camera);
            lightSubpath(sc, o, lightRng, light);
            const int region = (pixel / W * grid / H) * grid + (pixel % W) * grid / W;
            for (int t = 2; t <= int(camera.size()); ++t)
                for (int s = 0; s <= int(light.size()) && s + t - 1 <= 3; ++s) {
                    int at = pixel;
                    Connection c;
                    Vec3 value = connectStrategy(sc, light, s, camera, t, c, at);
                    if (isBlack(value)) continue;
                    float w = misWeight(sc, light, s, camera, t, o.heuristic, c, 0);
                    const int k = s + t - 1;
                    const double v = average(value) / (double(W) * H / (grid * grid)), all = average(value) / (double(W) * H);
                    if (!std::isfinite(v) || !std::isfinite(w)) throw std::runtime_error("a strategy's value or weight is NaN or infinite");
                    auto& u = sums[{s, t}];
                    u[size_t(region)] += v, u.back() += all;
                    weighted[k][size_t(region)] += v * w, weighted[k].back() += all * w;
                }
        }
        for (auto& [key, v] : sums) perPass[key].push_back(v);
        for (auto& [k, v] : weighted) weightedPass[k].push_back(v);
    }
    StrategyEstimates e;
    for (auto& [key, v] : perPass) e.unweighted[key] = summarize(v);
    for (auto& [k, v] : weightedPass) e.weightedByLength[k] = summarize(v);
    return e;
}

// Every strategy alone is an unbiased estimate of the paths it can make (page 11): each unweighted
// image with t >= 2 against the complete renderer's, region by region (s = 0 over the whole image:
// its rare hits of the lamp leave a region's error unknown).
Outcome strategiesAgainstRenderer() {
    StrategyEstimates e = strategyEstimates(256);
    for (int k = 1; k <= 3; ++k)
        for (int s = 0; s + 2 <= k + 1; ++s) {
            const int t = k + 1 - s;
            const std::string name = "C*_{" + std::to_string(s) + "," + std::to_string(t) + "}";
            const Estimate& mine = e.unweighted.at({s, t});
            std::vector<double> ref = regionMeans(dataImage("bdpt-s" + std::to_string(s) + "-t" + std::to_string(t)), 4);
            double refMean = 0;
            for (double r : ref) refMean += r / double(ref.size());
            if (s == 0) {
                double z = std::fabs(mine.imageMean - refMean) / std::max(mine.imageSe, 1e-12);
                if (z > 5 && std::fabs(mine.imageMean / refMean - 1) > 0.05)
                    return {false, name + " (s = 0: the camera subpath ends on the lamp) is " + num(mine.imageMean / refMean, 3) + "x the complete renderer's over the image" +
                                       (mine.imageMean == 0 ? ": black: its value is the camera subpath's throughput times the radiance the emitter sends toward the previous vertex"
                                                            : ": the camera subpath's throughput, times the radiance emitted toward the previous vertex (emittedRadiance, pt.wo)")};
                continue;
            }
            // Both ends away from the lamp and the camera (s, t >= 2): G = cos cos / d^2 unbounded near
            // corners, a heavy tail that passes' spread underestimates; such a strategy is held to 25%.
            Comparison c = compare(mine, ref, 4, s >= 2 ? 0.25 : 0.05);
            if (c.pass) continue;
            std::string text = name + ", the connection of " + std::to_string(s) + (s == 1 ? " light vertex and " : " light vertices and ") +
                               std::to_string(t) + " camera vertices, alone, against the complete renderer's (every strategy alone estimates the same image; page 11): " + c.text;
            if (mine.imageMean == 0) text += ": the connections give nothing (evalConnection, connectVertices, both ends connectable)";
            else if (c.worstRatio > 1.2) text += ": brighter where the blocks cast their shadows: a connection without V (mutuallyVisible) lights what the light cannot see";
            return {false, text};
        }
    return {true, ""};
}

Outcome weightedAgainstRenderer() {
    StrategyEstimates e = strategyEstimates(256);
    for (int k = 1; k <= 3; ++k) {
        Comparison c = compare(e.weightedByLength.at(k), regionMeans(dataImage("bdpt-t2-k" + std::to_string(k)), 4), 4, 0.04);
        if (!c.pass)
            return {false, "the MIS-weighted strategies of paths of " + std::to_string(k) + (k == 1 ? " segment" : " segments") + " (t >= 2) against the complete renderer's: " + c.text};
    }
    return {true, ""};
}

std::vector<Check> checksH5() {
    return {{"the MIS weights of a path sum to 1", 3, weightsSum},
            {"each weight follows its heuristic", 2, weightsDefinition},
            {"each strategy alone against the renderer's", 3, strategiesAgainstRenderer},
            {"the weighted strategies against the renderer's", 2, weightedAgainstRenderer}};
}

}  // namespace grade

// ============================================================================================
// H6 Metropolis: the acceptance at a few pairs of values, and a chain on a known target (every
// 10th state visited, and the expected-value splats) against its closed form by chi-square.
namespace grade {

// The chain on physics.h's known target, with the renderer's default steps and the student's acceptance.
TargetRun runOnTarget(uint64_t seed, const RenderOptions& steps = RenderOptions()) { return runOnKnownTarget(steps, checkRng(seed, 0, 0)); }

Outcome acceptance() {
    struct Pair { float current, proposal; };
    std::vector<double> measured, zero, right, inverted, unclamped;
    for (Pair p : {Pair{2, 1}, Pair{1, 2}, Pair{1, 0}, Pair{0.5f, 0.5f}, Pair{4, 1}}) {
        float a = symmetricAcceptance(p.current, p.proposal);
        measured.push_back(a), zero.push_back(0);
        right.push_back(std::min(1.0f, p.proposal / p.current));
        inverted.push_back(p.proposal > 0 ? std::min(1.0f, p.current / p.proposal) : 0);
        unclamped.push_back(p.proposal / p.current);
    }
    std::vector<Model> models = {
        {"right", "", right},
        {"inverted", "the ratio upside down: min(1, f(current) / f(proposal)) sends the chain away from the bright paths; detailed balance "
                     "needs the proposal's contribution over the current one's (page 16)", inverted},
        {"no min", "not bounded by 1: a probability; min(1, f(y)/f(x))", unclamped},
    };
    Fit f = fitModels(measured, zero, models, "symmetricAcceptance(f current, f proposal) at (2, 1), (1, 2), (1, 0), (0.5, 0.5), (4, 1)", 1e-5);
    return {f.pass, f.text, f.mistake};
}

Outcome chainVisits() {
    TargetRun run = runOnTarget(7);
    // 63 degrees of freedom: about 63 +- 11 when the chain fits; a broken balance gives thousands
    if (run.visitedChiSquare < 150) return {true, ""};
    return {false, "a chain on a known target (60 times brighter in one corner): the states it visits do not follow the target (chi-square " +
                       num(run.visitedChiSquare, 4) + " over 64 bins, about 63 when they do; acceptance " + num(run.acceptance, 3) +
                       "): detailed balance needs a = min(1, f(y)/f(x)), the proposal made current when accepted (page 16)"};
}

Outcome chainSplats() {
    TargetRun run = runOnTarget(9);
    if (run.splattedChiSquare < 150) return {true, ""};
    return {false, "a chain on a known target: its expected-value splats do not follow it (chi-square " + num(run.splattedChiSquare, 4) +
                       " over 64 bins, about 63 when they do): the proposal gets a / f(y) and the current state (1 - a) / f(x), the latter "
                       "paid out when the chain leaves it (Kelemen et al.; page 16)"};
}

std::vector<Check> checksH6() {
    return {{"the acceptance", 2, acceptance}, {"a chain visits its target", 4, chainVisits}, {"the expected-value splats", 4, chainSplats}};
}

}  // namespace grade

// ============================================================================================
// The data (made once, by the complete renderer, when the homework is handed out), and the run.
namespace grade {

Image downsampled(const Image& img, int f) {
    Image out(img.width / f, img.height / f);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) out.at(x / f, y / f) += img.at(x, y) / float(f * f);
    return out;
}

int writeData(const std::string& dir) {
    if (!makeFolders(dir)) { std::fprintf(stderr, "grade: cannot make %s\n", dir.c_str()); return 1; }
    auto save = [&](const Image& img, const std::string& name) {
        if (!writePFM(img, dir + "/" + name + ".pfm")) throw std::runtime_error("cannot write " + dir + "/" + name + ".pfm");
    };
    Image ref;
    for (const char* name : {"cornell", "cornell-point"}) {
        if (!readPFM(std::string("scenes/refs/") + name + ".pfm", ref)) throw std::runtime_error(std::string("no scenes/refs/") + name + ".pfm");
        save(downsampled(ref, ref.width / 32), std::string(name) + "-32");
    }
    if (!readPFM("tests/refs/cornell-direct.pfm", ref)) throw std::runtime_error("no tests/refs/cornell-direct.pfm");
    save(ref, "cornell-direct-24");
    // bdpt's MIS-weighted strategies with a camera subpath of two vertices or more, summed per length
    Scene sc = scene("scenes/cornell.scene", 32, 32);
    RenderOptions o = options(Method::BDPT, 4096, 101);
    o.strategyMaxLength = 3;
    o.threads = 0;
    RenderResult r = render(sc, o);
    for (int k = 1; k <= 3; ++k) {
        Image sum(32, 32);
        for (int s = 0; s + 2 <= k + 1; ++s) {
            const Image& w = r.strategies.at(s, k + 1 - s, true);
            for (size_t i = 0; i < sum.pixels.size(); ++i) sum.pixels[i] += w.pixels[i];
        }
        save(sum, "bdpt-t2-k" + std::to_string(k));
        for (int s = 0; s + 2 <= k + 1; ++s) save(r.strategies.at(s, k + 1 - s, false), "bdpt-s" + std::to_string(s) + "-t" + std::to_string(k + 1 - s));
    }
    std::ofstream numbers(dir + "/numbers.txt");
    char line[128];
    std::snprintf(line, sizeof line, "energy-generator-power-ratio %.6f\n", floorPowerRatio(scene("scenes/energy-generator.scene", 48, 36), 200, 10000, 99 + 1000 * gSeed).mean);
    numbers << line;
    return numbers ? 0 : 1;
}

#ifdef BDPT_HIDDEN_CHECKS
#include "hidden.h"  // the teacher's checks, in this namespace: never copied into a student's folder
#endif

std::vector<Check> checksFor(const std::string& id) {
    std::vector<Check> checks = id == "H1" ? checksH1() : id == "H2" ? checksH2() : id == "H3" ? checksH3() : id == "H4" ? checksH4()
                              : id == "H5" ? checksH5() : id == "H6" ? checksH6() : std::vector<Check>();
#ifdef BDPT_HIDDEN_CHECKS  // the teacher's grade: hidden.h's checks too (make grade-class, make gradescope)
    for (Check c : hiddenChecksFor(id)) c.hidden = true, checks.push_back(c);
#endif
    return checks;
}
// A task's CPU seconds: its checks take a few on a laptop; the limit only stops an endless loop
// (--cpu-limit S sets another).
double gCpuLimit = 60;

int run(const std::vector<TaskSpec>& tasks, const std::string& jsonPath) {
    const auto start = std::chrono::steady_clock::now();
    int total = 0, max = 0, hidden = 0, hiddenMax = 0;
    std::vector<TaskResult> results;
    for (const TaskSpec& t : tasks) {
        TaskResult r = runTask(checksFor(t.id), gCpuLimit);
        if (r.max != t.points) r.notes.push_back("the grader's checks add up to " + std::to_string(r.max) + " points, the task list says " + std::to_string(t.points));
        printTask(t, r);
        total += r.points, max += r.max, hidden += r.hiddenPoints, hiddenMax += r.hiddenMax;
        results.push_back(r);
    }
    if (hiddenMax > 0) std::printf("total %d / %d, hidden %d / %d\n", total, max, hidden, hiddenMax);
    else std::printf("total %d / %d\n", total, max);
    if (!jsonPath.empty() && !writeJson(jsonPath, tasks, results, secondsSince(start))) {
        std::fprintf(stderr, "grade: cannot write %s\n", jsonPath.c_str());
        return 1;
    }
    return 0;
}

}  // namespace grade

int main(int argc, char** argv) {
    std::string tasksFile = "grader/tasks.txt", only, json;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i], v = i + 1 < argc ? argv[i + 1] : "";
        if (a == "--write-data" && !v.empty()) {
            try {
                return grade::writeData(v);
            } catch (const std::exception& e) {
                std::fprintf(stderr, "grade --write-data: %s\n", e.what());
                return 1;
            }
        }
        if (a == "--data" && !v.empty()) grade::dataDir = v, ++i;
        else if (a == "--tasks" && !v.empty()) tasksFile = v, ++i;
        else if (a == "--task" && !v.empty()) only = v, ++i;
        else if (a == "--json" && !v.empty()) json = v, ++i;
        else if (a == "--cpu-limit" && std::atof(v.c_str()) > 0) grade::gCpuLimit = std::atof(v.c_str()), ++i;
        else if (a == "--seed" && !v.empty()) grade::gSeed = uint64_t(std::atoll(v.c_str())), ++i;
        else {
            std::fprintf(stderr, "usage: grade [--task ID] [--data DIR] [--tasks FILE] [--cpu-limit SECONDS] [--seed N] [--json FILE] | grade --write-data DIR\n");
            return 2;
        }
    }
    std::vector<grade::TaskSpec> tasks;
    std::ifstream in(tasksFile);
    for (std::string line; std::getline(in, line);) {
        std::istringstream f(line);
        grade::TaskSpec t;
        if (!(f >> t.id >> t.points)) continue;
        std::getline(f, t.title);
        t.title = t.title.substr(t.title.find_first_not_of(' '));
        if (only.empty() || only == t.id) tasks.push_back(t);
    }
    if (tasks.empty()) {
        std::fprintf(stderr, "grade: no task %s in %s\n", only.empty() ? "at all" : only.c_str(), tasksFile.c_str());
        return 2;
    }
    std::printf("bdpt homework: grading bdpt.cpp by the physics, task by task (each in a process of its own, at most %g CPU seconds)\n",
                grade::gCpuLimit);
    return grade::run(tasks, json);
}
