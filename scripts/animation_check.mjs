// A mechanism's animation page (`qdot cycle --animate FILE.html`, or the
// demo `QDOT_WRITE_DEMO=1 cargo test --release -p qdot --lib -- writes_the_demo`
// writes target/animation_demo.html) works offline in headless Chromium:
//   - it asks nothing of the network (every request but file: and data:
//     is refused and reported), and throws no error,
//   - playing, the drawing moves and the position advances,
//   - Pause stops it, Play starts it again,
//   - the scrub slider shows the position it is moved to: the drawing's
//     attributes are that row's frame, the text its value and note,
// then saves a screenshot.
//
//   node scripts/animation_check.mjs PAGE.html SCREENSHOT.png
//
// Needs playwright-core (scripts/book_assets.sh --test) and Chromium at
// $CHROMIUM or /usr/bin/chromium.
import { existsSync } from "node:fs";
import { resolve } from "node:path";

import { offlineBrowser, openPage } from "./offline_browser.mjs";

const [pageArg, shotArg] = process.argv.slice(2);
if (!pageArg || !shotArg) {
    console.error("usage: node scripts/animation_check.mjs PAGE.html SCREENSHOT.png");
    process.exit(2);
}
const file = resolve(pageArg);
if (!existsSync(file)) {
    console.error(`no page at ${file}`);
    process.exit(1);
}

const failures = [];
const check = (ok, what) => {
    if (!ok) failures.push(what);
};
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

const { browser, context, offline } = await offlineBrowser({ viewport: { width: 1360, height: 760 } });
try {
    const { page, errors } = await openPage(context, file);

    // the drawing's moving attributes now, the slider, the texts
    const state = () =>
        page.evaluate(() => {
            const data = JSON.parse(document.getElementById("cycle-data").textContent);
            const attrs = data.targets.map(([id, attr]) => {
                const el = document.getElementById(id);
                return attr === "translate" || attr === "rotate"
                    ? el.getAttribute("transform")
                    : el.getAttribute(attr);
            });
            const note = document.getElementById("note");
            return {
                attrs,
                row: Number(document.getElementById("scrub").value),
                button: document.getElementById("play").textContent,
                varied: document.getElementById("varied").textContent,
                note: note.hidden ? null : note.textContent,
                cells: [...document.querySelectorAll("#reactions td")].map((td) => td.textContent),
            };
        });
    const data = await page.evaluate(() =>
        JSON.parse(document.getElementById("cycle-data").textContent),
    );
    const n = data.rows.length;
    check(n >= 3, `the page has ${n} positions: at least 3 are needed to check it`);
    check(data.targets.length > 0, "the drawing has no moving part");
    const frame = (k) =>
        data.targets.map(([, attr], i) =>
            attr === "translate" || attr === "rotate" ? `${attr}(${data.frames[k][i]})` : data.frames[k][i],
        );
    const same = (a, b) => JSON.stringify(a) === JSON.stringify(b);

    // playing: the drawing moves
    const a = await state();
    check(a.button === "Pause", `playing, the button reads "${a.button}", not "Pause"`);
    await sleep(700);
    const b = await state();
    check(!same(a.attrs, b.attrs), "playing, the drawing did not move in 0.7 s");
    check(a.row !== b.row, `playing, the position stayed at ${a.row} for 0.7 s`);
    check(same(b.attrs, frame(b.row)), `playing, the drawing is not row ${b.row}'s frame`);

    // paused: it stays
    await page.click("#play");
    const c = await state();
    check(c.button === "Play", `paused, the button reads "${c.button}", not "Play"`);
    await sleep(500);
    const d = await state();
    check(same(c.attrs, d.attrs) && c.row === d.row, "paused, the drawing still moved");

    // scrubbing: the slider's row is drawn and described
    const target = Math.floor(n / 3) === d.row ? Math.floor(n / 3) + 1 : Math.floor(n / 3);
    await page.evaluate((k) => {
        const s = document.getElementById("scrub");
        s.value = String(k);
        s.dispatchEvent(new Event("input", { bubbles: true }));
    }, target);
    const e = await state();
    check(e.row === target, `scrubbed to ${target}, the slider reads ${e.row}`);
    check(same(e.attrs, frame(target)), `scrubbed to ${target}, the drawing is not its frame`);
    check(!same(e.attrs, d.attrs), `scrubbed from ${d.row} to ${target}, the drawing did not change`);
    check(e.note === data.rows[target].note, `scrubbed to ${target}, the note reads ${e.note}`);
    const v = data.rows[target].values[0];
    const shown = data.degrees ? ((v * 180) / Math.PI).toFixed(1) : null;
    check(!shown || e.varied.includes(shown), `scrubbed to ${target}, the position reads "${e.varied}", not ${shown}`);
    check(!same(e.cells, d.cells), "scrubbing did not change the reactions shown");
    check(e.cells.length > 0 && !e.cells.some((t) => t === "" || t === "NaN"), `reactions shown: ${e.cells}`);
    await sleep(400);
    const f = await state();
    check(same(e.attrs, f.attrs), "after scrubbing, the drawing moved by itself");

    // play again from there
    await page.click("#play");
    await sleep(600);
    const g = await state();
    check(g.button === "Pause" && g.row !== target, "Play did not restart the animation");

    // the screenshot: a noted row if there is one, else a third of the cycle
    const noted = data.rows.findIndex((r) => r.note !== null);
    await page.click("#play");
    await page.evaluate((k) => {
        const s = document.getElementById("scrub");
        s.value = String(k);
        s.dispatchEvent(new Event("input", { bubbles: true }));
    }, noted >= 0 ? noted : Math.floor(n / 6));
    await page.screenshot({ path: resolve(shotArg), fullPage: true });

    for (const err of errors) failures.push(`page error: ${err}`);
    for (const url of offline) failures.push(`the page asked the network for ${url}`);
} finally {
    await browser.close();
}

if (failures.length > 0) {
    console.error(`THE ANIMATION PAGE IS BROKEN (${failures.length} problem(s)) in ${file}:`);
    for (const f of failures) console.error(`  ${f}`);
    process.exit(1);
}
console.log(`animation: ${file} plays, pauses and scrubs offline; screenshot ${resolve(shotArg)}`);
