#!/usr/bin/env bash
# The largest hostile cases of issue 46 (acceptance 4): three 30-body
# chains through every command, each run timed and measured, as a markdown
# table: command | scene | CPU s | peak MB | the message or the answer.
#
#   scripts/hostile_table.sh                 # target/release/qdot
#   QDOT=/path/to/qdot scripts/hostile_table.sh > table.md
#
# The scenes (written to $WORK, default target/hostile-table):
#   planar30   30 equal rods in a plane (tests/hostile/budget.rs's planar_rod_chain(30));
#   planar30u  the same with a mass and a length per rod (m1..m30, l1..l30);
#   3d30       30 rods in space hinged about alternating axes (gallery::rod_chain_3d(30)).
# Every run is under `ulimit -t $LIMIT` (default 120 s of CPU); CPU s is
# user + system time, peak MB the maximum resident set (GNU time).
# ONLY='^(simulate|cycle)' runs only the commands whose label matches.
set -uo pipefail
cd "$(dirname "$0")/.."
qdot=${QDOT:-target/release/qdot}
limit=${LIMIT:-120}
work=${WORK:-target/hostile-table}
mkdir -p "$work"
[ -x /usr/bin/time ] || { echo "needs GNU time at /usr/bin/time" >&2; exit 2; }

# planar N UNIFORM(0|1)
planar() {
    local n=$1 u=$2 i qs="" ms="" ls="" m l prev
    for i in $(seq 1 "$n"); do qs="$qs${qs:+, }q$i: angle"; done
    echo "coordinates $qs"
    if [ "$u" = 1 ]; then
        for i in $(seq 1 "$n"); do
            ms="$ms${ms:+, }m$i: mass"
            ls="$ls, l$i: length"
        done
        echo "parameters $ms$ls, g: acceleration"
    else
        echo "parameters m: mass, l: length, g: acceleration"
    fi
    for i in $(seq 1 "$n"); do
        if [ "$u" = 1 ]; then m=m$i l=l$i; else m=m l=l; fi
        if [ "$i" -gt 1 ]; then prev="P$((i - 1)) + "; else prev=""; fi
        echo "body b$i: mass $m, inertia 1/12*$m*$l^2, angle q$i, at $prev$l/2*[sin(q$i), -cos(q$i)]"
        echo "P$i = $prev$l*[sin(q$i), -cos(q$i)]"
    done
    echo "gravity [0, -g]"
}

# rods3d N
rods3d() {
    local n=$1 i p axis qs=""
    echo "# $n rods in space, hinged about alternating x and y axes"
    for i in $(seq 1 "$n"); do qs="$qs${qs:+, }q$i"; done
    echo "coordinates $qs"
    echo "parameters m, A, C, l, g"
    for i in $(seq 1 "$n"); do
        if [ $((i % 2)) = 1 ]; then axis=x; else axis=y; fi
        if [ "$i" = 1 ]; then
            echo "frame B1 = rot($axis, q1)"
            echo "body b1: mass m, inertia [A, A, C], frame B1, at -l/2*axis(B1, 3)"
            echo "P1 = -l*axis(B1, 3)"
        else
            p=$((i - 1))
            echo "frame B$i = B$p * rot($axis, q$i)"
            echo "body b$i: mass m, inertia [A, A, C], frame B$i, at P$p - l/2*axis(B$i, 3)"
            echo "P$i = P$p - l*axis(B$i, 3)"
        fi
    done
    echo "gravity [0, 0, -g]"
}

planar 30 0 >"$work/planar30.qd"
planar 30 1 >"$work/planar30u.qd"
rods3d 30 >"$work/3d30.qd"

# every parameter's value, per scene
values() {
    local i s=""
    case $1 in
    planar30) echo "m=1,l=1,g=9.81" ;;
    planar30u)
        for i in $(seq 1 30); do s="$s${s:+,}m$i=1,l$i=1"; done
        echo "$s,g=9.81"
        ;;
    3d30) echo "m=1,A=1,C=1,l=1,g=9.81" ;;
    esac
}

# every coordinate's initial value: q1 = 0.1, the others 0
init="q1=0.1"
for i in $(seq 2 30); do init="$init,q$i=0"; done

# the message (stderr's first line) or the answer (stdout's first line),
# cut to 100 characters and made safe in a table cell
summary() {
    local code=$1 out=$2 err=$3 line
    if [ "$code" = 0 ]; then
        line=$(grep -m1 -v '^\s*$' "$out")
    elif [ "$code" -gt 128 ]; then
        line="killed by signal $((code - 128)) (CPU limit ${limit} s: $(grep -m1 -v '^\s*$' "$err"))"
    else
        line=$(grep -m1 -v '^\s*$' "$err")
    fi
    # 100 characters, not bytes
    line=$(LC_ALL=C.UTF-8 bash -c 'printf "%s" "${1:0:100}"' _ "$line")
    printf '%s' "$line" | sed 's/|/\\|/g; s/`/'"'"'/g'
}

# run SCENE LABEL ARGS…: one row
run() {
    local scene=$1 label=$2
    shift 2
    [[ $label =~ ${ONLY:-.} ]] || return 0
    local out="$work/out" err="$work/err" times="$work/times" code cpu mb
    (
        ulimit -t "$limit"
        /usr/bin/time -o "$times" -f '%U %S %M' "$qdot" "$@" >"$out" 2>"$err"
    )
    code=$?
    # time reports the child's status in its own first line when it was killed
    read -r u s k < <(tail -n1 "$times")
    cpu=$(awk -v u="$u" -v s="$s" 'BEGIN { printf "%.1f", u + s }')
    mb=$(awk -v k="$k" 'BEGIN { printf "%d", k / 1024 }')
    printf '| %s | %s | %s | %s | %s |\n' "$label" "$scene" "$cpu" "$mb" "$(summary "$code" "$out" "$err")"
}

echo "qdot: \`$("$qdot" --version)\`, CPU limit ${limit} s a run"
echo
echo "| command | scene | CPU s | peak MB | message or answer (first 100 characters) |"
echo "|---|---|---:|---:|---|"
for scene in planar30 planar30u 3d30; do
    f="$work/$scene.qd"
    set=$(values "$scene")
    run "$scene" derive derive "$f"
    run "$scene" solve solve "$f"
    run "$scene" forces forces "$f"
    run "$scene" equilibrium equilibrium "$f"
    run "$scene" modes modes "$f"
    run "$scene" "modes --set" modes "$f" --set "$set"
    run "$scene" hamilton hamilton "$f"
    run "$scene" integrals integrals "$f"
    run "$scene" check check "$f"
    run "$scene" latex latex "$f"
    run "$scene" "latex --steps" latex "$f" --steps
    run "$scene" "codegen c" codegen "$f" --lang c
    run "$scene" "simulate --t-end 0.01" simulate "$f" --set "$set" --init "$init" --t-end 0.01
    run "$scene" "sweep (4 runs)" sweep "$f" --set "${set%,g=9.81}" --vary g=9:10:4 --init "$init" --t-end 0.01
    run "$scene" response response "$f"
    run "$scene" "response --over" response "$f" --set "$set" --over Omega=0.1:2:5
    run "$scene" floquet floquet "$f" --set "$set"
    run "$scene" cycle cycle "$f" --set "$set" --over t=0:1:3
    run "$scene" "equilibrium --steady q1" equilibrium "$f" --steady q1
    run "$scene" "modes --steady q1" modes "$f" --steady q1
done
