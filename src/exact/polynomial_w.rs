//! W for a polynomial v' with no quadrature: every segment integrand is a
//! trigonometric polynomial in the cycle angle θ (proofs/series.md).
//!
//! With x = P − P0 = P1 cos θ and Q − Q0 = Q1 cos(θ − φ), the loads that govern the
//! segments are, in θ (f the friction coefficient):
//!
//! ```text
//! EB  P_S − P0 = −σ₋/(2f) − σ₊/(2f)·cos(θ − θ_B)
//! CH  P_Y − P0 = P1 cos(2θ_C − θ)
//! HE  P_K − P0 = −σ₊/(2f) − σ₋/(2f)·cos(θ − θ_E)
//! ```
//!
//! each of degree one in (cos θ, sin θ), as are P', Q', sin(θ − θ_B) and sin(θ − θ_E).
//! For v' = xⁿ the integrand of a segment is a sum of terms weight(θ)·load(θ)ⁿ with a
//! weight of degree two, integrated exactly by [`TrigPolynomial::integral_over`].

use super::trig::{Interval, TrigPolynomial};
use crate::compliance::Polynomial;
use crate::cycle::{CycleError, EllipseGeometry, LoadCycle};
use crate::dissipation::Segments;
use crate::real::Real;

/// One term weight·loadⁿ of a segment integrand.
pub(super) struct Term<R> {
    pub(super) weight: TrigPolynomial<R>,
    pub(super) load: TrigPolynomial<R>,
}

/// The integrand terms and the θ interval of each segment, per unit λ.
pub(super) fn segment_terms<R: Real>(g: &EllipseGeometry<R>) -> [(Vec<Term<R>>, R, R); 4] {
    let zero = g.phase.int(0);
    let two_f = g.friction.clone() * &zero.int(2);
    let (phase_sin, phase_cos) = &g.phase_sin_cos;
    let q1 = &g.tangential_amplitude;
    let tangential = TrigPolynomial::linear(zero.clone(), q1.clone() * phase_cos, q1.clone() * phase_sin);
    let tangential_rate = TrigPolynomial::linear(zero.clone(), q1.clone() * phase_sin, -(q1.clone() * phase_cos));
    let normal = TrigPolynomial::linear(zero.clone(), g.normal_amplitude.clone(), zero.clone());
    // f·(Q − Q0)·P' with P' = −P1 sin θ.
    let normal_work = tangential.times(&TrigPolynomial::linear(
        zero.clone(),
        zero.clone(),
        -(g.friction.clone() * &g.normal_amplitude),
    ));
    let (b_sin, b_cos) = &g.theta_b_sin_cos;
    let (e_sin, e_cos) = &g.theta_e_sin_cos;
    // sin(θ − θ_B) and sin(θ − θ_E).
    let from_b = TrigPolynomial::linear(zero.clone(), -b_sin.clone(), b_cos.clone());
    let from_e = TrigPolynomial::linear(zero.clone(), -e_sin.clone(), e_cos.clone());
    let (plus, minus) = (&g.sum_amplitude, &g.difference_amplitude);
    let reverse_load = TrigPolynomial::linear(
        -(minus.clone() / &two_f),
        -(plus.clone() / &two_f * b_cos),
        -(plus.clone() / &two_f * b_sin),
    );
    let forward_load = TrigPolynomial::linear(
        -(plus.clone() / &two_f),
        -(minus.clone() / &two_f * e_cos),
        -(minus.clone() / &two_f * e_sin),
    );
    // cos(2θ_C − θ) = cos 2θ_C cos θ + sin 2θ_C sin θ.
    let (c_sin, c_cos) = &g.theta_c_sin_cos;
    let double_c_cos = c_cos.square() - &c_sin.square();
    let double_c_sin = c_sin.clone() * c_cos * &zero.int(2);
    let mirror_load = TrigPolynomial::linear(
        zero.clone(),
        g.normal_amplitude.clone() * &double_c_cos,
        g.normal_amplitude.clone() * &double_c_sin,
    );
    let minus_one = zero.int(-1);
    let term = |weight: TrigPolynomial<R>, load: &TrigPolynomial<R>| Term {
        weight,
        load: load.clone(),
    };
    let slip_forward = |load: &TrigPolynomial<R>| term(tangential.times(&from_e).scaled(&-minus.clone()), load);
    [
        (
            vec![
                term(normal_work.scaled(&minus_one), &normal),
                term(tangential.times(&from_b).scaled(plus), &reverse_load),
            ],
            g.theta_e.clone(),
            g.slip_angle.clone(),
        ),
        (
            vec![term(tangential.times(&tangential_rate), &normal)],
            g.theta_b.clone(),
            g.stick_angle.clone(),
        ),
        (
            vec![term(normal_work.clone(), &normal), slip_forward(&mirror_load)],
            g.theta_c.clone(),
            g.stick_angle.clone(),
        ),
        (
            vec![term(normal_work.clone(), &normal), slip_forward(&forward_load)],
            g.theta_h.clone(),
            g.slip_angle.clone(),
        ),
    ]
}

