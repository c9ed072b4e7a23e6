// Headless Chromium for the offline checks (scripts/book_math_check.mjs,
// scripts/animation_check.mjs, scripts/motion_check.mjs): playwright-core from book/package.json
// (scripts/book_assets.sh --test), Chromium at $CHROMIUM or
// /usr/bin/chromium with a fresh profile and no background networking,
// and a context that refuses every request but file: and data: (listed in
// `offline`, so a page that reaches for the network fails its check).
import { createRequire } from "node:module";
import { join, resolve } from "node:path";
import { pathToFileURL } from "node:url";

const root = resolve(new URL("..", import.meta.url).pathname);

/// The browser and an offline context with `options` (playwright's).
export async function offlineBrowser(options = {}) {
    const require = createRequire(join(root, "book", "package.json"));
    let chromium;
    try {
        ({ chromium } = require("playwright-core"));
    } catch {
        console.error("playwright-core is missing: run scripts/book_assets.sh --test");
        process.exit(1);
    }
    const browser = await chromium.launch({
        executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
        headless: true,
        args: [
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
        ],
    });
    const context = await browser.newContext(options);
    const offline = [];
    await context.route("**/*", (route) => {
        const url = route.request().url();
        if (url.startsWith("file:") || url.startsWith("data:")) return route.continue();
        offline.push(url);
        return route.abort("internetdisconnected");
    });
    return { browser, context, offline };
}

/// A new page of `context` loaded from the local `file`, and the errors it
/// reports while it lives: uncaught exceptions, console errors and local
/// files it could not load.
export async function openPage(context, file) {
    const page = await context.newPage();
    const errors = [];
    page.on("pageerror", (e) => errors.push(String(e)));
    page.on("console", (m) => {
        if (m.type() === "error") errors.push(m.text());
    });
    page.on("requestfailed", (r) => {
        if (r.url().startsWith("file:")) errors.push(`missing ${r.url()}`);
    });
    await page.goto(pathToFileURL(file).href, { waitUntil: "load" });
    return { page, errors };
}
