//! The built-in compliance families.

use super::derivative_bounds::{at_the_ends, polynomial_bound, positive_range};
use super::{falling_factorial, regular_at_ends, ApproachChange, Compliance, SlopeChange};
use crate::real::Real;

/// v'(P) = C·P^β (β < 0 for a stiffening contact). Eq. (20) of the paper with the
/// misprint corrected (errata item 1): the power law is on v', not on v.
///
/// ```
/// use microslip::compliance::{Compliance, PowerLaw};
///
/// // v' = 2/√P: v'(4) = 1 and v''(4) = 2·(−½)·4^(−3/2) = −1/8.
/// let v = PowerLaw { coefficient: 2.0, exponent: -0.5 };
/// assert!((v.slope(&4.0) - 1.0).abs() < 1e-15);
/// assert!((v.curvature(&4.0) + 0.125).abs() < 1e-15);
/// ```
#[derive(Clone, Debug)]
pub struct PowerLaw<R> {
    /// The coefficient C.
    pub coefficient: R,
    /// The exponent β.
    pub exponent: R,
}

/// The largest numerator |k| of an exponent β = k/q (q ≤ 3) for which a power law's slope
/// change is formed algebraically (beyond it the products cost more than the two
/// transcendental functions).
const RATIONAL_EXPONENTS: u32 = 8;

impl<R: Real> PowerLaw<R> {
    /// x ↦ C·P0^β·[(1 + x/P0)^β − 1], formed without cancellation, with C·P0^β and
    /// 1/P0 computed once.
    ///
    /// A small rational β = k/q (q ≤ 3, |k| ≤ [`RATIONAL_EXPONENTS`]: Persson's −1, Hertz's
    /// −1/3, square roots) takes an algebraic form instead, with r = (1 + u)^(1/q):
    /// r − 1 = u/(1 + r + … + r^(q−1)), r^m − 1 = (r − 1)(1 + r + … + r^(m−1)) and
    /// r^(−m) − 1 = −(r^m − 1)/r^m, free of cancellation as well (every term is positive
    /// but the factor u) and with one square or cube root in place of ln1p and expm1.
    fn into_slope_change<'a>(self, reference: &R) -> SlopeChange<'a, R> {
        let (slope, rational) = (self.slope(reference), self.small_rational_exponent());
        power_change(slope, self.exponent, rational, reference)
    }

    /// x ↦ v(P0 + x) − v(P0) = v(P0)·[(1 + x/P0)^(β+1) − 1], the slope change's form with
    /// the exponent β + 1 (a small rational k/q giving (k + q)/q, so Hertz's v = K·P^(2/3)
    /// costs one cube root), free of cancellation; `None` for β = −1, whose C·ln1p(x/P0)
    /// costs more than the logarithms a caller differences and the v' it integrates.
    fn into_approach_change<'a>(self, reference: &R) -> Option<ApproachChange<'a, R>> {
        let exponent = self.exponent.clone() + &reference.int(1);
        if exponent == reference.int(0) {
            return None;
        }
        let rational = self
            .small_rational_exponent()
            .map(|(numerator, denominator)| (numerator + denominator as i32, denominator));
        Some(power_change(self.approach(reference), exponent, rational, reference))
    }

    /// β as k/q with q ≤ 3 and |k| ≤ [`RATIONAL_EXPONENTS`], when it is one (at the
    /// working precision: Hertz's −1/3 rounded times 3 is −1).
    fn small_rational_exponent(&self) -> Option<(i32, u32)> {
        let limit = self.exponent.int(RATIONAL_EXPONENTS as i64);
        (1..=3u32).find_map(|denominator| {
            let scaled = self.exponent.clone() * &self.exponent.int(i64::from(denominator));
            let rational = scaled.floor() == scaled && scaled.abs() <= limit;
            rational.then(|| (scaled.to_f64_lossy() as i32, denominator))
        })
    }
}

