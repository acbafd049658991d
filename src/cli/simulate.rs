//! `microslip simulate`: W by the independent history simulation of a harmonic cycle
//! (the case flags) or of any periodic path driven by force or by displacement (a file,
//! as `microslip path` reads it), with the steady loop as CSV and, for a cycle, its
//! picture on request.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use clap::{ArgGroup, Args};

use microslip::answer::simulation::{simulated_answer, simulated_path_answer, SimulatedAnswer};
use microslip::answer::{Answer, Value};
use microslip::decimal::printing::F64_MOST_DIGITS;
use microslip::files::{check_writable, destination, write_text_atomically, Destination};
use microslip::path::PathRequest;
use microslip::plot::{plot_cycle, PLOT_EXTENSIONS};
use microslip::simulate::{loop_csv, SimulationOptions, SimulationResult};

use super::case::{ContactArgs, CycleArgs};
use super::json::{
    printed, PathFileInputs, SimulatedAmplitudes, SimulatedLoads, SimulationInputs, SimulationReport, ValueEnvelope,
};
use super::parse;
use super::path::PathFileArgs;
use super::report::Failure;

/// The flags of a harmonic cycle, which a path file replaces.
const CYCLE_FLAGS: [&str; 5] = ["p0", "p1", "q0", "q1", "phi"];

#[derive(Args)]
// The case flags are required unless a path file is named, which conflicts with them.
#[command(group(ArgGroup::new("path_source").args(["harmonics", "samples"])))]
#[command(mut_arg("harmonics", |file| file.conflicts_with_all(CYCLE_FLAGS)))]
#[command(mut_arg("samples", |file| file.conflicts_with_all(CYCLE_FLAGS)))]
#[command(group(ArgGroup::new("path_drive").args(["drive"]).requires("path_source")))]
#[command(
    after_help = "The loads are a harmonic cycle (--p0 … --phi) or a periodic path in a file \
(--harmonics or --samples, read as `microslip path` reads them), driven by the tangential load Q \
(--drive force) or by the displacement u (--drive displacement: each step sets u and Q = Σ t_s \
follows, saturating at ±fP; P may vary, unlike in `microslip path`, but must stay positive; the \
contact is first loaded to the extreme of u of largest magnitude). \
W is energy per cycle in the units of load × approach of the inputs \
(N·m for loads in N and a compliance in m/N), printed only with the digits on which its whole \
estimated error interval rounds alike."
)]
pub struct SimulateArgs {
    #[command(flatten)]
    pub cycle: Option<CycleArgs>,
    #[command(flatten)]
    pub path: PathFileArgs,
    #[command(flatten)]
    pub contact: ContactArgs,
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
    /// Draw the load ellipse and the hysteresis loop to this .svg, .png or .pdf file (a harmonic cycle only).
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

/// W as the work of the load and as the frictional work, and the runs, of either loads.
struct Simulated<'a> {
    answer: &'a Answer,
    friction: &'a Value,
    result: &'a SimulationResult,
    /// Whether the loads are a path file, whose report gives the amplitudes of Q and u.
    path: bool,
}

