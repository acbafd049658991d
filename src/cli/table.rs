//! `microslip table`: W against the phase φ for a few tangential amplitudes Q1, by
//! default Ŵ for Persson's compliance as in the paper's Fig. 5, as text, CSV or JSON.

use clap::Args;
use serde::Serialize;

use std::time::Duration;

use microslip::answer::dissipation::dissipation_of;
use microslip::answer::Value;
use microslip::case::{CaseText, InputError};
use microslip::compliance::{spec_help, spec_summary};
use microslip::cycle::CycleError;
use microslip::dissipation::ExactZero;
use microslip::files::csv_text;

use super::report::Failure;

/// The most rows (phase steps) a table has.
const MAX_PHASE_STEPS: usize = 1000;

/// The time each cell's W may take.
const CELL_BUDGET: Duration = Duration::from_secs(60);

/// The defaults: the paper's Fig. 5, where γσλf² = 1 makes W the normalized Ŵ.
const FIG5_COMPLIANCE: &str = "persson:gamma=1,sigma=1";

#[derive(Args)]
pub struct TableArgs {
    /// Mean normal load P0 (> 0).
    #[arg(long, allow_hyphen_values = true, default_value = "1")]
    pub p0: String,
    /// Normal load amplitude P1 (0 ≤ P1 < P0).
    #[arg(long, allow_hyphen_values = true, default_value = "0.4")]
    pub p1: String,
    /// Mean tangential load Q0.
    #[arg(long, allow_hyphen_values = true, default_value = "0")]
    pub q0: String,
    /// Tangential load amplitudes Q1, one column each, separated by commas.
    #[arg(
        long,
        allow_hyphen_values = true,
        value_delimiter = ',',
        default_value = "0.2,0.4,0.5,0.6"
    )]
    pub q1: Vec<String>,
    /// Rows: φ = kπ/N for k = 0 … N (1–1000).
    #[arg(long, allow_hyphen_values = true, value_parser = phase_steps, default_value = "10")]
    pub phase_steps: usize,
    /// Coulomb friction coefficient f (> 0).
    #[arg(long, allow_hyphen_values = true, default_value = "1")]
    pub friction: String,
    /// Tangential/normal compliance ratio λ, in [1, 2] (default 1).
    #[arg(long, allow_hyphen_values = true, conflicts_with = "nu")]
    pub lambda: Option<String>,
    /// Poisson's ratio ν in [0, 2/3], giving λ = (2 − ν)/(2(1 − ν)).
    #[arg(long, allow_hyphen_values = true)]
    pub nu: Option<String>,
    #[arg(long, allow_hyphen_values = true, default_value = FIG5_COMPLIANCE,
          help = spec_summary(), long_help = spec_help())]
    pub compliance: String,
    /// Output format.
    #[arg(long, value_parser = ["text", "csv", "json"], default_value = "text")]
    pub format: String,
}

/// A number of phase steps, 1 to [`MAX_PHASE_STEPS`].
fn phase_steps(text: &str) -> Result<usize, String> {
    match text.trim().parse::<usize>() {
        Ok(steps) if (1..=MAX_PHASE_STEPS).contains(&steps) => Ok(steps),
        _ => Err(format!("must be a whole number from 1 to {MAX_PHASE_STEPS}")),
    }
}

/// One cell of the table: W at a phase and an amplitude.
#[derive(Serialize)]
struct Cell<'a> {
    phi_over_pi: f64,
    /// The phase as read, exactly: `kpi/N`.
    phi: String,
    #[serde(rename = "Q1")]
    q1: &'a str,
    /// W: the binary64 nearest the middle of its proven enclosure (absent in gross slip,
    /// where the theory gives none).
    #[serde(rename = "W", skip_serializing_if = "Option::is_none")]
    w: Option<f64>,
    /// W as proven, for the text.
    #[serde(skip)]
    value: Option<Value>,
    /// W is exactly 0, by a reason read from the exact inputs (in phase without slip, say).
    exact_zero: bool,
    /// `partial slip`; `no slip` (in phase within friction, or Q1 = 0), where W is 0; or
    /// `gross slip` where the load ellipse reaches |Q| = fP.
    regime: &'static str,
}

impl Cell<'_> {
    /// W as text: `0` when exactly 0, else at most `digits` proven significant digits; the
    /// regime in gross slip.
    fn shown(&self, digits: u32) -> String {
        match &self.value {
            None => self.regime.to_string(),
            Some(value) => value.to_at_most(digits).to_string(),
        }
    }
}

/// `microslip table --format json`.
#[derive(Serialize)]
struct TableReport<'a> {
    inputs: &'a TableArgs,
    cells: Vec<Cell<'a>>,
}

impl Serialize for TableArgs {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = serializer.serialize_map(None)?;
        map.serialize_entry("p0", &self.p0)?;
        map.serialize_entry("p1", &self.p1)?;
        map.serialize_entry("q0", &self.q0)?;
        map.serialize_entry("q1", &self.q1)?;
        map.serialize_entry("phase_steps", &self.phase_steps)?;
        map.serialize_entry("friction", &self.friction)?;
        match (&self.lambda, &self.nu) {
            (_, Some(nu)) => map.serialize_entry("nu", nu)?,
            (lambda, None) => map.serialize_entry("lambda", lambda.as_deref().unwrap_or("1"))?,
        }
        map.serialize_entry("compliance", &self.compliance)?;
        map.end()
    }
}

