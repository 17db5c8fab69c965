// classroom/web/bdpt-web.cpp: the lecture's renderer as a WebAssembly module for the page in this
// folder (make web). One module instance per Web Worker renders one panel on one thread, a few
// rows at a time (so that a large pass shows its progress): the same Rendering as ./bdpt, so a
// panel's mean agrees with ./bdpt's for the same options and seed (bit for bit for most methods;
// vcm's hash grid sums in another order: relative differences of 1e-7). The page calls the
// functions below through cwrap; strings come back as pointers to a buffer that the next call
// overwrites.
#include "../lecture.h"
#include "../metrics.h"  // compareToReference: the error as the charts measure it
#include "../physics.h"  // the path view's densities and weights from their definitions
#include <dirent.h>
#include <emscripten/emscripten.h>
#include <numeric>

// One panel: its scene (the Rendering refers to it), its options, its reference if there is one.
struct WebPanel {
    Scene scene;
    CommandLine cl;
    Image reference;                  // the one chosen by bdpt_start (see chooseReference)
    std::string referenceName;        // where it came from, as the page names it
    std::unique_ptr<Rendering> rendering;
    int rowsDone = 0;                 // of the pass in flight (0: none in flight)
    std::vector<float> image;         // the mean so far (or the first pass's rows), RGB, rows from the top
    std::vector<float> strategy;      // the strategy image last asked for, likewise
    ErrorMetrics error;
    int comparedWidth = 0;            // the size at which the image met its reference (0: none yet)
    int commonWidth = 0;              // the size at which it will (0: never)
    Scene maskScene;                  // the scene's camera at the compared size: a point light's pixel (lampPixels)
    VcmTotals vcm;                    // vcm's light vertices and memory over the passes, as ./bdpt counts them
    std::vector<Vec3> ownSamples;     // the last pass's pixels' own samples, before the splats (the path view)
};
static WebPanel gPanel;
static Image gGivenReference;         // a reference the page hands over (bdpt_reference_buffer)
static std::string gText;             // what a string-returning call returns

static const char* returned(const std::string& text) {
    gText = text;
    return gText.c_str();
}

// Two images meet at a common size: each averaged over blocks of f x f pixels (its own f), down to
// the largest size that both reach, of the same aspect, at least 16 pixels wide (coarser, the
// error would measure blocks, not pixels). The pixel filter is a box, so a block's mean estimates
// the pixel of the smaller image that covers it. Returns the common width, or 0.
static int commonWidth(int w1, int h1, int w2, int h2) {
    if (long(w1) * h2 != long(w2) * h1) return 0;
    int g = std::gcd(w1, w2);
    if (h1 % (w1 / g) || h2 % (w2 / g)) return 0;
    return g >= 16 ? g : 0;
}

// The image averaged over f x f blocks.
static Image boxAverage(const Image& img, int f) {
    if (f == 1) return img;
    Image out(img.width / f, img.height / f);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            Vec3 s(0);
            for (int v = 0; v < f; ++v)
                for (int u = 0; u < f; ++u) s = s + img.at(f * x + u, f * y + v);
            out.pixels[size_t(y) * out.width + x] = s * (1.0f / (f * f));
        }
    return out;
}

// NAME-WxH.pfm, of this scene's NAME exactly: sds-point-96x64.pfm is sds-point's, not sds's.
static bool isSizedReference(const std::string& file, const std::string& stem) {
    int w = 0, h = 0, end = 0;
    return file.rfind(stem + "-", 0) == 0 && std::sscanf(file.c_str() + stem.size() + 1, "%dx%d.pfm%n", &w, &h, &end) == 2 &&
           size_t(end) + stem.size() + 1 == file.size() && w > 0 && h > 0;
}

