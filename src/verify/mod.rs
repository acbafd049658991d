//! The theorem gate: the claims of the paper (Sections 5.1–5.2) and the
//! invariants of the construction, checked over seeded random draws of compliance
//! functions and cycles, in f64 and at 256 bits. `microslip verify` runs it and
//! fails when any claim fails; the property tests in `tests/theorems.rs` run the
//! same checks on shrinking cases drawn from the same families, with fixed seeds.

pub mod claims;
pub mod generators;
pub mod small_amplitude;

use rug::Float;
use serde::Serialize;

use crate::real::Precision;
use claims::{Claim, ConstantTerm, FourSegment, Invariants, Linearity, Roughness, Simulation};

/// The outcome of one claim at one precision.
#[non_exhaustive]
#[derive(Clone, Debug, Serialize)]
pub struct ClaimReport {
    /// The claim, numbered as in proofs/README.md.
    pub claim: String,
    /// `f64` or `N bits`.
    pub precision: String,
    /// Cases checked.
    pub cases: usize,
    /// The worst error against the claim (relative, or |order − 1| for the cubic law).
    pub worst_error: f64,
    /// The largest error allowed.
    pub tolerance: f64,
    /// Whether every case passed.
    pub passed: bool,
    /// What was found: the first failure, or a measured figure.
    pub note: String,
    /// For a claim proven over its whole domain rather than sampled: how.
    pub proof: Option<Proof>,
}

impl ClaimReport {
    /// Whether the claim is proven over its whole domain, not sampled.
    pub fn proved(&self) -> bool {
        self.passed && self.proof.is_some()
    }
}

/// How a claim is proven over its whole domain.
#[derive(Clone, Copy, Debug, Serialize)]
#[serde(tag = "by", rename_all = "snake_case")]
pub enum Proof {
    /// A rigorous subdivision: every box of the domain decided on balls.
    Subdivision {
        /// Boxes evaluated (proven or split).
        boxes: u64,
        /// Wall-clock seconds.
        seconds: f64,
    },
    /// A derivation, in the document named, whose computable steps the row's cases check
    /// on balls.
    Derivation {
        /// The file of proofs/ that holds it.
        document: &'static str,
    },
}

/// How much of the gate to run.
#[derive(Clone, Copy, Debug)]
pub struct GateOptions {
    /// The seed every draw derives from.
    pub seed: u64,
    /// A smaller sample (under 10 s on 2 cores).
    pub quick: bool,
}