/// W[v' = (P − P0)ⁿ] per unit λ for n = 0 … `order`, segment by segment (index n).
/// W\[1\] vanishes by the constant-term theorem; its computed value is rounding.
pub fn monomial_dissipations<R: Real>(geometry: &EllipseGeometry<R>, order: usize) -> Vec<Segments<R>> {
    monomials_with_scale(geometry, order).0
}

/// [`monomial_dissipations`] with, for each n, a bound on the magnitudes of the terms
/// summed (Σ |coefficients| × 2π over every term): their rounding is a few ulps of it.
pub(super) fn monomials_with_scale<R: Real>(geometry: &EllipseGeometry<R>, order: usize) -> (Vec<Segments<R>>, Vec<R>) {
    let zero = geometry.phase.int(0);
    let turn = zero.pi_like() * &zero.int(2);
    let mut per_segment: Vec<Vec<R>> = Vec::with_capacity(4);
    let mut scales = vec![zero.clone(); order + 1];
    for (terms, start, length) in segment_terms(geometry) {
        // Weights of degree 2, loads of degree 1: the integrands reach degree order + 2.
        let interval = Interval::new(&start, &length, order + 2);
        let mut values = vec![zero.clone(); order + 1];
        for Term { weight, load } in terms {
            let mut integrand = weight;
            for (value, scale) in values.iter_mut().zip(scales.iter_mut()) {
                *value += &integrand.integral_over(&interval);
                *scale += &(integrand.magnitude() * &turn);
                integrand = integrand.times(&load);
            }
        }
        per_segment.push(values);
    }
    let segments = (0..=order)
        .map(|n| Segments {
            eb: per_segment[0][n].clone(),
            bc: per_segment[1][n].clone(),
            ch: per_segment[2][n].clone(),
            he: per_segment[3][n].clone(),
        })
        .collect();
    (segments, scales)
}

/// The coefficients of a polynomial v' re-expanded about P0: v' = Σ dₖ (P − P0)^k,
/// by repeated synthetic division (Taylor shift).
pub fn coefficients_about<R: Real>(polynomial: &Polynomial<R>, mean_load: &R) -> Vec<R> {
    let shift = mean_load.clone() - &polynomial.reference;
    let mut coefficients = polynomial.coefficients.clone();
    let degree = coefficients.len();
    for i in 0..degree {
        for k in (i..degree - 1).rev() {
            let carried = coefficients[k + 1].clone() * &shift;
            coefficients[k] += &carried;
        }
    }
    coefficients
}

/// W for a polynomial compliance, exactly (up to rounding), with its segments: the
/// segments are those of v' − v'(P0), as the four-segment quadrature reports them.
pub fn polynomial_dissipation<R: Real>(
    cycle: &LoadCycle<R>,
    polynomial: &Polynomial<R>,
) -> Result<Segments<R>, CycleError> {
    let geometry = cycle.geometry()?;
    let coefficients = coefficients_about(polynomial, &cycle.mean_normal_load);
    let zero = cycle.mean_normal_load.int(0);
    if cycle.tangential_amplitude == zero {
        let nothing = || zero.clone();
        return Ok(Segments {
            eb: nothing(),
            bc: nothing(),
            ch: nothing(),
            he: nothing(),
        });
    }
    let monomials = monomial_dissipations(&geometry, coefficients.len() - 1);
    let lambda = &cycle.compliance_ratio;
    let weighted = |pick: fn(&Segments<R>) -> &R| {
        monomials
            .iter()
            .zip(&coefficients)
            .skip(1)
            .fold(zero.clone(), |acc, (w, c)| acc + &(pick(w).clone() * c))
            * lambda
    };
    Ok(Segments {
        eb: weighted(|s| &s.eb),
        bc: weighted(|s| &s.bc),
        ch: weighted(|s| &s.ch),
        he: weighted(|s| &s.he),
    })
}
