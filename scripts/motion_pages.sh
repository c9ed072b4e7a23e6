#!/bin/sh
# The book's motion pages (`qdot simulate … --animate`, `qdot modes …
# --animate`): runs every such line of book/src/simulation.md and
# book/src/oscillations.md from the repository root with the page written
# to target/motion/NAME.html, checks each in headless Chromium
# (scripts/motion_check.mjs: offline, drawn, play, pause, scrub) and
# saves its screenshot to target/motion/NAME.png, or with --book to
# book/src/simulation/NAME.png (the book's pictures).
#
#   scripts/motion_pages.sh [--book]   # uses target/release/qdot (or $QDOT_BIN)
set -eu
cd "$(dirname "$0")/.."
qdot=${QDOT_BIN:-target/release/qdot}
[ -x "$qdot" ] || { echo "no $qdot: cargo build --release first, or set QDOT_BIN" >&2; exit 1; }
shots=target/motion
if [ "${1:-}" = "--book" ]; then shots=book/src/simulation; fi
mkdir -p target/motion "$shots"
grep -h '^qdot \(simulate\|modes\) .* --animate [^ ]*\.html' book/src/simulation.md book/src/oscillations.md |
while IFS= read -r line; do
    name=$(printf '%s\n' "$line" | sed 's/.* --animate \([^ ]*\)\.html.*/\1/')
    page=target/motion/$name.html
    # the line is shell words as the book shows them, the page moved to target/
    eval "\"\$qdot\" $(printf '%s\n' "${line#qdot }" | sed "s| --animate [^ ]*\.html| --animate $page|")" > /dev/null 2>&1
    case $line in
        # a mode at a quarter period (its largest swing), the second one
        "qdot modes "*) node scripts/motion_check.mjs "$page" "$shots/$name.png" 0.25 1 ;;
        *) node scripts/motion_check.mjs "$page" "$shots/$name.png" ;;
    esac
done
