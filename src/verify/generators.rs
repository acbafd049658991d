//! Random admissible compliances and cycles, shared by `microslip verify` and the
//! property tests, so that every suite draws from the same families.
//!
//! Compliances are produced as SPEC strings: the same draw can then be read at
//! any precision (f64 and 256 bits see exactly the same function) and printed in
//! a report. Every draw has v' > 0 and v'' ≤ 0 on the load range it is made for.
//! The families and their parameter ranges are listed once, in [`Family`]: the gate
//! draws them with the seeded [`Draw`], the property tests with proptest strategies
//! (tests/common/strategies.rs) that shrink a failure to a small case.

use crate::case::CaseText;

/// A small seeded generator (SplitMix64): reproducible draws with no dependency.
#[derive(Clone, Debug)]
pub struct Draw {
    state: u64,
}

impl Draw {
    /// A generator started from `seed`.
    pub fn new(seed: u64) -> Self {
        Draw {
            state: seed ^ 0x9E37_79B9_7F4A_7C15,
        }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        mix(self.state)
    }

    /// Uniform in [low, high), rounded to 6 significant digits so that the value prints
    /// exactly as the decimal every precision reads.
    pub fn uniform(&mut self, low: f64, high: f64) -> f64 {
        let unit = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        significant(low + (high - low) * unit)
    }

    /// Uniform in 0..n.
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n.max(1) as u64) as usize
    }

    /// A value of each parameter, in order.
    pub fn parameters(&mut self, ranges: &[Range]) -> Vec<f64> {
        ranges.iter().map(|range| self.uniform(range.low, range.high)).collect()
    }
}

/// SplitMix64's output function: a bijection of the 64-bit words that spreads every
/// input bit over the whole word.
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The seed of the stream named `name` in a run seeded `seed`: the run's seed mixed with
/// a hash of the name (FNV-1a, the same on every platform and build). Each claim draws
/// from its own named stream, so adding or reordering claims leaves every other claim's
/// draws as they were.
pub fn stream_seed(seed: u64, name: &str) -> u64 {
    mix(seed ^ fnv1a(name))
}

/// The 64-bit FNV-1a hash of the text's bytes.
fn fnv1a(text: &str) -> u64 {
    text.bytes().fold(0xCBF2_9CE4_8422_2325, |hash, byte| {
        (hash ^ u64::from(byte)).wrapping_mul(0x0000_0100_0000_01B3)
    })
}

/// `value` rounded to 6 significant digits: a drawn number that prints exactly as the
/// decimal every precision reads.
pub fn significant(value: f64) -> f64 {
    format!("{value:.6e}").parse().unwrap_or(value)
}

/// The interval [low, high) a drawn parameter lies in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Range {
    /// The smallest value.
    pub low: f64,
    /// The bound no value reaches.
    pub high: f64,
}

const fn range(low: f64, high: f64) -> Range {
    Range { low, high }
}

/// The loads a drawn compliance must be admissible over, [low, high] with 0 < low < high,
/// and the mean load a polynomial is centred on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Loads {
    /// The lowest load.
    pub low: f64,
    /// The highest load.
    pub high: f64,
    /// The mean normal load P0.
    pub mean: f64,
}

/// The compliance families drawn from, simplest first (a shrinking property test
/// moves towards the first).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Family {
    /// v' = c P^β, β < 0.
    Power,
    /// The sum of two power laws.
    PowerSum,
    /// Persson's v' = γσ/P.
    Persson,
    /// A rational compliance.
    Rational,
    /// An exponential compliance.
    Exponential,
    /// A quadratic v' around P0, decreasing and positive over the loads.
    Polynomial,
}

const POWER: [Range; 2] = [range(0.1, 10.0), range(-2.0, -0.05)];

impl Family {
    /// Every family, in the order the gate's draw indexes them.
    pub const ALL: [Family; 6] = [
        Family::Power,
        Family::PowerSum,
        Family::Persson,
        Family::Rational,
        Family::Exponential,
        Family::Polynomial,
    ];

