// One panel's render: a module instance of bdpt-web.wasm on this worker's own thread. The page
// sends {type: "start", ...} and "stop"; the worker answers with a "frame" after every slice of
// passes (the image so far, its samples, seconds and error) and "done" at the end. The page's
// thread only draws. Passes run in slices of about 40 ms, so that a "stop" is read between them.
importScripts("bdpt-web.js");

let api = null;          // the module's functions, once it is loaded
let job = null;          // the render in progress
const pending = [];      // messages that came before the module

const ready = createBdpt().then((module) => {
    const fn = (name, ret, args) => module.cwrap(name, ret, args);
    api = {
        module,
        start: fn("bdpt_start", "string", ["string", "string", "string", "number", "number", "number", "number"]),
        pass: fn("bdpt_pass", "number", []),
        image: fn("bdpt_image", "number", []),
        width: fn("bdpt_width", "number", []),
        height: fn("bdpt_height", "number", []),
        exposure: fn("bdpt_exposure", "number", []),
        nonFinite: fn("bdpt_non_finite", "number", []),
        hasReference: fn("bdpt_has_reference", "number", []),
        mean: fn("bdpt_mean", "number", []),
        rmse: fn("bdpt_rmse", "number", []),
        rmseWithoutLamp: fn("bdpt_rmse_without_lamp", "number", []),
        strategies: fn("bdpt_strategies", "string", []),
        strategyImage: fn("bdpt_strategy_image", "number", ["number", "number"]),
        checkScene: fn("bdpt_check_scene", "string", ["string", "string"]),
    };
    postMessage({ type: "ready" });
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
    const w = api.width(), h = api.height(), n = 3 * w * h;
    const message = {
        type: final ? "done" : "frame", id: job.id, width: w, height: h, passes: job.passes, seconds: job.seconds,
        image: floats(api.image(), n), mean: api.mean(), nonFinite: api.nonFinite(),
        rmse: api.hasReference() ? api.rmse() : null, rmseWithoutLamp: api.hasReference() ? api.rmseWithoutLamp() : null,
        outOfMemory: job.outOfMemory,
    };
    const now = performance.now();
    if (job.strategies && (final || now - job.lastStrategies > 1000)) {
        job.lastStrategies = now;
        message.strategies = strategyImages(n);
    }
    const transfer = [message.image.buffer];
    if (message.strategies) for (const s of message.strategies) transfer.push(s.unweighted.buffer, s.weighted.buffer);
    postMessage(message, transfer);
}

// A slice of passes, then a yield through a message channel (setTimeout would wait 4 ms).
const channel = new MessageChannel();
channel.port1.onmessage = slice;
function slice() {
    if (!job || job.stopped) return;
    const t0 = performance.now();
    do {
        const t = performance.now();
        const passes = api.pass();
        job.seconds += (performance.now() - t) / 1000;
        if (passes < 0) { job.outOfMemory = true; break; }
        job.passes = passes;
    } while (performance.now() - t0 < 40 && !finished());
    if (job.outOfMemory || finished()) { frame(true); job = null; return; }
    frame(false);
    channel.port2.postMessage(0);
}
function finished() {
    return (job.spp > 0 && job.passes >= job.spp) || (job.limitSeconds > 0 && job.seconds >= job.limitSeconds);
}

onmessage = (event) => {
    const m = event.data;
    if (!api) { pending.push(m); return; }
    if (m.type === "check") {
        postMessage({ type: "checked", id: m.id, error: api.checkScene(m.sceneText, m.sceneName) });
    } else if (m.type === "start") {
        const error = api.start(m.sceneText, m.sceneName, m.entry, m.width, m.height, m.seed, m.strategyLength);
        if (error) { job = null; postMessage({ type: "error", id: m.id, error }); return; }
        job = { id: m.id, spp: m.spp, limitSeconds: m.seconds, passes: 0, seconds: 0, strategies: m.strategyLength > 0 && api.strategies() !== "",
                lastStrategies: -1e9, outOfMemory: false, stopped: false };
        postMessage({ type: "started", id: m.id, exposure: api.exposure(), hasReference: !!api.hasReference(), strategies: job.strategies });
        slice();
    } else if (m.type === "stop") {
        if (job) { job.stopped = true; frame(true); job = null; }
    }
};
