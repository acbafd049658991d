//! `microslip`: the command line. Parsing and printing only; the work is in the library.
//! Helpers (value parsers, JSON reports, progress, output) are in `cli/`.

mod cli;

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

use clap::{Args, Parser, Subcommand};

use cli::budget::within;
use cli::json::{
    ClaimRow, CoefficientReport, DissipationReport, GateReport, PartialSumsReport, Segments, SeriesReport, ShapeInputs,
    SimulationInputs, SimulationReport,
};
use cli::parse;
use cli::progress::Progress;
use cli::report::{emit, fail, parse_error, Failure};
use microslip::accuracy;
use microslip::batch::{self, case_dissipation, CaseError};
use microslip::catalogue;
use microslip::dissipation::{dissipation, DissipationError, Method, Options};
use microslip::files::{check_writable, write_atomically, write_text_atomically};
use microslip::inputs::{Case, CaseText};
use microslip::plot::{plot_accuracy, plot_cycle, PLOT_EXTENSIONS};
use microslip::real::{Precision, Real};
use microslip::reference::ReferenceError;
use microslip::simulate::{loop_csv, simulate, SimulationError, SimulationOptions, SimulationResult};
use microslip::verify::{self, small_amplitude, GateOptions};

#[derive(Parser)]
#[command(
    name = "microslip",
    version,
    about = "Frictional microslip dissipation per cycle in rough elastic contacts",
    arg_required_else_help = true
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// The dissipation per cycle W and its four segment contributions.
    Dissipation(Box<DissipationArgs>),
    /// W by brute-force simulation of the contact's loading history (an independent check).
    Simulate(Box<SimulateArgs>),
    /// Accuracy against cost of every quadrature rule and precision, against 100-digit references.
    Accuracy(AccuracyArgs),
    /// Run the theorem gate: every claim over seeded random draws, in f64 and at 256 bits.
    Verify(VerifyArgs),
    /// The small-amplitude coefficient I(ρ, φ) of W ≈ λ f² P1³ v''(P0) I.
    SmallAmplitude(SmallAmplitudeArgs),
    /// The small-amplitude series: Iₙ(ρ, φ) for n = 0 … N, or a case's partial sums beside W.
    Series(Box<SeriesArgs>),
    /// Check the reference values of a catalogue of cases against a fresh computation
    /// (or, with --write, replace them).
    Reference(ReferenceArgs),
    /// A table of Ŵ = W/(γσλf²) against the phase φ for Persson's compliance
    /// v' = γσ/P, P0 = 1, P1 = 0.4 (the paper's Fig. 5).
    Table,
    /// Regenerate the paper's Figures 4–8 (CSV, SVG, PNG) and the facts it states (facts.json).
    Figures(FiguresArgs),
    /// W for every load cycle (row) of a CSV file, on all cores, in input order.
    Batch(BatchArgs),
}

/// A load cycle P = P0 + P1 cos θ, Q = Q0 + Q1 cos(θ − φ) on a contact.
#[derive(Args)]
struct CaseArgs {
    /// Mean normal load P0 (> 0).
    #[arg(long, allow_hyphen_values = true)]
    p0: String,
    /// Normal load amplitude P1 (0 ≤ P1 < P0).
    #[arg(long, allow_hyphen_values = true)]
    p1: String,
    /// Mean tangential load Q0.
    #[arg(long, allow_hyphen_values = true, default_value = "0")]
    q0: String,
    /// Tangential load amplitude Q1 (≥ 0).
    #[arg(long, allow_hyphen_values = true)]
    q1: String,
    /// Phase lag φ of Q behind P, in radians or as a multiple of π (`0.4pi`, `pi-1e-6`).
    #[arg(long, allow_hyphen_values = true)]
    phi: String,
    /// Coulomb friction coefficient f (> 0).
    #[arg(long, allow_hyphen_values = true)]
    friction: String,
    /// Tangential/normal compliance ratio λ, in [1, 2].
    #[arg(
        long,
        allow_hyphen_values = true,
        conflicts_with = "nu",
        required_unless_present = "nu"
    )]
    lambda: Option<String>,
    /// Poisson's ratio ν in [0, 2/3], giving λ = (2 − ν)/(2(1 − ν)) in [1, 2].
    #[arg(long, allow_hyphen_values = true)]
    nu: Option<String>,
    /// Normal compliance SPEC, e.g. `persson:gamma=1,sigma=1`, `power:c=1,beta=-1`,
    /// `hertz:r=1,estar=1`, `poly:p0=1,coeffs=2;-0.5;-0.1`, terms joined by `+`
    /// (`persson:gamma=1,sigma=1+const:c=0.5`); v' > 0 and v'' ≤ 0 are needed.
    #[arg(long, allow_hyphen_values = true)]
    compliance: String,
}

