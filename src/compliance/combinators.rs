//! Compliances built from others: sums, multiples, a constant added to v', and
//! the load scaling that models scaled roughness.

use super::derivative_bounds::scaled_range;
use super::{merged_breakpoints, regular_at_ends, ApproachChange, Compliance, SlopeChange};
use crate::real::Real;

/// v = Σ vᵢ: compliances in series add.
///
/// ```
/// use microslip::compliance::{Compliance, Persson, PowerLaw, Sum};
///
/// // 1/P + 2/√P at P = 4: ¼ + 1.
/// let v = Sum {
///     terms: vec![
///         Box::new(Persson { gamma: 1.0, sigma: 1.0 }),
///         Box::new(PowerLaw { coefficient: 2.0, exponent: -0.5 }),
///     ],
/// };
/// assert_eq!(v.slope(&4.0), 1.25);
/// ```
#[derive(Debug)]
pub struct Sum<R: Real> {
    /// The terms.
    pub terms: Vec<Box<dyn Compliance<R>>>,
}

impl<R: Real> Sum<R> {
    fn total(&self, load: &R, term: impl Fn(&dyn Compliance<R>) -> R) -> R {
        self.terms.iter().fold(load.int(0), |acc, c| acc + term(c.as_ref()))
    }
}

impl<R: Real> Compliance<R> for Sum<R> {
    fn approach(&self, load: &R) -> R {
        self.total(load, |c| c.approach(load))
    }
    fn slope(&self, load: &R) -> R {
        self.total(load, |c| c.slope(load))
    }
    fn curvature(&self, load: &R) -> R {
        self.total(load, |c| c.curvature(load))
    }
    fn slope_change(&self, reference: &R, offset: &R) -> R {
        self.total(reference, |c| c.slope_change(reference, offset))
    }
    fn slope_change_about<'a>(&'a self, reference: &R) -> SlopeChange<'a, R> {
        let terms: Vec<SlopeChange<'a, R>> = self.terms.iter().map(|c| c.slope_change_about(reference)).collect();
        let zero = reference.int(0);
        Box::new(move |offset: &R| terms.iter().fold(zero.clone(), |acc, term| acc + term(offset)))
    }
    fn approach_change_about<'a>(&'a self, reference: &R) -> Option<ApproachChange<'a, R>> {
        // Where every term has its own form; else none, and the caller's general way serves.
        let terms = self
            .terms
            .iter()
            .map(|c| c.approach_change_about(reference))
            .collect::<Option<Vec<ApproachChange<'a, R>>>>()?;
        let zero = reference.int(0);
        Some(Box::new(move |offset: &R| {
            terms.iter().fold(zero.clone(), |acc, term| acc + term(offset))
        }))
    }
    fn slope_at_scaled_square(&self, scale: &R, root: &R) -> R {
        self.total(scale, |c| c.slope_at_scaled_square(scale, root))
    }
    fn breakpoints(&self, like: &R) -> Vec<R> {
        merged_breakpoints(self.terms.iter().map(|c| c.breakpoints(like)))
    }
    fn decay_load(&self) -> Option<R> {
        // The shortest of the terms' scales.
        self.terms
            .iter()
            .filter_map(|c| c.decay_load())
            .reduce(|shortest, scale| shortest.min_of(&scale))
    }
    fn describe(&self) -> String {
        let parts: Vec<String> = self.terms.iter().map(|c| c.describe()).collect();
        parts.join(" + ")
    }
    fn admissible_by_form(&self, low: &R, high: &R) -> bool {
        // A sum of admissible terms is admissible; the ends' check catches a sum that
        // overflows.
        self.terms.iter().all(|c| c.admissible_by_form(low, high)) && regular_at_ends(self, low, high)
    }
    fn derivative(&self, order: usize, load: &R) -> Option<R> {
        self.terms
            .iter()
            .try_fold(load.int(0), |acc, c| Some(acc + c.derivative(order, load)?))
    }
    fn derivative_range(&self, order: usize, low: &R, high: &R) -> Option<(R, R)> {
        self.terms
            .iter()
            .try_fold((low.int(0), low.int(0)), |(least, greatest), c| {
                let (term_least, term_greatest) = c.derivative_range(order, low, high)?;
                Some((least + &term_least, greatest + &term_greatest))
            })
    }
}

/// a·v: a scalar multiple.
///
/// ```
/// use microslip::compliance::{Compliance, Persson, Scaled};
///
/// let v = Scaled { factor: 3.0, inner: Box::new(Persson { gamma: 1.0, sigma: 1.0 }) };
/// assert_eq!(v.slope(&2.0), 1.5);
/// ```
#[derive(Debug)]
pub struct Scaled<R: Real> {
    /// The multiplier a.
    pub factor: R,
    /// v.
    pub inner: Box<dyn Compliance<R>>,
}

