// classroom/web/build_code.js: bdpt.cpp (and the two classroom headers the notes cite functions of)
// as the page's code view, highlighted once at build time (make web) by Debian's highlight.js
// (libjs-highlight.js), so that the page runs no highlighter:
//   node classroom/web/build_code.js OUT.js
// writes OUT.js: const BDPT_CODE = {files: {path: [HTML of each line]}, functions: {name: [path,
// line, last line]}}: a function's definition (the first, and bdpt.cpp's first) and its closing brace.
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

// A definition: a line (indented at most 4: free functions and struct members) that declares a
// type, then NAME(, and whose declaration reaches a "{" before any ";".
function definitions(text) {
    const lines = text.split("\n"), found = {};
    const head = /^ {0,4}(?!return\b|if\b|for\b|while\b|switch\b|else\b|case\b|using\b|delete\b|new\b)(?:template\s*<[^>]*>\s*)?(?:(?:inline|static|constexpr|explicit)\s+)*[A-Za-z_][\w:]*(?:<[^()]*?>)?(?:\s*[*&]+\s*|\s+)([A-Za-z_]\w*)\s*\(/;
    lines.forEach((line, i) => {
        const m = head.exec(line);
        if (!m || m[1] in found || /^\s*\/\//.test(line)) return;
        const rest = lines.slice(i, i + 12).join("\n").slice(m.index + m[0].length);
        const brace = rest.indexOf("{"), semicolon = rest.indexOf(";");
        if (brace < 0 || (semicolon >= 0 && semicolon < brace)) return;
        // its end: the first later line that closes a brace at the definition's own indentation
        const indent = line.match(/^ */)[0], end = lines.findIndex((l, j) => j > i && new RegExp("^" + indent + "}").test(l));
        found[m[1]] = [i + 1, end < 0 ? i + 1 : end + 1];
    });
    return found;
}

const code = { files: {}, functions: {} };
for (const file of FILES) {
    const source = fs.readFileSync(file, "utf8"), lines = splitLines(quiet(() => hljs.highlight("cpp", source).value));
    if (lines.length !== source.split("\n").length) throw new Error(`build_code.js: ${file}'s highlighted lines do not match its lines`);
    code.files[file] = lines;
    for (const [name, [line, end]] of Object.entries(definitions(source))) if (!(name in code.functions)) code.functions[name] = [file, line, end];
}
fs.writeFileSync(out + ".tmp", "const BDPT_CODE = " + JSON.stringify(code) + ";\n");
fs.renameSync(out + ".tmp", out);
console.log(`${out}: ${FILES.join(", ")}, ${Object.keys(code.functions).length} functions`);
