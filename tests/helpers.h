// Shared by the test files: each is its own program that includes the renderer, the lecture's
// bdpt.cpp with the classroom's tools around it (classroom/classroom.cpp), without their mains;
// lecture_test.h brings doctest and what the lecture's own tests share.
#pragma once
#define BDPT_NO_MAIN
#include "classroom/classroom.cpp"
#ifdef BDPT_STB_HEADER  // make STB_DIR=FOLDER: the tests need stb_image.h there too
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>
#else
#include <stb/stb_image.h>  // reading back what the renderer wrote (libstb-dev holds its code too)
#endif
#define BDPT_TEST_PROGRAM_IS_BDPT
#include "lecture_test.h"
#include <tuple>
#include <sys/stat.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <signal.h>

// A BSDF's value alone, f |cos wi| (evalBsdf without its densities), and the density with which
// sampleBsdf picks wi given wo (0 for delta lobes).
inline Vec3 evalBsdfCos(const Scene& scene, const SurfacePoint& sp, Vec3 wo, Vec3 wi, Transport mode) {
    float pdf, pdfReverse;
    return evalBsdf(scene, sp, wo, wi, mode, pdf, pdfReverse);
}
inline float pdfBsdf(const Scene& scene, const SurfacePoint& sp, Vec3 wo, Vec3 wi) {
    float pdf, pdfReverse;
    evalBsdf(scene, sp, wo, wi, Transport::Radiance, pdf, pdfReverse);
    return pdf;
}
inline float standardNormal(Rng& rng) {
    float a, b;
    standardNormals(rng, a, b);
    return a;
}

// A render whose passes fn(rendering) sees one by one, rendering.pass holding the pass's image.
template <class Fn>
inline RenderResult renderEachPass(const Scene& scene, const RenderOptions& opt, const Fn& fn) {
    bool interrupted = false;
    return renderWatched(scene, opt, false, interrupted, fn);
}


// Pixel by pixel over images of independent seeds: the sample variance of a pixel's value (its
// squared error, where the estimator is unbiased), summed over `pixels`, and their mean value.
struct SpreadOverSeeds {
    double varianceSum = 0, mean = 0;
};
inline SpreadOverSeeds spreadOverSeeds(const std::vector<Image>& images, const std::vector<std::pair<int, int>>& pixels) {
    SpreadOverSeeds s;
    const double n = double(images.size());
    for (auto [x, y] : pixels) {
        double m = 0, v = 0;
        for (const Image& im : images) m += average(im.at(x, y)) / n;
        for (const Image& im : images) v += sqr(float(average(im.at(x, y)) - m)) / (n - 1);
        s.varianceSum += v;
        s.mean += m / double(pixels.size());
    }
    return s;
}

struct RegionEstimate {
    std::vector<double> mean, stdError;  // per region; the last entry is the whole image
};

// Region means over seeds (per region, one value per seed), with standard errors from their spread.
inline RegionEstimate regionsOverSeeds(const std::vector<std::vector<double>>& perSeed) {
    RegionEstimate e;
    for (const auto& v : perSeed) {
        double m = 0, q = 0;
        for (double x : v) m += x;
        m /= v.size();
        for (double x : v) q += sqr(x - m);
        e.mean.push_back(m);
        e.stdError.push_back(std::sqrt(q / (v.size() - 1) / v.size()));
    }
    return e;
}

// Mean of each of grid x grid image regions (all channels), per pass: passes are independent,
// so the spread of a region's pass means gives an honest standard error, even for light
// tracing, whose one light path lands in many pixels of a pass.
inline RegionEstimate renderRegions(const Scene& scene, RenderOptions opt, int grid, RenderResult* out = nullptr) {
    const int W = scene.camera.width, H = scene.camera.height, R = grid * grid + 1;
    std::vector<std::vector<double>> samples(R);
    auto addPass = [&](const Rendering& rendering) {
        const std::vector<Vec3>& pass = rendering.pass;
        std::vector<double> s(R, 0.0);
        std::vector<int> n(R, 0);
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                int r = (y * grid / H) * grid + x * grid / W;
                double v = average(pass[size_t(y) * W + x]);
                s[r] += v; ++n[r];
                s[R - 1] += v; ++n[R - 1];
            }
        for (int r = 0; r < R; ++r) samples[r].push_back(s[r] / n[r]);
    };
    RenderResult result = renderEachPass(scene, opt, addPass);
    if (out) *out = std::move(result);
    return regionsOverSeeds(samples);
}