impl TableArgs {
    /// The case of one cell.
    fn case(&self, q1: &str, phi: &str) -> CaseText {
        CaseText {
            p0: self.p0.clone(),
            p1: self.p1.clone(),
            q0: self.q0.clone(),
            q1: q1.to_string(),
            phi: phi.to_string(),
            friction: self.friction.clone(),
            lambda: self
                .nu
                .is_none()
                .then(|| self.lambda.clone().unwrap_or_else(|| "1".into())),
            nu: self.nu.clone(),
            compliance: self.compliance.clone(),
        }
    }

    /// Whether the table is the paper's Fig. 5, whose W is the normalized Ŵ.
    fn is_fig5(&self) -> bool {
        let one = |text: &str| text.trim() == "1";
        one(&self.p0)
            && self.p1.trim() == "0.4"
            && self.q0.trim() == "0"
            && one(&self.friction)
            && self.lambda.as_deref().is_none_or(one)
            && self.nu.is_none()
            && self.compliance == FIG5_COMPLIANCE
    }

    /// Every cell, row by row (phase), each row's amplitudes in order.
    fn cells(&self) -> Result<Vec<Cell<'_>>, Failure> {
        let steps = self.phase_steps;
        let mut cells = Vec::with_capacity((steps + 1) * self.q1.len());
        for k in 0..=steps {
            let phi = format!("{k}pi/{steps}");
            for q1 in &self.q1 {
                let cell_failure = |message: String| Failure::refused(format!("φ = {phi}, Q1 = {q1}: {message}"));
                let gross_slip = |error: &CycleError| matches!(error, CycleError::GrossSlip { .. });
                // A cycle in gross slip is refused when read (decided exactly): the cell says so.
                let spec = match self.case(q1, &phi).spec() {
                    Ok(spec) => Some(spec),
                    Err(InputError::Cycle(error)) if gross_slip(&error) => None,
                    Err(error) => return Err(cell_failure(error.to_string())),
                };
                // The case read above, not its text again.
                let value = match &spec {
                    None => None,
                    Some(spec) => Some(
                        dissipation_of(spec, None, CELL_BUDGET)
                            .map_err(|e| cell_failure(e.to_string()))?
                            .answer
                            .value,
                    ),
                };
                let w = value.as_ref().map(|value| value.to_f64().unwrap_or(0.0));
                let exact_zero = spec.as_ref().and_then(|spec| spec.exact_zero());
                let regime = match (w, exact_zero) {
                    (None, _) => "gross slip",
                    (_, Some(ExactZero::InPhaseWithoutSlip | ExactZero::NoTangentialOscillation)) => "no slip",
                    _ => "partial slip",
                };
                cells.push(Cell {
                    phi_over_pi: k as f64 / steps as f64,
                    phi: phi.clone(),
                    q1,
                    w,
                    value,
                    exact_zero: w.is_some() && exact_zero.is_some(),
                    regime,
                });
            }
        }
        Ok(cells)
    }

    /// The table as text: a heading, then a row per phase and a column per amplitude.
    fn text(&self, cells: &[Cell]) -> String {
        let ratio = match &self.nu {
            Some(nu) => format!("ν = {nu}"),
            None => format!("λ = {}", self.lambda.as_deref().unwrap_or("1")),
        };
        let mut out = format!(
            "W per cycle (proven digits) for compliance {}, P0 = {}, P1 = {}, Q0 = {}, f = {}, {ratio}{}\n{:>8}",
            self.compliance,
            self.p0,
            self.p1,
            self.q0,
            self.friction,
            if self.is_fig5() {
                "; here W = Ŵ = W/(γσλf²), the paper's Fig. 5"
            } else {
                ""
            },
            "φ/π"
        );
        for q1 in &self.q1 {
            out.push_str(&format!("   Q1 = {q1:<11}"));
        }
        for row in cells.chunks(self.q1.len().max(1)) {
            let fraction = format!("{:.4}", row[0].phi_over_pi);
            let fraction = fraction.trim_end_matches('0').trim_end_matches('.');
            out.push_str(&format!("\n  {fraction:>6}"));
            for cell in row {
                out.push_str(&format!("   {:<16}", cell.shown(8)));
            }
        }
        out
    }
}

pub fn run(args: &TableArgs) -> Result<String, Failure> {
    let cells = args.cells()?;
    match args.format.as_str() {
        "csv" => {
            let rows = cells.iter().map(|cell| {
                // Every proven digit (15 at most).
                let w = cell
                    .value
                    .as_ref()
                    .map(|value| value.decimal.to_string())
                    .unwrap_or_default();
                [
                    cell.phi_over_pi.to_string(),
                    cell.q1.to_string(),
                    w,
                    cell.regime.to_string(),
                ]
            });
            let text = csv_text(&["phi_over_pi", "Q1", "W", "regime"], rows)?;
            Ok(text.trim_end().to_string())
        }
        "json" => Ok(serde_json::to_string(&TableReport { inputs: args, cells })?),
        _ => Ok(args.text(&cells)),
    }
}
