// classroom/checks.h: what the classroom's ./bdpt checks before it renders, so that a long render
// never ends in "cannot write" or in a black image: outputs writable, memory enough, a scene's
// path where it was probably meant, and mistakes in a scene that still renders.
#pragma once
#include "options.h"
#include "run.h"
#include <iomanip>

// A scene path that does not exist, from the wrong folder or without its extension: the message
// names the file probably meant.
inline Scene loadSceneOrGuess(const std::string& path) {
    struct stat st;
    if (stat(path.c_str(), &st) != 0) {
        std::string problem = path + ": cannot open the scene file: " + std::strerror(errno);
        for (const std::string& guess : {"scenes/" + path, path + ".scene", "scenes/" + path + ".scene"})
            if (stat(guess.c_str(), &st) == 0 && S_ISREG(st.st_mode)) throw InputError(problem + " (did you mean " + guess + "?)");
        if (path.find("scenes/") != std::string::npos)
            throw InputError(problem + " (the scenes are in the folder scenes/ of the repository: run ./bdpt from there)");
        throw InputError(problem);
    }
    return loadScene(path);
}

// Why a folder cannot be made: the first part of it that is a file, or the system's reason.
inline std::string folderProblem(const std::string& path, int reason = errno) {  // reason: mkdir's, before stat overwrites errno
    for (size_t i = 1; i <= path.size(); ++i) {
        if (i < path.size() && path[i] != '/') continue;
        struct stat st;
        if (stat(path.substr(0, i).c_str(), &st) == 0 && !S_ISDIR(st.st_mode)) return path.substr(0, i) + " is a file";
    }
    return std::strerror(reason);
}

// Why a file cannot be written at path ("" if it can): checked before any work, so that a long
// render never ends in "cannot write".
inline std::string unwritable(const std::string& path) {
    struct stat st;
    if (stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) return "it is a folder";
    const std::string dir = folderOf(path);
    if (stat(dir.c_str(), &st) != 0) return "the folder " + dir + " does not exist";
    if (!S_ISDIR(st.st_mode)) return dir + " is not a folder";
    if (access(dir.c_str(), W_OK) != 0) return "no permission to write in " + dir;
    if (stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) return "it is not a regular file";
    // /proc, /sys and the like pass the permission check as root and refuse files only when one
    // is made: make one now (and remove it), not after the render.
    std::string probe = dir + "/.bdpt-probe-" + std::to_string(getpid());
    std::FILE* f = std::fopen(probe.c_str(), "wb");
    if (!f) return "no file can be made in " + dir + " (" + std::strerror(errno) + ")";
    std::fclose(f);
    std::remove(probe.c_str());
    return "";
}

inline bool sameFile(const std::string& a, const std::string& b) {
    struct stat sa, sb;
    return stat(a.c_str(), &sa) == 0 && stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}


// A file the project ships, which a careless --out would lose: an existing file under a folder
// scenes/ or lecture_notes/ (a scene's reference, a figure of the notes).
inline bool shippedFile(const std::string& path) {
    char resolved[PATH_MAX];
    if (!realpath(path.c_str(), resolved)) return false;  // not there: nothing to lose
    std::string p = resolved;
    return p.find("/scenes/") != std::string::npos || p.find("/lecture_notes/") != std::string::npos;
}

// Every file the render will write, checked before it starts; a missing folder is made, for --out,
// --log and --strategies alike (a page's command into build/notes/ works from a fresh clone).
inline std::string checkOutputs(const ClassroomLine& cl, const std::string& pfm) {
    std::vector<std::string> files = {cl.out, pfm};
    if (!cl.logPath.empty()) files.push_back(cl.logPath);
    for (const std::string& f : files) {
        if (!makeFolders(folderOf(f))) return "cannot write " + f + ": the folder " + folderOf(f) + " cannot be made (" + folderProblem(folderOf(f)) + ")";
        if (sameFile(f, cl.scenePath) || (!cl.refPath.empty() && sameFile(f, cl.refPath)))
            return "will not write " + f + ": it is an input of this run";
        if (!cl.overwrite && shippedFile(f))
            return "will not overwrite " + f + ": the project ships it (a scene's reference or a figure of the notes); give --overwrite to replace it";
        std::string why = unwritable(f);
        if (!why.empty()) return "cannot write " + f + ": " + why;
    }
    if (!cl.strategiesDir.empty()) {
        if (!makeFolders(cl.strategiesDir))
            return "cannot write into " + cl.strategiesDir + ": the folder cannot be made (" + folderProblem(cl.strategiesDir) + ")";
        std::string why = unwritable(cl.strategiesDir + "/x.png");
        if (!why.empty()) return "cannot write into " + cl.strategiesDir + ": " + why;
    }
    return "";
}

