// The page: the lecture notes beside up to six panels, each a Web Worker rendering one method
// (worker.js, started from engine.js's text, so that the page also opens from a file); this
// thread only draws: the panels, the error-against-time chart, bdpt's pyramid and a pixel's
// strategy chart. window.bdptPage is what make test-web drives (tests/test_web.py).
"use strict";

const MAX_PANELS = 6;
const PYRAMID_LENGTH = 5;  // the pyramid's rows: paths up to 5 segments (page 15's exercise asks for row k = 5)
const COLOURS = ["#ff6b6b", "#4dabf7", "#51cf66", "#fcc419", "#cc5de8", "#e9ecef"];
const $ = (id) => document.getElementById(id);

// ---- what the page says about each method and each deliberate mistake: a method's caption, what
// it does and its notes pages come from bdpt.cpp's kMethodCaptions (with the first worker's
// "ready"); the variants' sentences are the page's.
const METHODS = {
    "nee --mis": "(b) with MIS: next event and hitting the lamp combined by the power heuristic (pages 9, 10).",
    "ir --clamp": "(e) Instant radiosity clamped: the blotches gone, and their energy with them: biased (page 1).",
    "bdpt --heuristic power": "(f) with the power heuristic (exponent 2): the best strategy weighted more (page 10).",
    "bdpt --heuristic max": "(f) with the maximum heuristic: each path to its one best strategy (page 10).",
    "bdpt --heuristic uniform": "(f) with uniform weights 1/(number of strategies): unbiased, but the noise of every strategy (page 10).",
};
function readCaptions(lines) {
    for (const line of lines.trim().split("\n")) {
        const [name, caption, what, pages] = line.split("\t");
        METHODS[name] = `${caption}: ${what} (page${/-/.test(pages) ? "s" : ""} ${pages}).`;
    }
}
// Which scenes show a mistake (a test on the scene's text), and what to look for: `look` says what
// the mistake is, `on` what it does to this method on the scene that shows it best (scene).
const hasSpecular = (text) => /^\s*material\s+\S+\s+(glass|mirror)\b/m.test(text);
const hasGlass = (text) => /^\s*material\s+\S+\s+glass\b/m.test(text);
const hasShadingNormals = (text) => /^\s*(quad|sphere)\b.*\s(bump|tilt)\s/m.test(text);
const MISTAKES = {
    "--symmetric-refraction": { shows: hasGlass, needs: "glass or water", scene: "refraction", page: "14-power-versus-radiance",
        look: "the two refraction rules swapped: radiance crossing glass or water without its eta^2, importance with it (page 14)",
        on: { pt: "pt's floor seen through the water 1.77 times too dark", lt: "lt's floor under the water 1.77 times too bright (lt cannot see the sky through the surface: its bias is large either way)" } },
    "--no-adjoint-correction": { shows: hasShadingNormals, needs: "shading normals (bump or tilt)", scene: "shading-normals", page: "13-shading-normals",
        look: "light paths use the shading-normal BSDF unchanged, without the adjoint's factor: light-traced images too bright in some places, too dark in others (page 13)",
        on: { lt: "lt's bumped floor and balls brighter in places and darker in others than nee's, whose camera paths need no adjoint (ratio of means about 1.06)" } },
    "--delta-density-one": { shows: hasSpecular, needs: "a mirror or glass", scene: "glass-box", page: "10m-mirrors-and-glass",
        look: "pbrt's convention, a density of 1 after a mirror or glass: the MIS weights of caustic paths wrong (page 10M)",
        on: { bdpt: "the caustic under the glass ball goes to s=0 t=5's speckles: click each panel, then compare the pyramid's s=4 t=1 weighted tiles; its RMSE is the larger" } },
    "--no-scramble": { shows: () => true, needs: "", scene: "cornell", page: "09-russian-roulette-and-sampling",
        look: "Sobol points without their scrambles: every pixel draws the same points, so every pixel errs the same way (page 9, Appendix C)",
        on: { "nee --mis": "at 16 samples a smooth, patterned image whose RMSE stays above the scrambled one's" } },
    "--fixed-ray-offset": { shows: (text, name) => /thin-gap/.test(name), needs: "a lamp close to a surface", scene: "thin-gap", page: "06-extending-paths",
        look: "new rays pushed off surfaces by a fixed distance, not by the hit point's error bound (page 6)",
        on: { lt: "lt loses the light of a lamp 0.5 mm above the floor: about 0.80 of the right mean (nee, which leaves from the floor's side, is right either way)" } },
    "--fixed-start": { shows: () => true, needs: "", scene: "door-hidden", page: "16-metropolis-sampling",
        look: "every Markov chain starts from one fixed state, not from the bootstrap's: start-up bias (page 16)",
        on: { pssmlt: "an orange blotch where the chains began, and an error that stays high" } },
};
// What a mistake does to a method on a scene: what it is, and on its own scene what to look for.
function mistakeText(flag, entry, name) {
    const m = MISTAKES[flag], method = Object.keys(m.on).find((k) => (entry + " ").startsWith(k + " "));
    return m.look + (method && shortName(name || "") === m.scene ? "; here: " + m.on[method] : "");
}
// The lessons of the "Show" menu: a scene and its panels, with what to look at.
const PRESETS = [
    { name: "the slides' results (a)-(f) at equal time", scene: "cornell-glass", entries: ["pt", "nee", "lt", "ir", "ir --clamp 1e-5", "bdpt"], page: "01-path-sampling-techniques" },
    { name: "light tracing against eye tracing (page 2)", scene: "indirect", entries: ["nee", "lt", "bdpt"], page: "02-light-and-path-tracing" },
    { name: "MIS heuristics: balance, power, max, uniform (page 10)", scene: "cornell", entries: ["bdpt", "bdpt --heuristic power", "bdpt --heuristic max", "bdpt --heuristic uniform", "nee", "nee --mis"], page: "10-combining-estimators" },
    { name: "the SDS paths: pt, bdpt and vcm with a point light (pages 12, 15)", scene: "sds-point", entries: ["pt", "bdpt", "vcm"], page: "15-vertex-merging" },
    { name: "Metropolis where bdpt struggles: door-hidden (pages 16, 17)", scene: "door-hidden", entries: ["bdpt", "pssmlt", "mmlt", "mlt"], resolution: "128x128", page: "16-metropolis-sampling" },
    // Each mistake beside the right method, at settings where the picture shows it and a number
    // (the ratio of means, the RMSE) says which is right.
    { name: "deliberate mistake --symmetric-refraction on refraction (page 14)", scene: "refraction", entries: ["pt", "pt --symmetric-refraction", "lt", "lt --symmetric-refraction"], page: "14-power-versus-radiance" },
    { name: "deliberate mistake --no-adjoint-correction on shading-normals (page 13)", scene: "shading-normals", entries: ["nee", "lt", "lt --no-adjoint-correction"], page: "13-shading-normals" },
    { name: "deliberate mistake --delta-density-one on glass-box (page 10M)", scene: "glass-box", entries: ["bdpt", "bdpt --delta-density-one"], resolution: "128x128", seconds: 20, page: "10m-mirrors-and-glass" },
    { name: "deliberate mistake --no-scramble on cornell (page 9)", scene: "cornell", entries: ["nee --mis --sampler random", "nee --mis", "nee --mis --no-scramble"], resolution: "128x128", spp: 16, page: "09-russian-roulette-and-sampling" },
    { name: "deliberate mistake --fixed-ray-offset on thin-gap (page 6)", scene: "thin-gap", entries: ["nee", "lt", "lt --fixed-ray-offset"], seconds: 30, page: "06-extending-paths" },
    { name: "deliberate mistake --fixed-start on door-hidden (page 16)", scene: "door-hidden", entries: ["pssmlt", "pssmlt --fixed-start"], resolution: "128x128", page: "16-metropolis-sampling" },
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
    commandReference: "",   // a notes command's --ref (a file the page holds), until the scene changes
    pageReferences: new Map(),  // an edited scene's text -> the reference the page rendered for it
    referenceJob: null,     // that rendering, in a worker of its own, paused while panels run
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
const tileMean = (rgb) => rgb.reduce((a, v) => a + v, 0) / rgb.length;
const luminance = (rgb, i) => (rgb[3 * i] + rgb[3 * i + 1] + rgb[3 * i + 2]) / 3;
const escapeHtml = (s) => String(s).replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;").replace(/"/g, "&quot;");

