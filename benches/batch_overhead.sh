#!/usr/bin/env bash
# The batch's own cost beside its rows', and its speed-up on two cores, for a baseline binary and
# this tree's side by side (the targets: per-row overhead ≤ 1.5×, `--jobs 2` ≥ 1.7× `--jobs 1`):
#   benches/batch_overhead.sh BASELINE [ROWS ...]     (default 2000 20000 rows; REPEATS=3)
# BASELINE is a microslip binary built from another commit (e.g. main's HEAD, copied to /tmp).
# Rows: benches/ordinary_rows.awk, seed 14. For each row count, binary and --jobs 1 and 2, the
# best wall time of REPEATS runs (the runs of both binaries interleaved) and that run's user and
# sys seconds give: rows/s, the jobs-2 speed-up, and the per-row overhead ratio = whole-process CPU
# per row / in-process CPU per row (examples/batch_in_process.rs: the same rows one after another,
# no batch). The outputs of both binaries are compared byte for byte. The control: the in-process
# pass alone, then two at once, is what two cores give any CPU-bound work at the time, and the load
# average says how shared the machine is. REALTIME=1 runs every timed command under `chrt -f 1`
# (root): ahead of the other work of a shared machine, as on an idle one, for the few seconds each
# run takes (Linux leaves other work 5 % of each second: a run over a second loses that much).
set -euo pipefail
cd "$(dirname "$0")/.."
base=${1:?usage: benches/batch_overhead.sh BASELINE [ROWS ...]}
shift
counts=("$@")
[ ${#counts[@]} -gt 0 ] || counts=(2000 20000)
repeats=${REPEATS:-3}
ahead=()
[ "${REALTIME:-0}" = 1 ] && ahead=(chrt -f 1)
cargo build --release --quiet --bin microslip --example batch_in_process
new=target/release/microslip
in_process=target/release/examples/batch_in_process
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

# Wall, user and sys seconds of one run (exit code 1, some rows failed, is not fatal here).
timed() {
    "${ahead[@]}" /usr/bin/env time -f "%e %U %S" -o "$dir/time" "$@" >/dev/null 2>&1 || true
    tail -1 "$dir/time"
}

for count in "${counts[@]}"; do
    rows=$dir/rows-$count.csv
    awk -v n="$count" -v seed=14 -f benches/ordinary_rows.awk >"$rows"
    per_row=$("${ahead[@]}" "$in_process" "$rows" "$repeats" | awk '{ print $(NF - 3) }')
    declare -A best=()
    for _ in $(seq "$repeats"); do
        for name in baseline new; do
            bin=$base
            [ "$name" = new ] && bin=$new
            for jobs in 1 2; do
                out=$dir/$name-$jobs.csv
                read -r wall user sys <<<"$(timed "$bin" batch --input "$rows" --output "$out" -q --jobs "$jobs")"
                key=$name-$jobs
                if [ -z "${best[$key]:-}" ] || awk -v w="$wall" -v b="${best[$key]%% *}" 'BEGIN { exit !(w < b) }'; then
                    best[$key]="$wall $user $sys"
                fi
            done
        done
    done
    for jobs in 1 2; do
        cmp -s "$dir/baseline-$jobs.csv" "$dir/new-$jobs.csv" || echo "OUTPUTS DIFFER: $count rows, --jobs $jobs"
    done
    echo "$count rows; in process ${per_row} µs of CPU per row; load average $(cut -d' ' -f1-3 /proc/loadavg)"
    printf "%-9s %4s %8s %7s %7s %6s %10s %9s %9s\n" binary jobs rows/s wall_s user_s sys_s cpu_µs/row overhead speed-up
    for name in baseline new; do
        for jobs in 1 2; do
            read -r wall user sys <<<"${best[$name-$jobs]}"
            read -r wall1 _ <<<"${best[$name-1]}"
            awk -v n="$name" -v j="$jobs" -v c="$count" -v w="$wall" -v u="$user" -v s="$sys" -v r="$per_row" -v w1="$wall1" 'BEGIN {
                cpu = (u + s) / c * 1e6
                printf "%-9s %4d %8.0f %7.2f %7.2f %6.2f %10.0f %8.2fx %8.2fx\n", n, j, c / w, w, u, s, cpu, cpu / r, w1 / w
            }'
        done
    done
    unset best
done

# The control: what two cores give CPU-bound work now (two in-process passes at once).
rows=$dir/rows-${counts[0]}.csv
start=$(date +%s.%N)
"${ahead[@]}" "$in_process" "$rows" 1 >/dev/null
one=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
start=$(date +%s.%N)
"${ahead[@]}" "$in_process" "$rows" 1 >/dev/null &
"${ahead[@]}" "$in_process" "$rows" 1 >/dev/null
wait
two=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
awk -v one="$one" -v two="$two" 'BEGIN {
    printf "control: one in-process pass %.2f s wall, two at once %.2f s: two cores give %.2fx\n", one, two, 2 * one / two
}'
echo "load average $(cut -d' ' -f1-3 /proc/loadavg); CPUs $(nproc); realtime ${REALTIME:-0}"