// Mistakes in a scene that still renders, but not as its author meant: said before the work.
//  - one light takes nearly all of the choice by power (a huge dim sky sphere starves a lamp);
//  - a light whose emitting side faces a surface right in front of it, or nothing at all (a
//    lamp under a ceiling with its u and v swapped: it lights a sliver of ceiling, and the room
//    renders almost black);
//  - a quick preview sees no light at all (a lamp facing away, or a light in a closed box).
// What a render will hold, in bytes, known before it starts: per pixel the pass sums and squares
// (6 doubles), the pass, the image and its variance (3 Vec3), the PNG's bytes, the log's running
// mean, two sums per strategy image and the image written; vcm's light subpaths and grid of a
// pass: a vertex and its grid record (with the grid's bucket) per light vertex, at most 12 a pixel
// (its summary line reports what a run took); mlt's pass image and
// its chains' splats of one pass, bounded by 128 bytes a pixel; its chains' states do not grow
// with the image. Appendix A gives the measurements behind both bounds.
inline double estimatedBytes(const Scene& scene, const RenderOptions& opt, bool logging) {
    int images = StrategyImages(opt).count();
    double perPixel = 6 * sizeof(double) + 3 * sizeof(Vec3) + 3 + (logging ? 3 * sizeof(double) + sizeof(Vec3) : 0) +
                      images * (2 * 3 * sizeof(double) + sizeof(Vec3) + 3) +
                      (opt.method == Method::VCM ? 12 * (sizeof(PathVertex) + sizeof(VcmPass::Stored) + 8) + sizeof(Subpath) : 0) +
                      (isMetropolis(opt.method) ? 128 : 0);
    return perPixel * scene.camera.width * scene.camera.height;
}

// The memory this process may use: the machine's, or less where `ulimit -v` says so.
inline double memoryLimitBytes() {
    double machine = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
    struct rlimit limit;
    if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) return std::min(machine, double(limit.rlim_cur));
    return machine;
}

inline void warnAboutScene(const Scene& scene, const RenderOptions& opt, std::ostream& err) {
    for (size_t i = 0; i < scene.lights.size() && scene.lights.size() > 1; ++i) {
        float share = lightChoiceProbability(scene, int(i));
        char percent[32];
        std::snprintf(percent, sizeof percent, "%.7g", 100.0 * share);
        if (share > 0.999f)
            err << scene.file << ":" << scene.lights[i].line << ": warning: this light takes " << percent
                << "% of the light choice (by power): the others are almost never sampled, and where they matter nee, lt "
                   "and bdpt will be noisy\n";
    }
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& light = scene.lights[i];
        if (light.type != Light::Area) continue;
        // Its light, sampled as light paths leave it, from its emitting side and, as if turned
        // around, from the other: the share that reaches a surface farther than a twentieth of
        // the lamp's size (closer: the ceiling it hangs under). A lamp that lights little on its
        // side and much on the other was meant the other way round; a lamp that lights nothing
        // either way (a sky, a lamp over an open floor) is left alone.
        const float near = 0.05f * std::sqrt(scene.shapes[light.shape].area);
        const int rays = 256;
        int lit[2] = {0, 0};
        float nearest = kInf;
        Rng rng = makeRng(0x1a4e, i, 0);
        for (int r = 0; r < rays; ++r) {
            float u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform(), u4 = rng.uniform();
            SurfacePoint sp = sampleShapePoint(scene, light.shape, u1, u2);
            for (int side = 0; side < 2; ++side) {
                Vec3 n = side == 0 ? sp.ng : -sp.ng;
                Hit hit = intersect(scene, spawnRay(sp, Frame(n).toWorld(sampleCosineHemisphere(u3, u4))));
                lit[side] += hit.found() && hit.t >= near;
                if (side == 0 && hit.found() && hit.t < near) nearest = std::min(nearest, hit.t);
            }
        }
        if (!(lit[0] < rays / 10 && lit[1] > rays / 2)) continue;
        char text[64];
        std::snprintf(text, sizeof text, "a surface %.3g away", double(nearest));
        err << scene.file << ":" << light.line << ": warning: this light's emitting side (u x v for a quad) faces "
            << (nearest < kInf ? text : "nothing") << ": " << 100 * lit[0] / rays << "% of its light gets farther, "
            << 100 * lit[1] / rays << "% would from its other side; to turn it around, swap its u and v\n";
    }
    Scene preview = scene;
    setResolution(preview.camera, 32, 32);
    RenderOptions o;
    o.method = opt.method == Method::VCM ? Method::VCM : Method::BDPT;  // vcm sees what bdpt cannot
    o.spp = 16;
    o.maxDepth = std::min(opt.maxDepth, 8);
    o.threads = 1;
    // Every sample is >= 0: if the first pass sees light, all 16 would. Most scenes stop there.
    RenderOptions firstPass = o;
    firstPass.spp = 1;
    if (imageMean(render(preview, firstPass).image) == 0 && imageMean(render(preview, o).image) == 0)
        err << scene.file << ": warning: a quick preview (" << methodName(o.method) << ", 32x32, 16 samples per pixel) sees no light at all: is a light "
               "facing away (a quad emits from its u x v side only), or shut in?\n";
}