impl CaseArgs {
    fn text(&self) -> CaseText {
        CaseText {
            p0: self.p0.clone(),
            p1: self.p1.clone(),
            q0: self.q0.clone(),
            q1: self.q1.clone(),
            phi: self.phi.clone(),
            friction: self.friction.clone(),
            lambda: self.lambda.clone(),
            nu: self.nu.clone(),
            compliance: self.compliance.clone(),
        }
    }
}

#[derive(Args)]
struct DissipationArgs {
    #[command(flatten)]
    case: CaseArgs,
    /// Significant digits to compute and verify (1–1000); without it, f64 and the digits
    /// its error estimate vouches for.
    #[arg(long, allow_hyphen_values = true, value_parser = parse::digits)]
    digits: Option<u32>,
    /// Time budget for verified digits, in seconds (up to 1e6).
    #[arg(long, allow_hyphen_values = true, value_parser = parse::seconds, default_value = "60")]
    max_seconds: Duration,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct SimulateArgs {
    #[command(flatten)]
    case: CaseArgs,
    /// Elements of the coarsest spring bed, at least 20 (doubled twice for the extrapolation); default 400.
    #[arg(long, allow_hyphen_values = true, value_parser = parse::elements)]
    elements: Option<usize>,
    /// Load steps per cycle of the coarsest run, at least 40 (doubled twice); default 1200.
    #[arg(long, allow_hyphen_values = true, value_parser = parse::steps)]
    steps: Option<usize>,
    /// Fail (exit 1) when the estimated relative error of W exceeds this.
    #[arg(long, allow_hyphen_values = true, value_parser = parse::tolerance, default_value = "1e-6")]
    tolerance: f64,
    /// Time budget, in seconds (up to 1e6).
    #[arg(long, allow_hyphen_values = true, value_parser = parse::seconds, default_value = "60")]
    max_seconds: Duration,
    /// Write the steady loop (theta,P,Q,u) to this .csv file.
    #[arg(long = "loop")]
    loop_csv: Option<PathBuf>,
    /// Draw the load ellipse and the hysteresis loop to this .svg or .png file.
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct AccuracyArgs {
    /// Directory for accuracy.csv, accuracy.svg and accuracy.png (created if missing).
    #[arg(long)]
    out: PathBuf,
    /// Fewer cases, precisions and repeats (well under a minute).
    #[arg(long)]
    quick: bool,
}

#[derive(Args)]
struct VerifyArgs {
    /// A smaller sample (under 10 s).
    #[arg(long)]
    quick: bool,
    /// The seed of the random draws.
    #[arg(long, allow_hyphen_values = true, value_parser = parse::seed, default_value = "2026")]
    seed: u64,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct SmallAmplitudeArgs {
    /// ρ = Q1/(f P1) (> 0).
    #[arg(long, allow_hyphen_values = true)]
    rho: String,
    /// The phase φ, in radians or as a multiple of π (`0.4pi`).
    #[arg(long, allow_hyphen_values = true)]
    phi: String,
    /// Significant digits, verified by a second run at higher precision (1–1000); without
    /// it, f64 with the digits it shares with 15 verified MPFR digits (those MPFR digits
    /// where f64 keeps fewer than 13 or I lies outside its range).
    #[arg(long, allow_hyphen_values = true, value_parser = parse::digits)]
    digits: Option<u32>,
    /// Time budget for verified digits, in seconds (up to 1e6).
    #[arg(long, allow_hyphen_values = true, value_parser = parse::seconds, default_value = "60")]
    max_seconds: Duration,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
}

/// `--rho` for the coefficients Iₙ alone, or a case (`--p0 … --compliance`) for its partial sums.
#[derive(Args)]
struct SeriesArgs {
    /// ρ = Q1/(f P1) (> 0): print I₀ … I_N.
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["p0", "compliance"])]
    rho: Option<String>,
    /// The phase φ, in radians or as a multiple of π (`0.4pi`).
    #[arg(long, allow_hyphen_values = true)]
    phi: String,
    /// The highest order N.
    #[arg(long)]
    order: usize,
    /// Mean normal load P0 (with a case).
    #[arg(long, allow_hyphen_values = true, requires_all = ["p1", "q1", "friction", "compliance"])]
    p0: Option<String>,
    /// Normal load amplitude P1.
    #[arg(long, allow_hyphen_values = true)]
    p1: Option<String>,
    /// Mean tangential load Q0.
    #[arg(long, allow_hyphen_values = true, default_value = "0")]
    q0: String,
    /// Tangential load amplitude Q1.
    #[arg(long, allow_hyphen_values = true)]
    q1: Option<String>,
    /// Coulomb friction coefficient f.
    #[arg(long, allow_hyphen_values = true)]
    friction: Option<String>,
    /// Tangential/normal compliance ratio λ, in [1, 2].
    #[arg(long, allow_hyphen_values = true, conflicts_with = "nu")]
    lambda: Option<String>,
    /// Poisson's ratio ν.
    #[arg(long, allow_hyphen_values = true)]
    nu: Option<String>,
    /// Normal compliance SPEC (as for `dissipation`).
    #[arg(long, allow_hyphen_values = true, requires = "p0")]
    compliance: Option<String>,
    /// Verified significant digits (1–1000); without it, f64 (Iₙ) or 15 verified digits (a case).
    #[arg(long, allow_hyphen_values = true, value_parser = parse::digits)]
    digits: Option<u32>,
    /// Time budget, in seconds (up to 1e6).
    #[arg(long, allow_hyphen_values = true, value_parser = parse::seconds, default_value = "60")]
    max_seconds: Duration,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct ReferenceArgs {
    /// The catalogue file (JSON).
    #[arg(long)]
    catalogue: PathBuf,
    /// Replace the stored values with freshly computed ones (atomically) instead of checking them.
    #[arg(long)]
    write: bool,
    /// Verified significant digits per case (1–1000): with --write, for every case (default 50);
    /// when checking, for cases without a stored value (the others are checked to their stored digits).
    #[arg(long, allow_hyphen_values = true, value_parser = parse::digits)]
    digits: Option<u32>,
    /// Time budget per case, in seconds (up to 1e6).
    #[arg(long, allow_hyphen_values = true, value_parser = parse::seconds, default_value = "120")]
    max_seconds: Duration,
}

#[derive(Args)]
struct BatchArgs {
    /// Input CSV (`-` for stdin): p0,p1,q1,phi,friction,lambda or nu,compliance; optional q0, id.
    #[arg(long)]
    input: String,
    /// Output file (`-` for stdout), written whole or not at all.
    #[arg(long)]
    output: String,
    /// Verified significant digits for every row (1–1000); without it, f64 as a single run.
    #[arg(long, allow_hyphen_values = true, value_parser = parse::digits)]
    digits: Option<u32>,
    /// Output format.
    #[arg(long, value_parser = ["csv", "jsonl"], default_value = "csv")]
    format: String,
    /// Time budget per row for --digits, in seconds (up to 1e6).
    #[arg(long, allow_hyphen_values = true, value_parser = parse::seconds, default_value = "60")]
    max_seconds: Duration,
}

#[derive(Args)]
struct FiguresArgs {
    /// Directory for fig4…fig8 (.csv, .svg, .png), limit_slopes.csv and facts.json.
    #[arg(long)]
    out: PathBuf,
}

fn method_name(method: Method) -> &'static str {
    match method {
        Method::FourSegment => "four-segment integrals in the cycle angle",
        Method::InPhase => "in-phase closed form (paper appendix)",
        Method::ConstantNormalLoad => "constant-normal-load closed form",
        Method::NoTangentialOscillation => "no tangential oscillation (W = 0)",
    }
}

/// A library error on a verified-digits path, with the flag that may help where it applies.
fn reference_failure(error: ReferenceError, digits_given: bool) -> Failure {
    let hint = match &error {
        ReferenceError::Dissipation(
            DissipationError::NotConverged { .. }
            | DissipationError::IllConditioned { .. }
            | DissipationError::OutOfRange { .. },
        ) if !digits_given => "; try --digits N (verified digits in MPFR)",
        ReferenceError::Budget { .. } if digits_given => "; raise --max-seconds or ask for fewer --digits",
        ReferenceError::Budget { .. } => "; raise --max-seconds",
        _ => "",
    };
    Failure::refused(format!("{error}{hint}"))
}

fn run_dissipation(args: &DissipationArgs) -> Result<String, Failure> {
    let case = args.case.text();
    let result = case_dissipation(&case, args.digits, args.max_seconds).map_err(|error| match error {
        CaseError::Reference(error) => reference_failure(error, args.digits.is_some()),
        CaseError::DigitsForTable => Failure::refused(format!("{error}; drop --digits")),
        other => Failure::refused(other.to_string()),
    })?;
    let (printed, table) = (result.printed, result.table);
    if args.json {
        let segments: Vec<String> = printed.segments.iter().map(|(_, value)| value.clone()).collect();
        let report = DissipationReport {
            w: printed.total.clone(),
            w_f64: printed.binary64.map(|values| values[0]),
            digits: printed.digits,
            digits_verified: printed.error_estimate.is_none().then_some(printed.digits),
            precision_bits: printed.precision_bits,
            error_estimate: printed.error_estimate,
            f64_fallback: printed.fallback.clone(),
            method: method_name(printed.method),
            segments: Segments::from_slice(&segments),
            segments_f64: printed.binary64.and_then(|values| Segments::from_slice(&values[1..])),
            inputs: &case,
            table_error: table.as_ref().map(|t| t.error),
            smoothing_residual: table.as_ref().map(|t| t.smoothing_residual),
        };
        return Ok(serde_json::to_string(&report)?);
    }
    let mut out = format!(
        "W = {}   ({}; {} significant digits{})\n",
        printed.total,
        method_name(printed.method),
        printed.digits,
        match (&printed.fallback, printed.error_estimate) {
            (Some(reason), _) => format!(", verified in MPFR: {reason}"),
            (None, Some(_)) if table.is_some() => ", f64, as far as the table and the quadrature vouch".to_string(),
            (None, Some(error)) if printed.digits < 15 => {
                format!(", f64, error estimate {error:.1e}; --digits N gives more")
            }
            (None, Some(_)) => ", f64".to_string(),
            (None, None) => ", verified".to_string(),
        }
    );
    for (name, value) in &printed.segments {
        out.push_str(&format!("  {name}  {value}\n"));
    }
    if let Some(table) = table {
        out.push_str(&format!(
            "  error estimates: table {:.1e} (from the table and its every other row), quadrature {:.1e}{}\n",
            table.error,
            printed.error_estimate.unwrap_or(0.0),
            match table.smoothing_residual {
                r if r > 0.0 => format!("; smoothing moved the data by up to {r:.1e} relative"),
                _ => String::new(),
            }
        ));
    }
    Ok(out.trim_end().to_string())
}

fn run_reference(args: &ReferenceArgs) -> Result<String, Failure> {
    let entries = catalogue::load(&args.catalogue)?;
    let total = entries.len();
    let progress = Progress::new(total);
    let show = |index: usize, name: &str| progress.at(index, name);
    if args.write {
        check_writable(&args.catalogue, &[])?;
        let digits = args.digits.unwrap_or(50);
        let updated = catalogue::regenerate(&entries, digits, args.max_seconds, show);
        progress.finish();
        let updated = updated?;
        catalogue::save(&args.catalogue, &updated).map_err(|e| Failure::failed(e.to_string()))?;
        return Ok(format!(
            "{} reference values to {digits} verified digits written to {}",
            updated.len(),
            args.catalogue.display()
        ));
    }
    let differences = catalogue::check(&entries, args.digits.unwrap_or(50), args.max_seconds, show);
    progress.finish();
    if differences.is_empty() {
        return Ok(format!(
            "all {total} reference values in {} reproduce to their stored digits",
            args.catalogue.display()
        ));
    }
    let mut message = format!(
        "{} of {total} reference values in {} are not reproduced (nothing written; --write replaces them):",
        differences.len(),
        args.catalogue.display()
    );
    for difference in &differences {
        message.push_str(&format!("\n  {difference}"));
    }
    Err(Failure::failed(message))
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
        SimulationError::OutOfTime { .. } => Failure::refused(format!(
            "{error}; raise --max-seconds or use fewer --elements or --steps"
        )),
        other => Failure::refused(other.to_string()),
    }
}