/// x ↦ A·[(1 + x/P0)^β − 1] with A the value at P0 of a power law of exponent β (its
/// v' for the slope change, its v for the approach change), algebraic where β = k/q is a
/// small rational (see [`PowerLaw::into_slope_change`]).
fn power_change<'a, R: Real>(
    at_reference: R,
    exponent: R,
    rational: Option<(i32, u32)>,
    reference: &R,
) -> SlopeChange<'a, R> {
    let inverse = reference.int(1) / reference;
    match rational {
        Some((0, _)) => Box::new(|offset: &R| offset.int(0)),
        Some((numerator, 1)) => rational_slope_change::<R, 1>(numerator, at_reference, reference.clone(), inverse),
        Some((numerator, 2)) => rational_slope_change::<R, 2>(numerator, at_reference, reference.clone(), inverse),
        Some((numerator, _)) => rational_slope_change::<R, 3>(numerator, at_reference, reference.clone(), inverse),
        None => Box::new(move |offset: &R| {
            let relative = (offset.clone() * &inverse).ln_1p() * &exponent;
            at_reference.clone() * &relative.exp_m1()
        }),
    }
}

/// x ↦ C·P0^β·[(1 + x/P0)^β − 1] for β = k/q, k ≠ 0, through r = (1 + x/P0)^(1/q) (see
/// [`PowerLaw::into_slope_change`]); the root's degree Q is a constant so that its sums
/// unroll, since this runs at every integrand evaluation.
fn rational_slope_change<'a, R: Real, const Q: u32>(
    numerator: i32,
    slope: R,
    reference: R,
    inverse: R,
) -> SlopeChange<'a, R> {
    Box::new(move |offset: &R| {
        let one = offset.int(1);
        // 1 + u as (P0 + x)/P0: one rounding, also where u is near −1.
        let base = (reference.clone() + offset) * &inverse;
        let root = match Q {
            1 => base,
            2 => base.sqrt(),
            _ => base.cbrt(),
        };
        let (mut root_sum, mut root_power) = (one.clone(), one.clone());
        for _ in 1..Q {
            root_power *= &root;
            root_sum += &root_power;
        }
        let ratio = offset.clone() * &inverse;
        let root_minus_one = if Q == 1 { ratio } else { ratio / &root_sum };
        let (mut sum, mut power) = (one.clone(), root.clone());
        for _ in 1..numerator.unsigned_abs() {
            sum = sum * &root + &one;
            power *= &root;
        }
        let growth = root_minus_one * &sum;
        if numerator > 0 {
            slope.clone() * &growth
        } else {
            -(slope.clone() * &growth / &power)
        }
    })
}

impl<R: Real> Compliance<R> for PowerLaw<R> {
    fn approach(&self, load: &R) -> R {
        let exponent_plus_one = self.exponent.clone() + load.int(1);
        if exponent_plus_one == load.int(0) {
            self.coefficient.clone() * &load.ln()
        } else {
            self.coefficient.clone() * &load.powr(&exponent_plus_one) / exponent_plus_one
        }
    }
    fn slope(&self, load: &R) -> R {
        self.coefficient.clone() * &load.powr(&self.exponent)
    }
    fn curvature(&self, load: &R) -> R {
        self.coefficient.clone() * &self.exponent * &load.powr(&(self.exponent.clone() - load.int(1)))
    }
    fn slope_change(&self, reference: &R, offset: &R) -> R {
        self.slope_change_about(reference)(offset)
    }
    fn slope_change_about<'a>(&'a self, reference: &R) -> SlopeChange<'a, R> {
        self.clone().into_slope_change(reference)
    }
    fn approach_change_about<'a>(&'a self, reference: &R) -> Option<ApproachChange<'a, R>> {
        self.clone().into_approach_change(reference)
    }
    fn slope_at_scaled_square(&self, scale: &R, root: &R) -> R {
        // C·s^β·r^(2β): r's enclosure, not r²'s, keeps away from 0.
        let doubled = self.exponent.clone().times_power_of_two(1);
        self.coefficient.clone() * &scale.powr(&self.exponent) * &root.powr(&doubled)
    }
    fn describe(&self) -> String {
        format!(
            "power law v' = {}·P^{}",
            self.coefficient.to_scientific(6),
            self.exponent.to_scientific(6)
        )
    }
    fn admissible_by_form(&self, low: &R, high: &R) -> bool {
        // v' = C·P^β > 0 for C > 0, and v'' = C·β·P^(β − 1) ≤ 0 for β ≤ 0.
        let zero = low.int(0);
        self.coefficient > zero && self.exponent <= zero && regular_at_ends(self, low, high)
    }
    fn slope_derivative(&self, order: usize, load: &R) -> Option<R> {
        // v'⁽ᵏ⁾ = C·β(β − 1)…(β − k + 1)·P^(β − k).
        Some(
            self.coefficient.clone()
                * &falling_factorial(&self.exponent, order)
                * &load.powr(&(self.exponent.clone() - &load.int(order as i64))),
        )
    }
    fn derivative_range(&self, order: usize, low: &R, high: &R) -> Option<(R, R)> {
        // C·β(β − 1)…·P^(β − k + 1): one power of P, monotone on P > 0.
        (order >= 2 && positive_range(low, high))
            .then(|| at_the_ends(self, order, low, high))
            .flatten()
    }
}

