// Quasi-random numbers (--sampler sobol): the points' defining property, independent scrambles,
// unchanged means, and an error that falls faster than independent numbers'.
#include "helpers.h"

// The numbers dimension by dimension of passes 0..n-1 of one pixel's stream.
static std::vector<std::vector<float>> pixelPoints(Sampler sampler, uint64_t seed, uint64_t pixel, int n, bool noScramble = false) {
    RenderOptions o;
    o.sampler = sampler;
    o.seed = seed;
    o.noScramble = noScramble;
    std::vector<std::vector<float>> u(kLowDiscrepancyDimensions, std::vector<float>(size_t(n)));
    for (int i = 0; i < n; ++i) {
        Rng rng = sampleRng(o, 0, pixel, uint64_t(i));
        for (uint32_t d = 0; d < kLowDiscrepancyDimensions; ++d) u[d][size_t(i)] = rng.uniform();
    }
    return u;
}

// Every elementary interval [a 2^-j, (a+1) 2^-j) x [b 2^-(m-j), (b+1) 2^-(m-j)) of area 2^-m holds
// exactly one of the first 2^m points (a (0,m,2)-net), for every split j = 0..m.
static bool isNet(const std::vector<float>& x, const std::vector<float>& y, int m) {
    const size_t n = size_t(1) << m;
    for (int j = 0; j <= m; ++j) {
        std::vector<int> count(n, 0);
        for (size_t i = 0; i < n; ++i) ++count[(size_t(x[i] * float(1 << j)) << (m - j)) + size_t(y[i] * float(1 << (m - j)))];
        if (std::count(count.begin(), count.end(), 1) != int(n)) return false;
    }
    return true;
}
static bool isStratified(const std::vector<float>& x, int m) {  // one point in each interval of 2^-m
    std::vector<int> count(size_t(1) << m, 0);
    for (size_t i = 0; i < count.size(); ++i) ++count[size_t(x[i] * float(count.size()))];
    return std::count(count.begin(), count.end(), 1) == int(count.size());
}

TEST_CASE("Sobol points: every prefix of 2^m fills the elementary intervals (film position) and each dimension's 2^m strata") {
    for (uint64_t seed : {1, 2}) {
        for (bool noScramble : {false, true}) {  // the scramble keeps the property; without it, it holds too
            CAPTURE(seed);
            CAPTURE(noScramble);
            auto u = pixelPoints(Sampler::Sobol, seed, 77, 1024, noScramble);
            for (int m = 0; m <= 10; ++m) {
                CAPTURE(m);
                CHECK(isNet(u[0], u[1], m));
                int strata = 0;
                for (uint32_t d = 0; d < kLowDiscrepancyDimensions; ++d) strata += isStratified(u[d], m);
                CHECK(strata == int(kLowDiscrepancyDimensions));
            }
        }
    }
    // The broken variant: independent numbers leave some cells empty and others double.
    auto r = pixelPoints(Sampler::Random, 1, 77, 1024);
    CHECK_FALSE(isNet(r[0], r[1], 6));
    CHECK_FALSE(isStratified(r[5], 6));
}

// Pearson's correlation of two lists.
static double correlation(const std::vector<double>& a, const std::vector<double>& b) {
    double ma = 0, mb = 0, sab = 0, saa = 0, sbb = 0;
    for (size_t i = 0; i < a.size(); ++i) ma += a[i] / a.size(), mb += b[i] / b.size();
    for (size_t i = 0; i < a.size(); ++i) sab += (a[i] - ma) * (b[i] - mb), saa += sqr(a[i] - ma), sbb += sqr(b[i] - mb);
    return sab / std::sqrt(saa * sbb);
}

