//! Proven remainders of the small-amplitude series: W − W_N = λ f² P1^(N+3) ∫ v⁽ᴺ⁺²⁾ K_{N+1},
//! with K_{N+1} one-signed on each side of τ = 0, lies in λ f² P1^(N+3) [B₋ R₋ + B₊ R₊], B±
//! the kernel's integrals over each side and R± the ranges of v⁽ᴺ⁺²⁾ over [P_T, P0] and
//! [P0, P0 + P1] (proofs/cubic-law-remainder.md).
//!
//! The kernel integrals depend on (ρ, φ) alone ([`PeanoKernels`]) and the derivative ranges
//! on the compliance over the loads the measure reaches ([`Compliance::derivative_range`]):
//! down to the permanent-stick load P_T, not only P0 − P1, since the slip loads P_S and P_K
//! reach it. On Arb balls every factor is an enclosure, so the upper end of the product
//! bounds the remainder; in f64 it is the same bound, unproven.

use super::kernel::PeanoKernels;
use super::series::{sums_at_amplitude, SeriesError};
use crate::compliance::{scaled_range, Compliance};
use crate::cycle::LoadCycle;
use crate::real::Real;

/// Why no remainder bound could be given.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RemainderError {
    /// The series itself could not be formed.
    #[error(transparent)]
    Series(#[from] SeriesError),
    /// The compliance gives no bound on the derivative the remainder needs.
    #[error("the compliance {describe} gives no bound on |v^({order})| over the loads [{low:e}, {high:e}] the cycle reaches (a table's interpolant has none, and a family singular at P = 0 has none on a range that reaches it); the series' remainder needs one")]
    NoDerivativeBound {
        /// The compliance, described.
        describe: String,
        /// The order of the derivative of v.
        order: usize,
        /// The lowest load, P_T.
        low: f64,
        /// The highest load, P0 + P1.
        high: f64,
    },
    /// The kernels could not be enclosed (a load's extreme at τ = 0, or a degenerate cycle).
    #[error("the Peano kernels of ρ = {rho:e}, φ = {phase:e} could not be enclosed (a load's extreme lies at P0 to within the working precision)")]
    Kernel {
        /// ρ = Q1/(fP1).
        rho: f64,
        /// φ.
        phase: f64,
    },
}

/// The pieces of a case's remainders that do not depend on the compliance.
#[derive(Clone, Debug)]
pub struct SeriesShape<R> {
    /// ρ = Q1/(fP1).
    pub rho: R,
    /// I₀ … I_{N+1} (I_{N+1}/(N+1)! = ∫ K_{N+1}), from the kernels' jumps at τ = 0.
    pub coefficients: Vec<R>,
    /// Index n − 1: the integrals of K_{n+1} below and above τ = 0, on each of which it is
    /// one-signed ([`PeanoKernels::at_origin`]).
    pub sides: Vec<(R, R)>,
    /// L = (P0 − P_T)/P1, how far below P0 the measure reaches in units of P1.
    pub reach: R,
}

/// W − W_N enclosed: every value of it lies between the lower end of `least` and the upper
/// end of `greatest` (on Arb balls; in f64 the same numbers, unproven).
#[derive(Clone, Debug)]
pub struct Remainder<R> {
    /// The least W − W_N can be.
    pub least: R,
    /// The greatest W − W_N can be.
    pub greatest: R,
}

impl<R: Real> Remainder<R> {
    /// An upper bound on |W − W_N|.
    pub fn bound(&self) -> R {
        self.least.abs().max_of(&self.greatest.abs())
    }
}

impl<R: Real> SeriesShape<R> {
    /// The shape of (ρ, φ) for orders up to `order`.
    pub fn new(rho: &R, phase: &R, order: usize) -> Result<Self, RemainderError> {
        let kernels = PeanoKernels::new(rho, phase, order + 1)?;
        let origin = kernels.at_origin().ok_or_else(|| RemainderError::Kernel {
            rho: rho.to_f64_lossy(),
            phase: phase.to_f64_lossy(),
        })?;
        Ok(SeriesShape {
            rho: rho.clone(),
            coefficients: origin.coefficients,
            sides: origin.sides,
            reach: kernels.reach().clone(),
        })
    }

