// The page: the lecture notes beside up to six panels, each a Web Worker rendering one method
// (worker.js, started from engine.js's text, so that the page also opens from a file); this
// thread only draws: the panels, the error-against-time chart, bdpt's pyramid and a pixel's
// strategy chart. window.bdptPage is what make test-web drives (tests/test_web.py).
"use strict";

const MAX_PANELS = 6;
const COLOURS = ["#ff6b6b", "#4dabf7", "#51cf66", "#fcc419", "#cc5de8", "#e9ecef"];
const $ = (id) => document.getElementById(id);

// ---- what the page says about each method and each deliberate mistake (the slides' captions
// (a)-(f) and the notes' pages)
const METHODS = {
    pt: "(a) Unidirectional eye tracing: a path counts light only when it hits a lamp by chance (page 1).",
    nee: "(b) Eye tracing with next event: at every diffuse hit a shadow ray to a point on a lamp (page 2).",
    "nee --mis": "(b) with MIS: next event and hitting the lamp combined by the balance heuristic (page 10).",
    lt: "(c) Light tracing: paths from the lamps, each hit joined to the camera; it cannot see a mirror or glass from the camera (page 2).",
    ir: "(d) Instant radiosity: light paths stored as virtual point lights, gathered at the eye's first diffuse hit; bright blotches in corners (page 1).",
    "ir --clamp": "(e) Instant radiosity clamped: the blotches gone, and their energy with them: biased (page 1).",
    bdpt: "(f) Bidirectional path tracing: every (s,t) strategy of a path, weighted by MIS, balance heuristic (pages 3-11).",
    "bdpt --heuristic power": "(f) with the power heuristic (exponent 2): the best strategy weighted more (page 10).",
    "bdpt --heuristic max": "(f) with the maximum heuristic: each path to its one best strategy (page 10).",
    "bdpt --heuristic uniform": "(f) with uniform weights 1/(number of strategies): unbiased, but the noise of every strategy (page 10).",
    vcm: "Vertex connection and merging: bdpt plus merging an eye vertex with nearby light vertices, for L S D S E caustics; biased, consistent (page 15).",
    pssmlt: "Metropolis on primary samples (Kelemen): a Markov chain mutates a bdpt path's random numbers (page 16).",
    mmlt: "Multiplexed Metropolis: chains over the random numbers, the path length and the strategy (page 16).",
    mlt: "Veach's Metropolis light transport: the chain mutates the paths themselves (page 17).",
};
// Which scenes show a mistake (a test on the scene's text), and what to look for.
const hasSpecular = (text) => /^\s*material\s+\S+\s+(glass|mirror)\b/m.test(text);
const hasGlass = (text) => /^\s*material\s+\S+\s+glass\b/m.test(text);
const hasShadingNormals = (text) => /^\s*(quad|sphere)\b.*\s(bump|tilt)\s/m.test(text);
const MISTAKES = {
    "--symmetric-refraction": { shows: hasGlass, needs: "glass or water", scene: "refraction",
        look: "the two refraction rules swapped: light paths through the water scaled by eta^2 as radiance is; with lt the floor under the water 1.77 times too bright (page 14)" },
    "--no-adjoint-correction": { shows: hasShadingNormals, needs: "shading normals (bump or tilt)", scene: "shading-normals",
        look: "light paths use the shading-normal BSDF unchanged (no adjoint): with lt the bumped floor and balls too bright in some places, too dark in others (page 13)" },
    "--delta-density-one": { shows: hasSpecular, needs: "a mirror or glass", scene: "glass-box",
        look: "pbrt's convention, a density of 1 after a mirror or glass: the caustic's weights wrong; look at the pyramid's s=4 t=1 weighted tile, darker (page 10M)" },
    "--no-scramble": { shows: () => true, needs: "", scene: "cornell",
        look: "Sobol points without their scrambles: every pixel draws the same points; smooth-looking, patterned, biased (page 9, Appendix C)" },
    "--fixed-ray-offset": { shows: (text, name) => /thin-gap/.test(name), needs: "a lamp close to a surface", scene: "thin-gap",
        look: "new rays pushed off surfaces by a fixed distance: lt loses the light of a lamp 0.5 mm above the floor (about a fifth), seen after thousands of samples" },
    "--fixed-start": { shows: () => true, needs: "", scene: "door-hidden",
        look: "every Markov chain starts from one fixed state: start-up bias, the error stays high (page 16)" },
};
// The lessons of the "Show" menu: a scene and its panels, with what to look at.
const PRESETS = [
    { name: "the slides' results (a)-(f) at equal time", scene: "cornell-glass", entries: ["pt", "nee", "lt", "ir", "ir --clamp 1e-5", "bdpt"], page: "01-path-sampling-techniques" },
    { name: "light tracing against eye tracing (page 2)", scene: "indirect", entries: ["nee", "lt", "bdpt"], page: "02-light-and-path-tracing" },
    { name: "MIS heuristics: balance, power, max, uniform (page 10)", scene: "cornell", entries: ["bdpt", "bdpt --heuristic power", "bdpt --heuristic max", "bdpt --heuristic uniform", "nee", "nee --mis"], page: "10-combining-estimators" },
    { name: "the SDS paths: pt, bdpt and vcm with a point light (pages 12, 15)", scene: "sds-point", entries: ["pt", "bdpt", "vcm"], page: "15-vertex-merging" },
    { name: "Metropolis where bdpt struggles: door-hidden (pages 16, 17)", scene: "door-hidden", entries: ["bdpt", "pssmlt", "mmlt", "mlt"], resolution: "128x128", page: "16-metropolis-sampling" },
    ...Object.entries(MISTAKES).map(([flag, m]) => {
        const base = { "--symmetric-refraction": "lt", "--no-adjoint-correction": "lt", "--delta-density-one": "bdpt", "--no-scramble": "nee --mis",
                       "--fixed-ray-offset": "lt", "--fixed-start": "pssmlt" }[flag];
        const extra = flag === "--no-adjoint-correction" ? ["nee"] : [];
        return { name: `deliberate mistake ${flag} on ${m.scene}`, scene: m.scene, entries: [...extra, base, `${base} ${flag}`],
                 resolution: m.scene === "door-hidden" ? "128x128" : undefined, seconds: m.scene === "thin-gap" ? 30 : undefined };
    }),
];
// Scenes in the lecture's order (keys 1-9 pick the first nine).
const SCENE_ORDER = ["cornell", "cornell-glass", "cornell-point", "indirect", "refraction", "shading-normals", "energy-generator", "glass-box",
                     "sds", "sds-point", "sds-ior1", "furnace", "door", "door-side", "door-hidden"];