// The construction against the published data: Joe and Kuo's direction numbers (the file
// new-joe-kuo-6.21201, its first 31 rows: d, degree s, the polynomial's coefficients a, m_1..m_s)
// turned into points by their own reference algorithm (V_k = m_k 2^(32-k); past s,
// V_k = V_(k-s) ^ V_(k-s)/2^s ^ the V_(k-j) whose coefficient a_j is set, a's bits read from the
// top), written here apart from the code; the first points of its first two dimensions are scipy's
// published ones. Every dimension alone is stratified even with a polynomial read backwards (each
// C_d stays invertible): the whole point must match, as a pixel draws it with --no-scramble (the
// camera's stream, point i in pass i): 1,024 points, 32 dimensions, to the 24 bits a number has.
static const char* const kNewJoeKuo = R"(2 1 0 1
3 2 1 1 3
4 3 1 1 3 1
5 3 2 1 1 1
6 4 1 1 1 3 3
7 4 4 1 3 5 13
8 5 2 1 1 5 5 17
9 5 4 1 1 5 5 5
10 5 7 1 1 7 11 19
11 5 11 1 1 5 1 1
12 5 13 1 1 1 3 11
13 5 14 1 3 5 5 31
14 6 1 1 3 3 9 7 49
15 6 13 1 1 1 15 21 21
16 6 16 1 3 1 13 27 49
17 6 19 1 1 1 15 7 5
18 6 22 1 3 1 15 13 25
19 6 25 1 1 5 5 19 61
20 7 1 1 3 7 11 23 15 103
21 7 4 1 3 7 13 13 15 69
22 7 7 1 1 3 13 7 35 63
23 7 8 1 3 5 9 1 25 53
24 7 14 1 3 1 13 9 35 107
25 7 19 1 3 1 5 27 61 31
26 7 21 1 1 5 11 19 41 61
27 7 28 1 3 5 3 3 13 69
28 7 31 1 1 7 13 1 19 1
29 7 32 1 3 7 5 13 19 59
30 7 37 1 1 3 9 25 29 41
31 7 41 1 3 5 13 23 1 55
32 7 42 1 3 7 3 13 59 17)";
static std::vector<std::array<uint32_t, 33>> joeKuoDirections() {  // V[1..32] per dimension, V_k as a 32-bit fraction
    std::vector<std::array<uint32_t, 33>> dims;
    std::array<uint32_t, 33> first{};
    for (int k = 1; k <= 32; ++k) first[k] = 1u << (32 - k);  // dimension 1: van der Corput
    dims.push_back(first);
    std::istringstream rows(kNewJoeKuo);
    for (std::string row; std::getline(rows, row);) {
        std::istringstream in(row);
        unsigned d, s, a;
        in >> d >> s >> a;
        std::array<uint32_t, 33> V{};
        for (unsigned k = 1; k <= s; ++k) {
            unsigned m;
            in >> m;
            V[k] = m << (32 - k);
        }
        for (unsigned k = s + 1; k <= 32; ++k) {
            V[k] = V[k - s] ^ (V[k - s] >> s);
            for (unsigned j = 1; j <= s - 1; ++j)
                if ((a >> (s - 1 - j)) & 1) V[k] ^= V[k - j];
        }
        dims.push_back(V);
    }
    return dims;
}
TEST_CASE("Sobol points: a pixel's unscrambled numbers are Joe and Kuo's published sequence, all 32 dimensions") {
    const auto V = joeKuoDirections();
    REQUIRE(V.size() == kLowDiscrepancyDimensions);
    auto point = [&](uint32_t i, size_t d) {  // x_d(i) = xor of V_k over the bits k of i (natural order)
        uint32_t x = 0;
        for (int k = 1; k <= 32; ++k)
            if ((i >> (k - 1)) & 1) x ^= V[d][k];
        return float(x >> 8) * 0x1p-24f;
    };
    // scipy's published first points (its order is Gray code's: its i-th is the natural (i ^ i/2)-th)
    const float scipy[8][2] = {{0, 0}, {0.5f, 0.5f}, {0.75f, 0.25f}, {0.25f, 0.75f}, {0.375f, 0.375f}, {0.875f, 0.875f}, {0.625f, 0.125f}, {0.125f, 0.625f}};
    for (uint32_t i = 0; i < 8; ++i) {
        CHECK(point(i ^ (i >> 1), 0) == scipy[i][0]);
        CHECK(point(i ^ (i >> 1), 1) == scipy[i][1]);
    }
    const auto u = pixelPoints(Sampler::Sobol, 1, 0, 1024, true);
    int differ = 0, first = -1;
    for (uint32_t i = 0; i < 1024; ++i)
        for (size_t d = 0; d < kLowDiscrepancyDimensions; ++d)
            if (u[d][i] != point(i, d)) {
                if (first < 0) first = int(d);
                ++differ;
            }
    MESSAGE(differ << " of " << 1024 * kLowDiscrepancyDimensions << " numbers differ from the published sequence's" << (first >= 0 ? ", first in dimension " + std::to_string(first) : std::string()));
    CHECK(differ == 0);
}