/// Persson's rough-surface compliance v'(P) = γσ/P (Akarapu et al. 2011; paper Section 5.2),
/// with σ the RMS roughness and γ a dimensionless constant of order one.
///
/// ```
/// use microslip::compliance::{Compliance, Persson, PowerLaw};
///
/// // v' = γσ/P, the power law γσ·P⁻¹: at P = 3 with γσ = 3, v' = 1.
/// let v = Persson { gamma: 1.5, sigma: 2.0 };
/// assert!((v.slope(&3.0) - 1.0).abs() < 1e-15);
/// let same = PowerLaw { coefficient: 3.0, exponent: -1.0 };
/// assert!((v.curvature(&3.0) - same.curvature(&3.0)).abs() < 1e-15);
/// ```
#[derive(Clone, Debug)]
pub struct Persson<R> {
    /// γ, dimensionless.
    pub gamma: R,
    /// σ, the RMS roughness height.
    pub sigma: R,
}

impl<R: Real> Persson<R> {
    fn as_power_law(&self) -> PowerLaw<R> {
        PowerLaw {
            coefficient: self.gamma.clone() * &self.sigma,
            exponent: self.gamma.int(-1),
        }
    }
}

impl<R: Real> Compliance<R> for Persson<R> {
    fn approach(&self, load: &R) -> R {
        self.as_power_law().approach(load)
    }
    fn slope(&self, load: &R) -> R {
        self.gamma.clone() * &self.sigma / load
    }
    fn curvature(&self, load: &R) -> R {
        -(self.gamma.clone() * &self.sigma / &load.square())
    }
    fn slope_change(&self, reference: &R, offset: &R) -> R {
        // γσ/(P0 + x) − γσ/P0 = −v'(P0)·x/(P0 + x): exact in form, one division, and no
        // product of two loads (which would overflow f64 for loads above 1e154, and
        // underflow below 1e-154).
        -(offset.clone() / &(offset.clone() + reference) * &self.slope(reference))
    }
    fn slope_change_about<'a>(&'a self, reference: &R) -> SlopeChange<'a, R> {
        // `slope_change` with v'(P0) formed once: the same operations, the same values.
        let (reference, slope) = (reference.clone(), self.slope(reference));
        Box::new(move |offset: &R| -(offset.clone() / &(offset.clone() + &reference) * &slope))
    }
    fn slope_at_scaled_square(&self, scale: &R, root: &R) -> R {
        // γσ/(s·r²) as two divisions by r: r's enclosure, not r²'s, keeps away from 0.
        self.gamma.clone() * &self.sigma / scale / root / root
    }
    fn describe(&self) -> String {
        format!(
            "Persson v' = γσ/P with γ = {}, σ = {}",
            self.gamma.to_scientific(6),
            self.sigma.to_scientific(6)
        )
    }
    fn admissible_by_form(&self, low: &R, high: &R) -> bool {
        // v' = γσ/P > 0 and v'' = −γσ/P² < 0 for γσ > 0.
        self.gamma.clone() * &self.sigma > low.int(0) && regular_at_ends(self, low, high)
    }
    fn slope_derivative(&self, order: usize, load: &R) -> Option<R> {
        Some(logarithmic_derivative(
            &(self.gamma.clone() * &self.sigma),
            load,
            order + 1,
        ))
    }
    fn derivative_range(&self, order: usize, low: &R, high: &R) -> Option<(R, R)> {
        self.as_power_law().derivative_range(order, low, high)
    }
}

