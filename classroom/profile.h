// classroom/profile.h: --profile's clock: the one hook of the lecture that the classroom fills.
// Included before ../bdpt.cpp (by lecture.h), whose PROFILE_PART it defines; the lecture alone
// leaves the macro empty.
#pragma once
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <ostream>
#include <algorithm>
#include <ctime>
#include <iterator>

// --profile: where a sample's time goes, by part of the work. The clock charges the time since its
// last reading to the part running then; a CostScope enters a part and, when it ends, hands the
// clock back to the part it interrupted (tracing inside a merge is tracing). Off, a scope costs a
// test of a flag. --profile renders on one thread, so one clock serves.
// The time-stamp counter costs a few cycles where a clock call costs tens, but it counts the wall
// clock: a thread preempted by other work hands its sleep to whichever part was running. So the
// split is kept pass by pass (PassSplit), and a pass whose thread did not run the whole of its
// wall time (its CPU clock, which preemption cannot move, fell behind) is left out of it.
enum class Cost { Other, Tracing, Mis, Merging, Count };  // Other: shading, sampling, camera, film
struct CostClock {
    bool on = false;
    Cost current = Cost::Other;
    uint64_t last = 0, ticks[int(Cost::Count)] = {};
    static uint64_t timeStampCounter() {
#if defined(__x86_64__) || defined(__i386__)
        return __builtin_ia32_rdtsc();  // a few cycles where a clock call is tens
#else
        return uint64_t(std::chrono::steady_clock::now().time_since_epoch().count());
#endif
    }
    uint64_t (*now)() = &timeStampCounter;  // a test gives it a clock of its own: advanced by hand, or a count
    void switchTo(Cost next) {
        uint64_t t = now();
        ticks[int(current)] += t - last;
        last = t, current = next;
    }
    void start() {  // on, from zero, keeping whichever clock it reads
        uint64_t (*clock)() = now;
        *this = CostClock();
        now = clock, on = true, last = now();
    }
};
inline CostClock gCostClock;
struct CostScope {
    Cost outer = gCostClock.current;
    explicit CostScope(Cost part) {
        if (gCostClock.on) gCostClock.switchTo(part);
    }
    ~CostScope() {
        if (gCostClock.on) gCostClock.switchTo(outer);
    }
};
#define PROFILE_PART(part) CostScope profiledPart(Cost::part)

// The split over the passes whose thread ran undisturbed: after every pass, its ticks are kept
// if the thread's CPU clock advanced by the pass's whole wall time (within 2% and 0.2 ms), and
// dropped if the thread waited for a core meanwhile. A clock a test gives (a count, a hand) is
// never preempted: every pass is kept.
struct PassSplit {
    uint64_t kept[int(Cost::Count)] = {}, all[int(Cost::Count)] = {};
    int passes = 0, keptPasses = 0;
    uint64_t before[int(Cost::Count)] = {};
    double cpuBefore = 0, wallBefore = 0;
    static double wallSeconds() { return 1e-9 * double(std::chrono::steady_clock::now().time_since_epoch().count()); }
    static double cpuSeconds() {
        timespec t{};
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
        return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
    }
    void beginPass() {
        std::copy(std::begin(gCostClock.ticks), std::end(gCostClock.ticks), before);
        cpuBefore = cpuSeconds(), wallBefore = wallSeconds();
    }
    void endPass() {
        gCostClock.switchTo(gCostClock.current);  // the ticks up to now, to the part running
        const double wall = wallSeconds() - wallBefore, cpu = cpuSeconds() - cpuBefore;
        const bool realClock = gCostClock.now == &CostClock::timeStampCounter;
        const bool undisturbed = !realClock || wall - cpu <= 0.02 * wall + 2e-4;
        ++passes, keptPasses += undisturbed;
        for (int p = 0; p < int(Cost::Count); ++p) {
            all[p] += gCostClock.ticks[p] - before[p];
            if (undisturbed) kept[p] += gCostClock.ticks[p] - before[p];
        }
    }
    const uint64_t* ticks() const { return keptPasses > 0 ? kept : all; }  // if none ran undisturbed, all (and a warning)
};

// --profile's line: the render's CPU time per sample, split as the kept passes' ticks split.
inline void printProfile(const PassSplit& split, double cpuSeconds, double samples, std::ostream& out) {
    const uint64_t* partTicks = split.ticks();
    double ticks = 0;
    for (int p = 0; p < int(Cost::Count); ++p) ticks += double(partTicks[p]);
    const double perSample = 1e6 * cpuSeconds / std::max(1.0, samples), share = 1 / std::max(1.0, ticks);
    const char* names[] = {"shading and sampling", "tracing", "MIS", "merging"};
    char text[160];
    std::snprintf(text, sizeof text, "profile (one thread): %.3g us per sample:", perSample);
    out << text;
    for (Cost part : {Cost::Tracing, Cost::Mis, Cost::Merging, Cost::Other}) {
        double f = double(partTicks[int(part)]) * share;
        std::snprintf(text, sizeof text, "%s %s %.3g (%.0f%%)", part == Cost::Tracing ? "" : ",", names[int(part)], f * perSample, 100 * f);
        out << text;
    }
    if (split.keptPasses < split.passes)
        std::snprintf(text, sizeof text, "; split over the %d of %d passes its thread ran undisturbed%s", split.keptPasses, split.passes,
                      split.keptPasses == 0 ? " (none: other work had the cores; the split is all passes', preemption included)" : "");
    else
        std::snprintf(text, sizeof text, "; split over all %d passes", split.passes);
    out << text << "\n";
}
