#!/bin/sh
# The book's figures of `qdot simulate --plot` (book/src/simulation.md):
# runs every `qdot simulate … --plot book/src/simulation/NAME.svg` line of
# that page from the repository root (the page is the one source of the
# commands; tests/simulate_plot.rs checks the SVGs against them), then
# renders each SVG to NAME.png at its own size with headless Chromium.
#
#   scripts/plot_pngs.sh            # uses target/release/qdot
#   QDOT_BIN=path/to/qdot scripts/plot_pngs.sh
set -eu
cd "$(dirname "$0")/.."
qdot=${QDOT_BIN:-target/release/qdot}
[ -x "$qdot" ] || { echo "no $qdot: cargo build --release first, or set QDOT_BIN" >&2; exit 1; }
browser=
for b in chromium chromium-browser google-chrome; do
    if command -v "$b" > /dev/null 2>&1; then browser=$b; break; fi
done
[ -n "$browser" ] || { echo "no Chromium found (apt-get install chromium)" >&2; exit 1; }

grep '^qdot simulate .* --plot book/src/simulation/' book/src/simulation.md |
while IFS= read -r line; do
    svg=$(printf '%s\n' "$line" | sed 's/.* --plot \(book\/src\/simulation\/[^ ]*\.svg\).*/\1/')
    # the line is shell words as the book shows them; qdot is the binary here
    eval "\"\$qdot\" ${line#qdot }" > /dev/null
    size=$(sed -n '1s/^<svg width="\([0-9]*\)" height="\([0-9]*\)".*/\1,\2/p' "$svg")
    png=${svg%.svg}.png
    "$browser" --headless --no-sandbox --disable-gpu --hide-scrollbars \
        --window-size="$size" --screenshot="$PWD/$png" "file://$PWD/$svg" > /dev/null 2>&1
    echo "$png: $(wc -c < "$png") bytes, $size"
done
