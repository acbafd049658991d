//! A rainflow cycle at constant P, proven: the certified W of a closed Masing loop, the Q
//! amplitude of a range of u under displacement driving, and the W of a cycle that
//! reaches gross slip.
//!
//! With g(Q) = λf (v(P) − v(P − Q/f)) the initial loading curve (increasing), a cycle of
//! range Δu below gross slip (Δu/2 < g(fP)) is the closed Masing loop at Q amplitude
//! g⁻¹(Δu/2), and one beyond it is the loop at fP plus 2fP(Δu − 2g(fP)) of sliding
//! (proofs/periodic-loading.md, "Proven W under displacement driving").

use crate::compliance::Compliance;
use crate::digits::enclosure::Enclosing;
use crate::doubts::if_decided;
use crate::real::Real;

use super::not_proven::NotProven;
use crate::cycle::LoadCycle;
use crate::digits::enclosure::enclose_dissipation;
use crate::path::{Contact, MasingLaw};

/// A rainflow cycle at constant P by what its W is made of.
#[derive(Clone, Debug)]
pub(super) enum ConstantLoadCycle<R> {
    /// A closed Masing loop of this Q amplitude, below fP.
    Loop(R),
    /// Gross slip: the loop at Q amplitude fP, and this displacement Δu − 2g(fP) slid
    /// at Q = ±fP in each direction.
    Sliding(R),
}

/// The cycles of the displacement `ranges` of u at normal load P (decided positive): a
/// Q amplitude g⁻¹(Δu/2) is the hull of a bracket whose ends' g are decided below and
/// above Δu/2 (`MasingLaw::initial_load`, which solves on enclosures); which side of
/// g(fP) each half range lies on is compared, and must be decided under the caller's watch.
pub(super) fn displacement_cycles<R: Real>(
    load: &R,
    contact: &Contact<R>,
    compliance: &dyn Compliance<R>,
    ranges: &[R],
) -> Result<Vec<ConstantLoadCycle<R>>, NotProven> {
    if *load <= load.int(0) {
        return Err(NotProven::NotCovered("its normal load is not positive"));
    }
    let law = MasingLaw::new(load, contact, compliance);
    // g'(Q) = λ v'(P − Q/f).
    let slope = |amplitude: &R| {
        contact.compliance_ratio.clone() * &compliance.slope(&(load.clone() - &(amplitude.clone() / &contact.friction)))
    };
    let cycles = ranges.iter().map(|range| {
        let two = range.int(2);
        let half = range.clone() / &two;
        match law.gross_slip_displacement() {
            Some(gross) if half >= *gross => ConstantLoadCycle::Sliding(range.clone() - &(gross.clone() * &two)),
            _ => ConstantLoadCycle::Loop(narrowed(&law, &slope, &half, law.initial_load(&half))),
        }
    });
    Ok(cycles.collect())
}

/// The certified W of the closed Masing loop of Q amplitude `amplitude` (< fP) at
/// constant normal load P: the constant-normal-load cycle P1 = 0, Q0 = 0.
pub(super) fn constant_load_w<R: Enclosing>(
    load: &R,
    amplitude: &R,
    contact: &Contact<R>,
    compliance: &dyn Compliance<R>,
    goal_bits: u32,
) -> Result<R, NotProven> {
    let zero = load.int(0);
    let cycle = LoadCycle {
        mean_normal_load: load.clone(),
        normal_amplitude: zero.clone(),
        mean_tangential_load: zero.clone(),
        tangential_amplitude: amplitude.clone(),
        phase: zero,
        friction: contact.friction.clone(),
        compliance_ratio: contact.compliance_ratio.clone(),
    };
    let enclosure = enclose_dissipation(&cycle, compliance, goal_bits).map_err(NotProven::Refused)?;
    Ok(enclosure.total)
}

/// The most fourfold widenings of the bracket [`narrowed`] tries, from 4 ulps.
const NARROWING_STEPS: i32 = 8;