impl<R: Real> Compliance<R> for Scaled<R> {
    fn approach(&self, load: &R) -> R {
        self.factor.clone() * &self.inner.approach(load)
    }
    fn slope(&self, load: &R) -> R {
        self.factor.clone() * &self.inner.slope(load)
    }
    fn curvature(&self, load: &R) -> R {
        self.factor.clone() * &self.inner.curvature(load)
    }
    fn slope_change(&self, reference: &R, offset: &R) -> R {
        self.factor.clone() * &self.inner.slope_change(reference, offset)
    }
    fn slope_change_about<'a>(&'a self, reference: &R) -> SlopeChange<'a, R> {
        let inner = self.inner.slope_change_about(reference);
        Box::new(move |offset: &R| self.factor.clone() * &inner(offset))
    }
    fn approach_change_about<'a>(&'a self, reference: &R) -> Option<ApproachChange<'a, R>> {
        let inner = self.inner.approach_change_about(reference)?;
        Some(Box::new(move |offset: &R| self.factor.clone() * &inner(offset)))
    }
    fn slope_at_scaled_square(&self, scale: &R, root: &R) -> R {
        self.factor.clone() * &self.inner.slope_at_scaled_square(scale, root)
    }
    fn breakpoints(&self, like: &R) -> Vec<R> {
        self.inner.breakpoints(like)
    }
    fn decay_load(&self) -> Option<R> {
        self.inner.decay_load()
    }
    fn describe(&self) -> String {
        format!("{} × ({})", self.factor.to_scientific(6), self.inner.describe())
    }
    fn admissible_by_form(&self, low: &R, high: &R) -> bool {
        self.factor > low.int(0) && self.inner.admissible_by_form(low, high) && regular_at_ends(self, low, high)
    }
    fn derivative(&self, order: usize, load: &R) -> Option<R> {
        Some(self.factor.clone() * &self.inner.derivative(order, load)?)
    }
    fn derivative_range(&self, order: usize, low: &R, high: &R) -> Option<(R, R)> {
        Some(scaled_range(
            &self.factor,
            &self.inner.derivative_range(order, low, high)?,
        ))
    }
}

/// v + c·P, i.e. v' + c: a constant added to the incremental compliance
/// (e.g. the bulk compliance of a finite body). It does not change the dissipation.
///
/// ```
/// use microslip::compliance::{Compliance, Persson, Shifted};
///
/// // v' + ½: the slope moves, the curvature (and so the dissipation) does not.
/// let v = Shifted { extra_slope: 0.5, inner: Box::new(Persson { gamma: 1.0, sigma: 1.0 }) };
/// assert_eq!(v.slope(&2.0), 1.0);
/// assert_eq!(v.curvature(&2.0), -0.25);
/// ```
#[derive(Debug)]
pub struct Shifted<R: Real> {
    /// The constant c added to v'.
    pub extra_slope: R,
    /// v.
    pub inner: Box<dyn Compliance<R>>,
}

impl<R: Real> Compliance<R> for Shifted<R> {
    fn approach(&self, load: &R) -> R {
        self.inner.approach(load) + &(self.extra_slope.clone() * load)
    }
    fn slope(&self, load: &R) -> R {
        self.inner.slope(load) + &self.extra_slope
    }
    fn curvature(&self, load: &R) -> R {
        self.inner.curvature(load)
    }
    fn slope_change(&self, reference: &R, offset: &R) -> R {
        self.inner.slope_change(reference, offset)
    }
    fn slope_change_about<'a>(&'a self, reference: &R) -> SlopeChange<'a, R> {
        self.inner.slope_change_about(reference)
    }
    fn approach_change_about<'a>(&'a self, reference: &R) -> Option<ApproachChange<'a, R>> {
        // v + c·P changes by the inner change plus c·x.
        let inner = self.inner.approach_change_about(reference)?;
        Some(Box::new(move |offset: &R| {
            inner(offset) + &(self.extra_slope.clone() * offset)
        }))
    }
    fn slope_at_scaled_square(&self, scale: &R, root: &R) -> R {
        self.inner.slope_at_scaled_square(scale, root) + &self.extra_slope
    }
    fn breakpoints(&self, like: &R) -> Vec<R> {
        self.inner.breakpoints(like)
    }
    fn decay_load(&self) -> Option<R> {
        self.inner.decay_load()
    }
    fn describe(&self) -> String {
        format!("({}) + {}·P", self.inner.describe(), self.extra_slope.to_scientific(6))
    }
    fn derivative(&self, order: usize, load: &R) -> Option<R> {
        let inner = self.inner.derivative(order, load)?;
        Some(match order {
            0 => inner + &(self.extra_slope.clone() * load),
            1 => inner + &self.extra_slope,
            _ => inner,
        })
    }
    fn derivative_range(&self, order: usize, low: &R, high: &R) -> Option<(R, R)> {
        // Beyond v' the added c·P leaves no trace.
        (order >= 2)
            .then(|| self.inner.derivative_range(order, low, high))
            .flatten()
    }
}

