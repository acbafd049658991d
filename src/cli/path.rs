//! `microslip path`: W, the amplitudes, the damping and the harmonics of a contact under
//! any periodic load path read from a file, and the steady loop as CSV on request.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use clap::{ArgGroup, Args};
use rug::Float;
use serde::Serialize;

use microslip::compliance::parse_spec;
use microslip::cycle::compliance_ratio_from_poisson;
use microslip::dissipation_answer::DEFAULT_DIGITS;
use microslip::files::{check_writable, csv_text, destination, write_text_atomically, Destination};
use microslip::path::dissipation::dissipation_of;
use microslip::path::input::{read_harmonics, read_samples};
use microslip::path::{path_dissipation, path_outputs, Contact, LoadPath, PathError, PathOutputs, SteadyCycle};
use microslip::real::{Precision, Real};
use microslip::verified::{agreement_radius, decimal_ball, verify, TwoPrecisions, VerifyError};

use super::case::ContactArgs;
use super::parse;
use super::report::Failure;

#[derive(Args)]
#[command(group(ArgGroup::new("source").required(true).args(["harmonics", "samples"])))]
#[command(after_help = "W is energy per cycle in the units of load × approach of the inputs. \
The path must keep P > 0 and |Q| < fP at every θ (force driving); it is refused naming the θ where \
it does not. W is printed with the digits on which two working precisions agree (agreement, not \
a proof): 15 without --digits, N with --digits N.")]
pub struct PathArgs {
    /// CSV with the header k,P_cos,P_sin,Q_cos,Q_sin: P(θ) = Σ P_cos cos kθ + P_sin sin kθ, Q alike (k ≤ 64).
    #[arg(long)]
    pub harmonics: Option<PathBuf>,
    /// CSV with the header P,Q: one period at equal steps of θ from 0, the last not repeating the
    /// first (at most 1,000,000), taken as their trigonometric interpolant.
    #[arg(long)]
    pub samples: Option<PathBuf>,
    #[command(flatten)]
    pub contact: ContactArgs,
    /// Significant digits of W on which two working precisions must agree (1–1000).
    #[arg(long, allow_hyphen_values = true, value_parser = parse::digits)]
    pub digits: Option<u32>,
    /// Time budget, in seconds (up to 1e6).
    #[arg(long, allow_hyphen_values = true, value_parser = parse::seconds, default_value = "60")]
    pub max_seconds: Duration,
    /// Harmonics k = 0 … K of Q and u to report (the joint's force in harmonic-balance form).
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u16).range(0..=64))]
    pub harmonics_out: u16,
    /// Write the steady loop (theta,P,Q,u) to this .csv file, or with `-` to standard output
    /// (the report then goes to standard error).
    #[arg(long = "loop")]
    pub loop_csv: Option<PathBuf>,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
}

/// Samples of the loop written with `--loop`.
const LOOP_POINTS: usize = 1024;

impl PathArgs {
    /// Whether the loop is written to standard output (`--loop -`), which then carries it alone.
    pub fn loop_on_standard_output(&self) -> bool {
        self.loop_csv
            .as_deref()
            .is_some_and(|path| matches!(destination(path), Ok(Destination::StandardOutput)))
    }

    /// The path file and whether it holds samples.
    fn source(&self) -> (&Path, bool) {
        match (&self.harmonics, &self.samples) {
            (Some(file), _) => (file, false),
            (None, Some(file)) => (file, true),
            (None, None) => unreachable!("clap requires one of --harmonics and --samples"),
        }
    }
}

/// The inputs as text, read again at every precision.
struct PathText {
    file: String,
    contents: String,
    samples: bool,
    friction: String,
    lambda: Option<String>,
    nu: Option<String>,
    compliance: String,
}

/// A path, a contact and a compliance at one precision.
struct Inputs<R: Real> {
    path: LoadPath<R>,
    contact: Contact<R>,
    compliance: Box<dyn microslip::compliance::Compliance<R>>,
}

