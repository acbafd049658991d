//! The claims of the theorem gate, each checked over random draws.
//!
//! Every function draws its cases from a seed, computes, and returns a
//! [`ClaimReport`]: how many cases, the worst error against the claim, the
//! tolerance, and whether all passed. A computation that fails counts as a failure.

use rug::Float;

use super::generators::{compliance_spec, shape, Draw};
use super::small_amplitude::{coefficient, coefficient_at};
use super::ClaimReport;
use crate::compliance::{parse_spec, Compliance, LoadScaled, Scaled, Shifted, Sum};
use crate::cycle::LoadCycle;
use crate::dissipation::{dissipation, four_segment, in_phase, Options};
use crate::inputs::CaseText;
use crate::real::{Precision, Real};

/// The tolerance on a relative identity at a precision: 1e−12 in f64, 1e−70 at 256 bits.
fn identity_tolerance(precision: Precision) -> f64 {
    if precision <= Precision::DOUBLE {
        1e-12
    } else {
        1e-70
    }
}

fn precision_name(precision: Precision) -> String {
    if precision == Precision::DOUBLE {
        "f64".to_string()
    } else {
        format!("{} bits", precision.in_bits())
    }
}

/// Accumulates the worst error over cases and remembers the first failure.
struct Tally {
    report: ClaimReport,
}

impl Tally {
    fn new(claim: &str, precision: Precision, tolerance: f64) -> Self {
        Tally {
            report: ClaimReport {
                claim: claim.to_string(),
                precision: precision_name(precision),
                cases: 0,
                worst_error: 0.0,
                tolerance,
                passed: true,
                note: String::new(),
            },
        }
    }

    fn record(&mut self, error: f64, case: &str) {
        let report = &mut self.report;
        report.cases += 1;
        let error = if error.is_nan() { f64::INFINITY } else { error };
        if error > report.worst_error {
            report.worst_error = error;
        }
        if error > report.tolerance && report.passed {
            report.passed = false;
            report.note = format!("first failure: {case} (error {error:.3e})");
        }
    }

    fn fail(&mut self, case: &str, why: impl std::fmt::Display) {
        self.report.cases += 1;
        self.report.worst_error = f64::INFINITY;
        if self.report.passed {
            self.report.passed = false;
            self.report.note = format!("{case}: {why}");
        }
    }

    fn note(mut self, note: impl Into<String>) -> ClaimReport {
        if self.report.passed {
            self.report.note = note.into();
        }
        self.report
    }
}

/// |a − b| / |b| in f64 terms (|a − b| when b is 0).
fn relative<R: Real>(a: &R, b: &R) -> f64 {
    let difference = (a.clone() - b).abs();
    if b.abs() > b.int(0) {
        (difference / b.abs()).to_f64_lossy()
    } else {
        difference.to_f64_lossy()
    }
}

/// A random cycle inside the theory: P0 = 1, P1/P0 ∈ (0.05, 0.9), φ ∈ (0, π), Q1 a
/// random fraction of the largest amplitude the friction cone allows, and a
/// compliance admissible over the loads the cycle reaches.
pub fn random_case(draw: &mut Draw) -> CaseText {
    let p1 = draw.uniform(0.05, 0.9);
    let f = draw.uniform(0.2, 2.0);
    let lambda = draw.uniform(1.0, 1.5);
    let phase_fraction = draw.uniform(0.02, 0.98);
    let phi = phase_fraction * std::f64::consts::PI;
    // σ± < fP0 ⇔ Q1 < −fP1|cos φ| + f√(P0² − P1² sin²φ).
    let largest = f * (-p1 * phi.cos().abs() + (1.0 - (p1 * phi.sin()).powi(2)).sqrt());
    let q1 = draw.uniform(0.1, 0.9) * largest;
    let q1: f64 = format!("{q1:.6e}").parse().unwrap_or(q1);
    // P_T ≥ P0 − (Q1 + fP1)/f: the compliance must be admissible from there.
    let low = (1.0 - p1).min(1.0 - (q1 + f * p1) / f).max(1e-3);
    CaseText {
        p0: "1".into(),
        p1: p1.to_string(),
        q0: "0".into(),
        q1: q1.to_string(),
        phi: format!("{phase_fraction}pi"),
        friction: f.to_string(),
        lambda: Some(lambda.to_string()),
        nu: None,
        compliance: compliance_spec(draw, low * 0.9, 1.0 + p1, 1.0),
    }
}

