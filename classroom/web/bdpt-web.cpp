// classroom/web/bdpt-web.cpp: the lecture's renderer as a WebAssembly module for the page in this
// folder (make web). One module instance per Web Worker renders one panel on one thread, a few
// rows at a time (so that a large pass shows its progress): the same Rendering as ./bdpt, so a
// panel's mean agrees with ./bdpt's for the same options and seed (bit for bit for most methods;
// vcm's hash grid sums in another order: relative differences of 1e-7). The page calls the
// functions below through cwrap; strings come back as pointers to a buffer that the next call
// overwrites.
#include "../lecture.h"
#include "../metrics.h"  // readPFM, compareToReference: the error as the charts measure it
#include <emscripten/emscripten.h>

// One panel: its scene (the Rendering refers to it), its options, its reference if there is one.
struct WebPanel {
    Scene scene;
    CommandLine cl;
    Image reference;                  // scenes/refs/NAME.pfm, of any size
    std::unique_ptr<Rendering> rendering;
    int rowsDone = 0;                 // of the pass in flight (0: none in flight)
    std::vector<float> image;         // the mean so far (or the first pass's rows), RGB, rows from the top
    std::vector<float> strategy;      // the strategy image last asked for, likewise
    ErrorMetrics error;
    int comparedWidth = 0;            // the size at which the image met its reference (0: none)
};
static WebPanel gPanel;
static std::string gText;             // what a string-returning call returns

static const char* returned(const std::string& text) {
    gText = text;
    return gText.c_str();
}

// "scenes/cornell.scene" -> "/scenes/refs/cornell.pfm" (the module holds scenes/ at its root).
static std::string referencePath(const std::string& sceneName) {
    std::string stem = sceneName.substr(sceneName.find_last_of('/') + 1);
    return "/scenes/refs/" + replaceExtension(stem, ".pfm");
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

// The image averaged over f x f blocks: the pixel filter is a box, so a block's mean estimates the
// pixel of the image f times smaller that covers it.
static Image boxAverage(const Image& img, int f) {
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

// The factor f (a power of two) with a * f = b, or 0.
static int powerOfTwoFactor(int a, int b) {
    for (int f = 1; f <= 64; f *= 2)
        if (a * f == b) return f;
    return 0;
}

// The error against the reference, at the smaller of the two sizes: the larger one averaged down.
static void compareWithReference(const Image& mean) {
    const Image& ref = gPanel.reference;
    gPanel.comparedWidth = 0;
    if (ref.width == 0) return;
    if (int f = powerOfTwoFactor(ref.width, mean.width); f && ref.height * f == mean.height) {
        gPanel.error = compareToReference(f == 1 ? mean : boxAverage(mean, f), ref);
        gPanel.comparedWidth = ref.width;
    } else if (int g = powerOfTwoFactor(mean.width, ref.width); g && mean.height * g == ref.height) {
        gPanel.error = compareToReference(mean, boxAverage(ref, g));
        gPanel.comparedWidth = mean.width;
    }
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

// The lecture program's --help: what an error's "(see --help)" points to.
EMSCRIPTEN_KEEPALIVE const char* bdpt_help() { return returned(usage(kOptions)); }

// Prepares a panel: scene text and name, the entry's method and options, the page's image size
// (0: the scene's), samples per pixel and seconds (0: none) and seed, which the entry's own
// options override, and the longest path with per-strategy images (bdpt and vcm; 0: none).
// Returns "" or the message that says what is wrong; nothing is rendered yet.
EMSCRIPTEN_KEEPALIVE const char* bdpt_start(const char* sceneText, const char* sceneName, const char* entry, int width, int height,
                                            int spp, double seconds, int seed, int strategyLength) {
    gPanel.rendering.reset();
    gPanel.rowsDone = 0;
    gPanel.comparedWidth = 0;
    try {
        gPanel.cl = entryCommandLine(sceneName, entry, width, height, spp, seconds, seed);
        gPanel.scene = parseScene(sceneText, sceneName);
        applyToScene(gPanel.cl, gPanel.scene);
    } catch (const InputError& e) {
        return returned(e.what());
    }
    RenderOptions& opt = gPanel.cl.opt;
    opt.threads = 1;  // a worker is one thread; the page runs one worker per panel
    opt.strategyMaxLength = opt.method == Method::BDPT || opt.method == Method::VCM ? strategyLength : 0;
    Image ref;
    gPanel.reference = readPFM(referencePath(sceneName), ref) ? ref : Image();
    gPanel.rendering = std::make_unique<Rendering>(gPanel.scene, opt);
    const Camera& cam = gPanel.scene.camera;
    gPanel.image.assign(3 * size_t(cam.width) * cam.height, 0.0f);
    return returned("");
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
            r.endPass();
            gPanel.rowsDone = 0;
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
EMSCRIPTEN_KEEPALIVE int bdpt_reference_height() { return gPanel.reference.height; }
EMSCRIPTEN_KEEPALIVE int bdpt_compared_width() { return gPanel.comparedWidth; }
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
