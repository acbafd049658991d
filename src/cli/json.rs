//! The JSON reports of the subcommands (`--json`, and the rows of `batch --format
//! jsonl`), one typed struct each, with one vocabulary; `docs/schema/` holds a JSON
//! Schema of each. Every key has one JSON type wherever it appears (or null where the
//! report has no such value): a value is a decimal string carrying exactly its printed
//! digits (`"W"`, `"I"`, `"value"`; `"0"` for an exact zero, null where not one digit
//! is determined), beside it the binary64 number computed, where there is one
//! (`"W_f64"`, `"I_f64"`, `"value_f64"`), and then the same envelope of what vouches
//! for it ([`ValueEnvelope`]). `inputs` holds the inputs as the strings written.

use serde::ser::SerializeMap;
use serde::Serialize;

use microslip::answer::dissipation::DissipationAnswer;
use microslip::answer::path::AgreedW;
use microslip::answer::{Answer, Provenance, Value};
use microslip::batch::{InputRow, RowResult};
use microslip::case::CaseText;

/// Keys and values serialized as a JSON object in the order given.
pub struct InOrder<K, V>(Vec<(K, V)>);

impl<K: Serialize, V: Serialize> Serialize for InOrder<K, V> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.0.len()))?;
        for (key, value) in &self.0 {
            map.serialize_entry(key, value)?;
        }
        map.end()
    }
}

/// A value as JSON prints it: its digits as printed, or None where not one digit is
/// determined (its enclosure then says where it lies).
pub fn printed(value: &Value) -> Option<String> {
    (value.digits() > 0).then(|| value.decimal.to_string())
}

/// What vouches for a printed value, with the same keys and types in every report that
/// prints one (all null in a failed batch row).
#[derive(Default, Serialize)]
pub struct ValueEnvelope {
    /// The significant digits printed.
    pub digits: Option<u32>,
    /// The digits proven or checked by a second computation at higher precision (null
    /// where they are estimated).
    pub digits_verified: Option<u32>,
    /// The digits proven, by a rigorous enclosure or exactly (0 where estimated).
    pub digits_certified: Option<u32>,
    /// [`Provenance::key`]: `exact`, `certified`, `agreement`, `estimate`,
    /// `table_error` or `simulated`.
    pub provenance: Option<&'static str>,
    /// Outward-rounded decimal ends of an interval that contains the value: proven for
    /// `certified`, by the estimate otherwise (null for an exact value).
    pub enclosure: Option<(String, String)>,
    /// The working precision of the value printed (53 for f64; null for an exact value).
    pub precision_bits: Option<u32>,
    /// Why the value is exactly the one printed, where it is.
    pub exact: Option<&'static str>,
}

impl ValueEnvelope {
    pub fn of(answer: &Answer) -> Self {
        let estimated = matches!(
            answer.provenance,
            Provenance::Table { .. } | Provenance::Simulated { .. }
        );
        ValueEnvelope {
            digits: Some(answer.digits()),
            digits_verified: (!estimated).then(|| answer.digits()),
            digits_certified: Some(answer.digits_certified()),
            provenance: Some(answer.provenance.key()),
            enclosure: answer.value.enclosure.clone(),
            precision_bits: answer.provenance.precision_bits(),
            exact: match &answer.provenance {
                Provenance::Exact(reason) => Some(reason.reason()),
                _ => None,
            },
        }
    }
}

/// One value of a list (a coefficient Iₙ, a partial sum W_N, a difference W_N − W).
#[derive(Serialize)]
pub struct ValueReport {
    pub value: Option<String>,
    pub value_f64: Option<f64>,
    #[serde(flatten)]
    pub envelope: ValueEnvelope,
}

impl ValueReport {
    pub fn of(answer: &Answer) -> Self {
        ValueReport {
            value: printed(&answer.value),
            value_f64: answer.value.binary64,
            envelope: ValueEnvelope::of(answer),
        }
    }
}

/// ρ and φ as written (`small-amplitude`, `series --rho`).
#[derive(Serialize)]
pub struct ShapeInputs<'a> {
    pub rho: &'a str,
    pub phi: &'a str,
}

/// W as `dissipation --json` and a batch row report it (all null in a failed row).
#[derive(Default, Serialize)]
pub struct DissipationFields {
    #[serde(rename = "W")]
    pub w: Option<String>,
    #[serde(rename = "W_f64")]
    pub w_f64: Option<f64>,
    #[serde(flatten)]
    pub envelope: ValueEnvelope,
    /// The absolute quadrature error estimate of an f64 W.
    pub error_estimate: Option<f64>,
    /// For a table compliance: the estimated error of W due to the table.
    pub table_error: Option<f64>,
    /// For a table compliance: the largest relative move smoothing made to the data.
    pub smoothing_residual: Option<f64>,
    /// Why the digits rest on agreement of two precisions rather than an enclosure.
    pub no_enclosure: Option<String>,
    /// How W was computed (`Method::key`).
    pub method: Option<&'static str>,
    /// The arithmetic of a rigorous enclosure (`Arithmetic::key`): `f64 intervals` or
    /// `arb balls`; null for any other provenance.
    pub arithmetic: Option<&'static str>,
}

