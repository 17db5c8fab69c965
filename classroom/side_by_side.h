// classroom/side_by_side.h: --side-by-side: several methods on one scene, each in a thread of its own,
// as one titled 16:9 figure with the slides' captions, at equal samples or equal CPU time.
#pragma once
#include "checks.h"
#include "figures.h"
#include "run.h"
#include <iomanip>

// --side-by-side: several methods on one scene at once, each in a thread of its own (with its
// share of the cores), and one titled image of their running means, rewritten every --live
// seconds from the first moment on. With --time each panel renders on one thread until that
// thread's own CPU clock reaches the time: equal CPU time, however the cores are shared.
struct SideBySidePanel {
    std::string label;  // the entry as written: "ir --clamp 1e-5"
    ClassroomLine cl;
    Scene scene;        // its own copy (sharing the BVH): the deliberate mistakes are the scene's
    std::mutex lock;    // guards what follows, which the render's thread writes and the frames read
    std::vector<double> sum, sumSquares;  // per pixel and channel, over passes
    int passes = 0;
    double seconds = 0;  // CPU seconds, the panel's threads together
    bool done = false, outOfMemory = false;
    RenderResult result;
};

// The slides' captions of "Results from Different Techniques", for the entries that are exactly
// the methods they name.
inline std::string slideCaption(const std::string& entry) {
    static const std::map<std::string, std::string> captions = [] {
        std::map<std::string, std::string> m = {{"nee --mis", std::string(kMethodCaptions[int(Method::NEE)].caption) + ", with MIS"}};
        for (int i = 0; i < int(std::size(kMethodNames)); ++i) m[kMethodNames[i]] = kMethodCaptions[i].caption;  // bdpt.cpp's table
        return m;
    }();
    if (entry.rfind("ir --clamp ", 0) == 0 && entry.find(' ', 11) == std::string::npos) return "(e) Instant radiosity (clamped)";
    // A method keeps its caption with its own budget or seed; a later one with options that tune
    // it but do not change what it is.
    std::istringstream words(entry);
    std::string method, option, value, rest;
    words >> method;
    const std::set<std::string> budget = {"--spp", "--seed"}, tuning = {"--bootstrap", "--chains", "--radius", "--alpha", "--sigma", "--large-step"};
    const bool later = method == "vcm" || method == "mlt" || method == "pssmlt" || method == "mmlt";
    for (std::string word; words >> word;) {
        if ((budget.count(word) || (later && tuning.count(word))) && words >> value) continue;
        rest += " " + word;
    }
    auto it = captions.find(method + rest);
    return it == captions.end() ? "" : it->second;
}

// The slides' captions belong to the slides' comparison: a figure of at least three methods the
// slides caption differently. A letter (a)-(f) points to a panel of "Results from Different
// Techniques", so it is drawn only where the figure has three of them; elsewhere (pt and bdpt
// beside vcm, one method's variants) the entry itself is the caption.
inline std::vector<std::string> slidesCaptions(const std::vector<std::unique_ptr<SideBySidePanel>>& panels) {
    std::set<std::string> captions, lettered;
    for (auto& panel : panels) {
        const std::string c = slideCaption(panel->label);
        if (!c.empty()) captions.insert(c);
        if (c.rfind("(", 0) == 0) lettered.insert(c);
    }
    std::vector<std::string> out;
    for (auto& panel : panels) {
        const std::string c = slideCaption(panel->label);
        out.push_back(captions.size() < 3 || (c.rfind("(", 0) == 0 && lettered.size() < 3) ? "" : c);
    }
    return out;
}