/// The n-th derivative (n ≥ 1) of b·ln s with respect to s: b (−1)ⁿ⁻¹ (n − 1)!/sⁿ; with
/// s = P + c that is v⁽ⁿ⁾ for v' = b/(P + c) (Persson's, and the rational family's
/// non-constant part for n ≥ 2).
fn logarithmic_derivative<R: Real>(numerator: &R, shifted_load: &R, n: usize) -> R {
    let factorial = falling_factorial(&shifted_load.int(n as i64 - 1), n - 1);
    let sign = if n % 2 == 0 {
        -shifted_load.int(1)
    } else {
        shifted_load.int(1)
    };
    numerator.clone() * &factorial * &sign / &shifted_load.powi(n as i32)
}

/// A smooth elastic sphere of radius R pressed by load P (Hertz):
/// v(P) = (9P²/(16·R·E*²))^(1/3), so v' = 1/(2E*·a(P)) with a the contact radius.
///
/// ```
/// use microslip::compliance::{Compliance, Hertz};
///
/// // A 10 mm steel sphere: v'(P) = 1/(2E*·a(P)) with a(P) the contact radius.
/// let sphere = Hertz { radius: 0.01, contact_modulus: 1.15e11 };
/// let load = 10.0;
/// let expected = 1.0 / (2.0 * 1.15e11 * sphere.contact_radius(&load));
/// assert!((sphere.slope(&load) / expected - 1.0).abs() < 1e-14);
/// ```
#[derive(Clone, Debug)]
pub struct Hertz<R> {
    /// Sphere radius R (relative radius for two spheres).
    pub radius: R,
    /// Contact modulus E*.
    pub contact_modulus: R,
}

impl<R: Real> Hertz<R> {
    /// The contact radius a(P) = (3PR/(4E*))^(1/3).
    pub fn contact_radius(&self, load: &R) -> R {
        // A product of cube roots: the product P·R of the plain formula leaves f64's range first.
        load.ratio(3, 4).cbrt() * &load.cbrt() * &self.radius.cbrt() / &self.contact_modulus.cbrt()
    }

    /// v'(P) = (2/3)·K·P^(−1/3) with K = (9/(16 R E*²))^(1/3): a power law with β = −1/3.
    pub fn as_power_law(&self) -> PowerLaw<R> {
        let r = &self.radius;
        // (9/16)^(1/3) / (R^(1/3)·E*^(2/3)): cube roots first, so that R·E*² cannot overflow.
        let k = r.ratio(9, 16).cbrt() / (r.cbrt() * &self.contact_modulus.cbrt().square());
        PowerLaw {
            coefficient: k * &r.ratio(2, 3),
            exponent: r.ratio(-1, 3),
        }
    }
}

impl<R: Real> Compliance<R> for Hertz<R> {
    fn approach(&self, load: &R) -> R {
        self.as_power_law().approach(load)
    }
    fn slope(&self, load: &R) -> R {
        self.as_power_law().slope(load)
    }
    fn curvature(&self, load: &R) -> R {
        self.as_power_law().curvature(load)
    }
    fn slope_change(&self, reference: &R, offset: &R) -> R {
        self.as_power_law().slope_change(reference, offset)
    }
    fn slope_change_about<'a>(&'a self, reference: &R) -> SlopeChange<'a, R> {
        self.as_power_law().into_slope_change(reference)
    }
    fn approach_change_about<'a>(&'a self, reference: &R) -> Option<ApproachChange<'a, R>> {
        self.as_power_law().into_approach_change(reference)
    }
    fn slope_at_scaled_square(&self, scale: &R, root: &R) -> R {
        self.as_power_law().slope_at_scaled_square(scale, root)
    }
    fn describe(&self) -> String {
        format!(
            "Hertz sphere R = {}, E* = {}",
            self.radius.to_scientific(6),
            self.contact_modulus.to_scientific(6)
        )
    }
    fn admissible_by_form(&self, low: &R, high: &R) -> bool {
        self.as_power_law().admissible_by_form(low, high)
    }
    fn slope_derivative(&self, order: usize, load: &R) -> Option<R> {
        self.as_power_law().slope_derivative(order, load)
    }
    fn derivative_range(&self, order: usize, low: &R, high: &R) -> Option<(R, R)> {
        self.as_power_law().derivative_range(order, low, high)
    }
}

