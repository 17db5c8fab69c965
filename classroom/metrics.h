// classroom/metrics.h: the error of an image against a reference, as the charts, the tables and
// the page measure it: the lamp's pixels, RMSE, relMSE, bias and fireflies (bdpt.cpp's readPFM
// reads the references).
#pragma once
#include "lecture.h"

// Error against a reference image (speed against accuracy). RMSE over pixels and channels;
// relMSE = mean (x - ref)^2 / (ref^2 + 0.01), as rendering papers report it; the relative bias of
// the image mean; and a firefly measure: the 99.9th percentile of the per-pixel absolute error
// over its median (large where a few pixels carry huge errors).
struct ErrorMetrics {
    double rmse = 0, relMse = 0, mean = 0, firefly = 0;
    double bias = 0;             // of the image mean, the lamp's pixels left out
    double rmseWithoutLamp = 0;  // rmse over the pixels that are not the lamp's (lampPixels)
};

// A lamp seen directly: a pixel within one pixel of a reference value above 5. Its edge pixels
// are part lamp (Le = 17 in the Cornell boxes) and part ceiling, and a camera sample's jitter lands
// on one or the other: that noise is the pixel filter's, the same for every camera-path method,
// and on the Cornell boxes it is most of their MSE, hiding the transport's error (light tracing
// splats many lamp points into each such pixel per pass and does not show it). make efficiency
// and the charts' curves leave these pixels out.
inline bool nearLamp(const Image& ref, int x, int y) {
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            int u = x + dx, v = y + dy;
            if (u >= 0 && v >= 0 && u < ref.width && v < ref.height && maxComponent(ref.at(u, v)) > 5) return true;
        }
    return false;
}

// The lamp's pixels: nearLamp's, and a point light's own pixel and its neighbours. A point light
// has no area, so no camera path meets it and a reference made by one shows nothing there, while
// light tracing splats the light's whole direct view into that one pixel: a difference of the
// pixel, not of the transport (on cornell-point it was +89% of lt's image mean).
inline std::vector<char> lampPixels(const Image& ref, const Scene* scene) {
    std::vector<char> lamp(ref.pixels.size(), 0);
    for (int y = 0; y < ref.height; ++y)
        for (int x = 0; x < ref.width; ++x) lamp[size_t(y) * ref.width + x] = nearLamp(ref, x, y);
    for (const Light& light : scene ? scene->lights : std::vector<Light>{}) {
        float fx, fy;
        if (light.type != Light::Point || !projectToFilm(scene->camera, light.position, fx, fy) || scene->camera.width != ref.width) continue;
        for (int y = int(fy) - 1; y <= int(fy) + 1; ++y)
            for (int x = int(fx) - 1; x <= int(fx) + 1; ++x)
                if (x >= 0 && y >= 0 && x < ref.width && y < ref.height) lamp[size_t(y) * ref.width + x] = 1;
    }
    return lamp;
}

// With the scene, a point light's pixels are the lamp's too (lampPixels). The bias leaves the
// lamp's pixels out, as rmseWithoutLamp does.
inline ErrorMetrics compareToReference(const Image& img, const Image& ref, const Scene* scene = nullptr) {
    ErrorMetrics m;
    std::vector<double> pixelError(img.pixels.size());
    const std::vector<char> lampMask = lampPixels(ref, scene);
    double sum = 0, lampless = 0, lamplessSum = 0, lamplessRefSum = 0;
    long lamplessValues = 0;
    for (size_t i = 0; i < img.pixels.size(); ++i) {
        bool lamp = ref.width > 0 && lampMask[i];
        for (int c = 0; c < 3; ++c) {
            double x = img.pixels[i][c], r = ref.pixels[i][c], e = x - r;
            m.rmse += e * e;
            if (!lamp) lampless += e * e, ++lamplessValues, lamplessSum += x, lamplessRefSum += r;
            m.relMse += e * e / (r * r + 0.01);
            sum += x;
        }
        pixelError[i] = std::fabs(double(average(img.pixels[i])) - average(ref.pixels[i]));
    }
    double n = 3.0 * img.pixels.size();
    m.rmse = std::sqrt(m.rmse / n);
    m.rmseWithoutLamp = std::sqrt(lampless / std::max(1L, lamplessValues));
    m.relMse /= n;
    m.mean = sum / n;
    m.bias = lamplessRefSum > 0 ? (lamplessSum - lamplessRefSum) / lamplessRefSum : 0;
    auto quantile = [&](double q) {
        size_t k = std::min(pixelError.size() - 1, size_t(q * (pixelError.size() - 1) + 0.5));
        std::nth_element(pixelError.begin(), pixelError.begin() + k, pixelError.end());
        return pixelError[k];
    };
    double median = quantile(0.5), p999 = quantile(0.999);
    m.firefly = p999 / std::max(median, 1e-12);
    return m;
}

inline std::string fileStem(const std::string& path) {  // "build/notes/pool-lt.pfm" -> "pool-lt"
    std::string name = replaceExtension(path, "");
    size_t slash = name.find_last_of('/');
    return slash == std::string::npos ? name : name.substr(slash + 1);
}

// vcm's passes as they ran: the radius of the first and the last, the most memory one held, and
// how many light vertices in all.
struct VcmTotals {
    float firstRadius = -1, lastRadius = 0;
    size_t mostBytes = 0;
    long long lightVertices = 0, mergeable = 0;
    void add(const VcmPass& vp) {
        if (firstRadius < 0) firstRadius = vp.radius;
        lastRadius = vp.radius;
        size_t bytes = vp.paths.capacity() * sizeof(Subpath) + vp.stored.capacity() * sizeof(VcmPass::Stored) +
                       vp.grid.bucketStart.capacity() * sizeof(uint32_t);
        for (const std::vector<PathVertex>& row : vp.rowVertices) {
            bytes += row.capacity() * sizeof(PathVertex);
            lightVertices += (long long)row.size();
        }
        mostBytes = std::max(mostBytes, bytes);
        mergeable += (long long)vp.stored.size();
    }
};

// vcm's line of the summary: the radius of the first and the last pass, the light vertices per
// pixel and pass (and how many were mergeable), the most memory one pass held.
inline std::string vcmSummary(const Scene& scene, int passes, const VcmTotals& vcm) {
    const double pixelPasses = double(passes) * scene.camera.width * scene.camera.height;
    char text[256];
    std::snprintf(text, sizeof text, "vcm: radius %g in pass 1, %g in pass %d; %.1f light vertices per pixel and pass, %.1f of them "
                  "mergeable; light subpaths and grid %.1f MB (%.0f bytes per light vertex)\n", vcm.firstRadius,
                  vcm.lastRadius, passes, vcm.lightVertices / pixelPasses, vcm.mergeable / pixelPasses,
                  vcm.mostBytes / 1e6, vcm.mostBytes * double(passes) / std::max(1.0, double(vcm.lightVertices)));
    return text;
}
