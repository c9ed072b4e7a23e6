// A motion's page (`qdot simulate --animate FILE.html`, `qdot modes
// --animate FILE.html`: three.js, WebGL) works offline in headless
// Chromium:
//   - it asks nothing of the network (every request but file: and data:
//     is refused and reported), and throws no error,
//   - it draws: the canvas has pixels other than the background,
//   - playing, the frame advances and the drawing is that frame's
//     positions; Pause stops it, Play starts it again,
//   - the scrub slider shows the frame it is moved to,
//   - with several motions (modes), choosing another draws it,
// then saves a screenshot, at the frame FRAME (a fraction of the motion,
// 0.6 unless given) and, for modes, the motion MOTION (0-based).
//
//   node scripts/motion_check.mjs PAGE.html SCREENSHOT.png [FRAME] [MOTION]
//
// Needs playwright-core (scripts/book_assets.sh --test) and Chromium at
// $CHROMIUM or /usr/bin/chromium.
import { existsSync } from "node:fs";
import { resolve } from "node:path";

import { offlineBrowser, openPage } from "./offline_browser.mjs";

const [pageArg, shotArg, frameArg, motionArg] = process.argv.slice(2);
if (!pageArg || !shotArg) {
    console.error("usage: node scripts/motion_check.mjs PAGE.html SCREENSHOT.png [FRAME] [MOTION]");
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

const { browser, context, offline } = await offlineBrowser({ viewport: { width: 1200, height: 760 } });
try {
    const { page, errors } = await openPage(context, file);
    await page.waitForFunction(() => window.qdotMotion !== undefined, null, { timeout: 20000 });

    const state = () =>
        page.evaluate(() => {
            const m = window.qdotMotion;
            return {
                frame: m.frame(),
                slider: Number(document.getElementById("scrub").value),
                button: document.getElementById("play").textContent,
                position: m.data.points.map((_, i) => m.position(i)),
                time: document.getElementById("time").textContent,
            };
        });
    // the non-background pixels of the canvas
    const inked = () =>
        page.evaluate(() => {
            const c = document.getElementById("view");
            const copy = document.createElement("canvas");
            copy.width = c.width;
            copy.height = c.height;
            const g = copy.getContext("2d");
            g.drawImage(c, 0, 0);
            const px = g.getImageData(0, 0, c.width, c.height).data;
            let n = 0;
            for (let i = 0; i < px.length; i += 4) if (px[i] < 235 || px[i + 1] < 235 || px[i + 2] < 235) n++;
            return n;
        });
    const data = await page.evaluate(() => window.qdotMotion.data);
    const motion = (k) => data.motions[k];
    const n = motion(0).t.length;
    check(n >= 3, `the page has ${n} frames: at least 3 are needed to check it`);
    check(data.points.length > 0, "the page draws no point");
    // the drawing's positions at frame k of motion m
    const expected = (m, k) =>
        data.points.map((_, i) => motion(m).positions[k].slice(3 * i, 3 * i + 3));
    const near = (a, b) =>
        a.length === b.length && a.every((p, i) => p.every((v, j) => Math.abs(v - b[i][j]) <= 1e-6 * data.size));

    const ink = await inked();
    check(ink > 500, `the canvas is blank (${ink} drawn pixels)`);

    // playing: the frame advances
    const a = await state();
    check(a.button === "Pause", `playing, the button reads "${a.button}", not "Pause"`);
    await sleep(900);
    const b = await state();
    check(a.frame !== b.frame, `playing, the frame stayed at ${a.frame} for 0.9 s`);
    check(b.slider === b.frame, `playing, the slider reads ${b.slider}, the frame is ${b.frame}`);
    check(near(b.position, expected(0, b.frame)), `playing, the drawing is not frame ${b.frame}'s positions`);

    // paused: it stays
    await page.click("#play");
    const c = await state();
    check(c.button === "Play", `paused, the button reads "${c.button}", not "Play"`);
    await sleep(500);
    const d = await state();
    check(c.frame === d.frame, "paused, the frame still advanced");

    // scrubbing: the slider's frame is drawn
    const target = Math.floor(n / 3) === d.frame ? Math.floor(n / 3) + 1 : Math.floor(n / 3);
    const scrub = (k) =>
        page.evaluate((k) => {
            const s = document.getElementById("scrub");
            s.value = String(k);
            s.dispatchEvent(new Event("input", { bubbles: true }));
        }, k);
    await scrub(target);
    const e = await state();
    check(e.frame === target, `scrubbed to ${target}, the frame is ${e.frame}`);
    check(near(e.position, expected(0, target)), `scrubbed to ${target}, the drawing is not its positions`);
    check(e.time.includes(motion(0).t[target].toPrecision(4)), `scrubbed to ${target}, the time reads "${e.time}"`);
    await sleep(400);
    const f = await state();
    check(f.frame === target, "after scrubbing while paused, the frame moved by itself");

    // play again from there
    await page.click("#play");
    await sleep(700);
    const g = await state();
    check(g.button === "Pause" && g.frame !== target, "Play did not restart the animation");
    await page.click("#play");

    // another motion (a mode)
    const chosen = Number(motionArg ?? 0);
    if (data.motions.length > 1) {
        await page.selectOption("#mode", "1");
        await scrub(Math.floor(motion(1).t.length / 4));
        const h = await state();
        check(near(h.position, expected(1, Math.floor(motion(1).t.length / 4))), "the second motion is not drawn when chosen");
        await page.selectOption("#mode", String(chosen));
    }

    // the screenshot
    const m = motion(chosen);
    await scrub(Math.round(Number(frameArg ?? 0.6) * (m.t.length - 1)));
    await sleep(100);
    await page.screenshot({ path: resolve(shotArg) });

    for (const err of errors) failures.push(`page error: ${err}`);
    for (const url of offline) failures.push(`the page asked the network for ${url}`);
} finally {
    await browser.close();
}

if (failures.length > 0) {
    console.error(`THE MOTION PAGE IS BROKEN (${failures.length} problem(s)) in ${file}:`);
    for (const f of failures) console.error(`  ${f}`);
    process.exit(1);
}
console.log(`motion: ${file} draws, plays, pauses and scrubs offline; screenshot ${resolve(shotArg)}`);
