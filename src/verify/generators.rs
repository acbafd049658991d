//! Random admissible compliances and cycles, shared by `microslip verify` and the
//! property tests, so that every suite draws from the same families.
//!
//! Compliances are produced as SPEC strings: the same draw can then be read at
//! any precision (f64 and 256 bits see exactly the same function) and printed in
//! a report. Every draw has v' > 0 and v'' ≤ 0 on the load range it is made for.

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
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [low, high), rounded to 6 significant digits so that the value prints
    /// exactly as the decimal every precision reads.
    pub fn uniform(&mut self, low: f64, high: f64) -> f64 {
        let unit = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        let value = low + (high - low) * unit;
        format!("{value:.6e}").parse().unwrap_or(value)
    }

    /// Uniform in 0..n.
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n.max(1) as u64) as usize
    }
}

/// The compliance families drawn from.
pub const FAMILIES: [&str; 6] = ["power", "power-sum", "persson", "rational", "exponential", "polynomial"];

/// A random admissible compliance SPEC for loads in [low, high] (0 < low < high),
/// with the polynomial family centred on `mean_load`.
pub fn compliance_spec(draw: &mut Draw, low: f64, high: f64, mean_load: f64) -> String {
    match FAMILIES[draw.below(FAMILIES.len())] {
        "power" => power_term(draw),
        "power-sum" => format!("{} + {}", power_term(draw), power_term(draw)),
        "persson" => format!(
            "persson:gamma={},sigma={}",
            draw.uniform(0.5, 2.0),
            draw.uniform(0.01, 1.0)
        ),
        "rational" => format!(
            "rational:a={},b={},c={}",
            draw.uniform(0.0, 1.0),
            draw.uniform(0.1, 5.0),
            draw.uniform(0.0, 1.0)
        ),
        "exponential" => format!(
            "exp:a={},c={},d={}",
            draw.uniform(0.1, 5.0),
            draw.uniform(0.3, 3.0),
            draw.uniform(0.0, 1.0)
        ),
        _ => polynomial(draw, low, high, mean_load),
    }
}

fn power_term(draw: &mut Draw) -> String {
    format!("power:c={},beta={}", draw.uniform(0.1, 10.0), draw.uniform(-2.0, -0.05))
}

/// v' = c0 + c1 x + c2 x², x = P − P0, with c2 < 0 and c1 chosen so that v'' = c1 + 2c2 x
/// is ≤ 0 over the range (it is largest at the lowest load, where c1 ≤ −2c2 x_low), and
/// c0 so that v' > 0 there.
fn polynomial(draw: &mut Draw, low: f64, high: f64, mean_load: f64) -> String {
    let (x_low, x_high) = (low - mean_load, high - mean_load);
    let c2 = -draw.uniform(0.1, 2.0);
    let c1 = -2.0 * c2 * x_low - draw.uniform(0.0, 2.0);
    let c1: f64 = format!("{c1:.6e}").parse().unwrap_or(c1);
    let lowest = [x_low, x_high]
        .iter()
        .map(|x| c1 * x + c2 * x * x)
        .fold(f64::INFINITY, f64::min);
    let c0 = -lowest.min(0.0) + draw.uniform(0.1, 2.0);
    let c0: f64 = format!("{c0:.6e}").parse().unwrap_or(c0);
    format!("poly:p0={mean_load},coeffs={c0};{c1};{c2}")
}

/// A random ratio ρ = Q1/(fP1) and phase φ ∈ (0, π) (as text, `…pi`).
pub fn shape(draw: &mut Draw) -> (f64, f64) {
    (draw.uniform(0.2, 3.0), draw.uniform(0.02, 0.98))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compliance::{check_admissible, parse_spec};
    use crate::real::Precision;

    #[test]
    fn every_family_is_drawn_and_admissible_on_its_range() {
        let mut draw = Draw::new(1);
        let mut seen = std::collections::BTreeSet::new();
        for _ in 0..300 {
            let spec = compliance_spec(&mut draw, 0.05, 1.9, 1.0);
            seen.insert(spec.split(':').next().unwrap().to_string());
            let compliance = parse_spec::<f64>(&spec, Precision::DOUBLE).unwrap();
            check_admissible(compliance.as_ref(), &0.05, &1.9).unwrap_or_else(|e| panic!("{spec}: {e}"));
        }
        assert!(seen.len() >= 5, "{seen:?}");
    }

    #[test]
    fn draws_are_reproducible() {
        let (mut a, mut b) = (Draw::new(42), Draw::new(42));
        for _ in 0..10 {
            assert_eq!(a.next_u64(), b.next_u64());
        }
    }
}
