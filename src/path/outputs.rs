//! What a structural-dynamics model needs from the joint besides W: the amplitudes of Q
//! and of the displacement u, the secant stiffness, the loss factor and damping ratio,
//! the harmonics of Q and u, and the steady loop itself.
//!
//! u = λ f U follows the steady loop from the start of the cycle by integrating dU on
//! every smooth segment (cut at the loop's sample angles); its harmonics come from the
//! same integrals by parts (u_cos,k = −(1/kπ) ∮ sin kθ du, u_sin,k = (1/kπ) ∮ cos kθ du), so
//! they are exact to the quadrature and free of the kinks that would slow a DFT of samples.

use crate::compliance::Compliance;
use crate::quad::gauss_legendre::{node_table, NodeTable};
use crate::real::Precision;

use super::events::{extreme, Segment, SteadyCycle};
use super::input::{LoadPath, Multiples};
use super::Contact;

/// Gauss–Legendre points per piece of the loop (each piece is smooth and at most 2π/256 long).
const LOOP_RULE: usize = 20;

/// The fewest samples of the loop used for its amplitude and harmonics.
const MIN_LOOP_POINTS: usize = 256;

/// One harmonic of the joint's force and displacement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathHarmonic {
    /// The harmonic k.
    pub k: usize,
    /// Q's cos kθ coefficient.
    pub q_cos: f64,
    /// Q's sin kθ coefficient.
    pub q_sin: f64,
    /// u's cos kθ coefficient (under force driving u's mean is taken as 0, u being defined
    /// up to a constant; under displacement driving the prescribed mean).
    pub u_cos: f64,
    /// u's sin kθ coefficient.
    pub u_sin: f64,
}

/// One sample of the steady loop.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoopPoint {
    /// The angle θ in [0, 2π).
    pub theta: f64,
    /// P(θ).
    pub normal_load: f64,
    /// Q(θ).
    pub tangential_load: f64,
    /// u(θ): with mean 0 over the samples under force driving, the prescribed u under
    /// displacement driving.
    pub displacement: f64,
}

/// The joint's response along the steady loop.
#[derive(Clone, Debug, PartialEq)]
pub struct PathOutputs {
    /// Half the peak-to-peak of Q.
    pub q_amplitude: f64,
    /// Half the peak-to-peak of u.
    pub u_amplitude: f64,
    /// q_amplitude / u_amplitude.
    pub secant_stiffness: f64,
    /// η = W / (π q_amplitude u_amplitude).
    pub loss_factor: f64,
    /// ζ = η / 2.
    pub damping_ratio: f64,
    /// Harmonics k = 0 … K of Q and u.
    pub harmonics: Vec<PathHarmonic>,
    /// The loop at equal steps of θ from 0.
    pub steady_loop: Vec<LoopPoint>,
}

/// The outputs of a steady cycle whose W is `w`, with harmonics up to `harmonics_out` and
/// the loop at `loop_points` equal steps (at least 256 are used for the amplitudes).
pub fn path_outputs(
    path: &LoadPath<f64>,
    cycle: &SteadyCycle<f64>,
    contact: &Contact<f64>,
    compliance: &dyn Compliance<f64>,
    w: f64,
    harmonics_out: usize,
    loop_points: usize,
) -> PathOutputs {
    let tau = std::f64::consts::TAU;
    // A multiple of the loop's samples, at least MIN_LOOP_POINTS.
    let n = loop_points.max(1) * MIN_LOOP_POINTS.div_ceil(loop_points.max(1));
    let scale = contact.compliance_ratio * contact.friction;
    let walk = Walk::new(cycle, compliance, n, harmonics_out);
    let mean = walk.displacement.iter().sum::<f64>() / n as f64;
    let displacement: Vec<f64> = walk.displacement.iter().map(|u| (u - mean) * scale).collect();
    let (q_low, q_high) = (extreme(&path.tangential, false).1, extreme(&path.tangential, true).1);
    let q_amplitude = 0.5 * (q_high - q_low);
    let (u_low, u_high) = (walk.refined_extreme(false), walk.refined_extreme(true));
    let u_amplitude = 0.5 * (u_high - u_low) * scale;
    let harmonics = (0..=harmonics_out)
        .map(|k| {
            let coefficient = |poly: &[f64]| poly.get(k).copied().unwrap_or(0.0);
            let (u_cos, u_sin) = if k == 0 {
                (0.0, 0.0)
            } else {
                let factor = scale / (k as f64 * std::f64::consts::PI);
                (-walk.sine_moments[k] * factor, walk.cosine_moments[k] * factor)
            };
            PathHarmonic {
                k,
                q_cos: coefficient(&path.tangential.cos),
                q_sin: if k == 0 { 0.0 } else { coefficient(&path.tangential.sin) },
                u_cos,
                u_sin,
            }
        })
        .collect();
    let step = loop_points.max(1);
    let stride = n / step;
    let steady_loop = (0..n)
        .step_by(stride)
        .map(|j| {
            let theta = tau * j as f64 / n as f64;
            LoopPoint {
                theta,
                normal_load: path.normal.value(&theta),
                tangential_load: path.tangential.value(&theta),
                displacement: displacement[j],
            }
        })
        .collect();
    PathOutputs::of_loop(w, q_amplitude, u_amplitude, harmonics, steady_loop)
}

impl PathOutputs {
    /// The outputs of a loop whose W and amplitudes are given: the secant stiffness
    /// Q_a/u_a, the loss factor η = W/(π Q_a u_a) and the damping ratio η/2 follow.
    pub fn of_loop(
        w: f64,
        q_amplitude: f64,
        u_amplitude: f64,
        harmonics: Vec<PathHarmonic>,
        steady_loop: Vec<LoopPoint>,
    ) -> Self {
        let loss_factor = w / (std::f64::consts::PI * q_amplitude * u_amplitude);
        PathOutputs {
            q_amplitude,
            u_amplitude,
            secant_stiffness: q_amplitude / u_amplitude,
            loss_factor,
            damping_ratio: 0.5 * loss_factor,
            harmonics,
            steady_loop,
        }
    }
}

