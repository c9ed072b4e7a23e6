#!/usr/bin/env bash
# Side-by-side timing of qdot against the anchors of ../shared/anchors
# (SymEngine and SymPy deriving the n-link pendulum chain), in one run.
#
# Set-up once: python3 -m venv /tmp/anchors && /tmp/anchors/bin/pip install sympy symengine scipy numpy
# Usage: scripts/anchors.sh [NMAX=12] [SYMPY_NMAX=8]
set -euo pipefail
cd "$(dirname "$0")/.."
NMAX=${1:-12}
SYMPY_NMAX=${2:-8}
PY=${PYTHON:-/tmp/anchors/bin/python}
ANCHORS=${ANCHORS:-../shared/anchors}
cargo build --release -q -p qdot-benches --example npendulum
echo "# qdot: n, derive seconds (best of 5), lhs terms, exact solve"
target/release/examples/npendulum "$NMAX" 3 | tee /tmp/qdot_np.txt
echo "# SymEngine: n, derive+expand seconds, size"
"$PY" "$ANCHORS/symengine_npendulum.py" "$NMAX" | tee /tmp/symengine_np.txt
echo "# SymPy LagrangesMethod: n, derive seconds, solve seconds"
"$PY" "$ANCHORS/sympy_npendulum.py" "$SYMPY_NMAX" 3 | tee /tmp/sympy_np.txt
echo
echo "| n | qdot derive (s) | SymEngine (s) | ratio | SymPy (s) | ratio |"
echo "|---|---|---|---|---|---|"
join <(awk '{print $1, $2}' /tmp/qdot_np.txt) <(awk '{print $1, $2}' /tmp/symengine_np.txt) \
  | join -a1 - <(awk '{print $1, $2}' /tmp/sympy_np.txt) \
  | awk '{ se = $3/$2; sp = ($4 == "" ? "—" : $4); r = ($4 == "" ? "—" : sprintf("%.0f×", $4/$2)); printf "| %d | %.6f | %.4f | %.1f× | %s | %s |\n", $1, $2, $3, se, sp, r }'

echo
echo "# Kinetostatic solve blocks, equilibria and modes: qdot (criterion) and SymPy, same run"
cargo bench -q -p qdot-benches --bench derive -- "seed/seed_2[12]_[12]_kinetostatic|equilibrium/seed_23_1|modes/" \
  --warm-up-time 1 --measurement-time 4 2>&1 | grep -E "time:" -B1 | grep -vE "^--|Warming|Collecting|Analyzing"
"$PY" scripts/anchor_kinetostatic.py 10

echo
echo "# Frames and rigid bodies: the heavy top and the chain of n rods in space (qdot criterion), SymPy LagrangesMethod on the same chain, same run"
FRAMES_NMAX=${FRAMES_NMAX:-5}
cargo bench -q -p qdot-benches --bench derive -- "frames/heavy_top|frames/chain3d/[235]$" \
  --warm-up-time 1 --measurement-time 4 2>&1 | grep -E "time:" -B1 | grep -vE "^--|Warming|Collecting|Analyzing"
for n in 2 3 5 10; do
  [ "$n" -le "$FRAMES_NMAX" ] && "$PY" scripts/anchor_frames.py --n "$n"
done

echo
echo "# The chain of n rods through named intermediates (qdot criterion: equations and accelerations), SymPy KanesMethod on the same chain, same run"
cargo bench -q -p qdot-benches --bench derive -- "frames/chain3d_structured/" \
  --warm-up-time 1 --measurement-time 4 2>&1 | grep -E "time:" -B1 | grep -vE "^--|Warming|Collecting|Analyzing"
for n in 4 8; do
  "$PY" scripts/anchor_kane.py --n "$n" --timeout 120
done