/// v'(P) = Σₖ cₖ (P − P_ref)^k, a polynomial in the offset from a reference load.
///
/// ```
/// use microslip::compliance::{Compliance, Polynomial};
///
/// // v' = 2 − ½(P − 1): v'(3) = 1, v'' = −½.
/// let v = Polynomial { reference: 1.0, coefficients: vec![2.0, -0.5] };
/// assert_eq!(v.slope(&3.0), 1.0);
/// assert_eq!(v.curvature(&3.0), -0.5);
/// ```
#[derive(Clone, Debug)]
pub struct Polynomial<R> {
    /// The reference load P_ref.
    pub reference: R,
    /// c₀, c₁, … (at least one).
    pub coefficients: Vec<R>,
}

impl<R: Real> Polynomial<R> {
    fn horner(coefficients: &[R], x: &R) -> R {
        coefficients.iter().rev().fold(x.int(0), |acc, c| acc * x + c)
    }
}

impl<R: Real> Compliance<R> for Polynomial<R> {
    fn approach(&self, load: &R) -> R {
        let x = load.clone() - &self.reference;
        let integrated: Vec<R> = std::iter::once(x.int(0))
            .chain(
                self.coefficients
                    .iter()
                    .enumerate()
                    .map(|(k, c)| c.clone() / x.int(k as i64 + 1)),
            )
            .collect();
        Self::horner(&integrated, &x)
    }
    fn slope(&self, load: &R) -> R {
        Self::horner(&self.coefficients, &(load.clone() - &self.reference))
    }
    fn curvature(&self, load: &R) -> R {
        let x = load.clone() - &self.reference;
        let derived: Vec<R> = self
            .coefficients
            .iter()
            .enumerate()
            .skip(1)
            .map(|(k, c)| c.clone() * &x.int(k as i64))
            .collect();
        Self::horner(&derived, &x)
    }
    fn slope_change(&self, reference: &R, offset: &R) -> R {
        // (x + d)^k − x^k = d · Σ_{j<k} (x + d)^j x^(k−1−j): no cancellation for small d.
        let x = reference.clone() - &self.reference;
        let shifted = x.clone() + offset;
        let mut total = x.int(0);
        for (k, c) in self.coefficients.iter().enumerate().skip(1) {
            let mut bracket = x.int(0);
            for j in 0..k {
                bracket += shifted.powi(j as i32) * &x.powi((k - 1 - j) as i32);
            }
            total += bracket * c;
        }
        total * offset
    }
    fn describe(&self) -> String {
        let terms: Vec<String> = self.coefficients.iter().map(|c| c.to_scientific(6)).collect();
        format!(
            "polynomial v' = Σ cₖ (P − {})^k, c = [{}]",
            self.reference.to_scientific(6),
            terms.join(", ")
        )
    }
    fn slope_derivative(&self, order: usize, load: &R) -> Option<R> {
        // v'⁽ʲ⁾ = Σ_{k ≥ j} cₖ k!/(k − j)! (P − P_ref)^(k − j).
        let x = load.clone() - &self.reference;
        let derived: Vec<R> = self
            .coefficients
            .iter()
            .enumerate()
            .skip(order)
            .map(|(k, c)| c.clone() * &falling_factorial(&x.int(k as i64), order))
            .collect();
        Some(Self::horner(&derived, &x))
    }
    fn derivative_range(&self, order: usize, low: &R, high: &R) -> Option<(R, R)> {
        (order >= 1).then(|| {
            let bound = polynomial_bound(&self.reference, &self.coefficients, order - 1, low, high);
            (-bound.clone(), bound)
        })
    }
}