fn read<R: Real>(case: &CaseText, precision: Precision) -> Option<(LoadCycle<R>, Box<dyn Compliance<R>>)> {
    case.read::<R>(precision).ok().map(|c| (c.cycle, c.compliance))
}

fn describe(case: &CaseText) -> String {
    format!(
        "P1={} Q1={} φ={} f={} λ={} v'={}",
        case.p1,
        case.q1,
        case.phi,
        case.friction,
        case.lambda.as_deref().unwrap_or("?"),
        case.compliance
    )
}

/// Claim 1, the cubic law: W/(λf²P1³v''(P0)) → I(ρ, φ) as P1 = 2^(−k) → 0 with error
/// O(P1); the order fitted over k = 8 … 15 must be 1 ± 0.1 (φ ∈ (0.1π, 0.9π)). At
/// 160 bits, where f64 would cancel.
pub fn cubic_law(seed: u64, cases: usize) -> ClaimReport {
    let precision = Precision::bits(160);
    let mut tally = Tally::new("1 cubic law: fitted order of W/(λf²P1³v'') → I", precision, 0.1);
    let mut draw = Draw::new(seed);
    let number = |text: String| Float::parse_decimal(&text, precision).unwrap_or_else(|_| Float::new(53));
    let mut orders = Vec::new();
    for _ in 0..cases {
        // Away from φ = 0, π, where I itself vanishes and the O(P1) term dominates longer.
        let (rho, phase_fraction) = (draw.uniform(0.2, 3.0), draw.uniform(0.1, 0.9));
        let f = draw.uniform(0.3, 1.0);
        let lambda = draw.uniform(1.0, 1.5);
        let spec = compliance_spec(&mut draw, 0.5, 1.5, 1.0);
        let label = format!("ρ={rho} φ={phase_fraction}π f={f} v'={spec}");
        let Ok(compliance) = parse_spec::<Float>(&spec, precision) else {
            tally.fail(&label, "spec did not parse");
            continue;
        };
        let phase = Float::pi(precision) * number(phase_fraction.to_string());
        let rho_r = number(rho.to_string());
        let Ok(limit) = coefficient(&rho_r, &phase) else {
            tally.fail(&label, "I(ρ, φ) failed");
            continue;
        };
        let one = Float::from_i64(1, precision);
        let curvature = compliance.curvature(&one);
        let (f_r, lambda_r) = (number(f.to_string()), number(lambda.to_string()));
        let mut points = Vec::new();
        for k in 8..=15 {
            let p1 = Float::from_i64(2, precision).powi(-k);
            let cycle = LoadCycle {
                mean_normal_load: one.clone(),
                normal_amplitude: p1.clone(),
                mean_tangential_load: one.int(0),
                tangential_amplitude: rho_r.clone() * &f_r * &p1,
                phase: phase.clone(),
                friction: f_r.clone(),
                compliance_ratio: lambda_r.clone(),
            };
            match dissipation(&cycle, compliance.as_ref(), &Options::default()) {
                Ok(result) => {
                    let scale = lambda_r.clone() * &f_r * &f_r * &p1.clone().powi(3) * &curvature;
                    let ratio = result.total / scale;
                    let error = (ratio - &limit).abs().to_f64();
                    points.push((-(k as f64), error.log2()));
                }
                Err(error) => {
                    tally.fail(&label, error);
                    break;
                }
            }
        }
        if points.len() == 8 {
            let order = least_squares_slope(&points);
            orders.push(order);
            tally.record((order - 1.0).abs(), &label);
        }
    }
    let (low, high) = orders
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &o| (l.min(o), h.max(o)));
    tally.note(format!("fitted orders in [{low:.4}, {high:.4}] over P1 = 2^-8 … 2^-15"))
}

