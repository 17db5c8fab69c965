// make efficiency: what each method is worth where the slides say bidirectional methods pay off
// (cornell-glass, glass-box, indirect), where they should not (cornell's direct light), and
// sds-ior1, whose light reaches the camera only along L S D S E and longer: only vcm's merges
// make those paths, and the reference is exact (the room without the balls, by nee).
// Every method renders each scene at the references' resolution with the same samples per pixel,
// on one thread, for several seeds, interleaved (seed by seed, method by method) so that a noisy
// machine slows them alike. Per run: CPU seconds of the rendering thread and the MSE against
// scenes/refs/SCENE.pfm, leaving out the lamp seen directly and its neighbours (nearLamp in
// bdpt.cpp: their noise is the pixel filter's, the same for every camera-path method).
// The table gives medians over the seeds, the efficiency 1/(MSE x CPU-s) relative to nee --mis,
// and the share of the squared error in the pixels that see a mirror or glass (seesSpecular).
//   build/efficiency [--spp N] [--seeds K] [--scenes a,b,...] [--alternatives] [--only TEXT] [--metropolis] [--mutations]
// --alternatives adds the Russian roulette variants (the measurements behind the choice in
// bdpt's banner); --only keeps the methods whose label contains TEXT, or any of a comma-separated
// list (and nee --mis, the baseline): --only "pt,nee,bdpt" gives both samplers of those.
#include "bench.h"

struct Variant {
    std::string label;
    RenderOptions opt;
};

static RenderOptions with(Method m, void (*change)(RenderOptions&) = nullptr) {
    RenderOptions o;
    o.method = m;
    o.threads = 1;
    if (change) change(o);
    return o;
}

static std::vector<Variant> variants(bool alternatives) {
    std::vector<Variant> v = {
        {"pt", with(Method::PT)},
        {"pt --sampler random", with(Method::PT, [](RenderOptions& o) { o.sampler = Sampler::Random; })},
        {"nee", with(Method::NEE)},
        {"nee --sampler random", with(Method::NEE, [](RenderOptions& o) { o.sampler = Sampler::Random; })},
        {"nee --mis", with(Method::NEE, [](RenderOptions& o) { o.mis = true; })},
        {"nee --mis --sampler random", with(Method::NEE, [](RenderOptions& o) { o.mis = true, o.sampler = Sampler::Random; })},
        {"lt", with(Method::LT)},
        {"ir", with(Method::IR)},
        {"bdpt", with(Method::BDPT)},
        {"bdpt --sampler random", with(Method::BDPT, [](RenderOptions& o) { o.sampler = Sampler::Random; })},
        {"bdpt --heuristic power", with(Method::BDPT, [](RenderOptions& o) { o.heuristic = Heuristic::Power; })},
        {"bdpt --heuristic max", with(Method::BDPT, [](RenderOptions& o) { o.heuristic = Heuristic::Max; })},
        {"bdpt --heuristic uniform", with(Method::BDPT, [](RenderOptions& o) { o.heuristic = Heuristic::Uniform; })},
        {"vcm", with(Method::VCM)},
        {"mlt", with(Method::MLT)},
        {"pssmlt", with(Method::PSSMLT)},
        {"mmlt", with(Method::MMLT)},
    };
    if (alternatives) {
        v.push_back({"bdpt --roulette throughput", with(Method::BDPT, [](RenderOptions& o) { o.roulette = Roulette::Throughput; })});
        v.push_back({"bdpt --roulette albedo", with(Method::BDPT, [](RenderOptions& o) { o.roulette = Roulette::Albedo; })});
        v.push_back({"bdpt --roulette off --maxdepth 9", with(Method::BDPT, [](RenderOptions& o) { o.roulette = Roulette::Off; o.maxDepth = 9; })});
        v.push_back({"lt --roulette throughput", with(Method::LT, [](RenderOptions& o) { o.roulette = Roulette::Throughput; })});
        v.push_back({"lt --roulette albedo", with(Method::LT, [](RenderOptions& o) { o.roulette = Roulette::Albedo; })});
        v.push_back({"ir --roulette throughput", with(Method::IR, [](RenderOptions& o) { o.roulette = Roulette::Throughput; })});
        v.push_back({"ir --roulette albedo", with(Method::IR, [](RenderOptions& o) { o.roulette = Roulette::Albedo; })});
    }
    return v;
}

static double maskedMse(const Image& img, const Image& ref, const Scene& scene) {  // without the lamp's pixels (lampPixels)
    double rmse = compareToReference(img, ref, &scene).rmseWithoutLamp;
    return rmse * rmse;
}

