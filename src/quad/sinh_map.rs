//! The change of variable s = c + w·sinh u, which resolves a narrow peak of an
//! integrand at c.
//!
//! An integrand whose nearest singularities sit at c ± iw, w small against the
//! interval, makes Gauss–Legendre rules converge only after their nodes crowd within
//! w of c: the points needed grow like a power of 1/w. In u the same singularities sit
//! at ±iπ/2 whatever w is, while the interval grows only to about ln(2L/w), so a rule
//! of a fixed size resolves the peak and the cost grows like ln(1/w). A peak nearer to
//! an end of the interval than w is resolved the same way, and one far from the
//! interval stays harmless (the map is then nearly exponential across the interval).

use crate::real::Real;

/// A narrow peak of an integrand: its centre c and half-width w (the distance of its
/// singularities from the real axis).
#[derive(Clone, Debug)]
pub struct Peak<R> {
    /// c, where the peak is highest (it may lie outside the interval).
    pub center: R,
    /// w > 0.
    pub width: R,
}

/// s = c + w·sinh u for one peak.
#[derive(Clone, Debug)]
pub struct SinhMap<R> {
    peak: Peak<R>,
}

/// A sub-interval [start, end] of an integral, in s when `map` is `None` and in u when
/// it is the map that resolves the peak at its end.
#[derive(Clone, Debug)]
pub struct Resolved<R> {
    /// Lower limit (in u when mapped).
    pub start: R,
    /// Upper limit (in u when mapped).
    pub end: R,
    /// The change of variable to apply, if any.
    pub map: Option<SinhMap<R>>,
    /// The sub-interval in s.
    pub window: (R, R),
    /// The index in the peaks given of the one whose centre the map takes.
    pub peak: Option<usize>,
}

/// Peaks narrower than this fraction of the interval, and that near it, are mapped.
const NARROW: i64 = 4;

impl<R: Real> SinhMap<R> {
    /// The map for one peak.
    pub fn new(peak: Peak<R>) -> Self {
        SinhMap { peak }
    }

    /// u = asinh((s − c)/w), the inverse map.
    pub fn to_u(&self, s: &R) -> R {
        asinh(&((s.clone() - &self.peak.center) / &self.peak.width))
    }

    /// (s, ds/du) = (c + w·sinh u, w·cosh u).
    pub fn point_and_rate(&self, u: &R) -> (R, R) {
        let (sinh, cosh) = u.sinh_cosh();
        // The same operations as c + w·sinh u and w·cosh u (both commute exactly), with
        // no copies of c and w.
        (sinh * &self.peak.width + &self.peak.center, cosh * &self.peak.width)
    }
}

/// asinh x = ln(1 + x + x²/(1 + √(1 + x²))) for x ≥ −1/2, accurate for small and
/// large x (ln 2x where x² would overflow), and −asinh(−x) below. The form needs no sign
/// of x near 0, where a mapped piece ends at its peak's centre (u = 0): on enclosures of
/// an end and a centre that are the same number the sign of their difference is never
/// decided, and asinh, odd and smooth, does not need it.
pub fn asinh<R: Real>(x: &R) -> R {
    if *x < x.ratio(-1, 2) {
        return -asinh(&-x.clone());
    }
    let (one, square) = (x.int(1), x.square());
    if square.is_finite() {
        (x.clone() + &(square.clone() / &((square + &one).sqrt() + &one))).ln_1p()
    } else {
        x.ln() + &x.int(2).ln()
    }
}

/// acosh(1 + x) = ln(1 + x + √(x(2 + x))) for x ≥ 0, accurate for small x.
pub fn acosh_one_plus<R: Real>(x: &R) -> R {
    (x.clone() + &(x.clone() * &(x.clone() + &x.int(2))).sqrt()).ln_1p()
}