/// The slope of the least-squares line through (x, y) points.
pub fn least_squares_slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (sx, sy) = points.iter().fold((0.0, 0.0), |(a, b), (x, y)| (a + x, b + y));
    let (mx, my) = (sx / n, sy / n);
    let (num, den) = points.iter().fold((0.0, 0.0), |(a, b), (x, y)| {
        (a + (x - mx) * (y - my), b + (x - mx) * (x - mx))
    });
    num / den
}

/// Claim 2, the coefficient: I(ρ, φ) does not depend on the amplitude it is computed
/// at (to 1e−30 at 128 bits), is negative for 0 < φ < π, and vanishes in phase for ρ ≤ 1.
pub fn small_amplitude_coefficient(seed: u64, cases: usize) -> ClaimReport {
    let precision = Precision::bits(128);
    let mut tally = Tally::new(
        "2 I(ρ,φ): amplitude-free, < 0, = 0 in phase for ρ ≤ 1",
        precision,
        1e-30,
    );
    let mut draw = Draw::new(seed);
    let number = |value: f64| Float::parse_decimal(&value.to_string(), precision).unwrap_or_else(|_| Float::new(53));
    let mut largest = f64::NEG_INFINITY;
    for _ in 0..cases {
        let (rho, phase_fraction) = shape(&mut draw);
        let label = format!("ρ={rho} φ={phase_fraction}π");
        let (rho_r, phase) = (number(rho), Float::pi(precision) * number(phase_fraction));
        let amplitude = Float::from_i64(1, precision) / (rho_r.clone() + 1i32) / 4i32;
        let smaller = amplitude.clone() / 7i32;
        match (
            coefficient_at(&rho_r, &phase, &amplitude),
            coefficient_at(&rho_r, &phase, &smaller),
        ) {
            (Ok(a), Ok(b)) => {
                largest = largest.max(a.to_f64());
                let sign_error = if a < 0 { 0.0 } else { f64::INFINITY };
                tally.record(relative(&a, &b).max(sign_error), &label);
            }
            (Err(e), _) | (_, Err(e)) => tally.fail(&label, e),
        }
        // In phase: zero for ρ ≤ 1 by the closed form, and the ellipse tends to it.
        let in_phase_rho = number(draw.uniform(0.1, 1.0));
        let zero = Float::from_i64(0, precision);
        match (
            coefficient(&in_phase_rho, &zero),
            coefficient(&in_phase_rho, &number(1e-9)),
        ) {
            (Ok(exact), Ok(near)) => tally.record(exact.abs().to_f64().max(near.abs().to_f64() * 1e-22), &label),
            (Err(e), _) | (_, Err(e)) => tally.fail(&label, e),
        }
    }
    tally.note(format!("largest I drawn: {largest:.6e} (all negative)"))
}

/// Options that integrate v' itself, so the segment formulas must cancel a constant.
fn raw_options<R: Real>() -> Options<R> {
    Options {
        remove_constant_slope: false,
        check_compliance: false,
        ..Options::default()
    }
}

