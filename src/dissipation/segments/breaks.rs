//! Where each segment breaks: its lowest-load points (θ ≡ π, and CH's mirror load), the
//! angles where a load of its integrand crosses a knot of the compliance, and the narrow
//! peaks about its lowest loads that [`super::plans`] maps.

use super::super::slope::knot_offsets;
use super::{LowLoad, Segment, SegmentIntegrands};
use crate::quad::sinh_map::{acosh_one_plus, asinh, Peak};
use crate::real::{Precision, Real};

/// A point of `s` to split an integral at: any point splits it exactly, and at double
/// precision the middle of an enclosure of s (a double) gives the pieces on either side
/// an exact common limit where s itself, an angle of the cycle near π formed from other
/// angles, would widen both by its width; other precisions keep s.
fn split_point<R: Real>(s: R) -> R {
    match s.real_span() {
        Some((lo, hi)) if s.precision() == Precision::DOUBLE && lo < hi => {
            R::from_f64(lo * 0.5 + hi * 0.5, Precision::DOUBLE)
        }
        _ => s,
    }
}

impl<'a, R: Real> SegmentIntegrands<'a, R> {
    /// The windows of `segment` in s, between its break points (lowest loads and
    /// knot crossings), before narrow peaks are mapped: for rules that integrate in s
    /// or in the load themselves.
    pub fn windows(&self, segment: Segment) -> Vec<(R, R)> {
        let mut breaks = self.lowest_load_points(segment);
        let knots = knot_offsets(self.compliance, &self.geometry.mean_normal_load);
        if !knots.is_empty() {
            breaks.extend(self.knot_crossings(segment, &knots));
            breaks.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
            breaks.dedup();
        }
        breaks.windows(2).map(|w| (w[0].clone(), w[1].clone())).collect()
    }

    /// The narrow peaks of segment `index` (in s), where a load that v' is taken at is
    /// least: P at θ ≡ π (mod 2π), and for CH P_Y at the mirror angle θ_C − s ≡ π, each
    /// of half-width acosh(P0/P1) (where P0 + P1 cos θ vanishes, off the real axis);
    /// for EB P_S = P_T + σ₊ sin²h/f at B, of half-width 2 asinh(√(fP_T/σ₊)), and for HE
    /// P_K likewise at E with σ₋. A compliance singular at P = 0 makes these peaks as
    /// narrow as √((P0 − P1)/P0) near separation and √(P_T/P0) near gross slip; one with a
    /// decay load c shorter than those loads
    /// ([`Compliance::decay_load`](crate::compliance::Compliance::decay_load)) as narrow as
    /// √(2c/P1), the load itself replaced by c in each width.
    pub(super) fn low_loads(&self, segment: Segment) -> Vec<(Peak<R>, LowLoad)> {
        let g = self.geometry;
        let (start, length) = self.extent(segment);
        let zero = length.int(0);
        let pi = length.pi_like();
        // Six turns, twice for CH, and the slip load's peak.
        let mut peaks = Vec::with_capacity(13);
        // A v' singular at P = 0 peaks over the load itself, one with a decay load of its
        // own over that where it is shorter.
        let decay_load = self.compliance.decay_load();
        let within_decay = |load: R| match &decay_load {
            Some(scale) => load.min_of(scale),
            None => load,
        };
        if let Some(margin) = self.normal_margin() {
            let margin = match &decay_load {
                Some(scale) => margin.min_of(&(scale.clone() / &g.normal_amplitude)),
                None => margin,
            };
            let width = acosh_one_plus(&margin);
            // A centre more than the segment's length outside it is farther than its length
            // from every window in it, which `resolve_peaks` skips: it is not formed in R.
            for (k, normal, mirror) in self.nearby_turns(segment, 1.0) {
                let lowest = pi.clone() * &pi.int(2 * k + 1);
                if normal {
                    let center = lowest.clone() - start;
                    peaks.push((
                        Peak {
                            center,
                            width: width.clone(),
                        },
                        LowLoad::Normal,
                    ));
                }
                if mirror {
                    let center = g.theta_c.clone() - &lowest;
                    peaks.push((
                        Peak {
                            center,
                            width: width.clone(),
                        },
                        LowLoad::Mirror,
                    ));
                }
            }
        }
        if let Some(amplitude) = self.slip_amplitude(segment).filter(|a| **a > zero) {
            let ratio = within_decay(g.permanent_stick_load()) * &g.friction / amplitude;
            let width = asinh(&ratio.max_of(&zero).sqrt()) * &zero.int(2);
            peaks.push((
                Peak {
                    center: length.clone(),
                    width,
                },
                LowLoad::Slip,
            ));
        }
        peaks
    }

