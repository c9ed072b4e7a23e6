#!/usr/bin/env bash
# The vendored three.js (assets/vendor/three/, embedded by qdot's motion
# pages: src/drawing/motion.rs) is byte for byte the file of the version
# pinned in book/package.json, as npm installed it (scripts/book_assets.sh
# --test installs it into book/node_modules).
set -euo pipefail
cd "$(dirname "$0")/.."
pkg=book/node_modules/three
if [ ! -d "$pkg" ]; then
    echo "three is not installed: run scripts/book_assets.sh --test" >&2
    exit 1
fi
status=0
for f in build/three.module.min.js LICENSE; do
    if ! cmp -s "$pkg/$f" "assets/vendor/three/$(basename "$f")"; then
        echo "assets/vendor/three/$(basename "$f") differs from three $(node -p "require('./$pkg/package.json').version")'s $f" >&2
        status=1
    fi
done
[ $status -eq 0 ] && echo "assets/vendor/three: three $(node -p "require('./$pkg/package.json').version")'s files, unchanged"
exit $status