impl PathText {
    fn read<R: Real>(&self, precision: Precision) -> Result<Inputs<R>, Failure> {
        let path = if self.samples {
            read_samples::<R>(&self.contents, precision)
        } else {
            read_harmonics::<R>(&self.contents, precision)
        }
        .map_err(|error| Failure::refused(format!("{}: {error}", self.file)))?;
        let number = |name: &str, text: &str| {
            R::parse_decimal(text, precision)
                .map_err(|_| Failure::refused(format!("--{name} '{text}' is not a decimal number")))
        };
        let friction = number("friction", &self.friction)?;
        let compliance_ratio = match (&self.lambda, &self.nu) {
            (Some(lambda), _) => number("lambda", lambda)?,
            (None, Some(nu)) => compliance_ratio_from_poisson(&number("nu", nu)?)
                .map_err(|error| Failure::refused(error.to_string()))?,
            (None, None) => unreachable!("clap requires --lambda or --nu"),
        };
        let contact = Contact {
            friction,
            compliance_ratio,
        };
        contact
            .validate()
            .map_err(|error| Failure::refused(error.to_string()))?;
        let compliance =
            parse_spec::<R>(&self.compliance, precision).map_err(|error| Failure::refused(error.to_string()))?;
        Ok(Inputs {
            path,
            contact,
            compliance,
        })
    }
}

/// A path failure: input the theory does not cover is refused (exit 2), a quadrature that
/// did not converge fails (exit 1).
fn path_failure(error: PathError) -> Failure {
    match error {
        PathError::Quadrature(_) => Failure::failed(error.to_string()),
        other => Failure::refused(other.to_string()),
    }
}

/// W at two precisions until they agree to the digits asked for.
struct Agreement<'a> {
    text: &'a PathText,
    deadline: Instant,
}

impl TwoPrecisions for Agreement<'_> {
    type Output = Vec<Float>;
    type Error = Failure;

    fn first(&mut self, precision: Precision, _attempt: u32) -> Result<Vec<Float>, Failure> {
        let inputs = self.text.read::<Float>(precision)?;
        let w = path_dissipation(
            &inputs.path,
            &inputs.contact,
            inputs.compliance.as_ref(),
            Some(self.deadline),
        )
        .map_err(path_failure)?;
        Ok(vec![w.total])
    }

    fn check(&mut self, _first: &Vec<Float>, precision: Precision, attempt: u32) -> Result<Vec<Float>, Failure> {
        self.first(precision, attempt)
    }

    fn values<'v>(&self, output: &'v Vec<Float>) -> &'v [Float] {
        output
    }
}

/// W as printed, its value in f64 and what vouches for it.
struct PrintedW {
    text: String,
    value: f64,
    /// `agreement`.
    provenance: &'static str,
    /// What the provenance rests on, in words.
    detail: String,
    /// The digits two precisions agreed on.
    digits_agreed: Option<u32>,
    /// The higher working precision.
    precision_bits: u32,
}

/// The JSON report.
#[derive(Serialize)]
#[allow(non_snake_case)]
struct PathReport {
    W: String,
    W_f64: f64,
    provenance: &'static str,
    digits_agreed: Option<u32>,
    precision_bits: u32,
    q_amplitude: f64,
    u_amplitude: f64,
    secant_stiffness: f64,
    loss_factor: f64,
    damping_ratio: f64,
    harmonics: Vec<HarmonicReport>,
    segments: usize,
}

#[derive(Serialize)]
#[allow(non_snake_case)]
struct HarmonicReport {
    k: usize,
    Q_cos: f64,
    Q_sin: f64,
    u_cos: f64,
    u_sin: f64,
}

