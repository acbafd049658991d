//! The simulation's W as one [`Answer`]: the policy around the history simulation — the
//! f64 cycle or path it runs on, the tables it reads, a W of 0 it cannot vouch for —
//! decided here, so that the command line and the bindings only format the result.

use crate::admissibility::prove_admissible;
use crate::answer::dissipation::tables_cover;
use crate::answer::path::decided::decide_boundaries;
use crate::answer::path::prove_admissible_on_path_loads;
use crate::answer::{Answer, ExitStatus, Provenance, Value};
use crate::case::{Case, CaseSpec, InputError};
use crate::compliance::{AdmissibilityError, TableError};
use crate::cycle::{CycleError, LoadCycle};
use crate::path::{Drive, PathRequest, PathRequestError};
use crate::real::Precision;
use crate::simulate::{
    simulate, simulate_displacement_path, simulate_path, SimulationError, SimulationOptions, SimulationResult,
};

/// The simulation's W, and what it ran on.
#[derive(Clone, Debug)]
pub struct SimulatedAnswer {
    /// W as the work of the load, printed by the one rule for the bound its estimated
    /// relative error gives it ([`Provenance::Simulated`]: an estimate, not a proof).
    pub answer: Answer,
    /// W as the frictional work, for the same bound.
    pub friction: Value,
    /// The runs: the steady loop, the resolution, the estimated error.
    pub result: SimulationResult,
    /// The cycle simulated, in f64, in time order (a phase read as its cycle's mirror
    /// image turned back).
    pub cycle: LoadCycle<f64>,
}

/// The simulation's W of a periodic path read from a file, driven by force or by displacement.
#[derive(Clone, Debug)]
pub struct SimulatedPathAnswer {
    /// W as the work of the load ([`Provenance::Simulated`]: an estimate, not a proof).
    pub answer: Answer,
    /// W as the frictional work, for the same bound.
    pub friction: Value,
    /// The runs: the steady loop, the resolution, the estimated error.
    pub result: SimulationResult,
}

