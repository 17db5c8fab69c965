// One panel's render: a module instance of the renderer (bdpt-web.cpp, whose loader precedes this
// text in engine.js) on this worker's own thread. The page sends {type: "start", ...} and "stop";
// the worker answers with a "frame" about five times a second (the image so far, its samples,
// seconds and error) and "done" at the end. The page's thread only draws. The worker renders a
// row at a time in slices of about 40 ms, so that a "stop" is read between them and a large
// pass shows its rows as they come.
let api = null;          // the module's functions, once it is loaded
let job = null;          // the render in progress
const pending = [];      // messages that came before the module

createBdpt().then((module) => {
    const fn = (name, ret, args) => module.cwrap(name, ret, args);
    api = {
        module,
        start: fn("bdpt_start", "string", ["string", "string", "string", "number", "number", "number", "number", "number", "number", "string"]),
        referenceBuffer: fn("bdpt_reference_buffer", "number", ["number", "number"]),
        referenceName: fn("bdpt_reference_name", "string", []),
        summary: fn("bdpt_summary", "string", []),
        relMse: fn("bdpt_relmse", "number", []),
        pathSample: fn("bdpt_path_sample", "string", ["number", "number"]),
        sceneOutline: fn("bdpt_scene_outline", "string", []),
        row: fn("bdpt_row", "number", []),
        rowsDone: fn("bdpt_rows_done", "number", []),
        snapshot: fn("bdpt_snapshot", null, []),
        image: fn("bdpt_image", "number", []),
        width: fn("bdpt_width", "number", []),
        height: fn("bdpt_height", "number", []),
        spp: fn("bdpt_spp", "number", []),
        seconds: fn("bdpt_seconds", "number", []),
        threadsGiven: fn("bdpt_threads_given", "number", []),
        exposure: fn("bdpt_exposure", "number", []),
        nonFinite: fn("bdpt_non_finite", "number", []),
        referenceWidth: fn("bdpt_reference_width", "number", []),
        referenceHeight: fn("bdpt_reference_height", "number", []),
        comparedWidth: fn("bdpt_compared_width", "number", []),
        commonWidth: fn("bdpt_common_width", "number", []),
        mean: fn("bdpt_mean", "number", []),
        rmse: fn("bdpt_rmse", "number", []),
        rmseWithoutLamp: fn("bdpt_rmse_without_lamp", "number", []),
        bias: fn("bdpt_bias", "number", []),
        strategies: fn("bdpt_strategies", "string", []),
        strategyImage: fn("bdpt_strategy_image", "number", ["number", "number"]),
        checkScene: fn("bdpt_check_scene", "string", ["string", "string"]),
        help: fn("bdpt_help", "string", []),
        captions: fn("bdpt_method_captions", "string", []),
    };
    postMessage({ type: "ready", help: api.help(), captions: api.captions() });
    for (const m of pending.splice(0)) onmessage({ data: m });
});

// A copy of n floats at pointer p of the module's memory (which may move when it grows).
function floats(p, n) {
    return new Float32Array(api.module.HEAPF32.buffer, p, n).slice();
}

// Every strategy's image, weighted and not, for the pyramid and the pixel's bar chart.
function strategyImages(n) {
    const list = api.strategies().split(";").filter((e) => e);
    return list.map((e) => {
        const [k, s, index] = e.split(" ").map(Number);
        return { k, s, unweighted: floats(api.strategyImage(index, 0), n), weighted: floats(api.strategyImage(index, 1), n) };
    });
}

function frame(final) {
    api.snapshot();
    const w = api.width(), h = api.height(), n = 3 * w * h, compared = api.comparedWidth() > 0;
    const message = {
        type: final ? "done" : "frame", id: job.id, width: w, height: h, passes: job.passes, rowsDone: api.rowsDone(), seconds: job.seconds,
        image: floats(api.image(), n), mean: api.mean(), nonFinite: api.nonFinite(),
        rmse: compared ? api.rmse() : null, rmseWithoutLamp: compared ? api.rmseWithoutLamp() : null, bias: compared ? api.bias() : null, comparedWidth: api.comparedWidth(),
        relMse: compared ? api.relMse() : null, summary: api.summary(),
        outOfMemory: job.outOfMemory,
    };
    // The strategies change a little with every pass: sent once a second (and with a new pass at first).
    const now = performance.now();
    if (job.strategies && job.passes > job.strategyPasses && (final || now - job.lastStrategies > 1000 || job.strategyPasses === 0)) {
        job.lastStrategies = now;
        job.strategyPasses = job.passes;
        message.strategies = strategyImages(n);
    }
    const transfer = [message.image.buffer];
    if (message.strategies) for (const s of message.strategies) transfer.push(s.unweighted.buffer, s.weighted.buffer);
    postMessage(message, transfer);
    job.lastFrame = now;
}

