#!/usr/bin/env bash
# Shows that the theorem gate catches wrong formulas. Each mutation below is applied,
# one at a time, as an exact text replacement to a copy of the working tree:
#   - for each of the four segment integrands (src/dissipation/segments.rs): a flipped
#     sign, a factor of 2, and a wrong evaluation point (P instead of P_S, P_Y, P_K;
#     P_T instead of P in the stick segment);
#   - in the ellipse geometry (src/cycle.rs): the slip loads P_S, P_K and P_T built
#     wrongly, and the stick and slip angles swapped;
#   - in the in-phase closed form (src/dissipation/closed_forms.rs): a sign and a factor;
#   - in the exact methods (src/exact/, claim 7): the closed-form I (a sign, a factor, the
#     stick angle for the slip angle), the exact segment integrands (a sign, a factor, a
#     wrong angle or load), the trigonometric product and integral, the series' factorial
#     and a compliance derivative.
#   - for each of the four segment integrands, a perturbation by 1e-40 (added to the
#     integrand): far below what f64 or the gate's precisions see, so only the certified
#     enclosures are asked to catch it (the mutations marked `certified`).
# MUTANTS_FILTER=regex runs only the mutations whose name matches it.
# The mutated release binary then runs `microslip verify --quick`, which must fail
# (exit 1). A mutation of a segment integrand (src/dissipation/segments.rs) must also
# make the certified enclosures exclude the exact polynomial W: the test
# `certified::segment_enclosures_hold_the_exact_polynomial_w` must fail on it
# (MUTANTS_CERTIFIED=0 skips this check, which adds a test build per mutation, and the
# `certified` mutations with it). Prints one line per mutation with the claims that failed,
# and exits 1 if any mutation is missed (or 2 if the tree does not build or the unmutated
# gate fails).
# Not run in CI: about 20 s per mutation (incremental build of a copy).
# MUTANTS_TARGET_DIR=DIR builds there (default /tmp/microslip-mutants-target).
# Usage: sh scripts/mutants.sh (re-runs itself under bash; needs python3 for exact replacements)
if [ -z "${BASH_VERSION:-}" ]; then exec bash "$0" "$@"; fi
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
export CARGO_TARGET_DIR="${MUTANTS_TARGET_DIR:-/tmp/microslip-mutants-target}"
# The working tree as it is (committed or not), without build output or history.
tar -C "$root" --exclude=./target --exclude=./.git -cf - . | tar -C "$work" -xf -
binary="$CARGO_TARGET_DIR/release/microslip"