    /// σ₊ for EB (P_S), σ₋ for HE (P_K): the amplitude of the slip load a slip segment
    /// takes v' at besides P; none for BC and CH.
    fn slip_amplitude(&self, segment: Segment) -> Option<&'a R> {
        match segment {
            Segment::EB => Some(&self.geometry.sum_amplitude),
            Segment::HE => Some(&self.geometry.difference_amplitude),
            Segment::BC | Segment::CH => None,
        }
    }

    /// The angles s strictly inside segment `index` where a load that v' is taken at
    /// crosses a knot (given as offsets x = P − P0), so that between two of them (and
    /// the lowest-load points) every v' in the integrand is one analytic piece:
    ///
    /// ```text
    /// P    = P0 + P1 cos θ                 θ = ±acos(x/P1) + 2πm          (all segments)
    /// P_Y  = P0 + P1 cos(θ_C − s)          s = θ_C ∓ acos(x/P1) − 2πm     (CH)
    /// P_S  = P_T + σ₊ sin²h/f, h = (s − L)/2 ∈ [−π/2, 0]:
    ///                                      s = L − 2 asin(√((P − P_T) f/σ₊))   (EB; HE with P_K, σ₋)
    /// ```
    fn knot_crossings(&self, segment: Segment, knots: &[R]) -> Vec<R> {
        let g = self.geometry;
        let (start, length) = self.extent(segment);
        let zero = length.int(0);
        let one = length.int(1);
        let two_pi = length.pi_like() * &length.int(2);
        let mut crossings = Vec::new();
        let slip_amplitude = self.slip_amplitude(segment);
        for knot in knots {
            if g.normal_amplitude > zero {
                let cosine = knot.clone() / &g.normal_amplitude;
                if cosine > -one.clone() && cosine < one {
                    // acos c = atan2(√((1 − c)(1 + c)), c), free of cancellation near c = ±1.
                    let sine = ((one.clone() - &cosine) * &(one.clone() + &cosine)).sqrt();
                    let angle = sine.atan2(&cosine);
                    for m in -2..=3i64 {
                        let turn = two_pi.clone() * &length.int(m);
                        for theta in [turn.clone() + &angle, turn.clone() - &angle] {
                            crossings.push(theta.clone() - start);
                            if segment == Segment::CH {
                                crossings.push(g.theta_c.clone() - &theta);
                            }
                        }
                    }
                }
            }
            if let Some(amplitude) = slip_amplitude.filter(|a| **a > zero) {
                let fraction = (knot.clone() - &g.permanent_stick_offset) * &g.friction / amplitude;
                if fraction > zero && fraction < one {
                    let half = fraction.sqrt().atan2(&(one.clone() - &fraction).sqrt());
                    crossings.push(length.clone() - &(half * &length.int(2)));
                }
            }
        }
        crossings.retain(|s| *s > zero && s < length);
        crossings
    }

    /// The six turns around the cycle (k = −2..=3) whose lowest loads can lie within
    /// `slack` lengths of `segment`'s [0, length], by a double's reckoning: k, and whether
    /// P's, at (2k + 1)π − start, and in CH the mirror load's, at θ_C − (2k + 1)π, can. The
    /// margin, 10⁻⁹·(1 + |s| + length), is far beyond a double's rounding of these angles
    /// or a ball's radius around them, so a turn skipped here is outside in every type; the
    /// callers skip it without the arithmetic of R (on balls, a product and comparisons of
    /// about 1 200 instructions each). A NaN skips nothing.
    fn nearby_turns(&self, segment: Segment, slack: f64) -> impl Iterator<Item = (i64, bool, bool)> {
        let (start, length) = self.extent(segment);
        let (start, length) = (start.to_f64_lossy(), length.to_f64_lossy());
        let theta_c = self.geometry.theta_c.to_f64_lossy();
        let near = move |s: f64| {
            let margin = 1e-9 * (1.0 + s.abs() + length.abs());
            !(s < -slack * length - margin || s > (1.0 + slack) * length + margin)
        };
        (-2..=3i64).filter_map(move |k| {
            let lowest = std::f64::consts::PI * (2 * k + 1) as f64;
            let normal = near(lowest - start);
            let mirror = segment == Segment::CH && near(theta_c - lowest);
            (normal || mirror).then_some((k, normal, mirror))
        })
    }

    /// The break points 0 = s₀ < s₁ < … < L of a segment: the angles where P (and,
    /// for CH, P at the mirror point θ_C − s) is least, θ ≡ π (mod 2π). A compliance
    /// singular at P → 0 is nearly singular there when the cycle nears separation,
    /// and a break puts the trouble at an end of a piece.
    fn lowest_load_points(&self, segment: Segment) -> Vec<R> {
        let (start, length) = self.extent(segment);
        let zero = length.int(0);
        let pi = length.pi_like();
        // At most two candidates for each of the six turns, and the two ends.
        let mut breaks = Vec::with_capacity(14);
        breaks.push(zero.clone());
        // A candidate outside [0, length] is not a break point: it is not formed in R.
        for (k, normal, mirror) in self.nearby_turns(segment, 0.0) {
            let lowest = pi.clone() * &pi.int(2 * k + 1);
            let mirror = mirror.then(|| self.geometry.theta_c.clone() - &lowest);
            let candidates = normal.then(|| lowest.clone() - start).into_iter().chain(mirror);
            breaks.extend(candidates.filter(|s| *s > zero && s < length).map(split_point));
        }
        breaks.push(length.clone());
        breaks.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        breaks
    }
}

