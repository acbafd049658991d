#!/usr/bin/env bash
# Two builds of microslip side by side on the verified-digits paths (proofs/reference-values.md):
# the printed output of W (3000 random f64 rows and 400 rows at 30 digits through `batch`, the
# catalogue written at 50 and 200 digits), of I(ρ, φ) and of the series over a grid, whether each
# f64-printed I is the 30-digit value rounded, and the CPU time of alternating runs.
# Usage: benches/verified_digits_ab.sh BEFORE_BIN AFTER_BIN [repeats]   (default 15)
set -euo pipefail
cd "$(dirname "$0")/.."
before=$1; after=$2; repeats=${3:-15}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
awk -v n=3000 -v seed=7 'BEGIN {
    srand(seed)
    split("persson:gamma=1,sigma=1|power:c=0.5,beta=-0.5|hertz:r=2,estar=3|exp:a=1,c=0.5,d=0.2|power:c=1e-3,beta=-2|persson:gamma=1,sigma=1+const:c=0.5", spec, "|")
    print "id,p0,p1,q0,q1,phi,friction,lambda,compliance"
    for (i = 0; i < n; i++) {
        f = 0.05 + 1.2 * rand(); p1 = 0.001 + 0.9 * rand(); q1 = (0.01 + 0.98 * rand()) * f * p1
        ph = (i % 3 == 0) ? rand() * 1e-3 : rand()
        printf "r%d,1,%.6f,%.3f,%.6f,%.6fpi,%.2f,%.3f,\"%s\"\n", i, p1, (i%5==0)? 0.3*rand()*f : 0, q1, ph, f, 1 + rand(), spec[i % 6 + 1]
    }
}' > "$dir/rows.csv"
head -400 "$dir/rows.csv" > "$dir/rows400.csv"
grid() {
    for rho in 1e-8 1e-4 0.01 0.1 0.3 0.5 0.7 0.9 0.99 0.999999 1 1.000001 1.01 1.1 1.5 2 3 10 100 1e4 1e8 1e50; do
        for phi in 1e-12 1e-9 1e-6 1e-4 0.01 0.1 0.3 0.7 1 1.3 0.5pi 2 2.5 3 pi-1e-3 pi-1e-6 pi-1e-9 3.5 5 6.2 1e3; do
            "$1" small-amplitude --rho $rho --phi $phi --json "${@:2}" 2>&1 || true; echo
        done
    done
}
for side in before after; do
    bin=${!side}; out="$dir/$side"; mkdir -p "$out"
    "$bin" batch --input "$dir/rows.csv" --output "$out/batch.csv" 2>/dev/null || true
    "$bin" batch --input "$dir/rows400.csv" --output "$out/batch30.csv" --digits 30 2>/dev/null || true
    for d in 50 200; do
        cp tests/data/catalogue.json "$out/catalogue$d.json"
        "$bin" reference --catalogue "$out/catalogue$d.json" --write --digits $d > /dev/null
    done
    for rho in 0.5 1.25 3; do for phi in 1e-6 0.4pi 2; do
        "$bin" series --rho $rho --phi $phi --order 6
        "$bin" series --rho $rho --phi $phi --order 4 --digits 25
    done; done > "$out/series.txt" 2>&1
    grid "$bin" > "$out/grid.jsonl"
done
grid "$after" --digits 30 > "$dir/truth.jsonl"
for f in batch.csv batch30.csv catalogue50.json catalogue200.json series.txt grid.jsonl; do
    if cmp -s "$dir/before/$f" "$dir/after/$f"; then echo "$f: same"; else echo "$f: $(diff "$dir/before/$f" "$dir/after/$f" | grep -c '^>') lines differ"; fi
done
python3 - "$dir" "$before" "$after" "$repeats" <<'PY'
import json, resource, subprocess, sys
from decimal import Decimal
d, before, after, repeats = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
load = lambda f: [json.loads(l) if l.startswith('{') else None for l in open(f) if l.strip()]
truth = load(f'{d}/truth.jsonl')
rounded = lambda x, k: Decimal(format(Decimal(x), f'.{k-1}e'))
for side in ('before', 'after'):
    rows = [(t, x) for t, x in zip(truth, load(f'{d}/{side}/grid.jsonl')) if t and x]
    wrong = sum(Decimal(x['I']) != rounded(t['I'], x['digits']) for t, x in rows)
    print(f'I(rho, phi) {side}: {wrong} of {len(rows)} printed values have a wrong digit')
case = ['--p0', '1', '--p1', '0.4', '--q1', '0.5', '--phi', '0.4pi', '--friction', '1', '--lambda', '1',
        '--compliance', 'persson:gamma=1,sigma=1']
runs = {'W 50 digits': ['dissipation', *case, '--digits', '50'], 'W 100 digits': ['dissipation', *case, '--digits', '100'],
        'I 30 digits': ['small-amplitude', '--rho', '0.5', '--phi', '1e-6', '--digits', '30'],
        'I 100 digits': ['small-amplitude', '--rho', '1.25', '--phi', '0.4pi', '--digits', '100'],
        'I0..I30 100 digits': ['series', '--rho', '1.25', '--phi', '0.4pi', '--order', '30', '--digits', '100']}
for name, args in runs.items():
    times = {before: [], after: []}
    for i in range(repeats):
        for b in ((before, after) if i % 2 == 0 else (after, before)):
            r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
            subprocess.run([b, *args], capture_output=True)
            r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
            times[b].append(1000 * (r1.ru_utime - r0.ru_utime + r1.ru_stime - r0.ru_stime))
    med = {b: sorted(t)[len(t) // 2] for b, t in times.items()}
    print(f'{name}: CPU ms median before {med[before]:.1f}, after {med[after]:.1f}')
PY