// Region means (grid x grid, all channels) of `seeds` independent renders, with their standard
// errors from the spread over seeds.
inline RegionEstimate overSeeds(const Scene& scene, RenderOptions opt, int grid, int seeds) {
    const int W = scene.camera.width, H = scene.camera.height, R = grid * grid;
    std::vector<std::vector<double>> perSeed(R);
    for (int s = 0; s < seeds; ++s) {
        opt.seed = 1000 + s;
        Image img = render(scene, opt).image;
        std::vector<double> sum(R, 0);
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) sum[(y * grid / H) * grid + x * grid / W] += average(img.at(x, y));
        for (int r = 0; r < R; ++r) perSeed[r].push_back(sum[r] / (double(W) * H / R));
    }
    return regionsOverSeeds(perSeed);
}

// A committed reference (scenes/refs/NAME.pfm, or tests/refs/NAME.pfm: make test-refs), each
// pixel the average of factor x factor of the file's: a pixel's value is the mean over its area
// (samples uniform in the pixel), so a 64x64 reference gives the 16x16 image exactly.
inline Image referenceImage(const std::string& file, int factor = 1) {
    Image ref;
    REQUIRE(readPFM(file, ref));
    REQUIRE(ref.width % factor == 0);
    REQUIRE(ref.height % factor == 0);
    Image out(ref.width / factor, ref.height / factor);
    for (int y = 0; y < ref.height; ++y)
        for (int x = 0; x < ref.width; ++x) out.at(x / factor, y / factor) += ref.at(x, y) / float(factor * factor);
    return out;
}

inline RegionEstimate referenceRegions(const std::string& name, int grid) {
    Image ref;
    REQUIRE(readPFM("scenes/refs/" + name + ".pfm", ref));
    RegionEstimate e;
    std::vector<double> sum(grid * grid, 0);
    for (int y = 0; y < ref.height; ++y)
        for (int x = 0; x < ref.width; ++x) sum[(y * grid / ref.height) * grid + x * grid / ref.width] += average(ref.at(x, y));
    for (double s : sum) e.mean.push_back(s / (double(ref.width) * ref.height / (grid * grid))), e.stdError.push_back(0);
    return e;
}

// Sum over regions of z^2, z = (estimate - reference) / its standard error: about the number of
// regions when the estimate is unbiased (the references' own noise is far below these errors).
inline double chiSquare(const RegionEstimate& e, const RegionEstimate& ref) {
    double c = 0;
    for (size_t r = 0; r < e.mean.size(); ++r) c += sqr((e.mean[r] - ref.mean[r]) / std::max(1e-12, e.stdError[r]));
    return c;
}

// The largest |difference| / standard error over the regions of two independent estimates.
inline double maxZ(const RegionEstimate& a, const RegionEstimate& b) {
    double z = 0;
    for (size_t r = 0; r < a.mean.size(); ++r)
        z = std::max(z, std::fabs(a.mean[r] - b.mean[r]) / std::sqrt(sqr(a.stdError[r]) + sqr(b.stdError[r])));
    return z;
}

inline bool fileExists(const std::string& path) {
    struct stat st;
    return stat(path.c_str(), &st) == 0;
}

inline std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// The tests' files go into build/tmp/, which make test empties before and removes after them.
inline const bool kTempFolderMade = (mkdir("build", 0777), mkdir("build/tmp", 0777), true);

