//! Trigonometric polynomials a₀ + Σₖ (aₖ cos kθ + bₖ sin kθ) with coefficients of any
//! [`Real`] type: products and exact integrals between two angles.
//!
//! Along a harmonic load cycle every load is a trigonometric polynomial of degree one
//! in the cycle angle, so for a polynomial compliance every segment integrand of W is
//! a trigonometric polynomial, and its integral is a finite sum of sines and cosines
//! of the segment's end angles: no quadrature error.

use crate::real::Real;

/// a₀ + Σₖ (aₖ cos kθ + bₖ sin kθ), k = 1 … degree.
#[derive(Clone, Debug, PartialEq)]
pub struct TrigPolynomial<R> {
    /// aₖ, k = 0 … degree.
    cos: Vec<R>,
    /// bₖ, k = 0 … degree (b₀ = 0).
    sin: Vec<R>,
}

impl<R: Real> TrigPolynomial<R> {
    /// The constant `value`.
    pub fn constant(value: R) -> Self {
        let zero = value.int(0);
        TrigPolynomial {
            cos: vec![value],
            sin: vec![zero],
        }
    }

    /// c + a cos θ + b sin θ.
    pub fn linear(constant: R, cos: R, sin: R) -> Self {
        let zero = constant.int(0);
        TrigPolynomial {
            cos: vec![constant, cos],
            sin: vec![zero, sin],
        }
    }

    /// The highest frequency present in the representation.
    pub fn degree(&self) -> usize {
        self.cos.len() - 1
    }

    /// aₖ, the coefficient of cos kθ (a₀ the constant); 0 beyond the degree.
    pub fn cos_coefficient(&self, k: usize) -> R {
        self.cos.get(k).cloned().unwrap_or_else(|| self.cos[0].int(0))
    }

    /// bₖ, the coefficient of sin kθ; 0 for k = 0 and beyond the degree.
    pub fn sin_coefficient(&self, k: usize) -> R {
        self.sin.get(k).cloned().unwrap_or_else(|| self.cos[0].int(0))
    }

    fn zero_of_degree(degree: usize, like: &R) -> Self {
        TrigPolynomial {
            cos: vec![like.int(0); degree + 1],
            sin: vec![like.int(0); degree + 1],
        }
    }

    /// The value at θ.
    pub fn value_at(&self, theta: &R) -> R {
        let mut total = self.cos[0].clone();
        for k in 1..=self.degree() {
            let (sin, cos) = (theta.clone() * &theta.int(k as i64)).sin_cos();
            total += self.cos[k].clone() * &cos + &(self.sin[k].clone() * &sin);
        }
        total
    }

    /// `self` + `other`.
    pub fn plus(&self, other: &Self) -> Self {
        let like = &self.cos[0];
        let mut sum = Self::zero_of_degree(self.degree().max(other.degree()), like);
        for part in [self, other] {
            for k in 0..=part.degree() {
                sum.cos[k] += &part.cos[k];
                sum.sin[k] += &part.sin[k];
            }
        }
        sum
    }

    /// `factor` × `self`.
    pub fn scaled(&self, factor: &R) -> Self {
        TrigPolynomial {
            cos: self.cos.iter().map(|c| c.clone() * factor).collect(),
            sin: self.sin.iter().map(|s| s.clone() * factor).collect(),
        }
    }

    /// `self` × `other`, by the product-to-sum formulas.
    pub fn times(&self, other: &Self) -> Self {
        let like = &self.cos[0];
        let mut product = Self::zero_of_degree(self.degree() + other.degree(), like);
        let half = like.ratio(1, 2);
        for j in 0..=self.degree() {
            let (aj, bj) = (self.cos[j].clone() * &half, self.sin[j].clone() * &half);
            for k in 0..=other.degree() {
                let (ak, bk) = (&other.cos[k], &other.sin[k]);
                let (sum, difference) = (j + k, j.abs_diff(k));
                // cos j cos k = ½[cos(j+k) + cos(j−k)],  sin j sin k = ½[cos(j−k) − cos(j+k)],
                // sin j cos k = ½[sin(j+k) + sin(j−k)],  cos j sin k = ½[sin(j+k) − sin(j−k)].
                let cos_cos = aj.clone() * ak;
                let sin_sin = bj.clone() * bk;
                let sin_cos = bj.clone() * ak;
                let cos_sin = aj.clone() * bk;
                product.cos[sum] += cos_cos.clone() - &sin_sin;
                product.cos[difference] += cos_cos + &sin_sin;
                product.sin[sum] += sin_cos.clone() + &cos_sin;
                // sin(j − k) = ±sin|j − k|, and 0 for j = k.
                if j > k {
                    product.sin[difference] += sin_cos - &cos_sin;
                } else if k > j {
                    product.sin[difference] += cos_sin - &sin_cos;
                }
            }
        }
        product
    }