    /// The shape of a cycle's (ρ, φ), ρ = Q1/(fP1), for orders up to `order`, once the cycle
    /// is checked inside the theory with P1 > 0; `None` where Q1 = 0 (W = 0, and every W_N).
    pub fn of_cycle(cycle: &LoadCycle<R>, order: usize) -> Result<Option<Self>, RemainderError> {
        cycle.validate().map_err(SeriesError::from)?;
        let zero = cycle.mean_normal_load.int(0);
        let p1 = &cycle.normal_amplitude;
        if *p1 == zero {
            return Err(SeriesError::NoNormalAmplitude.into());
        }
        let rho = cycle.tangential_amplitude.clone() / &(cycle.friction.clone() * p1);
        if rho == zero {
            return Ok(None);
        }
        Ok(Some(SeriesShape::new(&rho, &cycle.phase, order)?))
    }

    /// ‖K_{n+1}‖₁ (index n − 1): the sum of its sides' magnitudes.
    pub fn norms(&self) -> Vec<R> {
        self.sides
            .iter()
            .map(|(below, above)| below.abs() + &above.abs())
            .collect()
    }

    /// The partial sums W_1 … W_N and the enclosures of W − W_N (index N − 1) of the cycle
    /// with this shape, at normal amplitude `amplitude` (the tangential amplitude is
    /// ρ f P1: the shape is kept as P1 moves).
    ///
    /// W − W_N = λ f² P1^(N+3) [v⁽ᴺ⁺²⁾(ξ₋) ∫_{τ<0} K_{N+1} + v⁽ᴺ⁺²⁾(ξ₊) ∫_{τ>0} K_{N+1}] for some
    /// ξ₋ in [P_T, P0] and ξ₊ in [P0, P0 + P1], K_{N+1} being one-signed on each side: the
    /// ranges of v⁽ᴺ⁺²⁾ there give the enclosure.
    pub fn at_amplitude(
        &self,
        cycle: &LoadCycle<R>,
        compliance: &dyn Compliance<R>,
        amplitude: &R,
    ) -> Result<(Vec<R>, Vec<Remainder<R>>), RemainderError> {
        let p0 = &cycle.mean_normal_load;
        let order = self.sides.len();
        let sums = sums_at_amplitude(&self.coefficients[..=order], cycle, compliance, amplitude)?;
        let scale = cycle.compliance_ratio.clone() * &cycle.friction.square() * &amplitude.square();
        let (low, high) = (p0.clone() - &(self.reach.clone() * amplitude), p0.clone() + amplitude);
        let mut remainders = Vec::with_capacity(sums.len());
        let mut power = amplitude.clone();
        for (n, (below, above)) in self.sides.iter().enumerate().map(|(i, sides)| (i + 1, sides)) {
            power *= amplitude;
            let range = |from: &R, to: &R| {
                compliance
                    .derivative_range(n + 2, from, to)
                    .ok_or_else(|| RemainderError::NoDerivativeBound {
                        describe: compliance.describe(),
                        order: n + 2,
                        low: low.to_f64_lossy(),
                        high: high.to_f64_lossy(),
                    })
            };
            let lower_side = scaled_range(below, &range(&low, p0)?);
            let upper_side = scaled_range(above, &range(p0, &high)?);
            // λ f² P1² · P1^(n+1) is positive.
            let factor = scale.clone() * &power;
            remainders.push(Remainder {
                least: (lower_side.0 + &upper_side.0) * &factor,
                greatest: (lower_side.1 + &upper_side.1) * &factor,
            });
        }
        Ok((sums, remainders))
    }
}

