//! A path request as asked — by `microslip path`, a batch row or a binding: the file's
//! text, the contact and compliance as text (read again at every working precision), the
//! drive, the digits and the time budget — and why it may have no answer.

use std::time::Instant;

use crate::compliance::{parse_spec, Compliance};
use crate::cycle::{compliance_ratio_from_poisson, CycleError};
use crate::real::{Precision, Real};

use super::input::{read_driven_harmonics, read_driven_samples, Drive, LoadPath, PathError};
use super::Contact;

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
    /// Significant digits of W asked for (`--digits N`); `None` for the default: the 12
    /// to 15 digits an enclosure in f64 intervals proves, or 15 agreed on.
    pub digits: Option<u32>,
    /// When to give up.
    pub deadline: Instant,
    /// Harmonics k = 0 … K of Q and u to report.
    pub harmonics_out: usize,
    /// Samples of the steady loop to report.
    pub loop_points: usize,
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
    pub(crate) fn refused(message: impl Into<String>) -> Self {
        PathRequestError {
            message: message.into(),
            failure: false,
        }
    }

    pub(crate) fn failed(message: impl Into<String>) -> Self {
        PathRequestError {
            message: message.into(),
            failure: true,
        }
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
        let path = self.read_path::<R>(precision)?;
        let contact = self.read_contact::<R>(precision)?;
        let compliance = parse_spec::<R>(&self.compliance, precision)
            .map_err(|error| PathRequestError::refused(error.to_string()))?;
        Ok(Inputs {
            path,
            contact,
            compliance,
        })
    }

    /// The path of the file at `precision`.
    pub(crate) fn read_path<R: Real>(&self, precision: Precision) -> Result<LoadPath<R>, PathRequestError> {
        match self.format {
            PathFormat::Samples => read_driven_samples::<R>(&self.contents, precision, self.drive),
            PathFormat::Harmonics => read_driven_harmonics::<R>(&self.contents, precision, self.drive),
        }
        .map_err(|error| PathRequestError::refused(format!("{}: {error}", self.file)))
    }

    /// f and λ (from ν where given) at `precision`, checked: f > 0 and λ ∈ [1, 2].
    pub(crate) fn read_contact<R: Real>(&self, precision: Precision) -> Result<Contact<R>, PathRequestError> {
        let number = |name: &str, text: &str| {
            R::parse_decimal(text, precision)
                .map_err(|_| PathRequestError::refused(format!("--{name} '{text}' is not a decimal number")))
        };
        let friction = number("friction", &self.friction)?;
        // Refusals quote the decimals as written, not their copies at this precision.
        let compliance_ratio = match &self.ratio {
            RatioText::Lambda(lambda) => number("lambda", lambda)?,
            RatioText::Poisson(nu) => compliance_ratio_from_poisson(&number("nu", nu)?).map_err(|error| {
                let error = match error {
                    CycleError::PoissonRatioOutOfRange { .. } => CycleError::PoissonRatioOutOfRange { nu: nu.clone() },
                    other => other,
                };
                PathRequestError::refused(error.to_string())
            })?,
        };
        let contact = Contact {
            friction,
            compliance_ratio,
        };
        contact.validate().map_err(|_| {
            let zero = contact.friction.int(0);
            PathRequestError::refused(match &self.ratio {
                _ if contact.friction <= zero => {
                    format!("the friction coefficient f = {} must be positive", self.friction)
                }
                RatioText::Lambda(lambda) => format!("the compliance ratio λ = {lambda} lies outside [1, 2]"),
                RatioText::Poisson(nu) => {
                    format!("Poisson's ratio ν = {nu} gives λ outside [1, 2]; ν must lie in [0, 2/3]")
                }
            })
        })?;
        Ok(contact)
    }
}