// The pixels whose central camera ray first meets a mirror or glass. What they show arrives
// along ... S E, which no connection can end (the camera cannot connect through a specular
// vertex): there only s = 0 and, for vcm, merges help (panel (f)'s SDS limit), so their share
// of a method's squared error says how much of it the transport could not reach otherwise.
static std::vector<bool> seesSpecular(const Scene& scene) {
    const Camera& cam = scene.camera;
    std::vector<bool> mask(size_t(cam.width) * cam.height);
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            Hit hit = intersect(scene, cameraRay(cam, x + 0.5f, y + 0.5f));
            mask[size_t(y) * cam.width + x] = hit.found() && isSpecular(scene.materials[scene.shapes[hit.shape].material]);
        }
    return mask;
}

static double specularShare(const Image& img, const Image& ref, const std::vector<bool>& mask, const Scene& scene) {
    double inside = 0, all = 0;
    const std::vector<char> lamp = lampPixels(ref, &scene);  // the pixels maskedMse leaves out
    for (int y = 0; y < ref.height; ++y)
        for (int x = 0; x < ref.width; ++x) {
            if (lamp[size_t(y) * ref.width + x]) continue;
            double e = 0;
            for (int c = 0; c < 3; ++c) e += sqr(img.at(x, y)[c] - ref.at(x, y)[c]);
            all += e;
            if (mask[size_t(y) * ref.width + x]) inside += e;
        }
    return all > 0 ? inside / all : 0;
}

// --metropolis: the Markov chains where the slides place them (the showcase, door-hidden, whose
// camera sees no path of fewer than three segments) and where they should lose (cornell), against
// bdpt, with the variants that chain short paths too; 8 seeds at least (a chain's error varies
// from seed to seed far more than an independent sampler's), at 64x64 with 1,024 and at 128x128
// with 256 mutations (samples) per pixel. A reference of higher resolution is averaged down.
static Image downsampled(const Image& ref, int width, int height) {
    const int f = ref.width / width;
    Image out(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            Vec3 s(0);
            for (int j = 0; j < f; ++j)
                for (int i = 0; i < f; ++i) s += ref.at(x * f + i, y * f + j);
            out.at(x, y) = s / float(f * f);
        }
    return out;
}

static bool selected(const std::string& label, const std::string& only) {
    std::stringstream list(only);
    for (std::string item; std::getline(list, item, ',');)
        if (label.find(item) != std::string::npos) return true;
    return only.empty();
}

static int metropolis(int seeds, const std::vector<std::string>& scenes, const std::string& only) {
    std::vector<Variant> runs = {
        {"bdpt", with(Method::BDPT)},
        {"mlt", with(Method::MLT)},
        {"pssmlt", with(Method::PSSMLT)},
        {"mmlt", with(Method::MMLT)},
        {"pssmlt --chain-short-paths", with(Method::PSSMLT, [](RenderOptions& o) { o.metropolis.chainShortPaths = true; })},
        {"mmlt --chain-short-paths", with(Method::MMLT, [](RenderOptions& o) { o.metropolis.chainShortPaths = true; })},
    };
    if (!only.empty())  // bdpt, the yardstick, and the variants whose label contains `only`
        runs.erase(std::remove_if(runs.begin() + 1, runs.end(), [&](const Variant& v) { return !selected(v.label, only); }),
                   runs.end());
    struct Size { int width, spp; };
    std::printf("Equal samples (mutations) per pixel, %d seeds, one thread; medians of MSE and CPU seconds over the seeds; "
                "efficiency 1/(MSE x CPU-s) against bdpt's; the lamp's pixels left out.\n\n", seeds);
    std::printf("| scene | size | method | MSE | CPU-s | efficiency vs bdpt | mean vs reference |\n|---|---|---|---|---|---|---|\n");
    for (const std::string& name : scenes) {
        Scene scene;
        Image full;
        if (!sceneWithReference(name, scene, full)) return 2;
        for (Size size : {Size{64, 1024}, Size{128, 256}}) {
            if (full.width < size.width || full.width % size.width) continue;
            setResolution(scene.camera, size.width, size.width);
            Image ref = downsampled(full, size.width, size.width);
            std::vector<std::vector<double>> mse(runs.size()), cpu(runs.size()), mean(runs.size());
            size_t variants = runs.size();  // the short paths' lesson once, at 64x64
            if (size.width != 64)
                while (variants > 1 && runs[variants - 1].label.find("--chain-short-paths") != std::string::npos) --variants;
            for (int seed = 1; seed <= seeds; ++seed)
                for (size_t v = 0; v < variants; ++v) {
                    RenderOptions o = runs[v].opt;
                    o.spp = size.spp;
                    o.seed = uint64_t(seed);
                    double c0 = threadCpuSeconds();
                    RenderResult r = render(scene, o);
                    cpu[v].push_back(threadCpuSeconds() - c0);
                    mse[v].push_back(maskedMse(r.image, ref, scene));
                    mean[v].push_back(imageMean(r.image));
                    if (progressShown()) std::fprintf(stderr, "\r%s %dx%d: seed %d/%d, %zu/%zu   ", name.c_str(), size.width, size.width, seed, seeds, v + 1, variants);
                }
            if (progressShown()) std::fprintf(stderr, "\r%60s\r", "");
            double base = 1 / (median(mse[0]) * median(cpu[0])), refMean = imageMean(ref);
            for (size_t v = 0; v < variants; ++v) {
                double m = median(mse[v]), c = median(cpu[v]), average = 0;
                for (double x : mean[v]) average += x / mean[v].size();
                std::printf("| %s | %dx%d, %d | %s | %.3g | %.2f | %.2fx | %+.1f%% |\n", name.c_str(), size.width, size.width, size.spp,
                            runs[v].label.c_str(), m, c, 1 / (m * c) / base, 100 * (average / refMean - 1));
            }
            std::fflush(stdout);
        }
    }
    return 0;
}

