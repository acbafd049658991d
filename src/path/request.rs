//! A whole path request, as `microslip path`, a batch row or a binding asks it: the file's
//! text, the contact and compliance as text (read again at every working precision), the
//! drive, the digits and the time budget; answered with W on the digits two working
//! precisions agree on, and the f64 outputs.

use std::time::Instant;

use rug::Float;

use crate::compliance::{parse_spec, Compliance};
use crate::cycle::compliance_ratio_from_poisson;
use crate::decimal::printing::decimal_ball;
use crate::digits::agreement::{agreement_radius, verify, TwoPrecisions, VerifyError};
use crate::real::{Precision, Real};

use super::displacement::{displacement_dissipation, displacement_outputs, DisplacementCycle};
use super::dissipation::{dissipation_of, path_dissipation};
use super::input::{read_driven_harmonics, read_driven_samples, Drive, LoadPath, PathError};
use super::outputs::{path_outputs, PathOutputs};
use super::{Contact, SteadyCycle};

/// How the file gives the path.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathFormat {
    /// `k,P_cos,P_sin,Q_cos,Q_sin` (or `u_cos,u_sin`).
    Harmonics,
    /// One period of samples `P,Q` (or `P,u`).
    Samples,
}

impl PathFormat {
    /// The format of a path file's text: harmonics when its header (its first line that is
    /// neither blank nor a `#` comment) has a column `k`, samples otherwise.
    pub fn of_contents(contents: &str) -> Self {
        let header = contents
            .lines()
            .map(str::trim)
            .find(|line| !line.is_empty() && !line.starts_with('#'))
            .unwrap_or("");
        if header.split(',').any(|cell| cell.trim() == "k") {
            PathFormat::Harmonics
        } else {
            PathFormat::Samples
        }
    }
}

/// The compliance ratio λ, given directly or through Poisson's ratio ν, as text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum RatioText {
    /// λ.
    Lambda(String),
    /// ν, with λ = (2 − ν)/(2(1 − ν)).
    Poisson(String),
}

/// Everything a path's W and outputs depend on.
#[derive(Clone, Debug)]
pub struct PathRequest {
    /// The file's name, for messages.
    pub file: String,
    /// The file's text.
    pub contents: String,
    /// How the file gives the path.
    pub format: PathFormat,
    /// What the file prescribes besides P.
    pub drive: Drive,
    /// f as text.
    pub friction: String,
    /// λ or ν as text.
    pub ratio: RatioText,
    /// The compliance spec.
    pub compliance: String,
    /// Significant digits of W two precisions must agree on.
    pub digits: u32,
    /// When to give up.
    pub deadline: Instant,
    /// Harmonics k = 0 … K of Q and u to report.
    pub harmonics_out: usize,
    /// Samples of the steady loop to report.
    pub loop_points: usize,
}

/// W as printed: its digits, its value in f64 and what vouches for it.
#[derive(Clone, Debug, PartialEq)]
pub struct AgreedW {
    /// The digits two precisions agree on, as a decimal.
    pub text: String,
    /// The value in f64.
    pub value: f64,
    /// `agreement`: two working precisions agree; not a proof.
    pub provenance: &'static str,
    /// What the provenance rests on, in words.
    pub detail: String,
    /// The digits two precisions agreed on.
    pub digits_agreed: u32,
    /// The higher working precision.
    pub precision_bits: u32,
}

/// The answer to a [`PathRequest`].
#[derive(Clone, Debug)]
pub struct PathAnswer {
    /// W.
    pub w: AgreedW,
    /// The f64 outputs: amplitudes, damping, harmonics, the loop.
    pub outputs: PathOutputs,
    /// The smooth segments (force driving) or monotone legs of u (displacement driving).
    pub segments: usize,
    /// The drive the answer is for.
    pub drive: Drive,
}

/// Why a request has no answer: input refused (exit 2) or a run that failed (exit 1).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{message}")]
pub struct PathRequestError {
    /// One line naming the problem.
    pub message: String,
    /// Whether the run failed (the integrals, the budget) rather than the input being refused.
    pub failure: bool,
}

impl PathRequestError {
    fn refused(message: impl Into<String>) -> Self {
        PathRequestError {
            message: message.into(),
            failure: false,
        }
    }

    fn failed(message: impl Into<String>) -> Self {
        PathRequestError {
            message: message.into(),
            failure: true,
        }
    }

    /// The exit code of a command that ends on this error: 1 for a failed run, 2 for
    /// refused input.
    pub fn exit_code(&self) -> u8 {
        if self.failure {
            1
        } else {
            2
        }
    }

    /// What the user may change, as a clause to append to the message (empty where
    /// nothing helps).
    pub fn hint(&self) -> &'static str {
        ""
    }
}

/// A path failure: input the theory does not cover is refused, a quadrature that did not
/// converge fails.
impl From<PathError> for PathRequestError {
    fn from(error: PathError) -> Self {
        match error {
            PathError::Quadrature(_) => PathRequestError::failed(error.to_string()),
            other => PathRequestError::refused(other.to_string()),
        }
    }
}

/// A path, a contact and a compliance at one precision.
pub(crate) struct Inputs<R: Real> {
    pub(crate) path: LoadPath<R>,
    pub(crate) contact: Contact<R>,
    pub(crate) compliance: Box<dyn Compliance<R>>,
}