/// [a, b] split so that each part has at most one narrow peak near it, at one of its
/// ends, and mapped to resolve that peak. A peak counts when its width plus its
/// distance from [a, b] is under a quarter of b − a; where such peaks lie toward both
/// ends the interval is split midway between the innermost of them. Of several peaks
/// toward one end the innermost centres the map and the narrowest sets its width (a
/// narrower width than a peak's own still resolves it, at a slightly longer interval in u).
pub fn resolve_peaks<R: Real>(a: &R, b: &R, peaks: &[Peak<R>]) -> Vec<Resolved<R>> {
    let length = b.clone() - a;
    let limit = length.clone() / &length.int(NARROW);
    let middle = (a.clone() + b) / &a.int(2);
    let zero = a.int(0);
    // The peak each end's map takes, with the index of the one whose centre it keeps.
    let mut toward_start: Option<(Peak<R>, usize)> = None;
    let mut toward_end: Option<(Peak<R>, usize)> = None;
    let (start, end, span) = (a.to_f64_lossy(), b.to_f64_lossy(), length.to_f64_lossy());
    for (index, peak) in peaks.iter().enumerate() {
        // A centre farther outside [a, b] than its length, by a double's reckoning, is not
        // within a quarter of it (the test below): skipped without the arithmetic of R,
        // which on balls costs more than the rest of the planning. Rounding to doubles
        // cannot move a distance by three quarters of the length, and a NaN skips nothing.
        let center = peak.center.to_f64_lossy();
        if start - center > span || center - end > span {
            continue;
        }
        let outside = (a.clone() - &peak.center)
            .max_of(&(peak.center.clone() - b))
            .max_of(&zero);
        let narrow = peak.width > zero && outside + &peak.width < limit;
        if !narrow {
            continue;
        }
        let (side, start_side) = if peak.center < middle {
            (&mut toward_start, true)
        } else {
            (&mut toward_end, false)
        };
        *side = Some(match side.take() {
            None => (peak.clone(), index),
            Some((held, held_index)) => {
                let (inner, inner_index) = if (peak.center > held.center) == start_side {
                    (&peak.center, index)
                } else {
                    (&held.center, held_index)
                };
                let merged = Peak {
                    center: inner.clone(),
                    width: held.width.min_of(&peak.width),
                };
                (merged, inner_index)
            }
        });
    }
    let mapped = |start: &R, end: &R, (peak, index): (Peak<R>, usize)| {
        let map = SinhMap::new(peak);
        Resolved {
            start: map.to_u(start),
            end: map.to_u(end),
            map: Some(map),
            window: (start.clone(), end.clone()),
            peak: Some(index),
        }
    };
    match (toward_start, toward_end) {
        (None, None) => vec![Resolved {
            start: a.clone(),
            end: b.clone(),
            map: None,
            window: (a.clone(), b.clone()),
            peak: None,
        }],
        (Some(peak), None) => vec![mapped(a, b, peak)],
        (None, Some(peak)) => vec![mapped(a, b, peak)],
        (Some(first), Some(last)) => {
            let split = (first.0.center.clone() + &last.0.center) / &a.int(2);
            vec![mapped(a, &split, first), mapped(&split, b, last)]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quad::gauss_legendre::node_table;
    use crate::real::Precision;

    #[test]
    fn map_and_inverse_agree() {
        let map = SinhMap::new(Peak {
            center: 1.0f64,
            width: 1e-6,
        });
        for s in [1.0 - 1e-3, 1.0 - 1e-9, 1.0, 1.0 + 1e-7, 3.0] {
            let (back, rate) = map.point_and_rate(&map.to_u(&s));
            assert!((back - s).abs() <= 4.0 * f64::EPSILON * (s.abs() + 1e-6), "{s}: {back}");
            assert!(rate >= 1e-6);
        }
        assert!((asinh(&-2.5f64) + 2.5f64.asinh()).abs() < 1e-15);
        assert!((asinh(&1e200f64) - 1e200f64.asinh()).abs() < 1e-12);
        assert!((acosh_one_plus(&1e-20f64) - 2e-20f64.sqrt()).abs() < 1e-25);
    }

    #[test]
    fn a_peak_of_width_1e_12_takes_a_small_rule() {
        // ∫₀¹ w/(s² + w²) ds = atan(1/w): a Lorentzian peak at the start.
        let w = 1e-12f64;
        let peaks = [Peak { center: 0.0, width: w }];
        let parts = resolve_peaks(&0.0, &1.0, &peaks);
        assert_eq!(parts.len(), 1);
        let table = node_table::<f64>(128, Precision::DOUBLE);
        let part = &parts[0];
        let map = part.map.as_ref().unwrap();
        let value = table.integrate(
            |u: &f64| {
                let (s, rate) = map.point_and_rate(u);
                w / (s * s + w * w) * rate
            },
            &part.start,
            &part.end,
        );
        assert!((value - (1.0 / w).atan()).abs() < 1e-14, "{value}");
    }

    #[test]
    fn peaks_toward_both_ends_split_the_interval() {
        let peaks = [
            Peak {
                center: -1e-9,
                width: 1e-6,
            },
            Peak {
                center: 2.0,
                width: 1e-3,
            },
            Peak {
                center: 2.0 + 1e-4,
                width: 1e-5,
            },
            Peak {
                center: 0.5,
                width: 1.0,
            },
        ];
        let parts = resolve_peaks(&0.0, &2.0, &peaks);
        assert_eq!(parts.len(), 2);
        assert_eq!((parts[0].peak, parts[1].peak), (Some(0), Some(1)));
        let (first, last) = (parts[0].map.as_ref().unwrap(), parts[1].map.as_ref().unwrap());
        assert_eq!((first.peak.center, first.peak.width), (-1e-9, 1e-6));
        assert_eq!((last.peak.center, last.peak.width), (2.0, 1e-5));
        assert!((first.point_and_rate(&parts[0].end).0 - (2.0 - 1e-9) / 2.0).abs() < 1e-15);
        assert!(resolve_peaks(&0.0, &2.0, &peaks[3..]).iter().all(|p| p.map.is_none()));
    }

    /// Which peak takes [1, 3] with a narrow peak at `center` (and one always too far).
    fn chosen<R: Real>(center: f64, precision: Precision) -> Option<usize> {
        let at = |x: f64| R::from_f64(x, precision);
        let peaks = [
            Peak {
                center: at(-7.0),
                width: at(1e-9),
            },
            Peak {
                center: at(center),
                width: at(1e-9),
            },
        ];
        let parts = resolve_peaks(&at(1.0), &at(3.0), &peaks);
        assert_eq!(parts.len(), 1);
        parts[0].peak
    }

    #[test]
    fn a_peak_is_mapped_up_to_a_quarter_length_outside_in_every_type() {
        // The window [1, 3] maps a narrow peak whose centre lies within half a unit of it
        // (outside + width < 2/4); the doubles' shortcut skips only centres more than a
        // length outside, so the same peaks are taken in f64, MPFR and on balls.
        for (center, taken) in [
            (0.5 + 1e-6, Some(1)),
            (0.5 - 1e-6, None),
            (3.5 - 1e-6, Some(1)),
            (5.5, None),
        ] {
            assert_eq!(chosen::<f64>(center, Precision::DOUBLE), taken, "f64, {center}");
            assert_eq!(
                chosen::<rug::Float>(center, Precision::bits(200)),
                taken,
                "MPFR, {center}"
            );
            #[cfg(feature = "certified")]
            assert_eq!(
                chosen::<crate::ball::Ball>(center, Precision::bits(128)),
                taken,
                "ball, {center}"
            );
        }
    }
}
