#!/usr/bin/env bash
# The book's offline math: installs KaTeX at the version pinned in
# book/package.json + book/package-lock.json (npm ci, from the npm registry)
# and copies what the pages load into book/src/katex/ (git-ignored), which
# mdBook copies into the built book. book/theme/head.hbs loads it and
# typesets every \[…\] and \(…\) when a page opens: no network needed.
#
#   scripts/book_assets.sh          # KaTeX only (what a reader needs)
#   scripts/book_assets.sh --test   # also playwright-core, for
#                                   # scripts/book_math_check.mjs (CI)
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v npm >/dev/null 2>&1; then
    echo "npm is required (Node.js): apt-get install nodejs npm" >&2
    exit 1
fi
omit=(--omit=dev)
if [ "${1:-}" = "--test" ]; then omit=(); fi
# --loglevel=error: katex's own command-line tool depends on a commander
# that asks for Node 22 (a warning on Node 20); the pages never load it.
npm ci --prefix book --no-audit --no-fund --loglevel=error "${omit[@]}"

src=book/node_modules/katex/dist
dst=book/src/katex
rm -rf "$dst"
mkdir -p "$dst/fonts"
cp "$src/katex.min.js" "$src/katex.min.css" "$src/contrib/auto-render.min.js" "$dst/"
# woff2 only: every browser that runs KaTeX reads it, and the CSS lists it first
cp "$src"/fonts/*.woff2 "$dst/fonts/"
cp book/node_modules/katex/LICENSE "$dst/LICENSE"
echo "KaTeX $(node -p "require('./book/node_modules/katex/package.json').version") in $dst ($(du -sh "$dst" | cut -f1))"