/// v_k(P) = k·v(P/k), so v_k'(P) = v'(P/k): the compliance of the same surface
/// with every roughness height multiplied by k (lateral structure fixed).
///
/// ```
/// use microslip::compliance::{Compliance, LoadScaled, PowerLaw};
///
/// // v_k'(P) = v'(P/k): with v' = 1/√P and k = 4, v_k'(16) = v'(4) = ½.
/// let v = LoadScaled { factor: 4.0, inner: Box::new(PowerLaw { coefficient: 1.0, exponent: -0.5 }) };
/// assert_eq!(v.slope(&16.0), 0.5);
/// ```
#[derive(Debug)]
pub struct LoadScaled<R: Real> {
    /// The height factor k.
    pub factor: R,
    /// v.
    pub inner: Box<dyn Compliance<R>>,
}

impl<R: Real> Compliance<R> for LoadScaled<R> {
    fn approach(&self, load: &R) -> R {
        self.factor.clone() * &self.inner.approach(&(load.clone() / &self.factor))
    }
    fn slope(&self, load: &R) -> R {
        self.inner.slope(&(load.clone() / &self.factor))
    }
    fn curvature(&self, load: &R) -> R {
        self.inner.curvature(&(load.clone() / &self.factor)) / &self.factor
    }
    fn slope_change(&self, reference: &R, offset: &R) -> R {
        self.inner
            .slope_change(&(reference.clone() / &self.factor), &(offset.clone() / &self.factor))
    }
    fn approach_change_about<'a>(&'a self, reference: &R) -> Option<ApproachChange<'a, R>> {
        // k·[v((P0 + x)/k) − v(P0/k)].
        let inner = self.inner.approach_change_about(&(reference.clone() / &self.factor))?;
        Some(Box::new(move |offset: &R| {
            self.factor.clone() * &inner(&(offset.clone() / &self.factor))
        }))
    }
    fn slope_at_scaled_square(&self, scale: &R, root: &R) -> R {
        self.inner.slope_at_scaled_square(&(scale.clone() / &self.factor), root)
    }
    fn decay_load(&self) -> Option<R> {
        // v'(P/k) decays over k times the inner scale.
        self.inner.decay_load().map(|scale| (scale * &self.factor).abs())
    }
    fn breakpoints(&self, like: &R) -> Vec<R> {
        let mut loads: Vec<R> = self
            .inner
            .breakpoints(like)
            .into_iter()
            .map(|load| load * &self.factor)
            .collect();
        // A negative factor reverses the order.
        loads.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        loads
    }
    fn describe(&self) -> String {
        format!(
            "({}) with loads scaled by 1/{}",
            self.inner.describe(),
            self.factor.to_scientific(6)
        )
    }
    fn derivative(&self, order: usize, load: &R) -> Option<R> {
        // v_k⁽ⁿ⁾(P) = k¹⁻ⁿ v⁽ⁿ⁾(P/k).
        let inner = self.inner.derivative(order, &(load.clone() / &self.factor))?;
        Some(inner * &self.factor.powi(1 - order as i32))
    }
    fn derivative_range(&self, order: usize, low: &R, high: &R) -> Option<(R, R)> {
        let (a, b) = (low.clone() / &self.factor, high.clone() / &self.factor);
        let inner = self.inner.derivative_range(order, &a.min_of(&b), &a.max_of(&b))?;
        Some(scaled_range(&self.factor.powi(1 - order as i32), &inner))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compliance::{Hertz, PowerLaw};
    use rug::Float;

    /// Sums, multiples, added slopes and load scalings of laws with a closed-form change of
    /// approach have one too, equal to the difference of approaches formed at 300 bits.
    #[test]
    fn combined_approach_changes_match_the_difference_of_approaches() {
        fn combined<R: Real>(at: impl Fn(f64) -> R) -> Vec<Box<dyn Compliance<R>>> {
            let hertz = || -> Box<dyn Compliance<R>> {
                Box::new(Hertz {
                    radius: at(1.5),
                    contact_modulus: at(2.0),
                })
            };
            let power = || -> Box<dyn Compliance<R>> {
                Box::new(PowerLaw {
                    coefficient: at(0.7),
                    exponent: at(-1.5),
                })
            };
            vec![
                Box::new(Sum {
                    terms: vec![hertz(), power()],
                }),
                Box::new(Scaled {
                    factor: at(2.5),
                    inner: hertz(),
                }),
                Box::new(Shifted {
                    extra_slope: at(0.3),
                    inner: power(),
                }),
                Box::new(LoadScaled {
                    factor: at(4.0),
                    inner: hertz(),
                }),
            ]
        }
        let wide = combined(|x| Float::with_val(300, x));
        let reference = 2.0;
        for (index, compliance) in combined(|x| x).iter().enumerate() {
            let change = compliance.approach_change_about(&reference).expect("a closed form");
            for offset in [0.8, -1.9, 14.0, 2e-9, -2e-9] {
                let exact = wide[index].approach(&(Float::with_val(300, reference) + offset))
                    - wide[index].approach(&Float::with_val(300, reference));
                let error = (Float::with_val(300, change(&offset)) - &exact).abs();
                assert!(
                    error <= exact.clone().abs() * 1e-14,
                    "{}, x = {offset}: {:e} vs {exact:.17e}",
                    compliance.describe(),
                    change(&offset)
                );
            }
        }
    }
}