/// U = u/(λf) along the cycle at n equal steps from θ = 0, and the moments ∮ cos kθ dU,
/// ∮ sin kθ dU.
struct Walk<'a> {
    cycle: &'a SteadyCycle<f64>,
    compliance: &'a dyn Compliance<f64>,
    /// U at θ = 2πj/n.
    displacement: Vec<f64>,
    cosine_moments: Vec<f64>,
    sine_moments: Vec<f64>,
}

impl<'a> Walk<'a> {
    fn new(cycle: &'a SteadyCycle<f64>, compliance: &'a dyn Compliance<f64>, n: usize, harmonics: usize) -> Self {
        let tau = std::f64::consts::TAU;
        let start = cycle.start;
        // The sample angles, each moved into [start, start + 2π), in increasing order.
        let mut targets: Vec<(f64, usize)> = (0..n)
            .map(|j| {
                let theta = tau * j as f64 / n as f64;
                (if theta < start { theta + tau } else { theta }, j)
            })
            .collect();
        targets.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut walk = Walk {
            cycle,
            compliance,
            displacement: vec![0.0; n],
            cosine_moments: vec![0.0; harmonics + 1],
            sine_moments: vec![0.0; harmonics + 1],
        };
        let rule = node_table::<f64>(LOOP_RULE, Precision::DOUBLE);
        let mut u = 0.0;
        let mut next = 0;
        for segment in &cycle.segments {
            let mut from = segment.start;
            while next < n && targets[next].0 <= segment.end {
                let to = targets[next].0.max(from);
                u += walk.piece(&rule, segment, from, to);
                walk.displacement[targets[next].1] = u;
                from = to;
                next += 1;
            }
            u += walk.piece(&rule, segment, from, segment.end);
        }
        walk
    }

    /// ∫ dU over [a, b] inside `segment`, adding ∫ cos kθ dU and ∫ sin kθ dU to the moments.
    fn piece(&mut self, rule: &NodeTable<f64>, segment: &Segment<f64>, a: f64, b: f64) -> f64 {
        if b <= a {
            return 0.0;
        }
        let (half_width, middle) = (0.5 * (b - a), 0.5 * (b + a));
        let mut sum = 0.0;
        for (x, w) in rule.nodes.iter().zip(&rule.weights) {
            let theta = middle + half_width * x;
            let term = self.cycle.displacement_rate(segment, &theta, self.compliance) * w * half_width;
            let multiples = Multiples::of(&theta, self.cosine_moments.len() - 1);
            for k in 1..self.cosine_moments.len() {
                self.cosine_moments[k] += term * multiples.cos(k);
                self.sine_moments[k] += term * multiples.sin(k);
            }
            sum += term;
        }
        sum
    }

    /// The largest (or smallest) U: from the best sample, refined to where dU/dθ changes
    /// sign within a step either side (a bracket that would cross the cycle's start keeps
    /// the sample).
    fn refined_extreme(&self, largest: bool) -> f64 {
        let sign = if largest { 1.0 } else { -1.0 };
        let (best, value) = self
            .displacement
            .iter()
            .enumerate()
            .fold((0, self.displacement[0]), |(i, v), (j, &u)| {
                if sign * u > sign * v {
                    (j, u)
                } else {
                    (i, v)
                }
            });
        let tau = std::f64::consts::TAU;
        let n = self.displacement.len();
        let start = self.cycle.start;
        let mut at = tau * best as f64 / n as f64;
        if at < start {
            at += tau;
        }
        let step = tau / n as f64;
        let rate = |theta: f64| {
            self.segment_at(theta)
                .map(|s| self.cycle.displacement_rate(s, &theta, self.compliance))
        };
        let (Some(here), Some(_), Some(_)) = (rate(at), rate(at - step), rate(at + step)) else {
            return value;
        };
        // Towards the extreme: dU/dθ points up the slope of sign·U.
        let (a, b) = if sign * here > 0.0 {
            (at, at + step)
        } else {
            (at - step, at)
        };
        let (Some(ra), Some(rb)) = (rate(a), rate(b)) else {
            return value;
        };
        if sign * ra < 0.0 || sign * rb > 0.0 {
            return value;
        }
        let (mut low, mut high) = (a, b);
        for _ in 0..60 {
            let middle = 0.5 * (low + high);
            match rate(middle) {
                Some(r) if sign * r > 0.0 => low = middle,
                Some(_) => high = middle,
                None => break,
            }
        }
        value + self.integral(at, 0.5 * (low + high))
    }

    /// The segment holding θ, if θ lies in the cycle.
    fn segment_at(&self, theta: f64) -> Option<&'a Segment<f64>> {
        self.cycle.segments.iter().find(|s| s.start <= theta && theta <= s.end)
    }

    /// ∫ dU from a to b (either order) within the cycle, cut at segment ends.
    fn integral(&self, a: f64, b: f64) -> f64 {
        let (low, high, sign) = if a <= b { (a, b, 1.0) } else { (b, a, -1.0) };
        let rule = node_table::<f64>(LOOP_RULE, Precision::DOUBLE);
        let mut sum = 0.0;
        for segment in &self.cycle.segments {
            let (from, to) = (segment.start.max(low), segment.end.min(high));
            if to > from {
                sum += rule.integrate(
                    |t: &f64| self.cycle.displacement_rate(segment, t, self.compliance),
                    &from,
                    &to,
                );
            }
        }
        sign * sum
    }
}
