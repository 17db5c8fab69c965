// make uneven: the slides' "uneven convergence" of Metropolis sampling, measured. Each method
// renders a scene for the same time (one thread, interleaved seed by seed) for several seeds;
// per region of grid x grid, its relative RMSE against scenes/refs/SCENE.pfm over the seeds,
//     relRMSE(region) = sqrt(mean over seeds and pixels of (x - ref)^2) / mean of ref there;
// its unevenness = the largest region's relRMSE over the median region's (1 would be perfectly
// even). Writes OUT/uneven-SCENE.png: the reference, then each method's map (grey: the region's
// relRMSE on one scale for all, white at the largest), then mlt's (Veach's) relRMSE over bdpt's
// in the colours of --ratio (blue: mlt's error smaller, red: larger, full colour at a factor of 2).
//   build/uneven [--scene NAME] [--seconds S] [--seeds K] [--grid G] [--out DIR]
#include "classroom/workshop/workshop.h"

int main(int argc, char** argv) {
    std::string name = "door", outDir = "build";
    double seconds = 2;
    int seeds = 8, grid = 8;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--scene" && i + 1 < argc) name = argv[++i];
        else if (a == "--seconds" && i + 1 < argc) seconds = std::atof(argv[++i]);
        else if (a == "--seeds" && i + 1 < argc) seeds = std::atoi(argv[++i]);
        else if (a == "--grid" && i + 1 < argc) grid = std::atoi(argv[++i]);
        else if (a == "--out" && i + 1 < argc) outDir = argv[++i];
        else {
            std::fprintf(stderr, "usage: %s [--scene NAME] [--seconds S] [--seeds K] [--grid G] [--out DIR]\n", argv[0]);
            return 2;
        }
    }
    if (seconds <= 0 || seeds < 2 || grid < 2) { std::fprintf(stderr, "uneven: --seconds > 0, --seeds >= 2, --grid >= 2\n"); return 2; }
    Scene scene;
    Image ref;
    if (!sceneWithReference(name, scene, ref)) return 2;
    const int W = ref.width, H = ref.height, R = grid * grid;
    auto region = [&](int x, int y) { return (y * grid / H) * grid + x * grid / W; };
    std::vector<double> refSum(R, 0), pixels(R, 0);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) refSum[region(x, y)] += average(ref.at(x, y)), pixels[region(x, y)] += 1;
    const std::vector<Method> methods = {Method::BDPT, Method::MLT, Method::PSSMLT, Method::MMLT};
    std::vector<std::vector<double>> squared(methods.size(), std::vector<double>(R, 0));
    std::vector<double> passes(methods.size(), 0);
    for (int seed = 1; seed <= seeds; ++seed)
        for (size_t m = 0; m < methods.size(); ++m) {
            RenderOptions o;
            o.method = methods[m];
                    o.threads = 1;
            o.seconds = seconds;
            o.seed = uint64_t(seed);
            if (o.method != Method::PSSMLT) o.metropolis.bootstrap = 100000;  // mlt's and mmlt's default, 1,000,000, would take most of a 2 s run
            RenderResult r = render(scene, o);
            passes[m] += r.passes;
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x)
                    for (int c = 0; c < 3; ++c) squared[m][region(x, y)] += sqr(double(r.image.at(x, y)[c]) - ref.at(x, y)[c]) / 3;
            if (progressShown()) std::fprintf(stderr, "\r%s: seed %d/%d, %zu/%zu   ", name.c_str(), seed, seeds, m + 1, methods.size());
        }
    if (progressShown()) std::fprintf(stderr, "\r%60s\r", "");
    std::vector<std::vector<double>> rel(methods.size(), std::vector<double>(R, 0));
    double largest = 0;
    std::printf("%s, %g s per run on one thread, %d seeds, %d x %d regions: relative RMSE per region\n\n", name.c_str(), seconds, seeds,
                grid, grid);
    std::printf("| method | mutations or samples per pixel | median region | largest region | unevenness (largest / median) |\n|---|---|---|---|---|\n");
    for (size_t m = 0; m < methods.size(); ++m) {
        for (int r = 0; r < R; ++r)
            rel[m][r] = refSum[r] > 0 ? std::sqrt(squared[m][r] / (seeds * pixels[r])) / (refSum[r] / pixels[r]) : 0;
        double med = median(rel[m]), top = *std::max_element(rel[m].begin(), rel[m].end());
        largest = std::max(largest, top);
        std::printf("| %s | %.0f | %.3f | %.3f | %.1f |\n", methodName(methods[m]), passes[m] / seeds, med, top, top / med);
    }
    // The figure: reference | one grey map per method | mlt / bdpt ratio, each tile enlarged
    // (pixels repeated) so that the row is at least 1280 pixels wide, a projector's, with two lines
    // of label above each tile: what it is, and its scale (a map is the relative RMSE per region).
    const int tiles = int(methods.size()) + 2, zoom = std::max(1, (1280 + tiles * W - 1) / (tiles * W));
    const int scale = std::max(2, W * zoom / 80), gap = 2 * scale, strip = 2 * 7 * scale + gap;
    const int canvasW = tiles * W * zoom + (tiles + 1) * gap, canvasH = strip + H * zoom + 2 * gap;
    std::vector<unsigned char> canvas(3 * size_t(canvasW) * canvasH, 40);
    auto place = [&](const std::vector<unsigned char>& tile, int index, const std::string& name, const std::string& legend) {
        int x0 = gap + index * (W * zoom + gap);
        drawLabel(canvas, canvasW, canvasH, x0, gap, name, scale);
        drawLabel(canvas, canvasW, canvasH, x0, gap + 7 * scale, legend, scale);
        for (int y = 0; y < H * zoom; ++y)
            for (int x = 0; x < W * zoom; ++x)
                for (int c = 0; c < 3; ++c)
                    canvas[3 * (size_t(strip + gap + y) * canvasW + x0 + x) + c] = tile[3 * (size_t(y / zoom) * W + x / zoom) + c];
    };
    char white[64];
    std::snprintf(white, sizeof white, "white = relative RMSE %.3g", largest);
    place(toSRGBBytes(ref, scene.exposure), 0, "reference", name);
    for (size_t m = 0; m < methods.size(); ++m) {
        Image map(W, H);
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) map.at(x, y) = Vec3(float(rel[m][region(x, y)] / largest));
        place(toSRGBBytes(map, 0), int(m) + 1, methodName(methods[m]), white);
    }
    Image ratio(W, H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            double b = rel[0][region(x, y)], mlt = rel[1][region(x, y)];
            ratio.at(x, y) = Vec3(b > 0 && mlt > 0 ? float(mlt / b) : std::numeric_limits<float>::quiet_NaN());
        }
    Image colours = ratioColours(ratio);
    place(toSRGBBytes(colours, 0), tiles - 1, "mlt / bdpt", "blue 1/2, red 2");
    std::string png = outDir + "/uneven-" + name + ".png";
    if (!writePNGBytes(canvas, canvasW, canvasH, png)) { std::fprintf(stderr, "uneven: cannot write %s\n", png.c_str()); return 1; }
    std::printf("\nwrote %s: the reference, relative RMSE per region of bdpt, mlt, pssmlt and mmlt (white: %.3f), mlt's over bdpt's\n",
                png.c_str(), largest);
    return 0;
}