// The figure for a projector: a title over the panels, each panel's caption under its own image,
// the images enlarged by the largest whole factor that fits 1920x1080, the canvas 16:9 (padded,
// content centred). Tiles are the panels and, with --ratio-panel, the ratio after them.
struct SideBySideLayout {
    int W, H, cols, rows, zoom = 1, scale, titleScale, titleLines, gap, strip, titleH, panelW, panelH, contentW, contentH,
        canvasW, canvasH, left, top;
    SideBySideLayout(int n, int width, int height, int widest, int widestTitle, int lines) : W(width), H(height), titleLines(lines) {
        cols = n <= 3 ? n : (n + 1) / 2;
        rows = (n + cols - 1) / cols;
        for (int z = 64; z >= 1; --z) {
            zoom = z;
            size(widest, widestTitle);
            if (contentW <= 1920 && contentH <= 1080) break;
        }
        canvasW = std::max({1920, contentW, (contentH * 16 + 8) / 9}), canvasH = std::max(contentH, (canvasW * 9 + 15) / 16);
        left = (canvasW - contentW) / 2, top = (canvasH - contentH) / 2;
    }
    void size(int widest, int widestTitle) {
        panelW = W * zoom, panelH = H * zoom;
        scale = std::max(1, std::min(4, (panelW - 4) / std::max(1, widest)));
        titleScale = std::max(scale, std::min(6, (cols * panelW) / std::max(1, widestTitle)));
        gap = 3 * scale;
        strip = 3 * 7 * scale + gap;  // three lines of caption under each image
        titleH = titleLines * 7 * titleScale + 2 * gap;
        contentW = cols * (panelW + gap) + gap, contentH = titleH + rows * (panelH + strip + gap) + gap;
    }
    int tileX(int i) const { return left + gap + (i % cols) * (panelW + gap); }
    int tileY(int i) const { return top + titleH + (i / cols) * (panelH + strip + gap); }
};

// A panel's running mean and the variance of that mean per pixel (from the passes' spread).
inline void panelMean(SideBySidePanel& panel, Image& mean, Image* variance, int& passes, double& seconds) {
    std::lock_guard<std::mutex> hold(panel.lock);
    passes = panel.passes, seconds = panel.seconds;
    for (size_t p = 0; passes > 0 && p < mean.pixels.size(); ++p)
        for (int c = 0; c < 3; ++c) {
            double m = panel.sum[3 * p + c] / passes;
            mean.pixels[p][c] = float(m);
            if (variance) variance->pixels[p][c] = float(std::max(0.0, panel.sumSquares[3 * p + c] / passes - m * m) / std::max(1, passes - 1));
        }
}

struct RatioPanel {
    std::string kind;  // "mean": B/A of the means; "error": B's squared error over A's, against --ref
    Image colours;
    double overall = 0;  // the ratio of the image means, or of the MSEs
};

// --ratio-panel: the second panel over the first in blocks a twelfth of the image across (large
// enough to read from the back of a room). "mean": grey where the blocks' means differ by less
// than 3 standard errors, or where either's standard error is over 15% of it (a few rare splats:
// the passes' spread is then no error bar); "error": each block's squared error against the
// reference, over two stops either way (a mistake that adds noise, not bias).
inline RatioPanel ratioPanel(std::vector<std::unique_ptr<SideBySidePanel>>& panels, const std::string& kind, const Image& ref) {
    const int W = panels[0]->scene.camera.width, H = panels[0]->scene.camera.height, block = std::max(2, std::min(W, H) / 12);
    Image a(W, H), b(W, H), va(W, H), vb(W, H);
    int passesA, passesB;
    double seconds;
    panelMean(*panels[0], a, &va, passesA, seconds);
    panelMean(*panels[1], b, &vb, passesB, seconds);
    RatioPanel r{kind, Image(W, H)};
    auto lum3 = [](const Vec3& v) { return double(v.x) + v.y + v.z; };
    auto sq = [](double d) { return d * d; };
    double errA = 0, errB = 0;
    for (int by = 0; by < H; by += block)
        for (int bx = 0; bx < W; bx += block) {
            double sa = 0, sb = 0, vsa = 0, vsb = 0;
            for (int y = by; y < std::min(H, by + block); ++y)
                for (int x = bx; x < std::min(W, bx + block); ++x) {
                    if (kind == "error") {
                        sa += sq(lum3(a.at(x, y)) - lum3(ref.at(x, y))), sb += sq(lum3(b.at(x, y)) - lum3(ref.at(x, y)));
                    } else {
                        sa += lum3(a.at(x, y)), sb += lum3(b.at(x, y)), vsa += lum3(va.at(x, y)), vsb += lum3(vb.at(x, y));
                    }
                }
            errA += sa, errB += sb;
            Vec3 colour(0.03f);  // black in both
            if (sa > 0 && sb > 0) {
                const float stops = kind == "error" ? 2 : 1, t = std::max(-1.0f, std::min(1.0f, float(std::log2(sb / sa)) / stops));
                colour = t >= 0 ? Vec3(1, 1 - t, 1 - t) : Vec3(1 + t, 1 + t, 1);
                // Within the noise: closer than 3 standard errors, or a block so noisy (a few rare
                // splats) that its spread from the passes is no error bar.
                if (kind == "mean" && (std::fabs(sb - sa) < 3 * std::sqrt(vsa + vsb) || vsa > sqr(0.15 * sa) || vsb > sqr(0.15 * sb)))
                    colour = Vec3(0.25f);
            } else if (sa > 0 || sb > 0) {
                colour = sb > 0 ? Vec3(1, 0, 0) : Vec3(0, 0, 1);
            }
            for (int y = by; y < std::min(H, by + block); ++y)
                for (int x = bx; x < std::min(W, bx + block); ++x) r.colours.at(x, y) = colour;
        }
    r.overall = kind == "error" ? errB / std::max(1e-30, errA) : imageMean(b) / std::max(1e-30, imageMean(a));
    return r;
}