/// Claim 3, the constant term: W[v' + c] = W[v'] for any c, and W[c] = 0, through the
/// raw segment formulas (v' itself integrated, not v' − v'(P0)). In f64 the identity holds
/// to 1e−13 of the terms that cancel; at 256 bits to 1e−70 of W.
pub fn constant_term<R: Real>(seed: u64, cases: usize, precision: Precision) -> ClaimReport {
    let tolerance = if precision <= Precision::DOUBLE { 1e-13 } else { 1e-70 };
    let mut tally = Tally::new("3 constant term: W[v' + c] = W[v'], W[c] = 0", precision, tolerance);
    let mut draw = Draw::new(seed);
    for _ in 0..cases {
        let case = random_case(&mut draw);
        let c = draw.uniform(0.1, 10.0);
        let label = format!("{} c={c}", describe(&case));
        let Some((cycle, compliance)) = read::<R>(&case, precision) else {
            tally.fail(&label, "case did not read");
            continue;
        };
        let shift = R::parse_decimal(&c.to_string(), precision).unwrap_or_else(|_| R::from_i64(1, precision));
        let shifted = Shifted {
            extra_slope: shift.clone(),
            inner: compliance,
        };
        let constant = crate::compliance::Polynomial {
            reference: shift.int(0),
            coefficients: vec![shift.clone()],
        };
        // Raw values of either sign, without the non-negativity guard: a W that vanishes
        // in exact arithmetic is rounding noise here, which is what is measured.
        let options = raw_options::<R>();
        match (
            dissipation(&cycle, shifted.inner.as_ref(), &options),
            dissipation(&cycle, &shifted, &options),
            four_segment(&cycle, &constant, &options),
        ) {
            (Ok(base), Ok(with_constant), Ok(only_constant)) => {
                // In f64, "to working precision" is relative to the size of the terms that
                // cancel: 2πλ Q1 (Q1 + f P1) (max v' + c) bounds ∫|(Q − Q0) du/dθ| dθ. At
                // 256 bits the difference is held to 1e−70 of W itself.
                let magnitude = if precision <= Precision::DOUBLE {
                    let top = cycle.mean_normal_load.clone() - &cycle.normal_amplitude;
                    let low = top.min_of(&cycle.permanent_stick_load());
                    let steepest = shifted
                        .slope(&low)
                        .max_of(&shifted.slope(&(cycle.mean_normal_load.clone() * &top.int(2))));
                    cycle.compliance_ratio.clone()
                        * &cycle.tangential_amplitude
                        * &(cycle.tangential_amplitude.clone() + &(cycle.friction.clone() * &cycle.normal_amplitude))
                        * &steepest
                        * &(R::pi(precision) * &shift.int(2))
                } else {
                    base.total.abs()
                };
                let magnitude = magnitude.max_of(&R::smallest_full_precision(precision));
                let vanishing = (only_constant.total.abs() / &magnitude).to_f64_lossy();
                let difference = (with_constant.total - &base.total).abs() / &magnitude;
                tally.record(difference.to_f64_lossy().max(vanishing), &label);
            }
            (Err(e), _, _) | (_, Err(e), _) | (_, _, Err(e)) => tally.fail(&label, e),
        }
    }
    tally.note(if precision <= Precision::DOUBLE {
        "v' itself integrated (remove_constant_slope off); f64 error relative to the cancelling terms"
    } else {
        "v' itself integrated (remove_constant_slope off); error relative to W"
    })
}

/// Claim 4, linearity: W[a v1' + b v2'] = a W[v1'] + b W[v2'].
pub fn linearity<R: Real>(seed: u64, cases: usize, precision: Precision) -> ClaimReport {
    let tolerance = identity_tolerance(precision);
    let mut tally = Tally::new(
        "4 linearity: W[a v1' + b v2'] = a W[v1'] + b W[v2']",
        precision,
        tolerance,
    );
    let mut draw = Draw::new(seed);
    for _ in 0..cases {
        let case = random_case(&mut draw);
        let mut other = case.clone();
        other.compliance = compliance_spec(&mut draw, 0.05, 1.9, 1.0);
        let (a, b) = (draw.uniform(0.1, 3.0), draw.uniform(0.1, 3.0));
        let label = format!("{} + v2'={} a={a} b={b}", describe(&case), other.compliance);
        let (Some((cycle, first)), Some((_, second))) = (read::<R>(&case, precision), read::<R>(&other, precision))
        else {
            tally.fail(&label, "case did not read");
            continue;
        };
        let weight = |x: f64| R::parse_decimal(&x.to_string(), precision).unwrap_or_else(|_| R::from_i64(1, precision));
        let options = Options {
            check_compliance: false,
            ..Options::default()
        };
        let (w1, w2) = (
            dissipation(&cycle, first.as_ref(), &options),
            dissipation(&cycle, second.as_ref(), &options),
        );
        let combined = Sum {
            terms: vec![
                Box::new(Scaled {
                    factor: weight(a),
                    inner: first,
                }) as Box<dyn Compliance<R>>,
                Box::new(Scaled {
                    factor: weight(b),
                    inner: second,
                }),
            ],
        };
        match (w1, w2, dissipation(&cycle, &combined, &options)) {
            (Ok(w1), Ok(w2), Ok(sum)) => {
                let expected = w1.total * &weight(a) + &(w2.total * &weight(b));
                tally.record(relative(&sum.total, &expected), &label);
            }
            (Err(e), _, _) | (_, Err(e), _) | (_, _, Err(e)) => tally.fail(&label, e),
        }
    }
    tally.note("")
}