TEST_CASE("scrambles: pixels and seeds get independent points, uniform in every dimension; --no-scramble does not") {
    const int n = 4096;
    for (bool noScramble : {false, true}) {
        CAPTURE(noScramble);
        // The first point of n pixels (one seed), and of one pixel under n seeds.
        std::vector<double> pixelsX(n), pixelsY(n), seedsX(n), neighbour(n);
        for (int i = 0; i < n; ++i) {
            auto p = pixelPoints(Sampler::Sobol, 1, uint64_t(i), 1, noScramble);
            auto q = pixelPoints(Sampler::Sobol, 1, uint64_t(i + 1), 1, noScramble);
            auto s = pixelPoints(Sampler::Sobol, uint64_t(i + 10), 5, 1, noScramble);
            pixelsX[i] = p[3][0], pixelsY[i] = p[4][0], neighbour[i] = q[3][0], seedsX[i] = s[3][0];
        }
        // An 8 x 8 histogram of (x, y) over the pixels: chi^2 with 63 degrees of freedom, below 110
        // with probability 0.9998 when the points are uniform and independent.
        std::vector<double> cells(64, 0);
        for (int i = 0; i < n; ++i) cells[size_t(pixelsX[i] * 8) * 8 + size_t(pixelsY[i] * 8)] += 1;
        double chi2 = 0;
        for (double c : cells) chi2 += sqr(c - n / 64.0) / (n / 64.0);
        double meanSeeds = std::accumulate(seedsX.begin(), seedsX.end(), 0.0) / n;
        // Independent: |r| below 4 standard deviations, 4 / sqrt(n), of a correlation of n pairs.
        double r = correlation(pixelsX, neighbour);
        MESSAGE("noScramble " << noScramble << ": chi2 " << chi2 << ", correlation of neighbours " << r << ", mean over seeds " << meanSeeds);
        if (!noScramble) {
            CHECK(chi2 < 110);
            CHECK(std::fabs(r) < 4 / std::sqrt(double(n)));
            CHECK(meanSeeds == doctest::Approx(0.5).epsilon(4 * std::sqrt(1 / 12.0 / n) / 0.5));
        } else {
            CHECK(chi2 > 1000);  // every pixel's first point is the same
        }
    }
}

// bdpt's camera and light subpaths of a pixel meet in one path. Drawing both from point i of the
// sequence, each scrambled its own way, their coordinates share i's digits: a camera number in a
// cell of width 1/8 fixes the light number's cell too, for all 8 of a pixel's 64 passes there.
// The light stream draws the sequence in its own order (shuffledIndex), so their pairs fill the
// square as independent numbers would.
TEST_CASE("a pixel's camera and light subpaths draw the sequence in different orders: their pairs are independent") {
    RenderOptions o;
    const int pixels = 64, passes = 64;
    for (uint32_t d : {0u, 3u}) {
        std::vector<double> cells(64, 0);
        for (int p = 0; p < pixels; ++p)
            for (int i = 0; i < passes; ++i) {
                Rng camera = sampleRng(o, 0, uint64_t(p), uint64_t(i)), light = lightPathRng(o, p, i);
                float x = 0, y = 0;
                for (uint32_t k = 0; k <= d; ++k) x = camera.uniform(), y = light.uniform();
                cells[size_t(x * 8) * 8 + size_t(y * 8)] += 1;
            }
        const double expected = pixels * passes / 64.0;
        double chi2 = 0;
        for (double c : cells) chi2 += sqr(c - expected) / expected;
        MESSAGE("dimension " << d << ": chi^2 of (camera, light) pairs over 8 x 8 cells " << chi2);
        CHECK(chi2 < 110);  // 63 degrees of freedom: below 110 with probability 0.9998
    }
}

