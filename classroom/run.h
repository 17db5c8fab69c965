// classroom/run.h: running a render as a class watches it: durations a person reads, the
// progress bar, Ctrl-C, files written whole (and removed by a second Ctrl-C), the log and the live
// image after every pass, and the render loop that calls them.
#pragma once
#include "options.h"
#include "metrics.h"
#include <climits>
#include <csignal>
#include <ctime>
#include <mutex>
#include <sys/resource.h>

// 13 h 20 min, 4 min 05 s, 12.3 s: what a person reads at a glance.
inline std::string duration(double seconds) {
    char text[32];
    long s = long(seconds + 0.5);
    if (seconds >= 3600) std::snprintf(text, sizeof text, "%ld h %02ld min", s / 3600, s / 60 % 60);
    else if (seconds >= 60) std::snprintf(text, sizeof text, "%ld min %02ld s", s / 60, s % 60);
    else std::snprintf(text, sizeof text, "%.1f s", seconds);
    return text;
}

struct ProgressBar {
    std::chrono::steady_clock::time_point last;
    void show(double fraction, int passes, double etaSeconds) {
        auto now = std::chrono::steady_clock::now();
        if (fraction < 1 && now - last < std::chrono::milliseconds(200)) return;
        last = now;
        int width = 30, filled = int(std::min(1.0, fraction) * width);
        std::fprintf(stderr, "\r[%s%s] %3d%%  pass %d  ETA %s   ", std::string(filled, '#').c_str(),
                     std::string(width - filled, '.').c_str(), int(100 * std::min(1.0, fraction)), passes,
                     duration(std::max(0.0, etaSeconds)).c_str());
        if (fraction >= 1) std::fprintf(stderr, "\n");
    }
};

// Ctrl-C: the first interrupt lets the pass in flight finish, then the render stops and the
// completed passes are written as usual (status 130). A second one removes the file being
// written, if any, and exits at once (status 3, "abandoned"); but a second signal within a second
// of the first is the same key press: `timeout -s INT` and some terminals signal the process and
// then its whole group. Only async-signal-safe calls in the handler.
constexpr int kExitInterrupted = 130, kExitAbandoned = 3;
inline std::atomic<int> gInterrupts{0};
inline std::atomic<long long> gFirstInterruptNs{0};
inline char gFileBeingWritten[4096] = {0};
inline void writeToStderr(const char* text) {
    ssize_t written = write(2, text, std::strlen(text));
    (void)written;  // nothing more to do if stderr is gone
}
extern "C" inline void onInterrupt(int) {
    timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    long long now = ts.tv_sec * 1000000000LL + ts.tv_nsec;
    if (gInterrupts.fetch_add(1) == 0) {
        gFirstInterruptNs = now;
        writeToStderr("\nbdpt: interrupted: finishing the pass in flight, then writing the image (Ctrl-C again to abandon it)\n");
        return;
    }
    if (now - gFirstInterruptNs.load() < 1000000000LL) return;
    if (gFileBeingWritten[0]) unlink(gFileBeingWritten);
    writeToStderr("bdpt: abandoned: no image written\n");
    _exit(kExitAbandoned);
}


// The classroom's files, each remembered while it is written, so that a second Ctrl-C removes it.
inline bool savePNG(const Image& img, const std::string& path, float exposure) {
    std::snprintf(gFileBeingWritten, sizeof gFileBeingWritten, "%s", tempName(path).c_str());
    bool ok = writePNG(img, path, exposure);
    gFileBeingWritten[0] = 0;
    return ok;
}
inline bool savePFM(const Image& img, const std::string& path) {
    std::snprintf(gFileBeingWritten, sizeof gFileBeingWritten, "%s", tempName(path).c_str());
    bool ok = writePFM(img, path);
    gFileBeingWritten[0] = 0;
    return ok;
}