// The reference for a panel of width x height: the one asked for ("none", "given": the page's
// own, or a path in the module: a notes command's --ref), or else, of the scene's committed
// reference (scenes/refs/NAME.pfm) and the page's own for the sizes the notes use
// (/web-refs/NAME-WxH.pfm, classroom/web/refs/), the one that meets the image at the largest size.
static void chooseReference(const std::string& sceneName, const std::string& asked, int width, int height) {
    gPanel.reference = Image();
    gPanel.referenceName.clear();
    Image img;
    if (asked == "none") return;
    if (asked == "given") {
        gPanel.reference = gGivenReference, gPanel.referenceName = "given";
        return;
    }
    if (!asked.empty()) {
        if (!readPFM(asked, img)) ArgReader::fail("the reference " + asked.substr(1) + " is not in the page");
        gPanel.reference = img, gPanel.referenceName = asked.substr(1);
        return;
    }
    const std::string stem = replaceExtension(sceneName.substr(sceneName.find_last_of('/') + 1), "");
    std::vector<std::string> candidates = {"/scenes/refs/" + stem + ".pfm"};
    if (DIR* dir = opendir("/web-refs")) {
        while (dirent* e = readdir(dir))
            if (std::string name = e->d_name; isSizedReference(name, stem)) candidates.push_back("/web-refs/" + name);
        closedir(dir);
    }
    int best = 0;
    for (const std::string& path : candidates)
        if (readPFM(path, img) && commonWidth(width, height, img.width, img.height) > best) {
            best = commonWidth(width, height, img.width, img.height);
            gPanel.reference = img, gPanel.referenceName = path.substr(1);
        }
    if (!best && readPFM(candidates[0], img)) gPanel.reference = img, gPanel.referenceName = candidates[0].substr(1);  // says why it cannot compare
}

// What the page cannot do with an entry's option: a page writes no files and a worker is one thread.
static void refuseFileOptions(const CommandLine& cl) {
    for (const char* o : {"--out", "--log", "--strategies", "--live", "--profile"})
        if (cl.given.count(o))
            ArgReader::fail(std::string(o) + " writes files or a terminal's table: in the page, use a panel's PNG and PFM buttons and the pyramid");
}

// The words of a --side-by-side entry ("ir --clamp 1e-5 --spp 64") as ./bdpt's command line, with
// the page's size, samples, seconds and seed where the entry does not give its own, as
// ./bdpt --side-by-side treats an entry's options.
static CommandLine entryCommandLine(const std::string& sceneName, const std::string& entry, int width, int height, int spp,
                                    double seconds, int seed) {
    std::vector<std::string> args = {sceneName, "--method"};
    std::istringstream words(entry);
    for (std::string w; words >> w;) args.push_back(w);
    if (args.size() == 2) ArgReader::fail("an empty entry: name a method, as in 'bdpt --heuristic power'");
    std::set<std::string> own(args.begin(), args.end());
    if (!own.count("--res") && width > 0) args.insert(args.end(), {"--res", std::to_string(width) + "x" + std::to_string(height)});
    if (!own.count("--seed")) args.insert(args.end(), {"--seed", std::to_string(seed)});
    if (!own.count("--spp") && !own.count("--time") && !own.count("--wall-time")) {
        if (spp > 0) args.insert(args.end(), {"--spp", std::to_string(spp)});
        else if (seconds > 0) args.insert(args.end(), {"--time", std::to_string(seconds)});
    }
    CommandLine cl = parseOptions(args, kOptions);
    checkCombinations(cl, kOptions);
    refuseFileOptions(cl);
    if (!cl.given.count("--spp") && !cl.given.count("--time") && !cl.given.count("--wall-time")) cl.opt.spp = 1 << 30;  // until Stop
    return cl;
}

// The error against the reference, at the size where the two meet (commonWidth).
static void compareWithReference(const Image& mean) {
    const Image& ref = gPanel.reference;
    gPanel.comparedWidth = 0;
    int g = ref.width ? commonWidth(mean.width, mean.height, ref.width, ref.height) : 0;
    if (!g) return;
    gPanel.error = compareToReference(boxAverage(mean, mean.width / g), boxAverage(ref, ref.width / g), &gPanel.maskScene);
    gPanel.comparedWidth = g;
}

