//! Whether a valid cycle and a compliance can be computed at the working precision: the
//! rounding the cycle amplifies, the magnitudes it reaches, and (when asked) whether the
//! compliance is physical over its loads.

use super::error::DissipationError;
use super::options::Options;
use super::range;
use crate::compliance::{check_admissible, Compliance};
use crate::cycle::ValidCycle;
use crate::real::Real;

/// Checks the case once, before any formula: the cycle's rounding amplification, the
/// magnitudes of the case, and, when asked, the compliance over the loads reached.
pub(crate) fn check_case<R: Real>(
    cycle: &ValidCycle<R>,
    compliance: &dyn Compliance<R>,
    options: &Options<R>,
) -> Result<(), DissipationError> {
    let amplification = cycle.rounding_amplification();
    check_conditioning(&amplification, options, || {
        format!("min(P0 − P1, P_T) = P0/{:.3e}", amplification.to_f64_lossy())
    })?;
    let low = (cycle.mean_normal_load.clone() - &cycle.normal_amplitude).min_of(&cycle.permanent_stick_load());
    let high = cycle.mean_normal_load.clone() + &cycle.normal_amplitude;
    range::check_magnitudes(cycle, compliance, options, &low, &high)?;
    if options.check_compliance {
        check_admissible(compliance, &low, &high)?;
    }
    Ok(())
}

/// Refuses a cycle whose rounding amplification times ε exceeds `rounding_limit`, saying
/// why in the words of `cause` (formed only for a refusal).
pub(crate) fn check_conditioning<R: Real>(
    amplification: &R,
    options: &Options<R>,
    cause: impl FnOnce() -> String,
) -> Result<(), DissipationError> {
    let expected = (amplification.clone() * &amplification.epsilon_like()).to_f64_lossy();
    if expected > options.rounding_limit {
        return Err(DissipationError::IllConditioned {
            bits: amplification.precision().in_bits(),
            cause: cause(),
            expected,
            limit: options.rounding_limit,
        });
    }
    Ok(())
}