pub fn run(args: &SimulateArgs) -> Result<String, Failure> {
    // Output files are checked before anything is computed.
    if let Some(path) = &args.loop_csv {
        check_writable(path, &["csv"])?;
    }
    if let Some(path) = &args.plot {
        if args.cycle.is_none() {
            return Err(Failure::refused(
                "--plot draws the ellipse of a harmonic cycle (--p0 … --phi); for a path file write the loop with --loop and plot its CSV",
            ));
        }
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
    let deadline = Instant::now() + args.max_seconds;
    let options = SimulationOptions {
        elements: args.elements,
        steps: args.steps,
        deadline: Some(deadline),
        tolerance: Some(args.tolerance),
        ..SimulationOptions::default()
    };
    match (&args.cycle, args.path.request(&args.contact, deadline)?) {
        (Some(cycle), _) => run_cycle(args, cycle, &options),
        (None, Some(request)) => run_path(args, &request, &options),
        (None, None) => Err(Failure::refused(
            "give the loads: the case flags --p0 --p1 --q1 --phi, or a path file with --harmonics or --samples",
        )),
    }
}

/// The simulation of the harmonic cycle of the case flags.
fn run_cycle(args: &SimulateArgs, cycle: &CycleArgs, options: &SimulationOptions) -> Result<String, Failure> {
    let case = cycle.text(&args.contact);
    let spec = case.spec()?;
    let simulated: SimulatedAnswer = simulated_answer(&spec, options).map_err(|error| Failure::of(&error, false))?;
    let view = Simulated {
        answer: &simulated.answer,
        friction: &simulated.friction,
        result: &simulated.result,
        path: false,
    };
    write_loop(args, &view)?;
    if let Some(path) = &args.plot {
        plot_cycle(path, &simulated.cycle, &simulated.result).map_err(|e| kept_w(&view, &e))?;
    }
    report(args, &view, SimulatedLoads::Case(&case))
}

/// The simulation of the force path of a file.
fn run_path(args: &SimulateArgs, request: &PathRequest, options: &SimulationOptions) -> Result<String, Failure> {
    let simulated = simulated_path_answer(request, options).map_err(|error| Failure::of(&error, false))?;
    let view = Simulated {
        answer: &simulated.answer,
        friction: &simulated.friction,
        result: &simulated.result,
        path: true,
    };
    write_loop(args, &view)?;
    let file = || Some(request.file.clone());
    let inputs = PathFileInputs {
        harmonics: args.path.harmonics.as_ref().and_then(|_| file()),
        samples: args.path.samples.as_ref().and_then(|_| file()),
        drive: request.drive.name(),
        friction: args.contact.friction.clone(),
        lambda: args.contact.lambda.clone(),
        nu: args.contact.nu.clone(),
        compliance: args.contact.compliance.clone(),
    };
    report(args, &view, SimulatedLoads::Path(inputs))
}

/// A write that failed after the run, with the W it does not lose.
fn kept_w(simulated: &Simulated, error: &dyn std::fmt::Display) -> Failure {
    Failure::failed(format!(
        "{error} (the simulation's W = {} is not lost)",
        simulated.answer.value.decimal
    ))
}

/// The steady loop to the file of `--loop`, if named.
fn write_loop(args: &SimulateArgs, simulated: &Simulated) -> Result<(), Failure> {
    if let Some(path) = &args.loop_csv {
        let text = loop_csv(simulated.result).map_err(|e| kept_w(simulated, &e))?;
        write_text_atomically(path, &text).map_err(|e| kept_w(simulated, &e))?;
    }
    Ok(())
}

/// The report, as text or JSON.
fn report(args: &SimulateArgs, simulated: &Simulated, loads: SimulatedLoads) -> Result<String, Failure> {
    let (result, w) = (simulated.result, &simulated.answer.value.decimal);
    if args.json {
        return Ok(serde_json::to_string(&simulation_report(simulated, loads, args))?);
    }
    let digits = match simulated.answer.value.digits() {
        0 => "no significant digit determined".to_string(),
        1 => "1 significant digit".to_string(),
        n => format!("{} significant digits", n.min(F64_MOST_DIGITS)),
    };
    let amplitudes = if simulated.path {
        format!(
            "; Q amplitude {:.6e}, u amplitude {:.6e}, loss factor {:.6e}",
            result.tangential_amplitude(),
            result.displacement_amplitude(),
            result.loss_factor()
        )
    } else {
        String::new()
    };
    Ok(format!(
        "W = {w} (work of the load; the frictional work agrees: {}); estimated relative error {:.1e} (an estimate, not proven), {digits}; {} elements, {} steps per cycle (finest run){amplitudes}",
        simulated.friction.decimal,
        result.estimated_rel_error,
        result.elements,
        result.steps
    ))
}

/// The JSON report of a simulation: W with the envelope of a value whose provenance is
/// the simulation itself (an estimate from its refinements, not a proof).
fn simulation_report<'a>(
    simulated: &Simulated,
    loads: SimulatedLoads<'a>,
    args: &SimulateArgs,
) -> SimulationReport<'a> {
    let defaults = SimulationOptions::default();
    let (work, result) = (simulated.answer, simulated.result);
    SimulationReport {
        w: printed(&work.value),
        w_f64: result.w_work,
        w_friction: printed(simulated.friction),
        w_friction_f64: result.w_friction,
        envelope: ValueEnvelope::of(work),
        estimated_rel_error: result.estimated_rel_error,
        method: "history-simulation",
        elements: result.elements,
        steps: result.steps,
        amplitudes: simulated.path.then(|| SimulatedAmplitudes {
            q_amplitude: result.tangential_amplitude(),
            u_amplitude: result.displacement_amplitude(),
            loss_factor: result.loss_factor(),
        }),
        inputs: SimulationInputs {
            loads,
            elements: args.elements.or(defaults.elements).unwrap_or(result.elements / 4),
            steps: args.steps.or(defaults.steps).unwrap_or(result.steps / 4),
            tolerance: args.tolerance,
        },
    }
}