// A slice of rows, then a yield through a message channel (setTimeout would wait 4 ms).
const channel = new MessageChannel();
channel.port1.onmessage = slice;
function slice() {
    if (!job || job.stopped || job.paused) return;
    const t0 = performance.now();
    do {
        const passes = api.row();
        if (passes < 0) { job.outOfMemory = true; break; }
        job.passes = passes;
        // a frame at every power of two passes as well: the chart's log axis gets its points at
        // 1, 2, 4, 8, ... passes, however fast the passes go
        if (passes > job.framedPasses && (passes & (passes - 1)) === 0 && api.rowsDone() === 0 && !finished()) {
            job.framedPasses = passes;
            job.seconds += (performance.now() - t0) / 1000;
            frame(false);
            channel.port2.postMessage(0);
            return;
        }
    } while (performance.now() - t0 < 40 && !finished());
    job.seconds += (performance.now() - t0) / 1000;
    if (job.outOfMemory || finished()) { frame(true); job = null; return; }
    if (performance.now() - job.lastFrame > 200) frame(false);
    channel.port2.postMessage(0);
}
function finished() {
    if (api.rowsDone() > 0) return false;  // a pass ends whole
    return (job.spp > 0 && job.passes >= job.spp) || (job.spp === 0 && job.limitSeconds > 0 && job.seconds >= job.limitSeconds);
}

onmessage = (event) => {
    const m = event.data;
    if (!api) { pending.push(m); return; }
    if (m.type === "check") {
        postMessage({ type: "checked", id: m.id, error: api.checkScene(m.sceneText, m.sceneName) });
    } else if (m.type === "start") {
        let reference = m.reference || "";
        if (m.referenceImage) {  // the page's own reference (an edited scene's): into the module's buffer
            const r = m.referenceImage;
            api.module.HEAPF32.set(r.data, api.referenceBuffer(r.width, r.height) >> 2);
            reference = "given";
        }
        const error = api.start(m.sceneText, m.sceneName, m.entry, m.width, m.height, m.spp, m.seconds, m.seed, m.strategyLength, reference);
        if (error) { job = null; postMessage({ type: "error", id: m.id, error }); return; }
        job = { id: m.id, spp: api.spp(), limitSeconds: api.seconds(), passes: 0, seconds: 0, strategies: m.strategyLength > 0 && api.strategies() !== "",
                lastStrategies: -1e9, strategyPasses: 0, lastFrame: performance.now(), outOfMemory: false, stopped: false, paused: false, framedPasses: 0 };
        postMessage({ type: "started", id: m.id, exposure: api.exposure(), width: api.width(), height: api.height(), spp: job.spp, seconds: job.limitSeconds,
                      referenceWidth: api.referenceWidth(), referenceHeight: api.referenceHeight(), strategies: job.strategies,
                      threadsGiven: !!api.threadsGiven(), referenceName: api.referenceName(), commonWidth: api.commonWidth() });
        slice();
    } else if (m.type === "path") {  // one sample's paths at a pixel of the last pass (the page's path view)
        const sample = api.pathSample(m.x, m.y);
        postMessage({ type: "path", id: m.id, x: m.x, y: m.y, sample, outline: sample ? api.sceneOutline() : "" });
    } else if (m.type === "pause") {
        if (job) job.paused = true;
    } else if (m.type === "resume") {
        if (job && job.paused) { job.paused = false; channel.port2.postMessage(0); }
    } else if (m.type === "stop") {
        if (job) { job.stopped = true; frame(true); job = null; }
        else postMessage({ type: "idle", id: m.id });
    }
};