    /// ∫ from `start` to `start + length` dθ, exactly (see [`Interval`]).
    pub fn integral(&self, start: &R, length: &R) -> R {
        self.integral_over(&Interval::new(start, length, self.degree()))
    }

    /// ∫ over a prepared interval (which must reach this polynomial's degree).
    pub fn integral_over(&self, interval: &Interval<R>) -> R {
        let mut total = self.cos[0].clone() * &interval.length;
        for k in 1..=self.degree() {
            total += (self.cos[k].clone() * &interval.cos_integrals[k])
                + &(self.sin[k].clone() * &interval.sin_integrals[k]);
        }
        total
    }

    /// The sum of the coefficients' magnitudes: a bound on |value| anywhere, and the
    /// scale against which rounding in products and integrals is measured.
    pub fn magnitude(&self) -> R {
        let zero = self.cos[0].int(0);
        self.cos.iter().chain(&self.sin).fold(zero, |acc, c| acc + &c.abs())
    }
}

/// An interval of angles with the integrals of cos kθ and sin kθ over it, k ≤ a degree:
/// ∫ cos kθ = (2/k) cos(k m) sin(k L/2) and ∫ sin kθ = (2/k) sin(k m) sin(k L/2), with m
/// the middle and L the length, so that short intervals do not cancel.
#[derive(Clone, Debug)]
pub struct Interval<R> {
    length: R,
    cos_integrals: Vec<R>,
    sin_integrals: Vec<R>,
}

impl<R: Real> Interval<R> {
    /// [start, start + length], for trigonometric polynomials up to `degree`.
    pub fn new(start: &R, length: &R, degree: usize) -> Self {
        let two = length.int(2);
        let middle = start.clone() + &(length.clone() / &two);
        let (mut cos_integrals, mut sin_integrals) = (vec![length.int(0)], vec![length.int(0)]);
        for k in 1..=degree {
            let kk = length.int(k as i64);
            let (sin_m, cos_m) = (middle.clone() * &kk).sin_cos();
            let weight = (length.clone() * &kk / &two).sin() * &two / &kk;
            cos_integrals.push(cos_m * &weight);
            sin_integrals.push(sin_m * &weight);
        }
        Interval {
            length: length.clone(),
            cos_integrals,
            sin_integrals,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn products_and_integrals_match_pointwise_values_and_quadrature() {
        let p = TrigPolynomial::linear(0.3, -1.2, 0.7);
        let q = TrigPolynomial::linear(-0.5, 0.4, 2.0).times(&TrigPolynomial::linear(1.0, 0.0, -0.25));
        let product = p.times(&q).plus(&p.scaled(&3.0));
        for theta in [-2.0, 0.1, 1.3, 4.0] {
            let direct = p.value_at(&theta) * q.value_at(&theta) + 3.0 * p.value_at(&theta);
            assert!((product.value_at(&theta) - direct).abs() < 1e-13, "{theta}");
        }
        // Simpson's rule with many points against the exact integral.
        let (start, length) = (0.4, 2.3);
        let n = 2000;
        let h = length / n as f64;
        let mut simpson = product.value_at(&start) + product.value_at(&(start + length));
        for i in 1..n {
            simpson += if i % 2 == 1 { 4.0 } else { 2.0 } * product.value_at(&(start + i as f64 * h));
        }
        simpson *= h / 3.0;
        assert!((product.integral(&start, &length) - simpson).abs() < 1e-11);
        assert_eq!(product.degree(), 3);
    }
}
