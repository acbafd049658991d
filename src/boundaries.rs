//! The boundaries of the theory, decided exactly from the decimals as written.
//!
//! A cycle is inside the theory when P0 > 0, P1 ≥ 0, Q1 ≥ 0, f > 0, λ ∈ [1, 2], the contact
//! never separates (P0 − P1 > 0) and never slides (|Q| < fP throughout the cycle). Each is
//! decided here on the exact rationals the decimals denote, never on copies rounded to a
//! working precision, so that the f64 default, `--digits` and every command make the same
//! decision, and a refusal quotes a margin that is the exact one.
//!
//! Only gross slip involves π, through cos φ. Over the cycle, max(±Q − fP) = ±Q0 − fP0 + σ±
//! with σ±² = Q1² + f²P1² ± 2 Q1 f P1 cos φ, so the cycle stays inside the friction cone on
//! that side exactly when fP0 ∓ Q0 > 0 and the *margin* (fP0 ∓ Q0)² − σ±² is positive. The
//! margin is a rational plus a rational multiple of cos φ. Where cos φ is rational (Niven's
//! theorem: φ ≡ 0, ±π/3 or ±π/2 modulo π, and no other rational multiple of π) it is decided
//! in rational arithmetic; otherwise cos φ is enclosed at rising precision (MPFR rounds to
//! nearest; the enclosure adds the proven error bounds of the phase's reduction and of the
//! cosine) until the margin's sign is settled, and a cycle that no precision up to
//! [`MAX_BITS`] settles is refused as undecidable.

use rug::{Float, Rational};

use crate::cycle::CycleError;
use crate::phase::ReducedPhase;
use crate::real::{Precision, Real};

/// The most bits the enclosure of cos φ is carried to before a margin is called undecidable.
pub const MAX_BITS: u32 = 1 << 14;

/// The bits the enclosure of cos φ starts with.
const FIRST_BITS: u32 = 64;

/// A cycle's exact quantities: every decimal as the rational it denotes, λ exactly (from ν
/// where ν was given), and the phase reduced exactly modulo π.
pub(crate) struct ExactCycle<'a> {
    /// P0.
    pub mean_normal_load: &'a Rational,
    /// P1.
    pub normal_amplitude: &'a Rational,
    /// Q0.
    pub mean_tangential_load: &'a Rational,
    /// Q1.
    pub tangential_amplitude: &'a Rational,
    /// f.
    pub friction: &'a Rational,
    /// λ.
    pub compliance_ratio: &'a Rational,
    /// λ as written (or ν, where λ comes from it), for a refusal.
    pub compliance_ratio_text: &'a str,
    /// φ.
    pub phase: &'a ReducedPhase,
}

/// λ = (2 − ν)/(2(1 − ν)) exactly, for Poisson's ratio ν ∈ [0, 2/3] (λ ∈ [1, 2]), written `text`.
pub(crate) fn compliance_ratio_of_poisson(nu: &Rational, text: &str) -> Result<Rational, CycleError> {
    if *nu < 0 || *nu > Rational::from((2, 3)) {
        return Err(CycleError::PoissonRatioOutOfRange { nu: text.to_string() });
    }
    let two = Rational::from(2);
    Ok(Rational::from(&two - nu) / (two * Rational::from(1 - nu)))
}

/// Whether the cycle is one the theory covers, decided exactly (see the module
/// documentation); the first boundary crossed otherwise, in the order
/// [`crate::cycle::LoadCycle::validate`] checks them.
pub(crate) fn decide(cycle: &ExactCycle) -> Result<(), CycleError> {
    // A refusal quotes the double nearest each exact value (`-1/5` reads `-2e-1`), not
    // GMP's conversion towards zero.
    let p0 = cycle.mean_normal_load;
    if *p0 <= 0 {
        return Err(CycleError::NonPositiveMeanLoad {
            p0: f64::from_rational(p0, Precision::DOUBLE),
        });
    }
    for (quantity, value) in [("P1", cycle.normal_amplitude), ("Q1", cycle.tangential_amplitude)] {
        if *value < 0 {
            return Err(CycleError::NegativeAmplitude {
                quantity,
                value: f64::from_rational(value, Precision::DOUBLE),
            });
        }
    }
    let margin = Rational::from(p0 - cycle.normal_amplitude);
    if margin <= 0 {
        return Err(CycleError::Separation {
            p0: f64::from_rational(p0, Precision::DOUBLE),
            p1: f64::from_rational(cycle.normal_amplitude, Precision::DOUBLE),
            margin: f64::from_rational(&margin, Precision::DOUBLE),
        });
    }
    if *cycle.friction <= 0 {
        return Err(CycleError::NonPositiveFriction {
            f: f64::from_rational(cycle.friction, Precision::DOUBLE),
        });
    }
    let lambda = cycle.compliance_ratio;
    if *lambda < 1 || *lambda > 2 {
        return Err(CycleError::ComplianceRatioOutOfRange {
            lambda: cycle.compliance_ratio_text.to_string(),
        });
    }
    let sides = [Side::Forward, Side::Reverse].map(|side| Margin::of(side, cycle));
    // cos φ once per precision for both sides, the precision raised while a side is unsettled.
    let mut bits = FIRST_BITS;
    loop {
        let cosine = cosine_of_phase(cycle.phase, bits);
        let settled = sides.each_ref().map(|margin| margin.inside(&cosine));
        if let Some(margin) = sides
            .iter()
            .zip(&settled)
            .find_map(|(m, s)| (*s == Some(false)).then_some(m))
        {
            return Err(margin.gross_slip(&cosine));
        }
        if settled.iter().all(|s| *s == Some(true)) {
            return Ok(());
        }
        if bits >= MAX_BITS {
            return Err(CycleError::Undecidable {
                boundary: "gross slip (|Q| = fP somewhere in the cycle)",
                bits,
            });
        }
        bits *= 4;
    }
}

