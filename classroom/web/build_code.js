// classroom/web/build_code.js: bdpt.cpp (and the two classroom headers the notes cite functions of)
// as the page's code view, highlighted once at build time (make web) by Debian's highlight.js
// (libjs-highlight.js), so that the page runs no highlighter:
//   node classroom/web/build_code.js OUT.js
// writes OUT.js: const BDPT_CODE = {files: {path: [HTML of each line]}, functions: {name: [path,
// line, last line]}}: a function's definition (the first, and bdpt.cpp's first) and its closing brace,
// from build/homework-tools/cut --index.
"use strict";
const fs = require("fs");
// Debian's highlight.js 9 prints a notice of its end of support when it loads and highlights:
// the build's output keeps only the build's own lines.
const quiet = (f) => { const [log, warn] = [console.log, console.warn]; console.log = console.warn = () => {}; try { return f(); } finally { [console.log, console.warn] = [log, warn]; } };
const hljs = quiet(() => require("/usr/share/javascript/highlight.js/highlight.min.js"));

const [out] = process.argv.slice(2);
const FILES = ["bdpt.cpp", "classroom/metrics.h", "classroom/figures.h"];

// highlight.js's HTML split into lines: a span open at a line's end is closed there and opened
// again on the next line, so that every line stands alone.
function splitLines(html) {
    const lines = [], open = [];
    let line = "";
    for (const part of html.split(/(<[^>]+>)/)) {
        if (part.startsWith("</")) { open.pop(); line += part; }
        else if (part.startsWith("<")) { open.push(part); line += part; }
        else {
            const pieces = part.split("\n");
            pieces.forEach((piece, i) => {
                if (i > 0) {
                    lines.push(line + "</span>".repeat(open.length));
                    line = open.join("");
                }
                line += piece;
            });
        }
    }
    lines.push(line + "</span>".repeat(open.length));
    return lines;
}

// Where each function is defined: the one index of definitions (classroom/definitions.h), which
// the homework's cutter and the notes' tests read too, printed by `cut --index` (make builds it).
const { execFileSync } = require("child_process");
function definitions(file) {
    const found = {};
    for (const row of execFileSync("build/homework-tools/cut", ["--index", file], { encoding: "utf8" }).trim().split("\n")) {
        const [, name, first, last] = row.split(" ");
        if (name && !(name in found)) found[name] = [Number(first), Number(last)];
    }
    return found;
}

const code = { files: {}, functions: {} };
for (const file of FILES) {
    const source = fs.readFileSync(file, "utf8"), lines = splitLines(quiet(() => hljs.highlight("cpp", source).value));
    if (lines.length !== source.split("\n").length) throw new Error(`build_code.js: ${file}'s highlighted lines do not match its lines`);
    code.files[file] = lines;
    for (const [name, [line, end]] of Object.entries(definitions(file))) if (!(name in code.functions)) code.functions[name] = [file, line, end];
}
fs.writeFileSync(out + ".tmp", "const BDPT_CODE = " + JSON.stringify(code) + ";\n");
fs.renameSync(out + ".tmp", out);
console.log(`${out}: ${FILES.join(", ")}, ${Object.keys(code.functions).length} functions`);