# file | name | exact original text (must occur once) | replacement [| certified: only the
# certified enclosures must catch it]
mutations=$(cat <<'LIST'
src/dissipation/segments.rs|EB sign flip|tangential_offset * &(reverse - &normal)|tangential_offset * &(reverse + &normal)
src/dissipation/segments.rs|EB factor 2|* &g.sum_amplitude * &double_sin;|* &g.sum_amplitude * &double_sin * &double_sin.int(2);
src/dissipation/segments.rs|EB P instead of P_S|slope(&g.reverse_slip_offset(&half_sin))|slope(&g.loads_at(&theta).normal_offset())
src/dissipation/segments.rs|BC sign flip|loads.tangential_offset() * &change * &loads.tangential_rate()|-(loads.tangential_offset() * &change * &loads.tangential_rate())
src/dissipation/segments.rs|BC factor 2|loads.tangential_offset() * &change * &loads.tangential_rate()|loads.tangential_offset() * &change * &loads.tangential_rate() * &change.int(2)
src/dissipation/segments.rs|BC P_T instead of P|loads.tangential_offset() * &change * &loads.tangential_rate()|loads.tangential_offset() * &slope(&g.permanent_stick_offset) * &loads.tangential_rate()
src/dissipation/segments.rs|CH sign flip|tangential_offset * &(normal + &forward)|tangential_offset * &(normal - &forward)
src/dissipation/segments.rs|CH factor 2|* &g.difference_amplitude * &from_c_sin;|* &g.difference_amplitude * &from_c_sin * &from_c_sin.int(2);
src/dissipation/segments.rs|CH P instead of P_Y|slope(&(g.normal_amplitude.clone() * &mirror_cos))|slope(&g.loads_at(&theta).normal_offset())
src/dissipation/segments.rs|HE sign flip|tangential_offset * &(normal - &forward)|tangential_offset * &(normal + &forward)
src/dissipation/segments.rs|HE factor 2|* &g.difference_amplitude * &double_sin;|* &g.difference_amplitude * &double_sin * &double_sin.int(2);
src/dissipation/segments.rs|HE P instead of P_K|slope(&g.forward_slip_offset(&half_sin))|slope(&g.loads_at(&theta).normal_offset())
src/dissipation/segments.rs|EB plus 1e-40|tangential_offset * &(reverse - &normal)|tangential_offset * &(reverse - &normal) + &normal.int(10).powi(-40)|certified
src/dissipation/segments.rs|BC plus 1e-40|loads.tangential_offset() * &change * &loads.tangential_rate()|loads.tangential_offset() * &change * &loads.tangential_rate() + &change.int(10).powi(-40)|certified
src/dissipation/segments.rs|CH plus 1e-40|tangential_offset * &(normal + &forward)|tangential_offset * &(normal + &forward) + &forward.int(10).powi(-40)|certified
src/dissipation/segments.rs|HE plus 1e-40|tangential_offset * &(normal - &forward)|tangential_offset * &(normal - &forward) + &forward.int(10).powi(-40)|certified
src/cycle.rs|P_S with sigma- for sigma+|self.sum_amplitude.clone() * &half_angle_sin.square() / &self.friction|self.difference_amplitude.clone() * &half_angle_sin.square() / &self.friction
src/cycle.rs|P_K without 1/f|self.difference_amplitude.clone() * &half_angle_sin.square() / &self.friction|self.difference_amplitude.clone() * &half_angle_sin.square()
src/cycle.rs|P_T offset doubled|(cycle.friction.clone() * &phi.int(2))|cycle.friction.clone()
src/cycle.rs|stick and slip angles swapped|let stick_angle = cross.atan2(&dot);|let stick_angle = cross.atan2(&(-dot.clone()));
src/dissipation/closed_forms.rs|in-phase W2 sign flip|let w2 = f.clone() * q1|let w2 = -f.clone() * q1
src/dissipation/closed_forms.rs|in-phase W4 factor 2|let w4 = f.clone() * q1 * &zero.int(2)|let w4 = f.clone() * q1 * &zero.int(4)
src/exact/coefficient.rs|closed-form I slip sign|let j = -stick_part - &slip_part;|let j = -stick_part + &slip_part;
src/exact/coefficient.rs|closed-form I factor|m.square() * u * &rho.int(96)|m.square() * u * &rho.int(48)
src/exact/coefficient.rs|closed-form I stick angle|.atan2(&(gap * &span));|.atan2(&(-(gap * &span)));
src/exact/polynomial_w.rs|exact EB sign flip|term(normal_work.scaled(&minus_one), &normal)|term(normal_work.clone(), &normal)
src/exact/polynomial_w.rs|exact slip loads factor 2|let two_f = g.friction.clone() * &zero.int(2);|let two_f = g.friction.clone() * &zero.int(4);
src/exact/polynomial_w.rs|exact EB angle from E|TrigPolynomial::linear(zero.clone(), -b_sin.clone(), b_cos.clone())|TrigPolynomial::linear(zero.clone(), -e_sin.clone(), e_cos.clone())
src/exact/polynomial_w.rs|exact CH P_Y at C not 2C|g.normal_amplitude.clone() * &double_c_cos,|g.normal_amplitude.clone() * c_cos,
src/exact/trig.rs|trig product sign|product.cos[sum] += cos_cos.clone() - &sin_sin;|product.cos[sum] += cos_cos.clone() + &sin_sin;
src/exact/trig.rs|trig integral factor|.sin() * &two / &kk;|.sin() / &kk;
src/exact/series.rs|series factorial|factorial *= &zero.int(n as i64);|factorial *= &zero.int(n as i64 + 1);
src/compliance/families.rs|power-law derivative order|* &falling_factorial(&self.exponent, order)|* &falling_factorial(&self.exponent, order + 1)
LIST
)

