// classroom/figures.h: what the classroom's figures are made of: labels in a real typeface, the
// false-colour ratio of two images, and bdpt's per-strategy images laid out as the slides' pyramid.
#pragma once
#include "metrics.h"
#ifdef BDPT_STB_HEADER
#define STB_TRUETYPE_IMPLEMENTATION
#include <stb_truetype.h>
#else
#include <stb/stb_truetype.h>  // libstb-dev: the header here, its code in -lstb
#endif

// Labels burned into figures (the pyramid, --side-by-side, --ratio) are set in DejaVu Sans, Debian's
// fonts-dejavu-core and gnuplot's default sans: the charts and the figures share one typeface.
// A label of `scale` takes a line of 7 scale pixels (the font's ascent to its descent), white,
// its coverage blended over the image's sRGB bytes (blending in linear light makes text thin).
constexpr const char* kFontFile = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
struct LabelFont {
    std::vector<unsigned char> data;
    stbtt_fontinfo info{};
    bool ok = false;
};
inline const LabelFont& labelFont() {
    static const LabelFont font = [] {
        LabelFont f;
        std::ifstream in(kFontFile, std::ios::binary);
        f.data.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
        f.ok = !f.data.empty() && stbtt_InitFont(&f.info, f.data.data(), stbtt_GetFontOffsetForIndex(f.data.data(), 0)) != 0;
        return f;
    }();
    return font;
}
// Why labels cannot be drawn ("" if they can): checked before a render whose figure needs them.
inline std::string fontProblem() {
    return labelFont().ok ? "" : std::string("the figures' labels need the font ") + kFontFile + " (apt-get install fonts-dejavu-core)";
}

// Calls glyph(codepoint, x) for each character of text at `scale`, x its pen position; returns
// the text's advance in pixels.
template <class Glyph>
inline float layOutLabel(const std::string& text, int scale, const Glyph& glyph) {
    const LabelFont& font = labelFont();
    if (!font.ok) return 0;
    const float px = stbtt_ScaleForPixelHeight(&font.info, 7.0f * scale);
    float x = 0;
    for (size_t i = 0; i < text.size(); ++i) {
        int c = (unsigned char)text[i];
        glyph(c, x, px);
        int advance, bearing;
        stbtt_GetCodepointHMetrics(&font.info, c, &advance, &bearing);
        x += advance * px;
        if (i + 1 < text.size()) x += px * stbtt_GetCodepointKernAdvance(&font.info, c, (unsigned char)text[i + 1]);
    }
    return x;
}
inline int labelWidth(const std::string& text, int scale) { return int(std::ceil(layOutLabel(text, scale, [](int, float, float) {}))); }

inline void drawLabel(std::vector<unsigned char>& rgb, int width, int height, int x0, int y0, const std::string& text, int scale) {
    const LabelFont& font = labelFont();
    if (!font.ok) return;
    int ascent, descent, gap;
    stbtt_GetFontVMetrics(&font.info, &ascent, &descent, &gap);
    const int baseline = y0 + int(std::lround(ascent * stbtt_ScaleForPixelHeight(&font.info, 7.0f * scale)));
    std::vector<unsigned char> coverage;
    layOutLabel(text, scale, [&](int c, float x, float px) {
        int gx0, gy0, gx1, gy1;
        float shift = x - std::floor(x);
        stbtt_GetCodepointBitmapBoxSubpixel(&font.info, c, px, px, shift, 0, &gx0, &gy0, &gx1, &gy1);
        const int w = gx1 - gx0, h = gy1 - gy0;
        if (w <= 0 || h <= 0) return;
        coverage.assign(size_t(w) * h, 0);
        stbtt_MakeCodepointBitmapSubpixel(&font.info, coverage.data(), w, h, w, px, px, shift, 0, c);
        for (int y = 0; y < h; ++y)
            for (int xx = 0; xx < w; ++xx) {
                int X = x0 + int(std::floor(x)) + gx0 + xx, Y = baseline + gy0 + y, a = coverage[size_t(y) * w + xx];
                if (a == 0 || X < 0 || Y < 0 || X >= width || Y >= height) continue;
                for (int ch = 0; ch < 3; ++ch) {
                    unsigned char& v = rgb[3 * (size_t(Y) * width + X) + ch];
                    v = (unsigned char)(v + ((255 - v) * a + 127) / 255);
                }
            }
    });
}
// The labels' scale over an image `width` pixels wide: about 24 characters across, smaller if the
// widest line (its drawLabel width at scale 1) would not fit.
inline int labelScale(int width, int widest) { return std::max(1, std::min(std::max(2, width / 100), (width - 4) / std::max(1, widest))); }