// --log and --live, after every pass: the running mean against the reference, with the time spent
// measuring taken out of the clock. The log is flushed after each pass (tail -f follows a run);
// --live rewrites the PNG from the running mean (whole, by rename).
struct PassLog {
    const ClassroomLine& cl;
    const Image& ref;
    std::ofstream log;
    std::vector<double> running;
    std::chrono::steady_clock::time_point lastLive = std::chrono::steady_clock::now();
    PassLog(const ClassroomLine& c, const Scene& scene, const Image& reference)
        : cl(c), ref(reference), running(3 * size_t(scene.camera.width) * scene.camera.height, 0.0) {}
    bool open() {
        log.open(cl.logPath);
        log << "scene,method,options,pass,spp,cpu_seconds,rmse,relmse,mean,bias,firefly,nan_count,rmse_without_lamp\n";
        return bool(log.flush());
    }
    void add(const Rendering& r) {
        const int p = r.result.passes - 1;
        const double seconds = r.result.cpuSeconds;  // the render's own: the log's metrics are not in it
        Image mean(r.scene.camera.width, r.scene.camera.height);
        for (size_t i = 0; i < r.pass.size(); ++i)
            for (int c = 0; c < 3; ++c) mean.pixels[i][c] = float((running[3 * i + c] += r.pass[i][c]) / (p + 1));
        if (cl.liveSeconds > 0 && secondsSince(lastLive) >= cl.liveSeconds) {
            savePNG(mean, cl.out, cl.exposure);  // a failure here shows again at the end
            lastLive = std::chrono::steady_clock::now();
        }
        if (!cl.logPath.empty()) {
            log << fileStem(cl.scenePath) << "," << methodName(cl.opt.method) << "," << optionsLabel(cl.opt) << "," << p + 1 << "," << p + 1
                << "," << seconds << ",";
            if (ref.width > 0) {
                ErrorMetrics m = compareToReference(mean, ref, &r.scene);
                log << m.rmse << "," << m.relMse << "," << m.mean << "," << m.bias << "," << m.firefly << "," << r.result.nonFinite << ","
                    << m.rmseWithoutLamp << "\n";
            } else {
                log << ",," << imageMean(mean) << ",,," << r.result.nonFinite << ",\n";
            }
            log.flush();
        }
    }
};

// The classroom's render loop: the lecture's passes (Rendering), with after each one the pass
// handed to `watch` (the log, the live image, a side-by-side panel), a Ctrl-C honoured between
// passes, and the progress bar drawn by a thread of its own from the rows done in the pass.
// --time counts the render's CPU seconds (the bar reads the process's, as a single render is all it runs).
template <class Watch>
inline RenderResult renderWatched(const Scene& scene, const RenderOptions& opt, bool progressBar, bool& interrupted, const Watch& watch) {
    Rendering r(scene, opt);
    auto processCpuSeconds = [] {
        timespec t{};
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
        return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
    };
    const double cpuStart = processCpuSeconds();
    std::atomic<int> passesDone{0};
    std::atomic<bool> finished{false};
    std::thread bar;
    if (progressBar && isatty(2))
        bar = std::thread([&] {
            ProgressBar shown;
            for (; !finished; std::this_thread::sleep_for(std::chrono::milliseconds(100))) {
                double passes = passesDone + double(r.rowsDone) / scene.camera.height;
                double spent = opt.wallTime ? secondsSince(r.start) : processCpuSeconds() - cpuStart;
                double f = opt.seconds > 0 ? spent / opt.seconds : passes / std::max(1, opt.spp);
                shown.show(std::min(0.999, f), passesDone, secondsSince(r.start) * (1 / std::max(1e-9, f) - 1));
            }
            shown.show(1, passesDone, 0);
        });
    do {
        if (r.result.passes > 0 && gInterrupts.load() > 0) {
            interrupted = true;
            break;
        }
        r.addPass();
        passesDone = r.result.passes;
        watch(r);
    } while (morePasses(r));
    finished = true;
    if (bar.joinable()) bar.join();
    return r.finish();
}