/// v'(P) = a + b/(P + c): a rational compliance (b > 0 stiffens).
///
/// ```
/// use microslip::compliance::{Compliance, Rational};
///
/// // v' = 1 + 2/(P + 1): v'(1) = 2, v''(1) = −2/(1 + 1)² = −½.
/// let v = Rational { constant: 1.0, numerator: 2.0, offset: 1.0 };
/// assert_eq!(v.slope(&1.0), 2.0);
/// assert_eq!(v.curvature(&1.0), -0.5);
/// ```
#[derive(Clone, Debug)]
pub struct Rational<R> {
    /// The constant part a.
    pub constant: R,
    /// The numerator b.
    pub numerator: R,
    /// The load offset c.
    pub offset: R,
}

impl<R: Real> Compliance<R> for Rational<R> {
    fn approach(&self, load: &R) -> R {
        self.constant.clone() * load + &(self.numerator.clone() * &(load.clone() + &self.offset).ln())
    }
    fn slope(&self, load: &R) -> R {
        self.constant.clone() + &(self.numerator.clone() / &(load.clone() + &self.offset))
    }
    fn curvature(&self, load: &R) -> R {
        -(self.numerator.clone() / &(load.clone() + &self.offset).square())
    }
    fn slope_change(&self, reference: &R, offset: &R) -> R {
        // −b·d/(s(s + d)) with s = P0 + c, formed as −b·(d/s)/(s + d): no product of two loads.
        let shifted = reference.clone() + &self.offset;
        let ratio = offset.clone() / &shifted;
        -(self.numerator.clone() * &ratio / &(shifted + offset))
    }
    fn admissible_by_form(&self, low: &R, high: &R) -> bool {
        // v' = a + b/(P + c) > 0 and v'' = −b/(P + c)² ≤ 0 at every positive load for a, b,
        // c ≥ 0 (not a = b = 0).
        let zero = low.int(0);
        self.numerator >= zero
            && self.constant >= zero
            && self.offset >= zero
            && (self.numerator > zero || self.constant > zero)
            && regular_at_ends(self, low, high)
    }
    fn describe(&self) -> String {
        format!(
            "rational v' = {} + {}/(P + {})",
            self.constant.to_scientific(6),
            self.numerator.to_scientific(6),
            self.offset.to_scientific(6)
        )
    }
    fn slope_derivative(&self, order: usize, load: &R) -> Option<R> {
        Some(match order {
            0 => self.slope(load),
            k => logarithmic_derivative(&self.numerator, &(load.clone() + &self.offset), k + 1),
        })
    }
    fn derivative_range(&self, order: usize, low: &R, high: &R) -> Option<(R, R)> {
        // b·(k − 2)!·(P + c)^(1 − k) up to sign, monotone while P + c > 0.
        let (low_shifted, high_shifted) = (low.clone() + &self.offset, high.clone() + &self.offset);
        (order >= 2 && positive_range(&low_shifted, &high_shifted))
            .then(|| at_the_ends(self, order, low, high))
            .flatten()
    }
}

/// v'(P) = a·e^(−P/c) + d: an exponential-type compliance (a, c > 0 stiffens).
///
/// ```
/// use microslip::compliance::{Compliance, Exponential};
///
/// // v' = e^(−P/2) + ½: v'(0) = 3/2, v''(0) = −½.
/// let v = Exponential { amplitude: 1.0, decay_load: 2.0, constant: 0.5 };
/// assert_eq!(v.slope(&0.0), 1.5);
/// assert_eq!(v.curvature(&0.0), -0.5);
/// ```
#[derive(Clone, Debug)]
pub struct Exponential<R> {
    /// The amplitude a.
    pub amplitude: R,
    /// The decay load c.
    pub decay_load: R,
    /// The constant part d.
    pub constant: R,
}

