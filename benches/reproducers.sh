#!/usr/bin/env bash
# Times the reproducers of the proven-digits issue (wrong digits, spins, refusals) with the
# release binary: each must print the right digits or the exact value, in under a second.
# Usage: bash benches/reproducers.sh   (after `cargo build --release`)
set -euo pipefail
bin="$(cd "$(dirname "$0")/.." && pwd)/target/release/microslip"
persson="--friction 1 --lambda 1 --compliance persson:gamma=1,sigma=1"
run() {
    local start end
    start=$(date +%s.%N)
    out=$("$bin" "$@" 2>&1 | head -1 | cut -c1-110) || true
    end=$(date +%s.%N)
    printf '%6.3f s  %s\n         %s\n' "$(echo "$end - $start" | bc)" "$*" "$out"
}
run dissipation --p0 1 --p1 0.4 --q1 0.2 --phi 3.141592653589793 $persson
run dissipation --p0 1 --p1 0.4 --q1 0.2 --phi pi-1e-100 --digits 20 $persson
run small-amplitude --rho 0.5 --phi pi-1e-100 --digits 20
run series --rho 0.5 --phi pi-1e-100 --order 2
run dissipation --p0 1 --p1 0.82575 --q1 0.25651 --phi 1.7464 --friction 1.217 --lambda 1.78 --compliance persson:gamma=1,sigma=1
run dissipation --p0 1 --p1 0.3 --q0 0.12526586642305143 --q1 0.7650853137335195 --phi 1 --friction 0.8 --lambda 1.2 --compliance power:c=1,beta=-3
run series --p0 1 --p1 0.1 --q1 0.1 --phi 0.4pi --friction 1 --lambda 1 --compliance 'poly:p0=1,coeffs=2;-0.5' --order 3
for spec in const:c=0.8 '2*const:c=1' 'const:c=1+const:c=2' 'poly:p0=1,coeffs=1;0;0' 'rational:a=1,b=0,c=1' 'exp:a=0,c=1,d=1' 'power:c=1,beta=-1+power:c=-1,beta=-1+const:c=1'; do
    run dissipation --p0 1 --p1 0.4 --q1 0.2 --phi 0.4pi --friction 1 --lambda 1 --compliance "$spec" --digits 25
done
run simulate --p0 1 --p1 0.4 --q1 0.2 --phi 0.4pi --friction 1 --lambda 1 --compliance const:c=1
run dissipation --p0 1 --p1 0.4 --q1 0.2 --phi 1e-50 $persson
run series --rho 1.000001 --phi 1e-6 --order 2
run dissipation --p0 1 --p1 0.999999999999999 --q1 1e-16 --phi 0.4pi $persson
