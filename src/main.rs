//! `microslip`: the command line. Parsing and printing only; the work is in the library.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

use clap::{Args, Parser, Subcommand};
use serde_json::json;

use microslip::accuracy;
use microslip::catalogue;
use microslip::dissipation::{dissipation, Method, Options};
use microslip::inputs::{Case, CaseText};
use microslip::plot::{plot_accuracy, plot_cycle};
use microslip::real::{Precision, Real};
use microslip::reference::printable_dissipation;
use microslip::simulate::{simulate, write_loop_csv, SimulationOptions};
use microslip::verify::{self, small_amplitude, GateOptions};

#[derive(Parser)]
#[command(
    name = "microslip",
    version,
    about = "Frictional microslip dissipation per cycle in rough elastic contacts"
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
    /// Recompute the reference values of a catalogue of cases, in place.
    Reference(ReferenceArgs),
    /// A table of Ŵ = W/(γσλf²) against the phase φ for Persson's compliance
    /// v' = γσ/P, P0 = 1, P1 = 0.4 (the paper's Fig. 5).
    Table,
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
    /// Phase lag φ of Q behind P, in radians or as a multiple of π (`0.4pi`).
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
    /// Poisson's ratio ν, giving λ = (2 − ν)/(2(1 − ν)).
    #[arg(long, allow_hyphen_values = true)]
    nu: Option<String>,
    /// Normal compliance SPEC, e.g. `persson:gamma=1,sigma=1`, `power:c=1,beta=-1`,
    /// `hertz:r=1,estar=1`, `poly:p0=1,coeffs=2;0.5;-0.1`, terms joined by `+`.
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
    /// Significant digits to compute and verify (1–1000); without it, f64 and 15 digits.
    #[arg(long)]
    digits: Option<u32>,
    /// Time budget for --digits, in seconds.
    #[arg(long, default_value_t = 60.0)]
    max_seconds: f64,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct SimulateArgs {
    #[command(flatten)]
    case: CaseArgs,
    /// Elements of the coarsest spring bed (doubled twice for the extrapolation).
    #[arg(long)]
    elements: Option<usize>,
    /// Load steps per cycle of the coarsest run (doubled twice).
    #[arg(long)]
    steps: Option<usize>,
    /// Write the steady loop (theta,P,Q,u) to this CSV file.
    #[arg(long = "loop")]
    loop_csv: Option<PathBuf>,
    /// Draw the load ellipse and the hysteresis loop (SVG, or PNG for a .png name).
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct AccuracyArgs {
    /// Directory for accuracy.csv, accuracy.svg and accuracy.png.
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
    #[arg(long, default_value_t = 2026)]
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
    #[arg(long)]
    digits: Option<u32>,
    /// Time budget for verified digits, in seconds.
    #[arg(long, default_value_t = 60.0)]
    max_seconds: f64,
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
    #[arg(long)]
    digits: Option<u32>,
    /// Time budget, in seconds.
    #[arg(long, default_value_t = 60.0)]
    max_seconds: f64,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct ReferenceArgs {
    /// The catalogue file (JSON), rewritten with the new reference values.
    #[arg(long)]
    catalogue: PathBuf,
    /// Verified significant digits per case.
    #[arg(long, default_value_t = 50)]
    digits: u32,
    /// Time budget per case, in seconds.
    #[arg(long, default_value_t = 120.0)]
    max_seconds: f64,
}

/// A failure to report: one line on stderr, exit code 2.
struct Failure(String);

impl<E: std::fmt::Display> From<E> for Failure {
    fn from(error: E) -> Self {
        Failure(error.to_string())
    }
}

fn method_name(method: Method) -> &'static str {
    match method {
        Method::FourSegment => "four-segment integrals in the cycle angle",
        Method::InPhase => "in-phase closed form (paper appendix)",
        Method::ConstantNormalLoad => "constant-normal-load closed form",
        Method::NoTangentialOscillation => "no tangential oscillation (W = 0)",
    }
}

fn run_dissipation(args: &DissipationArgs) -> Result<String, Failure> {
    let case = args.case.text();
    if !(args.max_seconds.is_finite() && args.max_seconds > 0.0) {
        return Err(Failure(format!(
            "--max-seconds must be a positive number, got {}",
            args.max_seconds
        )));
    }
    let printed = printable_dissipation(&case, args.digits, Duration::from_secs_f64(args.max_seconds))?;
    if args.json {
        let segments: serde_json::Map<String, serde_json::Value> = printed
            .segments
            .iter()
            .map(|(name, value)| (name.to_string(), json!(value)))
            .collect();
        let object = json!({
            "W": printed.total,
            "digits": printed.digits,
            "digits_verified": printed.error_estimate.is_none().then_some(printed.digits),
            "precision_bits": printed.precision_bits,
            "error_estimate": printed.error_estimate,
            "f64_fallback": printed.fallback,
            "method": method_name(printed.method),
            "segments": segments,
            "inputs": case,
        });
        return Ok(object.to_string());
    }
    let mut out = format!(
        "W = {}   ({}; {} significant digits{})\n",
        printed.total,
        method_name(printed.method),
        printed.digits,
        match (&printed.fallback, printed.error_estimate) {
            (Some(reason), _) => format!(", verified in MPFR: {reason}"),
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
    Ok(out.trim_end().to_string())
}

fn run_reference(args: &ReferenceArgs) -> Result<String, Failure> {
    if !(args.max_seconds.is_finite() && args.max_seconds > 0.0) {
        return Err(Failure(format!(
            "--max-seconds must be a positive number, got {}",
            args.max_seconds
        )));
    }
    let entries = catalogue::load(&args.catalogue)?;
    let total = entries.len();
    let updated = catalogue::regenerate(
        &entries,
        args.digits,
        Duration::from_secs_f64(args.max_seconds),
        |index, name| {
            if std::io::stderr().is_terminal() {
                eprint!("\r\x1b[K[{}/{total}] {name}", index + 1);
            }
        },
    )?;
    if std::io::stderr().is_terminal() {
        eprintln!();
    }
    catalogue::save(&args.catalogue, &updated)?;
    Ok(format!(
        "{} reference values to {} verified digits written to {}",
        updated.len(),
        args.digits,
        args.catalogue.display()
    ))
}

fn run_simulate(args: &SimulateArgs) -> Result<String, Failure> {
    let Case { cycle, compliance } = args.case.text().read::<f64>(Precision::DOUBLE)?;
    let options = SimulationOptions {
        elements: args.elements,
        steps: args.steps,
        ..SimulationOptions::default()
    };
    let result = simulate(&cycle, compliance.as_ref(), &options)?;
    if let Some(path) = &args.loop_csv {
        write_loop_csv(path, &result).map_err(|e| Failure(format!("{}: {e}", path.display())))?;
    }
    if let Some(path) = &args.plot {
        plot_cycle(path, &cycle, &result)?;
    }
    if args.json {
        return Ok(json!({
            "W_work": result.w_work,
            "W_friction": result.w_friction,
            "estimated_rel_error": result.estimated_rel_error,
            "elements": result.elements,
            "steps": result.steps,
        })
        .to_string());
    }
    Ok(format!(
        "W = {:.10e} (work of the load) = {:.10e} (frictional work); estimated relative error {:.1e}; {} elements, {} steps per cycle (finest run)",
        result.w_work, result.w_friction, result.estimated_rel_error, result.elements, result.steps
    ))
}

fn run_accuracy(args: &AccuracyArgs) -> Result<String, Failure> {
    std::fs::create_dir_all(&args.out).map_err(|e| Failure(format!("{}: {e}", args.out.display())))?;
    let show = std::io::stderr().is_terminal();
    let cases = accuracy::standard_cases(args.quick);
    let mut measurements = Vec::new();
    for (index, case) in cases.iter().enumerate() {
        if show {
            eprint!(
                "\r\x1b[K[{}/{}] {}: 100-digit reference",
                index + 1,
                cases.len(),
                case.name
            );
        }
        let reference = accuracy::reference_value(&case.text)?;
        measurements.extend(accuracy::measure_case(case, &reference, args.quick, |stage| {
            if show {
                eprint!("\r\x1b[K[{}/{}] {}: {stage}", index + 1, cases.len(), case.name);
            }
        }));
    }
    if show {
        eprintln!();
    }
    let csv = args.out.join("accuracy.csv");
    std::fs::write(&csv, accuracy::to_csv(&measurements)).map_err(|e| Failure(format!("{}: {e}", csv.display())))?;
    plot_accuracy(&args.out.join("accuracy.svg"), &measurements)?;
    plot_accuracy(&args.out.join("accuracy.png"), &measurements)?;
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

fn run_verify(args: &VerifyArgs) -> Result<(String, bool), Failure> {
    let options = GateOptions {
        seed: args.seed,
        quick: args.quick,
    };
    let show_progress = std::io::stderr().is_terminal();
    let started = std::time::Instant::now();
    let reports = verify::run(options, |done, total, name| {
        if show_progress {
            eprint!("\r\x1b[K[{done}/{total}] {name} done");
        }
    });
    if show_progress {
        eprintln!();
    }
    let passed = reports.iter().all(|r| r.passed);
    let seconds = started.elapsed().as_secs_f64();
    if args.json {
        let object =
            json!({"passed": passed, "seed": args.seed, "quick": args.quick, "seconds": seconds, "claims": reports});
        return Ok((object.to_string(), passed));
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
    if !(args.max_seconds.is_finite() && args.max_seconds > 0.0) {
        return Err(Failure(format!(
            "--max-seconds must be a positive number, got {}",
            args.max_seconds
        )));
    }
    let budget = Duration::from_secs_f64(args.max_seconds);
    let printed = small_amplitude::evaluate(&args.rho, &args.phi, args.digits, budget)?;
    if args.json {
        return Ok(
            json!({"rho": args.rho, "phi": args.phi, "I": printed.value, "I_f64": printed.binary64,
            "digits": printed.digits, "digits_verified": printed.digits})
            .to_string(),
        );
    }
    Ok(format!("I(ρ = {}, φ = {}) = {}", args.rho, args.phi, printed.value))
}

fn run_series(args: &SeriesArgs) -> Result<String, Failure> {
    use microslip::exact::printing::{printed_coefficients, printed_partial_sums};
    if !(args.max_seconds.is_finite() && args.max_seconds > 0.0) {
        return Err(Failure(format!(
            "--max-seconds must be a positive number, got {}",
            args.max_seconds
        )));
    }
    let budget = Duration::from_secs_f64(args.max_seconds);
    let Some(p0) = &args.p0 else {
        let rho = args
            .rho
            .as_deref()
            .ok_or_else(|| Failure("give --rho, or a case with --p0 … --compliance".into()))?;
        let printed = printed_coefficients(rho, &args.phi, args.order, args.digits, budget)?;
        let digits = printed.digits.iter().copied().min().unwrap_or(0);
        if args.json {
            let mut out = json!({"rho": rho, "phi": args.phi, "digits": digits, "coefficients": printed.values,
                "digits_verified": printed.digits});
            if !printed.binary64.is_empty() {
                out["coefficients_f64"] = json!(printed.binary64);
            }
            return Ok(out.to_string());
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
    let missing = || Failure("a case needs --p0, --p1, --q1, --friction, --lambda or --nu, and --compliance".into());
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
        return Ok(
            json!({"W": printed.dissipation, "W_digits_verified": printed.dissipation_digits,
            "partial_sums": printed.sums, "differences": differences, "digits_verified": printed.digits})
            .to_string(),
        );
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

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(error) => {
            use clap::error::ErrorKind;
            if matches!(error.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
                print!("{error}");
                return ExitCode::SUCCESS;
            }
            let rendered = error.to_string();
            let first = rendered.lines().next().unwrap_or("invalid arguments");
            eprintln!("microslip: {}", first.trim_start_matches("error: "));
            return ExitCode::from(2);
        }
    };
    let outcome = match &cli.command {
        Command::Dissipation(args) => run_dissipation(args),
        Command::Verify(args) => match run_verify(args) {
            Ok((text, passed)) => {
                println!("{text}");
                return if passed { ExitCode::SUCCESS } else { ExitCode::from(1) };
            }
            Err(failure) => Err(failure),
        },
        Command::SmallAmplitude(args) => run_small_amplitude(args),
        Command::Series(args) => run_series(args),
        Command::Simulate(args) => run_simulate(args),
        Command::Accuracy(args) => run_accuracy(args),
        Command::Reference(args) => run_reference(args),
        Command::Table => run_table(),
    };
    match outcome {
        Ok(text) => {
            println!("{text}");
            ExitCode::SUCCESS
        }
        Err(Failure(message)) => {
            eprintln!("microslip: {message}");
            ExitCode::from(2)
        }
    }
}