// The consequence, end to end: bdpt's variance over seeds falls as 1/N or faster with either
// sampler (with one order for both subpaths it falls 4.2x from 64 to 512 samples, against
// random numbers' 8x, and ends 1.5x above them).
TEST_CASE("bdpt with --sampler sobol: the variance over seeds falls at least as 1/N") {
    Scene scene = sceneAt("scenes/cornell.scene", 12, 12);
    auto varianceOverSeeds = [&](Sampler sampler, int spp) {
        const int seeds = 8;
        std::vector<Image> images;
        for (int k = 0; k < seeds; ++k) {
            RenderOptions o = quietOptions(Method::BDPT, spp, 300 + k);
            o.sampler = sampler;
            images.push_back(render(scene, o).image);
        }
        std::vector<std::pair<int, int>> awayFromLamp;
        for (int y = 0; y < scene.camera.height; ++y)
            for (int x = 0; x < scene.camera.width; ++x)
                if (!nearLamp(images[0], x, y)) awayFromLamp.push_back({x, y});
        return spreadOverSeeds(images, awayFromLamp).varianceSum;
    };
    for (Sampler sampler : {Sampler::Sobol, Sampler::Random}) {
        double fall = varianceOverSeeds(sampler, 64) / varianceOverSeeds(sampler, 512);
        MESSAGE(std::string(kSamplerNames[int(sampler)]) << ": variance 64 -> 512 samples falls " << fall << "x (1/N: 8x)");
        CHECK(fall > 6);
    }
}

// Neighbouring pixels' errors against an independent estimate are uncorrelated when the pixels'
// scrambles are independent. A scramble whose seeds are too alike between pixels makes blotches
// several pixels wide: the error of one pixel predicts its neighbour's.
TEST_CASE("neighbouring pixels' errors are uncorrelated with either sampler, not without the scramble") {
    Scene scene = sceneAt("scenes/cornell.scene", 48, 48);
    RenderOptions o = quietOptions(Method::NEE, 16);
    o.mis = true;
    o.maxDepth = 1;
    RenderOptions longRun = o;
    longRun.spp = 1024;
    longRun.sampler = Sampler::Random;
    longRun.seed = 99;
    Image ref = render(scene, longRun).image;
    struct Variant { Sampler sampler; bool noScramble; };
    for (Variant v : {Variant{Sampler::Sobol, false}, Variant{Sampler::Random, false}, Variant{Sampler::Sobol, true}}) {
        o.sampler = v.sampler;
        o.noScramble = v.noScramble;
        Image img = render(scene, o).image;
        std::vector<double> left, right;
        for (int y = 0; y < ref.height; ++y)
            for (int x = 0; x + 1 < ref.width; ++x) {
                if (nearLamp(ref, x, y) || nearLamp(ref, x + 1, y)) continue;
                left.push_back(average(img.at(x, y)) - average(ref.at(x, y)));
                right.push_back(average(img.at(x + 1, y)) - average(ref.at(x + 1, y)));
            }
        double r = correlation(left, right);
        CAPTURE(int(v.sampler));
        CAPTURE(v.noScramble);
        MESSAGE("sampler " << std::string(kSamplerNames[int(v.sampler)]) << (v.noScramble ? " --no-scramble" : "") << ": neighbours' error correlation " << r);
        if (v.noScramble) CHECK(r > 0.3);
        else CHECK(std::fabs(r) < 4 / std::sqrt(double(left.size())) + 0.02);  // + the long run's own noise, shared
    }
}

TEST_CASE("every method's mean with --sampler sobol agrees with the reference and with --sampler random's, over seeds") {
    Scene scene = sceneAt("scenes/cornell.scene", 32, 32);
    RegionEstimate ref = referenceRegions("cornell", 4);
    for (Method m : {Method::PT, Method::NEE, Method::LT, Method::IR, Method::BDPT, Method::VCM}) {
        RenderOptions o = quietOptions(m, m == Method::PT ? 64 : 16);
        o.mis = m == Method::NEE;
        RegionEstimate sobol = overSeeds(scene, o, 4, 8);
        o.sampler = Sampler::Random;
        RegionEstimate random = overSeeds(scene, o, 4, 8);
        double c = chiSquare(sobol, ref), z = maxZ(sobol, random);
        MESSAGE(std::string(kMethodNames[int(m)]) << ": chi^2 over 16 regions " << c << ", largest z against random numbers " << z);
        CAPTURE(int(m));
        // 16 regions from 8 seeds (t with 7 degrees of freedom): about 16 x 7/5 = 22 when unbiased.
        // vcm is consistent, not unbiased: at 16 passes its merges still blur (with either sampler).
        if (m != Method::VCM) CHECK(c < 45);
        CHECK(z < 4);
    }
    // Without the scramble every seed gives the same image (but for the numbers past the Sobol
    // dimensions): its spread says nothing, and its error, where the points happen to fall, is not
    // noise that seeds would average out.
    RenderOptions o = quietOptions(Method::NEE, 16);
    o.mis = true;
    o.noScramble = true;
    RegionEstimate e = overSeeds(scene, o, 4, 2);
    CHECK(chiSquare(e, ref) > 1000);
    double worst = 0;
    for (size_t r = 0; r < e.mean.size(); ++r) worst = std::max(worst, std::fabs(e.mean[r] / ref.mean[r] - 1));
    MESSAGE("--no-scramble: largest region error " << 100 * worst << "%");
    CHECK(worst > 0.01);
}

