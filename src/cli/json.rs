//! The JSON reports of the subcommands (`--json`), one typed struct each, with one
//! vocabulary: a value is a decimal string with its printed digits (`"W"`), and where
//! it was computed in f64 also the binary64 number itself in shortest round-trip form
//! (`"W_f64"`); `digits` is the significant digits printed, `digits_verified` the
//! digits checked by a second computation at higher precision (null where none were),
//! `bound` what vouches for the digits printed (`"estimate"`, `"agreement"`,
//! `"table_error"` or `"exact"`), `precision_bits` the working precision (53 for f64),
//! `inputs` the inputs as given. Every value string is printed by one rule: only the
//! digits on which its whole error interval rounds alike; `"0"` for an exact zero.

use serde::ser::SerializeMap;
use serde::Serialize;

use microslip::answer::{Provenance, Value};
use microslip::case::CaseText;
use microslip::dissipation::{self, Segment};
use microslip::dissipation_answer::{method_key, DissipationAnswer};

/// The four segment values as an object keyed by the segments' names, in cycle order.
pub struct Segments<T>(dissipation::Segments<T>);

impl<T: Serialize> Serialize for Segments<T> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(4))?;
        for (segment, value) in self.0.iter() {
            map.serialize_entry(segment.name(), value)?;
        }
        map.end()
    }
}

/// `microslip dissipation --json`.
#[derive(Serialize)]
pub struct DissipationReport<'a> {
    /// W as printed; null where no digit of it is known (a table too coarse for it).
    #[serde(rename = "W")]
    pub w: Option<String>,
    #[serde(rename = "W_f64")]
    pub w_f64: Option<f64>,
    pub digits: u32,
    /// The digits proven or checked at a second precision (null for estimated ones).
    pub digits_verified: Option<u32>,
    /// The digits proven: by a rigorous enclosure, or exact (0 for estimated ones).
    pub digits_certified: u32,
    /// What vouches for the digits ([`Provenance::key`]): `"exact"`, `"certified"`,
    /// `"agreement"` (not a proof), `"estimate"` (f64's error estimate, not proven) or
    /// `"table_error"`.
    pub provenance: &'static str,
    /// The same as `provenance`, under the name the JSON reports share.
    pub bound: &'static str,
    /// Decimal strings of an interval that contains W (null for an exact value).
    pub enclosure: Option<[&'a str; 2]>,
    /// The working precision of the value printed (53 for f64; null for an exact value).
    pub precision_bits: Option<u32>,
    /// The absolute error estimate of an f64 W (null otherwise).
    pub error_estimate: Option<f64>,
    /// Why a run without --digits did not print f64.
    pub f64_fallback: Option<String>,
    /// Why the digits rest on agreement of two precisions rather than an enclosure.
    pub no_enclosure: Option<String>,
    /// How W was computed ([`microslip::dissipation_answer::method_key`]).
    pub method: &'static str,
    /// Why W is exactly 0, where it is (the value is then exact, not rounded).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub exact: Option<&'static str>,
    /// EB, BC, CH, HE as printed; a segment with no known digit is null.
    pub segments: Option<Segments<Option<String>>>,
    pub segments_f64: Option<Segments<f64>>,
    pub inputs: &'a CaseText,
    /// For a table compliance: the error of W due to the table (null otherwise).
    pub table_error: Option<f64>,
    /// For a smoothed table: the largest relative move of the data (null otherwise).
    pub smoothing_residual: Option<f64>,
}