/// Bounds on |W − W_N|, N = 1 … `order` (index N − 1), for a cycle on a compliance.
///
/// ```
/// use microslip::compliance::Persson;
/// use microslip::cycle::LoadCycle;
/// use microslip::dissipation::{dissipation, Options};
/// use microslip::exact::{partial_sums, remainder_bounds};
///
/// let cycle = LoadCycle {
///     mean_normal_load: 1.0,
///     normal_amplitude: 0.05,
///     mean_tangential_load: 0.0,
///     tangential_amplitude: 0.04,
///     phase: 1.0,
///     friction: 1.0,
///     compliance_ratio: 1.5,
/// };
/// let v = Persson { gamma: 1.0, sigma: 1.0 };
/// let bounds = remainder_bounds(&cycle, &v, 3)?;
/// let sums = partial_sums(&cycle, &v, 3)?;
/// let w = dissipation(&cycle, &v, &Options::default())?.total;
/// for (sum, bound) in sums.iter().zip(&bounds) {
///     assert!((w - sum).abs() <= *bound);
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn remainder_bounds<R: Real>(
    cycle: &LoadCycle<R>,
    compliance: &dyn Compliance<R>,
    order: usize,
) -> Result<Vec<R>, RemainderError> {
    Ok(remainders(cycle, compliance, order)?
        .iter()
        .map(Remainder::bound)
        .collect())
}

/// W − W_N enclosed, N = 1 … `order` (index N − 1), for a cycle on a compliance: sharper
/// than ± [`remainder_bounds`], and one-sided where the derivative's sign makes it so (a
/// completely monotone v' at even N: W ≥ W_N).
pub fn remainders<R: Real>(
    cycle: &LoadCycle<R>,
    compliance: &dyn Compliance<R>,
    order: usize,
) -> Result<Vec<Remainder<R>>, RemainderError> {
    Ok(sums_and_remainders(cycle, compliance, order)?.1)
}

/// The partial sums W_1 … W_N and the enclosures of W − W_N (index N − 1) of a cycle on a
/// compliance: all 0 where Q1 = 0, where W and every W_N are.
pub fn sums_and_remainders<R: Real>(
    cycle: &LoadCycle<R>,
    compliance: &dyn Compliance<R>,
    order: usize,
) -> Result<(Vec<R>, Vec<Remainder<R>>), RemainderError> {
    let shape = SeriesShape::of_cycle(cycle, order)?;
    sums_and_remainders_with(shape.as_ref(), cycle, compliance, order)
}

/// [`sums_and_remainders`] from the cycle's shape already formed ([`SeriesShape::of_cycle`],
/// to `order` or beyond).
pub fn sums_and_remainders_with<R: Real>(
    shape: Option<&SeriesShape<R>>,
    cycle: &LoadCycle<R>,
    compliance: &dyn Compliance<R>,
    order: usize,
) -> Result<(Vec<R>, Vec<Remainder<R>>), RemainderError> {
    let Some(shape) = shape else {
        let zero = cycle.mean_normal_load.int(0);
        let none = Remainder {
            least: zero.clone(),
            greatest: zero.clone(),
        };
        return Ok((vec![zero; order], vec![none; order]));
    };
    let (mut sums, mut remainders) = shape.at_amplitude(cycle, compliance, &cycle.normal_amplitude)?;
    sums.truncate(order);
    remainders.truncate(order);
    Ok((sums, remainders))
}

/// Why the amplitude stops where `--within` stops it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WithinLimit {
    /// The bound reaches R·|W| first.
    Remainder,
    /// The cycle leaves the theory first: P1 reaches P0 (separation).
    Separation,
    /// The cycle leaves the theory first: it would slip as a whole (gross slip).
    GrossSlip,
}

/// The largest normal amplitude found at which |W − W₁| ≤ R·|W| is proven.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Within {
    /// The amplitude P1 (None: not proven even at 10⁻¹² P0).
    pub p1_max: Option<f64>,
    /// What stops it.
    pub limit: WithinLimit,
    /// Where the theory ends (P1 with the shape kept), if the search met it.
    pub theory_end: f64,
}

#[cfg(feature = "certified")]
mod within {
    use super::*;
    use crate::ball::{watch, Ball};
    use crate::cycle::CycleError;

    /// The cycle with its normal amplitude moved to `amplitude` and Q1 with it (ρ kept).
    fn moved(cycle: &LoadCycle<Ball>, amplitude: f64) -> LoadCycle<Ball> {
        let p1 = Ball::from_f64(amplitude, cycle.mean_normal_load.precision());
        let mut moved = cycle.clone();
        moved.tangential_amplitude = cycle.tangential_amplitude.clone() / &cycle.normal_amplitude * &p1;
        moved.normal_amplitude = p1;
        moved
    }

