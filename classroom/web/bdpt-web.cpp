// classroom/web/bdpt-web.cpp: the lecture's renderer as a WebAssembly module for the page in this
// folder (make web). One module instance per Web Worker renders one panel, pass by pass, on one
// thread: the same Rendering as ./bdpt, so a panel's image is ./bdpt's for the same options and
// seed, bit for bit. The page calls the functions below through cwrap; strings come back as
// pointers to a buffer that the next call overwrites.
#include "../lecture.h"
#include "../metrics.h"  // readPFM, compareToReference: the error as the charts measure it
#include <emscripten/emscripten.h>

// One panel: its scene (the Rendering refers to it), its options, its reference if there is one.
struct WebPanel {
    Scene scene;
    CommandLine cl;
    Image reference;                  // scenes/refs/NAME.pfm when it has the panel's size
    std::unique_ptr<Rendering> rendering;
    std::vector<float> image;         // the mean so far, RGB, rows from the top
    std::vector<float> strategy;      // the strategy image last asked for, likewise
    ErrorMetrics error;
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

// The words of a --side-by-side entry ("ir --clamp 1e-5") as ./bdpt's command line.
static CommandLine entryCommandLine(const std::string& sceneName, const std::string& entry, int seed) {
    std::vector<std::string> args = {sceneName, "--method"};
    std::istringstream words(entry);
    for (std::string w; words >> w;) args.push_back(w);
    if (args.size() == 2) ArgReader::fail("an empty entry: name a method, as in 'bdpt --heuristic power'");
    args.insert(args.end(), {"--seed", std::to_string(seed)});
    CommandLine cl = parseOptions(args, kOptions);
    checkCombinations(cl, kOptions);
    return cl;
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

// Prepares a panel: scene text and name, the entry's method and options, the image size (0: the
// scene's), the seed, and the longest path with per-strategy images (bdpt and vcm; 0: none).
// Returns "" or the message that says what is wrong; nothing is rendered yet.
EMSCRIPTEN_KEEPALIVE const char* bdpt_start(const char* sceneText, const char* sceneName, const char* entry, int width, int height,
                                            int seed, int strategyLength) {
    gPanel.rendering.reset();
    try {
        gPanel.cl = entryCommandLine(sceneName, entry, seed);
        if (width > 0) gPanel.cl.width = width, gPanel.cl.height = height;
        gPanel.scene = parseScene(sceneText, sceneName);
        applyToScene(gPanel.cl, gPanel.scene);
    } catch (const InputError& e) {
        return returned(e.what());
    }
    RenderOptions& opt = gPanel.cl.opt;
    opt.threads = 1;  // a worker is one thread; the page runs one worker per panel
    opt.strategyMaxLength = opt.method == Method::BDPT || opt.method == Method::VCM ? strategyLength : 0;
    Image ref;
    const Camera& cam = gPanel.scene.camera;
    gPanel.reference = readPFM(referencePath(sceneName), ref) && ref.width == cam.width && ref.height == cam.height ? ref : Image();
    gPanel.rendering = std::make_unique<Rendering>(gPanel.scene, opt);
    gPanel.image.assign(3 * size_t(cam.width) * cam.height, 0.0f);
    return returned("");
}

// One more pass (one sample per pixel); the image, the mean and the error then include it.
// Returns the passes so far, or -1 when the module ran out of memory (the image is as it was).
EMSCRIPTEN_KEEPALIVE int bdpt_pass() {
    Rendering& r = *gPanel.rendering;
    try {
        r.addPass();
    } catch (const std::bad_alloc&) {
        return -1;
    }
    const double n = r.result.passes;
    Image mean(r.film.width, r.film.height);
    for (size_t i = 0; i < gPanel.image.size(); ++i) gPanel.image[i] = float(r.film.sum[i] / n);
    for (size_t p = 0; p < mean.pixels.size(); ++p) mean.pixels[p] = Vec3(gPanel.image[3 * p], gPanel.image[3 * p + 1], gPanel.image[3 * p + 2]);
    if (gPanel.reference.width > 0) gPanel.error = compareToReference(mean, gPanel.reference);
    return r.result.passes;
}

EMSCRIPTEN_KEEPALIVE float* bdpt_image() { return gPanel.image.data(); }
EMSCRIPTEN_KEEPALIVE int bdpt_width() { return gPanel.scene.camera.width; }
EMSCRIPTEN_KEEPALIVE int bdpt_height() { return gPanel.scene.camera.height; }
EMSCRIPTEN_KEEPALIVE float bdpt_exposure() { return gPanel.cl.exposure; }
EMSCRIPTEN_KEEPALIVE long long bdpt_non_finite() { return gPanel.rendering->result.nonFinite; }
EMSCRIPTEN_KEEPALIVE int bdpt_has_reference() { return gPanel.reference.width > 0; }
// The image's mean over pixels and channels, as ./bdpt's summary line prints it.
EMSCRIPTEN_KEEPALIVE double bdpt_mean() {
    double s = 0;
    for (float v : gPanel.image) s += v;
    return s / std::max<size_t>(1, gPanel.image.size());
}
EMSCRIPTEN_KEEPALIVE double bdpt_rmse() { return gPanel.error.rmse; }
EMSCRIPTEN_KEEPALIVE double bdpt_rmse_without_lamp() { return gPanel.error.rmseWithoutLamp; }

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