impl DissipationFields {
    /// A batch row's path W: two working precisions agree on its digits; `method` is
    /// `path-force` or `path-displacement`.
    pub fn of_path(w: &AgreedW, digits: Option<u32>, method: &str) -> Self {
        DissipationFields {
            w: Some(w.text.clone()),
            w_f64: Some(w.value),
            envelope: ValueEnvelope {
                digits,
                digits_verified: digits,
                digits_certified: Some(w.digits_certified),
                provenance: Some(w.provenance),
                // An exact W has no working precision.
                precision_bits: w.exact.is_none().then_some(w.precision_bits),
                enclosure: w.enclosure.clone(),
                exact: w.exact,
            },
            no_enclosure: w.no_enclosure.clone(),
            arithmetic: w.arithmetic,
            method: Some(if method == "path-displacement" {
                "path-displacement"
            } else {
                "path-force"
            }),
            ..DissipationFields::default()
        }
    }

    pub fn of(report: &DissipationAnswer) -> Self {
        let answer = &report.answer;
        DissipationFields {
            w: printed(&answer.value),
            w_f64: answer.value.binary64,
            envelope: ValueEnvelope::of(answer),
            error_estimate: match &answer.provenance {
                Provenance::Table { .. } => report.table.as_ref().map(|t| t.quadrature_error),
                _ => None,
            },
            table_error: report.table.as_ref().map(|t| t.error),
            smoothing_residual: report.table.as_ref().map(|t| t.smoothing_residual),
            no_enclosure: report.no_enclosure.as_ref().map(ToString::to_string),
            method: answer.method.map(microslip::dissipation::Method::key),
            arithmetic: answer.provenance.arithmetic().map(microslip::answer::Arithmetic::key),
        }
    }
}

/// `microslip dissipation --json`.
#[derive(Serialize)]
pub struct DissipationReport<'a> {
    #[serde(flatten)]
    pub w: DissipationFields,
    /// EB, BC, CH, HE as printed, each null where not one of its digits is determined.
    pub segments: Option<InOrder<&'static str, Option<String>>>,
    /// EB, BC, CH, HE in binary64, where W was computed in f64.
    pub segments_f64: Option<InOrder<&'static str, f64>>,
    pub inputs: &'a CaseText,
}

impl<'a> DissipationReport<'a> {
    /// The report of W as the policy gave it, for the inputs `case`.
    pub fn new(report: &'a DissipationAnswer, case: &'a CaseText) -> Self {
        let segments = report.answer.segments.as_ref();
        DissipationReport {
            w: DissipationFields::of(report),
            segments: segments.map(|s| InOrder(s.named().map(|(name, value)| (name, printed(value))).into())),
            segments_f64: segments.and_then(|s| {
                let values: Option<Vec<_>> = s
                    .named()
                    .into_iter()
                    .map(|(name, value)| value.binary64.map(|v| (name, v)))
                    .collect();
                values.map(InOrder)
            }),
            inputs: case,
        }
    }
}

/// One row of `microslip batch --format jsonl`: its input columns as written, and W as
/// `dissipation --json` reports it, or why the row failed.
#[derive(Serialize)]
pub struct BatchRow<'a> {
    pub inputs: InOrder<&'a str, &'a str>,
    #[serde(flatten)]
    pub w: DissipationFields,
    /// Why the row failed (null when it succeeded).
    pub error: Option<&'a str>,
}

/// The JSON rows of a batch's rows and their results, in input order.
pub fn batch_rows<'a>(header: &'a [String], rows: &'a [InputRow], results: &'a [RowResult]) -> Vec<BatchRow<'a>> {
    rows.iter()
        .zip(results)
        .map(|(row, result)| BatchRow {
            inputs: InOrder(
                header
                    .iter()
                    .map(String::as_str)
                    .zip(row.cells.iter().map(String::as_str))
                    .collect(),
            ),
            w: match (&result.answer, &result.path) {
                (Some(answer), _) => DissipationFields::of(answer),
                (None, Some(path)) => DissipationFields::of_path(path, result.digits, &result.method),
                (None, None) => DissipationFields::default(),
            },
            error: (!result.succeeded()).then_some(result.error.as_str()),
        })
        .collect()
}