pub fn run(args: &PathArgs) -> Result<String, Failure> {
    let deadline = Instant::now() + args.max_seconds;
    if let Some(path) = &args.loop_csv {
        check_writable(path, &["csv"])?;
    }
    let (file, samples) = args.source();
    let contents = std::fs::read_to_string(file)
        .map_err(|error| Failure::refused(format!("cannot read the path file {}: {error}", file.display())))?;
    let text = PathText {
        file: file.display().to_string(),
        contents,
        samples,
        friction: args.contact.friction.clone(),
        lambda: args.contact.lambda.clone(),
        nu: args.contact.nu.clone(),
        compliance: args.contact.compliance.clone(),
    };
    let inputs = text.read::<f64>(Precision::DOUBLE)?;
    let cycle = SteadyCycle::new(&inputs.path, &inputs.contact).map_err(path_failure)?;
    // The f64 run checks the path and counts its pieces.
    let w =
        dissipation_of(&cycle, &inputs.contact, inputs.compliance.as_ref(), Some(deadline)).map_err(path_failure)?;
    // Never the f64 estimate: two working precisions must agree (the default asks for
    // the default's digits), and the output says it is agreement, not proof.
    let digits = args.digits.unwrap_or(DEFAULT_DIGITS);
    let printed = {
        let mut agreement = Agreement { text: &text, deadline };
        let verified = verify(digits, deadline, &mut agreement).map_err(|error| match error {
            VerifyError::Failed(failure) => failure,
            VerifyError::OutOfBudget(out) => Failure::failed(format!(
                "the time budget ran out before two precisions agreed on {} digits of W ({} agreed); raise --max-seconds",
                out.digits_required(),
                out.digits_agreed
            )),
        })?;
        let (first, second) = (&verified.first[0], &verified.output[0]);
        PrintedW {
            text: decimal_ball(second, &agreement_radius(first, second), digits).to_string(),
            value: second.to_f64(),
            provenance: "agreement",
            detail: format!(
                "two working precisions agree on {} digits, up to {} bits; not proven",
                verified.agreed,
                verified.precision.in_bits()
            ),
            digits_agreed: Some(verified.agreed),
            precision_bits: verified.precision.in_bits(),
        }
    };
    let outputs = path_outputs(
        &inputs.path,
        &cycle,
        &inputs.contact,
        inputs.compliance.as_ref(),
        printed.value,
        usize::from(args.harmonics_out),
        LOOP_POINTS,
    );
    if let Some(path) = &args.loop_csv {
        let rows = outputs
            .steady_loop
            .iter()
            .map(|p| [p.theta, p.normal_load, p.tangential_load, p.displacement].map(|value| value.to_string()));
        let csv = csv_text(&["theta", "P", "Q", "u"], rows).map_err(|error| {
            Failure::failed(format!(
                "the loop could not be written: {error} (W = {} is not lost)",
                printed.text
            ))
        })?;
        write_text_atomically(path, &csv)
            .map_err(|error| Failure::failed(format!("{error} (W = {} is not lost)", printed.text)))?;
    }
    if args.json {
        return Ok(serde_json::to_string(&report(&printed, &outputs, w.segments))?);
    }
    Ok(text_report(&printed, &outputs))
}

fn report(printed: &PrintedW, outputs: &PathOutputs, segments: usize) -> PathReport {
    PathReport {
        W: printed.text.clone(),
        W_f64: printed.value,
        provenance: printed.provenance,
        digits_agreed: printed.digits_agreed,
        precision_bits: printed.precision_bits,
        q_amplitude: outputs.q_amplitude,
        u_amplitude: outputs.u_amplitude,
        secant_stiffness: outputs.secant_stiffness,
        loss_factor: outputs.loss_factor,
        damping_ratio: outputs.damping_ratio,
        harmonics: outputs
            .harmonics
            .iter()
            .map(|h| HarmonicReport {
                k: h.k,
                Q_cos: h.q_cos,
                Q_sin: h.q_sin,
                u_cos: h.u_cos,
                u_sin: h.u_sin,
            })
            .collect(),
        segments,
    }
}

fn text_report(printed: &PrintedW, outputs: &PathOutputs) -> String {
    let mut lines = vec![
        format!("W = {} ({}: {})", printed.text, printed.provenance, printed.detail),
        // What follows is computed in f64 from the path and W: estimates, not proven digits.
        "in f64 (estimates, not proven):".to_string(),
        format!("q_amplitude = {:.10e}", outputs.q_amplitude),
        format!("u_amplitude = {:.10e}", outputs.u_amplitude),
        format!("secant_stiffness = {:.10e}", outputs.secant_stiffness),
        format!("loss_factor = {:.10e}", outputs.loss_factor),
        format!("damping_ratio = {:.10e}", outputs.damping_ratio),
        "k, Q_cos, Q_sin, u_cos, u_sin".to_string(),
    ];
    lines.extend(
        outputs
            .harmonics
            .iter()
            .map(|h| format!("{}, {:e}, {:e}, {:e}, {:e}", h.k, h.q_cos, h.q_sin, h.u_cos, h.u_sin)),
    );
    lines.join("\n")
}
