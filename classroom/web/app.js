// The page: up to six panels, each a Web Worker rendering one method (worker.js); this thread only
// draws: the panels, the error-against-time chart, bdpt's pyramid and a pixel's strategy chart.
// window.bdptPage is what make test-web drives (tests/test_web.py).
"use strict";

const MAX_PANELS = 6;
const COLOURS = ["#ff6b6b", "#4dabf7", "#51cf66", "#fcc419", "#cc5de8", "#e9ecef"];
const $ = (id) => document.getElementById(id);

const state = {
    workers: [],          // one per panel slot, created at load so that Start renders at once
    ready: 0,
    panels: [],           // the running or finished panels
    running: false,
    startedAt: 0,
    pixel: null,          // {x, y}: the pixel whose strategies the bar chart shows
    strategyPanel: null,  // the panel whose strategies the pyramid shows
    nextId: 1,
    whenDone: null,       // resolves run()'s promise
};

// ---- tone mapping: the PNG's sRGB curve (bdpt.cpp's toSRGB8), the scene's exposure plus the slider's.
function srgb8(linear) {
    const v = linear <= 0.0031308 ? 12.92 * linear : 1.055 * Math.pow(linear, 1 / 2.4) - 0.055;
    return Math.floor(Math.min(1, Math.max(0, v)) * 255 + 0.5);
}
function toImageData(rgb, w, h, stops) {
    const scale = Math.pow(2, stops), data = new ImageData(w, h);
    for (let i = 0; i < w * h; ++i) {
        for (let c = 0; c < 3; ++c) data.data[4 * i + c] = srgb8(rgb[3 * i + c] * scale);
        data.data[4 * i + 3] = 255;
    }
    return data;
}
const sliderStops = () => Number($("exposure").value);
const fmt = (x) => (x === null || x === undefined || !isFinite(x) ? "–" : Number(x).toPrecision(3));
const luminance = (rgb, i) => (rgb[3 * i] + rgb[3 * i + 1] + rgb[3 * i + 2]) / 3;