extern "C" {

// The scene's error message (file:line, as ./bdpt prints it), or "" if it parses.
EMSCRIPTEN_KEEPALIVE const char* bdpt_check_scene(const char* text, const char* name) {
    try {
        parseScene(text, name);
        return returned("");
    } catch (const InputError& e) {
        return returned(e.what());
    }
}

// Each method's caption, what it does and the notes' pages (bdpt.cpp's kMethodCaptions), as
// "name\tcaption\twhat\tpages" lines: the page describes its panels with them.
EMSCRIPTEN_KEEPALIVE const char* bdpt_method_captions() {
    std::string lines;
    for (int m = 0; m < int(std::size(kMethodNames)); ++m) {
        const MethodCaption& c = kMethodCaptions[m];
        lines += std::string(kMethodNames[m]) + "\t" + c.caption + "\t" + c.what + "\t" + c.pages + "\n";
    }
    return returned(lines);
}

// The lecture program's --help: what an error's "(see --help)" points to.
EMSCRIPTEN_KEEPALIVE const char* bdpt_help() { return returned(usage(kOptions)); }

// Prepares a panel: scene text and name, the entry's method and options, the page's image size
// (0: the scene's), samples per pixel and seconds (0: none) and seed, which the entry's own
// options override, the longest path with per-strategy images (bdpt and vcm; 0: none), and the
// reference to measure against ("": the scene's; "none"; "given"; a path: chooseReference).
// Returns "" or the message that says what is wrong; nothing is rendered yet.
EMSCRIPTEN_KEEPALIVE const char* bdpt_start(const char* sceneText, const char* sceneName, const char* entry, int width, int height,
                                            int spp, double seconds, int seed, int strategyLength, const char* reference) {
    gPanel.rendering.reset();
    gPanel.rowsDone = 0;
    gPanel.comparedWidth = 0;
    gPanel.vcm = VcmTotals();
    try {
        gPanel.cl = entryCommandLine(sceneName, entry, width, height, spp, seconds, seed);
        gPanel.scene = parseScene(sceneText, sceneName);
        applyToScene(gPanel.cl, gPanel.scene);
        const Camera& cam = gPanel.scene.camera;
        chooseReference(sceneName, reference, cam.width, cam.height);
    } catch (const InputError& e) {
        return returned(e.what());
    }
    RenderOptions& opt = gPanel.cl.opt;
    opt.threads = 1;  // a worker is one thread; the page runs one worker per panel
    opt.strategyMaxLength = opt.method == Method::BDPT || opt.method == Method::VCM ? strategyLength : 0;
    gPanel.rendering = std::make_unique<Rendering>(gPanel.scene, opt);
    const Camera& cam = gPanel.scene.camera;
    gPanel.maskScene = gPanel.scene;
    gPanel.commonWidth = gPanel.reference.width ? commonWidth(cam.width, cam.height, gPanel.reference.width, gPanel.reference.height) : 0;
    if (gPanel.commonWidth) setResolution(gPanel.maskScene.camera, gPanel.commonWidth, cam.height * gPanel.commonWidth / cam.width);
    gPanel.image.assign(3 * size_t(cam.width) * cam.height, 0.0f);
    return returned("");
}

// Room for a reference the page rendered itself (an edited scene's): width x height RGB floats,
// rows from the top, which the page fills before a bdpt_start(..., "given").
EMSCRIPTEN_KEEPALIVE float* bdpt_reference_buffer(int width, int height) {
    gGivenReference = Image(width, height);
    return &gGivenReference.pixels[0].x;
}

// One more row of the pass in flight (a pass begins with its light paths, VPLs or chains, and
// ends with the splats and the film). Returns the passes done, or -1 when the module ran out of
// memory (the image is as it was).
EMSCRIPTEN_KEEPALIVE int bdpt_row() {
    Rendering& r = *gPanel.rendering;
    try {
        if (gPanel.rowsDone == 0) r.beginPass();
        r.renderRow(gPanel.rowsDone++);
        if (gPanel.rowsDone == r.scene.camera.height) {
            gPanel.ownSamples = r.pass;
            r.endPass();
            gPanel.rowsDone = 0;
            if (r.opt.method == Method::VCM) gPanel.vcm.add(r.storage.vcm);
        }
    } catch (const std::bad_alloc&) {
        return -1;
    }
    return r.result.passes;
}
EMSCRIPTEN_KEEPALIVE int bdpt_rows_done() { return gPanel.rowsDone; }

// The image to show: the mean of the passes done, or before the first pass ends, its rows so far
// (light tracing's splats arrive only at a pass's end). The mean and the error follow it.
EMSCRIPTEN_KEEPALIVE void bdpt_snapshot() {
    const Rendering& r = *gPanel.rendering;
    const double n = r.result.passes;
    if (n > 0) {
        for (size_t i = 0; i < gPanel.image.size(); ++i) gPanel.image[i] = float(r.film.sum[i] / n);
    } else {
        for (size_t p = 0; p < r.pass.size(); ++p)
            for (int c = 0; c < 3; ++c) gPanel.image[3 * p + c] = p < size_t(gPanel.rowsDone) * r.scene.camera.width ? r.pass[p][c] : 0.0f;
    }
    Image mean(r.film.width, r.film.height);
    for (size_t p = 0; p < mean.pixels.size(); ++p) mean.pixels[p] = Vec3(gPanel.image[3 * p], gPanel.image[3 * p + 1], gPanel.image[3 * p + 2]);
    if (n > 0) compareWithReference(mean);
}

EMSCRIPTEN_KEEPALIVE float* bdpt_image() { return gPanel.image.data(); }
EMSCRIPTEN_KEEPALIVE int bdpt_width() { return gPanel.scene.camera.width; }
EMSCRIPTEN_KEEPALIVE int bdpt_height() { return gPanel.scene.camera.height; }
EMSCRIPTEN_KEEPALIVE int bdpt_spp() { return gPanel.cl.opt.seconds > 0 ? 0 : gPanel.cl.opt.spp; }
EMSCRIPTEN_KEEPALIVE double bdpt_seconds() { return gPanel.cl.opt.seconds; }
EMSCRIPTEN_KEEPALIVE int bdpt_threads_given() { return gPanel.cl.given.count("--threads") > 0; }
EMSCRIPTEN_KEEPALIVE float bdpt_exposure() { return gPanel.cl.exposure; }
EMSCRIPTEN_KEEPALIVE long long bdpt_non_finite() { return gPanel.rendering->result.nonFinite; }
EMSCRIPTEN_KEEPALIVE int bdpt_reference_width() { return gPanel.reference.width; }
EMSCRIPTEN_KEEPALIVE const char* bdpt_reference_name() { return returned(gPanel.referenceName); }
EMSCRIPTEN_KEEPALIVE int bdpt_reference_height() { return gPanel.reference.height; }
EMSCRIPTEN_KEEPALIVE int bdpt_compared_width() { return gPanel.comparedWidth; }
EMSCRIPTEN_KEEPALIVE int bdpt_common_width() { return gPanel.commonWidth; }
// The image's mean over pixels and channels, as ./bdpt's summary line prints it.
EMSCRIPTEN_KEEPALIVE double bdpt_mean() {
    double s = 0;
    for (float v : gPanel.image) s += v;
    return s / std::max<size_t>(1, gPanel.image.size());
}
EMSCRIPTEN_KEEPALIVE double bdpt_rmse() { return gPanel.error.rmse; }
EMSCRIPTEN_KEEPALIVE double bdpt_rmse_without_lamp() { return gPanel.error.rmseWithoutLamp; }
// The image mean's relative difference from the reference's, the lamp's pixels left out (./bdpt's "bias").
EMSCRIPTEN_KEEPALIVE double bdpt_bias() { return gPanel.error.bias; }

// What ./bdpt's summary says beyond the image's mean, as it prints it: the rays per sample, vcm's
// radius, light vertices and memory, the chains' b and acceptance (per mutation for mlt), the
// energy ir's clamp removed; and the relMSE of its line against a reference.
EMSCRIPTEN_KEEPALIVE const char* bdpt_summary() {
    const Rendering& r = *gPanel.rendering;
    if (r.result.passes == 0) return returned("");
    RenderResult counted;
    counted.passes = r.result.passes;
    counted.rays = r.result.rays;
    counted.image.width = r.scene.camera.width, counted.image.height = r.scene.camera.height;
    std::string s = raysPerSample(counted);
    if (r.opt.strategyMaxLength > 0)  // ./bdpt counts them only with --strategies: its figure without them is lower
        s += " with the pyramid's record (./bdpt --strategies's count: the record traces the (1,1) connections' shadow rays, "
             "which bdpt alone spares, their weight being 0)";
    s += "\n";
    if (r.opt.method == Method::VCM) s += vcmSummary(r.scene, r.result.passes, gPanel.vcm);
    s += methodSummary(r.opt, r.storage.metropolis, r.result.clampRemoved());
    return returned(s);
}
EMSCRIPTEN_KEEPALIVE double bdpt_relmse() { return gPanel.error.relMse; }

// The strategies recorded, "k s index;" each (s = k + 1: vcm's merges of length k), in the order
// of the slides' pyramid; "" when the panel records none.
EMSCRIPTEN_KEEPALIVE const char* bdpt_strategies() {
    std::ostringstream list;
    gPanel.rendering->film.strategies.forEach([&](int k, int s, int index) { list << k << " " << s << " " << index << ";"; });
    return returned(list.str());
}

// Strategy image `index` so far, MIS-weighted or not: RGB floats, rows from the top.
EMSCRIPTEN_KEEPALIVE float* bdpt_strategy_image(int index, int weighted) {
    const Rendering& r = *gPanel.rendering;
    const std::vector<double>& sum = r.film.strategySum[2 * size_t(index) + (weighted ? 1 : 0)];
    const double n = std::max(1, r.result.passes);
    gPanel.strategy.resize(sum.size());
    for (size_t i = 0; i < sum.size(); ++i) gPanel.strategy[i] = float(sum[i] / n);
    return gPanel.strategy.data();
}

}  // extern "C"

