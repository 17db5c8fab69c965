// What the homework's grader (grade.cpp) and the tests (test_bdpt, test_mlt) both check against,
// written once: a heuristic's weight by its definition, and a Metropolis chain on a target whose
// integral over any box is a closed form. The file that includes it has included bdpt.cpp. `make
// homework` copies it beside the grader: it holds no line of a task's solution.
#pragma once
#include <map>

// A heuristic's weight of strategy s by its definition, from the densities p of all the strategies
// able to make the path: balance p_s / sum p, power p_s^2 / sum p^2, max 1 for the largest (ties
// within 1e-4 share), uniform 1 / count.
inline double definitionWeight(Heuristic h, const std::map<int, double>& p, int s) {
    double ps = p.at(s), sum = 0;
    int larger = 0, equal = 0;
    for (auto [i, pi] : p) {
        sum += h == Heuristic::Power ? pi * pi : h == Heuristic::Uniform ? 1 : pi;
        if (i == s) continue;
        larger += pi / ps > 1 + 1e-4;
        equal += std::fabs(pi / ps - 1) <= 1e-4;
    }
    if (h == Heuristic::Max) return larger ? 0 : 1.0 / (1 + equal);
    return (h == Heuristic::Power ? ps * ps : h == Heuristic::Uniform ? 1 : ps) / sum;
}

// A known target on [0,1)^2, read through the chain's replayed numbers as the renderer's walkers
// read theirs: 60 times brighter in one corner than in the dimmest part.
inline float knownTarget(float x, float y) { return std::exp(3 * x) * (1 + 8 * sqr(y - 0.5f)); }
inline double knownTargetIntegral(double x0, double x1, double y0, double y1) {  // closed form over a box
    auto X = [](double x) { return std::exp(3 * x) / 3; };
    auto Y = [](double y) { return y + 8 * std::pow(y - 0.5, 3) / 3; };
    return (X(x1) - X(x0)) * (Y(y1) - Y(y0));
}

struct TargetRun {
    double visitedChiSquare = 0, splattedChiSquare = 0;
    double acceptance = 0;
};

// A chain on the target (opt's large-step probability and sigma, the acceptance rule given): the
// chi-square of the visited states (every 10th, nearly independent) and of the expected-value
// splats' weights, over 8 x 8 bins against the closed form (63 degrees of freedom: about 63 +- 11
// when they fit). A chain that splats nothing gets 1e9.
inline TargetRun runOnKnownTarget(const RenderOptions& opt, Rng rng, float (*accept)(float, float) = symmetricAcceptance) {
    constexpr int kBins = 8, kSteps = 200000, kThin = 10;
    PrimarySampleChain chain;
    chain.rng = rng;
    auto evaluate = [&](PrimarySampleState& u) {
        Rng numbers;
        numbers.replay = &u.camera;
        u.camera.used = 0;
        u.camera.fresh = &chain.rng;
        float x = numbers.uniform(), y = numbers.uniform();
        u.f = knownTarget(x, y);
        u.contributions.assign(1, {std::min(kBins - 1, int(x * kBins)) + kBins * std::min(kBins - 1, int(y * kBins)), Vec3(1)});
    };
    evaluate(chain.current);
    std::vector<double> visited(kBins * kBins, 0), splatted(kBins * kBins, 0);
    auto splat = [&](const PrimarySampleState& u, double weight) {
        if (!u.contributions.empty()) splatted[size_t(u.contributions[0].pixel)] += weight * u.f;
    };
    for (int i = 0; i < kSteps; ++i) {
        metropolisStep(opt, chain, evaluate, splat, accept);
        if (i % kThin == 0 && !chain.current.contributions.empty()) visited[size_t(chain.current.contributions[0].pixel)] += 1;
    }
    splat(chain.current, chain.currentWeight);
    TargetRun run;
    double total = knownTargetIntegral(0, 1, 0, 1), samples = kSteps / kThin, splatTotal = 0;
    for (double w : splatted) splatTotal += w;
    for (int b = 0; b < kBins * kBins; ++b) {
        double x0 = double(b % kBins) / kBins, y0 = double(b / kBins) / kBins;
        double p = knownTargetIntegral(x0, x0 + 1.0 / kBins, y0, y0 + 1.0 / kBins) / total;
        run.visitedChiSquare += sqr(visited[size_t(b)] - samples * p) / (samples * p);
        run.splattedChiSquare += splatTotal > 0 ? sqr(splatted[size_t(b)] / splatTotal * samples - samples * p) / (samples * p) : 1e9;
    }
    run.acceptance = chain.proposed > 0 ? double(chain.accepted) / double(chain.proposed) : 0;
    return run;
}