// Direct light at a pixel is a smooth 4D integrand (film position, lamp point) but for the shadows'
// edges: stratified points cut its MSE several times at 64 samples, and it falls faster than
// independent numbers' 1/N (Owen-scrambled nets: N^-3/2 where the integrand is smooth).
static double directMse(const Scene& scene, const Image& ref, Sampler sampler, int spp) {
    double sum = 0;
    for (uint64_t seed = 1; seed <= 4; ++seed) {
        RenderOptions o = quietOptions(Method::NEE, spp, seed);
        o.mis = true;
        o.maxDepth = 1;
        o.sampler = sampler;
        Image img = render(scene, o).image;
        for (int y = 0; y < ref.height; ++y)
            for (int x = 0; x < ref.width; ++x)
                if (!nearLamp(ref, x, y)) sum += sqr(average(img.at(x, y)) - average(ref.at(x, y)));
    }
    return sum;
}

TEST_CASE("stratification: direct light's MSE several times lower than with independent numbers, and falling faster than 1/N") {
    Scene scene = sceneAt("scenes/cornell.scene", 24, 24);
    // The reference: another sampler, another seed, 262,144 passes (make test-refs).
    Image ref = referenceImage("tests/refs/cornell-direct.pfm");
    REQUIRE(ref.width == 24);
    double random16 = directMse(scene, ref, Sampler::Random, 16), random256 = directMse(scene, ref, Sampler::Random, 256);
    double sobol16 = directMse(scene, ref, Sampler::Sobol, 16), sobol256 = directMse(scene, ref, Sampler::Sobol, 256);
    MESSAGE("direct light MSE ratios: sobol/random at 16 spp " << sobol16 / random16 << ", at 256 " << sobol256 / random256
            << "; 16 -> 256 spp: random " << random16 / random256 << "x, sobol " << sobol16 / sobol256 << "x");
    CHECK(random16 / random256 == doctest::Approx(16).epsilon(0.4));  // independent numbers: 1/N
    CHECK(sobol16 / sobol256 > 32);
    CHECK(sobol16 < 0.5 * random16);
    CHECK(sobol256 < 0.2 * random256);
}

TEST_CASE("the furnace with --sampler random too: L = 2 within 1% for every method") {
    Scene scene = sceneAt("scenes/furnace.scene", 16, 16);
    for (Method m : {Method::PT, Method::NEE, Method::LT, Method::IR, Method::BDPT, Method::VCM}) {
        RenderOptions o = quietOptions(m, 64);
        o.sampler = Sampler::Random;
        CAPTURE(int(m));
        CHECK(imageMean(render(scene, o).image) == doctest::Approx(2.0).epsilon(0.01));
    }
}

TEST_CASE("--sampler sobol: the image does not depend on the thread count, and differs from --sampler random's") {
    Scene scene = sceneAt("scenes/cornell.scene", 16, 16);
    for (Method m : {Method::PT, Method::BDPT, Method::VCM}) {
        RenderOptions o = quietOptions(m, 8);
        o.threads = 1;
        Image one = render(scene, o).image;
        o.threads = 3;
        Image three = render(scene, o).image;
        o.sampler = Sampler::Random;
        Image random = render(scene, o).image;
        CAPTURE(int(m));
        CHECK(compareToReference(one, three).rmse == 0);
        CHECK(compareToReference(one, random).rmse > 0);
    }
}