fn scaled_cycle<R: Real>(cycle: &LoadCycle<R>, divisor: &R) -> LoadCycle<R> {
    LoadCycle {
        mean_normal_load: cycle.mean_normal_load.clone() / divisor,
        normal_amplitude: cycle.normal_amplitude.clone() / divisor,
        mean_tangential_load: cycle.mean_tangential_load.clone() / divisor,
        tangential_amplitude: cycle.tangential_amplitude.clone() / divisor,
        ..cycle.clone()
    }
}

/// Claim 5, roughness: scaling the roughness heights by k (v_k'(P) = v'(P/k)) gives
/// W_k(P0, P1, Q1) = k² W(P0/k, P1/k, Q1/k) for any compliance; for Persson's
/// v' = γσ/P that makes W ∝ σ exactly, and for v' = C P^β, W_k = k^(−β) W — linear
/// in the roughness only for β = −1. The note reports how far from linear.
pub fn roughness<R: Real>(seed: u64, cases: usize, precision: Precision) -> ClaimReport {
    let tolerance = identity_tolerance(precision);
    let mut tally = Tally::new(
        "5 roughness: W_k = k²W(·/k); Persson W ∝ σ; power law ∝ k^-β",
        precision,
        tolerance,
    );
    let mut draw = Draw::new(seed);
    let mut worst_departure: (f64, f64) = (0.0, 0.0);
    for _ in 0..cases {
        let case = random_case(&mut draw);
        let k = draw.uniform(0.2, 5.0);
        let beta = draw.uniform(-2.0, -0.05);
        let label = format!("{} k={k} β={beta}", describe(&case));
        let Some((cycle, compliance)) = read::<R>(&case, precision) else {
            tally.fail(&label, "case did not read");
            continue;
        };
        let number = |x: f64| R::parse_decimal(&x.to_string(), precision).unwrap_or_else(|_| R::from_i64(1, precision));
        let k_r = number(k);
        let options = Options {
            check_compliance: false,
            ..Options::default()
        };
        // The general identity, on the drawn compliance.
        let scaled = LoadScaled {
            factor: k_r.clone(),
            inner: compliance,
        };
        let general = (
            dissipation(&cycle, &scaled, &options),
            dissipation(&scaled_cycle(&cycle, &k_r), scaled.inner.as_ref(), &options),
        );
        // Persson at σ and kσ, and a power law with loads scaled by k.
        let persson = |sigma: R| crate::compliance::Persson {
            gamma: number(1.0),
            sigma,
        };
        let sigma = number(draw.uniform(0.01, 1.0));
        let persson_pair = (
            dissipation(&cycle, &persson(sigma.clone()), &options),
            dissipation(&cycle, &persson(sigma * &k_r), &options),
        );
        let power = crate::compliance::PowerLaw {
            coefficient: number(1.0),
            exponent: number(beta),
        };
        let power_scaled = LoadScaled {
            factor: k_r.clone(),
            inner: Box::new(power.clone()),
        };
        let power_pair = (
            dissipation(&cycle, &power, &options),
            dissipation(&cycle, &power_scaled, &options),
        );
        match (general, persson_pair, power_pair) {
            ((Ok(wk), Ok(w)), (Ok(p1), Ok(pk)), (Ok(q1), Ok(qk))) => {
                let identity = relative(&wk.total, &(w.total * &k_r * &k_r));
                let linear_sigma = relative(&pk.total, &(p1.total * &k_r));
                let power_law = relative(&qk.total, &(q1.total.clone() * &k_r.powr(&(-number(beta)))));
                tally.record(identity.max(linear_sigma).max(power_law), &label);
                let departure = (qk.total / q1.total / &k_r).to_f64_lossy() - 1.0;
                if departure.abs() > worst_departure.1.abs() {
                    worst_departure = (beta, departure);
                }
            }
            _ => tally.fail(&label, "a computation failed"),
        }
    }
    tally.note(format!(
        "linearity in roughness fails for β ≠ −1: at β = {:.3}, W(kσ)/(k W(σ)) − 1 = {:.3e}",
        worst_departure.0, worst_departure.1
    ))
}

