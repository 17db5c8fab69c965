// classroom/profile.h: --profile's clock: the one hook of the lecture that the classroom fills.
// Included before ../bdpt.cpp (by lecture.h), whose PROFILE_PART it defines; the lecture alone
// leaves the macro empty.
#pragma once
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <ostream>

// --profile: where a sample's time goes, by part of the work. The clock charges the time since its
// last reading to the part running then; a CostScope enters a part and, when it ends, hands the
// clock back to the part it interrupted (tracing inside a merge is tracing). Off, a scope costs a
// test of a flag. --profile renders on one thread, so one clock serves.
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
    uint64_t (*now)() = &timeStampCounter;  // a test gives it a clock of its own, advanced by hand
    void switchTo(Cost next) {
        uint64_t t = now();
        ticks[int(current)] += t - last;
        last = t, current = next;
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

// --profile's line: the render's CPU time per sample, split as the clock's ticks split.
inline void printProfile(const CostClock& clock, double cpuSeconds, double samples, std::ostream& out) {
    double ticks = 0;
    for (uint64_t t : clock.ticks) ticks += double(t);
    const double perSample = 1e6 * cpuSeconds / std::max(1.0, samples), share = 1 / std::max(1.0, ticks);
    const char* names[] = {"shading and sampling", "tracing", "MIS", "merging"};
    char text[128];
    std::snprintf(text, sizeof text, "profile (one thread): %.3g us per sample:", perSample);
    out << text;
    for (Cost part : {Cost::Tracing, Cost::Mis, Cost::Merging, Cost::Other}) {
        double f = double(clock.ticks[int(part)]) * share;
        std::snprintf(text, sizeof text, "%s %s %.3g (%.0f%%)", part == Cost::Tracing ? "" : ",", names[int(part)], f * perSample, 100 * f);
        out << text;
    }
    out << "\n";
}