# Runs the gate in the copy; prints the failing claims (numbers) and returns verify's exit code.
run_gate() {
    local code=0
    (cd "$work" && "$binary" verify --quick --json >"$work/report.json" 2>/dev/null) || code=$?
    python3 - "$work/report.json" <<'PY' || true
import json, sys
try:
    report = json.load(open(sys.argv[1]))
    failed = [c["claim"].split(" ")[0] + ("" if c["precision_bits"] == 53 else "(" + str(c["precision_bits"]) + ")")
              for c in report["claims"] if not c["passed"]]
    print(",".join(failed) if failed else "-")
except Exception:
    print("(no report)")
PY
    return "$code"
}

build() {
    (cd "$work" && cargo build --release --quiet 2>"$work/build.log")
}

if ! build; then
    cat "$work/build.log" >&2
    echo "the unmutated tree does not build" >&2
    exit 2
fi
if ! baseline=$(run_gate); then
    echo "the unmutated gate fails (claims $baseline): nothing to compare against" >&2
    exit 2
fi

missed=0
printf '%-32s %-8s %s\n' "mutation" "result" "claims that failed"
while IFS='|' read -r file name original replacement kind; do
    if [ -n "${MUTANTS_FILTER:-}" ] && ! [[ "$name" =~ $MUTANTS_FILTER ]]; then
        continue
    fi
    if [ "$kind" = certified ] && [ "${MUTANTS_CERTIFIED:-1}" = 0 ]; then
        continue
    fi
    cp "$root/$file" "$work/$file"
    python3 - "$work/$file" "$original" "$replacement" <<'PY'
import sys
path, original, replacement = sys.argv[1:]
text = open(path).read()
if text.count(original) != 1:
    sys.exit(f"{path}: mutation text found {text.count(original)} times: {original}")
open(path, "w").write(text.replace(original, replacement))
PY
    if [ "$kind" != certified ]; then
        if ! build; then
            cat "$work/build.log" >&2
            echo "mutation '$name' does not build" >&2
            exit 2
        fi
        code=0
        failed=$(run_gate) || code=$?
        if [ "$code" -eq 0 ]; then
            printf '%-32s %-8s %s\n' "$name" "MISSED" "(the gate passed)"
            missed=$((missed + 1))
        else
            printf '%-32s %-8s %s\n' "$name" "caught" "$failed"
        fi
    fi
    if [ "$file" = src/dissipation/segments.rs ] && [ "${MUTANTS_CERTIFIED:-1}" != 0 ]; then
        if (cd "$work" && cargo test --release --quiet --test certified segment_enclosures_hold_the_exact_polynomial_w \
            >"$work/certified.log" 2>&1); then
            printf '%-32s %-8s %s\n' "$name" "MISSED" "(the certified enclosures held the exact W)"
            missed=$((missed + 1))
        elif ! grep -q "segment_enclosures_hold_the_exact_polynomial_w" "$work/certified.log"; then
            cat "$work/certified.log" >&2
            echo "mutation '$name': the certified test does not build or run" >&2
            exit 2
        else
            printf '%-32s %-8s %s\n' "$name" "caught" "certified enclosure excludes the exact W"
        fi
    fi
    cp "$root/$file" "$work/$file"
done <<<"$mutations"
if [ "$missed" -gt 0 ]; then
    echo "$missed mutation(s) missed"
    exit 1
fi
echo "all mutations caught"