// ---- one sample's paths, drawn (the page's path view): page 7's worked path, live.

static void appendVec(std::ostringstream& o, Vec3 v) { o << "[" << v.x << "," << v.y << "," << v.z << "]"; }

// A vertex as the page draws it: where it is, where it appears on the film (null: behind the
// camera), what it is, and its densities from its own side and from the other.
static void writeVertexJson(std::ostringstream& o, const Scene& scene, const PathVertex& v) {
    float filmX = NAN, filmY = NAN;
    projectToFilm(scene.camera, v.sp.p, filmX, filmY);  // sets them for any point in front of the pinhole
    o << "{\"p\":";
    appendVec(o, v.sp.p);
    if (v.type == PathVertex::Camera || std::isnan(filmX)) o << ",\"film\":null";
    else o << ",\"film\":[" << filmX << "," << filmY << "]";
    const char* kind = v.type == PathVertex::Camera ? "pinhole" : v.type == PathVertex::Light ? (v.deltaPosition ? "point light" : "lamp")
                     : v.delta ? "specular" : "surface";
    o << ",\"kind\":\"" << kind << "\",\"pdfFwd\":" << v.pdfFwd << ",\"pdfRev\":" << v.pdfRev << "}";
}

static const Heuristic kHeuristics[4] = {Heuristic::Balance, Heuristic::Power, Heuristic::Max, Heuristic::Uniform};

