#!/bin/sh
# The f64 default run beside the same integrand on inari intervals (outward rounding), per
# case, in µs: `sh benches/f64_intervals.sh [BUDGET_MS]` (best of runs over BUDGET_MS, default
# 400). A separate crate (benches/f64_intervals), not a workspace member and not in CI: inari
# needs x86-64 Haswell or newer, set in its .cargo/config.toml. proofs/certified-digits.md,
# "f64 against Arb at 53 bits", records the figures.
set -eu
cd "$(dirname "$0")/f64_intervals"
cargo run --release --quiet -- "$@"
