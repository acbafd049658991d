//! A path request ([`PathRequest`]) answered: W proven by an enclosure where the path
//! allows it (`proven`, feature `certified`: force- or displacement-driven at constant P,
//! force-driven where P varies), else on the digits
//! two working precisions agree on, and the f64 outputs.

#[cfg(feature = "certified")]
mod constant_load;
pub(crate) mod decided;
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
    /// `certified`: a rigorous enclosure proves every printed digit; `exact`: W is exactly
    /// the value printed (0, for a constant Q); `agreement`: two working precisions agree,
    /// not a proof (the keys `microslip dissipation` uses).
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
    /// Why W is exactly the value printed, where it is (provenance `exact`).
    pub exact: Option<&'static str>,
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

/// W proven by an enclosure (`proven`), else by
/// agreement of two working precisions with the reason it is not proven (never the f64
/// estimate), and the outputs.
pub fn path_answer(request: &PathRequest) -> Result<PathAnswer, PathRequestError> {
    decided::decide_boundaries(request)?;
    // Read as written, the path was read at higher precisions above: an f64 copy that
    // fails to read (λ from ν beyond 2) has crossed a boundary.
    let inputs = request.read::<f64>(Precision::DOUBLE).map_err(rounded_across)?;
    let (path, contact, compliance) = (&inputs.path, &inputs.contact, inputs.compliance.as_ref());
    // The f64 run builds the cycle (and counts its pieces) for the outputs.
    let (f64_w, force_cycle, displacement_cycle) = match request.drive {
        Drive::Force => {
            let cycle = SteadyCycle::new(path, contact).map_err(|error| match error {
                boundary if boundary.is_boundary() => rounded_across(boundary.into()),
                other => other.into(),
            })?;
            let w = dissipation_of(&cycle, contact, compliance, Some(request.deadline))?;
            (w, Some(cycle), None)
        }
        Drive::Displacement => {
            let cycle = DisplacementCycle::new(path, contact, compliance)?;
            (cycle.dissipation(Some(request.deadline))?, None, Some(cycle))
        }
    };
    let (low, high) = match (&force_cycle, &displacement_cycle) {
        (Some(cycle), _) => (cycle.lowest_slip, cycle.highest_load),
        (None, Some(cycle)) => cycle.slip_load_range(),
        (None, None) => unreachable!("one drive's cycle is built"),
    };
    let admissible = prove_admissible_on_path_loads(request, low, high)?;
    let w = if request.drive == Drive::Force && path.tangential.is_constant() && tangential_constant_as_written(request)
    {
        exact_zero_w(request)
    } else {
        match proven_or_why(request, f64_w.total, &admissible)? {
            Ok(w) => w,
            Err(why) => agreed_w(request, why)?,
        }
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

/// Whether Q is constant as written: every harmonic k ≥ 1 of the file exactly 0 (a
/// decimal too small for f64, zero in its f64 copy, is not), or a column of samples all
/// one decimal. Asked only where the f64 copy is constant, which it then is.
fn tangential_constant_as_written(request: &PathRequest) -> bool {
    request
        .read_path::<crate::interval::Interval>(Precision::DOUBLE)
        .is_ok_and(|path| crate::doubts::if_decided(|| path.tangential.is_constant()) == Some(true))
}

/// W = 0 exactly for a force-driven path whose Q is constant: W = Q ∮ du, and u returns
/// to itself over the steady cycle, whatever P does.
fn exact_zero_w(request: &PathRequest) -> AgreedW {
    let digits = request.digits_asked();
    AgreedW {
        text: "0".to_string(),
        value: 0.0,
        provenance: "exact",
        detail: CONSTANT_Q.to_string(),
        digits_agreed: digits,
        digits_certified: digits,
        precision_bits: 53,
        arithmetic: None,
        no_enclosure: None,
        enclosure: None,
        exact: Some(CONSTANT_Q),
    }
}

/// Why a constant Q dissipates nothing.
const CONSTANT_Q: &str = "Q is constant, so W = Q ∮ du = 0 over the closed loop";

/// The f64 copy of a path decided inside the theory (separation, gross slip, λ) refused:
/// the copy crossed a boundary the decimals keep off, and the f64 run, which builds the
/// outputs, cannot follow it; a failure (exit 1), not a refusal.
fn rounded_across(error: PathRequestError) -> PathRequestError {
    PathRequestError::failed(format!(
        "rounded to f64 the path crosses a boundary that its decimals keep off (in f64: {}); \
         its outputs are computed in f64: move the path further from the boundary",
        error.message
    ))
}

/// The least load, as a fraction 2⁻ᵏ of the highest, down to which admissibility is
/// checked where the slip reaches load 0 (gross slip): as near 0 as a check can come.
const FLOOR_BELOW_HIGHEST: u32 = 1024;

/// How far beyond the f64 run's loads admissibility is checked, as a fraction 2⁻ᵏ of the
/// highest load: far beyond the run's rounding (a few ulps of the highest load).
const MARGIN_BELOW_HIGHEST: u32 = 40;

/// The loads on which the compliance was proven admissible (read where a W is proven:
/// not built without ball arithmetic).
#[cfg_attr(not(feature = "certified"), allow(dead_code))]
pub(crate) struct AdmissibleLoads {
    /// The lowest.
    low: Float,
    /// The highest.
    high: Float,
    /// Whether the check reached down to the floor (the slip may reach load 0).
    to_floor: bool,
}

/// The compliance proven admissible ([`crate::admissibility::prove_admissible_on`]: by its
/// form, else v'' ≤ 0 and v' > 0 on Arb balls) on the loads the f64 run's slip reaches,
/// [low, high], widened by 2⁻⁴⁰ of `high`; from 2⁻¹⁰²⁴ of `high` where the widened end is not
/// positive or the run's lowest load is its floor `high`/1024 (gross slip reaches load 0).
pub(crate) fn prove_admissible_on_path_loads(
    request: &PathRequest,
    low: f64,
    high: f64,
) -> Result<AdmissibleLoads, PathRequestError> {
    let refused = |error: &dyn std::fmt::Display| PathRequestError::refused(error.to_string());
    let spec = crate::compliance::ComplianceSpec::parse(&request.compliance).map_err(|error| refused(&error))?;
    let top = Float::with_val(64, high);
    let margin = top.clone() >> MARGIN_BELOW_HIGHEST;
    let widened = Float::with_val(64, low) - &margin;
    let to_floor = low <= high / 1024.0 || widened <= 0;
    let low = if to_floor {
        top.clone() >> FLOOR_BELOW_HIGHEST
    } else {
        widened
    };
    let high = top + &margin;
    crate::admissibility::prove_admissible_on(&spec, &low, &high).map_err(|error| refused(&error))?;
    Ok(AdmissibleLoads { low, high, to_floor })
}

/// W proven by an enclosure, or why it is not (an error where the time budget ran out).
/// The loads its cycles or segments reach must lie among those the compliance was proven
/// admissible on.
#[cfg(feature = "certified")]
fn proven_or_why(
    request: &PathRequest,
    estimate: f64,
    admissible: &AdmissibleLoads,
) -> Result<Result<AgreedW, String>, PathRequestError> {
    use proven::NotProven;
    let proven = match proven::proven_w(request) {
        Ok(proven) => proven,
        // A budget that runs out is a failure, not a reason to fall back on agreement.
        Err(out @ NotProven::OutOfTime { .. }) => {
            return Err(PathRequestError::failed(format!("{out}; raise --max-seconds")));
        }
        Err(why) => return Ok(Err(why.to_string())),
    };
    let covered = match proven.lowest_slip_load {
        Some(lowest) => admissible.low <= lowest,
        None => admissible.to_floor,
    };
    if !covered || admissible.high < proven.highest_load {
        return Ok(Err(
            "its loads reach beyond those on which the compliance was proven admissible".to_string(),
        ));
    }
    let digits = proven.value.digits().min(request.digits_asked());
    Ok(Ok(AgreedW {
        text: proven.value.decimal.to_string(),
        value: proven.value.to_f64().unwrap_or(estimate),
        provenance: proven.provenance.key(),
        detail: format!(
            "{} over {}",
            proven.provenance,
            match (proven.summed, request.drive) {
                (proven::SummedOver::RainflowCycles(cycles), Drive::Force) => format!("{cycles} rainflow cycles of Q"),
                (proven::SummedOver::RainflowCycles(cycles), Drive::Displacement) =>
                    format!("{cycles} rainflow cycles of u"),
                (proven::SummedOver::Segments(segments), _) =>
                    format!("{segments} smooth segments of the steady cycle"),
            }
        ),
        digits_agreed: digits,
        digits_certified: digits,
        precision_bits: proven.provenance.precision_bits().unwrap_or(53),
        arithmetic: proven.provenance.arithmetic().map(crate::answer::Arithmetic::key),
        no_enclosure: None,
        enclosure: proven.value.enclosure.clone(),
        exact: None,
    }))
}

/// Without ball arithmetic there is no enclosure.
#[cfg(not(feature = "certified"))]
fn proven_or_why(_: &PathRequest, _: f64, _: &AdmissibleLoads) -> Result<Result<AgreedW, String>, PathRequestError> {
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
        exact: None,
    })
}
