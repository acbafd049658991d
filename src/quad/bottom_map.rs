//! The change of variable s = c + 2 asin(t sinh u) about the lowest load of a cycle
//! P(θ) = P0 + P1 cos θ near separation (proofs/certified-digits.md, "Near separation").
//!
//! With δ = P0 − P1 > 0 the lowest load, t = √(δ/(2P1)) and θ = π + 2α (α = (s − c)/2,
//! c where θ ≡ π), sin α = t sinh u gives
//!
//! ```text
//! P = P0 − P1 cos 2α = δ + 2P1 sin²α = δ (1 + sinh²u) = δ cosh²u,
//! ds/du = 2 t cosh u / cos α,   cos α = √((1 − t sinh u)(1 + t sinh u)).
//! ```
//!
//! The load is a product, not a difference of nearly equal numbers, so that on an
//! enclosure of u it stays as narrow as u's own relative width, and the zeros of P
//! (cosh u = 0) sit at u = ±iπ/2 whatever δ is: a rule of a fixed size resolves the
//! bottom of the cycle, as the sinh map does, without forming 1 + cos θ.

use super::sinh_map::asinh;
use crate::real::Real;

/// s = c + 2 asin(t sinh u) about one lowest-load point c.
#[derive(Clone, Debug)]
pub struct BottomMap<R> {
    center: R,
    scale: R,
}

/// One point of a [`BottomMap`]: the half-angle α = (s − c)/2 from the lowest load
/// through its sine and cosine, and ds/du.
#[derive(Clone, Debug)]
pub struct BottomPoint<R> {
    /// sin α = t sinh u.
    pub half_sin: R,
    /// cos α > 0.
    pub half_cos: R,
    /// ds/du.
    pub rate: R,
    /// cosh u, whose square times δ is the load the map is centred on.
    pub load_root: R,
}

impl<R: Real> BottomMap<R> {
    /// The map about the lowest load at s = `center`, for lowest load δ = `margin`·P1
    /// (t = √(margin/2)).
    pub fn new(center: R, margin: &R) -> Self {
        let scale = margin.clone().times_power_of_two(-1).sqrt();
        BottomMap { center, scale }
    }

    /// c, where θ ≡ π.
    pub fn center(&self) -> &R {
        &self.center
    }

    /// u = asinh(sin((s − c)/2)/t), the inverse map (for |s − c| < π).
    pub fn to_u(&self, s: &R) -> R {
        let half = (s.clone() - &self.center).times_power_of_two(-1);
        self.to_u_from_half_sin(&half.sin())
    }

    /// u = asinh(sin α/t) from sin α itself, α = (s − c)/2: for a point whose angle from
    /// the lowest load is known more accurately than s − c.
    pub fn to_u_from_half_sin(&self, half_sin: &R) -> R {
        asinh(&(half_sin.clone() / &self.scale))
    }

    /// The half-angle and the rate at u.
    pub fn point(&self, u: &R) -> BottomPoint<R> {
        let (sinh, cosh) = u.sinh_cosh();
        let half_sin = self.scale.clone() * &sinh;
        let one = u.int(1);
        let half_cos = ((one.clone() - &half_sin) * &(one + &half_sin)).sqrt();
        let rate = (self.scale.clone() * &cosh).times_power_of_two(1) / &half_cos;
        BottomPoint {
            half_sin,
            half_cos,
            rate,
            load_root: cosh,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_load_is_the_product_and_the_map_inverts() {
        let (p0, p1) = (1.0f64, 1.0 - 1e-12);
        let margin = (p0 - p1) / p1;
        let map = BottomMap::new(0.0, &margin);
        for u in [-13.0, -2.0, -1e-3, 0.0, 0.5, 4.0, 12.0, 14.0] {
            let point = map.point(&u);
            let alpha = point.half_sin.asin();
            let theta = std::f64::consts::PI + 2.0 * alpha;
            // P − δ = 2P1 sin²α = δ sinh²u, and the angle returns to u.
            let lift = 2.0 * p1 * point.half_sin * point.half_sin;
            let expected = (p0 - p1) * u.sinh().powi(2);
            assert!(
                (lift - expected).abs() <= 1e-14 * expected.max(1e-300),
                "{u}: {lift} {expected}"
            );
            assert!((map.to_u(&(2.0 * alpha)) - u).abs() <= 1e-12 * (1.0 + u.abs()), "{u}");
            assert!((point.half_cos - alpha.cos()).abs() < 1e-15);
            // ds/du by a central difference.
            let h = 1e-6;
            let ds = 2.0 * (map.point(&(u + h)).half_sin.asin() - map.point(&(u - h)).half_sin.asin()) / (2.0 * h);
            assert!((ds - point.rate).abs() <= 1e-6 * point.rate, "{u}: {ds} {}", point.rate);
            assert!(theta.is_finite());
        }
    }
}