    /// The family's name.
    pub fn name(self) -> &'static str {
        match self {
            Family::Power => "power",
            Family::PowerSum => "power-sum",
            Family::Persson => "persson",
            Family::Rational => "rational",
            Family::Exponential => "exponential",
            Family::Polynomial => "polynomial",
        }
    }

    /// The ranges of the parameters drawn, in the order [`Family::spec`] takes them. Every
    /// value in them gives v' > 0 and v'' ≤ 0 over the loads (the polynomial's are margins,
    /// see [`Family::spec`]).
    pub fn parameters(self) -> &'static [Range] {
        const POWER_SUM: [Range; 4] = [POWER[0], POWER[1], POWER[0], POWER[1]];
        // γ, σ.
        const PERSSON: [Range; 2] = [range(0.5, 2.0), range(0.01, 1.0)];
        const RATIONAL: [Range; 3] = [range(0.0, 1.0), range(0.1, 5.0), range(0.0, 1.0)];
        const EXPONENTIAL: [Range; 3] = [range(0.1, 5.0), range(0.3, 3.0), range(0.0, 1.0)];
        // −c2, the margin of c1 below −2c2 x_low, the margin of v' above 0.
        const POLYNOMIAL: [Range; 3] = [range(0.1, 2.0), range(0.0, 2.0), range(0.1, 2.0)];
        match self {
            Family::Power => &POWER,
            Family::PowerSum => &POWER_SUM,
            Family::Persson => &PERSSON,
            Family::Rational => &RATIONAL,
            Family::Exponential => &EXPONENTIAL,
            Family::Polynomial => &POLYNOMIAL,
        }
    }

    /// The SPEC of the member with parameters `values` (one per [`Family::parameters`]),
    /// admissible over `loads`.
    pub fn spec(self, values: &[f64], loads: Loads) -> String {
        match self {
            Family::Power => power_term(values),
            Family::PowerSum => format!("{} + {}", power_term(&values[..2]), power_term(&values[2..])),
            Family::Persson => format!("persson:gamma={},sigma={}", values[0], values[1]),
            Family::Rational => format!("rational:a={},b={},c={}", values[0], values[1], values[2]),
            Family::Exponential => format!("exp:a={},c={},d={}", values[0], values[1], values[2]),
            Family::Polynomial => polynomial(values, loads),
        }
    }
}

/// A random admissible compliance SPEC for loads in [low, high] (0 < low < high),
/// with the polynomial family centred on `mean_load`.
pub fn compliance_spec(draw: &mut Draw, low: f64, high: f64, mean_load: f64) -> String {
    let family = Family::ALL[draw.below(Family::ALL.len())];
    let values = draw.parameters(family.parameters());
    let loads = Loads {
        low,
        high,
        mean: mean_load,
    };
    family.spec(&values, loads)
}

fn power_term(values: &[f64]) -> String {
    format!("power:c={},beta={}", values[0], values[1])
}

/// v' = c0 + c1 x + c2 x², x = P − P0, with c2 < 0 and c1 chosen so that v'' = c1 + 2c2 x
/// is ≤ 0 over the range (it is largest at the lowest load, where c1 ≤ −2c2 x_low), and
/// c0 so that v' > 0 there.
fn polynomial(values: &[f64], loads: Loads) -> String {
    let (x_low, x_high) = (loads.low - loads.mean, loads.high - loads.mean);
    let c2 = -values[0];
    let c1 = significant(-2.0 * c2 * x_low - values[1]);
    let lowest = [x_low, x_high]
        .iter()
        .map(|x| c1 * x + c2 * x * x)
        .fold(f64::INFINITY, f64::min);
    let c0 = significant(-lowest.min(0.0) + values[2]);
    format!("poly:p0={},coeffs={c0};{c1};{c2}", loads.mean)
}

/// The ranges of a random ratio ρ = Q1/(fP1) and phase fraction φ/π ∈ (0, 1).
pub const SHAPE: [Range; 2] = [range(0.2, 3.0), range(0.02, 0.98)];

/// A random ratio ρ = Q1/(fP1) and phase φ/π ∈ (0, 1), as numbers.
pub fn shape(draw: &mut Draw) -> (f64, f64) {
    (
        draw.uniform(SHAPE[0].low, SHAPE[0].high),
        draw.uniform(SHAPE[1].low, SHAPE[1].high),
    )
}