#[cfg(test)]
mod tests {
    use super::super::cycle_at;
    use super::*;
    use crate::compliance::{Compliance, Persson};
    use crate::cycle::LoadCycle;

    /// Persson's v' = 1/P with knots declared at given loads (v' itself stays analytic).
    #[derive(Debug)]
    struct WithKnots {
        inner: Persson<f64>,
        knots: Vec<f64>,
    }

    impl Compliance<f64> for WithKnots {
        fn approach(&self, load: &f64) -> f64 {
            self.inner.approach(load)
        }
        fn slope(&self, load: &f64) -> f64 {
            self.inner.slope(load)
        }
        fn curvature(&self, load: &f64) -> f64 {
            self.inner.curvature(load)
        }
        fn breakpoints(&self, _: &f64) -> Vec<f64> {
            self.knots.clone()
        }
        fn describe(&self) -> String {
            "Persson with knots".into()
        }
    }

    #[test]
    fn knot_crossings_are_where_a_load_of_the_integrand_meets_a_knot() {
        let knots: Vec<f64> = (0..40).map(|i| 0.3 + 0.04 * i as f64).collect();
        let compliance = WithKnots {
            inner: Persson { gamma: 1.0, sigma: 1.0 },
            knots: knots.clone(),
        };
        for phase in [0.1, 0.4, 0.7, 0.95].map(|x| x * std::f64::consts::PI) {
            let g = cycle_at(phase).geometry().expect("valid cycle");
            let integrands = SegmentIntegrands {
                geometry: &g,
                compliance: &compliance,
                remove_constant_slope: true,
            };
            let offsets = knot_offsets(integrands.compliance, &g.mean_normal_load);
            let on_knot = |offset: f64| offsets.iter().any(|x| (x - offset).abs() < 1e-12);
            let mut normal_crossings = 0;
            for segment in Segment::ALL {
                let (start, length) = integrands.extent(segment);
                for s in integrands.knot_crossings(segment, &offsets) {
                    assert!(s > 0.0 && s < *length);
                    let half_sin = ((s - length) / 2.0).sin();
                    let normal = on_knot(g.normal_offset(&(start + s)));
                    let other = match segment {
                        Segment::EB => on_knot(g.reverse_slip_offset(&half_sin)),
                        Segment::CH => on_knot(g.normal_offset(&(g.theta_c - s))),
                        Segment::HE => on_knot(g.forward_slip_offset(&half_sin)),
                        Segment::BC => false,
                    };
                    assert!(normal || other, "segment {segment}, s = {s}: no load on a knot");
                    normal_crossings += usize::from(normal);
                }
            }
            // P = P0 + P1 cos θ meets each knot strictly inside (P0 − P1, P0 + P1) twice a cycle.
            let inside = knots.iter().filter(|&&k| (k - 1.0).abs() < 0.6).count();
            assert_eq!(normal_crossings, 2 * inside, "phase {phase}");
        }
    }