/// A side of the friction cone: Q = fP (forward) or Q = −fP (reverse).
#[derive(Clone, Copy)]
enum Side {
    Forward,
    Reverse,
}

/// cos φ: exact where it is rational, else an interval containing it.
enum Cosine {
    Exact(Rational),
    Between(Rational, Rational),
}

/// One side's margin, room² − σ², as `fixed + coupling·cos φ` (rationals), with room = fP0 ∓ Q0.
struct Margin {
    side: Side,
    room: Rational,
    fixed: Rational,
    coupling: Rational,
    friction_limit: Rational,
}

impl Margin {
    fn of(side: Side, cycle: &ExactCycle) -> Margin {
        let sign = match side {
            Side::Forward => 1,
            Side::Reverse => -1,
        };
        let friction_limit = Rational::from(cycle.friction * cycle.mean_normal_load);
        // fP0 ∓ Q0: how far the mean load lies inside this side's line.
        let room = &friction_limit - Rational::from(cycle.mean_tangential_load * sign);
        let (q1, fp1) = (
            cycle.tangential_amplitude,
            Rational::from(cycle.friction * cycle.normal_amplitude),
        );
        let fixed =
            Rational::from(room.square_ref()) - Rational::from(q1.square_ref()) - Rational::from(fp1.square_ref());
        let coupling = Rational::from(q1 * &fp1) * (2 * sign);
        Margin {
            side,
            room,
            fixed,
            coupling,
            friction_limit,
        }
    }

    /// Whether the cycle stays inside this side's line: Some(true) or Some(false) where
    /// `cosine` settles it, None where it does not.
    fn inside(&self, cosine: &Cosine) -> Option<bool> {
        let at = |c: &Rational| Rational::from(&self.coupling * c) + &self.fixed;
        let (low, high) = match cosine {
            Cosine::Exact(c) => (at(c), at(c)),
            Cosine::Between(low, high) => {
                let (a, b) = (at(low), at(high));
                if a <= b {
                    (a, b)
                } else {
                    (b, a)
                }
            }
        };
        if self.room <= 0 || high <= 0 {
            Some(false)
        } else if low > 0 {
            Some(true)
        } else {
            None
        }
    }

    /// The refusal for a cycle that reaches this side's line: max(±Q − fP) = σ − room.
    fn gross_slip(&self, cosine: &Cosine) -> CycleError {
        const BITS: u32 = 128;
        let cos = match cosine {
            Cosine::Exact(c) => c.clone(),
            Cosine::Between(low, high) => Rational::from(low + high) / 2,
        };
        // σ² = room² − margin, and σ − room = −margin/(σ + room) without cancellation.
        let (room, friction_limit) = (&self.room, &self.friction_limit);
        let margin = Rational::from(&self.coupling * &cos) + &self.fixed;
        let amplitude_squared = Rational::from(room.square_ref()) - &margin;
        let amplitude = Float::with_val(BITS, &amplitude_squared).max(&Float::new(BITS)).sqrt();
        let excess = if *room > 0 {
            -Float::with_val(BITS, &margin) / (amplitude + Float::with_val(BITS, room))
        } else {
            amplitude - Float::with_val(BITS, room)
        };
        let relative = Float::with_val(BITS, &excess / Float::with_val(BITS, friction_limit));
        let (sign, sign_word) = match self.side {
            Side::Forward => ("+", ""),
            Side::Reverse => ("−", "−"),
        };
        CycleError::GrossSlip {
            sign,
            sign_word,
            excess: excess.to_f64().max(0.0),
            relative: relative.to_f64().max(0.0),
        }
    }
}

/// cos φ for φ = nπ + ψ, ψ = mπ + x: (−1)ⁿ cos ψ, exact where ψ is 0, ±π/3 or ±π/2, and
/// otherwise enclosed from ψ at `bits` bits.
fn cosine_of_phase(phase: &ReducedPhase, bits: u32) -> Cosine {
    let (reverses, multiple, offset) = phase.offset_parts();
    let turn = |c: Rational| if reverses { -c } else { c };
    if *offset == 0 {
        let m = Rational::from(multiple.abs_ref());
        let rational_cosine = if m == 0 {
            Some(Rational::from(1))
        } else if m == Rational::from((1, 3)) {
            Some(Rational::from((1, 2)))
        } else if m == Rational::from((1, 2)) {
            Some(Rational::new())
        } else {
            None
        };
        if let Some(c) = rational_cosine {
            return Cosine::Exact(turn(c));
        }
    }
    // ψ to `bits` bits: a relative error below 2^(1−bits) (`ReducedPhase::offset_float`),
    // taken as 2^(2−bits); its cosine rounded to nearest, an error below 2^(−bits); cos is
    // 1-Lipschitz.
    let psi = phase.offset_float(bits);
    let psi_error = Float::with_val(bits, psi.abs_ref()) >> (bits as i32 - 2);
    let cosine = Float::with_val(bits, psi.cos_ref());
    let error = psi_error.to_rational().unwrap_or_default() + two_to_minus(bits);
    let centre = cosine.to_rational().unwrap_or_default();
    let one = Rational::from(1);
    let low = (Rational::from(&centre - &error)).max(-one.clone());
    let high = (Rational::from(&centre + &error)).min(one);
    if reverses {
        Cosine::Between(-high, -low)
    } else {
        Cosine::Between(low, high)
    }
}

/// 2^(−bits), exactly.
fn two_to_minus(bits: u32) -> Rational {
    Rational::from((rug::Integer::from(1), rug::Integer::from(1) << bits))
}