// A render of a million pixels or more says up front how long it will take: a 64x64 pass of the
// same scene and options, its CPU time scaled by the pixels (the Metropolis methods' bootstrap apart).
inline void warnAboutDuration(const ClassroomLine& cl, const Scene& scene, std::ostream& err) {
    const double pixels = double(scene.camera.width) * scene.camera.height;
    if (cl.quiet || pixels < 1e6 || isMetropolis(cl.opt.method)) return;
    Scene trial = scene;
    setResolution(trial.camera, 64, 64);
    RenderOptions opt = cl.opt;
    opt.spp = 1;
    opt.seconds = 0;
    const double trialSeconds = render(trial, opt).cpuSeconds, pass = trialSeconds * pixels / (64.0 * 64.0);  // CPU seconds, as --time counts
    if (pass < 2) return;
    err << "bdpt: " << scene.camera.width << "x" << scene.camera.height << " pixels: a pass (one sample per pixel) takes about "
        << duration(pass) << " of CPU time here";
    if (cl.opt.seconds <= 0 && cl.opt.spp > 1) err << ", its " << cl.opt.spp << " passes about " << duration(pass * cl.opt.spp);
    char trialText[32];
    std::snprintf(trialText, sizeof trialText, "%.3g", trialSeconds);
    err << " (from a 64x64 pass of " << trialText << " CPU s); Ctrl-C stops after the pass in flight\n";
}

// Before any work: every output writable, the memory there, the reference readable and of the
// image's size. Returns the exit status if the render cannot go ahead, else 0.
inline int checkBeforeRendering(const ClassroomLine& cl, const Scene& scene, const std::string& pfm, Image& ref, std::ostream& err) {
    std::string problem = checkOutputs(cl, pfm);
    if (!problem.empty()) {
        err << "bdpt: " << problem << " (nothing rendered)\n";
        return 1;
    }
    double needed = estimatedBytes(scene, cl.opt, !cl.logPath.empty()), limit = memoryLimitBytes();
    if (needed + 200e6 > limit) {  // 200 MB for the program, its threads' stacks and the scene
        err << "bdpt: this render needs about " << std::setprecision(2) << std::fixed << needed / 1e9 << " GB for " << scene.camera.width
            << "x" << scene.camera.height << " pixels, more than the " << limit / 1e9
            << " GB this process may use (the machine's memory or ulimit -v): use a smaller --res (nothing rendered)\n";
        return 1;
    }
    if (cl.refPath.empty()) return 0;
    if (!readPFM(cl.refPath, ref)) {
        err << cl.refPath << ": cannot read the reference (a PFM written by bdpt)\n";
        return 2;
    }
    if (ref.width != scene.camera.width || ref.height != scene.camera.height) {
        err << cl.refPath << ": the reference is " << ref.width << "x" << ref.height << ", the image " << scene.camera.width << "x"
            << scene.camera.height << " (use --res)\n";
        return 2;
    }
    return 0;
}

