//! The harmonic layout of a solver's unknowns and the passage between harmonics and the
//! samples of one period: u(t_n) from U, and the discrete Fourier coefficients of Q.

use std::cell::RefCell;
use std::f64::consts::TAU;
use std::rc::Rc;

use super::AftError;

/// The most time points per period.
pub const MAX_TIME_POINTS: usize = 1 << 20;

/// The coefficients [U_0 (k = 0), cos k₁, sin k₁, …] and their basis functions at the time
/// points t_n = 2πn/N: `basis[n · coefficients + j]`.
pub(super) struct Layout {
    /// The harmonic numbers, as given.
    harmonics: Vec<usize>,
    /// The harmonic number of each coefficient.
    orders: Vec<usize>,
    basis: Vec<f64>,
    time_points: usize,
}

thread_local! {
    /// The layout last built on this thread: a solver calls `aft` with the same harmonics
    /// and time points at every iteration, and the basis costs two trigonometric functions
    /// per time point.
    static LAST_LAYOUT: RefCell<Option<Rc<Layout>>> = const { RefCell::new(None) };
}

impl Layout {
    /// The layout of `harmonics` on `time_points` (as [`Layout::new`]), reused while the
    /// calls on this thread keep both.
    pub(super) fn cached(harmonics: &[usize], time_points: usize) -> Result<Rc<Self>, AftError> {
        LAST_LAYOUT.with_borrow_mut(|last| match last {
            Some(layout) if layout.time_points == time_points && layout.harmonics == harmonics => Ok(Rc::clone(layout)),
            _ => {
                let layout = Rc::new(Layout::new(harmonics, time_points)?);
                *last = Some(Rc::clone(&layout));
                Ok(layout)
            }
        })
    }

    /// The layout of strictly increasing `harmonics` on `time_points` equal steps, which must
    /// exceed twice the highest harmonic (a cosine and a sine of every k apart from aliasing).
    pub(super) fn new(harmonics: &[usize], time_points: usize) -> Result<Self, AftError> {
        let Some(&highest) = harmonics.last() else {
            return Err(AftError::Harmonics(
                "no harmonics given: list the harmonic numbers, e.g. [0, 1, 3]".to_string(),
            ));
        };
        if let Some(pair) = harmonics.windows(2).find(|pair| pair[0] >= pair[1]) {
            return Err(AftError::Harmonics(format!(
                "the harmonics must be strictly increasing, but {} is followed by {}: list each k once, in order",
                pair[0], pair[1]
            )));
        }
        if time_points <= 2 * highest || time_points > MAX_TIME_POINTS {
            return Err(AftError::TimePoints {
                given: time_points,
                highest,
            });
        }
        let orders: Vec<usize> = harmonics
            .iter()
            .flat_map(|&k| if k == 0 { vec![0] } else { vec![k, k] })
            .collect();
        let cosines: Vec<f64> = (0..time_points)
            .map(|m| (TAU * m as f64 / time_points as f64).cos())
            .collect();
        let sines: Vec<f64> = (0..time_points)
            .map(|m| (TAU * m as f64 / time_points as f64).sin())
            .collect();
        let mut basis = Vec::with_capacity(time_points * orders.len());
        for n in 0..time_points {
            for (j, &k) in orders.iter().enumerate() {
                let phase = (k as u64 * n as u64 % time_points as u64) as usize;
                basis.push(match k {
                    0 => 1.0,
                    _ if is_cosine(&orders, j) => cosines[phase],
                    _ => sines[phase],
                });
            }
        }
        Ok(Layout {
            harmonics: harmonics.to_vec(),
            orders,
            basis,
            time_points,
        })
    }

    /// The number of coefficients.
    pub(super) fn coefficients(&self) -> usize {
        self.orders.len()
    }

    /// The time points per period.
    pub(super) fn time_points(&self) -> usize {
        self.time_points
    }

    /// The basis functions at time point n: du(t_n)/dU.
    pub(super) fn at(&self, n: usize) -> &[f64] {
        let width = self.coefficients();
        &self.basis[n * width..(n + 1) * width]
    }

    /// u(t_n) for every time point.
    pub(super) fn synthesize(&self, coefficients: &[f64]) -> Vec<f64> {
        (0..self.time_points)
            .map(|n| self.at(n).iter().zip(coefficients).map(|(b, c)| b * c).sum())
            .collect()
    }

    /// The discrete Fourier coefficients of the samples: the mean for k = 0, and
    /// (2/N) Σ Q_n cos(k t_n), (2/N) Σ Q_n sin(k t_n).
    pub(super) fn analyze(&self, samples: &[f64]) -> Vec<f64> {
        let mut sums = vec![0.0; self.coefficients()];
        for (n, &sample) in samples.iter().enumerate() {
            for (sum, b) in sums.iter_mut().zip(self.at(n)) {
                *sum += sample * b;
            }
        }
        sums.iter()
            .zip(&self.orders)
            .map(|(sum, &k)| sum * self.weight(k))
            .collect()
    }

    /// The coefficients of each column of the gradients (row n: dQ(t_n)/dU): dF/dU row-major.
    pub(super) fn analyze_gradients(&self, gradients: &[f64]) -> Vec<f64> {
        let width = self.coefficients();
        let mut jacobian = vec![0.0; width * width];
        for n in 0..self.time_points {
            let gradient = &gradients[n * width..(n + 1) * width];
            for (row, b) in jacobian.chunks_exact_mut(width).zip(self.at(n)) {
                if *b != 0.0 {
                    for (entry, g) in row.iter_mut().zip(gradient) {
                        *entry += b * g;
                    }
                }
            }
        }
        for (row, &k) in jacobian.chunks_exact_mut(width).zip(&self.orders) {
            let weight = self.weight(k);
            row.iter_mut().for_each(|entry| *entry *= weight);
        }
        jacobian
    }

    /// 1/N for the mean, 2/N for a cosine or sine coefficient.
    fn weight(&self, k: usize) -> f64 {
        let scale = if k == 0 { 1.0 } else { 2.0 };
        scale / self.time_points as f64
    }
}

/// Whether coefficient j is the cosine of its harmonic (the first of its pair).
fn is_cosine(orders: &[usize], j: usize) -> bool {
    j == 0 || orders[j - 1] != orders[j]
}

/// π Σ_k k (U_sin,k F_cos,k − U_cos,k F_sin,k): ∫₀^{2π} Q u̇ dt with Q's coefficients F.
pub(super) fn work_per_cycle(harmonics: &[usize], displacement: &[f64], force: &[f64]) -> f64 {
    // The harmonics increase strictly, so k = 0 (one coefficient) can only come first.
    let start = usize::from(harmonics.first() == Some(&0));
    let pairs = displacement[start..]
        .chunks_exact(2)
        .zip(force[start..].chunks_exact(2));
    let sum: f64 = harmonics[start..]
        .iter()
        .zip(pairs)
        .map(|(&k, (u, f))| k as f64 * (u[1] * f[0] - u[0] * f[1]))
        .sum();
    std::f64::consts::PI * sum
}