// Connection (s,t) as the render made it (C_{s,t}, the pixel it lands on), as JSON: the renderer's
// weight w_{s,t} in each heuristic (misWeight), and the path's table from the definitions
// (classroom/physics.h, as the tests judge the renderer): every strategy able to make the path
// (vcm: and every merge, s its light vertices), its density p_i (through mirrors and glass the
// chains' common G left out: ratios only) and each heuristic's weight of it.
static void writeConnectionJson(std::ostringstream& o, const Scene& scene, const RenderOptions& opt, const std::vector<PathVertex>& light,
                                const std::vector<PathVertex>& camera, const StrategySplat& made, double mergeEta) {
    const int s = made.s, t = made.t;
    Connection c;
    int pixel = -1;
    connectStrategy(scene, light, s, camera, t, c, pixel);  // the connection misWeight reads
    std::vector<PathVertex> x = joinPath(light, s, camera, t);
    std::map<int, double> density = strategyDensities(scene, x, opt.roulette, mergeEta);
    o << "{\"s\":" << s << ",\"t\":" << t << ",\"C\":" << average(made.value) << ",\"density\":" << pathDensity(scene, x, s, opt.roulette)
      << ",\"pixel\":" << made.pixel << ",\"weight\":" << made.weight << ",\"w\":[";
    for (int h = 0; h < 4; ++h) o << (h ? "," : "") << misWeight(scene, light, s, camera, t, kHeuristics[h], c, mergeEta);
    o << "],\"strategies\":[";
    bool first = true;
    auto writeStrategy = [&](int key) {  // (s,t) itself first, as the page lists it
        bool merge = key >= kMergeKey;
        o << (first ? "" : ",") << "{\"s\":" << (merge ? key - kMergeKey + 1 : key) << ",\"merge\":" << (merge ? "true" : "false")
          << ",\"density\":" << density.at(key) << ",\"w\":[";
        for (int h = 0; h < 4; ++h)  // the light seen directly is left to s = 0, whatever the densities (misWeight)
            o << (h ? "," : "") << (s + t == 2 ? (key == 0 ? 1.0 : 0.0) : definitionWeight(kHeuristics[h], density, key));
        o << "]}";
        first = false;
    };
    writeStrategy(s);
    for (const auto& [key, p] : density)
        if (key != s) writeStrategy(key);
    o << "]}";
}