/// Claim 6, invariants, as two reports: (a) W ≥ 0, W does not depend on Q0, and
/// W(φ + π) = W(φ), to 1e−12; (b) the ellipse at φ = 1e−7 agrees with the in-phase
/// closed form to 1e−5 of W (it converges linearly in φ), which is 0 when Q1 ≤ fP1.
pub fn invariants(seed: u64, cases: usize) -> (ClaimReport, ClaimReport) {
    let precision = Precision::DOUBLE;
    let mut identities = Tally::new("6a invariants: W ≥ 0, W free of Q0, period π in φ", precision, 1e-12);
    let mut limit = Tally::new(
        "6b invariants: φ → 0 tends to the in-phase closed form",
        precision,
        1e-5,
    );
    let mut draw = Draw::new(seed);
    let mut zero_cases = 0;
    for _ in 0..cases {
        let case = random_case(&mut draw);
        let label = describe(&case);
        let Some((cycle, compliance)) = read::<f64>(&case, precision) else {
            identities.fail(&label, "case did not read");
            continue;
        };
        let w = |c: &LoadCycle<f64>| dissipation(c, compliance.as_ref(), &Options::default()).map(|r| r.total);
        let base = match w(&cycle) {
            Ok(base) => base,
            Err(e) => {
                identities.fail(&label, e);
                continue;
            }
        };
        // Q0 anywhere inside the gross-slip limit, and φ moved by ±π multiples.
        let (plus, minus) = cycle.slip_line_amplitudes();
        let room = cycle.friction * cycle.mean_normal_load;
        let q0 = draw.uniform(-(room - plus), room - minus) * 0.99;
        let variant = |change: &dyn Fn(&mut LoadCycle<f64>)| {
            let mut c = cycle.clone();
            change(&mut c);
            w(&c)
        };
        let variants = [
            variant(&|c| c.mean_tangential_load = q0),
            variant(&|c| c.phase += std::f64::consts::PI),
            variant(&|c| c.phase -= 3.0 * std::f64::consts::PI),
        ];
        let mut worst: f64 = if base >= 0.0 { 0.0 } else { f64::INFINITY };
        for value in variants {
            match value {
                Ok(value) => worst = worst.max(relative(&value, &base)),
                Err(e) => identities.fail(&label, e),
            }
        }
        identities.record(worst, &label);
        // In phase the ellipse is a line: it stays inside the friction cone only when
        // Q1 + fP1 < fP0, so the amplitude is capped there for this check.
        let (mut near, mut exact) = (cycle.clone(), cycle.clone());
        let in_phase_limit = cycle.friction * (cycle.mean_normal_load - cycle.normal_amplitude) * 0.95;
        for c in [&mut near, &mut exact] {
            c.tangential_amplitude = c.tangential_amplitude.min(in_phase_limit);
        }
        near.phase = 1e-7;
        exact.phase = 0.0;
        // The scale of the comparison: W of the capped cycle at its drawn phase.
        let base = match w(&LoadCycle {
            phase: cycle.phase,
            ..near.clone()
        }) {
            Ok(value) => value,
            Err(e) => {
                limit.fail(&label, e);
                continue;
            }
        };
        match (
            four_segment(&near, compliance.as_ref(), &Options::default()),
            in_phase(&exact, compliance.as_ref(), &Options::default()),
        ) {
            (Ok(a), Ok(b)) => {
                let no_slip = exact.tangential_amplitude <= exact.friction * exact.normal_amplitude;
                zero_cases += usize::from(no_slip);
                let zero_error = if no_slip && b.total != 0.0 { f64::INFINITY } else { 0.0 };
                let scale = b.total.abs().max(base.abs());
                limit.record(((a.total - b.total).abs() / scale).max(zero_error), &label);
            }
            (Err(e), _) | (_, Err(e)) => limit.fail(&label, e),
        }
    }
    (
        identities.note("Q0 drawn across the whole gross-slip margin; φ + π and φ − 3π"),
        limit.note(format!(
            "{zero_cases} of the draws had Q1 ≤ fP1 (in-phase W = 0 exactly)"
        )),
    )
}
