//! Proptest strategies for the property tests, built from the same definitions as the
//! gate's seeded draws (`microslip::verify::generators`: the `Family` list with its
//! parameter ranges, the cycle parameters and `cycle_case`), so that every drawn
//! compliance is admissible (v' > 0, v'' ≤ 0 over the loads) and every cycle lies inside
//! the gross-slip and separation limits. A failing case shrinks towards the simplest
//! family, a single term, and each parameter's low end, and prints as a report does: the
//! loads and a SPEC.

// Each test file uses the strategies its claims need.
#![allow(dead_code)]

use microslip::case::CaseText;
use microslip::verify::claims::{
    mean_tangential_margin, second_compliance_loads, CaseWith, CubicLawCase, Drawn, LinearityCase, RoughnessCase,
    SimulatedHistoryCase, Source,
};
use microslip::verify::generators::{cycle_case, significant, Family, Loads, Range, CYCLE};
use proptest::prelude::*;
use proptest::strategy::Union;

/// A number in `range`, rounded to 6 significant digits as the gate's draws are (so that
/// it prints exactly as the decimal every precision reads).
pub fn number(low: f64, high: f64) -> impl Strategy<Value = f64> {
    (low..high).prop_map(significant)
}

/// One value in each range, in order.
fn parameters(ranges: &'static [Range]) -> Vec<BoxedStrategy<f64>> {
    ranges
        .iter()
        .map(|range| number(range.low, range.high).boxed())
        .collect()
}

/// A member of a compliance family: its parameters, before the loads fix a polynomial.
#[derive(Clone, Debug)]
pub struct Member {
    family: Family,
    values: Vec<f64>,
}

/// A member of any family, simplest first (`Family::ALL`'s order).
pub fn member() -> impl Strategy<Value = Member> {
    Union::new(
        Family::ALL.map(|family| parameters(family.parameters()).prop_map(move |values| Member { family, values })),
    )
}

/// Whether a drawn compliance may be a sum of families.
#[derive(Clone, Copy, Debug)]
pub enum Terms {
    /// One family member.
    Single,
    /// One member or, one time in four, the sum of two.
    WithSums,
}

/// An admissible compliance: one family member or, with `Terms::WithSums`, one time in
/// four the sum of two (v' > 0 and v'' ≤ 0 add up). A sum makes every evaluation of v'
/// dearer (at 256 bits a test with sums in a fifth of its cases took 60 % longer), so the
/// tests in MPFR and of the simulation draw single members, as the gate does.
pub fn compliance(terms: Terms) -> BoxedStrategy<Vec<Member>> {
    let single = member().prop_map(|member| vec![member]);
    match terms {
        Terms::WithSums => prop_oneof![3 => single, 1 => [member(), member()].prop_map(Vec::from)].boxed(),
        Terms::Single => single.boxed(),
    }
}

/// The SPEC of a compliance, admissible over `loads`.
pub fn spec(terms: &[Member], loads: Loads) -> String {
    let specs: Vec<String> = terms.iter().map(|term| term.family.spec(&term.values, loads)).collect();
    specs.join(" + ")
}

prop_compose! {
    /// A cycle inside the theory (P0 = 1, Q0 = 0, P1/P0 ∈ (0.05, 0.9), φ ∈ (0, π), Q1 inside
    /// the gross-slip amplitude) and a compliance admissible over the loads it reaches
    /// (with `Terms::WithSums`, sometimes a sum of families).
    pub fn case(terms: Terms)(cycle in parameters(&CYCLE), members in compliance(terms)) -> CaseText {
        cycle_case(&cycle, |loads| spec(&members, loads))
    }
}

prop_compose! {
    /// A case printed as a report prints it.
    pub fn drawn(terms: Terms)(case in case(terms)) -> Drawn {
        Drawn(case)
    }
}

prop_compose! {
    /// Claim 3's case: c ∈ [0.1, largest) added to v'.
    pub fn constant_term_case(largest: f64, terms: Terms)(case in case(terms), constant in number(0.1, largest)) -> CaseWith {
        CaseWith { case, symbol: "c", value: constant }
    }
}

prop_compose! {
    /// Claim 4's case: a second compliance admissible where the evaluator of `source`
    /// needs it, and weights a, b ∈ [0.1, 3).
    pub fn linearity_case(source: Source, terms: Terms)(case in case(terms), members in compliance(terms), a in number(0.1, 3.0), b in number(0.1, 3.0)) -> LinearityCase {
        let second = spec(&members, second_compliance_loads(&case, source));
        LinearityCase { case, second, a, b }
    }
}

prop_compose! {
    /// Claim 5's case: k ∈ [0.2, 5), σ ∈ [0.01, 1), and β ∈ [−2, −0.05) for the power law
    /// when W comes from the segment formulas (the gate's draw leaves the power law out of
    /// the simulated row).
    pub fn roughness_case(source: Source, terms: Terms)(case in case(terms), k in number(0.2, 5.0), beta in number(-2.0, -0.05), sigma in number(0.01, 1.0)) -> RoughnessCase {
        RoughnessCase { case, k, beta: (source == Source::Segments).then_some(beta), sigma }
    }
}

prop_compose! {
    /// Claim 6a's case: another Q0 anywhere inside the gross-slip margin.
    pub fn invariants_case(terms: Terms)(case in case(terms), fraction in number(0.0, 1.0)) -> CaseWith {
        let cycle = case.read::<f64>(microslip::real::Precision::DOUBLE).expect("a drawn case reads").cycle;
        let (low, high) = mean_tangential_margin(&cycle);
        CaseWith { case, symbol: "Q0", value: significant(low + (high - low) * fraction) }
    }
}

prop_compose! {
    /// Claim 6c's case: Q0 of the simulated cycle at a fraction in (−0.9, 0.9) of its
    /// margin, and half of the time the phase φ + π.
    pub fn simulated_history_case()(case in case(Terms::Single), q0_fraction in number(-0.9, 0.9), reverse in any::<bool>()) -> SimulatedHistoryCase {
        SimulatedHistoryCase { case, q0_fraction, reverse }
    }
}

prop_compose! {
    /// Claim 1's case: ρ ∈ [0.2, 3), φ/π ∈ [0.1, 0.9), f ∈ [0.3, 1), λ ∈ [1, 1.5) and a
    /// compliance admissible on [0.5, 1.5].
    pub fn cubic_law_case()(rho in number(0.2, 3.0), phase_fraction in number(0.1, 0.9), friction in number(0.3, 1.0), lambda in number(1.0, 1.5), terms in compliance(Terms::Single)) -> CubicLawCase {
        let compliance = spec(&terms, Loads { low: 0.5, high: 1.5, mean: 1.0 });
        CubicLawCase { rho, phase_fraction, friction, lambda, compliance }
    }
}