// An image of w x h sRGB bytes copied into a canvas canvasW wide at (x0, y0), each pixel `zoom`
// times larger.
inline void blitZoomed(std::vector<unsigned char>& canvas, int canvasW, const std::vector<unsigned char>& rgb, int w, int h, int zoom,
                       int x0, int y0) {
    for (int y = 0; y < h * zoom; ++y)
        for (int x = 0; x < w * zoom; ++x)
            std::copy_n(&rgb[3 * (size_t(y / zoom) * w + x / zoom)], 3, &canvas[3 * (size_t(y0 + y) * canvasW + x0 + x)]);
}

// Where two methods differ: the ratio A/B of the two images' means over blocks of block x block
// pixels (the blocks average the noise away), as a false-colour image that is white where A = B,
// redder where A is brighter and bluer where darker, saturating at one stop; dark grey where
// both are black. Each block's pixels hold its ratio (the PFM).
inline Image blockRatio(const Image& a, const Image& b, int block) {
    Image r(a.width, a.height);
    for (int by = 0; by < a.height; by += block)
        for (int bx = 0; bx < a.width; bx += block) {
            double sa = 0, sb = 0;
            for (int y = by; y < std::min(a.height, by + block); ++y)
                for (int x = bx; x < std::min(a.width, bx + block); ++x) {
                    sa += double(a.at(x, y).x) + a.at(x, y).y + a.at(x, y).z;
                    sb += double(b.at(x, y).x) + b.at(x, y).y + b.at(x, y).z;
                }
            float ratio = sb > 0 ? float(sa / sb) : sa > 0 ? kInf : std::numeric_limits<float>::quiet_NaN();
            for (int y = by; y < std::min(a.height, by + block); ++y)
                for (int x = bx; x < std::min(a.width, bx + block); ++x) r.at(x, y) = Vec3(ratio);
        }
    return r;
}

inline Image ratioColours(const Image& ratio) {
    Image c(ratio.width, ratio.height);
    for (size_t i = 0; i < ratio.pixels.size(); ++i) {
        float q = ratio.pixels[i].x;
        if (std::isnan(q)) { c.pixels[i] = Vec3(0.03f); continue; }
        float t = std::max(-1.0f, std::min(1.0f, q > 0 ? std::log2(q) : -1.0f));
        c.pixels[i] = t >= 0 ? Vec3(1, 1 - t, 1 - t) : Vec3(1 + t, 1 + t, 1);
    }
    return c;
}


// --ratio's PNG: the false-colour ratio enlarged to at least 560 pixels across (two side by side
// fill a slide), under a strip that names the division, gives the ratio of the means and draws the
// colour key from 1/2 (blue) through 1 (white) to 2 (red).
inline std::vector<unsigned char> ratioFigure(const Image& ratio, const std::string& title, const std::string& means, int& figureW, int& figureH) {
    const int zoom = std::max(1, (560 + ratio.width - 1) / ratio.width), W = ratio.width * zoom;
    const int scale = labelScale(W, std::max(labelWidth(title, 1), labelWidth(means, 1)));
    const int gap = 2 * scale, line = 7 * scale, barH = 3 * scale, strip = 2 * line + barH + line + gap;
    figureW = W + 2 * gap, figureH = strip + ratio.height * zoom + 2 * gap;
    std::vector<unsigned char> canvas(size_t(figureW) * figureH * 3, 24);
    blitZoomed(canvas, figureW, toSRGBBytes(ratioColours(ratio), 0), ratio.width, ratio.height, zoom, gap, gap + strip);
    Image key(W, 1);
    for (int x = 0; x < W; ++x) key.pixels[x] = Vec3(std::exp2(2.0f * (x + 0.5f) / W - 1));  // log2 from -1 to 1
    std::vector<unsigned char> keyRGB = toSRGBBytes(ratioColours(key), 0);
    for (int y = 0; y < barH; ++y) blitZoomed(canvas, figureW, keyRGB, W, 1, 1, gap, gap + 2 * line + y);
    drawLabel(canvas, figureW, figureH, gap, gap, title, scale);
    drawLabel(canvas, figureW, figureH, gap, gap + line, means, scale);
    const int keyY = gap + 2 * line + barH + scale;
    drawLabel(canvas, figureW, figureH, gap, keyY, "1/2", scale);
    drawLabel(canvas, figureW, figureH, gap + W / 2 - labelWidth("1", scale) / 2, keyY, "1", scale);
    drawLabel(canvas, figureW, figureH, gap + W - labelWidth("2", scale), keyY, "2", scale);
    return canvas;
}