/// g⁻¹(`half`), enclosed in `hull` by the solver, in a narrower bracket where one is
/// decided: two Newton steps on points from the hull's midpoint give m, and
/// [m − δ, m + δ] brackets the root where g(m − δ) < `half` < g(m + δ) is decided (g
/// increasing), δ from 4 ulps of m up by fourfold steps; `hull` where none is. The
/// solver's hull stops tens of ulps wide, and W's enclosure over the amplitude is about
/// ten times as wide relative to W as the amplitude is.
fn narrowed<R: Real>(law: &MasingLaw<'_, R>, slope: &dyn Fn(&R) -> R, half: &R, hull: R) -> R {
    let target = half.midpoint_value();
    let mut middle = hull.midpoint_value();
    for _ in 0..2 {
        let step = (law.initial_displacement(&middle) - &target) / &slope(&middle);
        middle = (middle - &step).midpoint_value();
    }
    let ulp = (middle.abs() * &middle.epsilon_like()).midpoint_value();
    (1..=NARROWING_STEPS)
        .find_map(|step| {
            let width = ulp.clone().times_power_of_two(2 * step);
            let (low, high) = (
                (middle.clone() - &width).midpoint_value(),
                (middle.clone() + &width).midpoint_value(),
            );
            let bracketed =
                if_decided(|| law.initial_displacement(&low) < *half && *half < law.initial_displacement(&high));
            bracketed.unwrap_or(false).then(|| low.union(&high))
        })
        .unwrap_or(hull)
}

/// The most bits below P of the load s = P·2⁻ᵏ at which the loop at fP is cut
/// ([`loop_at_friction_limit`]), under the working precision: P − s must stay apart from
/// P for the loop at f(P − s) to be decided short of gross slip.
const CUT_BELOW_PRECISION: u32 = 8;

/// The bits by which the width of the loop's tail is kept below P(v(P) − v(0)) beyond
/// the goal: W's loop integral is a fraction of that scale (a fifth for Hertz).
const TAIL_GUARD_BITS: u32 = 6;

/// W of the Masing loop at Q amplitude fP (the loop a cycle in gross slip closes), which
/// the constant-normal-load enclosure refuses as gross slip: W(a) at a = f(P − s) just
/// below it, plus 4λf² T(s), what W gains from a to fP,
/// T(s) = ∫₀ˢ ((P − y) v'(y) + v(y) − v(P)) dy = (P − s) v(s) − P v(0) − s v(P) + 2∫₀ˢ v.
/// With v increasing and v(0) finite, ∫₀ˢ v lies in [s v(0), s v(s)]: T is enclosed to a
/// width 2s(v(s) − v(0)), and s = P·2⁻ᵏ is the largest that keeps it below W's
/// `goal_bits` (the loop near gross slip is the harder to enclose the smaller s is).
pub(super) fn loop_at_friction_limit<R: Enclosing>(
    load: &R,
    contact: &Contact<R>,
    compliance: &dyn Compliance<R>,
    goal_bits: u32,
) -> Result<R, NotProven> {
    let bits = load.precision().in_bits();
    let at_zero = compliance.approach(&load.int(0));
    let at_load = compliance.approach(load);
    let scale = load.clone() * &(at_load.clone() - &at_zero);
    if !scale.is_finite() {
        return Err(NotProven::NotCovered(
            "its compliance has no finite approach at zero load",
        ));
    }
    let deepest = bits.saturating_sub(CUT_BELOW_PRECISION).max(1);
    let first = ((goal_bits + TAIL_GUARD_BITS) / 2).min(deepest);
    let mut cut = first;
    let (gap, at_gap) = loop {
        let gap = load.clone().times_power_of_two(-(cut as i32));
        let at_gap = compliance.approach(&gap);
        let width = gap.clone() * &(at_gap.clone() - &at_zero) * &load.int(2);
        let narrow = width.is_below_scaled(&scale, -i64::from(goal_bits + TAIL_GUARD_BITS));
        if narrow || cut >= deepest {
            break (gap, at_gap);
        }
        cut += 1;
    };
    let two = load.int(2);
    let known = (load.clone() - &gap) * &at_gap - &(load.clone() * &at_zero) - &(gap.clone() * &at_load);
    let lower = known.clone() + &(gap.clone() * &at_zero * &two);
    let upper = known + &(gap.clone() * &at_gap * &two);
    let tail = lower.union(&upper);
    let below = constant_load_w(
        load,
        &(contact.friction.clone() * &(load.clone() - &gap)),
        contact,
        compliance,
        goal_bits,
    )?;
    let factor = contact.compliance_ratio.clone() * &contact.friction.square() * &load.int(4);
    Ok(below + &(tail * &factor))
}