extern "C" {

// Pixel (x, y)'s sample of the last pass done, made again from its own random streams as
// sampleBDPT makes it (the camera subpath, the light subpath: bdpt's and vcm's are the same), its
// connections listed by the lecture's own connectSubpaths as it weighs them (writeConnectionJson),
// and the value the pixel got in that pass (before other pixels' splats): make test-web checks
// that the connections' sum of C w for t >= 2 is that value, so what is drawn is the pixel's own
// sample. vcm's weights count its merges (the pass's mergeEta); the merges themselves are not
// drawn. "" for other methods.
EMSCRIPTEN_KEEPALIVE const char* bdpt_path_sample(int x, int y) {
    const Rendering& r = *gPanel.rendering;
    const Scene& scene = r.scene;
    const RenderOptions& opt = r.opt;
    if ((opt.method != Method::BDPT && opt.method != Method::VCM) || r.result.passes == 0) return returned("");
    const int pass = r.result.passes - 1, ownPixel = y * scene.camera.width + x;
    const double mergeEta = opt.method == Method::VCM ? r.storage.vcm.mergeEta : 0;
    Rng cameraRng = sampleRng(opt, kCameraStream, uint64_t(ownPixel), uint64_t(pass));
    FilmPoint f = jitteredFilmPoint(x, y, cameraRng);
    std::vector<PathVertex> camera, light;
    cameraSubpath(scene, opt, f.x, f.y, cameraRng, camera);
    Rng lightRng = lightPathRng(opt, ownPixel, pass);
    lightSubpath(scene, opt, lightRng, light);
    RowOutput made;
    connectSubpaths(scene, opt, light, camera, ownPixel, mergeEta, made, std::numeric_limits<int>::max(),
                    [&made](const StrategySplat& c) { made.strategySplats.push_back(c); });
    std::ostringstream o;
    o.precision(7);
    o << "{\"pass\":" << pass << ",\"film\":[" << f.x << "," << f.y << "],\"mergeEta\":" << mergeEta
      << ",\"pixelValue\":" << average(gPanel.ownSamples[size_t(ownPixel)]) << ",\"camera\":[";
    for (size_t i = 0; i < camera.size(); ++i) o << (i ? "," : ""), writeVertexJson(o, scene, camera[i]);
    o << "],\"light\":[";
    for (size_t i = 0; i < light.size(); ++i) o << (i ? "," : ""), writeVertexJson(o, scene, light[i]);
    o << "],\"connections\":[";
    for (size_t i = 0; i < made.strategySplats.size(); ++i)
        o << (i ? "," : ""), writeConnectionJson(o, scene, opt, light, camera, made.strategySplats[i], mergeEta);
    o << "]}";
    return returned(o.str());
}

// The scene's shapes for the path view's side view: quads (corner, edges), spheres (centre,
// radius), point lights, and the camera's frame.
EMSCRIPTEN_KEEPALIVE const char* bdpt_scene_outline() {
    const Scene& scene = gPanel.rendering->scene;
    std::ostringstream o;
    o << "{\"quads\":[";
    bool first = true;
    for (const Shape& sh : scene.shapes)
        if (sh.type == Shape::Quad) {
            o << (first ? "" : ",") << "[", appendVec(o, sh.p), o << ",", appendVec(o, sh.u), o << ",", appendVec(o, sh.v),
                o << "," << (isBlack(sh.emission) ? "false" : "true") << "]";
            first = false;
        }
    o << "],\"spheres\":[";
    first = true;
    for (const Shape& sh : scene.shapes)
        if (sh.type == Shape::Sphere) o << (first ? "" : ",") << "[", appendVec(o, sh.p), o << "," << sh.radius << "]", first = false;
    o << "],\"points\":[";
    first = true;
    for (const Light& l : scene.lights)
        if (l.type == Light::Point) o << (first ? "" : ","), appendVec(o, l.position), first = false;
    const Camera& cam = scene.camera;
    o << "],\"eye\":", appendVec(o, cam.eye), o << ",\"forward\":", appendVec(o, cam.forward), o << ",\"up\":", appendVec(o, cam.up),
        o << ",\"right\":", appendVec(o, cam.right), o << "}";
    return returned(o.str());
}

}  // extern "C"