/// One step of the gate: a name for progress, and the check that produces its reports.
pub type GateStep = (&'static str, Box<dyn Fn() -> Vec<ClaimReport> + Send + Sync>);

/// The steps in claim order (independent of each other, so they may run in parallel): the
/// gate's table of contents, one entry per claim, which is why it is long.
/// Each claim draws from its own stream, named as the claim ([`generators::stream_seed`]).
///
/// ```
/// use microslip::verify::{gate, GateOptions};
///
/// // One step of the quick gate: the cubic law W ∝ P1³ at small amplitude.
/// let steps = gate(GateOptions { seed: 7, quick: true });
/// let (name, check) = steps.iter().find(|(name, _)| *name == "cubic law").unwrap();
/// for report in check() {
///     assert!(report.passed, "{name}: {}", report.note);
/// }
/// ```
pub fn gate(options: GateOptions) -> Vec<GateStep> {
    let GateOptions { seed, quick } = options;
    let n = move |quick_cases: usize, full_cases: usize| if quick { quick_cases } else { full_cases };
    let stream = move |name: &str| generators::stream_seed(seed, name);
    let constant_term = evaluated(
        ConstantTerm,
        options,
        &[(F64, 40, 1000), (Wide, 3, 40), (Simulated, 2, 10)],
    );
    let linearity = evaluated(
        Linearity,
        options,
        &[(F64, 40, 1000), (Wide, 3, 40), (Simulated, 2, 10)],
    );
    let roughness = evaluated(
        Roughness,
        options,
        &[(F64, 40, 1000), (Wide, 2, 30), (Simulated, 2, 10)],
    );
    // Where the certified enclosure is built, each of claims 3–5 first proved by derivation.
    #[cfg(feature = "certified")]
    let (constant_term, linearity, roughness) = (
        with_derivation(constant_term, move || {
            claims::constant_term_proved(stream("constant term proved"), n(2, 8))
        }),
        with_derivation(linearity, move || {
            claims::linearity_proved(stream("linearity proved"), n(2, 8))
        }),
        with_derivation(roughness, move || {
            claims::roughness_proved(stream("roughness proved"), n(2, 8))
        }),
    );
    vec![
        (
            "cubic law",
            Box::new(move || {
                #[allow(unused_mut)]
                let mut rows = vec![claims::cubic_law(stream("cubic law"), n(3, 60))];
                #[cfg(feature = "certified")]
                rows.extend([
                    claims::cubic_law_proved(stream("cubic law proved"), n(3, 12)),
                    claims::cubic_law_remainder(stream("cubic law remainder"), n(2, 20)),
                    claims::completely_monotone_bracket(stream("completely monotone bracket"), n(3, 20)),
                ]);
                rows
            }),
        ),
        (
            "small-amplitude coefficient",
            Box::new(move || {
                let (homogeneous, in_phase) =
                    claims::small_amplitude_coefficient(stream("small-amplitude coefficient"), n(4, 100));
                let mut rows = Vec::new();
                #[cfg(feature = "certified")]
                rows.push(claims::coefficient_is_negative());
                rows.extend([homogeneous, in_phase]);
                rows
            }),
        ),
        (
            "coefficient against the simulation",
            Box::new(move || {
                vec![claims::coefficient_against_simulation(
                    stream("coefficient against the simulation"),
                    n(4, 30),
                )]
            }),
        ),
        ("constant term", constant_term),
        ("linearity", linearity),
        ("roughness", roughness),
        (
            "invariants",
            evaluated(Invariants, options, &[(F64, 40, 1000), (Wide, 2, 30)]),
        ),
        (
            "in-phase limit",
            Box::new(move || vec![claims::in_phase_limit(stream("in-phase limit"), n(40, 1000))]),
        ),
        (
            "simulation",
            Box::new(move || vec![claims::simulation_agrees(stream("simulation"), n(6, 60))]),
        ),
        (
            "exact methods",
            Box::new(move || {
                vec![
                    claims::closed_form_coefficient_claim(stream("closed-form coefficient"), n(6, 60)),
                    claims::polynomial_dissipation_claim(stream("exact polynomial dissipation"), n(3, 30)),
                    claims::series_claim(stream("series"), n(4, 20)),
                ]
            }),
        ),
    ]
}

/// The row of a claim proved by its derivation (which `proved` checks), then `rows`.
#[cfg(feature = "certified")]
fn with_derivation(
    rows: Box<dyn Fn() -> Vec<ClaimReport> + Send + Sync>,
    proved: impl Fn() -> ClaimReport + Send + Sync + 'static,
) -> Box<dyn Fn() -> Vec<ClaimReport> + Send + Sync> {
    Box::new(move || std::iter::once(proved()).chain(rows()).collect())
}

/// The evaluators the gate runs a claim with.
#[derive(Clone, Copy, Debug)]
enum Method {
    /// The segment formulas in f64.
    F64,
    /// The segment formulas at 256 bits.
    Wide,
    /// The history simulation.
    Simulated,
}
use Method::{Simulated, Wide, F64};

impl Method {
    /// The name of a claim's row computed with this evaluator, which names its stream.
    fn row<C: Claim>(self) -> String {
        match self {
            F64 => format!("{} in f64", C::NAME),
            Wide => format!("{} at 256 bits", C::NAME),
            Simulated => format!("{} by simulation", C::SIMULATED_NAME),
        }
    }
}

/// A step checking `claim` with each evaluator listed, as (evaluator, quick cases, full
/// cases); each row draws from the stream its name gives.
fn evaluated<C: Claim + Send + Sync + 'static>(
    claim: C,
    options: GateOptions,
    rows: &'static [(Method, usize, usize)],
) -> Box<dyn Fn() -> Vec<ClaimReport> + Send + Sync> {
    Box::new(move || {
        rows.iter()
            .map(|&(method, quick_cases, full_cases)| {
                let (seed, cases) = (
                    generators::stream_seed(options.seed, &method.row::<C>()),
                    if options.quick { quick_cases } else { full_cases },
                );
                match method {
                    F64 => claims::check_claim(&claim, &FourSegment::<f64>::new(Precision::DOUBLE), seed, cases),
                    Wide => claims::check_claim(&claim, &FourSegment::<Float>::new(Precision::bits(256)), seed, cases),
                    Simulated => claims::check_claim(&claim, &Simulation, seed, cases),
                }
            })
            .collect()
    })
}

/// Runs the whole gate on as many threads as rayon's pool has (one per core unless
/// the pool was sized otherwise), and returns the reports in claim order;
/// `progress(done, total, name)` is told each step's name as it finishes.
///
/// ```no_run
/// use microslip::verify::{run, GateOptions};
///
/// let reports = run(GateOptions { seed: 1, quick: true }, |done, total, name| eprintln!("{done}/{total} {name}"));
/// assert!(reports.iter().all(|report| report.passed));
/// ```
pub fn run(options: GateOptions, mut progress: impl FnMut(usize, usize, &str)) -> Vec<ClaimReport> {
    let steps = gate(options);
    let total = steps.len();
    let mut done = 0;
    let reports = crate::workers::each_on_own_threads(
        total,
        rayon::current_num_threads(),
        |index| (steps[index].1)(),
        |index, _| {
            done += 1;
            progress(done, total, steps[index].0);
        },
    );
    reports.into_iter().flatten().collect()
}