inline std::string threeDigits(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", x);
    return text;
}

// Whether the second of a ratio panel's entries is the first with a deliberate mistake (the
// panels are then "right" and "deliberate mistake"), not another method.
inline bool comparesDeliberateMistake(const std::vector<std::unique_ptr<SideBySidePanel>>& panels) {
    for (const char* flag : {"--symmetric-refraction", "--no-adjoint-correction", "--fixed-ray-offset", "--delta-density-one", "--fixed-start",
                             "--no-scramble"})
        if (panels.size() == 2 && panels[1]->label.find(flag) != std::string::npos) return true;
    return false;
}

inline std::vector<unsigned char> sideBySideFrame(std::vector<std::unique_ptr<SideBySidePanel>>& panels, const Image& ref,
                                                  const SideBySideLayout& L, const std::vector<std::string>& title, const std::string& ratioKind) {
    std::vector<unsigned char> canvas(size_t(L.canvasW) * L.canvasH * 3, 24);
    const bool comparesMistake = comparesDeliberateMistake(panels);
    const std::vector<std::string> slides = slidesCaptions(panels);
    auto caption = [&](int tile, int line, const std::string& text) {
        drawLabel(canvas, L.canvasW, L.canvasH, L.tileX(tile), L.tileY(tile) + L.panelH + L.gap / 2 + line * 7 * L.scale, text, L.scale);
    };
    for (size_t i = 0; i < panels.size(); ++i) {
        SideBySidePanel& panel = *panels[i];
        Image mean(L.W, L.H);
        int passes;
        double seconds;
        panelMean(panel, mean, nullptr, passes, seconds);
        blitZoomed(canvas, L.canvasW, toSRGBBytes(mean, panel.cl.exposure), L.W, L.H, L.zoom, L.tileX(int(i)), L.tileY(int(i)));
        const std::string slide = !ratioKind.empty() && comparesMistake ? (i == 0 ? "right" : "deliberate mistake") : slides[i];
        std::string counts = passes > 0 ? std::to_string(passes) + " spp, " + threeDigits(seconds) + " CPU s" : "starting";
        caption(int(i), 0, slide.empty() ? panel.label : slide);
        caption(int(i), 1, slide.empty() ? counts : panel.label + ": " + counts);
        if (ref.width > 0 && passes > 0) caption(int(i), 2, "RMSE " + threeDigits(compareToReference(mean, ref, &panel.scene).rmse));
    }
    std::vector<std::string> lines = title;
    if (!ratioKind.empty() && panels[0]->passes > 0 && panels[1]->passes > 0) {
        RatioPanel r = ratioPanel(panels, ratioKind, ref);
        const int t = int(panels.size());
        blitZoomed(canvas, L.canvasW, toSRGBBytes(r.colours, 0), L.W, L.H, L.zoom, L.tileX(t), L.tileY(t));
        const std::string division = "'" + panels[1]->label + "' / '" + panels[0]->label + "'";
        if (ratioKind == "error") {
            caption(t, 0, "squared error: " + division);
            caption(t, 1, "blue 1/4 - white 1 - red 4");
            lines.push_back("squared error " + division + " = " + threeDigits(r.overall));
        } else {
            caption(t, 0, "mean: " + division);
            caption(t, 1, "blue 1/2 - white 1 - red 2");
            caption(t, 2, "grey: within the noise; dark: black in both");
            lines.push_back(division + " = " + threeDigits(r.overall) + " on average");
        }
    }
    for (size_t k = 0; k < lines.size(); ++k)
        drawLabel(canvas, L.canvasW, L.canvasH, (L.canvasW - labelWidth(lines[k], L.titleScale)) / 2, L.top + L.gap + int(k) * 7 * L.titleScale,
                  lines[k], L.titleScale);
    return canvas;
}