fn run_simulate(args: &SimulateArgs) -> Result<String, Failure> {
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
    let Case { cycle, compliance } = case.read::<f64>(Precision::DOUBLE)?;
    batch::check_table_range(&args.case.compliance, &cycle)?;
    let options = SimulationOptions {
        elements: args.elements,
        steps: args.steps,
        deadline: Some(Instant::now() + args.max_seconds),
        tolerance: Some(args.tolerance),
        ..SimulationOptions::default()
    };
    let result = simulate(&cycle, compliance.as_ref(), &options).map_err(simulation_failure)?;
    let digits = result.vouched_digits().max(1);
    let w = result.w_work.to_scientific(digits as usize);
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
        return Ok(serde_json::to_string(&simulation_report(&result, digits, &case, args))?);
    }
    Ok(format!(
        "W = {w} (work of the load) = {} (frictional work); estimated relative error {:.1e}, {digits} significant digits; {} elements, {} steps per cycle (finest run)",
        result.w_friction.to_scientific(digits as usize),
        result.estimated_rel_error,
        result.elements,
        result.steps
    ))
}

fn simulation_report<'a>(
    result: &SimulationResult,
    digits: u32,
    case: &'a CaseText,
    args: &SimulateArgs,
) -> SimulationReport<'a> {
    let defaults = SimulationOptions::default();
    SimulationReport {
        w: result.w_work.to_scientific(digits as usize),
        w_f64: result.w_work,
        w_friction: result.w_friction.to_scientific(digits as usize),
        w_friction_f64: result.w_friction,
        digits,
        digits_verified: None,
        precision_bits: 53,
        estimated_rel_error: result.estimated_rel_error,
        method: "history simulation of a spring bed, Richardson-extrapolated from three resolutions",
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

fn run_accuracy(args: &AccuracyArgs) -> Result<String, Failure> {
    // The directory and its three files are checked before the (long) measurement.
    if args.out.exists() && !args.out.is_dir() {
        return Err(Failure::refused(format!(
            "--out {}: exists and is not a directory",
            args.out.display()
        )));
    }
    std::fs::create_dir_all(&args.out).map_err(|e| Failure::refused(format!("{}: {e}", args.out.display())))?;
    let csv = args.out.join("accuracy.csv");
    let (svg, png) = (args.out.join("accuracy.svg"), args.out.join("accuracy.png"));
    for path in [&csv, &svg, &png] {
        check_writable(path, &[])?;
    }
    let cases = accuracy::standard_cases(args.quick);
    let progress = Progress::new(cases.len());
    let mut measurements = Vec::new();
    for (index, case) in cases.iter().enumerate() {
        progress.at(index, &format!("{}: 100-digit reference", case.name));
        let reference = accuracy::reference_value(&case.text);
        let reference = match reference {
            Ok(reference) => reference,
            Err(error) => {
                progress.finish();
                return Err(error.into());
            }
        };
        measurements.extend(accuracy::measure_case(case, &reference, args.quick, |stage| {
            progress.at(index, &format!("{}: {stage}", case.name));
        }));
    }
    progress.finish();
    let written = accuracy::to_csv(&measurements)
        .map_err(|e| e.to_string())
        .and_then(|text| write_text_atomically(&csv, &text).map_err(|e| e.to_string()))
        .and_then(|()| plot_accuracy(&svg, &measurements).map_err(|e| e.to_string()))
        .and_then(|()| plot_accuracy(&png, &measurements).map_err(|e| e.to_string()));
    written.map_err(Failure::failed)?;
    let mut out = format!(
        "{:>8}  {:<28} {:>9} {:>9}  {:>12}  {}\n",
        "target", "cheapest rule", "bits", "parameter", "seconds", "case"
    );
    for case in &cases {
        let of_case: Vec<_> = measurements.iter().filter(|m| m.case == case.name).cloned().collect();
        for target in [1e-8, 1e-13, 1e-30, 1e-50, 1e-100] {
            match accuracy::cheapest_for(&of_case, target) {
                Some(m) => out.push_str(&format!(
                    "{target:>8.0e}  {:<28} {:>9} {:>9} {:>12.3e}  {}\n",
                    m.rule, m.precision_bits, m.parameter, m.seconds, m.case
                )),
                None => out.push_str(&format!(
                    "{target:>8.0e}  {:<28} {:>9} {:>9} {:>12}  {}\n",
                    "(none reached it)", "", "", "", case.name
                )),
            }
        }
    }
    out.push_str(&format!(
        "{} measurements written to {}",
        measurements.len(),
        args.out.display()
    ));
    Ok(out)
}

/// The working precision of a gate row (`f64` or `N bits`) in bits.
fn precision_bits(precision: &str) -> u32 {
    if precision == "f64" {
        return 53;
    }
    precision
        .split_whitespace()
        .next()
        .and_then(|bits| bits.parse().ok())
        .unwrap_or(0)
}

fn run_verify(args: &VerifyArgs) -> Result<(String, bool), Failure> {
    let options = GateOptions {
        seed: args.seed,
        quick: args.quick,
    };
    let started = Instant::now();
    let progress = Progress::new(0);
    let reports = verify::run(options, |done, total, name| {
        progress.at_of(done, total, &format!("{name} done"));
    });
    progress.finish();
    let passed = reports.iter().all(|r| r.passed);
    let seconds = started.elapsed().as_secs_f64();
    if args.json {
        let report = GateReport {
            passed,
            seed: args.seed,
            quick: args.quick,
            seconds,
            claims: reports
                .iter()
                .map(|r| ClaimRow {
                    claim: &r.claim,
                    precision_bits: precision_bits(&r.precision),
                    cases: r.cases,
                    worst_error: r.worst_error,
                    tolerance: r.tolerance,
                    passed: r.passed,
                    note: &r.note,
                })
                .collect(),
        };
        return Ok((serde_json::to_string(&report)?, passed));
    }
    let mut out = format!(
        "{:<62} {:<9} {:>6} {:>11} {:>9}  result\n",
        "claim", "precision", "cases", "worst", "tolerance"
    );
    for r in &reports {
        out.push_str(&format!(
            "{:<62} {:<9} {:>6} {:>11.3e} {:>9.0e}  {}\n",
            r.claim,
            r.precision,
            r.cases,
            r.worst_error,
            r.tolerance,
            if r.passed { "pass" } else { "FAIL" }
        ));
        if !r.note.is_empty() {
            out.push_str(&format!("    {}\n", r.note));
        }
    }
    out.push_str(&format!(
        "{} in {seconds:.1} s (seed {})",
        if passed { "all claims hold" } else { "SOME CLAIMS FAIL" },
        args.seed
    ));
    Ok((out, passed))
}

fn run_small_amplitude(args: &SmallAmplitudeArgs) -> Result<String, Failure> {
    let printed = small_amplitude::evaluate(&args.rho, &args.phi, args.digits, args.max_seconds)?;
    if args.json {
        let report = CoefficientReport {
            i: printed.value.clone(),
            i_f64: printed.binary64,
            digits: printed.digits,
            digits_verified: Some(printed.digits),
            precision_bits: printed.precision_bits,
            inputs: ShapeInputs {
                rho: &args.rho,
                phi: &args.phi,
            },
        };
        return Ok(serde_json::to_string(&report)?);
    }
    Ok(format!("I(ρ = {}, φ = {}) = {}", args.rho, args.phi, printed.value))
}

fn run_series(args: &SeriesArgs) -> Result<String, Failure> {
    use microslip::exact::printing::{printed_coefficients, printed_partial_sums};
    let budget = args.max_seconds;
    let Some(p0) = &args.p0 else {
        let rho = args
            .rho
            .as_deref()
            .ok_or_else(|| Failure::refused("give --rho, or a case with --p0 … --compliance"))?;
        let printed = printed_coefficients(rho, &args.phi, args.order, args.digits, budget)?;
        let digits = printed.digits.iter().copied().min().unwrap_or(0);
        if args.json {
            let report = SeriesReport {
                rho,
                phi: &args.phi,
                digits,
                coefficients: &printed.values,
                digits_verified: &printed.digits,
                coefficients_f64: (!printed.binary64.is_empty()).then_some(&printed.binary64),
            };
            return Ok(serde_json::to_string(&report)?);
        }
        let rows: Vec<String> = printed
            .values
            .iter()
            .enumerate()
            .map(|(n, v)| format!("I_{n:<3} = {v}"))
            .collect();
        return Ok(format!(
            "Iₙ(ρ = {rho}, φ = {}), n = 0 … {}:\n{}",
            args.phi,
            args.order,
            rows.join("\n")
        ));
    };
    let missing = || Failure::refused("a case needs --p0, --p1, --q1, --friction, --lambda or --nu, and --compliance");
    let case = CaseText {
        p0: p0.clone(),
        p1: args.p1.clone().ok_or_else(missing)?,
        q0: args.q0.clone(),
        q1: args.q1.clone().ok_or_else(missing)?,
        phi: args.phi.clone(),
        friction: args.friction.clone().ok_or_else(missing)?,
        lambda: args.lambda.clone(),
        nu: args.nu.clone(),
        compliance: args.compliance.clone().ok_or_else(missing)?,
    };
    let printed = printed_partial_sums(&case, args.order, args.digits, budget)?;
    let differences: Vec<String> = printed
        .differences
        .iter()
        .map(|d| d.clone().unwrap_or_else(|| "0".into()))
        .collect();
    if args.json {
        let report = PartialSumsReport {
            w: &printed.dissipation,
            w_digits_verified: printed.dissipation_digits,
            partial_sums: &printed.sums,
            differences: &differences,
            digits_verified: printed.digits,
            inputs: &case,
        };
        return Ok(serde_json::to_string(&report)?);
    }
    let width = printed.digits as usize + 8;
    let mut out = format!(
        "W (four-segment) = {}\n   N  {:<width$}  W_N − W",
        printed.dissipation, "W_N (series to order N)"
    );
    for (n, (sum, difference)) in printed.sums.iter().zip(&differences).enumerate() {
        out.push_str(&format!("\n{:>4}  {sum:<width$}  {difference}", n + 1));
    }
    Ok(out)
}

fn run_table() -> Result<String, Failure> {
    let amplitudes = ["0.2", "0.4", "0.5", "0.6"];
    let mut out = String::from("Ŵ = W/(γσλf²) for v' = γσ/P, P0 = 1, P1 = 0.4, f = 1 (f64)\n   φ/π");
    for q1 in amplitudes {
        out.push_str(&format!("   Q1 = {q1:<11}"));
    }
    for tenths in 0..=10 {
        out.push_str(&format!("\n  {:>4.1}", f64::from(tenths) / 10.0));
        for q1 in amplitudes {
            let case = CaseText {
                p0: "1".into(),
                p1: "0.4".into(),
                q0: "0".into(),
                q1: q1.into(),
                phi: format!("{}pi", f64::from(tenths) / 10.0),
                friction: "1".into(),
                lambda: Some("1".into()),
                nu: None,
                compliance: "persson:gamma=1,sigma=1".into(),
            };
            let Case { cycle, compliance } = case.read::<f64>(Precision::DOUBLE)?;
            let cell = match dissipation(&cycle, compliance.as_ref(), &Options::default()) {
                Ok(result) => result.total.to_scientific(8),
                Err(_) => "gross slip".to_string(),
            };
            out.push_str(&format!("   {cell:<16}"));
        }
    }
    Ok(out)
}

fn run_figures(args: &FiguresArgs) -> Result<String, Failure> {
    let progress = Progress::new(0);
    let summary = microslip::figures::regenerate(&args.out, &|done, total| progress.at_of(done, total, "steps"));
    progress.finish();
    let summary = summary?;
    let facts = microslip::figures::output::FactsJson::of(&summary.figures.facts);
    Ok(format!(
        "{} files written to {}\n{}\n{}",
        summary.files.len(),
        args.out.display(),
        serde_json::to_string_pretty(&facts)?,
        summary.figures.facts.settling_report()
    ))
}

/// Runs a batch; Ok(failed rows). Nothing is written when the input cannot be read.
fn run_batch(args: &BatchArgs) -> Result<usize, Failure> {
    if args.output != "-" {
        check_writable(Path::new(&args.output), &[])?;
    }
    let input = if args.input == "-" {
        batch::read_input(std::io::stdin().lock())?
    } else {
        let file = std::fs::File::open(&args.input).map_err(|e| Failure::refused(format!("{}: {e}", args.input)))?;
        batch::read_input(std::io::BufReader::new(file))
            .map_err(|e| Failure::refused(format!("{}: {e}", args.input)))?
    };
    let progress = Progress::new(input.rows.len());
    let done = std::sync::atomic::AtomicUsize::new(0);
    let started = Instant::now();
    let results = batch::run(&input, args.digits, args.max_seconds, &|| {
        let finished = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        progress.at(finished, "rows");
    });
    progress.finish();
    let contents = match args.format.as_str() {
        "jsonl" => cli::json::lines(&batch::records(&input, &results))?,
        _ => batch::to_csv(&input, &results)?,
    };
    if args.output == "-" {
        let mut stdout = std::io::stdout().lock();
        match std::io::Write::write_all(&mut stdout, &contents).and_then(|()| std::io::Write::flush(&mut stdout)) {
            Err(error) if error.kind() != std::io::ErrorKind::BrokenPipe => {
                return Err(Failure::failed(format!("writing to standard output: {error}")));
            }
            _ => {}
        }
    } else {
        write_atomically(Path::new(&args.output), |file| std::fs::write(file, &contents))
            .map_err(|e| Failure::failed(e.to_string()))?;
    }
    let failed = results.iter().filter(|r| !r.succeeded()).count();
    if failed > 0 || args.output != "-" {
        cli::report::warn(&format!(
            "{} rows in {:.2} s, {failed} failed{}",
            results.len(),
            started.elapsed().as_secs_f64(),
            if failed > 0 { " (see their error column)" } else { "" }
        ));
    }
    Ok(failed)
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(error) => return parse_error(&error),
    };
    let outcome = match &cli.command {
        Command::Dissipation(args) => within(args.max_seconds, || run_dissipation(args)),
        Command::Verify(args) => match run_verify(args) {
            Ok((text, passed)) => {
                return emit(&text, if passed { ExitCode::SUCCESS } else { ExitCode::from(1) });
            }
            Err(failure) => Err(failure),
        },
        Command::SmallAmplitude(args) => within(args.max_seconds, || run_small_amplitude(args)),
        Command::Series(args) => within(args.max_seconds, || run_series(args)),
        Command::Simulate(args) => within(args.max_seconds, || run_simulate(args)),
        Command::Accuracy(args) => run_accuracy(args),
        Command::Reference(args) => run_reference(args),
        Command::Table => run_table(),
        Command::Figures(args) => run_figures(args),
        Command::Batch(args) => match run_batch(args) {
            Ok(0) => return ExitCode::SUCCESS,
            Ok(_) => return ExitCode::from(cli::report::FAILED),
            Err(failure) => Err(failure),
        },
    };
    match outcome {
        Ok(text) => emit(&text, ExitCode::SUCCESS),
        Err(failure) => fail(&failure),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_digits_hint_is_given_only_where_digits_were_not() {
        let out_of_range = || ReferenceError::Dissipation(DissipationError::OutOfRange { scale: 1e-310 });
        assert!(reference_failure(out_of_range(), false)
            .message
            .ends_with("try --digits N (verified digits in MPFR)"));
        assert!(!reference_failure(out_of_range(), true).message.contains("--digits"));
        let budget = || ReferenceError::Budget {
            digits_requested: 30,
            digits_reached: 3,
            seconds: 1.0,
            precision_bits: 256,
        };
        assert!(reference_failure(budget(), true).message.contains("fewer --digits"));
        assert!(!reference_failure(budget(), false).message.contains("--digits"));
    }

    #[test]
    fn gate_precisions_read_as_bits() {
        assert_eq!(precision_bits("f64"), 53);
        assert_eq!(precision_bits("256 bits"), 256);
    }
}
