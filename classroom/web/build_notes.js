// classroom/web/build_notes.js: the lecture notes (lecture_notes/*.md) as the page's notes view,
// rendered once at build time (make web) by Debian's marked (libjs-marked) and KaTeX
// (libjs-katex), so that the page fetches nothing and opens from a file:
//   node classroom/web/build_notes.js OUT.js FIGURE_DIR
// writes OUT.js (const BDPT_NOTES = [{file, title, html}], README first, then the pages in the
// slides' order) and copies every figure a page shows into FIGURE_DIR.
"use strict";
const fs = require("fs"), path = require("path");
const { marked } = require("/usr/share/javascript/marked/marked.umd.js");
const katex = require("/usr/share/javascript/katex/katex.min.js");

const [out, figureDir] = process.argv.slice(2);
const notes = "lecture_notes";
// File names sort in the slides' order: 04 before 04n (notation), 10 before 10m (mirrors).
const files = ["README.md", ...fs.readdirSync(notes).filter((f) => /^(\d|appendix).*\.md$/.test(f)).sort()];

// Formulas first, as KaTeX's HTML behind placeholders: Markdown would eat their backslashes and
// underscores. $$...$$ on lines of their own is a display formula, $...$ inside a line an inline
// one; code (fenced blocks and `spans`) is left alone.
function renderFormulas(text, formulas) {
    const keep = (tex, display) => {
        formulas.push(katex.renderToString(tex, { displayMode: display, throwOnError: true, output: "html" }));
        return `\u0000F${formulas.length - 1}\u0000`;
    };
    const parts = text.split(/(```[\s\S]*?```)/);
    return parts.map((part, i) => {
        if (i % 2) return part;
        part = part.replace(/^\$\$\n?([\s\S]*?)\n?\$\$$/gm, (_, tex) => keep(tex, true));
        return part.split(/(`[^`\n]*`)/).map((p, j) => (j % 2 ? p : p.replace(/\$([^$\n]+?)\$/g, (_, tex) => keep(tex, false)))).join("");
    }).join("");
}

// "### Answers (for the instructor)" and what follows it, up to the next heading of its level or
// above: folded (<details>), so that a student reads the exercise before its answer.
function foldAnswers(html) {
    return html.replace(/<h3[^>]*>(Answers? \(for the instructor\))<\/h3>([\s\S]*?)(?=<h[123][ >]|$)/g,
        (_, title, body) => `<details class="answers"><summary>${title}</summary>${body}</details>\n`);
}

const figures = new Set();
function renderPage(file) {
    const text = fs.readFileSync(path.join(notes, file), "utf8"), formulas = [];
    let html = marked.parse(renderFormulas(text, formulas), { gfm: true, headerIds: true, mangle: false });
    html = html.replace(/\u0000F(\d+)\u0000/g, (_, n) => formulas[Number(n)]);
    // Figures beside the page; links to other pages open them in the notes view; links into the
    // repository (../bdpt.cpp) name the file, which the page cannot open.
    html = html.replace(/src="figures\/([^"]+)"/g, (_, f) => (figures.add(f), `src="notes/figures/${f}"`));
    html = html.replace(/href="([\w-]+)\.md(#[\w-]*)?"/g, (_, page, anchor) => `href="#notes=${page}" data-page="${page}"${anchor ? ` data-anchor="${anchor.slice(1)}"` : ""}`);
    html = html.replace(/<a href="\.\.\/([^"]+)">/g, (_, f) => `<a class="repository" title="in the repository: ${f}">`);
    html = foldAnswers(html);
    // The title for the contents menu, whose options hold text: a formula as plain letters.
    const title = (text.match(/^# (.*)$/m) || [, file])[1].replace(/\$([^$]*)\$/g, (_, tex) => tex.replace(/\\pi\b/g, "π").replace(/\\[a-z]+/g, "").replace(/[{}]/g, ""));
    return { file: file.replace(/\.md$/, ""), title, html };
}

const pages = files.map(renderPage);
fs.mkdirSync(figureDir, { recursive: true });
for (const f of figures) {
    const from = path.join(notes, "figures", f);
    if (!fs.existsSync(from)) throw new Error(`${notes}/...: figure figures/${f} is not in ${notes}/figures/`);
    fs.mkdirSync(path.dirname(path.join(figureDir, f)), { recursive: true });
    fs.copyFileSync(from, path.join(figureDir, f));
}
fs.writeFileSync(out + ".tmp", "const BDPT_NOTES = " + JSON.stringify(pages) + ";\n");
fs.renameSync(out + ".tmp", out);
console.log(`${out}: ${pages.length} pages, ${figures.size} figures, ${pages.reduce((n, p) => n + (p.html.match(/class="katex"/g) || []).length, 0)} formulas`);