// The panels' own command lines: the scene, the entry's method and options, and every option of
// the whole line but those of the one figure (--out, --live, --title, --ratio-panel) and
// --side-by-side itself.
inline std::vector<std::unique_ptr<SideBySidePanel>> sideBySidePanels(const std::vector<std::string>& args, const ClassroomLine& cl) {
    std::vector<std::string> shared;
    for (size_t i = 0; i < args.size(); ++i) {
        if (args[i] == "--side-by-side" || args[i] == "--out" || args[i] == "--live" || args[i] == "--title" || args[i] == "--ratio-panel") {
            ++i;
            continue;
        }
        if (args[i] != "--overwrite" && args[i] != cl.scenePath) shared.push_back(args[i]);
    }
    std::vector<std::unique_ptr<SideBySidePanel>> panels;
    for (const std::string& entry : cl.sideBySide) {
        auto panel = std::make_unique<SideBySidePanel>();
        std::vector<std::string> line = {cl.scenePath, "--method"};
        std::stringstream words(entry);
        for (std::string w; words >> w;) {
            if (hasExtension(w, "scene") && line.back().rfind("--", 0) != 0) line[0] = w;  // the entry's own scene
            else line.push_back(w);
            panel->label += (panel->label.empty() ? "" : " ") + w;
        }
        if (line.size() == 2) ArgReader::fail("--side-by-side has an empty entry (two commas, or one at an end)");
        line.insert(line.end(), shared.begin(), shared.end());
        try {
            panel->cl = parseCommandLine(line);
        } catch (const InputError& e) {
            throw InputError(std::string(e.what()) + ", in --side-by-side's entry '" + printable(entry) +
                             "' (an option of some methods only goes in their entries)");
        }
        panels.push_back(std::move(panel));
    }
    return panels;
}

// Each entry's scene: the main one (a copy, sharing its BVH), or its own, which must be of the
// same size and goes without a reference. Returns the exit status if one cannot be rendered.
inline int loadPanelScenes(std::vector<std::unique_ptr<SideBySidePanel>>& panels, const ClassroomLine& cl, const Scene& scene,
                           const Image& ref, std::ostream& err) {
    const int W = scene.camera.width, H = scene.camera.height;
    for (auto& panel : panels) {
        panel->scene = scene;
        if (panel->cl.scenePath == cl.scenePath) continue;
        try {
            panel->scene = loadSceneOrGuess(panel->cl.scenePath);
        } catch (const InputError& e) {
            err << e.what() << ", in --side-by-side's entry '" << printable(panel->label) << "'\n";
            return 2;
        }
        if (cl.width > 0) setResolution(panel->scene.camera, cl.width, cl.height);
        if (ref.width > 0) {
            err << "bdpt: --ref is one scene's reference: leave it out when an entry names its own scene (nothing rendered)\n";
            return 2;
        }
        if (panel->scene.camera.width != W || panel->scene.camera.height != H) {
            err << "bdpt: the scenes' images differ in size (" << cl.scenePath << " " << W << "x" << H << ", " << panel->cl.scenePath
                << " " << panel->scene.camera.width << "x" << panel->scene.camera.height
                << "): give them one with --res WxH (nothing rendered)\n";
            return 2;
        }
    }
    double needed = 0;
    for (auto& panel : panels) needed += estimatedBytes(panel->scene, panel->cl.opt, false);
    if (needed + 200e6 > memoryLimitBytes()) {
        err << "bdpt: these " << panels.size() << " renders need about " << std::setprecision(2) << std::fixed << needed / 1e9
            << " GB together, more than this process may use: use a smaller --res (nothing rendered)\n";
        return 1;
    }
    std::set<std::string> warned;  // every scene an entry renders, once
    for (auto& panel : panels)
        if (warned.insert(panel->cl.scenePath).second) warnAboutScene(panel->scene, panel->cl.opt, err);
    return 0;
}

