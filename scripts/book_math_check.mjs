// The book's math renders offline: opens every built page that has a
// formula in headless Chromium, from file:// with every other request
// refused, and checks that
//   - no raw \[ \] \( \) \begin or other control word (\frac, an unknown
//     macro KaTeX printed as text) is left in the text a reader sees
//     (code blocks and KaTeX's hidden MathML annotation excluded),
//   - the number of typeset formulas (.katex) equals the number of
//     formulas in the page's HTML, and none is a KaTeX error,
//   - KaTeX's fonts loaded,
// and that no built page references a CDN (or anything off this machine).
//
//   node scripts/book_math_check.mjs [BOOK_DIR]      (default book/book)
//
// Needs `scripts/book_assets.sh --test` (KaTeX + playwright-core) and
// `mdbook build book` first; Chromium at $CHROMIUM or /usr/bin/chromium.
import { readFileSync, readdirSync, statSync } from "node:fs";
import { join, relative, resolve } from "node:path";
import { pathToFileURL } from "node:url";

import { offlineBrowser } from "./offline_browser.mjs";

const root = resolve(new URL("..", import.meta.url).pathname);

const bookDir = resolve(process.argv[2] ?? join(root, "book", "book"));

function htmlFiles(dir) {
    return readdirSync(dir).flatMap((name) => {
        const p = join(dir, name);
        if (statSync(p).isDirectory()) return htmlFiles(p);
        return name.endsWith(".html") ? [p] : [];
    });
}

// The formulas of a page as its HTML has them: \[…\] and \(…\) in <main>,
// outside code, scripts and comments (what the page's auto-render sees).
function formulasInSource(html) {
    const open = html.indexOf("<main>");
    const close = html.lastIndexOf("</main>");
    if (open < 0 || close < 0) return [];
    const text = html
        .slice(open, close)
        .replace(/<!--[\s\S]*?-->/g, "")
        .replace(/<(pre|code|script|style)\b[\s\S]*?<\/\1>/g, "");
    return text.match(/\\\[[\s\S]*?\\\]|\\\([\s\S]*?\\\)/g) ?? [];
}

// Anything a page would fetch from off this machine: src/href to http(s)
// or protocol-relative URLs, CSS @import/url() of one, and the CDNs by name.
function offMachineReferences(html) {
    const found = [];
    const patterns = [
        /<(?:script|link|img|iframe|source|audio|video)\b[^>]*\b(?:src|href)\s*=\s*["']?(?:https?:)?\/\/[^"'\s>]+/gi,
        /@import\s+(?:url\()?["']?(?:https?:)?\/\/[^"')\s]+/gi,
        /url\(\s*["']?(?:https?:)?\/\/[^"')\s]+/gi,
        /\b(?:cdnjs|jsdelivr|unpkg|googleapis|cloudflare|mathjax)\b[^\s"'<>]*/gi,
    ];
    for (const re of patterns) for (const m of html.matchAll(re)) found.push(m[0]);
    return found;
}

const failures = [];
const pages = htmlFiles(bookDir).sort();
if (pages.length === 0) {
    console.error(`no HTML under ${bookDir}: run mdbook build book first`);
    process.exit(1);
}
const withMath = [];
for (const page of pages) {
    const html = readFileSync(page, "utf8");
    for (const ref of offMachineReferences(html)) {
        failures.push(`${relative(bookDir, page)}: references ${ref}`);
    }
    const formulas = formulasInSource(html);
    if (formulas.length > 0) withMath.push({ page, expected: formulas.length });
}
if (withMath.length === 0) failures.push("no built page has a formula: is this the book?");

// playwright-core starts Chromium with a fresh, empty profile of its own
const { browser, context, offline } = await offlineBrowser();
let passed = 0;
let failed = 0;
try {
    for (const { page: file, expected } of withMath) {
        const name = relative(bookDir, file);
        const page = await context.newPage();
        const errors = [];
        page.on("pageerror", (e) => errors.push(String(e)));
        page.on("requestfailed", (r) => {
            if (r.url().startsWith("file:")) errors.push(`missing ${r.url()}`);
        });
        // print.html asks to print once it has loaded: make that a no-op
        await page.addInitScript(() => {
            window.print = () => {};
        });
        await page.goto(pathToFileURL(file).href, { waitUntil: "load" });
        const r = await page.evaluate(async () => {
            await document.fonts.ready;
            const main = document.querySelector("main");
            const skip = "pre, code, script, style, .katex-mathml";
            const walker = document.createTreeWalker(main, NodeFilter.SHOW_TEXT, {
                acceptNode: (n) =>
                    n.parentElement.closest(skip) ? NodeFilter.FILTER_REJECT : NodeFilter.FILTER_ACCEPT,
            });
            let text = "";
            for (let n = walker.nextNode(); n; n = walker.nextNode()) text += n.data;
            const raw = [];
            // \[ \] \( \) or any control word (\begin, \frac, an unknown
            // macro KaTeX printed as text)
            for (const m of text.matchAll(/\\[[\]()]|\\[A-Za-z]+/g)) {
                raw.push(text.slice(Math.max(0, m.index - 30), m.index + 50).replace(/\s+/g, " "));
            }
            const fonts = [...document.fonts].filter((f) => f.family.startsWith("KaTeX"));
            return {
                katex: main.querySelectorAll(".katex").length,
                display: main.querySelectorAll(".katex-display").length,
                errors: [...main.querySelectorAll(".katex-error")].map((e) => e.title || e.textContent),
                raw,
                fontsLoaded: fonts.filter((f) => f.status === "loaded").map((f) => f.family),
                fontsFailed: fonts.filter((f) => f.status === "error").map((f) => f.family),
                typeset: typeof window.katex === "object",
            };
        });
        const bad = [];
        if (!r.typeset) bad.push("KaTeX did not load (scripts/book_assets.sh installs it)");
        for (const s of r.raw) bad.push(`raw TeX visible: …${s}…`);
        if (r.katex !== expected) bad.push(`${r.katex} formulas typeset, ${expected} in the page`);
        for (const e of r.errors) bad.push(`KaTeX error: ${e}`);
        if (r.fontsLoaded.length === 0) bad.push("no KaTeX font loaded");
        for (const f of r.fontsFailed) bad.push(`font ${f} failed to load`);
        for (const e of errors) bad.push(e);
        for (const b of bad) failures.push(`${name}: ${b}`);
        console.log(
            `${bad.length ? "FAIL" : "ok  "} ${name}: ${r.katex}/${expected} formulas (${r.display} displayed), ` +
                `${r.fontsLoaded.length} KaTeX fonts`,
        );
        if (bad.length) failed++;
        else passed++;
        await page.close();
    }
    for (const url of offline) failures.push(`a page asked the network for ${url}`);
} finally {
    await browser.close();
}

if (failures.length > 0) {
    console.error(`\nTHE BOOK'S MATH IS BROKEN (${failures.length} problem(s)):`);
    for (const f of failures) console.error(`  ${f}`);
} else {
    console.log(`${pages.length} built pages reference nothing off this machine`);
}
// pages with formulas, each typeset offline or not
console.log(`book_math: ${passed} passed, ${failed} failed`);
process.exit(failures.length > 0 ? 1 : 0);