inline std::string writeTempFile(const std::string& name, const std::string& text) {
    std::string path = "build/tmp/" + name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

// A scene of one 2x2 quad in the z = 0 plane with material m, to query a BSDF in isolation at
// surfaceAtOrigin(), whose shading normal may differ from the geometric one.
inline Scene singleQuadScene(Material m) {
    Scene s;
    s.materials.push_back(m);
    Shape q;
    q.type = Shape::Quad;
    q.p = Vec3(-1, -1, 0);
    q.u = Vec3(2, 0, 0);
    q.v = Vec3(0, 2, 0);
    q.normal = Vec3(0, 0, 1);
    q.area = 4;
    s.shapes.push_back(q);
    return s;
}
inline SurfacePoint surfaceAtOrigin(Vec3 ns = Vec3(0, 0, 1)) {
    SurfacePoint sp;
    sp.ng = Vec3(0, 0, 1);
    sp.ns = ns;
    sp.shape = 0;
    return sp;
}

// Renders twice, with 1 and with 2 threads: are the two images the same bit for bit?
inline bool sameWithOneAndTwoThreads(const Scene& scene, RenderOptions o) {
    o.threads = 1;
    RenderResult a = render(scene, o);
    o.threads = 2;
    RenderResult b = render(scene, o);
    return std::memcmp(a.image.pixels.data(), b.image.pixels.data(), a.image.pixels.size() * sizeof(Vec3)) == 0;
}

// A material for BSDF tests: parameter is the glossy exponent or the glass ior.
inline Material makeMaterial(Material::Type type, float albedo, float parameter = 0) {
    Material m;
    m.type = type;
    m.albedo = Vec3(albedo);
    if (type == Material::Glossy) m.exponent = parameter;
    if (type == Material::Glass) m.ior = parameter;
    return m;
}

// No test races the wall clock: a test of a running program waits for an event it can see (a file
// written, a line printed, a pass logged), with a generous limit that only guards against a hang,
// so that the suite passes as well on a machine whose cores are busy with other work.
constexpr double kHangGuardSeconds = 600;
// Waits until ready() holds, looking every 10 ms; false if it never did within the hang guard.
template <class Ready>
inline bool waitFor(const Ready& ready, double guardSeconds = kHangGuardSeconds) {
    for (int i = 0; i < int(guardSeconds * 100); ++i) {
        if (ready()) return true;
        usleep(10000);
    }
    return ready();
}
// A program started in the background by `bash -c`, in a process group of its own, its stdout
// and stderr into one file; stop() signals the group and returns the exit status (-1: killed).
struct BackgroundRun {
    pid_t pid = -1;
    std::string outputFile;
    std::string output() const { return readFile(outputFile); }
    bool running() const { return waitpid(pid, nullptr, WNOHANG) == 0; }
    int stop(int signal) {
        kill(-pid, signal);
        return wait();
    }
    int wait() {
        int status = 0;
        waitpid(pid, &status, 0);
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }
};
inline BackgroundRun startInBackground(const std::string& command, const std::string& outputFile) {
    std::remove(outputFile.c_str());
    BackgroundRun run{fork(), outputFile};
    if (run.pid == 0) {
        setpgid(0, 0);
        int out = open(outputFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (out >= 0) dup2(out, 1), dup2(out, 2);
        execl("/bin/bash", "bash", "-c", ("exec " + command).c_str(), (char*)nullptr);
        _exit(127);
    }
    setpgid(run.pid, run.pid);  // whichever of the two runs first
    return run;
}
// How many lines of a --log file are a pass of the given scene and method ("cornell,bdpt,").
inline int loggedPasses(const std::string& logFile, const std::string& sceneAndMethod) {
    std::istringstream log(readFile(logFile));
    int rows = 0;
    for (std::string line; std::getline(log, line);) rows += line.rfind(sceneAndMethod + ",", 0) == 0;
    return rows;
}
// CPU seconds this process (RUSAGE_SELF) or its finished children have used, as the kernel counts
// them: a budget that a busy machine does not change, unlike the wall clock's.
inline double cpuSeconds(int who) {
    rusage u{};
    getrusage(who, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}
inline double cpuSecondsWithChildren() { return cpuSeconds(RUSAGE_SELF) + cpuSeconds(RUSAGE_CHILDREN); }

// The program a test runs as ./bdpt, its main and its signal handler: this test program itself
// (--as-bdpt: lecture_test.h), so that make test compiles the renderer once for its tests. Under
// the sanitizers (make test-sanitize) the real ./bdpt, which that target builds: a sanitized
// program cannot run under a tests' `ulimit -v`.
inline std::string bdptProgram() {
#if defined(__SANITIZE_ADDRESS__)
    return "./bdpt";
#else
    static const std::string self = [] {
        char path[4096];
        ssize_t n = readlink("/proc/self/exe", path, sizeof path - 1);
        return n > 0 ? std::string(path, size_t(n)) + " --as-bdpt" : std::string("./bdpt");
    }();
    return self;
#endif
}

// Runs ./bdpt (the real program, its main and signal handler) with args, its stderr into
// build/tmp/NAME.err; sends SIGINT once `ready` holds (an event: a pass logged, a line printed)
// and, with secondAfter > 0, once more when the first press has been answered ("bdpt:
// interrupted:" on stderr) and at least secondAfter seconds have passed (a second press within a
// second is the same press, so the wait has a floor, not a ceiling). Each wait says whether it saw
// its event: a test checks that it did, or its second press may have come before the first was
// answered, or its first before the render ran.
struct InterruptedRun {
    int status;
    std::string err;
    bool readySeen = false, firstAnswered = false;
};
template <class Ready>
inline InterruptedRun interruptRun(const std::vector<std::string>& args, const std::string& name, const Ready& ready, double secondAfter) {
    std::string command = bdptProgram();
    for (const std::string& a : args) command += " '" + a + "'";
    const std::string errFile = "build/tmp/" + name + ".err";
    std::remove(errFile.c_str());  // an earlier run's would be `ready` before this one starts
    BackgroundRun run = startInBackground(command + " 2>" + errFile + " >/dev/null", "build/tmp/" + name + ".out");
    InterruptedRun r{0, "", waitFor(ready), false};
    kill(run.pid, SIGINT);
    r.firstAnswered = waitFor([&] { return readFile(errFile).find("bdpt: interrupted:") != std::string::npos || !run.running(); }) &&
                      readFile(errFile).find("bdpt: interrupted:") != std::string::npos;
    if (r.readySeen && r.firstAnswered && secondAfter > 0) {
        usleep(useconds_t(secondAfter * 1e6));
        kill(run.pid, SIGINT);
    }
    r.status = run.wait();
    r.err = readFile(errFile);
    return r;
}