// --mutations: Veach's table of mlt's mutations per scene, at the references' resolution: from the
// bootstrap's 1,024 starts, 256 proposals per chain, each mutation's share of the proposals, its
// acceptance, the mean distance on the film its accepted proposals move the path (pixels,
// weighted by the acceptance a) and its time per proposal (CPU of this thread, measured around each
// call); then mutations per CPU-second of whole mlt and pssmlt renders (64 per pixel, bootstrap in),
// and how many splats a mutation leaves on the film: one path's for mlt, a whole bdpt sample's
// strategies for pssmlt (a proposal's and, when it is left, the current state's).
static int mutationTable(const std::vector<std::string>& scenes) {
    const char* names[4] = {"bidirectional", "lens", "caustic", "multi-chain"};
    std::printf("| scene | mutation | share of proposals | accepted | mean move of the accepted (pixels) | us per proposal |\n"
                "|---|---|---|---|---|---|\n");
    std::vector<std::string> rates;
    for (const std::string& name : scenes) {
        Scene scene;
        Image ref;
        if (!sceneWithReference(name, scene, ref)) return 2;
        RenderOptions o = with(Method::MLT);
        MetropolisPass mp;
        startPathChains(scene, o, 1, mp);
        const SampleOptions walk = chainOptions(o);
        const LengthRange lengths{shortestChainPath(o), o.maxDepth + 1};
        double proposed[4] = {}, accepted[4] = {}, moved[4] = {}, seconds[4] = {}, all = 0;
        const int W = scene.camera.width;
        for (PathChain& chain : mp.paths) {
            if (!(chain.current.f > 0)) continue;
            for (int i = 0; i < 256; ++i) {
                double t0 = threadCpuSeconds();
                chain.proposal.mutation = 0;
                double a = mutate(scene, walk, lengths, chain.current, chain.rng, chain.proposal);
                int m = mutationIndex(chain.proposal.mutation);
                seconds[m] += threadCpuSeconds() - t0;
                ++proposed[m], ++all;
                if (a > 0) {
                    int p = chain.current.pixel, q = chain.proposal.pixel;
                    accepted[m] += a;
                    moved[m] += a * std::hypot(double(p % W - q % W), double(p / W - q / W));
                }
                if (chain.rng.uniform() < a) std::swap(chain.current, chain.proposal);
            }
        }
        for (int m = 0; m < 4; ++m)
            if (proposed[m] > 0)
                std::printf("| %s | %s | %.0f%% | %.1f%% | %.2f | %.2f |\n", name.c_str(), names[m], 100 * proposed[m] / all,
                            100 * accepted[m] / proposed[m], accepted[m] > 0 ? moved[m] / accepted[m] : 0.0, 1e6 * seconds[m] / proposed[m]);
        char line[200];
        double rate[2];
        for (Method method : {Method::MLT, Method::PSSMLT}) {
            RenderOptions r = with(method);
            r.spp = 64;
            double c0 = threadCpuSeconds();
            render(scene, r);
            rate[method == Method::PSSMLT] = 64.0 * ref.width * ref.height / (threadCpuSeconds() - c0);
        }
        double splats[2];  // splats per mutation over 4 passes: what one mutation brings to the image
        for (Method method : {Method::MLT, Method::PSSMLT}) {
            RenderOptions r = with(method);
            MetropolisPass pass;
            double count = 0;
            for (int k = 0; k < 4; ++k) {
                if (method == Method::MLT) tracePathPass(scene, r, k, 1, pass);
                else tracePrimarySamplePass(scene, r, k, 1, pass);
                for (const std::vector<Splat>& c : pass.chainSplats) count += double(c.size());
            }
            splats[method == Method::PSSMLT] = count / (4.0 * ref.width * ref.height);
        }
        std::snprintf(line, sizeof line, "| %s | %.0f | %.0f | %.2fx | %.2f | %.2f |", name.c_str(), rate[0], rate[1], rate[0] / rate[1],
                      splats[0], splats[1]);
        rates.push_back(line);
        std::fflush(stdout);
    }
    std::printf("\nMutations per CPU-second of whole renders (64 per pixel, one thread, the bootstrap and the bdpt sample of the short paths included):\n\n"
                "| scene | mlt | pssmlt | mlt / pssmlt | mlt's splats per mutation | pssmlt's |\n|---|---|---|---|---|---|\n");
    for (const std::string& line : rates) std::printf("%s\n", line.c_str());
    return 0;
}