    /// Whether the moved cycle is decidedly inside the theory; else what it leaves by.
    fn inside(cycle: &LoadCycle<Ball>) -> Result<(), WithinLimit> {
        let (checked, doubts) = watch(|| cycle.validate());
        match checked {
            Err(CycleError::Separation { .. }) => Err(WithinLimit::Separation),
            Err(_) => Err(WithinLimit::GrossSlip),
            Ok(()) if doubts.none() => Ok(()),
            Ok(()) => Err(WithinLimit::GrossSlip),
        }
    }

    /// The lower end of a ball's real interval, and the upper end.
    fn ends(x: &Ball) -> (f64, f64) {
        x.real_span().unwrap_or((f64::NEG_INFINITY, f64::INFINITY))
    }

    /// Whether |W − W₁| ≤ `ratio`·|W| is proven at `amplitude`: the bound on |W − W₁| against
    /// the lower bound on |W| from the tightest of the enclosures W_N ± bound_N.
    fn proven(
        shape: &SeriesShape<Ball>,
        cycle: &LoadCycle<Ball>,
        compliance: &dyn Compliance<Ball>,
        ratio: f64,
        amplitude: f64,
    ) -> Result<bool, WithinLimit> {
        let cycle = moved(cycle, amplitude);
        inside(&cycle)?;
        let Ok((sums, remainders)) = shape.at_amplitude(&cycle, compliance, &cycle.normal_amplitude) else {
            return Ok(false);
        };
        // |W| from below: the enclosure W_N + [least, greatest] farthest from 0.
        let smallest_w = sums
            .iter()
            .zip(&remainders)
            .map(|(sum, remainder)| {
                let (low, high) = (
                    ends(&(sum.clone() + &remainder.least)).0,
                    ends(&(sum.clone() + &remainder.greatest)).1,
                );
                low.max(-high)
            })
            .fold(f64::NEG_INFINITY, f64::max);
        // The f64 products are rounded down by a few ulps to stay on the proven side.
        let allowed = ratio * smallest_w * (1.0 - 8.0 * f64::EPSILON);
        Ok(smallest_w > 0.0 && ends(&remainders[0].bound()).1 <= allowed)
    }

    /// The largest P1 (ρ, φ, P0, Q0, f, λ and the compliance kept) at which
    /// |W − W₁| ≤ `ratio`·|W| is proven, by bisection in ln P1 on the proven predicate
    /// (64 steps); the theory's end is found first, by bisection on the cycle's validity.
    pub fn largest_amplitude(
        shape: &SeriesShape<Ball>,
        cycle: &LoadCycle<Ball>,
        compliance: &dyn Compliance<Ball>,
        ratio: f64,
    ) -> Within {
        let p0 = cycle.mean_normal_load.to_f64_lossy();
        // The theory's end: valid at `low`, not at `high`.
        let (mut low, mut high) = (p0 * 1e-12, p0);
        let mut limit = inside(&moved(cycle, high)).err().unwrap_or(WithinLimit::Separation);
        for _ in 0..64 {
            let middle = (low * high).sqrt();
            match inside(&moved(cycle, middle)) {
                Ok(()) => low = middle,
                Err(why) => (high, limit) = (middle, why),
            }
        }
        let theory_end = low;
        if proven(shape, cycle, compliance, ratio, theory_end) == Ok(true) {
            return Within {
                p1_max: Some(theory_end),
                limit,
                theory_end: high,
            };
        }
        let (mut good, mut bad) = (p0 * 1e-12, theory_end);
        if proven(shape, cycle, compliance, ratio, good) != Ok(true) {
            return Within {
                p1_max: None,
                limit: WithinLimit::Remainder,
                theory_end: high,
            };
        }
        for _ in 0..64 {
            let middle = (good * bad).sqrt();
            if proven(shape, cycle, compliance, ratio, middle) == Ok(true) {
                good = middle;
            } else {
                bad = middle;
            }
        }
        Within {
            p1_max: Some(good),
            limit: WithinLimit::Remainder,
            theory_end: high,
        }
    }
}

#[cfg(feature = "certified")]
pub use within::largest_amplitude;