// The two files of a ratio as its title names them: their stems, or where the stems are the same
// (two folders of strategy images) their folders' names too: "bdpt/s4_t1_weighted".
inline std::string ratioTitle(const std::string& a, const std::string& b) {
    auto named = [](const std::string& path) {
        size_t slash = path.find_last_of('/');
        std::string dir = slash == std::string::npos ? "" : path.substr(0, slash);
        return (dir.empty() ? "" : fileStem(dir) + "/") + fileStem(path);
    };
    return fileStem(a) == fileStem(b) ? named(a) + " / " + named(b) : fileStem(a) + " / " + fileStem(b);
}

// --ratio: A/B over 4x4 blocks as a labelled false-colour PNG and a PFM of the ratios (0 where
// undefined), and its percentiles on out. Returns the exit status.
inline int writeRatio(const Image& a, const Image& b, const std::string& nameA, const std::string& nameB, const std::string& png,
                      std::ostream& out, std::ostream& err) {
    Image r = blockRatio(a, b, 4);
    std::vector<float> q;
    for (const Vec3& p : r.pixels)
        if (std::isfinite(p.x)) q.push_back(p.x);
    if (q.empty()) {
        err << "bdpt: cannot divide: B is black in every 4x4 block, so A/B is nowhere defined\n";
        return 2;
    }
    std::sort(q.begin(), q.end());
    auto pct = [&](double f) { return q[size_t(f * (q.size() - 1))]; };
    size_t off = size_t(std::count_if(q.begin(), q.end(), [](float v) { return std::fabs(std::log2(v)) > 0.5f; }));
    out << "ratio of means " << imageMean(a) / imageMean(b) << "; A/B over 4x4 blocks: 5% " << pct(0.05) << ", median "
        << pct(0.5) << ", 95% " << pct(0.95) << "; " << 100.0 * off / std::max<size_t>(1, q.size())
        << "% of the blocks more than half a stop apart\n";
    std::string pfm = replaceExtension(png, ".pfm");
    char means[64];
    std::snprintf(means, sizeof means, "ratio of means %.3f", imageMean(a) / imageMean(b));
    int figureW, figureH;
    std::vector<unsigned char> figure = ratioFigure(r, ratioTitle(nameA, nameB), means, figureW, figureH);
    for (Vec3& p : r.pixels) p = std::isfinite(p.x) ? p : Vec3(0);
    if (writePNGBytes(figure, figureW, figureH, png) && writePFM(r, pfm)) {
        out << "wrote " << png << " and " << pfm << "\n";
        return 0;
    }
    err << "bdpt: cannot write " << png << " or " << pfm << "\n";
    return 1;
}


// The pyramid's rows differ by orders of magnitude (each bounce keeps about the albedo), so each
// row k is brightened by whole stops until its light, the sum of its weighted tiles, comes within
// half a stop of the brightest row's; the tile's label prints them ("s1 t3 +2").
inline std::vector<int> pyramidRowStops(const StrategyImages& strategies) {
    const int maxLength = strategies.maxLength;
    std::vector<double> rowMean(maxLength + 1, 0);
    strategies.forEach([&](int k, int, int index) { rowMean[k] += imageMean(strategies.images[2 * size_t(index) + 1]); });
    double brightest = *std::max_element(rowMean.begin(), rowMean.end());
    std::vector<int> stops(maxLength + 1, 0);
    for (int k = 1; k <= maxLength; ++k)
        if (rowMean[k] > 0) stops[k] = std::min(12, int(std::lround(std::log2(brightest / rowMean[k]))));
    return stops;
}

