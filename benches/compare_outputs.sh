#!/usr/bin/env bash
# Compares what two microslip binaries print for `dissipation` (plain, --json, --digits 20)
# over 11 compliances (three of them refused) and 6 cycles: 198 command lines. Times in
# messages are masked; a difference is printed with its command line.
# Usage: bash benches/compare_outputs.sh OLD_BINARY NEW_BINARY
set -uo pipefail
old=$1 new=$2 compared=0 differ=0
specs=("persson:gamma=1,sigma=1" "power:c=0.5,beta=-0.5" "hertz:r=1,estar=1" "poly:p0=1,coeffs=2;-0.5;-0.1"
    "rational:a=0.1,b=2,c=0.5" "exp:a=3,c=0.7,d=0.2" "2*persson:gamma=1,sigma=1+power:c=1,beta=-0.5" "const:c=1"
    "power:c=1,beta=0.5" "persson:gamma=-1,sigma=1" "power:c=1e-300,beta=-1")
cycles=("--p0 1 --p1 0.4 --q1 0.5 --phi 0.4pi" "--p0 1 --p1 0.9 --q1 0.3 --phi 1" "--p0 1 --p1 0.4 --q1 0.2 --phi 0"
    "--p0 1 --p1 0 --q1 0.5 --phi 1" "--p0 1e200 --p1 4e199 --q1 5e199 --phi 2" "--p0 1 --p1 0.999999 --q1 0.0005 --phi 0.5pi")
output() {
    # shellcheck disable=SC2086
    { "$1" dissipation $2 --friction 1 --lambda 1 --compliance "$3" $4 2>&1; echo "exit $?"; } |
        sed -E 's/[0-9.]+ ?(s|ms)\b/T/g'
}
for spec in "${specs[@]}"; do
    for cycle in "${cycles[@]}"; do
        for extra in "" "--json" "--digits 20"; do
            compared=$((compared + 1))
            if ! differences=$(diff <(output "$old" "$cycle" "$spec" "$extra") <(output "$new" "$cycle" "$spec" "$extra")); then
                differ=$((differ + 1))
                echo "differs: $cycle --compliance $spec $extra"
                head -5 <<<"$differences"
            fi
        done
    done
done
echo "$compared compared, $differ differ"