impl<'a> DissipationReport<'a> {
    /// The report of W as the policy gave it, for the inputs `case`.
    pub fn new(report: &'a DissipationAnswer, case: &'a CaseText) -> Self {
        let answer = &report.answer;
        let printed = |value: &Value| (value.digits() > 0).then(|| value.decimal.to_string());
        let segments = answer.segments.as_ref();
        let proven_or_checked = !matches!(
            answer.provenance,
            Provenance::Estimate { .. } | Provenance::Table { .. } | Provenance::Simulated { .. }
        );
        let error_estimate = match &answer.provenance {
            Provenance::Estimate { error_estimate } => Some(*error_estimate),
            Provenance::Table { .. } => report.table.as_ref().map(|t| t.quadrature_error),
            _ => None,
        };
        DissipationReport {
            w: printed(&answer.value),
            w_f64: answer.value.binary64,
            digits: answer.digits(),
            digits_verified: proven_or_checked.then(|| answer.digits()),
            digits_certified: answer.digits_certified(),
            provenance: answer.provenance.key(),
            bound: answer.provenance.key(),
            enclosure: answer
                .value
                .enclosure
                .as_ref()
                .map(|(lower, upper)| [lower.as_str(), upper.as_str()]),
            precision_bits: answer.provenance.precision_bits(),
            error_estimate,
            f64_fallback: report.fallback.as_ref().map(ToString::to_string),
            no_enclosure: report.no_enclosure.as_ref().map(ToString::to_string),
            method: answer.method.map_or("", method_key),
            exact: match &answer.provenance {
                Provenance::Exact(reason) => Some(reason.reason()),
                _ => None,
            },
            // Only a table's segment can have no known digit: null; elsewhere the interval.
            segments: segments.map(|s| {
                Segments(dissipation::Segments::from_fn(|segment| match report.table {
                    Some(_) => printed(s.get(segment)),
                    None => Some(s.get(segment).decimal.to_string()),
                }))
            }),
            segments_f64: segments.and_then(|s| {
                let values = dissipation::Segments::from_fn(|segment| s.get(segment).binary64);
                Segment::ALL
                    .iter()
                    .all(|&segment| values.get(segment).is_some())
                    .then(|| {
                        Segments(dissipation::Segments::from_fn(|segment| {
                            values.get(segment).unwrap_or(0.0)
                        }))
                    })
            }),
            inputs: case,
            table_error: report.table.as_ref().map(|t| t.error),
            smoothing_residual: report.table.as_ref().map(|t| t.smoothing_residual),
        }
    }
}

/// The inputs of `microslip simulate`: the case and the resolution asked for.
#[derive(Serialize)]
pub struct SimulationInputs<'a> {
    #[serde(flatten)]
    pub case: &'a CaseText,
    /// Elements of the coarsest bed.
    pub elements: usize,
    /// Steps per cycle of the coarsest run.
    pub steps: usize,
    pub tolerance: f64,
}

/// `microslip simulate --json`.
#[derive(Serialize)]
pub struct SimulationReport<'a> {
    /// W as the work of the load, to the digits the estimate determines.
    #[serde(rename = "W")]
    pub w: String,
    #[serde(rename = "W_f64")]
    pub w_f64: f64,
    /// W as the frictional work of the elements, to the same digits.
    #[serde(rename = "W_friction")]
    pub w_friction: String,
    #[serde(rename = "W_friction_f64")]
    pub w_friction_f64: f64,
    pub digits: u32,
    /// Simulated digits are estimated, not verified: always null.
    pub digits_verified: Option<u32>,
    /// Always `"estimate"`: the simulation's error is estimated from its refinements.
    pub bound: &'static str,
    pub precision_bits: u32,
    pub estimated_rel_error: f64,
    pub method: &'static str,
    /// Elements of the finest run.
    pub elements: usize,
    /// Steps per cycle of the finest run.
    pub steps: usize,
    pub inputs: SimulationInputs<'a>,
}

/// One row of `microslip verify --json`.
#[derive(Serialize)]
pub struct ClaimRow<'a> {
    pub claim: &'a str,
    pub precision_bits: u32,
    pub cases: usize,
    pub worst_error: f64,
    pub tolerance: f64,
    pub passed: bool,
    /// Proven over the whole domain (true), or checked on random draws (false).
    pub proved: bool,
    /// The proof's boxes and seconds, for a proved row.
    pub proof: Option<microslip::verify::ProofSize>,
    pub note: &'a str,
}

/// `microslip verify --json`.
#[derive(Serialize)]
pub struct GateReport<'a> {
    pub passed: bool,
    pub seed: u64,
    pub quick: bool,
    pub seconds: f64,
    pub claims: Vec<ClaimRow<'a>>,
}

/// JSON lines: one object per record, each on a line of its own.
pub fn lines<T: Serialize>(records: &[T]) -> Result<Vec<u8>, serde_json::Error> {
    let mut out = Vec::new();
    for record in records {
        serde_json::to_writer(&mut out, record)?;
        out.push(b'\n');
    }
    Ok(out)
}
