// classroom/workshop/workshop.h: what the figure workshop's programs share (estimators.cpp,
// uneven.cpp, worked_path.cpp) and the benchmarks of tests/ too: the renderer with the classroom's
// tools, without its main; a harness's progress line; a scene at its reference's size; a median.
#pragma once
#ifndef BDPT_NO_MAIN  // a test program may have included the renderer already
#define BDPT_NO_MAIN
#include "classroom/classroom.cpp"
#endif

// A long harness's progress: redrawn in place on a terminal, left out of a log file (where
// carriage returns would pile up on one line).
inline bool progressShown() {
    static const bool terminal = isatty(2);
    return terminal;
}

// scenes/NAME.scene at the resolution of its reference scenes/refs/NAME.pfm (make efficiency,
// make uneven); false, with the reason on stderr, if either cannot be read.
inline bool sceneWithReference(const std::string& name, Scene& scene, Image& ref) {
    try {
        scene = loadScene("scenes/" + name + ".scene");
    } catch (const InputError& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return false;
    }
    if (!readPFM("scenes/refs/" + name + ".pfm", ref)) {
        std::fprintf(stderr, "scenes/refs/%s.pfm: no reference (make refs)\n", name.c_str());
        return false;
    }
    setResolution(scene.camera, ref.width, ref.height);
    return true;
}

inline double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

