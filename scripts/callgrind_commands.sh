#!/usr/bin/env bash
# Instruction counts (valgrind --tool=callgrind, Ir) of qdot's main commands
# on fixed inputs: a machine-independent measure for "speed unchanged" when
# a change is structural. Run it on the old and the new binary and compare.
#
#   QDOT=/path/to/old/qdot scripts/callgrind_commands.sh > before.txt
#   scripts/callgrind_commands.sh > after.txt
#
# QDOT (default target/release/qdot) is the binary measured.
set -euo pipefail
cd "$(dirname "$0")/.."
qdot=${QDOT:-target/release/qdot}
command -v valgrind >/dev/null || { echo "valgrind is required" >&2; exit 1; }

set_213='G1=20,G2=15,G3=10,g=9.81,R=0.1,AB=0.4,AC=0.15,J2=0.02,k=500,l0=0.45,mu=0.15,omega=20'
runs=(
    "derive double_pendulum|derive examples/double_pendulum.qd"
    "solve double_pendulum|solve examples/double_pendulum.qd"
    "solve seed_23_4|solve examples/seed_23_4.qd"
    "modes four_mass_chain|modes examples/four_mass_chain.qd"
    "cycle seed_21_3, 3,600 positions|cycle examples/seed_21_3.qd --over phi=0:360deg:3600 --set $set_213 --guess x2=0.25,xB=0.5"
    "response absorber, 10,000 frequencies|response examples/vibration_absorber.qd --set m1=1,m2=0.2,k1=1,k2=0.2,c=0.02,F0=1 --over Omega=0.6:1.4:10000"
    "floquet mathieu|floquet examples/mathieu.qd --set delta=0.25,eps=0.2,m=1,w=1"
)
printf '| run | instructions (Ir) |\n|---|---:|\n'
for run in "${runs[@]}"; do
    IFS='|' read -r name args <<< "$run"
    read -r -a argv <<< "$args"
    ir=$(valgrind --tool=callgrind --callgrind-out-file=/dev/null "$qdot" "${argv[@]}" 2>&1 >/dev/null \
        | sed -n 's/.*Collected : *\([0-9]*\).*/\1/p')
    printf '| %s | %s |\n' "$name" "$ir"
done