// A panel's render, on its own thread with its share of the cores, adding each pass to the
// panel's running sum for the frames.
inline std::thread startPanel(SideBySidePanel& panel, int threads) {
    panel.scene.conventions = panel.cl.conventions;
    if (!panel.cl.exposureGiven) panel.cl.exposure = panel.scene.exposure;
    panel.cl.opt.threads = threads;
    panel.sum.assign(3 * size_t(panel.scene.camera.width) * panel.scene.camera.height, 0.0);
    panel.sumSquares = panel.sum;
    return std::thread([&panel] {
        auto addPass = [&](const Rendering& r) {
            std::lock_guard<std::mutex> hold(panel.lock);
            for (size_t i = 0; i < r.pass.size(); ++i)
                for (int c = 0; c < 3; ++c) panel.sum[3 * i + c] += r.pass[i][c], panel.sumSquares[3 * i + c] += sqr(r.pass[i][c]);
            panel.passes = r.result.passes;
            panel.seconds = r.result.cpuSeconds;
        };
        bool interrupted = false;
        try {
            panel.result = renderWatched(panel.scene, panel.cl.opt, false, interrupted, addPass);
        } catch (const std::bad_alloc&) {
            panel.outOfMemory = true;
        }
        std::lock_guard<std::mutex> hold(panel.lock);
        panel.done = true;
    });
}

// Each panel's PFM beside the PNG (FILE-1-pt.pfm, ...) and its line of the summary.
inline int writePanels(const std::vector<std::unique_ptr<SideBySidePanel>>& panels, const ClassroomLine& cl, const Image& ref,
                       std::ostream& out, std::ostream& err) {
    const std::string base = replaceExtension(cl.out, "");
    for (size_t i = 0; i < panels.size(); ++i) {
        const SideBySidePanel& panel = *panels[i];
        const std::string pfm = base + "-" + std::to_string(i + 1) + "-" + methodName(panel.cl.opt.method) + ".pfm";
        if (!savePFM(panel.result.image, pfm)) {
            err << "bdpt: cannot write " << pfm << "\n";
            return 1;
        }
        if (cl.quiet) continue;
        char text[160];
        std::snprintf(text, sizeof text, "%zu. %s: %d samples per pixel in %.2f CPU s on %d thread%s, mean %g, ", i + 1, panel.label.c_str(),
                      panel.result.passes, panel.result.cpuSeconds, panel.cl.opt.threads,
                      panel.cl.opt.threads > 1 ? "s" : "",
                      imageMean(panel.result.image));
        out << text << raysPerSample(panel.result) << "; wrote " << pfm;
        if (ref.width > 0) {
            ErrorMetrics m = compareToReference(panel.result.image, ref, &panel.scene);
            std::snprintf(text, sizeof text, "; rmse %.4g (%.4g without the lamp's pixels), bias %+.2f%%", m.rmse, m.rmseWithoutLamp, 100 * m.bias);
            out << text;
        }
        out << "\n";
    }
    return 0;
}

// The figure's title: --title's line, then what is compared: the scene, its size, the budget.
inline std::vector<std::string> sideBySideTitle(const std::vector<std::unique_ptr<SideBySidePanel>>& panels, const ClassroomLine& cl,
                                                const Scene& scene) {
    std::set<std::string> scenes;
    std::set<int> spps;
    for (auto& panel : panels) scenes.insert(fileStem(panel->cl.scenePath)), spps.insert(panel->cl.opt.spp);
    std::string what = scenes.size() == 1 ? *scenes.begin() : std::to_string(scenes.size()) + " scenes";
    what += " (" + std::to_string(scene.camera.width) + "x" + std::to_string(scene.camera.height) + "): ";
    if (cl.opt.seconds > 0) {
        what += "equal CPU time, " + threeDigits(cl.opt.seconds) + " s each on one thread";
    } else if (spps.size() == 1) {  // each panel's own --spp, which an entry may set
        what += std::to_string(*spps.begin()) + (*spps.begin() == 1 ? " sample" : " samples") + " per pixel each";
    } else {
        for (size_t i = 0; i < panels.size(); ++i) what += (i ? ", " : "") + std::to_string(panels[i]->cl.opt.spp);
        what += " samples per pixel";
    }
    std::vector<std::string> lines;
    if (!cl.title.empty()) lines.push_back(cl.title);
    lines.push_back(what);
    return lines;
}

// The figure's layout: room under each image for its widest caption, above them for the title.
inline SideBySideLayout sideBySideLayout(const std::vector<std::unique_ptr<SideBySidePanel>>& panels, const ClassroomLine& cl,
                                         const Scene& scene, const std::vector<std::string>& title) {
    int widest = labelWidth("(b) Unidirectional + next event", 1), widestTitle = 1;
    for (auto& panel : panels)
        widest = std::max({widest, labelWidth(panel->label + ": 999 spp, 99.9 CPU s", 1), labelWidth(slideCaption(panel->label), 1)});
    if (!cl.ratioPanel.empty()) widest = std::max(widest, labelWidth("squared error: '" + panels[1]->label + "' / '" + panels[0]->label + "'", 1));
    for (const std::string& line : title) widestTitle = std::max(widestTitle, labelWidth(line, 1));
    return SideBySideLayout(int(panels.size()) + !cl.ratioPanel.empty(), scene.camera.width, scene.camera.height, widest, widestTitle,
                            int(title.size()) + !cl.ratioPanel.empty());
}