/// Why the simulation gave no W.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SimulatedError {
    /// The case cannot be read in f64.
    #[error(transparent)]
    Input(#[from] InputError),
    /// Rounded to f64, the cycle crosses a boundary the exact one keeps off.
    #[error("rounded to f64 the inputs cross a boundary that the exact cycle keeps off (in f64: {0}); the simulation runs in f64, `microslip dissipation` computes this cycle")]
    RoundedAcrossBoundary(CycleError),
    /// The compliance is not admissible on the cycle's slip loads, proven as `microslip
    /// dissipation` proves it.
    #[error("{0} = [P_T, P0 + P1]: the slip loads of the cycle reach down to the permanent-stick load P_T")]
    Compliance(AdmissibilityError),
    /// Rounded to f64, the path crosses a boundary that its decimals keep off.
    #[error("rounded to f64 the path crosses a boundary that its decimals keep off (in f64: {0}); the simulation runs in f64: move the path further from the boundary")]
    PathRoundedAcrossBoundary(String),
    /// The cycle leaves a table of the compliance.
    #[error(transparent)]
    Table(#[from] TableError),
    /// The path file, the contact or the compliance of a path request was refused, as
    /// `microslip path` refuses them.
    #[error(transparent)]
    Path(#[from] PathRequestError),
    /// The simulation itself failed.
    #[error(transparent)]
    Simulation(#[from] SimulationError),
    /// Every change of v' over the cycle's loads underflows f64, so the simulated W is 0,
    /// which nothing in the input makes exact.
    #[error("the simulation's W rounds to 0 in f64 (the changes of v' over the cycle's loads underflow), though nothing in the input makes W exactly 0; `microslip dissipation` gives W at any size")]
    ZeroInF64,
    /// No element slipped on a path whose loads vary.
    #[error("the simulation's W rounds to 0 in f64 (the changes of v' over the path's loads underflow, or v' is constant); `microslip path` gives W at any size")]
    PathZeroInF64,
}

impl ExitStatus for SimulatedError {
    fn is_failure(&self) -> bool {
        match self {
            SimulatedError::Path(error) => error.is_failure(),
            SimulatedError::RoundedAcrossBoundary(_)
            | SimulatedError::PathRoundedAcrossBoundary(_)
            | SimulatedError::ZeroInF64
            | SimulatedError::PathZeroInF64
            | SimulatedError::Simulation(
                SimulationError::ToleranceNotReached { .. } | SimulationError::OutOfTime { .. },
            ) => true,
            _ => false,
        }
    }

    fn hint(&self, _digits_asked: bool) -> &'static str {
        match self {
            SimulatedError::Simulation(SimulationError::ToleranceNotReached { .. }) => {
                "; more --elements and --steps may reach it, or a larger --tolerance accepts it"
            }
            SimulatedError::Simulation(SimulationError::TooLarge { .. }) => "; use fewer --elements or --steps",
            SimulatedError::Simulation(SimulationError::OutOfTime { .. }) => {
                "; raise --max-seconds or use fewer --elements or --steps"
            }
            _ => "",
        }
    }
}

/// W of `case` by the history simulation with `options`.
pub fn simulated_answer(case: &CaseSpec, options: &SimulationOptions) -> Result<SimulatedAnswer, SimulatedError> {
    let Case { mut cycle, compliance } = case.at::<f64>(Precision::DOUBLE)?;
    // The exact cycle is inside the theory (the case was read); its f64 copy may round
    // across a boundary it keeps off, and the simulation runs in f64.
    cycle.validate().map_err(SimulatedError::RoundedAcrossBoundary)?;
    // The simulation follows the loads in time: a phase within 2⁻²⁰ of an odd multiple of
    // π is read as the mirror image of its cycle (the same W), turned back here.
    if case.phase().is_mirror_image() {
        cycle.phase += std::f64::consts::PI;
        cycle.mean_tangential_load = -cycle.mean_tangential_load;
    }
    tables_cover(&case.compliance().tables(), &cycle)?;
    // Admissibility proven as `microslip dissipation` proves it: the simulation's own
    // check samples v'' in f64, which a convex term below its rounding passes.
    prove_admissible(case).map_err(SimulatedError::Compliance)?;
    let result = simulate(&cycle, compliance.as_ref(), options)?;
    // Only a W that is 0 by its reason is printed as 0.
    if result.w_work == 0.0 && result.w_friction == 0.0 && case.exact_zero().is_none() {
        return Err(SimulatedError::ZeroInF64);
    }
    let (answer, friction) = simulated_values(&result);
    Ok(SimulatedAnswer {
        answer,
        friction,
        result,
        cycle,
    })
}

/// W of the path of `request` (its file, contact and compliance read as `microslip path`
/// reads them, in f64, driven as the request says) by the history simulation with
/// `options`; the request's digits, budget and outputs play no part. Driven by
/// displacement, P may vary (which `microslip path` refuses).
pub fn simulated_path_answer(
    request: &PathRequest,
    options: &SimulationOptions,
) -> Result<SimulatedPathAnswer, SimulatedError> {
    // The path's boundaries decided from its decimals, as `microslip path` decides them;
    // its f64 copy may still round across one, and the simulation runs in f64.
    decide_boundaries(request)?;
    let inputs = request
        .read::<f64>(Precision::DOUBLE)
        .map_err(|error| rounded_across(&error))?;
    let (path, contact, compliance) = (&inputs.path, &inputs.contact, inputs.compliance.as_ref());
    let result = match request.drive {
        Drive::Force => simulate_path(path, contact, compliance, options),
        Drive::Displacement => simulate_displacement_path(path, contact, compliance, options),
    }
    .map_err(|error| match error {
        SimulationError::Path(boundary) if boundary.is_boundary() => rounded_across(&boundary),
        other => other.into(),
    })?;
    // Admissibility proven as `microslip path` proves it, on the loads the run's elements
    // slip over: the simulation's own check samples v'' in f64, which a convex term below
    // its rounding passes (and then leaves a W of 0).
    let (lowest_slip, highest) = result.slip_loads;
    prove_admissible_on_path_loads(request, lowest_slip, highest)?;
    // Only a W that is 0 by its reason is printed as 0: loads that do not vary.
    let constant = inputs.path.normal.is_constant() && inputs.path.tangential.is_constant();
    if result.w_work == 0.0 && result.w_friction == 0.0 && !constant {
        return Err(SimulatedError::PathZeroInF64);
    }
    let (answer, friction) = simulated_values(&result);
    Ok(SimulatedPathAnswer {
        answer,
        friction,
        result,
    })
}

/// A boundary that the f64 copy of a path decided inside the theory crosses.
fn rounded_across(error: &dyn std::fmt::Display) -> SimulatedError {
    SimulatedError::PathRoundedAcrossBoundary(error.to_string())
}

/// W as the work of the load and as the frictional work, each with the bound the
/// estimated relative error gives it.
fn simulated_values(result: &SimulationResult) -> (Answer, Value) {
    let bound = result.estimated_rel_error * result.w_work.abs();
    let answer = Answer {
        value: Value::from_f64(result.w_work, bound),
        segments: None,
        digits_requested: None,
        provenance: Provenance::Simulated { error_estimate: bound },
        method: None,
    };
    (answer, Value::from_f64(result.w_friction, bound))
}