int main(int argc, char** argv) {
    int spp = 256, seeds = 4;
    bool alternatives = false, metropolisRows = false, mutationRows = false;
    std::string only;
    std::vector<std::string> scenes = {"cornell", "cornell-glass", "indirect", "glass-box", "sds-ior1", "door"};
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--spp" && i + 1 < argc) spp = std::atoi(argv[++i]);
        else if (a == "--seeds" && i + 1 < argc) seeds = std::atoi(argv[++i]);
        else if (a == "--alternatives") alternatives = true;
        else if (a == "--metropolis") metropolisRows = true;
        else if (a == "--mutations") mutationRows = true;
        else if (a == "--only" && i + 1 < argc) only = argv[++i];
        else if (a == "--scenes" && i + 1 < argc) {
            scenes.clear();
            std::stringstream list(argv[++i]);
            for (std::string s; std::getline(list, s, ',');) scenes.push_back(s);
        } else {
            std::fprintf(stderr, "usage: %s [--spp N] [--seeds K] [--scenes a,b,...] [--alternatives] [--only TEXT] [--metropolis] [--mutations]\n", argv[0]);
            return 2;
        }
    }
    if (spp < 1 || seeds < 1) { std::fprintf(stderr, "efficiency: --spp and --seeds must be at least 1\n"); return 2; }
    if (metropolisRows) return metropolis(seeds, scenes, only);
    if (mutationRows) return mutationTable(scenes);
    std::vector<Variant> runs;
    for (const Variant& v : variants(alternatives))
        if (selected(v.label, only) || v.label == "nee --mis") runs.push_back(v);
    std::printf("Equal samples (%d per pixel), %d seeds, one thread; medians over the seeds.\n\n", spp, seeds);
    std::printf("| scene | method | MSE | CPU-s | rays/sample | efficiency vs nee --mis | MSE share seen via mirror or glass |\n"
                "|---|---|---|---|---|---|---|\n");
    for (const std::string& name : scenes) {
        Scene scene;
        Image ref;
        if (!sceneWithReference(name, scene, ref)) return 2;
        std::vector<std::vector<double>> mse(runs.size()), cpu(runs.size()), rays(runs.size()), share(runs.size());
        std::vector<bool> specularPixels = seesSpecular(scene);
        for (int seed = 1; seed <= seeds; ++seed)
            for (size_t v = 0; v < runs.size(); ++v) {
                RenderOptions o = runs[v].opt;
                o.spp = spp;
                o.seed = uint64_t(seed);
                double c0 = threadCpuSeconds();
                RenderResult r = render(scene, o);
                cpu[v].push_back(threadCpuSeconds() - c0);
                mse[v].push_back(maskedMse(r.image, ref, scene));
                share[v].push_back(specularShare(r.image, ref, specularPixels, scene));
                rays[v].push_back(double(r.rays.closest + r.rays.shadow) / (double(r.passes) * ref.width * ref.height));
                if (progressShown()) std::fprintf(stderr, "\r%s: seed %d/%d, %zu/%zu   ", name.c_str(), seed, seeds, v + 1, runs.size());
            }
        if (progressShown()) std::fprintf(stderr, "\r%60s\r", "");
        double baseline = 0;
        for (size_t v = 0; v < runs.size(); ++v)
            if (runs[v].label == "nee --mis") baseline = 1 / (median(mse[v]) * median(cpu[v]));
        for (size_t v = 0; v < runs.size(); ++v) {
            double m = median(mse[v]), c = median(cpu[v]);
            std::printf("| %s | %s | %.3g | %.3f | %.2f | %.2fx | %.0f%% |\n", name.c_str(), runs[v].label.c_str(), m, c, median(rays[v]),
                        1 / (m * c) / baseline, 100 * median(share[v]));
        }
        std::fflush(stdout);
    }
    return 0;
}