// --ratio-panel's needs, before any work: two entries, and for "error" a reference. Returns the exit status, or 0.
inline int checkRatioPanel(const ClassroomLine& cl, size_t entries, const Image& ref, std::ostream& err) {
    if (!cl.ratioPanel.empty() && entries != 2) {
        err << "bdpt: --ratio-panel divides the second entry by the first: give --side-by-side two entries (nothing rendered)\n";
        return 2;
    }
    if (cl.ratioPanel == "error" && ref.width == 0) {
        err << "bdpt: --ratio-panel error compares each entry's squared error against the reference: give --ref (nothing rendered)\n";
        return 2;
    }
    return 0;
}

// Runs every panel on its threads (one each with --time, else a share of the cores) until all are
// done, rewriting the figure every --live seconds meanwhile.
template <class WriteFrame>
inline void renderPanels(std::vector<std::unique_ptr<SideBySidePanel>>& panels, const ClassroomLine& cl, const WriteFrame& writeFrame) {
    const int n = int(panels.size()), cores = cl.opt.threads > 0 ? cl.opt.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    std::vector<std::thread> running;
    for (auto& panel : panels) running.push_back(startPanel(*panel, cl.opt.seconds > 0 ? 1 : std::max(1, cores / n)));
    auto lastFrame = std::chrono::steady_clock::now();
    for (bool all = false; !all;) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        all = true;
        for (auto& panel : panels) {
            std::lock_guard<std::mutex> hold(panel->lock);
            all = all && panel->done;
        }
        if (!all && cl.liveSeconds > 0 && secondsSince(lastFrame) >= cl.liveSeconds) writeFrame(), lastFrame = std::chrono::steady_clock::now();
    }
    for (std::thread& t : running) t.join();
    for (auto& panel : panels)
        if (panel->outOfMemory) throw std::bad_alloc();
}

inline int runSideBySide(const std::vector<std::string>& args, ClassroomLine& cl, const Scene& scene, const Image& ref, std::ostream& out,
                         std::ostream& err) {
    std::vector<std::unique_ptr<SideBySidePanel>> panels;
    try {
        panels = sideBySidePanels(args, cl);
    } catch (const InputError& e) {
        err << e.what() << "\n";
        return 2;
    }
    if (int status = loadPanelScenes(panels, cl, scene, ref, err)) return status;
    if (int status = checkRatioPanel(cl, panels.size(), ref, err)) return status;
    const std::vector<std::string> title = sideBySideTitle(panels, cl, scene);
    const SideBySideLayout layout = sideBySideLayout(panels, cl, scene, title);
    auto writeFrame = [&] {
        std::snprintf(gFileBeingWritten, sizeof gFileBeingWritten, "%s", tempName(cl.out).c_str());
        bool ok = writePNGBytes(sideBySideFrame(panels, ref, layout, title, cl.ratioPanel), layout.canvasW, layout.canvasH, cl.out);
        gFileBeingWritten[0] = 0;
        return ok;
    };
    if (cl.liveSeconds > 0) writeFrame();  // at once: a viewer opens it, and never shows an older run's image
    renderPanels(panels, cl, writeFrame);
    if (!writeFrame()) {
        err << "bdpt: cannot write " << cl.out << "\n";
        return 1;
    }
    if (int status = writePanels(panels, cl, ref, out, err)) return status;
    if (!cl.quiet && !cl.ratioPanel.empty())
        out << "ratio panel: '" << panels[1]->label << "' / '" << panels[0]->label << "' = " << ratioPanel(panels, cl.ratioPanel, ref).overall
            << (cl.ratioPanel == "error" ? " (of the squared errors)" : " (of the means)") << "\n";
    if (!cl.quiet) out << "wrote " << cl.out << " (" << layout.canvasW << "x" << layout.canvasH << ")\n";
    if (gInterrupts.load() > 0) {
        err << "bdpt: interrupted: wrote the completed samples per pixel of every panel\n";
        return kExitInterrupted;
    }
    return 0;
}