// The slides' "Contributions of different paths" as a pyramid: row k = path length (segments),
// column s = vertices from the light (t = k+1-s from the camera), one image per strategy p_{k,s}.
// Each tile's label sits in a strip above it, never on the image: the lamp, row 1's whole
// content, lies at the top of the frame.
// Each row is labelled with its k in a margin on the left.
// Two title lines over it say what the tiles are and what a label's "+N" means; the canvas is
// padded to 16:9, the pyramid centred.
struct PyramidLayout {
    bool merges;  // vcm: a column "m k" of merges
    int W, H, gap = 4, scale, strip, margin, rowH, titleH, contentW, contentH, canvasW, canvasH, left, top;
    PyramidLayout(int width, int height, int maxLength, bool withMerges)
        : merges(withMerges), W(width), H(height), scale(std::max(1, std::min(width / 40, height / 32))), strip(7 * scale),
          margin(labelWidth("k=" + std::to_string(maxLength), scale) + 2 * gap), rowH(strip + H + gap), titleH(2 * 7 * scale + 3 * gap),
          contentW(margin + (maxLength + 1 + merges) * (W + gap) + gap), contentH(titleH + maxLength * rowH + gap) {
        canvasW = std::max(contentW, (contentH * 16 + 8) / 9), canvasH = std::max(contentH, (canvasW * 9 + 15) / 16);
        left = (canvasW - contentW) / 2, top = (canvasH - contentH) / 2;
    }
    int tileX(int k, int s, int maxLength) const { return left + margin + gap + (maxLength - k) * (W + gap) / 2 + s * (W + gap); }
    int tileY(int k) const { return top + titleH + gap + (k - 1) * rowH + strip; }
};

inline std::string tileName(int k, int s) {  // "s1 t3", or "m k3" for the merges
    return s == k + 1 ? "m k" + std::to_string(k) : "s" + std::to_string(s) + " t" + std::to_string(k + 1 - s);
}

// The montage of one kind (weighted or not), as sRGB bytes of layout.canvasW x layout.canvasH.
inline std::vector<unsigned char> pyramidCanvas(const StrategyImages& strategies, float exposure, bool weighted, const PyramidLayout& layout,
                                                const std::vector<int>& rowStops) {
    std::vector<unsigned char> canvas(size_t(layout.canvasW) * layout.canvasH * 3, 40);
    strategies.forEach([&](int k, int s, int index) {
        std::vector<unsigned char> tile = toSRGBBytes(strategies.images[2 * size_t(index) + weighted], exposure + rowStops[k]);
        int x0 = layout.tileX(k, s, strategies.maxLength), y0 = layout.tileY(k);
        blitZoomed(canvas, layout.canvasW, tile, layout.W, layout.H, 1, x0, y0);
        std::string label = tileName(k, s) + (rowStops[k] > 0 ? " +" + std::to_string(rowStops[k]) : "");
        drawLabel(canvas, layout.canvasW, layout.canvasH, x0, y0 - layout.strip, label, layout.scale);
        if (s == 0)
            drawLabel(canvas, layout.canvasW, layout.canvasH, layout.left + layout.gap, y0 + (layout.H - layout.strip) / 2, "k=" + std::to_string(k),
                      layout.scale);
    });
    const std::string title[2] = {
        weighted ? "Contributions of different paths, MIS-weighted: w_{s,t} <C_{s,t}>; each row k sums to the paths of k segments"
                 : "Contributions of different paths, unweighted: <C_{s,t}> alone; each tile of row k estimates all of it",
        "row k: path length; s vertices from the light, t from the eye; \"+N\": the row brightened N stops to be seen"};
    for (int line = 0; line < 2; ++line) {
        const int scale = std::max(1, std::min(layout.scale, (layout.canvasW - 8) / std::max(1, labelWidth(title[line], 1))));
        drawLabel(canvas, layout.canvasW, layout.canvasH, (layout.canvasW - labelWidth(title[line], scale)) / 2,
                  layout.top + layout.gap + line * 7 * layout.scale, title[line], scale);
    }
    return canvas;
}

// The two labelled pyramids (unweighted and MIS-weighted) beside the strategy images in dir.
inline bool writePyramids(const StrategyImages& strategies, const std::string& dir, float exposure, std::ostream& out) {
    if (strategies.images.empty()) return true;
    const int maxLength = strategies.maxLength;
    const PyramidLayout layout(strategies.images[0].width, strategies.images[0].height, maxLength, strategies.merges);
    const std::vector<int> rowStops = pyramidRowStops(strategies);
    for (int weighted = 0; weighted < 2; ++weighted) {
        std::string pyramid = dir + (weighted ? "/pyramid-weighted.png" : "/pyramid-unweighted.png");
        if (!writePNGBytes(pyramidCanvas(strategies, exposure, weighted, layout, rowStops), layout.canvasW, layout.canvasH, pyramid))
            return false;
        out << "wrote " << pyramid << "\n";
    }
    out << "pyramid rows k = 1.." << maxLength << " brightened by";
    for (int k = 1; k <= maxLength; ++k) out << " +" << rowStops[k];
    out << " stops (printed in each tile's label)\n";
    return true;
}
