#!/usr/bin/env bash
# Fuzzing qdot with cargo-fuzz (libFuzzer), on the stable toolchain.
#
#   scripts/fuzz.sh run [SECONDS] [TARGET…]   each target for SECONDS (default 60)
#   scripts/fuzz.sh seeds                     rewrite the seed-* files of fuzz/corpus/
#   scripts/fuzz.sh cmin [TARGET…]            minimize fuzz/corpus/TARGET in place
#   scripts/fuzz.sh build                     build the targets only
#
# Targets: parse, pipeline, repl, simulate, commands, motions (fuzz/src/pipeline.rs
# says what each does). `run` reads the committed seeds (fuzz/corpus/TARGET, never
# written) and keeps what it finds new in fuzz/work/TARGET (not committed),
# so a long campaign resumes where the last one stopped. A crash, a time-out
# (-timeout, seconds per input) or a memory blow-up (-rss_limit_mb) stops
# the target and fails the script; the input is in fuzz/artifacts/TARGET/
# and is printed (base64) in the log. fuzz/README.md tells what to do then.
#
# Environment: FUZZ_TIMEOUT (10), FUZZ_RSS_MB (2048), FUZZ_MAX_LEN (4096),
# FUZZ_JOBS (1; more runs libFuzzer's -fork=N, N processes a target),
# FUZZ_TARGET_DIR (fuzz/target), FUZZ_ARGS (more libFuzzer flags: "-seed=1").
set -euo pipefail
cd "$(dirname "$0")/.."

TARGETS=(parse pipeline repl simulate commands motions)
CARGO_FUZZ_VERSION=0.13.2
TIMEOUT=${FUZZ_TIMEOUT:-10}
RSS_MB=${FUZZ_RSS_MB:-2048}
MAX_LEN=${FUZZ_MAX_LEN:-4096}
JOBS=${FUZZ_JOBS:-1}
TARGET_DIR=${FUZZ_TARGET_DIR:-fuzz/target}
export PATH="$HOME/.cargo/bin:$PATH"

# cargo-fuzz on stable: no sanitizer (`--sanitizer none` needs no -Z flag;
# Rust's own checks, debug assertions and overflow checks included, find
# the panics), one build shared by all targets.
FUZZ_FLAGS=(--sanitizer none --target-dir "$TARGET_DIR")

install() {
    if ! cargo fuzz --version 2>/dev/null | grep -q "$CARGO_FUZZ_VERSION"; then
        echo "== installing cargo-fuzz $CARGO_FUZZ_VERSION"
        cargo install cargo-fuzz --version "$CARGO_FUZZ_VERSION" --locked --quiet
    fi
}

build() {
    install
    echo "== cargo fuzz build (${TARGETS[*]})"
    local t0=$SECONDS
    cargo fuzz build "${FUZZ_FLAGS[@]}"
    echo "   built in $((SECONDS - t0)) s"
}

# run SECONDS TARGET: one bounded campaign; the last lines of libFuzzer's
# log (its final stats) are echoed.
run_one() {
    local secs=$1 t=$2 log
    mkdir -p "fuzz/work/$t" "fuzz/artifacts/$t"
    log=$(mktemp)
    echo "== fuzz $t for ${secs}s"
    local status=0
    cargo fuzz run "${FUZZ_FLAGS[@]}" "$t" "fuzz/work/$t" "fuzz/corpus/$t" -- \
        -max_total_time="$secs" -timeout="$TIMEOUT" -rss_limit_mb="$RSS_MB" -max_len="$MAX_LEN" -dict=fuzz/qd.dict \
        -print_final_stats=1 $([ "$JOBS" -gt 1 ] && echo "-fork=$JOBS") \
        -artifact_prefix="fuzz/artifacts/$t/" ${FUZZ_ARGS:-} >"$log" 2>&1 || status=$?
    # the final stats: plain mode's `Done N runs in S second(s)` and
    # stat:: lines, fork mode's last `#N: cov:` line
    grep -E '^(Done [0-9]+ runs|stat::number_of_executed_units|stat::peak_rss_mb)' "$log" | sed 's/^/   /' || true
    grep -E '^#[0-9]+: cov:' "$log" | tail -1 | sed 's/^/   /' || true
    if [ "$status" != 0 ]; then
        echo "!! fuzz target $t found a failure (exit $status):"
        grep -E -A30 'panicked at|ERROR: libFuzzer|overflowed its stack|SUMMARY' "$log" | head -80
        for f in "fuzz/artifacts/$t"/*; do
            [ -f "$f" ] || continue
            echo "   input $f (base64):"
            base64 -w 0 "$f" | head -c 8000
            echo
        done
    fi
    rm -f "$log"
    return "$status"
}

run() {
    local secs=${1:-60}
    shift || true
    local ts=("$@")
    [ ${#ts[@]} -gt 0 ] || ts=("${TARGETS[@]}")
    build
    local failed=()
    local t0=$SECONDS
    for t in "${ts[@]}"; do
        run_one "$secs" "$t" || failed+=("$t")
    done
    echo "== fuzzing took $((SECONDS - t0)) s"
    if [ ${#failed[@]} -gt 0 ]; then
        echo "!! findings in: ${failed[*]} (inputs in fuzz/artifacts/; see fuzz/README.md)"
        return 1
    fi
    echo "   no findings"
}

cmin() {
    local ts=("$@")
    [ ${#ts[@]} -gt 0 ] || ts=("${TARGETS[@]}")
    install
    for t in "${ts[@]}"; do
        cargo fuzz cmin "${FUZZ_FLAGS[@]}" "$t" "fuzz/corpus/$t" -- \
            -timeout="$TIMEOUT" -rss_limit_mb="$RSS_MB"
    done
}

# A name for a seed file: seed-<origin>-<file stem>.
seed_name() { basename "$1" | sed 's/\.[a-z]*$//'; }

# The parameters of a scene, each set to 1: "m=1,g=1" (for --set).
ones() {
    sed -n 's/#.*//; s/^[[:space:]]*parameters[[:space:]]\+//p' "$1" |
        tr ',' '\n' | tr -d ' \t' | sed '/^$/d; s/:.*//; s/$/=1/' | paste -sd, -
}