// A pixel's camera and light streams are scrambled with keys of their own: drawn with one key,
// the light's numbers would be the camera's own points taken in another order, and every one of
// the light's first 256 would be among the camera's 65,536 (by chance about one in 256 is).
TEST_CASE("a pixel's light numbers are not its camera numbers reordered: they meet no more than by chance") {
    RenderOptions o;
    o.seed = 7;
    long long met = 0, drawn = 0;
    for (int pixel : {0, 1, 517}) {
        for (uint32_t d : {0u, 2u}) {
            auto coordinate = [d](Rng rng) {
                float u = 0;
                for (uint32_t k = 0; k <= d; ++k) u = rng.uniform();
                return uint32_t(u * 0x1p24f);
            };
            std::set<uint32_t> camera;
            for (int pass = 0; pass < 65536; ++pass) camera.insert(coordinate(sampleRng(o, 0, uint64_t(pixel), uint64_t(pass))));
            for (int pass = 0; pass < 256; ++pass) met += camera.count(coordinate(lightPathRng(o, pixel, pass))), ++drawn;
        }
    }
    MESSAGE(met << " of " << drawn << " light numbers among their pixel's 65,536 camera numbers (chance: about " << drawn / 256 << ")");
    CHECK(met < 40);  // Poisson of mean 6 (65,536 of 2^24 values each): below 40 with probability 1 - 1e-20
}

// Every pixel has its own stream, numbered y W + x: on an image wider than high, y H + x would give
// pixel (x + H, y) the stream of (x, y + 1). lt traces one light path per pixel stream, so shared
// streams trace the same path twice, and its splats (one per vertex, in a row's list one after
// another) appear in two rows. One splat alone can repeat by right: a fronto-parallel wall lit
// straight from the lamp splats the same value wherever it is seen. Two in a row do not.
TEST_CASE("every pixel of a 64x32 image draws its own numbers: no light path of lt is traced twice in a pass") {
    Scene scene = sceneAt("scenes/cornell.scene", 64, 32);
    Rendering rendering(scene, quietOptions(Method::LT, 1, 5));
    rendering.addPass();
    std::map<std::tuple<int, float, int, float>, std::set<int>> rowsOf;  // two splats in a row, and the rows that made them
    size_t pairs = 0;
    for (int y = 0; y < 32; ++y) {
        const std::vector<Splat>& s = rendering.rows[y].splats;
        for (size_t i = 0; i + 1 < s.size(); ++i)
            if (!isBlack(s[i].value) && !isBlack(s[i + 1].value))
                rowsOf[{s[i].pixel, s[i].value.y, s[i + 1].pixel, s[i + 1].value.y}].insert(y), ++pairs;
    }
    int repeated = 0;
    for (const auto& entry : rowsOf) repeated += entry.second.size() > 1;
    MESSAGE(pairs << " pairs of splats, " << repeated << " of them made in two rows");
    CHECK(pairs > 1000);
    CHECK(repeated == 0);
}

// Section 1's sobolSample is the definition (C_d's columns xor-ed by the index's bits, scrambled,
// reversed into a fraction); Appendix C's fast path must give the same numbers. The scramble seed
// of dimension d is step d+1 of PCG's LCG from the stream's key, stepped here one at a time.
TEST_CASE("Sobol points: Appendix C's fast path gives section 1's sobolSample over 2^16 indices x 32 dimensions") {
    SampleOptions o;
    o.seed = 5;
    long long compared = 0, differ = 0;
    for (uint32_t index = 0; index < 65536; ++index) {
        Rng rng = sampleRng(o, kCameraStream, 12345, index);
        uint64_t state = rng.scrambleKey;
        for (uint32_t d = 0; d < kLowDiscrepancyDimensions; ++d) {
            state = state * 6364136223846793005ULL + 1442695040888963407ULL;
            differ += rng.uniform() != sobolSample(index, d, uint32_t(state >> 32));
            ++compared;
        }
    }
    CHECK(compared == 65536LL * 32);
    CHECK(differ == 0);
    // And the reference is a (0,1)-sequence in every dimension, scrambled or not: its first 2^m
    // numbers lie one in each of the 2^m intervals [j/2^m, (j+1)/2^m).
    int stratified = 0;
    for (uint32_t d = 0; d < kLowDiscrepancyDimensions; ++d)
        for (uint32_t m = 1; m <= 10; ++m) {
            std::vector<int> hits(1u << m, 0);
            for (uint32_t i = 0; i < (1u << m); ++i) ++hits[size_t(sobolSample(i, d, 77 * d + 1) * float(1u << m))];
            stratified += std::count(hits.begin(), hits.end(), 1) == int(1u << m);
        }
    CHECK(stratified == int(kLowDiscrepancyDimensions) * 10);
}