/// The ranges of a random cycle's parameters, in the order [`cycle_case`] takes them:
/// P1/P0, f, λ, φ/π, and Q1 as a fraction of the largest amplitude the friction cone
/// allows ([`gross_slip_amplitude`]).
pub const CYCLE: [Range; 5] = [
    range(0.05, 0.9),
    range(0.2, 2.0),
    range(1.0, 1.5),
    range(0.02, 0.98),
    range(0.1, 0.9),
];

/// The largest Q1 that keeps the ellipse of (P0, P1, φ) inside the friction cone with
/// Q0 = 0: σ± < fP0 ⇔ Q1 < f(√(P0² − P1² sin²φ) − P1|cos φ|).
pub fn gross_slip_amplitude(p0: f64, p1: f64, phi: f64, friction: f64) -> f64 {
    friction * ((p0 * p0 - (p1 * phi.sin()).powi(2)).sqrt() - p1 * phi.cos().abs())
}

/// The cycle with P0 = 1, Q0 = 0 and parameters `values` (one per [`CYCLE`]), inside the
/// gross-slip and separation limits, with the compliance `compliance` gives for the loads
/// the cycle reaches.
pub fn cycle_case(values: &[f64], compliance: impl FnOnce(Loads) -> String) -> CaseText {
    let [p1, f, lambda, phase_fraction, amplitude_fraction] = values[..5] else {
        unreachable!("a cycle has five parameters")
    };
    let phi = phase_fraction * std::f64::consts::PI;
    let q1 = significant(amplitude_fraction * gross_slip_amplitude(1.0, p1, phi, f));
    // P_T ≥ P0 − (Q1 + fP1)/f: the compliance must be admissible from there.
    let low = (1.0 - p1).min(1.0 - (q1 + f * p1) / f).max(1e-3);
    let loads = Loads {
        low: low * 0.9,
        high: 1.0 + p1,
        mean: 1.0,
    };
    CaseText {
        p0: "1".into(),
        p1: p1.to_string(),
        q0: "0".into(),
        q1: q1.to_string(),
        phi: format!("{phase_fraction}pi"),
        friction: f.to_string(),
        lambda: Some(lambda.to_string()),
        nu: None,
        compliance: compliance(loads),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compliance::{check_admissible, ComplianceSpec};
    use crate::real::Precision;

    #[test]
    fn every_family_is_drawn_and_admissible_on_its_range() {
        let mut draw = Draw::new(1);
        let mut seen = std::collections::BTreeSet::new();
        for _ in 0..300 {
            let spec = compliance_spec(&mut draw, 0.05, 1.9, 1.0);
            seen.insert(spec.split(':').next().unwrap().to_string());
            let compliance = ComplianceSpec::parse(&spec)
                .unwrap()
                .build::<f64>(Precision::DOUBLE)
                .unwrap();
            check_admissible(compliance.as_ref(), &0.05, &1.9).unwrap_or_else(|e| panic!("{spec}: {e}"));
        }
        assert!(seen.len() >= 5, "{seen:?}");
    }

    #[test]
    fn the_generator_is_splitmix64_and_names_hash_by_fnv1a() {
        // Published values: SplitMix64's first output from state 0, and FNV-1a of "" and "a".
        assert_eq!(Draw::new(0x9E37_79B9_7F4A_7C15).next_u64(), 0xE220_A839_7B1D_CDAF);
        assert_eq!(fnv1a(""), 0xCBF2_9CE4_8422_2325);
        assert_eq!(fnv1a("a"), 0xAF63_DC4C_8601_EC8C);
    }

    #[test]
    fn each_name_has_its_own_stream_and_a_name_draws_the_same_in_every_run_of_a_seed() {
        let names = ["cubic law", "linearity at f64", "linearity at 256 bits", "series"];
        let seeds: std::collections::BTreeSet<u64> = names.iter().map(|name| stream_seed(2026, name)).collect();
        assert_eq!(seeds.len(), names.len());
        assert_eq!(stream_seed(2026, "series"), stream_seed(2026, "series"));
        assert_ne!(stream_seed(2026, "series"), stream_seed(2027, "series"));
    }

    #[test]
    fn draws_are_reproducible() {
        let (mut a, mut b) = (Draw::new(42), Draw::new(42));
        for _ in 0..10 {
            assert_eq!(a.next_u64(), b.next_u64());
        }
    }
}
