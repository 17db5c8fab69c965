// classroom/homework/hidden.h: the teacher's checks, which no student's folder holds (make homework
// copies grade.cpp, harness.h and physics.h, never this file). grade.cpp includes it, inside its namespace,
// where it is compiled with -DBDPT_HIDDEN_CHECKS: make grade-class and make gradescope. Each task
// gets at least one: other scenes, points, sizes and options than the public checks', and two
// cases the public ones do not try (a lamp seen from behind; the light seen directly).

// H1: a one-sided lamp turned to face up, above the floor: the floor sees its back, which emits
// nothing (emittedRadiance and estimateDirect alike: only the side toward the normal emits).
Outcome directLampFromBehind() {
    std::string text = kLampScene;
    const std::string down = "quad -0.4 2 -0.4  0.8 0 0  0 0 0.8", up = "quad -0.4 2 -0.4  0 0 0.8  0.8 0 0";  // u and v swapped: facing up
    text.replace(text.find(down), down.size(), up);
    Scene s = parseScene(text, "lamp from behind");
    DirectSample facing = directAt(parseScene(kLampScene, "lamp"), {kLampPoints[0]}, false, 200);
    if (facing.mean[0] <= 0) return {false, "estimateDirect gives nothing even under a lamp that faces the floor: its back cannot be told from its front", ""};
    DirectSample d = directAt(s, kLampPoints, false, 2000);
    double most = 0;
    for (double m : d.mean) most = std::max(most, std::fabs(m));
    if (most == 0) return {true, "", ""};
    return {false, "estimateDirect under a lamp that faces up, away from the floor: expected 0 at 4 points (the floor sees the lamp's back), "
                   "measured up to " + num(most) + ": the back of a one-sided lamp emits; only its front side, toward its normal, does "
                   "(cos at the lamp > 0; page 2)", "the back of a one-sided lamp emits"};
}

// H5: the light seen directly, a path of one segment: strategy (0,2) (the camera ray hits the
// lamp) gets weight 1 and (1,1) (the lamp's point joined to the pinhole) 0, whatever the densities,
// as the renderer leaves it (misWeight); the --strategies images of bdpt say so.
Outcome lightSeenDirectly() {
    Scene s = scene("scenes/cornell.scene", 24, 24);
    RenderOptions o = options(Method::BDPT, 8, 41);
    o.strategyMaxLength = 1;
    RenderResult r = render(s, o);
    double direct = 0, directWeighted = 0, joined = 0;
    for (size_t i = 0; i < r.strategies.at(0, 2, false).pixels.size(); ++i)
        direct += average(r.strategies.at(0, 2, false).pixels[i]), directWeighted += average(r.strategies.at(0, 2, true).pixels[i]),
            joined += average(r.strategies.at(1, 1, true).pixels[i]);
    if (direct <= 0) return {false, "bdpt's camera rays see no lamp on cornell (s = 0, t = 2): its strategy image is black", ""};
    if (std::fabs(directWeighted - direct) <= 1e-5 * direct && joined == 0) return {true, "", ""};
    return {false, "the light seen directly (a path of one segment) with --strategies: expected the weighted image of s = 0, t = 2 to be its "
                   "unweighted one and that of s = 1, t = 1 black, measured " + num(directWeighted / direct, 4) + " and " + num(joined / direct, 4) +
                   " of the lamp's light: the light seen directly goes to s = 0 alone (misWeight), never to both strategies",
            "the light seen directly weighted twice"};
}

std::vector<Check> hiddenChecksFor(const std::string& id) {
    if (id == "H1") return {{"next event under a lamp seen from behind", 2, directLampFromBehind}};
    if (id == "H2") return {{"connectToCamera: the importance on a wide image", 2, [] { return cameraImportanceAt(48, 24); }}};
    if (id == "H3") return {{"refraction by transport mode in water", 2, [] { return refractionWeightsAt(1.33f); }}};
    if (id == "H4") return {{"the clamp at another C", 2, [] { return gatherClampAt(0.05f); }}};
    if (id == "H5") return {{"the light seen directly, with --strategies", 2, lightSeenDirectly}};
    if (id == "H6") return {{"a chain with other steps visits its target", 2, [] {
                                 RenderOptions steps;
                                 steps.metropolis.largeStep = 0.1f, steps.metropolis.sigma = 0.05f;
                                 TargetRun run = runOnTarget(13, steps);
                                 if (run.visitedChiSquare < 150) return Outcome{true, "", ""};
                                 return Outcome{false, "a chain with large steps of probability 0.1 and small ones of sigma 0.05 on the known target: its "
                                                       "states do not follow it (chi-square " + num(run.visitedChiSquare, 4) + " over 64 bins, about 63 "
                                                       "when they do; page 16)", ""};
                             }}};
    return {};
}
