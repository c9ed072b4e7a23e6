#!/usr/bin/env bash
# Every exact command's output on every example, every book scene and a few
# pendulum chains, one file per (scene, command, format), and the REPL's
# commands on each, into DIR. Run it
# before and after a change meant to keep behaviour, then `diff -r A B`:
# a restructuring must leave the two byte-identical. (simulate has its
# own tests against exact solutions.)
#
#   scripts/output_snapshot.sh /tmp/before      # on the old commit
#   scripts/output_snapshot.sh /tmp/after       # on the new one
#   diff -r /tmp/before /tmp/after
#
# QDOT (default target/release/qdot, built if missing) is the binary used.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:?usage: scripts/output_snapshot.sh DIR}
qdot=${QDOT:-target/release/qdot}
[ -x "$qdot" ] || cargo build --release --quiet
mkdir -p "$out"

scenes=(examples/*.qd book/scenes/*.qd)
# chains of 2 and 4 links, generated like the benches' (src/engine/gallery.rs)
# (at a fixed path: the LaTeX title shows it)
tmp=target/output-snapshot
mkdir -p "$tmp/gallery"
for n in 2 4; do
    {
        printf 'coordinates'
        for i in $(seq 1 $n); do printf '%s th%d' "$([ $i = 1 ] || echo ,)" $i; done
        printf '\nparameters m, l, g\n'
        x=0; y=0
        for i in $(seq 1 $n); do
            x="$x + l*sin(th$i)"; y="$y - l*cos(th$i)"
            printf 'x%d = %s\ny%d = %s\n' $i "$x" $i "$y"
            printf "kinetic T%d = 1/2*m*(x%d'^2 + y%d'^2)\n" $i $i $i
            printf 'potential V%d = m*g*y%d\n' $i $i
        done
    } > "$tmp/gallery/chain$n.qd"
    scenes+=("$tmp/gallery/chain$n.qd")
done

for f in "${scenes[@]}"; do
    name=$(basename "$(dirname "$f")")_$(basename "$f" .qd)
    for cmd in derive solve forces equilibrium modes hamilton integrals; do
        for fmt in text json latex; do
            # the exit code is part of the output
            { "$qdot" "$cmd" "$f" --format "$fmt" 2>&1; echo "exit $?"; } \
                > "$out/$name.$cmd.$fmt" || true
        done
    done
    { "$qdot" latex "$f" --steps --standalone 2>&1; echo "exit $?"; } > "$out/$name.latex-steps" || true
    for fmt in text json; do
        { "$qdot" check "$f" --format "$fmt" 2>&1; echo "exit $?"; } > "$out/$name.check.$fmt" || true
    done
    # the REPL's commands on the scene, in each format
    printf ':load %s\n:derive\n:solve\n:forces\n:equilibrium\n:hamilton\n:integrals\n:format json\n:solve\n:modes\n:format latex\n:derive\n:latex\n' "$f" \
        | { "$qdot" repl 2>&1; echo "exit $?"; } > "$out/$name.repl" || true
done
echo "$(ls "$out" | wc -l) outputs in $out"