impl<R: Real> Compliance<R> for Exponential<R> {
    fn approach(&self, load: &R) -> R {
        let decay = (-(load.clone() / &self.decay_load)).exp();
        self.constant.clone() * load - &(self.amplitude.clone() * &self.decay_load * &decay)
    }
    fn slope(&self, load: &R) -> R {
        self.amplitude.clone() * &(-(load.clone() / &self.decay_load)).exp() + &self.constant
    }
    fn curvature(&self, load: &R) -> R {
        -(self.amplitude.clone() / &self.decay_load * &(-(load.clone() / &self.decay_load)).exp())
    }
    fn slope_change(&self, reference: &R, offset: &R) -> R {
        let decay = -(offset.clone() / &self.decay_load);
        if decay > decay.int(1) {
            // The two exponentials differ by more than a factor e: no cancellation, and
            // no e^(−P0/c)·(e^(−x/c) − 1) = 0·∞ where c is tiny against the loads.
            let at = |load: &R| (-(load.clone() / &self.decay_load)).exp();
            return self.amplitude.clone() * &(at(&(reference.clone() + offset)) - &at(reference));
        }
        self.amplitude.clone() * &(-(reference.clone() / &self.decay_load)).exp() * &decay.exp_m1()
    }
    fn slope_change_about<'a>(&'a self, reference: &R) -> SlopeChange<'a, R> {
        // a·e^(−P0/c)·(e^(−x/c) − 1) for every offset: one analytic formula on both sides
        // of x = −c (where `slope_change` switches forms, a switch that a ball around
        // that point cannot decide), free of cancellation. It needs e^(−P0/c) well above
        // the type's smallest full-precision number, so that e^(−x/c) ≤ e^(P0/c) for
        // the positive loads P0 + x cannot overflow (c > 0); otherwise offset by offset.
        let decay_at_reference = (-(reference.clone() / &self.decay_load)).exp();
        let floor = R::smallest_full_precision(reference.precision());
        if self.decay_load > reference.int(0) && decay_at_reference > floor {
            let (scale, decay_load) = (self.amplitude.clone() * &decay_at_reference, self.decay_load.clone());
            return Box::new(move |offset: &R| scale.clone() * &(-(offset.clone() / &decay_load)).exp_m1());
        }
        let reference = reference.clone();
        Box::new(move |offset: &R| self.slope_change(&reference, offset))
    }
    fn decay_load(&self) -> Option<R> {
        (self.decay_load > self.decay_load.int(0)).then(|| self.decay_load.clone())
    }
    fn admissible_by_form(&self, low: &R, _high: &R) -> bool {
        // v' = a·e^(−P/c) + d > 0 and v'' = −(a/c)·e^(−P/c) < 0 at every load for a, c > 0
        // and d ≥ 0, even where e^(−P/c) is below the type's smallest number.
        let zero = low.int(0);
        self.amplitude > zero && self.decay_load > zero && self.constant >= zero
    }
    fn describe(&self) -> String {
        format!(
            "exponential v' = {}·exp(−P/{}) + {}",
            self.amplitude.to_scientific(6),
            self.decay_load.to_scientific(6),
            self.constant.to_scientific(6)
        )
    }
    fn slope_derivative(&self, order: usize, load: &R) -> Option<R> {
        // v'⁽ᵏ⁾ = a (−1/c)ᵏ e^(−P/c) for k ≥ 1.
        Some(match order {
            0 => self.slope(load),
            k => {
                let rate = -(load.int(1) / &self.decay_load);
                self.amplitude.clone() * &rate.powi(k as i32) * &(-(load.clone() / &self.decay_load)).exp()
            }
        })
    }
    fn derivative_range(&self, order: usize, low: &R, high: &R) -> Option<(R, R)> {
        // a·(−1/c)^(k − 1)·e^(−P/c): monotone in P.
        (order >= 2 && *low <= *high)
            .then(|| at_the_ends(self, order, low, high))
            .flatten()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rug::Float;

    /// The algebraic slope change of a rational exponent k/q equals the general one,
    /// C·P0^β·expm1(β·ln1p(x/P0)), evaluated at 300 bits, to a few ulps of f64 (and to
    /// 1e−85 at 330 bits), from near P = 0 to large loads.
    #[test]
    fn rational_exponents_match_the_general_slope_change() {
        let general = |beta: &Float, reference: &Float, offset: &Float| {
            let relative = (offset.clone() / reference).ln_1p() * beta;
            Float::with_val(300, 1.5) * reference.powr(beta) * relative.exp_m1()
        };
        let exponents = [(-8, 1), (-3, 1), (-2, 1), (-1, 1), (0, 1), (1, 1), (2, 1), (5, 1)]
            .into_iter()
            .chain([(-1, 2), (1, 2), (-3, 2), (-1, 3), (2, 3), (-5, 3), (7, 3)]);
        for (k, q) in exponents {
            let beta = Float::with_val(300, k) / q;
            for (reference, offset) in [(1.0, 0.4), (1.0, -0.999), (2.5, -1.0), (0.3, 7.0), (1.0, 1e-9)] {
                let exact = general(&beta, &Float::with_val(300, reference), &Float::with_val(300, offset));
                let law = PowerLaw {
                    coefficient: 1.5,
                    exponent: f64::from(k) / f64::from(q),
                };
                assert_eq!(law.small_rational_exponent(), Some((k, q)));
                let value = law.slope_change(&reference, &offset);
                let error = (Float::with_val(300, value) - &exact).abs();
                let tolerance = exact.clone().abs() * 1e-14;
                assert!(error <= tolerance, "β={k}/{q} x={offset}: {value:e} vs {exact:.17e}");
                let precise = PowerLaw {
                    coefficient: Float::with_val(330, 1.5),
                    exponent: Float::with_val(330, k) / q,
                };
                let value = precise.slope_change(&Float::with_val(330, reference), &Float::with_val(330, offset));
                let error = (value - &exact).abs();
                assert!(
                    error <= exact.clone().abs() * 1e-85,
                    "β={k}/{q} x={offset} at 330 bits: {error:.3e}"
                );
            }
        }
    }

    /// The prepared approach change of a power law equals v(P0 + x) − v(P0) evaluated at
    /// 300 bits, C·P0^(β+1)/(β+1)·expm1((β+1)·ln1p(x/P0)), to a few ulps of f64, from near
    /// P = 0 to large loads and at |x| = 1e−9·P0, where a difference of v would keep 7
    /// digits; β = −1 (Persson's) has none, Hertz's is its power law's.
    #[test]
    fn approach_changes_match_the_difference_of_approaches() {
        let exact_change = |beta: f64, reference: f64, offset: f64| {
            let raised = Float::with_val(300, beta) + 1u32;
            let reference = Float::with_val(300, reference);
            let relative = (Float::with_val(300, offset) / &reference).ln_1p() * &raised;
            Float::with_val(300, 1.5) * reference.powr(&raised) / &raised * relative.exp_m1()
        };
        let exponents = [-3.0, -2.0, -1.5, -0.5, -1.0 / 3.0, -0.3, 0.0, 0.5, 2.0];
        for beta in exponents {
            let law = PowerLaw {
                coefficient: 1.5,
                exponent: beta,
            };
            let change = law.approach_change_about(&2.0).unwrap();
            for offset in [0.8, -1.998, -1.2, 14.0, 2e-9, -2e-9] {
                let exact = exact_change(beta, 2.0, offset);
                let value = change(&offset);
                let error = (Float::with_val(300, value) - &exact).abs();
                assert!(
                    error <= exact.clone().abs() * 1e-14,
                    "β = {beta}, x = {offset}: {value:e} vs {exact:.17e}"
                );
            }
        }
        let persson = Persson {
            gamma: 0.01,
            sigma: 1.0,
        };
        assert!(persson.approach_change_about(&1.0).is_none());
        let hertz = Hertz {
            radius: 1.0,
            contact_modulus: 100.0,
        };
        let law = hertz.as_power_law();
        let (mine, its_law) = (
            hertz.approach_change_about(&1.0).unwrap(),
            law.approach_change_about(&1.0).unwrap(),
        );
        for offset in [-1.0, -0.9, -1e-6, 0.3] {
            assert_eq!(mine(&offset), its_law(&offset));
        }
    }
}