// ---- scenes
const shortName = (path) => path.replace(/^.*\//, "").replace(/\.scene$/, "");
function sceneName() { return $("scene").value; }
function sceneText() { return $("scene-text").value; }
function scenePath(short) { return Object.keys(BDPT_SCENES).find((p) => shortName(p) === short) || null; }
function loadSceneList() {
    const names = Object.keys(BDPT_SCENES).filter((p) => p.startsWith("scenes/") || p === "tests/thin-gap.scene" || p === "tests/glass-camera.scene");
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
    setCommandReference("");
    $("scene").value = name;
    $("scene-text").value = BDPT_SCENES[name];
    $("scene-error").hidden = true;
    const own = BDPT_SCENES[name].match(/^\s*camera(?:\s+\S+){10}\s+(\d+)\s+(\d+)/m);
    $("resolution").options[0].textContent = own ? `the scene's own (${own[1]} × ${own[2]})` : "the scene's own";
    sceneLines();
    describeEntries();
    referenceState();
    saveState();
}
function sceneLines() {
    const n = $("scene-text").value.split("\n").length;
    $("scene-lines").textContent = Array.from({ length: n }, (_, i) => i + 1).join("\n");
    $("scene-lines").scrollTop = $("scene-text").scrollTop;
}

// ---- references: a notes command's --ref, and the one the page renders for an edited scene
function setCommandReference(path) {
    state.commandReference = path;
    $("command-reference").hidden = !path;
    $("command-reference-name").textContent = path;
}
// The reference's size for the current image setting: at most 64 pixels wide, the image's own
// aspect, and a whole fraction of it (so that a panel and it meet: commonWidth in bdpt-web.cpp).
function referenceSize() {
    let { width: w, height: h } = options();
    if (!w) {
        const own = sceneText().match(/^\s*camera(?:\s+\S+){10}\s+(\d+)\s+(\d+)/m);
        [w, h] = own ? [Number(own[1]), Number(own[2])] : [64, 64];
    }
    for (let f = Math.max(1, Math.ceil(w / 64)); f <= w; ++f) if (w % f === 0 && h % f === 0 && w / f <= 64) return [w / f, h / f];
    return [w, h];
}
// bdpt on this text in a worker of its own, 64 pixels wide, for `seconds` (or `spp` passes), paused
// while panels run: the browser gives a worker no priority, so a run keeps its cores.
function renderReference({ seconds = 300, spp = 0 } = {}) {
    stopReference();
    const [width, height] = referenceSize(), text = sceneText();
    const worker = new Worker(state.workerURL), job = { worker, text, width, height, passes: 0, image: null, id: state.nextId++, done: false };
    state.referenceJob = job;
    state.pageReferences.set(text, job);
    worker.onmessage = (e) => {
        const m = e.data;
        if (m.type === "ready" || m.id !== job.id) return;
        if (m.type === "error") { job.done = true, job.error = m.error; }
        else if (m.type === "frame" || m.type === "done") {
            if (m.passes > 0) job.image = m.image, job.passes = m.passes;
            if (m.type === "done") job.done = true;
        }
        referenceState();
        if (job.done && job.whenDone) job.whenDone();
    };
    worker.postMessage({ type: "start", id: job.id, sceneText: text, sceneName: sceneName(), entry: "bdpt", width, height, seed: 7, spp, seconds: spp ? 0 : seconds,
                         strategyLength: 0, reference: "none" });
    if (state.running) worker.postMessage({ type: "pause" });
    referenceState();
    return new Promise((resolve) => { job.whenDone = resolve; });
}
function stopReference() {
    const job = state.referenceJob;
    if (!job) return;
    if (!job.done) job.worker.postMessage({ type: "stop" });
    setTimeout(() => job.worker.terminate(), 2000);
    state.referenceJob = null;
}
function pauseReference(pause) {
    const job = state.referenceJob;
    if (job && !job.done) job.worker.postMessage({ type: pause ? "pause" : "resume" });
}
function referenceState() {
    const own = state.pageReferences.get(sceneText()), edited = sceneText() !== BDPT_SCENES[sceneName()];
    $("render-reference").disabled = !edited;
    $("reference-state").textContent = !edited ? "the committed scene has its reference (scenes/refs/)"
        : !own ? "this text has no reference: the panels show no error"
        : own.error ? "its reference failed: " + own.error
        : `its reference: bdpt, ${own.width}×${own.height}, ${own.passes} spp${own.done ? "" : state.running ? " so far (paused while the panels run)" : " so far (rendering)"}; the next Start measures against it`;
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
        if (!METHODS.pt) { readCaptions(m.captions); describeEntries(); fillExamples(); }
        if (++state.ready === MAX_PANELS) { $("start").disabled = state.running; showStatus("Ready: choose a scene and methods (or a lesson under Show), then Start (Space)."); }
        return;
    }
    if (m.type === "checked") { state.onChecked && state.onChecked(m.error); return; }
    if (m.type === "path") { receivePath(slot, m); return; }
    const panel = state.panels.find((p) => p.slot === slot && p.id === m.id);
    if (!panel || panel.done) return;  // a message from a run that was replaced, or of a panel ended
    if (m.type === "error") {
        endPanel(panel, m.error.replace("(see --help)", "(see the options under 'The options an entry may carry')"));
    } else if (m.type === "started") {
        Object.assign(panel, { exposure: m.exposure, width: m.width, height: m.height, spp: m.spp, limitSeconds: m.seconds,
                               referenceWidth: m.referenceWidth, referenceHeight: m.referenceHeight, recordsStrategies: m.strategies,
                               referenceName: m.referenceName, commonWidth: m.commonWidth });
        panel.canvas.width = m.width, panel.canvas.height = m.height;
        panel.canvas.style.aspectRatio = `${m.width} / ${m.height}`;
        if (m.threadsGiven) panel.notes.push("--threads: a panel renders on one thread in the page");
        if (m.strategies) pyramidChoices();
    } else if (m.type === "frame" || m.type === "done") {
        Object.assign(panel, { passes: m.passes, rowsDone: m.rowsDone, seconds: m.seconds, image: m.image, mean: m.mean, rmse: m.rmse,
                               rmseWithoutLamp: m.rmseWithoutLamp, bias: m.bias, comparedWidth: m.comparedWidth, nonFinite: m.nonFinite, outOfMemory: m.outOfMemory,
                               relMse: m.relMse, summary: m.summary });
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

// What a panel is measured against: an entry's own scene, its committed reference; a notes
// command's --ref, that file; an edited scene, the reference the page rendered for its text, or
// none (never the unedited scene's: its error would say the opposite of the truth).
function referenceFor(panel, entryOwnScene) {
    if (entryOwnScene) return { reference: "" };
    if (sceneText() !== BDPT_SCENES[sceneName()]) {
        const own = state.pageReferences.get(sceneText());
        panel.edited = own ? "rendered" : "none";
        if (!own || !own.image) return { reference: "none" };
        panel.pageReferencePasses = own.passes;
        return { referenceImage: { width: own.width, height: own.height, data: own.image.slice() } };
    }
    panel.commandReference = !!state.commandReference;  // the notes' own file: its depth is the command's business
    return { reference: state.commandReference ? "/" + state.commandReference : "" };
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
    pauseReference(true);
    state.run = { ...opt, sceneLabel: $("scene").selectedOptions[0].textContent };
    state.runCount = (state.runCount || 0) + 1;
    document.body.classList.add("has-run");
    state.startedAt = performance.now();
    list.slice(0, MAX_PANELS).forEach((text, slot) => {
        const { entry, scene } = entryScene(text);
        const panel = makePanel(text, slot, opt);
        state.panels.push(panel);
        const name = scene || sceneName(), sceneTextToUse = scene ? BDPT_SCENES[scene] : sceneText();
        panel.sceneName = name;
        if (scene && !sceneTextToUse) { endPanel(panel, `the page has no scene ${scene}: its scenes are scenes/*.scene, tests/energy-generator-flat.scene, tests/thin-gap.scene and tests/glass-camera.scene`); return; }
        warnAboutMistakes(panel, entry, sceneTextToUse, name);
        // bdpt and vcm panels record their strategies for the pyramid (paths up to 5 segments, or
        // the entry's --strategy-length, which ./bdpt takes only with --strategies DIR).
        const asked = /(?:^|\s)--strategy-length\s+(\d+)/.exec(entry), recorded = asked ? Math.min(Number(asked[1]), PYRAMID_LENGTH) : PYRAMID_LENGTH;
        const sent = asked ? entry.replace(/\s*--strategy-length\s+\d+/, "") : entry;
        if (asked) panel.notes.push(`--strategy-length ${asked[1]}: the pyramid below records every strategy up to ${recorded} segments`);
        panel.strategyLength = $("record-strategies").checked && /^(bdpt|vcm)\b/.test(entry) ? recorded : 0;
        const reference = referenceFor(panel, scene);
        state.workers[slot].lastMessage = performance.now();
        state.workers[slot].postMessage({ type: "start", id: panel.id, sceneText: sceneTextToUse, sceneName: name, entry: sent, width: opt.width, height: opt.height,
                                          seed: opt.seed, spp: opt.spp, seconds: opt.seconds, strategyLength: panel.strategyLength, ...reference });
    });
    // The pyramid shows the first bdpt or vcm panel in order until a click on another chooses it.
    state.strategyPanel = state.panels.find((p) => p.strategyLength > 0) || null;
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
// (Only this run's panels: a run started within the 2 s is not stopped by it.)
function stop() {
    if (!state.running) return;
    const panels = state.panels;
    panels.forEach((p) => { if (!p.done) state.workers[p.slot].postMessage({ type: "stop" }); });
    setTimeout(() => {
        for (const p of panels) if (!p.done) workerDied(p.slot, "stopped: its worker did not answer");
    }, 2000);
}

function finishRun() {
    if (!state.running) return;
    state.running = false;
    pauseReference(false);
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
        panel.notes.push(`deliberate mistake ${flag}: ${mistakeText(flag, entry, name)}`);
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
        input.title = text ? [describe(entry), ...mistakesIn(entry).map((f) => "deliberate mistake: " + mistakeText(f, entry, sceneName()))].filter((s) => s).join("\n") : "";
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
}
// The entry fields' suggestions: every method and variant, and each mistake on its method.
function fillExamples() {
    const examples = [...Object.keys(METHODS).map((k) => (k === "ir --clamp" ? "ir --clamp 1e-5" : k)),
                      ...Object.keys(MISTAKES).map((f) => ({ "--fixed-start": "pssmlt", "--delta-density-one": "bdpt", "--no-scramble": "nee --mis" }[f] || "lt") + " " + f)];
    $("entry-examples").replaceChildren();
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
    const method = entryScene(entry).entry.split(/\s+/)[0], fn = METHOD_FUNCTIONS[method];
    if (fn && BDPT_CODE.functions[fn]) {
        const a = document.createElement("a");
        a.href = "#", a.className = "code-link", a.textContent = method, a.title = `${fn}() in bdpt.cpp: open it beside the notes`;
        a.onclick = (e) => { e.preventDefault(); state.notesScroll = $("notes-view").scrollTop; openCode(fn); };
        el.querySelector("h2").replaceChildren(a, entry.slice(entry.indexOf(method) + method.length));
    }
    el.querySelector(".what").textContent = describe(entryScene(entry).entry);
    const canvas = el.querySelector("canvas");
    canvas.addEventListener("click", (e) => {
        const r = canvas.getBoundingClientRect();
        if (panel.strategyLength > 0 && state.strategyPanel !== panel) {  // the pyramid and the bars follow the clicked panel
            state.strategyPanel = panel;
            pyramidChoices();
            state.pyramidDirty = true;
        }
        const x = Math.floor((e.clientX - r.left) / r.width * canvas.width), y = Math.floor((e.clientY - r.top) / r.height * canvas.height);
        choosePixel(x, y);
        requestPath(panel, x, y);
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
    if (panel.edited === "none") return "edited scene: no reference (render one for its text under 'Edit the scene's text')";
    if (!panel.referenceWidth) return "no reference for this scene: no error";
    if (!panel.comparedWidth) return panel.passes ? `no error at this size: the reference (${panel.referenceName}) is ${panel.referenceWidth}×${panel.referenceHeight}, ` +
        "and the two meet at no common size of 16 pixels or more (64×64 has a reference for every scene)" : "";
    // The page's references have paths of every length; a notes command's --ref (cornell-direct) need not.
    const partial = /--maxdepth|--strategy-length/.test(panel.entry) && !panel.commandReference ? " (the reference has paths of every length)" : "";
    const at = panel.comparedWidth !== panel.width ? ` at ${panel.comparedWidth}×${panel.comparedWidth * panel.height / panel.width}` : "";
    const bias = `${panel.bias >= 0 ? "+" : ""}${(100 * panel.bias).toFixed(2)}%`;  // as ./bdpt prints it
    const against = panel.edited === "rendered" ? ` against the reference the page rendered for this text (bdpt, ${panel.pageReferencePasses} spp: its own noise included)`
        : panel.referenceName && !/^scenes\/refs\/[\w-]+\.pfm$/.test(panel.referenceName) ? ` against ${panel.referenceName}` : "";
    return `RMSE${at} <b>${fmt4(panel.rmseWithoutLamp)}</b> (${fmt4(panel.rmse)} with the lamp's pixels) · relMSE ${fmt4(panel.relMse)} · bias <b>${bias}</b> (the mean's, the lamp's pixels left out)${against}${partial}`;
}
// The rest of ./bdpt's summary: rays per sample, vcm's light vertices and memory, the chains' b
// and acceptance, the energy the clamp removed: a line each, as the program prints them.
// A panel with a deliberate mistake beside the same entry without it: the ratio of their means,
// as ./bdpt --ratio prints it (which of the two is right, the error against the reference says).
function ratioText(panel) {
    const flags = mistakesIn(panel.entry);
    if (!flags.length || !panel.passes) return "";
    const plain = panel.entry.split(/\s+/).filter((w) => !flags.includes(w)).join(" ");
    const right = state.panels.find((p) => p.entry === plain && p.passes > 0);
    return right && right.mean > 0 ? ` · ratio of means <b>${(panel.mean / right.mean).toFixed(4)}</b> against ${escapeHtml(plain)}` : "";
}
function summaryText(panel) {
    return (panel.summary || "").trim().split("\n").filter((l) => l).map((l) => `<div class="summary">${escapeHtml(l)}</div>`).join("");
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
    panel.el.querySelector(".stats").innerHTML = `<b>${panel.passes}</b> spp · <b>${panel.seconds.toFixed(1)}</b> s · mean <b>${fmt4(panel.mean)}</b>${ratioText(panel)} · ${errorText(panel)}${progress}` +
        (panel.nonFinite > 0 ? ` · ${panel.nonFinite} non-finite dropped` : "") + (panel.outOfMemory ? " · out of memory: stopped" : "") + summaryText(panel);
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
    // a phone gets a narrower drawing, so that its labels are as large there as on a laptop
    const svg = $("chart"), W = innerWidth < 700 ? 560 : 900, H = innerWidth < 700 ? 420 : 460, left = 90, right = 20, top = 15, bottom = 60;
    svg.setAttribute("viewBox", `0 0 ${W} ${H}`);
    const points = state.panels.flatMap((p) => p.curve).filter(([t, e]) => t > 0 && e > 0);
    if (points.length < 2) {
        // Say why there is no curve, in the caption too (it may still list the last run's panels).
        const started = state.panels.filter((p) => p.width), measured = started.filter((p) => p.comparedWidth || (!p.passes && p.referenceWidth && !p.edited));
        const why = !state.panels.length ? "no panel yet"
            : started.length === state.panels.length && !measured.length ? (started.every((p) => p.edited === "none") ? "an edited scene without a reference: no error to chart"
                : started.every((p) => !p.referenceWidth) ? "this scene has no reference (scenes/refs/): no error to chart" : "no error at this size: no reference meets it (64×64 has one for every scene)")
            : "the curves appear as the panels render their passes";
        svg.innerHTML = `<text x="${W / 2}" y="${H / 2}" text-anchor="middle" font-size="${Math.min(22, 1.6 * W / why.length).toFixed(1)}">${why}</text>`;  // one line inside the chart
        $("chart-caption").textContent = "Error against time: " + why;
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
    const w = panel.width, h = panel.height, gap = Math.max(2, w >> 4), line = Math.max(14, h >> 2), strip = 2 * line, margin = Math.max(40, w >> 1);
    return { L, w, h, gap, line, strip, margin, cols: L + 1 + (merges ? 1 : 0), W: margin + (L + 1 + (merges ? 1 : 0)) * (w + gap) + gap,
             H: L * (strip + h + gap) + gap,
             tileX: (k, s) => margin + gap + (L - k) * (w + gap) / 2 + s * (w + gap), tileY: (k) => gap + (k - 1) * (strip + h + gap) + strip };
}
function rowStops(panel, weighted) {
    const L = Math.max(...panel.strategies.map((s) => s.k)), rows = new Array(L + 1).fill(0);
    for (const st of panel.strategies) rows[st.k] += tileMean(weighted ? st.weighted : st.unweighted);  // tiles of one size: means rank as sums
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
    const font = (share) => `${Math.round(g.line * z * share)}px "DejaVu Sans", sans-serif`;
    c.textBaseline = "bottom";
    state.pyramidLabels = [];
    for (const st of panel.strategies) {
        const x = g.tileX(st.k, st.s), y = g.tileY(st.k), img = weighted ? st.weighted : st.unweighted;
        tile.getContext("2d").putImageData(toImageData(img, g.w, g.h, panel.exposure + sliderStops() + stops[st.k]), 0, 0);
        c.drawImage(tile, x * z, y * z, g.w * z, g.h * z);
        // each tile's mean over pixels and colours, as ./bdpt's summary gives an image's: the share of
        // the row's light a strategy carries is read here, not guessed from the exposure
        const mean = tileMean(img), label = [st.s === st.k + 1 ? `merge k=${st.k}` : `s=${st.s} t=${st.k + 1 - st.s}`, `mean ${mean ? mean.toPrecision(3) : 0}`];
        c.font = font(0.7);
        c.fillText(label[0], x * z, (y - g.line - 1) * z, g.w * z);
        c.font = font(0.6);
        c.fillText(label[1], x * z, (y - 2) * z, g.w * z);
        state.pyramidLabels.push(label.join(" "));
    }
    c.font = font(0.7);
    for (let k = 1; k <= g.L; ++k) {
        c.fillText(`k=${k}`, g.gap * z, (g.tileY(k) + g.h / 2) * z);
        if (stops[k]) c.fillText(`+${stops[k]}`, g.gap * z, (g.tileY(k) + g.h / 2 + g.line) * z);
    }
    $("pyramid-caption").textContent = `${panel.entry}, ${panel.passes} spp, ${weighted ? "MIS-weighted: a row's tiles sum to that row of the image" : "unweighted: each strategy alone"}; ` +
        `row k: path length in segments; s: vertices from the light, t: from the camera; mean: the tile's, before the row's +N stops of brightening`;
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
    if (bars.top > innerHeight || bars.bottom < 0) {  // out of sight: say where the click's answer is, where the eye is
        const where = `Pixel (${x}, ${y}): its strategies and one sample's paths are ${bars.top > innerHeight ? "below" : "above"} the panels: show them`;
        showStatus(where);
        const hint = $("tap-hint");  // on a phone the status line is screens away: a bar at the bottom
        if (innerWidth < 1100) hint.textContent = where, hint.hidden = false;
        clearTimeout(state.tapHintTimer);
        state.tapHintTimer = setTimeout(() => (hint.hidden = true), 8000);
    }
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
    const svg = $("bars"), bars = strategyBars(), W = innerWidth < 700 ? 600 : 900, H = 300, left = 80, bottom = 60, top = 20;
    svg.setAttribute("viewBox", `0 0 ${W} ${H}`);
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

// ---- one sample's paths (the path view): the clicked pixel's sample of the last pass, made again
// by its worker from the pixel's own random streams: the camera subpath and the light subpath in
// the image and from the side, each connection (s,t) that carries light, and for the path the
// chosen one makes, every strategy that could make it: its density p and weight w in each heuristic
// (page 7's worked path, for any pixel). The connections and their w_{s,t} are the render's own
// (connectSubpaths, misWeight); the table's densities and weights come from their definitions
// (classroom/physics.h), as the tests judge the renderer.
const HEURISTICS = ["balance", "power", "max", "uniform"];
function requestPath(panel, x, y) {
    if (!/^(bdpt|vcm)\b/.test(entryScene(panel.entry).entry)) return;
    if (!panel.passes) { $("path-caption").textContent = "One sample's paths: the panel has no pass yet; click again when it has"; return; }
    state.workers[panel.slot].postMessage({ type: "path", id: panel.id, x, y });
}
function receivePath(slot, m) {
    const panel = state.panels.find((p) => p.slot === slot && p.id === m.id);
    if (!panel || !m.sample) return;
    const sample = JSON.parse(m.sample), connections = sample.connections;
    // at first the connection that adds most to the pixel, weighted by the panel's heuristic
    const h = panelHeuristic(panel);
    let chosen = 0;
    connections.forEach((c, i) => { if (c.C * c.w[h] > connections[chosen].C * connections[chosen].w[h]) chosen = i; });
    state.path = { panel, x: m.x, y: m.y, sample, outline: JSON.parse(m.outline), chosen };
    drawPath();
}
function panelHeuristic(panel) {
    const m = panel.entry.match(/--heuristic\s+(\w+)/);
    return Math.max(0, HEURISTICS.indexOf(m ? m[1] : "balance"));
}
// The sum of C w over a sample's connections that stay in its pixel (t >= 2), with the weights the render used.
function ownSum(sample) { return sample.connections.reduce((a, c) => a + (c.t >= 2 ? c.C * c.weight : 0), 0); }
// The path of connection c: x_0 ... x_k, light vertices first, the pinhole last.
function pathVertices(sample, c) { return [...sample.light.slice(0, c.s), ...sample.camera.slice(0, c.t).reverse()]; }
function drawPath() {
    const v = state.path;
    if (!v) return;
    const { panel, sample, outline } = v, c = sample.connections[v.chosen];
    const f4 = (x) => (x === 0 ? "0" : Number(x).toPrecision(4));
    $("path-caption").textContent = `One sample of pixel (${v.x}, ${v.y}) of ${panel.entry}, pass ${sample.pass + 1}: the camera subpath (blue, ${sample.camera.length} vertices, ` +
        `the pinhole first) and the light subpath (amber, ${sample.light.length}), and ${sample.connections.length} connection${sample.connections.length === 1 ? "" : "s"} (s,t) ` +
        "that carry light (white; the chosen one thick). Left: in the image; right: from the side (depth across, the camera's up upward)." +
        (sample.mergeEta > 0 ? " vcm: its weights count the merges too (mergeEta " + f4(sample.mergeEta) + "); the chosen path's merges are drawn from the side " +
         "as dashed circles of the merging radius r around the vertex where they would merge (the light subpath's vertex found within r of the camera's)." :
         ` The pixel's value in this pass, ${f4(sample.pixelValue)}, is the sum of C w over the connections with t ≥ 2 (${f4(ownSum(sample))}): ` +
         "this is the pixel's own sample; a t = 1 connection's light lands on the pixel it passes through (light tracing's splat).");
    drawPathImage(panel, sample, c);
    drawPathSide(sample, outline, c);
    // Where its light goes: the pixel's own value (t >= 2), or the pixel light tracing's splat lands on (t = 1).
    const landsOn = (x) => (x.t >= 2 ? "this pixel" : `pixel (${x.pixel % panel.width}, ${Math.floor(x.pixel / panel.width)})`);
    const connRows = sample.connections.map((x, i) => `<tr class="connection${i === v.chosen ? " chosen" : ""}" data-index="${i}"><td>s=${x.s} t=${x.t}</td><td>${x.s + x.t - 1}</td>` +
        `<td class="lands">${landsOn(x)}</td><td>${f4(x.C)}</td>${x.w.map((w) => `<td>${w.toFixed(4)}</td>`).join("")}<td>${f4(x.density)}</td></tr>`).join("");
    const sums = [0, 1, 2, 3].map((h) => c.strategies.reduce((a, st) => a + st.w[h], 0));
    const stRows = c.strategies.slice().sort((a, b) => a.s - b.s || a.merge - b.merge).map((st) => {
        const self = st.s === c.s && !st.merge;
        return `<tr class="${self ? "self" : ""}" data-s="${st.s}" data-merge="${st.merge}"><td>${st.merge ? `merge at x_${st.s - 1}` : `s=${st.s} t=${c.s + c.t - st.s}`}</td>` +
            `<td>${f4(st.density)}</td><td>${f4(st.density / c.density)}</td>${st.w.map((w) => `<td>${w.toFixed(4)}</td>`).join("")}</tr>`;
    }).join("");
    const k = c.s + c.t - 1;
    $("path-tables").innerHTML =
        `<table class="connections"><tr><th>connection</th><th>k</th><th>its light goes to</th><th>C<sub>s,t</sub> (unweighted)</th>${HEURISTICS.map((h) => `<th>w<sub>s,t</sub> ${h}</th>`).join("")}<th>p<sub>s,t</sub></th></tr>${connRows}</table>` +
        `<p>The path of s=${c.s} t=${c.t}: x<sub>0</sub> … x<sub>${k}</sub> (${pathVertices(sample, c).map((x) => x.kind).join(", ")}), k = ${k} segments. ` +
        `Every strategy that can make it, its density p from its definition (area measure, the product of its vertices' densities; through a mirror or glass the chain's factor that every strategy shares is left out) and its weight in each heuristic: ` +
        `each column of weights sums to 1 (unbiased), and the row in bold is the renderer's own w<sub>s,t</sub> above.` +
        (k === 1 ? ` <span class="direct-rule">k = 1 is the light seen directly: the renderer gives it to s = 0 alone, whatever the densities ` +
                   `(misWeight(): w = 1 for s = 0, 0 for s = 1 t = 1, in every heuristic; pages 1 and 3), so a point light, which s = 0 cannot hit, stays unseen ` +
                   `as in pbrt; the heuristics' formulas are not applied to this row.</span>` : "") + `</p>` +
        `<table class="strategies"><tr><th>strategy</th><th>p<sub>${k},s</sub></th><th>/ p<sub>s,t</sub></th>${HEURISTICS.map((h) => `<th>${h}</th>`).join("")}</tr>${stRows}` +
        `<tr class="sums"><td>sum</td><td></td><td></td>${sums.map((x) => `<td data-sum="${x}">${x.toFixed(4)}</td>`).join("")}</tr></table>`;
    $("path-tables").querySelectorAll("tr.connection").forEach((row) => (row.onclick = () => { state.path.chosen = Number(row.dataset.index); drawPath(); }));
}
// Polylines of a subpath's vertices at the given 2-D positions (null: not drawable; the line breaks).
function polyline(points, colour, width, dash) {
    const runs = [[]];
    for (const p of points) p ? runs[runs.length - 1].push(p) : runs.push([]);
    return runs.filter((r) => r.length > 1).map((r) => `<polyline fill="none" stroke="${colour}" stroke-width="${width}" ${dash ? `stroke-dasharray="${dash}"` : ""} ` +
        `points="${r.map(([x, y]) => `${x.toFixed(3)},${y.toFixed(3)}`).join(" ")}"/>`).join("");
}
function dots(points, colour, r, kind) {
    return points.map((p, i) => (p ? `<circle class="${kind}" data-i="${i}" cx="${p[0].toFixed(3)}" cy="${p[1].toFixed(3)}" r="${r}" fill="${colour}"/>` : "")).join("");
}
function drawPathImage(panel, sample, c) {
    const svg = $("path-image"), W = panel.width, H = panel.height, u = W / 64;
    const canvas = document.createElement("canvas");
    canvas.width = W, canvas.height = H;
    canvas.getContext("2d").putImageData(toImageData(panel.image, W, H, panel.exposure + sliderStops()), 0, 0);
    svg.setAttribute("viewBox", `0 0 ${W} ${H}`);
    const cam = [sample.film, ...sample.camera.slice(1).map((v) => v.film)], light = sample.light.map((v) => v.film);
    let html = `<image href="${canvas.toDataURL()}" x="0" y="0" width="${W}" height="${H}" style="image-rendering: pixelated" opacity="0.55"/>`;
    for (const x of sample.connections) {
        const a = x.s > 0 ? sample.light[x.s - 1].film : null, b = x.t > 1 ? sample.camera[x.t - 1].film : x.t === 1 ? null : null;
        if (x.t === 1 && a) html += polyline([a, [((x.pixel % W) + 0.5), (Math.floor(x.pixel / W) + 0.5)]], "#ffffff", (x === c ? 0.8 : 0.3) * u, "1.5 1");
        else if (a && b) html += polyline([a, b], "#ffffff", (x === c ? 0.8 : 0.3) * u, x === c ? "" : "1.5 1");
    }
    html += polyline(cam, "#4dabf7", 0.5 * u) + polyline(light, "#ffb000", 0.5 * u) + dots(cam, "#4dabf7", 0.9 * u, "camera") + dots(light, "#ffb000", 0.9 * u, "light");
    svg.innerHTML = html;
}
function drawPathSide(sample, outline, c) {
    const svg = $("path-side"), sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]], dot3 = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    const P = (p) => [dot3(sub(p, outline.eye), outline.forward), -dot3(sub(p, outline.eye), outline.up)];
    const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
    const quads = outline.quads.map(([q, e1, e2, lamp]) => ({ lamp, corners: [q, add(q, e1), add(add(q, e1), e2), add(q, e2)].map(P) }));
    const spheres = outline.spheres.map(([centre, r]) => ({ centre: P(centre), r }));
    const all = [P(outline.eye), ...quads.flatMap((q) => q.corners), ...spheres.flatMap((s) => [[s.centre[0] - s.r, s.centre[1] - s.r], [s.centre[0] + s.r, s.centre[1] + s.r]]),
                 ...sample.camera.map((v) => P(v.p)), ...sample.light.map((v) => P(v.p)), ...outline.points.map(P)];
    const x0 = Math.min(...all.map((p) => p[0])), x1 = Math.max(...all.map((p) => p[0])), y0 = Math.min(...all.map((p) => p[1])), y1 = Math.max(...all.map((p) => p[1]));
    const pad = 0.05 * Math.max(x1 - x0, y1 - y0), u = Math.max(x1 - x0, y1 - y0) / 100;
    svg.setAttribute("viewBox", `${x0 - pad} ${y0 - pad} ${x1 - x0 + 2 * pad} ${y1 - y0 + 2 * pad}`);
    let html = quads.map((q) => `<polygon fill="none" stroke="${q.lamp ? "#ffb000" : "#777"}" stroke-width="${0.4 * u}" points="${q.corners.map((p) => p.join(",")).join(" ")}"/>`).join("") +
        spheres.map((s) => `<circle cx="${s.centre[0]}" cy="${s.centre[1]}" r="${s.r}" fill="none" stroke="#777" stroke-width="${0.4 * u}"/>`).join("") +
        outline.points.map((p) => `<circle cx="${P(p)[0]}" cy="${P(p)[1]}" r="${1.2 * u}" fill="#ffb000"/>`).join("");
    const cam = sample.camera.map((v) => P(v.p)), light = sample.light.map((v) => P(v.p));
    if (sample.mergeEta > 0) {  // the chosen path's merges: radius r from mergeEta = pi r^2 N, N the light paths of a pass
        const r = Math.sqrt(sample.mergeEta / (Math.PI * state.path.panel.width * state.path.panel.height)), x = pathVertices(sample, c);
        for (const st of c.strategies.filter((st) => st.merge)) {
            const at = P(x[st.s - 1].p);
            html += `<circle class="merge" cx="${at[0]}" cy="${at[1]}" r="${r}" fill="none" stroke="#e64980" stroke-width="${0.4 * u}" stroke-dasharray="${u} ${u}"/>`;
        }
    }
    for (const x of sample.connections) if (x.s > 0) html += polyline([P(sample.light[x.s - 1].p), P(sample.camera[x.t - 1].p)], "#ffffff", (x === c ? 0.9 : 0.3) * u, x === c ? "" : `${2 * u} ${u}`);
    html += polyline(cam, "#4dabf7", 0.6 * u) + polyline(light, "#ffb000", 0.6 * u) + dots(cam, "#4dabf7", 1.1 * u, "camera") + dots(light, "#ffb000", 1.1 * u, "light");
    svg.innerHTML = html;
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
// A display formula wider than the notes' column is set smaller until it fits (down to 0.5em,
// past that it scrolls): a formula cut at the right edge reads as a different formula.
function fitFormulas(root) {
    for (const d of root.querySelectorAll(".katex-display")) {
        const k = d.querySelector(".katex");
        if (!k) continue;
        k.style.fontSize = "";
        if (!d.clientWidth || d.scrollWidth <= d.clientWidth) continue;
        let size = 1.21;  // KaTeX's own size, em; its spacing does not all scale with it: a few rounds
        for (let round = 0; round < 4 && d.scrollWidth > d.clientWidth && size > 0.5; ++round)
            size = Math.max(0.5, size * 0.97 * d.clientWidth / d.scrollWidth), k.style.fontSize = `${size}em`;
    }
}
function openNotes(file, anchor) {
    const i = Math.max(0, notesIndex(file)), page = BDPT_NOTES[i], text = $("notes-text");
    state.notesPage = page.file;
    $("notes-page").value = page.file;
    text.innerHTML = page.html;
    linkPages(text);
    linkCode(text);
    addCommandButtons(text);
    fitFormulas(text);
    if (!$("code-view").hidden) closeCode();
    const target = anchor && text.querySelector(`[id="${CSS.escape(anchor)}"]`);
    if (target) target.scrollIntoView(); else text.scrollTop = 0, $("notes-view").scrollTop = 0;
    saveState();
}
// ---- the code view: bdpt.cpp (and two classroom headers) in the notes' column, highlighted at
// build time (build_code.js); a function the notes cite, or a panel's method, opens it there.
const METHOD_FUNCTIONS = { pt: "samplePT", nee: "sampleNEE", lt: "sampleLT", ir: "sampleIR", bdpt: "sampleBDPT", vcm: "sampleVCM",
                           pssmlt: "sampleMLT", mmlt: "sampleMLT", mlt: "sampleMLT" };
function openCode(name) {
    const where = BDPT_CODE.functions[name];
    if (!where) return false;
    const [file, line, end] = where;
    showCodeFile(file);
    const text = $("code-text");
    text.querySelectorAll(".line.target").forEach((l) => l.classList.remove("target"));
    for (let n = line; n <= end; ++n) text.children[n - 1].classList.add("target");
    $("code-where").textContent = `${name}(): ${file}, lines ${line}-${end}`;
    $("notes-text").hidden = true;
    $("code-view").hidden = false;
    if (document.body.classList.contains("no-notes")) $("notes-toggle").click();
    // the definition a few lines below the column's top, under its sticky bar
    const view = $("notes-view"), bar = $("code-view").querySelector(".code-bar");
    view.scrollTop += text.children[line - 1].getBoundingClientRect().top - view.getBoundingClientRect().top - bar.offsetHeight - 8;
    state.codeFunction = name;
    return true;
}
function showCodeFile(file) {
    if (state.codeFile === file) return;
    state.codeFile = file;
    $("code-file").value = file;
    // a block per line (long ones wrap, style.css), its newline inside it, so a copy keeps the lines
    $("code-text").innerHTML = BDPT_CODE.files[file].map((html, i) => `<span class="line" data-n="${i + 1}">${html}\n</span>`).join("");
}
function closeCode() {
    $("code-view").hidden = true;
    $("notes-text").hidden = false;
    state.codeFunction = null;
    const anchor = state.notesScroll || 0;
    $("notes-view").scrollTop = anchor;
}
// `name()` in a page's text: a link to its definition, where the code view has it.
function linkCode(root) {
    for (const code of root.querySelectorAll("code")) {
        const m = !code.closest("pre") && code.textContent.match(/^([A-Za-z_]\w*)\(\)$/);
        if (!m || !BDPT_CODE.functions[m[1]]) continue;
        const [file, line] = BDPT_CODE.functions[m[1]];
        const a = document.createElement("a");
        a.href = "#", a.className = "code-link", a.dataset.function = m[1], a.title = `${file}, line ${line}: open it beside the notes`;
        code.replaceWith(a);
        a.append(code);
    }
}

// A notes figure at its own size (the notes column shows it shrunk, its labels unreadable).
function showFigure(img) {
    const view = $("figure-view");
    view.querySelector("img").src = img.src;
    view.querySelector("img").alt = img.alt;
    view.hidden = false;
    view.scrollTop = view.scrollLeft = 0;
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
const FIGURE_OPTIONS = ["--out", "--title", "--ratio-panel", "--strategies", "--log", "--live", "--strategy-length"];
// The references the page holds: scenes/refs/*.pfm and the one test reference the notes name.
const PAGE_REFERENCES = /^(scenes\/refs\/[\w-]+|tests\/refs\/cornell-direct)\.pfm$/;
const FLAGS = ["--overwrite", "--quiet", "--profile"];
function parseCommand(line) {
    const words = splitWords(line.trim());
    if (words[0] !== "./bdpt") return { reason: "run it in a terminal, in the repository's folder" };
    if (words.includes("--ratio")) return { reason: "--ratio compares two files: run it in a terminal after the renders (in the page, two panels of the same scene, one with a mistake's flag, show their ratio of means)" };
    for (const tool of ["--compare", "--average"])
        if (words.includes(tool)) return { reason: `${tool} reads two PFM files the renders wrote: in the page, render both as panels instead; each panel's RMSE, relMSE and bias against the scene's reference, and a mistake's ratio of means, stand for it` };
    if (words.some((w) => /^[A-Z]{2,}(\.\w+)?$/.test(w))) return { reason: "a template: put your own values for its capitals and run it in a terminal" };
    // strategies: the pyramid's record (and its rays, the (1,1) connections') only where ./bdpt's --strategies asks for it
    const written = words.find((w) => /^build\/.*\.scene$/.test(w));  // a scene the exercise has the student write
    if (written) return { reason: `${written} is a scene you write: in the page, choose the scene it starts from, make the change in the scene editor (its text, above the panels) and press Start with these options` };
    const settings = { scene: null, entries: null, method: null, spp: 0, seconds: 0, resolution: "0x0", seed: 1, shared: [], reference: "", strategies: false };
    for (let i = 1; i < words.length; ++i) {
        const w = words[i], v = words[i + 1];
        if (w === "--side-by-side") settings.entries = v.split(",").map((e) => e.trim()), ++i;
        else if (w === "--method") settings.method = v, ++i;
        else if (w === "--spp") settings.spp = Number(v), ++i;
        else if (w === "--time" || w === "--wall-time") settings.seconds = Number(v), ++i;
        else if (w === "--res") settings.resolution = v, ++i;
        else if (w === "--seed") settings.seed = Number(v), ++i;
        else if (w === "--ref") {
            if (!PAGE_REFERENCES.test(v || "")) return { reason: `its reference ${v} is a file you render first: run it in a terminal (or, in the page, edit the scene and render its reference there)` };
            settings.reference = v, ++i;
        }
        else if (FIGURE_OPTIONS.includes(w)) { if (w === "--strategies") settings.strategies = true; ++i; }
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
    setCommandReference(s.reference || "");
    setResolution(s.resolution);
    $("spp").value = s.spp;
    $("seconds").value = s.seconds || (s.spp ? 0 : 10);
    $("seed").value = s.seed;
    if ("strategies" in s) $("record-strategies").checked = s.strategies;
    if ("weighted" in s) $("weighted").checked = s.weighted;
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
// The figure a command block makes: the image in the paragraphs just above it, if any.
function figureBefore(code) {
    let node = code.closest("pre") || code.closest("p");
    for (let i = 0; node && i < 3; ++i) {
        node = node.previousElementSibling;
        const img = node && (node.matches("img") ? node : node.querySelector("img"));
        if (img) return img;
    }
    return null;
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
                const figure = figureBefore(code);  // the pyramid the figure above shows: weighted or each alone
                if (parsed.settings.strategies && figure) parsed.settings.weighted = !/unweighted/.test(figure.getAttribute("src"));
                b.textContent = `▶ Run in the page (${n} panel${n > 1 ? "s" : ""})`;
                // several commands in one block: each button says which it runs
                if (lines.length > 1) b.textContent += `: ${parsed.settings.entries.join(", ")}`;
                if (/--ratio-panel/.test(line)) b.textContent += " (the ratio image is the terminal's figure: the page shows both panels, each with its error)";
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
        // a command inside a sentence gets its buttons after the sentence's paragraph, not inside it
        const block = code.closest("pre") ? null : code.closest("p, li");
        if (code.closest("pre")) code.closest("pre").after(bar);
        else if (block) bar.classList.add("after-text"), block.append(bar);
        else code.after(bar);
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
    $("scene-text").addEventListener("input", () => { sceneLines(); describeEntries(); referenceState(); saveState(); });
    $("render-reference").onclick = () => renderReference();
    $("command-reference-clear").onclick = () => setCommandReference("");
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
        applySettings({ scene: scenePath(p.scene), entries: p.entries, spp: p.spp || 0, seconds: p.spp ? 0 : p.seconds || 10, seed: 1, resolution: p.resolution || "64x64",
                        strategies: true });  // a lesson shows its pyramid
        if (p.page) openNotes(p.page);
        $("preset").value = "";
    };
    $("notes-page").onchange = () => openNotes($("notes-page").value);
    $("notes-previous").onclick = () => openNotes(BDPT_NOTES[Math.max(0, notesIndex(state.notesPage) - 1)].file);
    $("notes-next").onclick = () => openNotes(BDPT_NOTES[Math.min(BDPT_NOTES.length - 1, notesIndex(state.notesPage) + 1)].file);
    $("notes-text").addEventListener("click", (e) => {
        const a = e.target.closest("a[data-page]");
        if (a) { e.preventDefault(); openNotes(a.dataset.page, a.dataset.anchor); }
        const c = e.target.closest("a.code-link");
        if (c) { e.preventDefault(); state.notesScroll = $("notes-view").scrollTop; openCode(c.dataset.function); }
        if (e.target.matches("img")) showFigure(e.target);
    });
    $("figure-view").onclick = () => ($("figure-view").hidden = true);
    $("code-back").onclick = closeCode;
    $("tap-hint").onclick = () => { $("tap-hint").hidden = true; $("bars-figure").scrollIntoView(); };
    for (const file of Object.keys(BDPT_CODE.files)) $("code-file").append(new Option(file, file));
    $("code-file").onchange = () => { showCodeFile($("code-file").value); $("code-where").textContent = ""; $("notes-view").scrollTop = 0; };
    $("notes-toggle").onclick = () => {
        const hidden = document.body.classList.toggle("no-notes");
        $("notes-toggle").textContent = hidden ? "Show the notes" : "Hide the notes";
    };
    $("share").onclick = () => {
        saveState();
        navigator.clipboard && navigator.clipboard.writeText(location.href).catch(() => {});
        showStatus("This setting's link (copied, where the browser allows): " + location.href);
    };
    window.addEventListener("resize", () => { fitFormulas($("notes-text")); drawChart(); });  // the chart's drawing depends on the width
    document.addEventListener("keydown", (e) => {
        if (e.target.matches("input:not([type=range]):not([type=checkbox]), textarea, select")) return;  // typing
        const ex = $("exposure");
        if (e.key === " ") { e.preventDefault(); state.running ? stop() : start(); }
        else if (e.key === "Escape") { if (!$("figure-view").hidden) $("figure-view").hidden = true; else stop(); }
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
    setSceneText: (text) => { $("scene-text").value = text; sceneLines(); describeEntries(); referenceState(); },
    applyCommand: (line) => { const parsed = parseCommand(line); if (parsed.settings) applySettings(parsed.settings); return parsed.reason || ""; },
    renderReference,   // ({seconds, spp}): resolves when the page's own reference is done
    referenceState: () => $("reference-state").textContent,
    setEntries: (list) => { entryInputs().forEach((e, i) => { e.value = list[i] || ""; }); describeEntries(); },
    setOptions: (o) => {
        if (o.resolution) setResolution(o.resolution);
        for (const k of ["seconds", "spp", "seed"]) if (k in o) $(k).value = o[k];
        if ("strategies" in o) $("record-strategies").checked = o.strategies;
    },
    run: () => start(),
    stop,
    running: () => state.running,
    runs: () => state.runCount || 0,  // runs started: a test waits for the next one
    longestFrameGap: () => state.longestFrameGap,  // ms between two drawn frames during the last run
    sceneError: () => ($("scene-error").hidden ? "" : $("scene-error").textContent),
    panels: () => state.panels.map((p) => ({ entry: p.entry, passes: p.passes, seconds: p.seconds, mean: p.mean, rmse: p.rmse, rmseWithoutLamp: p.rmseWithoutLamp, bias: p.bias,
                                             error: p.error, done: p.done, nonFinite: p.nonFinite, firstFrameMs: p.firstFrameMs, firstFramePasses: p.firstFramePasses, curve: p.curve,
                                             strategies: p.strategies ? p.strategies.length : 0, width: p.width, height: p.height,
                                             comparedWidth: p.comparedWidth, commonWidth: p.commonWidth, referenceWidth: p.referenceWidth, notes: p.notes, what: p.el.querySelector(".what").textContent,
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
    pyramidLabels: () => state.pyramidLabels || [],  // the tiles' labels as drawn: "s=2 t=1 mean 0.125"
    clickPixel: (panelIndex, x, y) => {
        const p = state.panels[panelIndex], r = p.canvas.getBoundingClientRect();
        p.canvas.dispatchEvent(new MouseEvent("click", { clientX: r.left + (x + 0.5) / p.width * r.width, clientY: r.top + (y + 0.5) / p.height * r.height, bubbles: true }));
        return [...$("bars").querySelectorAll("rect")].map((b) => ({ strategy: b.dataset.strategy, kind: b.dataset.kind, value: Number(b.dataset.value) }));
    },
    openNotes,
    // The notes' `name()` links on the open page, and what the code view shows after a click on one.
    codeLinks: () => [...document.querySelectorAll("#notes-text a.code-link")].map((a) => a.dataset.function),
    citedFunctions: () => [...document.querySelectorAll("#notes-text code")].filter((c) => !c.closest("pre") && /^[A-Za-z_]\w*\(\)$/.test(c.textContent)).map((c) => c.textContent.slice(0, -2)),
    clickCodeLink: (name) => {
        const a = document.querySelector(`#notes-text a.code-link[data-function="${name}"]`);
        if (!a) return null;
        a.click();
        return bdptPage.codeShown();
    },
    openCode: (name) => (openCode(name) ? bdptPage.codeShown() : null),
    clickPanelMethod: (i) => { state.panels[i].el.querySelector("h2 a.code-link").click(); return bdptPage.codeShown(); },
    codeShown: () => {
        if ($("code-view").hidden) return null;
        const view = $("notes-view").getBoundingClientRect(), lines = [...$("code-text").querySelectorAll(".line.target")];
        const first = lines[0], r = first && first.getBoundingClientRect();
        const text = (l) => l.textContent.replace(/\n$/, "");  // a line's text without the newline its block carries
        return { where: $("code-where").textContent, first: first ? text(first) : "", lines: lines.length, firstLine: first ? Number(first.dataset.n) : 0,
                 marked: lines.map(text),
                 inView: !!r && r.top >= view.top && r.bottom <= view.bottom, beside: view.right <= $("live").getBoundingClientRect().left + 1 };
    },
    notesButtons: () => [...document.querySelectorAll("#notes-text .run-command")].map((b) => ({ command: b.dataset.command, runs: b.tagName === "BUTTON", reason: b.dataset.reason || "", label: b.textContent })),
    clickNotesButton: (command) => {
        const b = [...document.querySelectorAll("#notes-text button.run-command")].find((x) => x.dataset.command === command);
        if (!b || b.disabled) return false;
        b.click();
        return true;
    },
    // The path view as drawn: the pixel, each connection's weights, the chosen path's vertices and
    // strategies, and the sums of its columns of weights as the table shows them.
    pathView: () => {
        const v = state.path;
        if (!v) return null;
        const c = v.sample.connections[v.chosen];
        return { entry: v.panel.entry, x: v.x, y: v.y, pass: v.sample.pass, width: v.panel.width, height: v.panel.height,
                 pixelValue: v.sample.pixelValue, ownSum: ownSum(v.sample),
                 connections: v.sample.connections.map((x) => ({ s: x.s, t: x.t, C: x.C, w: x.w, weight: x.weight, pixel: x.pixel, strategies: x.strategies.length })),
                 chosen: { s: c.s, t: c.t, w: c.w, vertices: pathVertices(v.sample, c).map((x) => ({ p: x.p, kind: x.kind })), strategies: c.strategies },
                 sums: [...document.querySelectorAll("#path-tables tr.sums td[data-sum]")].map((td) => Number(td.dataset.sum)),
                 table: [...document.querySelectorAll("#path-tables table.strategies tr[data-s]")].map((tr) => [...tr.cells].map((td) => td.textContent)),
                 drawn: { camera: $("path-image").querySelectorAll("circle.camera").length, light: $("path-image").querySelectorAll("circle.light").length,
                          sideCamera: $("path-side").querySelectorAll("circle.camera").length, lines: $("path-image").querySelectorAll("polyline").length,
                          merges: $("path-side").querySelectorAll("circle.merge").length },
                 landsOn: [...document.querySelectorAll("#path-tables td.lands")].map((td) => td.textContent),
                 directRule: !!document.querySelector("#path-tables .direct-rule") };
    },
    choosePath: (i) => { state.path.chosen = i; drawPath(); return bdptPage.pathView(); },
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