/// The loads `microslip simulate` ran on: a case, or a path file on a contact.
#[derive(Serialize)]
#[serde(untagged)]
pub enum SimulatedLoads<'a> {
    Case(&'a CaseText),
    Path(PathFileInputs),
}

/// A path file (under the key of its flag, `harmonics` or `samples`) on a contact, as written.
#[derive(Serialize)]
pub struct PathFileInputs {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub harmonics: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub samples: Option<String>,
    /// What the file prescribes besides P: `force` (Q) or `displacement` (u).
    pub drive: &'static str,
    pub friction: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub nu: Option<String>,
    pub compliance: String,
}

/// The inputs of `microslip simulate`: the loads and the resolution asked for.
#[derive(Serialize)]
pub struct SimulationInputs<'a> {
    #[serde(flatten)]
    pub loads: SimulatedLoads<'a>,
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
    pub w: Option<String>,
    #[serde(rename = "W_f64")]
    pub w_f64: f64,
    /// W as the frictional work of the elements, to the digits the same bound determines.
    #[serde(rename = "W_friction")]
    pub w_friction: Option<String>,
    #[serde(rename = "W_friction_f64")]
    pub w_friction_f64: f64,
    /// Provenance `simulated`: an estimate from the refinements, not a proof.
    #[serde(flatten)]
    pub envelope: ValueEnvelope,
    pub estimated_rel_error: f64,
    /// `history-simulation`.
    pub method: &'static str,
    /// Elements of the finest run.
    pub elements: usize,
    /// Steps per cycle of the finest run.
    pub steps: usize,
    /// Of a path file: the amplitudes of Q and u and the loss factor, of the finest run's loop.
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub amplitudes: Option<SimulatedAmplitudes>,
    pub inputs: SimulationInputs<'a>,
}

/// Half the spreads of Q and u over the simulated steady loop, and η = W/(π Q_a u_a).
#[derive(Serialize)]
pub struct SimulatedAmplitudes {
    pub q_amplitude: f64,
    pub u_amplitude: f64,
    pub loss_factor: f64,
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
    /// How a proved row is proven: its boxes and seconds, or the derivation's document.
    pub proof: Option<microslip::verify::Proof>,
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

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use super::*;

    #[test]
    fn a_row_echoes_its_inputs_as_written_and_a_failed_row_has_null_results() {
        let text = "id,p0,p1,q1,phi,friction,lambda,compliance,W\n\
                    a,1,0.4,0.5,0.4pi,1,1,\"persson:gamma=1,sigma=1\",old\n\
                    b,1,0.4,5,0.4pi,1,1,\"persson:gamma=1,sigma=1\",old\n";
        let input = microslip::batch::read_input(text.as_bytes()).unwrap();
        let header = input.header.clone();
        let rows: Vec<InputRow> = input.map(Result::unwrap).collect();
        let results = microslip::batch::run(&rows, None, Duration::from_secs(10));
        let lines: Vec<serde_json::Value> = batch_rows(&header, &rows, &results)
            .iter()
            .map(|row| serde_json::to_value(row).unwrap())
            .collect();
        assert_eq!(lines[0]["W"], "4.062475792458e-1");
        assert_eq!(lines[0]["arithmetic"], "f64 intervals");
        assert_eq!(
            lines[0]["W_f64"]
                .as_f64()
                .map(|w| (w - 0.406247579245824).abs() < 1e-15),
            Some(true)
        );
        // The input's own W column is echoed among the inputs, as written.
        assert_eq!(lines[0]["inputs"]["W"], "old");
        assert_eq!(lines[0]["inputs"]["p1"], "0.4");
        assert_eq!(lines[0]["inputs"]["phi"], "0.4pi");
        assert_eq!(lines[0]["inputs"]["compliance"], "persson:gamma=1,sigma=1");
        assert_eq!(
            (&lines[0]["digits"], &lines[0]["digits_certified"]),
            (&13.into(), &13.into())
        );
        assert_eq!(
            (&lines[0]["provenance"], &lines[0]["method"]),
            (&"certified".into(), &"four-segment".into())
        );
        assert!(lines[0]["error"].is_null() && lines[0]["table_error"].is_null());
        assert!(lines[1]["error"].as_str().unwrap().contains("gross slip"));
        // Both rows have the same keys; the failed one has every result null.
        let keys = |line: &serde_json::Value| line.as_object().unwrap().keys().cloned().collect::<Vec<_>>();
        assert_eq!(keys(&lines[0]), keys(&lines[1]));
        let failed = lines[1].as_object().unwrap();
        assert!(failed
            .iter()
            .all(|(key, value)| value.is_null() || key == "inputs" || key == "error"));
    }
}