    /// The break points at the lowest loads, with far turns skipped by doubles, are every
    /// angle strictly inside the segment where P (or CH's mirror load) is least, in f64 and
    /// at 200 bits, for phases that put the segments' ends on all sides of those angles.
    #[test]
    fn lowest_load_points_are_every_lowest_load_inside_the_segment() {
        use crate::real::Precision;
        use rug::Float;
        let p = Precision::bits(200);
        let compliance = Persson { gamma: 1.0, sigma: 1.0 };
        let precise_compliance = Persson {
            gamma: Float::from_i64(1, p),
            sigma: Float::from_i64(1, p),
        };
        for phase in [0.05, 0.3, 1.0, 1.6, 2.5, 3.1] {
            let cycle = cycle_at(phase);
            let g = cycle.geometry().expect("valid cycle");
            let precise_cycle = LoadCycle {
                mean_normal_load: Float::from_f64(cycle.mean_normal_load, p),
                normal_amplitude: Float::from_f64(cycle.normal_amplitude, p),
                mean_tangential_load: Float::from_f64(cycle.mean_tangential_load, p),
                tangential_amplitude: Float::from_f64(cycle.tangential_amplitude, p),
                phase: Float::from_f64(phase, p),
                friction: Float::from_f64(cycle.friction, p),
                compliance_ratio: Float::from_i64(1, p),
            };
            let precise_g = precise_cycle.geometry().expect("valid cycle");
            let integrands = SegmentIntegrands {
                geometry: &g,
                compliance: &compliance,
                remove_constant_slope: true,
            };
            let precise = SegmentIntegrands {
                geometry: &precise_g,
                compliance: &precise_compliance,
                remove_constant_slope: true,
            };
            for segment in Segment::ALL {
                let (start, length) = integrands.extent(segment);
                let pi = std::f64::consts::PI;
                let mut expected: Vec<f64> = (-4..=6i64)
                    .flat_map(|k| {
                        let lowest = (2 * k + 1) as f64 * pi;
                        let mirror = (segment == Segment::CH).then_some(g.theta_c - lowest);
                        std::iter::once(lowest - start).chain(mirror)
                    })
                    .filter(|s| *s > 0.0 && s < length)
                    .collect();
                expected.push(0.0);
                expected.push(*length);
                expected.sort_by(f64::total_cmp);
                assert_eq!(
                    integrands.lowest_load_points(segment),
                    expected,
                    "{segment}, φ = {phase}"
                );
                let found: Vec<f64> = precise.lowest_load_points(segment).iter().map(Float::to_f64).collect();
                assert_eq!(found.len(), expected.len(), "{segment}, φ = {phase}: {found:?}");
                for (found, expected) in found.iter().zip(&expected) {
                    assert!(
                        (found - expected).abs() < 1e-12,
                        "{segment}, φ = {phase}: {found} {expected}"
                    );
                }
            }
        }
    }

    #[test]
    fn an_analytic_compliance_gets_no_extra_pieces() {
        let cycle = LoadCycle {
            mean_normal_load: 1.0,
            normal_amplitude: 0.6,
            mean_tangential_load: 0.0,
            tangential_amplitude: 0.3,
            phase: 1.0,
            friction: 0.8,
            compliance_ratio: 1.0,
        };
        let g = cycle.geometry().expect("valid cycle");
        let plain = Persson { gamma: 1.0, sigma: 1.0 };
        let knotted = WithKnots {
            inner: plain.clone(),
            knots: vec![0.7, 1.2],
        };
        let count = |compliance: &dyn Compliance<f64>| {
            SegmentIntegrands {
                geometry: &g,
                compliance,
                remove_constant_slope: true,
            }
            .pieces()
            .pieces
            .len()
        };
        assert!(count(&knotted) > count(&plain));
        let lowest: usize = Segment::ALL
            .into_iter()
            .map(|segment| {
                let integrands = SegmentIntegrands {
                    geometry: &g,
                    compliance: &plain,
                    remove_constant_slope: true,
                };
                integrands.lowest_load_points(segment).len() - 1
            })
            .sum();
        assert!(count(&plain) >= lowest && count(&plain) <= 2 * lowest);
    }
}