impl PathRequest {
    pub(crate) fn read<R: Real>(&self, precision: Precision) -> Result<Inputs<R>, PathRequestError> {
        let path = match self.format {
            PathFormat::Samples => read_driven_samples::<R>(&self.contents, precision, self.drive),
            PathFormat::Harmonics => read_driven_harmonics::<R>(&self.contents, precision, self.drive),
        }
        .map_err(|error| PathRequestError::refused(format!("{}: {error}", self.file)))?;
        let number = |name: &str, text: &str| {
            R::parse_decimal(text, precision)
                .map_err(|_| PathRequestError::refused(format!("--{name} '{text}' is not a decimal number")))
        };
        let friction = number("friction", &self.friction)?;
        let compliance_ratio = match &self.ratio {
            RatioText::Lambda(lambda) => number("lambda", lambda)?,
            RatioText::Poisson(nu) => compliance_ratio_from_poisson(&number("nu", nu)?)
                .map_err(|error| PathRequestError::refused(error.to_string()))?,
        };
        let contact = Contact {
            friction,
            compliance_ratio,
        };
        contact
            .validate()
            .map_err(|error| PathRequestError::refused(error.to_string()))?;
        let compliance = parse_spec::<R>(&self.compliance, precision)
            .map_err(|error| PathRequestError::refused(error.to_string()))?;
        Ok(Inputs {
            path,
            contact,
            compliance,
        })
    }

    /// W at one precision.
    fn dissipation<R: Real>(&self, precision: Precision) -> Result<R, PathRequestError> {
        let inputs = self.read::<R>(precision)?;
        let (path, contact, compliance) = (&inputs.path, &inputs.contact, inputs.compliance.as_ref());
        let w = match self.drive {
            Drive::Force => path_dissipation(path, contact, compliance, Some(self.deadline)),
            Drive::Displacement => displacement_dissipation(path, contact, compliance, Some(self.deadline)),
        }?;
        Ok(w.total)
    }
}

/// W at two precisions until they agree to the digits asked for.
struct Agreement<'a> {
    request: &'a PathRequest,
}

impl TwoPrecisions for Agreement<'_> {
    type Output = Vec<Float>;
    type Error = PathRequestError;

    fn first(&mut self, precision: Precision, _attempt: u32) -> Result<Vec<Float>, PathRequestError> {
        Ok(vec![self.request.dissipation::<Float>(precision)?])
    }

    fn check(
        &mut self,
        _first: &Vec<Float>,
        precision: Precision,
        attempt: u32,
    ) -> Result<Vec<Float>, PathRequestError> {
        self.first(precision, attempt)
    }

    fn values<'v>(&self, output: &'v Vec<Float>) -> &'v [Float] {
        output
    }
}

/// W by agreement of two working precisions (never the f64 estimate), and the outputs.
pub fn path_answer(request: &PathRequest) -> Result<PathAnswer, PathRequestError> {
    let inputs = request.read::<f64>(Precision::DOUBLE)?;
    let (path, contact, compliance) = (&inputs.path, &inputs.contact, inputs.compliance.as_ref());
    // The f64 run checks the path (and counts its pieces) before the precisions are raised.
    let (f64_w, force_cycle, displacement_cycle) = match request.drive {
        Drive::Force => {
            let cycle = SteadyCycle::new(path, contact)?;
            let w = dissipation_of(&cycle, contact, compliance, Some(request.deadline))?;
            (w, Some(cycle), None)
        }
        Drive::Displacement => {
            let cycle = DisplacementCycle::new(path, contact, compliance)?;
            (cycle.dissipation(Some(request.deadline))?, None, Some(cycle))
        }
    };
    let w = agreed_w(request)?;
    let outputs = match (&force_cycle, &displacement_cycle) {
        (Some(cycle), _) => path_outputs(
            path,
            cycle,
            contact,
            compliance,
            w.value,
            request.harmonics_out,
            request.loop_points,
        ),
        (None, Some(cycle)) => displacement_outputs(cycle, w.value, request.harmonics_out, request.loop_points),
        (None, None) => unreachable!("one drive's cycle is built"),
    };
    Ok(PathAnswer {
        w,
        outputs,
        segments: f64_w.segments,
        drive: request.drive,
    })
}

/// W on the digits two working precisions agree on.
fn agreed_w(request: &PathRequest) -> Result<AgreedW, PathRequestError> {
    let mut agreement = Agreement { request };
    let verified = verify(request.digits, request.deadline, &mut agreement).map_err(|error| match error {
        VerifyError::Failed(failure) => failure,
        VerifyError::OutOfBudget(out) => PathRequestError::failed(format!(
            "the time budget ran out before two precisions agreed on {} digits of W ({} agreed); raise --max-seconds",
            out.digits_required(),
            out.digits_agreed
        )),
    })?;
    let (first, second) = (&verified.first[0], &verified.output[0]);
    Ok(AgreedW {
        text: decimal_ball(second, &agreement_radius(first, second), request.digits).to_string(),
        value: second.to_f64(),
        provenance: "agreement",
        detail: format!(
            "two working precisions agree on {} digits, up to {} bits; not proven",
            verified.agreed,
            verified.precision.in_bits()
        ),
        digits_agreed: verified.agreed,
        precision_bits: verified.precision.in_bits(),
    })
}
