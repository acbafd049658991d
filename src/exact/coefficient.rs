//! The small-amplitude coefficient I(ρ, φ) in closed form
//! (proofs/small-amplitude-coefficient.md):
//!
//! ```text
//! I = −(S² − 4)·Z / (96 σ₋² σ₊) − ρ sin φ (σ₊ − σ₋)(π − δ)/4,
//! Z = (σ₊² − 4)² − 11 σ₋σ₊(σ₊² − 4) + σ₋²(27σ₊² − 4) − σ₋³σ₊,
//! ```
//!
//! with σ± = |ρe^{iφ} ± 1| the amplitudes of (Q ± fP)/(fP1), S = σ₊ + σ₋ and
//! δ = atan2(2ρ sin φ, ρ² − 1) the stick angle. Each difference that could cancel is
//! written in a form that does not, and the formula is evaluated homogeneously in
//! (ρ, 1)/max(1, ρ) so that no intermediate overflows before I itself does (I ≈ −⅔ρ³).

use crate::cycle::PhaseTrig;
use crate::real::Real;

/// I(ρ, φ), the coefficient of the cubic law W ≈ λ f² P1³ v''(P0) I, for ρ > 0 and
/// any φ (period π; a phase in [−π/2, 0) is the offset below π, as [`PhaseTrig::reduced`]
/// reads it). At ρ = 1, φ ≡ 0 it returns the limit 0.
///
/// ```
/// use microslip::exact::closed_form_coefficient;
///
/// // Claim 2 of the paper: I < 0 for every ρ > 0 and 0 < φ < π; I(ρ, 0) = 0 for ρ ≤ 1.
/// assert!(closed_form_coefficient(&0.5, &1.0) < 0.0);
/// assert_eq!(closed_form_coefficient(&0.5, &0.0), 0.0);
/// // Far beyond gross slip of the load line (ρ → ∞), I ≈ −⅔ρ³.
/// let rho: f64 = 1e4;
/// assert!((closed_form_coefficient(&rho, &1.0) / (-2.0 / 3.0 * rho.powi(3)) - 1.0).abs() < 1e-3);
/// ```
pub fn closed_form_coefficient<R: Real>(rho: &R, phase: &R) -> R {
    let one = rho.int(1);
    // (r, e) = (ρ, 1)/k with k = max(1, ρ); I = k³ J(r, e), J homogeneous of degree 3.
    let (scale, r, e) = if *rho > one {
        (rho.clone(), one.clone(), one.clone() / rho)
    } else {
        (one.clone(), rho.clone(), one.clone())
    };
    let PhaseTrig {
        sin,
        cos,
        half_sin_squared: half_sin_sq,
        half_cos_squared,
    } = PhaseTrig::reduced(phase);
    let two = rho.int(2);
    // r cos φ + e, near φ = π as (e − r) + 2r cos²(φ/2).
    let plus_line = if cos >= rho.int(0) {
        r.clone() * &cos + &e
    } else {
        (e.clone() - &r) + &(r.clone() * &half_cos_squared * &two)
    };
    let sigma_plus = plus_line.hypot(&(r.clone() * &sin));
    let sigma_minus = ((r.clone() - &e) - &(r.clone() * &half_sin_sq * &two)).hypot(&(r.clone() * &sin));
    let zero = rho.int(0);
    if sigma_minus == zero {
        return zero;
    }
    let (u, m) = (&sigma_plus, &sigma_minus);
    let product = u.clone() * m;
    let (gap, span) = (e.clone() - &r, e.clone() + &r);
    // S² − 4e² = 2(σ₊σ₋ − (e² − r²)), and σ₊²σ₋² = (e² − r²)² + 4r²e² sin²φ.
    let sum_excess = if r < e {
        (r.clone() * &e * &sin).square() * &rho.int(8) / &(product.clone() + &(gap.clone() * &span))
    } else {
        (product.clone() - &(gap.clone() * &span)) * &two
    };
    // σ₊² − 4e² = (r − e)(r + 3e) − 4re sin²(φ/2).
    let plus_excess =
        -(gap.clone() * &(r.clone() + &(e.clone() * &rho.int(3)))) - &(r.clone() * &e * &half_sin_sq * &rho.int(4));
    let z = plus_excess.square() - &(product.clone() * &plus_excess * &rho.int(11))
        + &(m.square() * &(u.square() * &rho.int(27) - &(e.square() * &rho.int(4))))
        - &(m.square() * &product);
    let difference = r.clone() * &e * &cos * &rho.int(4) / &(u.clone() + m);
    let slip_angle = (r.clone() * &e * &sin * &two).atan2(&(gap * &span));
    let stick_part = sum_excess * &z / &(m.square() * u * &rho.int(96));
    let slip_part = r * &e * &sin * &difference * &slip_angle / &rho.int(4);
    let j = -stick_part - &slip_part;
    j * &scale.square() * &scale
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_the_quadrature_value_and_the_limits() {
        // 35 verified digits by quadrature (microslip small-amplitude --digits 35 before the switch).
        let value = closed_form_coefficient(&2.0, &(std::f64::consts::PI / 2.0));
        assert!((value / -8.586501033599192 - 1.0).abs() < 1e-14, "{value}");
        // ρ → ∞: −⅔ρ³ + (⅔ … )ρ; φ → 0 with ρ < 1: −(8/3)ρ²φ²/(1 − ρ).
        let big = closed_form_coefficient(&1e6, &0.7);
        assert!((big / (-2.0 / 3.0 * 1e18) - 1.0).abs() < 1e-10, "{big}");
        let thin = closed_form_coefficient(&0.5, &1e-9);
        assert!((thin / (-4.0 / 3.0 * 1e-18) - 1.0).abs() < 1e-8, "{thin}");
        assert_eq!(closed_form_coefficient(&1.0, &0.0), 0.0);
    }
}
