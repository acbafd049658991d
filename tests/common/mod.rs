//! What several test files share.

use microslip::cycle::LoadCycle;
use microslip::real::Real;

/// The first acceptance case of the project: P0 = f = λ = 1, P1 = 0.4, Q1 = 0.5, Q0 = 0
/// (with v' = 1/P in most tests), at the given phase and the phase's precision.
pub fn acceptance_cycle<R: Real>(phase: R) -> LoadCycle<R> {
    let one = phase.int(1);
    LoadCycle {
        mean_normal_load: one.clone(),
        normal_amplitude: one.ratio(2, 5),
        mean_tangential_load: one.int(0),
        tangential_amplitude: one.ratio(1, 2),
        phase,
        friction: one.clone(),
        compliance_ratio: one,
    }
}