const state = {
    workers: [],          // one per panel slot
    workerURL: null,
    ready: 0,
    panels: [],           // the running or finished panels
    running: false,
    run: null,            // the options the run started with (the status and file names keep them)
    pixel: null,          // {x, y}: the pixel whose strategies the bar chart shows
    strategyPanel: null,  // the panel whose strategies the pyramid shows
    pyramidDirty: false,
    barsDirty: false,
    chartDirty: false,
    nextId: 1,
    whenDone: null,       // resolves run()'s promise
    notesPage: null,
    silenceLimitMs: 60000,  // a running panel's worker silent this long has died (watchWorkers)
    loading: true,          // until loadState has read the link: nothing overwrites it before
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
const fmt4 = (x) => (x === null || x === undefined || !isFinite(x) ? "–" : String(Number(x.toPrecision(4))));
const fmt = (x) => (x === null || x === undefined || !isFinite(x) ? "–" : Number(x).toPrecision(3));
const luminance = (rgb, i) => (rgb[3 * i] + rgb[3 * i + 1] + rgb[3 * i + 2]) / 3;
const escapeHtml = (s) => String(s).replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;").replace(/"/g, "&quot;");

// ---- scenes
const shortName = (path) => path.replace(/^.*\//, "").replace(/\.scene$/, "");
function sceneName() { return $("scene").value; }
function sceneText() { return $("scene-text").value; }
function scenePath(short) { return Object.keys(BDPT_SCENES).find((p) => shortName(p) === short) || null; }
function loadSceneList() {
    const names = Object.keys(BDPT_SCENES).filter((p) => p.startsWith("scenes/") || p === "tests/thin-gap.scene");
    names.sort((a, b) => rank(a) - rank(b) || a.localeCompare(b));
    function rank(p) { const i = SCENE_ORDER.indexOf(shortName(p)); return i < 0 ? 99 : i; }
    for (const name of names) {
        const o = document.createElement("option");
        o.value = name;
        o.textContent = shortName(name) + (name.startsWith("tests/") ? " (a test's scene)" : "");
        $("scene").append(o);
    }
    selectScene("scenes/cornell.scene");
}
function selectScene(name) {
    if (!BDPT_SCENES[name]) name = scenePath(shortName(name)) || "scenes/cornell.scene";
    $("scene").value = name;
    $("scene-text").value = BDPT_SCENES[name];
    $("scene-error").hidden = true;
    const own = BDPT_SCENES[name].match(/^\s*camera(?:\s+\S+){10}\s+(\d+)\s+(\d+)/m);
    $("resolution").options[0].textContent = own ? `the scene's own (${own[1]} × ${own[2]})` : "the scene's own";
    sceneLines();
    describeEntries();
    saveState();
}
function sceneLines() {
    const n = $("scene-text").value.split("\n").length;
    $("scene-lines").textContent = Array.from({ length: n }, (_, i) => i + 1).join("\n");
    $("scene-lines").scrollTop = $("scene-text").scrollTop;
}

// ---- workers: their script is engine.js's text, started from a Blob (file:// forbids a Worker
// from a file, not from a Blob).
function newWorker(slot) {
    const w = new Worker(state.workerURL);
    w.onmessage = (e) => onWorkerMessage(slot, e.data);
    w.onerror = (e) => { e.preventDefault(); workerDied(slot, "its worker failed: " + (e.message || "an error") + " (reload the page if it persists)"); };
    w.lastMessage = performance.now();
    w.isReady = false;
    return w;
}
function createWorkers() {
    try {
        state.workerURL = URL.createObjectURL(new Blob([BDPT_WORKER_SOURCE], { type: "text/javascript" }));
        for (let i = 0; i < MAX_PANELS; ++i) state.workers.push(newWorker(i));
    } catch (e) {
        showStatus("This browser cannot start the renderer's workers here (" + e.message + "): serve the page with make serve-web and open http://localhost:8000/.");
    }
}
// A worker that failed or stopped answering: its panel ends with a message, a new worker takes the slot.
function workerDied(slot, message) {
    state.workers[slot].terminate();
    state.workers[slot] = newWorker(slot);
    for (const p of state.panels) if (p.slot === slot && !p.done) endPanel(p, message);
    if (state.running && state.panels.every((p) => p.done)) finishRun();
}
function endPanel(panel, message) {
    panel.done = true;
    panel.error = message;
    panel.el.querySelector(".error").textContent = message;
    if (!panel.image) panel.canvas.hidden = true;
    if (!panel.passes) panel.el.querySelector(".stats").textContent = "";
}
// A running panel whose worker has said nothing for 60 s has lost it. A slice takes 40 ms and a
// frame comes every 200 ms, but a pass begins in one call, and mmlt's bootstrap at 128x128 takes
// about 3 CPU s of it (natively): with six panels on a busy 2-core machine, ten times that.
function watchWorkers() {
    const now = performance.now();
    for (const p of state.panels)
        if (!p.done && now - state.workers[p.slot].lastMessage > state.silenceLimitMs) workerDied(p.slot, "its worker stopped answering (out of memory?): the panel ended");
}

function onWorkerMessage(slot, m) {
    const worker = state.workers[slot];
    worker.lastMessage = performance.now();
    if (m.type === "ready") {
        worker.isReady = true;
        $("help-text").textContent = m.help;
        if (++state.ready === MAX_PANELS) { $("start").disabled = state.running; showStatus("Ready: choose a scene and methods (or a lesson under Show), then Start (Space)."); }
        return;
    }
    if (m.type === "checked") { state.onChecked && state.onChecked(m.error); return; }
    const panel = state.panels.find((p) => p.slot === slot && p.id === m.id);
    if (!panel || panel.done) return;  // a message from a run that was replaced, or of a panel ended
    if (m.type === "error") {
        endPanel(panel, m.error.replace("(see --help)", "(see the options under 'The options an entry may carry')"));
    } else if (m.type === "started") {
        Object.assign(panel, { exposure: m.exposure, width: m.width, height: m.height, spp: m.spp, limitSeconds: m.seconds,
                               referenceWidth: m.referenceWidth, referenceHeight: m.referenceHeight, recordsStrategies: m.strategies });
        panel.canvas.width = m.width, panel.canvas.height = m.height;
        panel.canvas.style.aspectRatio = `${m.width} / ${m.height}`;
        if (m.threadsGiven) panel.notes.push("--threads: a panel renders on one thread in the page");
        if (m.strategies) { if (!state.strategyPanel) state.strategyPanel = panel; pyramidChoices(); }
    } else if (m.type === "frame" || m.type === "done") {
        Object.assign(panel, { passes: m.passes, rowsDone: m.rowsDone, seconds: m.seconds, image: m.image, mean: m.mean, rmse: m.rmse,
                               rmseWithoutLamp: m.rmseWithoutLamp, bias: m.bias, comparedWidth: m.comparedWidth, nonFinite: m.nonFinite, outOfMemory: m.outOfMemory });
        if (m.strategies) {
            panel.strategies = m.strategies;
            if (panel === state.strategyPanel) state.pyramidDirty = state.barsDirty = true;
        }
        if (panel.firstFrameMs === null) panel.firstFrameMs = performance.now() - state.startedAt, panel.firstFramePasses = m.passes;
        if (m.rmseWithoutLamp !== null && m.passes > 0 && (!panel.curve.length || panel.curve[panel.curve.length - 1][2] !== m.passes))
            panel.curve.push([m.seconds, m.rmseWithoutLamp, m.passes]), state.chartDirty = true;
        if (m.type === "done") panel.done = true;
        panel.dirty = true;
    }
    if (state.running && state.panels.every((p) => p.done)) finishRun();
}

// ---- a run
function entryInputs() { return [...document.querySelectorAll("input.entry")]; }
function entries() { return entryInputs().map((e) => e.value.trim()).filter((e) => e); }
function options() {
    const [w, h] = $("resolution").value.split("x").map(Number);
    return { width: w, height: h, seconds: Math.max(0, Number($("seconds").value) || 0), spp: Math.max(0, Math.floor(Number($("spp").value) || 0)),
             seed: Math.max(1, Math.floor(Number($("seed").value) || 1)), scene: sceneName(), resolution: $("resolution").value };
}
// An entry may name its own scene ("bdpt scenes/sds.scene"): that panel renders it.
function entryScene(entry) {
    const words = entry.split(/\s+/), i = words.findIndex((w, k) => w.endsWith(".scene") && (k === 0 || !words[k - 1].startsWith("--")));
    return i < 0 ? { entry, scene: null } : { entry: words.filter((_, k) => k !== i).join(" "), scene: words[i] };
}

// The scene's text is checked first: its error (file:line, as ./bdpt prints it) stops the run. A
// worker that does not answer (3 s once loaded: a check takes milliseconds) is replaced and asked again.
function checkScene() {
    const ask = (resolve, attempt) => {
        const worker = state.workers[0];
        const timer = setTimeout(() => {
            state.onChecked = null;
            workerDied(0, "");
            if (attempt < 2) ask(resolve, attempt + 1);
            else resolve("The renderer does not answer: reload the page.");
        }, worker.isReady ? 3000 : 30000);
        state.onChecked = (error) => { clearTimeout(timer); state.onChecked = null; resolve(error); };
        worker.postMessage({ type: "check", id: 0, sceneText: sceneText(), sceneName: sceneName() });
    };
    return new Promise((resolve) => ask(resolve, 1));
}

async function start() {
    if (state.running || !state.workers.length) return;
    const list = entries();
    if (list.length === 0) { showStatus("Name at least one method."); return; }
    state.running = true;  // against a second Start while the scene is checked
    $("start").disabled = true;
    const error = await checkScene();
    $("scene-error").hidden = !error;
    $("scene-error").textContent = error;
    if (error) {
        state.running = false;
        $("start").disabled = false;
        $("panels").replaceChildren();
        state.panels = [];
        drawAll();
        showStatus("The scene has an error: nothing rendered (its line number is at the left of the scene's text).");
        $("scene-editor").open = true;
        return;
    }
    const opt = options();
    $("panels").replaceChildren();
    state.panels = [];
    state.strategyPanel = null;
    state.run = { ...opt, sceneLabel: $("scene").selectedOptions[0].textContent };
    document.body.classList.add("has-run");
    state.startedAt = performance.now();
    list.slice(0, MAX_PANELS).forEach((text, slot) => {
        const { entry, scene } = entryScene(text);
        const panel = makePanel(text, slot, opt);
        state.panels.push(panel);
        const name = scene || sceneName(), sceneTextToUse = scene ? BDPT_SCENES[scene] : sceneText();
        panel.sceneName = name;
        if (scene && !sceneTextToUse) { endPanel(panel, `the page has no scene ${scene}: its scenes are scenes/*.scene and tests/energy-generator-flat.scene`); return; }
        warnAboutMistakes(panel, entry, sceneTextToUse, name);
        // bdpt and vcm panels record their strategies for the pyramid (paths up to 4 segments).
        const strategyLength = $("record-strategies").checked && /^(bdpt|vcm)\b/.test(entry) ? 4 : 0;
        state.workers[slot].lastMessage = performance.now();
        state.workers[slot].postMessage({ type: "start", id: panel.id, sceneText: sceneTextToUse, sceneName: name, entry,
                                          width: opt.width, height: opt.height, seed: opt.seed, spp: opt.spp, seconds: opt.seconds, strategyLength });
    });
    pyramidChoices();
    $("stop").disabled = false;
    state.lastFrame = undefined;
    state.longestFrameGap = 0;
    state.watchdog = setInterval(watchWorkers, 1000);
    requestAnimationFrame(draw);
    saveState();
    if (state.panels.every((p) => p.done)) finishRun();
    return new Promise((resolve) => { state.whenDone = resolve; });
}

// Stop: every panel is asked; one whose worker has not answered within 2 s ends without it.
function stop() {
    if (!state.running) return;
    state.panels.forEach((p) => { if (!p.done) state.workers[p.slot].postMessage({ type: "stop" }); });
    setTimeout(() => {
        for (const p of state.panels) if (!p.done) workerDied(p.slot, "stopped: its worker did not answer");
    }, 2000);
}

function finishRun() {
    if (!state.running) return;
    state.running = false;
    clearInterval(state.watchdog);
    $("start").disabled = false;
    $("stop").disabled = true;
    drawAll();
    showStatus(runningText(true));
    if (state.whenDone) { const r = state.whenDone; state.whenDone = null; r(); }
}

function runningText(done) {
    const run = state.run;
    const wall = ((performance.now() - state.startedAt) / 1000).toFixed(done ? 1 : 0);
    const size = run.width ? `${run.width}×${run.height}` : "its own size";
    const budget = run.spp > 0 ? `${run.spp} sample${run.spp > 1 ? "s" : ""} per pixel` : run.seconds > 0 ? `${run.seconds} s each` : "until Stop";
    return `${done ? "Done" : "Running"}: ${run.sceneLabel} at ${size}, ${state.panels.length} panel${state.panels.length > 1 ? "s" : ""}, ${budget} (unless an entry sets its own); ${wall} s since Start (wall clock)`;
}
function showStatus(text) { if ($("status").textContent !== text) $("status").textContent = text; }

// ---- explanations
function describe(entry) {
    const words = entry.split(/\s+/);
    const key = [words.slice(0, 3).join(" "), words.slice(0, 2).join(" "), words[0]].find((k) => METHODS[k]);
    return key ? METHODS[key] : "";
}
function mistakesIn(entry) { return Object.keys(MISTAKES).filter((flag) => entry.split(/\s+/).includes(flag)); }
function warnAboutMistakes(panel, entry, text, name) {
    for (const flag of mistakesIn(entry)) {
        const m = MISTAKES[flag];
        panel.notes.push(`deliberate mistake ${flag}: ${m.look}`);
        if (!m.shows(text, name)) panel.notes.push(`this scene cannot show it: it has no ${m.needs}; try ${m.scene} (the Show menu has it)`);
    }
    drawNotes(panel);
}
function describeEntries() {
    entryInputs().forEach((input) => {
        const text = input.value.trim(), { entry } = entryScene(text), line = input.parentElement.querySelector(".entry-text");
        const warnings = mistakesIn(entry).filter((f) => !MISTAKES[f].shows(sceneText(), sceneName()))
            .map((f) => `${f} shows nothing on this scene (it needs ${MISTAKES[f].needs}; try ${MISTAKES[f].scene})`);
        line.textContent = warnings.join(" · ");  // the method's description is under its panel
        input.title = text ? [describe(entry), ...mistakesIn(entry).map((f) => "deliberate mistake: " + MISTAKES[f].look)].filter((s) => s).join("\n") : "";
        line.classList.toggle("warning", warnings.length > 0);
    });
}
function makeEntries() {
    const list = ["pt", "nee --mis", "lt", "ir --clamp 1e-5", "bdpt --heuristic power", "vcm"];
    list.forEach((value, i) => {
        const div = document.createElement("div");
        div.className = "entry-box";
        div.style.setProperty("--colour", COLOURS[i]);
        div.innerHTML = `<input class="entry" list="entry-examples" aria-label="method ${i + 1}"><div class="entry-text"></div>`;
        div.querySelector("input").value = value;
        div.querySelector("input").addEventListener("input", () => { describeEntries(); saveState(); });
        $("entries").append(div);
    });
    const examples = [...Object.keys(METHODS).map((k) => (k === "ir --clamp" ? "ir --clamp 1e-5" : k)),
                      ...Object.keys(MISTAKES).map((f) => ({ "--fixed-start": "pssmlt", "--delta-density-one": "bdpt", "--no-scramble": "nee --mis" }[f] || "lt") + " " + f)];
    for (const e of examples) {
        const o = document.createElement("option");
        o.value = e;
        o.label = describe(e) || (MISTAKES[e.split(" ").pop()] || {}).look || "";
        $("entry-examples").append(o);
    }
}

// ---- panels
function makePanel(entry, slot, opt) {
    const el = document.createElement("article");
    el.className = "panel";
    el.style.setProperty("--colour", COLOURS[slot]);
    el.innerHTML = `<h2></h2><p class="what"></p><canvas width="${opt.width || 64}" height="${opt.height || 64}"></canvas><div class="stats">starting…</div>
        <div class="error"></div><ul class="notes-list"></ul><div class="downloads"><button data-kind="png">PNG</button> <button data-kind="pfm">PFM</button></div>`;
    el.querySelector("h2").textContent = entry;
    el.querySelector(".what").textContent = describe(entryScene(entry).entry);
    const canvas = el.querySelector("canvas");
    canvas.addEventListener("click", (e) => {
        const r = canvas.getBoundingClientRect();
        choosePixel(Math.floor((e.clientX - r.left) / r.width * canvas.width), Math.floor((e.clientY - r.top) / r.height * canvas.height));
    });
    const panel = { id: state.nextId++, slot, entry, el, canvas, curve: [], passes: 0, rowsDone: 0, seconds: 0, done: false, dirty: false, error: null,
                    exposure: 0, width: 0, height: 0, image: null, strategies: null, firstFrameMs: null, notes: [], comparedWidth: 0,
                    referenceWidth: 0, referenceHeight: 0 };
    el.querySelector('[data-kind="png"]').onclick = () => downloadPNG(panel);
    el.querySelector('[data-kind="pfm"]').onclick = () => downloadPFM(panel);
    $("panels").append(el);
    return panel;
}
function drawNotes(panel) {
    panel.el.querySelector(".notes-list").innerHTML = panel.notes.map((n) => `<li>${escapeHtml(n)}</li>`).join("");
}

function errorText(panel) {
    if (!panel.referenceWidth) return "no reference for this scene: no error";
    if (!panel.comparedWidth) return panel.passes ? `no error: the reference is ${panel.referenceWidth}×${panel.referenceHeight}, not a power-of-two multiple of this size` : "";
    const partial = /--maxdepth|--rr-start/.test(panel.entry) ? " (the reference has paths of every length)" : "";
    const at = panel.comparedWidth !== panel.width ? ` at ${panel.comparedWidth}×${panel.comparedWidth * panel.height / panel.width}` : "";
    const bias = `${panel.bias >= 0 ? "+" : ""}${(100 * panel.bias).toFixed(2)}%`;  // as ./bdpt prints it
    return `RMSE${at} <b>${fmt4(panel.rmseWithoutLamp)}</b> (${fmt4(panel.rmse)} with the lamp's pixels) · bias <b>${bias}</b>${partial}`;
}
function drawPanel(panel) {
    if (!panel.image) return;
    const g = panel.canvas.getContext("2d");
    g.putImageData(toImageData(panel.image, panel.width, panel.height, panel.exposure + sliderStops()), 0, 0);
    if (state.pixel && state.strategyPanel && panel.width === state.strategyPanel.width) {
        g.strokeStyle = "#00ffff";
        g.lineWidth = Math.max(1, panel.width / 128);
        g.strokeRect(state.pixel.x - 1.5, state.pixel.y - 1.5, 4, 4);
    }
    const progress = panel.rowsDone > 0 && !panel.done ? ` · pass ${panel.passes + 1}: ${Math.round(100 * panel.rowsDone / panel.height)}% of its rows` : "";
    panel.el.querySelector(".stats").innerHTML = `<b>${panel.passes}</b> spp · <b>${panel.seconds.toFixed(1)}</b> s · mean <b>${fmt4(panel.mean)}</b> · ${errorText(panel)}${progress}` +
        (panel.nonFinite > 0 ? ` · ${panel.nonFinite} non-finite dropped` : "") + (panel.outOfMemory ? " · out of memory: stopped" : "");
}

function fileStem(panel) {
    return `${shortName(panel.sceneName || state.run.scene)}-${panel.entry.replace(/[^A-Za-z0-9.]+/g, "-")}-${panel.passes}spp`;
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

// ---- error against time, log axes, one curve per panel with a reference; ticks at 1, 2 and 5
// of each decade the data spans
function logTicks(lo, hi) {
    const ticks = [];
    for (let d = Math.floor(Math.log10(lo)); d <= Math.ceil(Math.log10(hi)); ++d)
        for (const m of [1, 2, 5]) { const v = m * 10 ** d; if (v >= lo * 0.999 && v <= hi * 1.001) ticks.push(v); }
    return ticks;
}
function drawChart() {
    const svg = $("chart"), W = 900, H = 460, left = 90, right = 20, top = 15, bottom = 60;
    const points = state.panels.flatMap((p) => p.curve).filter(([t, e]) => t > 0 && e > 0);
    if (points.length < 2) {
        const noReference = state.panels.length && state.panels.every((p) => p.done || p.referenceWidth) && !state.panels.some((p) => p.referenceWidth);
        svg.innerHTML = `<text x="${W / 2}" y="${H / 2}" text-anchor="middle" font-size="22">${
            noReference ? "this scene has no reference (scenes/refs/): no error to chart" : "the curves appear as the panels render their passes"}</text>`;
        return;
    }
    const ts = points.map((p) => p[0]), es = points.map((p) => p[1]);
    let t0 = Math.min(...ts), t1 = Math.max(...ts), e0 = Math.min(...es), e1 = Math.max(...es);
    if (t1 < t0 * 2) t0 /= 1.5, t1 *= 1.5;
    if (e1 < e0 * 2) e0 /= 1.5, e1 *= 1.5;
    const lx = Math.log10, X = (t) => left + (lx(t) - lx(t0)) / (lx(t1) - lx(t0)) * (W - left - right);
    const Y = (e) => H - bottom - (lx(e) - lx(e0)) / (lx(e1) - lx(e0)) * (H - top - bottom);
    let html = "";
    for (const t of logTicks(t0, t1))
        html += `<line x1="${X(t)}" x2="${X(t)}" y1="${top}" y2="${H - bottom}" stroke="#444"/><text x="${X(t)}" y="${H - bottom + 24}" text-anchor="middle" font-size="18">${+t.toPrecision(2)}</text>`;
    for (const e of logTicks(e0, e1))
        html += `<line x1="${left}" x2="${W - right}" y1="${Y(e)}" y2="${Y(e)}" stroke="#444"/><text x="${left - 8}" y="${Y(e) + 6}" text-anchor="end" font-size="18">${+e.toPrecision(2)}</text>`;
    html += `<text x="${(left + W - right) / 2}" y="${H - 12}" text-anchor="middle" font-size="18">seconds of rendering (each panel its own; wall clock)</text>`;
    html += `<text transform="translate(20 ${(top + H - bottom) / 2}) rotate(-90)" text-anchor="middle" font-size="18">RMSE, the lamp's pixels left out</text>`;
    state.panels.forEach((p) => {
        const c = p.curve.filter(([t, e]) => t > 0 && e > 0);
        if (c.length) html += `<polyline fill="none" stroke="${COLOURS[p.slot]}" stroke-width="3" data-entry="${escapeHtml(p.entry)}" points="${c.map(([t, e]) => `${X(t).toFixed(1)},${Y(e).toFixed(1)}`).join(" ")}"/>`;
    });
    svg.innerHTML = html;
    $("chart-caption").innerHTML = "Error against time, log axes: " + state.panels.map((p) =>
        `<span class="key" style="--colour:${COLOURS[p.slot]}">${escapeHtml(p.entry)}${p.curve.length ? "" : " (no curve)"}</span>`).join(" ");
}

// ---- bdpt's pyramid: row k = path length in segments, column s = vertices from the light, each
// row brightened by whole stops to the brightest row's level (each bounce keeps about the albedo).
function pyramidGeometry(panel) {
    const L = Math.max(...panel.strategies.map((s) => s.k)), merges = panel.strategies.some((s) => s.s === s.k + 1);
    const w = panel.width, h = panel.height, gap = Math.max(2, w >> 4), strip = Math.max(14, h >> 2), margin = Math.max(40, w >> 1);
    return { L, w, h, gap, strip, margin, cols: L + 1 + (merges ? 1 : 0), W: margin + (L + 1 + (merges ? 1 : 0)) * (w + gap) + gap,
             H: L * (strip + h + gap) + gap,
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
// Drawn only when its strategies, the exposure or the weighting change, at a scale that keeps
// its labels legible (about 1,600 pixels across), not at the screen's.
function drawPyramid() {
    const panel = state.strategyPanel, canvas = $("pyramid");
    canvas.hidden = !panel || !panel.strategies;
    if (canvas.hidden) return;
    state.pyramidRedraws = (state.pyramidRedraws || 0) + 1;
    const weighted = $("weighted").checked, g = pyramidGeometry(panel), stops = rowStops(panel, weighted);
    const z = Math.max(1, Math.round(1600 / g.W));
    canvas.width = g.W * z, canvas.height = g.H * z;
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
    $("pyramid-caption").textContent = `${panel.entry}, ${panel.passes} spp, ${weighted ? "MIS-weighted: a row's tiles sum to that row of the image" : "unweighted: each strategy alone"}; ` +
        `row k: path length in segments; s: vertices from the light, t: from the camera; +N: the row brightened N stops`;
}
function pyramidChoices() {
    const select = $("pyramid-panel"), choices = state.panels.filter((p) => /^(bdpt|vcm)\b/.test(entryScene(p.entry).entry));
    select.innerHTML = choices.map((p) => `<option value="${p.id}">${escapeHtml(p.entry)}</option>`).join("") || "<option>(no bdpt or vcm panel)</option>";
    if (state.strategyPanel) select.value = state.strategyPanel.id;
}
function pyramidPixel(e) {
    const panel = state.strategyPanel;
    if (!panel || !panel.strategies) return;
    const canvas = $("pyramid"), r = canvas.getBoundingClientRect(), g = pyramidGeometry(panel);
    const px = (e.clientX - r.left) / r.width * g.W, py = (e.clientY - r.top) / r.height * g.H;
    for (const st of panel.strategies) {
        const x = g.tileX(st.k, st.s), y = g.tileY(st.k);
        if (px >= x && px < x + g.w && py >= y && py < y + g.h) { choosePixel(Math.floor(px - x), Math.floor(py - y)); return; }
    }
}

// ---- a pixel's strategies: each (s,t)'s contribution there, unweighted and MIS-weighted
function choosePixel(x, y) {
    state.pixel = { x, y };
    state.barsDirty = true;
    state.panels.forEach((p) => (p.dirty = true));
    drawAll();
    const bars = $("bars-figure").getBoundingClientRect();
    if (bars.top > innerHeight || bars.bottom < 0)  // out of sight: say where the click's answer is
        showStatus(`Pixel (${x}, ${y}): its strategies are in the bar chart ${bars.top > innerHeight ? "below" : "above"} the panels`);
    return strategyBars();
}
function strategyBars() {
    const panel = state.strategyPanel;
    if (!state.pixel || !panel || !panel.strategies || state.pixel.x >= panel.width || state.pixel.y >= panel.height) return [];
    const i = state.pixel.y * panel.width + state.pixel.x;
    return panel.strategies.map((st) => ({ k: st.k, s: st.s, t: st.k + 1 - st.s, merge: st.s === st.k + 1,
                                          unweighted: luminance(st.unweighted, i), weighted: luminance(st.weighted, i) }));
}
function drawBars() {
    const svg = $("bars"), bars = strategyBars(), W = 900, H = 300, left = 80, bottom = 60, top = 20;
    if (!bars.length) {
        const has = state.panels.some((p) => /^(bdpt|vcm)\b/.test(p.entry));
        svg.innerHTML = `<text x="${W / 2}" y="${H / 2}" text-anchor="middle" font-size="22">${
            !has ? "a bdpt or vcm panel shows its strategies here: put one in the methods" : "click a pixel of a panel"}</text>`;
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
    $("bars-caption").textContent = `Pixel (${state.pixel.x}, ${state.pixel.y}) of ${panel.entry}: grey each strategy alone (unweighted), ` +
        `amber MIS-weighted; the weighted ones sum to ${fmt(sum)} of the pixel's ${fmt(luminance(panel.image, i))} (paths up to ${Math.max(...bars.map((b) => b.k))} segments)`;
}

// ---- drawing, at most once per display frame, each part only when its data changed
function drawAll() {
    state.panels.forEach((p) => (p.dirty = false, drawPanel(p)));
    drawChart();
    drawPyramid();
    drawBars();
    state.pyramidDirty = state.barsDirty = state.chartDirty = false;
    $("exposure-value").textContent = `${sliderStops() >= 0 ? "+" : ""}${sliderStops()} stops`;
}
function draw(now) {
    if (state.lastFrame !== undefined && now !== undefined) state.longestFrameGap = Math.max(state.longestFrameGap, now - state.lastFrame);
    state.lastFrame = now;
    for (const p of state.panels) if (p.dirty) { p.dirty = false; drawPanel(p); }
    if (state.chartDirty) { state.chartDirty = false; drawChart(); }
    if (state.pyramidDirty) { state.pyramidDirty = false; drawPyramid(); }
    if (state.barsDirty) { state.barsDirty = false; drawBars(); }
    if (state.running) {
        showStatus(runningText(false));
        requestAnimationFrame(draw);
    }
}

// ---- the notes: a page at a time, its commands with a button that sets the panels to them
function notesIndex(file) { return BDPT_NOTES.findIndex((p) => p.file === file); }
function loadNotesList() {
    for (const p of BDPT_NOTES) {
        const o = document.createElement("option");
        o.value = p.file;
        o.textContent = p.file === "README" ? "Contents" : p.title.replace(/^Appendix/, "Appendix");
        $("notes-page").append(o);
    }
}
function openNotes(file, anchor) {
    const i = Math.max(0, notesIndex(file)), page = BDPT_NOTES[i], text = $("notes-text");
    state.notesPage = page.file;
    $("notes-page").value = page.file;
    text.innerHTML = page.html;
    linkPages(text);
    addCommandButtons(text);
    const target = anchor && text.querySelector(`[id="${CSS.escape(anchor)}"]`);
    if (target) target.scrollIntoView(); else text.scrollTop = 0, $("notes-view").scrollTop = 0;
    saveState();
}
// "page 7", "page 10M", "Appendix A" in the text: links to those pages.
function linkPages(root) {
    const byNumber = (n) => BDPT_NOTES.find((p) => p.file.toLowerCase().startsWith(/^\d$/.test(n) ? "0" + n + "-" : n.toLowerCase() + "-"));
    const walker = document.createTreeWalker(root, NodeFilter.SHOW_TEXT, { acceptNode: (n) => (n.parentElement.closest("a, code, pre, h1, h2, h3, .katex") ? NodeFilter.FILTER_REJECT : NodeFilter.FILTER_ACCEPT) });
    const nodes = [];
    while (walker.nextNode()) nodes.push(walker.currentNode);
    for (const node of nodes) {
        const re = /\b(pages? (\d{1,2}M?)|Appendix ([ABC]))\b/g;
        if (!re.test(node.nodeValue)) continue;
        const html = escapeHtml(node.nodeValue).replace(re, (all, _, n, a) => {
            const page = n ? byNumber(n) : BDPT_NOTES.find((p) => p.file === "appendix-" + a.toLowerCase() || p.file.startsWith("appendix-" + a.toLowerCase() + "-"));
            return page ? `<a href="#notes=${page.file}" data-page="${page.file}">${all}</a>` : all;
        });
        const span = document.createElement("span");
        span.innerHTML = html;
        node.replaceWith(...span.childNodes);
    }
}

// A command of the notes as the page's settings: the scene, one panel per entry, and the options
// the page has controls for. Returns {settings} or {reason} why the page cannot run it.
function splitWords(line) {
    const words = [];
    line.replace(/"([^"]*)"|'([^']*)'|(\S+)/g, (_, a, b, c) => words.push(a ?? b ?? c));
    return words;
}
const FIGURE_OPTIONS = ["--out", "--title", "--ratio-panel", "--ref", "--strategies", "--log", "--live", "--strategy-length"];
const FLAGS = ["--overwrite", "--quiet", "--profile"];
function parseCommand(line) {
    const words = splitWords(line.trim());
    if (words[0] !== "./bdpt") return { reason: "run it in a terminal, in the repository's folder" };
    if (words.includes("--ratio")) return { reason: "--ratio compares two files: run it in a terminal after the renders" };
    const settings = { scene: null, entries: null, method: null, spp: 0, seconds: 0, resolution: "0x0", seed: 1, shared: [] };
    for (let i = 1; i < words.length; ++i) {
        const w = words[i], v = words[i + 1];
        if (w === "--side-by-side") settings.entries = v.split(",").map((e) => e.trim()), ++i;
        else if (w === "--method") settings.method = v, ++i;
        else if (w === "--spp") settings.spp = Number(v), ++i;
        else if (w === "--time" || w === "--wall-time") settings.seconds = Number(v), ++i;
        else if (w === "--res") settings.resolution = v, ++i;
        else if (w === "--seed") settings.seed = Number(v), ++i;
        else if (FIGURE_OPTIONS.includes(w)) ++i;
        else if (FLAGS.includes(w)) { if (w === "--profile") return { reason: "--profile prints a terminal's table: run it in a terminal" }; }
        else if (!w.startsWith("--") && w.endsWith(".scene") && !settings.scene) settings.scene = w;
        else if (w.startsWith("--")) {
            settings.shared.push(w);
            if (v !== undefined && !v.startsWith("--")) settings.shared.push(v), ++i;
        } else return { reason: `'${w}': not an option the page knows` };
    }
    if (!settings.scene || !BDPT_SCENES[settings.scene]) return { reason: `the page has no scene ${settings.scene || ""}: run it in a terminal` };
    const list = (settings.entries || [settings.method || "pt"]).map((e) => [e, ...settings.shared].join(" "));
    for (const e of list) {
        const { scene } = entryScene(e);
        if (scene && !BDPT_SCENES[scene]) return { reason: `the page has no scene ${scene}: run it in a terminal` };
    }
    if (list.length > MAX_PANELS) return { reason: `more than ${MAX_PANELS} panels` };
    settings.entries = list;
    if (!settings.spp && !settings.seconds) settings.spp = 16;  // ./bdpt's default
    return { settings };
}
function applySettings(s) {
    selectScene(s.scene);
    setResolution(s.resolution);
    $("spp").value = s.spp;
    $("seconds").value = s.seconds || (s.spp ? 0 : 10);
    $("seed").value = s.seed;
    entryInputs().forEach((input, i) => (input.value = s.entries[i] || ""));
    describeEntries();
    saveState();
}
function setResolution(value) {
    const select = $("resolution");
    if (![...select.options].some((o) => o.value === value)) {
        const o = document.createElement("option");
        const [w, h] = value.split("x");
        o.value = value, o.textContent = `${w} × ${h}`;
        select.append(o);
    }
    select.value = value;
}
const until = (condition) => new Promise((resolve) => { const poll = () => (condition() ? resolve() : setTimeout(poll, 50)); poll(); });
async function runSettings(s) {
    if (state.running) { stop(); await until(() => !state.running); }
    applySettings(s);
    return start();
}
function addCommandButtons(root) {
    const blocks = [...root.querySelectorAll("pre > code")];
    const inline = [...root.querySelectorAll("code")].filter((c) => !c.closest("pre") && c.textContent.startsWith("./bdpt "));
    for (const code of [...blocks, ...inline]) {
        const lines = code.textContent.split("\n").filter((l) => /^(\.\/bdpt|make|build\/)/.test(l.trim()));
        if (!lines.length) continue;
        const bar = document.createElement(code.closest("pre") ? "div" : "span");
        bar.className = "commands";
        for (const line of lines) {
            const parsed = parseCommand(line);
            const b = document.createElement(parsed.settings ? "button" : "span");
            b.className = "run-command";
            if (parsed.settings) {
                const n = parsed.settings.entries.length;
                b.textContent = `▶ Run in the page (${n} panel${n > 1 ? "s" : ""})`;
                b.title = line;
                b.dataset.command = line;
                b.onclick = () => { runSettings(parsed.settings); if (innerWidth < 1100) $("panels").scrollIntoView(); };
            } else {
                b.textContent = `${line.trim().split(" ").slice(0, 2).join(" ")}: ${parsed.reason}`;
                b.classList.add("terminal");
                b.dataset.command = line;
                b.dataset.reason = parsed.reason;
            }
            bar.append(b);
        }
        (code.closest("pre") || code).after(bar);
    }
}

// ---- the page's state as a link: scene, entries, settings and the notes page in the URL's hash
function saveState() {
    if (state.loading) return;
    const p = new URLSearchParams();
    p.set("scene", shortName(sceneName()));
    p.set("res", $("resolution").value);
    p.set("seconds", $("seconds").value);
    p.set("spp", $("spp").value);
    p.set("seed", $("seed").value);
    p.set("m", entryInputs().map((e) => e.value.trim()).join("|"));
    if (state.notesPage) p.set("notes", state.notesPage);
    if (sceneText() !== BDPT_SCENES[sceneName()]) p.set("text", sceneText());
    history.replaceState(null, "", "#" + p.toString());
}
function loadState() {
    const p = new URLSearchParams(location.hash.slice(1));
    state.loading = true;
    if (p.get("scene")) selectScene(scenePath(p.get("scene")) || "scenes/cornell.scene");
    if (p.get("text")) $("scene-text").value = p.get("text"), sceneLines();
    if (p.get("res")) setResolution(p.get("res"));
    for (const k of ["seconds", "spp", "seed"]) if (p.get(k) !== null) $(k).value = p.get(k);
    if (p.get("m") !== null) p.get("m").split("|").forEach((v, i) => { if (entryInputs()[i]) entryInputs()[i].value = v; });
    describeEntries();
    state.loading = false;
    openNotes(p.get("notes") || "README");
}

// ---- controls and keys
function bindControls() {
    $("start").onclick = start;
    $("stop").onclick = stop;
    $("scene").onchange = () => selectScene(sceneName());
    $("scene-reset").onclick = () => { selectScene(sceneName()); };
    $("scene-text").addEventListener("input", () => { sceneLines(); describeEntries(); saveState(); });
    $("scene-text").addEventListener("scroll", () => ($("scene-lines").scrollTop = $("scene-text").scrollTop));
    for (const id of ["resolution", "seconds", "spp", "seed"]) $(id).addEventListener("change", saveState);
    $("exposure").oninput = () => { state.pyramidDirty = true; drawAll(); };
    $("weighted").onchange = drawAll;
    $("pyramid").addEventListener("click", pyramidPixel);
    $("pyramid-panel").onchange = () => {
        state.strategyPanel = state.panels.find((p) => String(p.id) === $("pyramid-panel").value) || state.strategyPanel;
        drawAll();
    };
    for (const p of PRESETS) {
        const o = document.createElement("option");
        o.value = PRESETS.indexOf(p);
        o.textContent = p.name;
        $("preset").append(o);
    }
    $("preset").onchange = () => {
        const p = PRESETS[Number($("preset").value)];
        if (!p) return;
        applySettings({ scene: scenePath(p.scene), entries: p.entries, spp: 0, seconds: p.seconds || 10, seed: 1, resolution: p.resolution || "64x64" });
        if (p.page) openNotes(p.page);
        $("preset").value = "";
    };
    $("notes-page").onchange = () => openNotes($("notes-page").value);
    $("notes-previous").onclick = () => openNotes(BDPT_NOTES[Math.max(0, notesIndex(state.notesPage) - 1)].file);
    $("notes-next").onclick = () => openNotes(BDPT_NOTES[Math.min(BDPT_NOTES.length - 1, notesIndex(state.notesPage) + 1)].file);
    $("notes-text").addEventListener("click", (e) => {
        const a = e.target.closest("a[data-page]");
        if (a) { e.preventDefault(); openNotes(a.dataset.page, a.dataset.anchor); }
    });
    $("notes-toggle").onclick = () => {
        const hidden = document.body.classList.toggle("no-notes");
        $("notes-toggle").textContent = hidden ? "Show the notes" : "Hide the notes";
    };
    $("share").onclick = () => {
        saveState();
        navigator.clipboard && navigator.clipboard.writeText(location.href).catch(() => {});
        showStatus("This setting's link (copied, where the browser allows): " + location.href);
    };
    document.addEventListener("keydown", (e) => {
        if (e.target.matches("input:not([type=range]):not([type=checkbox]), textarea, select")) return;  // typing
        const ex = $("exposure");
        if (e.key === " ") { e.preventDefault(); state.running ? stop() : start(); }
        else if (e.key === "Escape") stop();
        else if (e.key === "+" || e.key === "=") { ex.value = Number(ex.value) + 0.5; state.pyramidDirty = true; drawAll(); }
        else if (e.key === "-") { ex.value = Number(ex.value) - 0.5; state.pyramidDirty = true; drawAll(); }
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
    setSceneText: (text) => { $("scene-text").value = text; sceneLines(); },
    setEntries: (list) => { entryInputs().forEach((e, i) => { e.value = list[i] || ""; }); describeEntries(); },
    setOptions: (o) => {
        if (o.resolution) setResolution(o.resolution);
        for (const k of ["seconds", "spp", "seed"]) if (k in o) $(k).value = o[k];
        if ("strategies" in o) $("record-strategies").checked = o.strategies;
    },
    run: () => start(),
    stop,
    running: () => state.running,
    longestFrameGap: () => state.longestFrameGap,  // ms between two drawn frames during the last run
    sceneError: () => ($("scene-error").hidden ? "" : $("scene-error").textContent),
    panels: () => state.panels.map((p) => ({ entry: p.entry, passes: p.passes, seconds: p.seconds, mean: p.mean, rmse: p.rmse, rmseWithoutLamp: p.rmseWithoutLamp, bias: p.bias,
                                             error: p.error, done: p.done, nonFinite: p.nonFinite, firstFrameMs: p.firstFrameMs, firstFramePasses: p.firstFramePasses, curve: p.curve,
                                             strategies: p.strategies ? p.strategies.length : 0, width: p.width, height: p.height,
                                             comparedWidth: p.comparedWidth, notes: p.notes, what: p.el.querySelector(".what").textContent,
                                             limitSpp: p.spp, limitSeconds: p.limitSeconds,
                                             stats: p.el.querySelector(".stats").textContent })),
    // The canvas as drawn: RGBA bytes of panel i.
    canvasPixels: (i) => Array.from(state.panels[i].canvas.getContext("2d").getImageData(0, 0, state.panels[i].width, state.panels[i].height).data),
    // The chart's curves as drawn: each polyline's entry and its points' y (SVG: down is larger).
    chartCurves: () => [...$("chart").querySelectorAll("polyline")].map((l) => ({ entry: l.dataset.entry, points: l.getAttribute("points").split(" ").map((p) => p.split(",").map(Number)) })),
    // The pyramid panel's weighted tiles summed over strategies (the luminance of each pixel),
    // beside that panel's image: they agree for paths within the pyramid's lengths.
    pyramidSums: () => {
        const p = state.strategyPanel;
        if (!p || !p.strategies) return null;
        const n = p.width * p.height, sum = new Array(n).fill(0), image = [];
        for (const st of p.strategies) for (let i = 0; i < n; ++i) sum[i] += luminance(st.weighted, i);
        for (let i = 0; i < n; ++i) image.push(luminance(p.image, i));
        return { entry: p.entry, passes: p.passes, sum, image, tiles: p.strategies.length, drawn: !$("pyramid").hidden };
    },
    pyramidRedraws: () => state.pyramidRedraws,
    // Each recorded strategy's mean over pixels and channels, weighted and not (./bdpt --strategies's images' means).
    strategyMeans: () => (state.strategyPanel && state.strategyPanel.strategies || []).map((st) => ({ k: st.k, s: st.s, t: st.k + 1 - st.s,
        weighted: st.weighted.reduce((a, v) => a + v, 0) / st.weighted.length, unweighted: st.unweighted.reduce((a, v) => a + v, 0) / st.unweighted.length })),
    clickPixel: (panelIndex, x, y) => {
        const p = state.panels[panelIndex], r = p.canvas.getBoundingClientRect();
        p.canvas.dispatchEvent(new MouseEvent("click", { clientX: r.left + (x + 0.5) / p.width * r.width, clientY: r.top + (y + 0.5) / p.height * r.height, bubbles: true }));
        return [...$("bars").querySelectorAll("rect")].map((b) => ({ strategy: b.dataset.strategy, kind: b.dataset.kind, value: Number(b.dataset.value) }));
    },
    openNotes,
    notesButtons: () => [...document.querySelectorAll("#notes-text .run-command")].map((b) => ({ command: b.dataset.command, runs: b.tagName === "BUTTON", reason: b.dataset.reason || "" })),
    clickNotesButton: (command) => {
        const b = [...document.querySelectorAll("#notes-text button.run-command")].find((x) => x.dataset.command === command);
        if (!b || b.disabled) return false;
        b.click();
        return true;
    },
    // A worker killed without a word, as the system kills one out of memory (the test's own hook).
    killWorker: (slot) => state.workers[slot].terminate(),
    setSilenceLimit: (ms) => { state.silenceLimitMs = ms; },
    overflow: () => ({ scrollWidth: document.documentElement.scrollWidth, innerWidth }),
};

makeEntries();
loadSceneList();
loadNotesList();
bindControls();
createWorkers();
loadState();
window.addEventListener("hashchange", () => { if (!state.running) loadState(); });  // a link pasted into this tab
drawAll();
if (location.protocol === "file:") showStatus("Opened from a file: loading the renderer…");
