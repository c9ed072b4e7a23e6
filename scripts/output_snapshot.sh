#!/usr/bin/env bash
# Every exact command's output on every example, every book scene and a few
# pendulum chains, one file per (scene, command, format), the REPL's
# commands on each, and the numeric commands (cycle, response, floquet,
# simulate, sweep, codegen) on each scene and on the book's runs, into DIR. Run it
# before and after a change meant to keep behaviour, then `diff -r A B`:
# a restructuring must leave the two byte-identical.
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
# the numeric commands: every scene once with no options (the refusals and
# their messages), then the book's runs in each of their output formats
scenes+=(examples/mechanisms/*.qd)
for f in "${scenes[@]}"; do
    name=$(basename "$(dirname "$f")")_$(basename "$f" .qd)
    for cmd in cycle response floquet simulate sweep; do
        { "$qdot" "$cmd" "$f" 2>&1; echo "exit $?"; } > "$out/$name.$cmd.bare" || true
    done
    { "$qdot" codegen "$f" --lang c 2>&1; echo "exit $?"; } > "$out/$name.codegen.c" || true
done
set_mech='R=0.1,L=0.4,omega=10,m1=1,J1=0.005,m2=2,J2=0.03,m3=1.5,g=9.81'
set_213='G1=20,G2=15,G3=10,g=9.81,R=0.1,AB=0.4,AC=0.15,J2=0.02,k=500,l0=0.45,mu=0.15,omega=20'
runs=(
    "cycle1|csv json text|cycle examples/mechanisms/slider_driven_crank.qd --over t=0:0.6:9 --set $set_mech --guess xb=0.5,phi=0.2"
    "cycle2|csv json text|cycle examples/seed_21_3.qd --over phi=0:360deg:13 --set $set_213 --guess x2=0.25,xB=0.5"
    "cycle3|text|cycle examples/seed_21_3.qd --over phi=0:360deg:13 --set $set_213 --guess x2=0.25,xB=0.5 --columns xB,alpha,O_x,M"
    "response1|text json|response examples/forced_oscillator.qd"
    "response2|text json|response examples/vibration_absorber.qd"
    "response3|csv json text|response examples/vibration_absorber.qd --set m1=1,m2=0.2,k1=1,k2=0.2,c=0.02,F0=1 --over Omega=0.6:1.4:9"
    "floquet1|text json|floquet examples/kapitza.qd --at theta=pi --set m=1,l=1,g=9.81,a=0.05,w=100"
    "floquet2|text csv json|floquet examples/kapitza.qd --at theta=pi --set m=1,l=1,g=9.81,a=0.05 --over w=80:100:11"
    "floquet3|text csv json|floquet examples/mathieu.qd --set m=1,w=1 --over delta=-0.5:2.5:13,eps=0:2:5"
    "floquet4|text json|floquet examples/moving_support.qd --function s=1/10*cos(3*t) --set m=1,l=1,g=9.81"
    "simulate1|csv json|simulate examples/pendulum.qd --set m=1,l=1,g=1 --init theta=3,theta'=0 --t-end 10 --stop-when theta=0 --points 3 --rtol 1e-12 --atol 1e-12"
    "simulate2|csv json|simulate examples/seed_24_2.qd --set m=1,k=6,R=0.5 --init x1=1,x2=1.3333333333333333,x1'=0,x2'=0 --t-end 6.283185307179586 --points 5 --rtol 1e-12 --atol 1e-12"
    "simulate3|csv|simulate examples/moving_support.qd --t-end 2 --points 3 --set m=1,l=1,g=9.81 --init theta=0,theta'=0 --function s=1/10*sin(2*t)"
    "sweep1|csv json|sweep examples/pendulum.qd --set m=1,g=9.81 --init theta'=0 --vary l=0.5:2:3 --vary theta=0.5:3:2 --t-end 5 --points 11 --threads 1"
    "codegen1|-|codegen examples/pendulum.qd --lang python --set g=9.81,l=1"
    "codegen2|-|codegen examples/seed_24_2.qd --lang rust --form mass-matrix"
    "codegen3|-|codegen examples/double_pendulum.qd --lang julia"
)
for run in "${runs[@]}"; do
    IFS='|' read -r name fmts args <<< "$run"
    read -r -a argv <<< "$args"
    for fmt in $fmts; do
        extra=()
        [ "$fmt" = - ] || extra=(--output "$fmt")
        { "$qdot" "${argv[@]}" "${extra[@]}" 2>&1; echo "exit $?"; } > "$out/numeric_$name.$fmt" || true
    done
done
echo "$(ls "$out" | wc -l) outputs in $out"