// ---- scenes
function sceneName() { return $("scene").value; }
function sceneText() { return $("scene-text").value; }
function loadSceneList() {
    const names = Object.keys(BDPT_SCENES).sort();
    for (const name of names) {
        const o = document.createElement("option");
        o.value = name;
        o.textContent = name.replace(/^scenes\//, "").replace(/\.scene$/, "");
        $("scene").append(o);
    }
    $("scene").value = "scenes/cornell.scene";
    $("scene-text").value = BDPT_SCENES[sceneName()];
}

// ---- workers
function createWorkers() {
    for (let i = 0; i < MAX_PANELS; ++i) {
        const w = new Worker("worker.js");
        w.onmessage = (e) => onWorkerMessage(i, e.data);
        w.onerror = (e) => showStatus("A worker failed: " + e.message);
        state.workers.push(w);
    }
}

function onWorkerMessage(slot, m) {
    if (m.type === "ready") {
        if (++state.ready === MAX_PANELS) { $("start").disabled = false; showStatus("Ready: choose a scene and methods, then Start (Space)."); }
        return;
    }
    if (m.type === "checked") { state.onChecked && state.onChecked(m.error); return; }
    const panel = state.panels.find((p) => p.slot === slot && p.id === m.id);
    if (!panel) return;  // a message from a run that was replaced
    if (m.type === "error") {
        panel.error = m.error;
        panel.done = true;
        panel.el.querySelector(".error").textContent = m.error;
    } else if (m.type === "started") {
        panel.exposure = m.exposure;
        panel.hasReference = m.hasReference;
        if (m.strategies && !state.strategyPanel) state.strategyPanel = panel;
    } else if (m.type === "frame" || m.type === "done") {
        Object.assign(panel, { width: m.width, height: m.height, passes: m.passes, seconds: m.seconds, image: m.image, mean: m.mean,
                               rmse: m.rmse, rmseWithoutLamp: m.rmseWithoutLamp, nonFinite: m.nonFinite, outOfMemory: m.outOfMemory });
        if (m.strategies) panel.strategies = m.strategies;
        if (panel.firstFrameMs === null) panel.firstFrameMs = performance.now() - state.startedAt;
        if (m.rmseWithoutLamp !== null) panel.curve.push([m.seconds, m.rmseWithoutLamp]);
        if (m.type === "done") panel.done = true;
        panel.dirty = true;
    }
    if (state.panels.every((p) => p.done)) finishRun();
}

// ---- a run
function entries() {
    return [...document.querySelectorAll("input.entry")].map((e) => e.value.trim()).filter((e) => e);
}
function options() {
    const [w, h] = $("resolution").value.split("x").map(Number);
    return { width: w, height: h, seconds: Math.max(0, Number($("seconds").value) || 0), spp: Math.max(0, Math.floor(Number($("spp").value) || 0)),
             seed: Math.max(1, Math.floor(Number($("seed").value) || 1)) };
}

// The scene's text is checked first: its error (file:line, as ./bdpt prints it) stops the run.
function checkScene() {
    return new Promise((resolve) => {
        state.onChecked = (error) => { state.onChecked = null; resolve(error); };
        state.workers[0].postMessage({ type: "check", id: 0, sceneText: sceneText(), sceneName: sceneName() });
    });
}

async function start() {
    if (state.running || state.ready < MAX_PANELS) return;
    const list = entries();
    if (list.length === 0) { showStatus("Name at least one method."); return; }
    const error = await checkScene();
    $("scene-error").hidden = !error;
    $("scene-error").textContent = error;
    if (error) { showStatus("The scene has an error: nothing rendered."); return; }
    const opt = options();
    $("panels").replaceChildren();
    state.panels = [];
    state.strategyPanel = null;
    state.running = true;
    state.startedAt = performance.now();
    list.forEach((entry, slot) => {
        const panel = makePanel(entry, slot, opt);
        state.panels.push(panel);
        // The first bdpt or vcm panel records its strategies for the pyramid (paths up to 4 segments).
        panel.wantsStrategies = /^(bdpt|vcm)\b/.test(entry) && !state.panels.some((p) => p.wantsStrategies);
        state.workers[slot].postMessage({ type: "start", id: panel.id, sceneText: sceneText(), sceneName: sceneName(), entry,
                                          width: opt.width, height: opt.height, seed: opt.seed, spp: opt.spp, seconds: opt.seconds,
                                          strategyLength: panel.wantsStrategies ? 4 : 0 });
    });
    $("start").disabled = true;
    $("stop").disabled = false;
    state.lastFrame = undefined;
    state.longestFrameGap = 0;
    requestAnimationFrame(draw);
    return new Promise((resolve) => { state.whenDone = resolve; });
}

function stop() {
    if (!state.running) return;
    state.panels.forEach((p) => { if (!p.done) state.workers[p.slot].postMessage({ type: "stop" }); });
}

function finishRun() {
    if (!state.running) return;
    state.running = false;
    $("start").disabled = false;
    $("stop").disabled = true;
    drawAll();
    showStatus(runningText(true));
    if (state.whenDone) { const r = state.whenDone; state.whenDone = null; r(); }
}

function runningText(done) {
    const name = $("scene").selectedOptions[0].textContent, opt = options();
    const wall = ((performance.now() - state.startedAt) / 1000).toFixed(1);
    const budget = opt.spp > 0 ? `${opt.spp} samples per pixel` : opt.seconds > 0 ? `${opt.seconds} s each` : "until Stop";
    return `${done ? "Done" : "Running"}: ${name} at ${opt.width}×${opt.height}, ${state.panels.length} panels, ${budget}; ${wall} s since Start`;
}
function showStatus(text) { $("status").textContent = text; }

// ---- panels
function makePanel(entry, slot, opt) {
    const el = document.createElement("article");
    el.className = "panel";
    el.style.setProperty("--colour", COLOURS[slot]);
    el.innerHTML = `<h2></h2><canvas width="${opt.width}" height="${opt.height}"></canvas><div class="stats">starting…</div>
        <div class="error"></div><div class="downloads"><button data-kind="png">PNG</button> <button data-kind="pfm">PFM</button></div>`;
    el.querySelector("h2").textContent = entry;
    const canvas = el.querySelector("canvas");
    canvas.style.aspectRatio = `${opt.width} / ${opt.height}`;
    canvas.addEventListener("click", (e) => {
        const r = canvas.getBoundingClientRect();
        choosePixel(Math.floor((e.clientX - r.left) / r.width * opt.width), Math.floor((e.clientY - r.top) / r.height * opt.height));
    });
    const panel = { id: state.nextId++, slot, entry, el, canvas, curve: [], passes: 0, seconds: 0, done: false, dirty: false, error: null,
                    exposure: 0, hasReference: false, image: null, strategies: null, firstFrameMs: null };
    el.querySelector('[data-kind="png"]').onclick = () => downloadPNG(panel);
    el.querySelector('[data-kind="pfm"]').onclick = () => downloadPFM(panel);
    $("panels").append(el);
    return panel;
}

function drawPanel(panel) {
    if (!panel.image) return;
    panel.canvas.getContext("2d").putImageData(toImageData(panel.image, panel.width, panel.height, panel.exposure + sliderStops()), 0, 0);
    if (state.pixel) {
        const g = panel.canvas.getContext("2d");
        g.strokeStyle = "#00ffff";
        g.lineWidth = Math.max(1, panel.width / 128);
        g.strokeRect(state.pixel.x - 1.5, state.pixel.y - 1.5, 4, 4);
    }
    const error = panel.rmse === null ? "no reference at this size" : `RMSE <b>${fmt(panel.rmseWithoutLamp)}</b> (${fmt(panel.rmse)} with the lamp's pixels)`;
    panel.el.querySelector(".stats").innerHTML = `<b>${panel.passes}</b> spp · <b>${panel.seconds.toFixed(1)}</b> s · ${error}` +
        (panel.nonFinite > 0 ? ` · ${panel.nonFinite} non-finite dropped` : "") + (panel.outOfMemory ? " · out of memory: stopped" : "");
}

function fileStem(panel) {
    const scene = sceneName().replace(/^.*\//, "").replace(/\.scene$/, "");
    return `${scene}-${panel.entry.replace(/[^A-Za-z0-9.]+/g, "-")}-${panel.passes}spp`;
}
function save(blob, name) {
    const a = document.createElement("a");
    a.href = URL.createObjectURL(blob);
    a.download = name;
    a.click();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}
function downloadPNG(panel) {
    if (!panel.image) return;
    const c = document.createElement("canvas");
    c.width = panel.width, c.height = panel.height;
    c.getContext("2d").putImageData(toImageData(panel.image, panel.width, panel.height, panel.exposure + sliderStops()), 0, 0);
    c.toBlob((b) => save(b, fileStem(panel) + ".png"), "image/png");
}
// PFM as ./bdpt writes it: little-endian floats, rows from the bottom.
function pfmBytes(rgb, w, h) {
    const header = new TextEncoder().encode(`PF\n${w} ${h}\n-1\n`);
    const body = new Float32Array(3 * w * h);
    for (let y = 0; y < h; ++y) body.set(rgb.subarray(3 * w * (h - 1 - y), 3 * w * (h - y)), 3 * w * y);
    return new Blob([header, body.buffer]);
}
function downloadPFM(panel) { if (panel.image) save(pfmBytes(panel.image, panel.width, panel.height), fileStem(panel) + ".pfm"); }

// ---- error against time, log axes, one curve per panel with a reference
function drawChart() {
    const svg = $("chart"), W = 900, H = 460, left = 80, right = 250, top = 15, bottom = 60;
    const points = state.panels.flatMap((p) => p.curve).filter(([t, e]) => t > 0 && e > 0);
    let html = "";
    if (points.length < 2) {
        html = `<text x="${W / 2}" y="${H / 2}" text-anchor="middle" font-size="22">${
            state.panels.length && !state.panels.some((p) => p.hasReference) ? "no reference for this scene at this size" : "the curves appear as the panels render"}</text>`;
        svg.innerHTML = html;
        return;
    }
    const lx = (t) => Math.log10(t), ts = points.map((p) => lx(p[0])), es = points.map((p) => lx(p[1]));
    const x0 = Math.floor(Math.min(...ts)), x1 = Math.max(x0 + 1, Math.ceil(Math.max(...ts)));
    const y0 = Math.floor(Math.min(...es)), y1 = Math.max(y0 + 1, Math.ceil(Math.max(...es)));
    const X = (t) => left + (lx(t) - x0) / (x1 - x0) * (W - left - right), Y = (e) => H - bottom - (lx(e) - y0) / (y1 - y0) * (H - top - bottom);
    for (let d = x0; d <= x1; ++d) {
        const x = X(10 ** d);
        html += `<line x1="${x}" x2="${x}" y1="${top}" y2="${H - bottom}" stroke="#444"/><text x="${x}" y="${H - bottom + 24}" text-anchor="middle" font-size="18">${10 ** d >= 1 ? 10 ** d : (10 ** d).toPrecision(1)}</text>`;
    }
    for (let d = y0; d <= y1; ++d) {
        const y = Y(10 ** d);
        html += `<line x1="${left}" x2="${W - right}" y1="${y}" y2="${y}" stroke="#444"/><text x="${left - 8}" y="${y + 6}" text-anchor="end" font-size="18">1e${d}</text>`;
    }
    html += `<text x="${(left + W - right) / 2}" y="${H - 12}" text-anchor="middle" font-size="18">seconds of rendering (each panel its own)</text>`;
    html += `<text transform="translate(20 ${(top + H - bottom) / 2}) rotate(-90)" text-anchor="middle" font-size="18">RMSE without the lamp's pixels</text>`;
    state.panels.forEach((p, i) => {
        const c = p.curve.filter(([t, e]) => t > 0 && e > 0);
        if (c.length) html += `<polyline fill="none" stroke="${COLOURS[p.slot]}" stroke-width="3" points="${c.map(([t, e]) => `${X(t).toFixed(1)},${Y(e).toFixed(1)}`).join(" ")}"/>`;
        const ly = top + 14 + i * 30;
        html += `<line x1="${W - right + 16}" x2="${W - right + 46}" y1="${ly}" y2="${ly}" stroke="${COLOURS[p.slot]}" stroke-width="4"/>` +
                `<text x="${W - right + 54}" y="${ly + 6}" font-size="16">${escapeXml(shorten(p.entry, 21))}${c.length ? "" : " (no curve)"}</text>`;
    });
    svg.innerHTML = html;
}
const escapeXml = (s) => s.replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;");
const shorten = (s, n) => (s.length > n ? s.slice(0, n - 1) + "…" : s);

// ---- bdpt's pyramid: row k = path length in segments, column s = vertices from the light, each
// row brightened by whole stops to the brightest row's level (each bounce keeps about the albedo).
function pyramidGeometry(panel) {
    const L = Math.max(...panel.strategies.map((s) => s.k)), merges = panel.strategies.some((s) => s.s === s.k + 1);
    const w = panel.width, h = panel.height, gap = Math.max(2, w >> 4), strip = Math.max(14, h >> 2), margin = Math.max(40, w >> 1);
    return { L, w, h, gap, strip, margin, cols: L + 1 + (merges ? 1 : 0),
             tileX: (k, s) => margin + gap + (L - k) * (w + gap) / 2 + s * (w + gap), tileY: (k) => gap + (k - 1) * (strip + h + gap) + strip };
}
function rowStops(panel, weighted) {
    const L = Math.max(...panel.strategies.map((s) => s.k)), rows = new Array(L + 1).fill(0);
    for (const st of panel.strategies) {
        const img = weighted ? st.weighted : st.unweighted;
        let sum = 0;
        for (let i = 0; i < img.length; ++i) sum += img[i];
        rows[st.k] += sum;
    }
    const brightest = Math.max(...rows);
    return rows.map((r) => (r > 0 ? Math.min(12, Math.round(Math.log2(brightest / r))) : 0));
}
function drawPyramid() {
    const panel = state.strategyPanel, canvas = $("pyramid");
    if (!panel || !panel.strategies) return;
    const weighted = $("weighted").checked, g = pyramidGeometry(panel), stops = rowStops(panel, weighted);
    const W = g.margin + g.cols * (g.w + g.gap) + g.gap, H = g.L * (g.strip + g.h + g.gap) + g.gap;
    // drawn at 4 canvas pixels per image pixel so that the labels are sharp
    const z = Math.max(1, Math.round(512 / g.h));
    if (canvas.width !== W * z || canvas.height !== H * z) canvas.width = W * z, canvas.height = H * z;
    const c = canvas.getContext("2d");
    c.imageSmoothingEnabled = false;
    c.fillStyle = "#282828";
    c.fillRect(0, 0, canvas.width, canvas.height);
    const tile = document.createElement("canvas");
    tile.width = g.w, tile.height = g.h;
    c.fillStyle = "#e8e8e8";
    c.font = `${Math.round(g.strip * z * 0.7)}px "DejaVu Sans", sans-serif`;
    c.textBaseline = "bottom";
    for (const st of panel.strategies) {
        const x = g.tileX(st.k, st.s), y = g.tileY(st.k);
        tile.getContext("2d").putImageData(toImageData(weighted ? st.weighted : st.unweighted, g.w, g.h, panel.exposure + sliderStops() + stops[st.k]), 0, 0);
        c.drawImage(tile, x * z, y * z, g.w * z, g.h * z);
        c.fillText(st.s === st.k + 1 ? `merge k=${st.k}` : `s=${st.s} t=${st.k + 1 - st.s}`, x * z, (y - 1) * z);
    }
    for (let k = 1; k <= g.L; ++k) {
        c.fillText(`k=${k}`, g.gap * z, (g.tileY(k) + g.h / 2) * z);
        if (stops[k]) c.fillText(`+${stops[k]}`, g.gap * z, (g.tileY(k) + g.h / 2 + g.strip) * z);
    }
    $("pyramid-caption").textContent = `${panel.entry}, ${panel.passes} spp: ${weighted ? "MIS-weighted (the strategies of a row sum to that row of the image)" : "unweighted (each strategy alone, as if it were the only one)"}; ` +
        `row k = path length in segments, s = vertices from the light, t = from the camera; "+N": the row brightened by N stops (x 2^N) to show it`;
}
function pyramidPixel(e) {
    const panel = state.strategyPanel;
    if (!panel || !panel.strategies) return;
    const canvas = $("pyramid"), r = canvas.getBoundingClientRect(), g = pyramidGeometry(panel);
    const z = canvas.width / (g.margin + g.cols * (g.w + g.gap) + g.gap);
    const px = (e.clientX - r.left) / r.width * canvas.width / z, py = (e.clientY - r.top) / r.height * canvas.height / z;
    for (const st of panel.strategies) {
        const x = g.tileX(st.k, st.s), y = g.tileY(st.k);
        if (px >= x && px < x + g.w && py >= y && py < y + g.h) { choosePixel(Math.floor(px - x), Math.floor(py - y)); return; }
    }
}

// ---- a pixel's strategies: each (s,t)'s contribution there, unweighted and MIS-weighted
function choosePixel(x, y) {
    state.pixel = { x, y };
    drawAll();
    return strategyBars();
}
function strategyBars() {
    const panel = state.strategyPanel;
    if (!state.pixel || !panel || !panel.strategies) return [];
    const i = state.pixel.y * panel.width + state.pixel.x;
    return panel.strategies.map((st) => ({ k: st.k, s: st.s, t: st.k + 1 - st.s, merge: st.s === st.k + 1,
                                          unweighted: luminance(st.unweighted, i), weighted: luminance(st.weighted, i) }));
}
function drawBars() {
    const svg = $("bars"), bars = strategyBars(), W = 900, H = 300, left = 80, bottom = 60, top = 20;
    if (!bars.length) {
        svg.innerHTML = `<text x="${W / 2}" y="${H / 2}" text-anchor="middle" font-size="22">${state.strategyPanel ? "click a pixel" : "needs a bdpt or vcm panel"}</text>`;
        return;
    }
    const panel = state.strategyPanel, i = state.pixel.y * panel.width + state.pixel.x;
    const max = Math.max(1e-30, ...bars.map((b) => Math.max(b.unweighted, b.weighted)));
    const slot = (W - left - 20) / bars.length, bw = slot * 0.38, Y = (v) => H - bottom - v / max * (H - top - bottom);
    let html = `<line x1="${left}" x2="${W - 20}" y1="${H - bottom}" y2="${H - bottom}" stroke="#888"/>` +
               `<text x="${left - 8}" y="${top + 6}" text-anchor="end" font-size="16">${fmt(max)}</text><text x="${left - 8}" y="${H - bottom}" text-anchor="end" font-size="16">0</text>`;
    bars.forEach((b, j) => {
        const x = left + j * slot + slot * 0.1, name = b.merge ? `m k${b.k}` : `s${b.s} t${b.t}`;
        html += `<rect x="${x}" y="${Y(b.unweighted)}" width="${bw}" height="${H - bottom - Y(b.unweighted)}" fill="#8a8f98" data-strategy="${name}" data-kind="unweighted" data-value="${b.unweighted}"/>` +
                `<rect x="${x + bw}" y="${Y(b.weighted)}" width="${bw}" height="${H - bottom - Y(b.weighted)}" fill="#ffb000" data-strategy="${name}" data-kind="weighted" data-value="${b.weighted}"/>` +
                `<text x="${x + bw}" y="${H - bottom + 20}" text-anchor="middle" font-size="15">${name}</text>` +
                (j === 0 || bars[j - 1].k !== b.k ? `<text x="${x}" y="${H - bottom + 42}" font-size="15" fill="#a0a4ab">k=${b.k}</text>` : "");
    });
    const sum = bars.reduce((a, b) => a + b.weighted, 0);
    svg.innerHTML = html;
    $("bars-caption").textContent = `Pixel (${state.pixel.x}, ${state.pixel.y}) of ${panel.entry}: each strategy's contribution, grey unweighted (its own estimate), ` +
        `amber MIS-weighted; the weighted ones sum to ${fmt(sum)} of the pixel's ${fmt(luminance(panel.image, i))} (paths up to ${Math.max(...bars.map((b) => b.k))} segments)`;
}

// ---- drawing, at most once per display frame
function drawAll() {
    state.panels.forEach(drawPanel);
    drawChart();
    drawPyramid();
    drawBars();
    $("exposure-value").textContent = `${sliderStops() >= 0 ? "+" : ""}${sliderStops()} stops`;
}
function draw(now) {
    if (state.lastFrame !== undefined && now !== undefined) state.longestFrameGap = Math.max(state.longestFrameGap, now - state.lastFrame);
    state.lastFrame = now;
    if (state.panels.some((p) => p.dirty)) {
        state.panels.forEach((p) => (p.dirty = false));
        drawAll();
    }
    if (state.running) {
        showStatus(runningText(false));
        requestAnimationFrame(draw);
    }
}

// ---- controls and keys
function selectScene(name) {
    $("scene").value = name;
    $("scene-text").value = BDPT_SCENES[name];
    $("scene-error").hidden = true;
}
function bindControls() {
    $("start").onclick = start;
    $("stop").onclick = stop;
    $("scene").onchange = () => selectScene(sceneName());
    $("scene-reset").onclick = () => selectScene(sceneName());
    $("exposure").oninput = drawAll;
    $("weighted").onchange = drawAll;
    $("pyramid").addEventListener("click", pyramidPixel);
    document.addEventListener("keydown", (e) => {
        if (e.target.matches("input:not([type=range]):not([type=checkbox]), textarea, select")) return;  // typing
        const ex = $("exposure");
        if (e.key === " ") { e.preventDefault(); state.running ? stop() : start(); }
        else if (e.key === "Escape") stop();
        else if (e.key === "+" || e.key === "=") { ex.value = Number(ex.value) + 0.5; drawAll(); }
        else if (e.key === "-") { ex.value = Number(ex.value) - 0.5; drawAll(); }
        else if (e.key === "w" || e.key === "W") { $("weighted").checked = !$("weighted").checked; drawAll(); }
        else if (/^[1-9]$/.test(e.key) && !state.running) {
            const o = $("scene").options[Number(e.key) - 1];
            if (o) selectScene(o.value);
        }
    });
}

// ---- what make test-web drives
window.bdptPage = {
    ready: () => state.ready === MAX_PANELS,
    selectScene,
    setSceneText: (text) => { $("scene-text").value = text; },
    setEntries: (list) => document.querySelectorAll("input.entry").forEach((e, i) => { e.value = list[i] || ""; }),
    setOptions: (o) => {
        if (o.resolution) $("resolution").value = o.resolution;
        for (const k of ["seconds", "spp", "seed"]) if (k in o) $(k).value = o[k];
    },
    run: () => start(),
    stop,
    longestFrameGap: () => state.longestFrameGap,  // ms between two drawn frames during the last run
    sceneError: () => ($("scene-error").hidden ? "" : $("scene-error").textContent),
    panels: () => state.panels.map((p) => ({ entry: p.entry, passes: p.passes, seconds: p.seconds, mean: p.mean, rmse: p.rmse, error: p.error,
                                             nonFinite: p.nonFinite, firstFrameMs: p.firstFrameMs, curvePoints: p.curve.length,
                                             strategies: p.strategies ? p.strategies.length : 0 })),
    clickPixel: (panelIndex, x, y) => {
        const p = state.panels[panelIndex], r = p.canvas.getBoundingClientRect();
        p.canvas.dispatchEvent(new MouseEvent("click", { clientX: r.left + (x + 0.5) / p.width * r.width, clientY: r.top + (y + 0.5) / p.height * r.height, bubbles: true }));
        return [...$("bars").querySelectorAll("rect")].map((b) => ({ strategy: b.dataset.strategy, kind: b.dataset.kind, value: Number(b.dataset.value) }));
    },
};

loadSceneList();
bindControls();
createWorkers();
drawAll();