seeds() {
    local c=fuzz/corpus
    mkdir -p "$c/parse" "$c/pipeline" "$c/repl" "$c/simulate" "$c/commands" "$c/motions"
    rm -f "$c"/*/seed-*
    local scenes=(examples/*.qd book/scenes/*.qd tests/data/dimensions/*/*.qd tests/data/frames/*/*.qd tests/data/constraints/*/*.qd)
    for f in "${scenes[@]}"; do
        local n
        n=$(seed_name "$f")
        cp "$f" "$c/parse/seed-$n"
        # pipeline: solve (no header), derive as JSON, the LaTeX, the
        # equilibria with every parameter 1, the modes
        cp "$f" "$c/pipeline/seed-$n"
        { echo "#@ derive json"; cat "$f"; } >"$c/pipeline/seed-$n-derive-json"
        { echo "#@ latex latex"; cat "$f"; } >"$c/pipeline/seed-$n-latex"
        { echo "#@ equilibrium json $(ones "$f")"; cat "$f"; } >"$c/pipeline/seed-$n-equilibrium"
        { echo "#@ modes text"; cat "$f"; } >"$c/pipeline/seed-$n-modes"
        { echo "#@ check json"; cat "$f"; } >"$c/pipeline/seed-$n-check"
        { echo "#@ hamilton json"; cat "$f"; } >"$c/pipeline/seed-$n-hamilton"
        { echo "#@ integrals text"; cat "$f"; } >"$c/pipeline/seed-$n-integrals"
        # repl: the scene's lines, then the commands
        { cat "$f"; printf ':solve\n:equations\n:format json\n:forces\n:format latex\n:show\n:undo\n:scene\n:reset\n'; } \
            >"$c/repl/seed-$n"
    done
    for f in book/scenes/*.repl; do
        cp "$f" "$c/repl/seed-$(seed_name "$f")"
        cp "$f" "$c/parse/seed-$(seed_name "$f")"
    done
    # the book's inline scene fragments (```qd and unlabelled blocks that
    # are not includes)
    awk -v dir="$c/parse" '
        FNR == 1 { inb = 0 }
        /^```/ {
            if (inb) { inb = 0; if (keep && body != "") { k++; printf "%s", body > (dir "/seed-book-" k); close(dir "/seed-book-" k) } }
            else { inb = 1; lang = substr($0, 4); keep = (lang == "" || lang == "qd"); body = "" }
            next
        }
        inb && keep && !/\{\{#include/ { body = body $0 "\n" }
    ' book/src/*.md book/src/simulation/*.md
    # simulate: the book's runs, every method, events, the edges of the options
    local s=$c/simulate
    printf -- '--set m=1,l=1,g=1\n--init theta=3,theta'"'"'=0\n--t-end 10\n--stop-when theta=0\n--points 3\n--rtol 1e-12\n--atol 1e-12\n' >"$s/seed-book-pendulum-event"
    { printf -- '--set m=1,k=6,R=0.5\n--init x1=1,x2=1.3333333333333333,x1'"'"'=0,x2'"'"'=0\n--t-end 6.283185307179586\n--points 5\n--rtol 1e-12\n--atol 1e-12\n---\n'; cat examples/seed_24_2.qd; } >"$s/seed-book-seed_24_2"
    for m in rk4 dopri5 dop853 vern7 gauss6 radau5; do
        printf -- '--set m=1,l=1,g=9.81\n--init theta=0.5,theta'"'"'=0\n--t-end 2\n--method %s\n--dt 0.01\n--points 11\n--output json\n' "$m" >"$s/seed-method-$m"
    done
    printf -- '--set m=1,l=1,g=9.81\n--init theta=2.5,theta'"'"'=0\n--t-end 5\n--plot\n--stop-when theta'"'"' = 0\n' >"$s/seed-plot-stop"
    { printf -- '--set m=1,k=1,c=1,F0=1,p=2\n--init x=0,x'"'"'=0\n--t-end 3\n--points 4\n---\n'; cat examples/forced_oscillator.qd; } >"$s/seed-forced"
    # commands: each example's integrals and Hamiltonian as JSON, its C
    # (every parameter bound) and its Python M and f (the example's name
    # as the file name)
    local k=$c/commands
    for f in examples/*.qd; do
        local n
        n=$(seed_name "$f")
        { printf -- '--command integrals\n--format json\n---\n'; cat "$f"; } >"$k/seed-$n-integrals"
        { printf -- '--command hamilton\n--format latex\n---\n'; cat "$f"; } >"$k/seed-$n-hamilton"
        { printf -- '--command codegen\n--lang c\n--file %s.qd\n--set %s\n---\n' "$n" "$(ones "$f")"; cat "$f"; } >"$k/seed-$n-codegen-c"
        { printf -- '--command codegen\n--lang python\n--form mass-matrix\n--file %s.qd\n---\n' "$n"; cat "$f"; } >"$k/seed-$n-codegen-python"
    done
    # commands: sweeps (grids, random designs, events, threads, a name
    # varied twice), codegen names that are keywords or macros
    printf -- '--command sweep\n--set m=1,g=9.81\n--init theta'"'"'=0\n--vary l=0.5:2:3\n--vary theta=0.5:3:2\n--t-end 5\n--points 11\n' >"$k/seed-sweep-book"
    printf -- '--command sweep\n--set m=1,g=1,l=1\n--init theta'"'"'=0\n--vary theta=0.1:3\n--samples 8\n--seed 7\n--threads 2\n--t-end 2\n--output json\n' >"$k/seed-sweep-random"
    printf -- '--command sweep\n--set m=1,g=1\n--init theta=1,theta'"'"'=0\n--vary l=1:2:3\n--stop-when 1/(theta-0.5) = 0\n--t-end 3\n' >"$k/seed-sweep-pole"
    printf -- '--command sweep\n--set m=1,g=1\n--init theta'"'"'=0\n--vary l=1:2:3\n--vary l=1:2:3\n--t-end 1\n' >"$k/seed-sweep-twice"
    printf -- '--command sweep\n--set m=1,g=1\n--init theta=1,theta'"'"'=0\n--vary l=1:2:2\n--threads 100000\n--t-end 1\n' >"$k/seed-sweep-threads"
    { printf -- '--command codegen\n--lang c\n--file M_PI.qd\n---\n'; printf 'coordinates x\nparameters M_E, unix, FP_NAN, _Bool, double\nkinetic E = 1/2*M_E*x'"'"'^2\npotential V = 1/2*(unix + FP_NAN + _Bool + double)*x^2\n'; } >"$k/seed-codegen-macros"
    { printf -- '--command integrals\n--format json\n---\n'; cat examples/moving_support.qd; } >"$k/seed-integrals-given"
    { printf -- '--command codegen\n--lang python\n--function s=t^2\n---\n'; cat examples/moving_support.qd; } >"$k/seed-codegen-given"
    motion_seeds
    echo "seeds: $(ls "$c"/*/seed-* | wc -l) files, $(cat "$c"/*/* | wc -c) bytes"
}

# motions: each example's exact response (every parameter 1); the book's cycles, responses, Floquet runs and
# steady motions; each mechanism fixture's cycle at 7 positions. Counts
# stay within the target's bound (fuzz/src/pipeline.rs, MAX_FUZZ_POINTS).
motion_seeds() {
    local m=fuzz/corpus/motions f n
    for f in examples/*.qd; do
        n=$(seed_name "$f")
        { printf -- '--command response\n--set %s\n---\n' "$(ones "$f")"; cat "$f"; } >"$m/seed-$n-response"
    done
    # seed(NAME, SCENE, OPTION LINES…)
    seed() {
        local name=$1 scene=$2
        shift 2
        { printf -- '%s\n' "$@" ---; cat "$scene"; } >"$m/seed-$name"
    }
    local s213='G1=20,G2=15,G3=10,g=9.81,R=0.1,AB=0.4,AC=0.15,J2=0.02,k=500,l0=0.45,mu=0.15,omega=20'
    seed cycle-seed_21_3 examples/seed_21_3.qd '--command cycle' '--over phi=0:360deg:7' "--set $s213" \
        '--guess x2=0.25,xB=0.5' '--columns xB,alpha,O_x,O_y,A_x,A_y,B_x,B_y,S_n,S_f,M'
    seed cycle-slider_driven_crank examples/mechanisms/slider_driven_crank.qd '--command cycle' '--over t=0:0.6:9' \
        '--set R=0.1,L=0.4,omega=10,m1=1,J1=0.005,m2=2,J2=0.03,m3=1.5,g=9.81' '--guess xb=0.5,phi=0.2'
    local fx field
    for fx in tests/fixtures/mechanisms/*.json; do
        field() { sed -n 's/^  "'"$1"'": "\(.*\)",\{0,1\}$/\1/p' "$fx"; }
        seed "cycle-$(seed_name "$fx")" "$(field scene)" '--command cycle' \
            "--over $(field over | sed 's/:[0-9]*$/:7/')" "--set $(field set)" "--guess $(field guess)"
    done
    seed response-vibration_absorber-over examples/vibration_absorber.qd '--command response' \
        '--set m1=1,m2=0.2,k1=1,k2=0.2,c=0.02,F0=1' '--over Omega=0.6:1.4:9'
    seed response-forced_oscillator examples/forced_oscillator.qd '--command response'
    seed floquet-kapitza examples/kapitza.qd '--command floquet' '--at theta=pi' '--set m=1,l=1,g=9.81,a=0.05,w=100'
    seed floquet-kapitza-over examples/kapitza.qd '--command floquet' '--at theta=pi' \
        '--set m=1,l=1,g=9.81,a=0.05' '--over w=80:100:3'
    seed floquet-moving_support examples/moving_support.qd '--command floquet' \
        "--function s=1/10*cos(3*t)" '--set m=1,l=1,g=9.81'
    seed floquet-mathieu examples/mathieu.qd '--command floquet' '--set delta=0.25,eps=0.2,m=1,w=1'
    seed floquet-mathieu-chart examples/mathieu.qd '--command floquet' '--set m=1,w=1' \
        '--over delta=-0.5:2.5:4,eps=0:2:3'
    seed floquet-mathieu-period examples/mathieu.qd '--command floquet' '--set delta=0.5,eps=0.2,m=1,w=1' '--period 6.283185307179586'
    seed modes-steady-spherical examples/spherical_pendulum.qd '--command modes' '--steady phi' '--at theta=theta0'
    seed modes-steady-spherical-pi3 examples/spherical_pendulum.qd '--command modes' '--steady phi' '--at theta=pi/3' '--format json'
    seed modes-steady-heavy_top examples/heavy_top.qd '--command modes' '--steady phi,psi' '--at theta=theta0' '--format latex'
    seed modes-steady-central_force examples/central_force.qd '--command modes' '--steady phi' '--at r=r0'
    seed equilibrium-steady-spherical examples/spherical_pendulum.qd '--command equilibrium' '--steady phi'
    # a bead on a hoop that spins freely (the hoop's inertia J)
    local hoop
    hoop=$(mktemp)
    printf '%s\n' 'coordinates theta: angle, phi: angle' 'parameters m, R, g, J' \
        "kinetic E = 1/2*m*R^2*(theta'^2 + sin(theta)^2*phi'^2) + 1/2*J*phi'^2" \
        'potential V = -m*g*R*cos(theta)' >"$hoop"
    seed equilibrium-steady-hoop "$hoop" '--command equilibrium' '--steady phi' '--format json'
    seed modes-steady-hoop "$hoop" '--command modes' '--steady phi' '--at theta=pi/3' '--set m=1,R=1,g=9.81,J=1' \
        "--init theta=1/10,theta'=0"
    rm -f "$hoop"
    seed equilibrium-steady-heavy_top examples/heavy_top.qd '--command equilibrium' '--steady phi,psi' '--set m=1,g=1,l=1,A=2,C=1'
}

case "${1:-run}" in
run) shift || true; run "$@" ;;
build) build ;;
cmin) shift; cmin "$@" ;;
seeds) seeds ;;
*) echo "usage: scripts/fuzz.sh run [SECONDS] [TARGET…] | build | cmin [TARGET…] | seeds" >&2; exit 2 ;;
esac
