//! A path request ([`PathRequest`]) answered: W proven by an enclosure where the path
//! allows it (`proven`, feature `certified`: constant P, force- or displacement-driven), else on the digits
//! two working precisions agree on, and the f64 outputs.

#[cfg(feature = "certified")]
mod constant_load;
#[cfg(feature = "certified")]
mod not_proven;
#[cfg(feature = "certified")]
pub mod proven;

use rug::Float;

use crate::answer::dissipation::DEFAULT_DIGITS;
use crate::decimal::printing::decimal_ball;
use crate::digits::agreement::{agreement_radius, verify, TwoPrecisions, VerifyError};
use crate::real::{Precision, Real};

use crate::path::dissipation::dissipation_of;
use crate::path::{
    displacement_dissipation, displacement_outputs, path_dissipation, path_outputs, DisplacementCycle, Drive,
    PathOutputs, PathRequest, PathRequestError, SteadyCycle,
};

/// W as printed: its digits, its value in f64 and what vouches for it (an enclosure or
/// the agreement of two precisions).
#[derive(Clone, Debug, PartialEq)]
pub struct AgreedW {
    /// The digits two precisions agree on, as a decimal.
    pub text: String,
    /// The value in f64.
    pub value: f64,
    /// `certified`: a rigorous enclosure proves every printed digit; `agreement`: two
    /// working precisions agree, not a proof (the keys `microslip dissipation` uses).
    pub provenance: &'static str,
    /// What the provenance rests on, in words.
    pub detail: String,
    /// The digits two precisions agreed on (for a proven W, the digits printed).
    pub digits_agreed: u32,
    /// The digits proven: all printed ones for a proven W, else 0.
    pub digits_certified: u32,
    /// The working precision: of the enclosure, or the higher of the two that agree.
    pub precision_bits: u32,
    /// The arithmetic of the enclosure (`f64 intervals`, `arb balls`); `None` by agreement.
    pub arithmetic: Option<&'static str>,
    /// Why W rests on agreement rather than an enclosure; `None` for a proven W.
    pub no_enclosure: Option<String>,
    /// Decimal ends, rounded outwards, of the enclosure W was read from; `None` by agreement.
    pub enclosure: Option<(String, String)>,
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

impl PathRequest {
    /// The significant digits W is printed to at most: those asked for, else
    /// [`DEFAULT_DIGITS`].
    pub fn digits_asked(&self) -> u32 {
        self.digits.unwrap_or(DEFAULT_DIGITS)
    }
}

/// A failed run (the integrals, the budget) or refused input.
impl crate::answer::ExitStatus for PathRequestError {
    fn is_failure(&self) -> bool {
        self.failure
    }
}

/// W of the request at one precision.
fn dissipation_at<R: Real>(request: &PathRequest, precision: Precision) -> Result<R, PathRequestError> {
    let inputs = request.read::<R>(precision)?;
    let (path, contact, compliance) = (&inputs.path, &inputs.contact, inputs.compliance.as_ref());
    let deadline = Some(request.deadline);
    let w = match request.drive {
        Drive::Force => path_dissipation(path, contact, compliance, deadline),
        Drive::Displacement => displacement_dissipation(path, contact, compliance, deadline),
    }?;
    Ok(w.total)
}

/// W at two precisions until they agree to the digits asked for.
struct Agreement<'a> {
    request: &'a PathRequest,
}

impl TwoPrecisions for Agreement<'_> {
    type Output = Vec<Float>;
    type Error = PathRequestError;

    fn first(&mut self, precision: Precision, _attempt: u32) -> Result<Vec<Float>, PathRequestError> {
        Ok(vec![dissipation_at::<Float>(self.request, precision)?])
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

/// W proven by an enclosure (`proven`: force driving at constant P), else by
/// agreement of two working precisions with the reason it is not proven (never the f64
/// estimate), and the outputs.
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
    let w = match proven_or_why(request, f64_w.total)? {
        Ok(w) => w,
        Err(why) => agreed_w(request, why)?,
    };
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

/// W proven by an enclosure, or why it is not (an error where the time budget ran out).
#[cfg(feature = "certified")]
fn proven_or_why(request: &PathRequest, estimate: f64) -> Result<Result<AgreedW, String>, PathRequestError> {
    use proven::NotProven;
    let proven = match proven::proven_w(request) {
        Ok(proven) => proven,
        // A budget that runs out is a failure, not a reason to fall back on agreement.
        Err(out @ NotProven::OutOfTime { .. }) => {
            return Err(PathRequestError::failed(format!("{out}; raise --max-seconds")));
        }
        Err(why) => return Ok(Err(why.to_string())),
    };
    let digits = proven.value.digits().min(request.digits_asked());
    Ok(Ok(AgreedW {
        text: proven.value.decimal.to_string(),
        value: proven.value.to_f64().unwrap_or(estimate),
        provenance: proven.provenance.key(),
        detail: format!(
            "{} over {} rainflow cycles of {}",
            proven.provenance,
            proven.cycles,
            match request.drive {
                Drive::Force => "Q",
                Drive::Displacement => "u",
            }
        ),
        digits_agreed: digits,
        digits_certified: digits,
        precision_bits: proven.provenance.precision_bits().unwrap_or(53),
        arithmetic: proven.provenance.arithmetic().map(crate::answer::Arithmetic::key),
        no_enclosure: None,
        enclosure: proven.value.enclosure.clone(),
    }))
}

/// Without ball arithmetic there is no enclosure.
#[cfg(not(feature = "certified"))]
fn proven_or_why(_: &PathRequest, _: f64) -> Result<Result<AgreedW, String>, PathRequestError> {
    Ok(Err("this build has no ball arithmetic".to_string()))
}

/// W on the digits two working precisions agree on; `why` says why it is not proven.
fn agreed_w(request: &PathRequest, why: String) -> Result<AgreedW, PathRequestError> {
    let mut agreement = Agreement { request };
    let verified = verify(request.digits_asked(), request.deadline, &mut agreement).map_err(|error| match error {
        VerifyError::Failed(failure) => failure,
        VerifyError::OutOfBudget(out) => PathRequestError::failed(format!(
            "the time budget ran out before two precisions agreed on {} digits of W ({} agreed); raise --max-seconds",
            out.digits_required(),
            out.digits_agreed
        )),
    })?;
    let (first, second) = (&verified.first[0], &verified.output[0]);
    Ok(AgreedW {
        text: decimal_ball(second, &agreement_radius(first, second), request.digits_asked()).to_string(),
        value: second.to_f64(),
        provenance: "agreement",
        detail: format!(
            "two working precisions agree on {} digits, up to {} bits; not proven: {why}",
            verified.agreed,
            verified.precision.in_bits()
        ),
        digits_agreed: verified.agreed,
        digits_certified: 0,
        precision_bits: verified.precision.in_bits(),
        arithmetic: None,
        no_enclosure: Some(why),
        enclosure: None,
    })
}
