//! `microslip path`: W, the amplitudes, the damping and the harmonics of a contact under
//! any periodic load path read from a file, and the steady loop as CSV on request.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use clap::{ArgGroup, Args, ValueEnum};
use serde::Serialize;

use microslip::answer::path::{path_answer, AgreedW, PathAnswer};
use microslip::files::{check_writable, csv_text, destination, write_text_atomically, Destination};
use microslip::path::{Drive, PathFormat, PathOutputs, PathRequest, RatioText};

use super::case::ContactArgs;
use super::parse;
use super::report::Failure;

/// What the path file prescribes besides P.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum DriveArg {
    /// The tangential load Q (columns Q_cos,Q_sin or Q).
    #[default]
    Force,
    /// The tangential displacement u (columns u_cos,u_sin or u): at constant P for `path`;
    /// `simulate` follows a varying P too.
    Displacement,
}

impl From<DriveArg> for Drive {
    fn from(drive: DriveArg) -> Self {
        match drive {
            DriveArg::Force => Drive::Force,
            DriveArg::Displacement => Drive::Displacement,
        }
    }
}

/// A periodic load path in a file and what it prescribes besides P.
#[derive(Args)]
pub struct PathFileArgs {
    /// CSV with the header k,P_cos,P_sin,Q_cos,Q_sin: P(θ) = Σ P_cos cos kθ + P_sin sin kθ, Q alike (k ≤ 64).
    #[arg(long)]
    pub harmonics: Option<PathBuf>,
    /// CSV with the header P,Q: one period at equal steps of θ from 0, the last not repeating the
    /// first (at most 1,000,000), taken as their trigonometric interpolant.
    #[arg(long)]
    pub samples: Option<PathBuf>,
    /// What the file prescribes besides P: the tangential load Q (force) or the tangential
    /// displacement u (displacement: at constant P for `path`, a varying P too for
    /// `simulate`; from the unloaded state, first loaded to the extreme of u of largest
    /// magnitude).
    #[arg(long, value_enum, default_value_t = DriveArg::Force)]
    pub drive: DriveArg,
}

impl PathFileArgs {
    /// The request for the path in the file named on `contact`, if one is named: the
    /// file's text read (refused in one line when it cannot be), with the default digits
    /// and no outputs.
    pub fn request(&self, contact: &ContactArgs, deadline: Instant) -> Result<Option<PathRequest>, Failure> {
        let (file, samples): (&Path, bool) = match (&self.harmonics, &self.samples) {
            (Some(file), _) => (file, false),
            (None, Some(file)) => (file, true),
            (None, None) => return Ok(None),
        };
        let contents = std::fs::read_to_string(file)
            .map_err(|error| Failure::refused(format!("cannot read the path file {}: {error}", file.display())))?;
        let ratio = match (&contact.lambda, &contact.nu) {
            (Some(lambda), _) => RatioText::Lambda(lambda.clone()),
            (None, Some(nu)) => RatioText::Poisson(nu.clone()),
            (None, None) => unreachable!("clap requires --lambda or --nu"),
        };
        Ok(Some(PathRequest {
            file: file.display().to_string(),
            contents,
            format: if samples {
                PathFormat::Samples
            } else {
                PathFormat::Harmonics
            },
            drive: self.drive.into(),
            friction: contact.friction.clone(),
            ratio,
            compliance: contact.compliance.clone(),
            digits: None,
            deadline,
            harmonics_out: 0,
            loop_points: 0,
        }))
    }
}

#[derive(Args)]
#[command(group(ArgGroup::new("source").required(true).args(["harmonics", "samples"])))]
#[command(after_help = "W is energy per cycle in the units of load × approach of the inputs. \
The path must keep P > 0 and |Q| < fP at every θ (force driving); it is refused naming the θ where \
it does not. Under --drive displacement P must be constant and u is in the units of the outputs' u \
(λf times the approach); Q follows by Masing's rules and saturates at ±fP (gross slip): the contact \
starts unloaded, is loaded monotonically to the extreme of u of largest magnitude, and the steady \
loop is the period that starts there. W is proven (a rigorous enclosure, provenance certified), at \
constant P and where P varies: the 12 to 15 digits f64 intervals prove without --digits (else 15 \
on Arb balls), N with --digits N. Where the proof does not reach, W is printed with the digits on \
which two working precisions agree (agreement, not a proof; no_enclosure says why): 15 without \
--digits, N with --digits N.")]
pub struct PathArgs {
    #[command(flatten)]
    pub file: PathFileArgs,
    #[command(flatten)]
    pub contact: ContactArgs,
    /// Significant digits of W to prove, or on which two working precisions must agree (1–1000).
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
}

/// The JSON report.
#[derive(Serialize)]
#[allow(non_snake_case)]
struct PathReport {
    drive: &'static str,
    W: String,
    W_f64: f64,
    provenance: &'static str,
    digits_agreed: Option<u32>,
    digits_certified: u32,
    precision_bits: u32,
    arithmetic: Option<&'static str>,
    no_enclosure: Option<String>,
    enclosure: Option<(String, String)>,
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
    let request = PathRequest {
        digits: args.digits,
        harmonics_out: usize::from(args.harmonics_out),
        loop_points: LOOP_POINTS,
        ..args
            .file
            .request(&args.contact, deadline)?
            .unwrap_or_else(|| unreachable!("clap requires one of --harmonics and --samples"))
    };
    let answer = path_answer(&request).map_err(|error| Failure::of(&error, request.digits.is_some()))?;
    let printed = &answer.w;
    if let Some(path) = &args.loop_csv {
        let rows = answer
            .outputs
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
        return Ok(serde_json::to_string(&report(&answer))?);
    }
    Ok(text_report(printed, &answer.outputs))
}

fn report(answer: &PathAnswer) -> PathReport {
    let (printed, outputs) = (&answer.w, &answer.outputs);
    PathReport {
        drive: answer.drive.name(),
        W: printed.text.clone(),
        W_f64: printed.value,
        provenance: printed.provenance,
        digits_agreed: Some(printed.digits_agreed),
        digits_certified: printed.digits_certified,
        precision_bits: printed.precision_bits,
        arithmetic: printed.arithmetic,
        no_enclosure: printed.no_enclosure.clone(),
        enclosure: printed.enclosure.clone(),
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
        segments: answer.segments,
    }
}

fn text_report(printed: &AgreedW, outputs: &PathOutputs) -> String {
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
