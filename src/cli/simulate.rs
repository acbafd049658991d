//! `microslip simulate`: W by the independent history simulation, with the steady loop
//! as CSV and its picture on request.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use clap::Args;

use microslip::case::CaseText;
use microslip::files::{check_writable, destination, write_text_atomically, Destination};
use microslip::plot::{plot_cycle, PLOT_EXTENSIONS};
use microslip::simulate::{loop_csv, SimulationOptions};
use microslip::simulation_answer::{simulated_answer, SimulatedAnswer, SimulatedError};
use microslip::verified::F64_MOST_DIGITS;

use super::case::CaseArgs;
use super::json::{printed, SimulationInputs, SimulationReport, ValueEnvelope};
use super::parse;
use super::report::Failure;

#[derive(Args)]
#[command(after_help = "W is energy per cycle in the units of load × approach of the inputs \
(N·m for loads in N and a compliance in m/N), printed only with the digits on which its whole \
estimated error interval rounds alike.")]
pub struct SimulateArgs {
    #[command(flatten)]
    pub case: CaseArgs,
    /// Elements of the coarsest spring bed, at least 20 (doubled twice for the extrapolation); default 400.
    #[arg(long, allow_hyphen_values = true, value_parser = parse::elements)]
    pub elements: Option<usize>,
    /// Load steps per cycle of the coarsest run, at least 40 (doubled twice); default 1200.
    #[arg(long, allow_hyphen_values = true, value_parser = parse::steps)]
    pub steps: Option<usize>,
    /// Fail (exit 1) when the estimated relative error of W exceeds this.
    #[arg(long, allow_hyphen_values = true, value_parser = parse::tolerance, default_value = "1e-6")]
    pub tolerance: f64,
    /// Time budget, in seconds (up to 1e6).
    #[arg(long, allow_hyphen_values = true, value_parser = parse::seconds, default_value = "60")]
    pub max_seconds: Duration,
    /// Write the steady loop (theta,P,Q,u) to this .csv file, or with `-` to standard output
    /// (the report then goes to standard error).
    #[arg(long = "loop")]
    pub loop_csv: Option<PathBuf>,
    /// Draw the load ellipse and the hysteresis loop to this .svg, .png or .pdf file.
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
}

impl SimulateArgs {
    /// Whether the loop is written to standard output (`--loop -`), which then carries it alone.
    pub fn loop_on_standard_output(&self) -> bool {
        self.loop_csv
            .as_deref()
            .is_some_and(|path| matches!(destination(path), Ok(Destination::StandardOutput)))
    }
}

/// Whether two paths name the same file (as far as can be told before either exists).
fn same_file(a: &Path, b: &Path) -> bool {
    let resolve = |p: &Path| {
        std::fs::canonicalize(p)
            .or_else(|_| std::path::absolute(p))
            .unwrap_or_else(|_| p.to_path_buf())
    };
    resolve(a) == resolve(b)
}

/// A failure of the simulation's answer, with the flag that may help and the exit code
/// (both the library's).
fn simulation_failure(error: SimulatedError) -> Failure {
    let message = format!("{error}{}", error.hint());
    match error.exit_code() {
        1 => Failure::failed(message),
        _ => Failure::refused(message),
    }
}

pub fn run(args: &SimulateArgs) -> Result<String, Failure> {
    // Output files are checked before anything is computed.
    if let Some(path) = &args.loop_csv {
        check_writable(path, &["csv"])?;
    }
    if let Some(path) = &args.plot {
        check_writable(path, &PLOT_EXTENSIONS)?;
    }
    if let (Some(csv), Some(plot)) = (&args.loop_csv, &args.plot) {
        if same_file(csv, plot) {
            return Err(Failure::refused(format!(
                "--loop and --plot name the same file {}",
                csv.display()
            )));
        }
    }
    let case = args.case.text();
    let spec = case.spec()?;
    let options = SimulationOptions {
        elements: args.elements,
        steps: args.steps,
        deadline: Some(Instant::now() + args.max_seconds),
        tolerance: Some(args.tolerance),
        ..SimulationOptions::default()
    };
    let simulated = simulated_answer(&spec, &options).map_err(simulation_failure)?;
    let (result, cycle) = (&simulated.result, &simulated.cycle);
    let w = simulated.answer.value.decimal.to_string();
    // A write that fails after the run still reports W.
    let lost =
        |error: &dyn std::fmt::Display| Failure::failed(format!("{error} (the simulation's W = {w} is not lost)"));
    if let Some(path) = &args.loop_csv {
        let text = loop_csv(result).map_err(|e| lost(&e))?;
        write_text_atomically(path, &text).map_err(|e| lost(&e))?;
    }
    if let Some(path) = &args.plot {
        plot_cycle(path, cycle, result).map_err(|e| lost(&e))?;
    }
    if args.json {
        return Ok(serde_json::to_string(&simulation_report(&simulated, &case, args))?);
    }
    let digits = match simulated.answer.value.digits() {
        0 => "no significant digit determined".to_string(),
        1 => "1 significant digit".to_string(),
        n => format!("{} significant digits", n.min(F64_MOST_DIGITS)),
    };
    Ok(format!(
        "W = {w} (work of the load; the frictional work agrees: {}); estimated relative error {:.1e} (an estimate, not proven), {digits}; {} elements, {} steps per cycle (finest run)",
        simulated.friction.decimal,
        result.estimated_rel_error,
        result.elements,
        result.steps
    ))
}

/// The JSON report of a simulation: W with the envelope of a value whose provenance is
/// the simulation itself (an estimate from its refinements, not a proof).
fn simulation_report<'a>(simulated: &SimulatedAnswer, case: &'a CaseText, args: &SimulateArgs) -> SimulationReport<'a> {
    let defaults = SimulationOptions::default();
    let (work, result) = (&simulated.answer, &simulated.result);
    SimulationReport {
        w: printed(&work.value),
        w_f64: result.w_work,
        w_friction: printed(&simulated.friction),
        w_friction_f64: result.w_friction,
        envelope: ValueEnvelope::of(work),
        estimated_rel_error: result.estimated_rel_error,
        method: "history-simulation",
        elements: result.elements,
        steps: result.steps,
        inputs: SimulationInputs {
            case,
            elements: args.elements.or(defaults.elements).unwrap_or(result.elements / 4),
            steps: args.steps.or(defaults.steps).unwrap_or(result.steps / 4),
            tolerance: args.tolerance,
        },
    }
}
