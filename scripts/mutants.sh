#!/usr/bin/env bash
# Shows that the theorem gate catches broken segment formulas: for each of the four
# segments a flipped sign, a factor of 2 and a wrong evaluation point are applied, one
# at a time, to a copy of the tree; `microslip verify --quick` must then fail.
# Prints a table and exits 1 if any mutation is missed. Takes ~30 s per mutation.
# Needs python3 (for exact text replacement). Run from anywhere: sh scripts/mutants.sh
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
export CARGO_TARGET_DIR="${MUTANTS_TARGET_DIR:-/tmp/microslip-mutants-target}"
(cd "$root" && git ls-files -z | xargs -0 -I{} cp --parents {} "$work")

file=src/dissipation/segments.rs
# name | exact original text | replacement
mutations=$(cat <<'LIST'
EB sign flip|loads.tangential_offset * &(reverse - &normal)|loads.tangential_offset * &(reverse + &normal)
EB factor 2|g.sum_amplitude * &double_sin;|g.sum_amplitude * &double_sin * &two;
EB P instead of P_S|slope(&g.reverse_slip_offset(&half_sin))|slope(&loads.normal_offset)
BC sign flip|loads.tangential_offset * &slope(&loads.normal_offset) * &loads.tangential_rate|-(loads.tangential_offset * &slope(&loads.normal_offset) * &loads.tangential_rate)
BC factor 2|* &slope(&loads.normal_offset) * &loads.tangential_rate|* &slope(&loads.normal_offset) * &loads.tangential_rate * &two
BC P_T instead of P|* &slope(&loads.normal_offset) * &loads.tangential_rate|* &slope(&g.permanent_stick_offset) * &loads.tangential_rate
CH sign flip|loads.tangential_offset * &(normal + &forward)|loads.tangential_offset * &(normal - &forward)
CH factor 2|g.difference_amplitude * &s_sin_cos.0;|g.difference_amplitude * &s_sin_cos.0 * &two;
CH P instead of P_Y|slope(&mirror_offset)|slope(&loads.normal_offset)
HE sign flip|loads.tangential_offset * &(normal - &forward)|loads.tangential_offset * &(normal + &forward)
HE factor 2|g.difference_amplitude * &double_sin;|g.difference_amplitude * &double_sin * &two;
HE P instead of P_K|slope(&g.forward_slip_offset(&half_sin))|slope(&loads.normal_offset)
LIST
)

missed=0
printf '%-24s %s\n' "mutation" "verify --quick"
while IFS='|' read -r name original replacement; do
    cp "$root/$file" "$work/$file"
    python3 - "$work/$file" "$original" "$replacement" <<'PY'
import sys
path, original, replacement = sys.argv[1:]
text = open(path).read()
if text.count(original) != 1:
    sys.exit(f"mutation text found {text.count(original)} times: {original}")
open(path, "w").write(text.replace(original, replacement))
PY
    (cd "$work" && cargo build --release --quiet 2>/dev/null)
    if (cd "$work" && "$CARGO_TARGET_DIR/release/microslip" verify --quick >/dev/null 2>&1); then
        printf '%-24s %s\n' "$name" "MISSED (gate passed)"
        missed=$((missed + 1))
    else
        printf '%-24s %s\n' "$name" "caught"
    fi
done <<< "$mutations"
cp "$root/$file" "$work/$file"
if [ "$missed" -gt 0 ]; then
    echo "$missed mutation(s) missed"
    exit 1
fi
echo "all mutations caught"
