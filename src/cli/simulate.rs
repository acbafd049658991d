//! `microslip simulate`: W by the independent history simulation, with the steady loop
//! as CSV and its picture on request.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use clap::Args;

use microslip::answer::{Answer, Provenance, Value};
use microslip::batch;
use microslip::case::{Case, CaseText};
use microslip::files::{check_writable, destination, write_text_atomically, Destination};
use microslip::plot::{plot_cycle, PLOT_EXTENSIONS};
use microslip::real::Precision;
use microslip::simulate::{loop_csv, simulate, SimulationError, SimulationOptions, SimulationResult};
use microslip::verified::{decimal_f64, Decimal, F64_MOST_DIGITS};

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

/// A simulation failure with the flags that may help.
fn simulation_failure(error: SimulationError) -> Failure {
    match error {
        SimulationError::ToleranceNotReached { .. } => Failure::failed(format!(
            "{error}; more --elements and --steps may reach it, or a larger --tolerance accepts it"
        )),
        SimulationError::TooLarge { .. } => Failure::refused(format!("{error}; use fewer --elements or --steps")),
        SimulationError::OutOfTime { .. } => Failure::failed(format!(
            "{error}; raise --max-seconds or use fewer --elements or --steps"
        )),
        other => Failure::refused(other.to_string()),
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
    let Case { mut cycle, compliance } = spec.at::<f64>(Precision::DOUBLE)?;
    // The exact cycle is inside the theory (read above); its f64 copy may round across a
    // boundary it keeps off, and the simulation runs in f64.
    if let Err(error) = cycle.validate() {
        return Err(Failure::failed(format!(
            "rounded to f64 the inputs cross a boundary that the exact cycle keeps off (in f64: {error}); the simulation runs in f64, `microslip dissipation` computes this cycle"
        )));
    }
    // The simulation follows the loads in time: a phase within 2⁻²⁰ of an odd multiple of π is
    // read as the mirror image of its cycle (the same W), turned back here for the loop and plot.
    if spec.phase().is_mirror_image() {
        cycle.phase += std::f64::consts::PI;
        cycle.mean_tangential_load = -cycle.mean_tangential_load;
    }
    batch::check_table_range(spec.compliance(), &cycle)?;
    let options = SimulationOptions {
        elements: args.elements,
        steps: args.steps,
        deadline: Some(Instant::now() + args.max_seconds),
        tolerance: Some(args.tolerance),
        ..SimulationOptions::default()
    };
    let result = simulate(&cycle, compliance.as_ref(), &options).map_err(simulation_failure)?;
    // Where every change of v' over the cycle's loads underflows f64 (an exponential at loads
    // of hundreds of decay loads) the simulated W is 0; only a W that is 0 by its reason is
    // printed as 0.
    if result.w_work == 0.0 && result.w_friction == 0.0 && spec.exact_zero().is_none() {
        return Err(Failure::failed(
            "the simulation's W rounds to 0 in f64 (the changes of v' over the cycle's loads underflow), though \
             nothing in the input makes W exactly 0; `microslip dissipation` gives W at any size"
                .to_string(),
        ));
    }
    let printed = PrintedSimulation::of(&result);
    let w = printed.work.to_string();
    // A write that fails after the run still reports W.
    let lost =
        |error: &dyn std::fmt::Display| Failure::failed(format!("{error} (the simulation's W = {w} is not lost)"));
    if let Some(path) = &args.loop_csv {
        let text = loop_csv(&result).map_err(|e| lost(&e))?;
        write_text_atomically(path, &text).map_err(|e| lost(&e))?;
    }
    if let Some(path) = &args.plot {
        plot_cycle(path, &cycle, &result).map_err(|e| lost(&e))?;
    }
    if args.json {
        return Ok(serde_json::to_string(&simulation_report(&result, &case, args))?);
    }
    let digits = match printed.work.digits() {
        0 => "no significant digit determined".to_string(),
        1 => "1 significant digit".to_string(),
        n => format!("{} significant digits", n.min(F64_MOST_DIGITS)),
    };
    Ok(format!(
        "W = {w} (work of the load; the frictional work agrees: {}); estimated relative error {:.1e} (an estimate, not proven), {digits}; {} elements, {} steps per cycle (finest run)",
        printed.friction,
        result.estimated_rel_error,
        result.elements,
        result.steps
    ))
}

/// The simulation's two measures of W, each printed by the one rule with the absolute
/// bound its estimated relative error gives W (which includes their difference).
struct PrintedSimulation {
    work: Decimal,
    friction: Decimal,
}

impl PrintedSimulation {
    fn of(result: &SimulationResult) -> Self {
        let bound = result.estimated_rel_error * result.w_work.abs();
        PrintedSimulation {
            work: decimal_f64(result.w_work, bound),
            friction: decimal_f64(result.w_friction, bound),
        }
    }
}

/// The JSON report of a simulation: W with the envelope of a value whose provenance is
/// the simulation itself (an estimate from its refinements, not a proof).
fn simulation_report<'a>(result: &SimulationResult, case: &'a CaseText, args: &SimulateArgs) -> SimulationReport<'a> {
    let defaults = SimulationOptions::default();
    let bound = result.estimated_rel_error * result.w_work.abs();
    let work = Answer {
        value: Value::from_f64(result.w_work, bound),
        segments: None,
        digits_requested: None,
        provenance: Provenance::Simulated { error_estimate: bound },
        method: None,
    };
    SimulationReport {
        w: printed(&work.value),
        w_f64: result.w_work,
        w_friction: printed(&Value::from_f64(result.w_friction, bound)),
        w_friction_f64: result.w_friction,
        envelope: ValueEnvelope::of(&work),
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
