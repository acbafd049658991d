//! Masing's memory over the samples of one period: Q at every sample and its gradient
//! with respect to the displacement's harmonics, by the chain rule through the samples
//! that are reversal points and the anchor.

use super::backbone::{Backbone, SlipState};
use super::fourier::Layout;
use super::FrictionElement;

/// Q(t_n) and dQ(t_n)/dU (row n of `gradient`, one entry per coefficient).
pub(super) struct SteadyLoop {
    pub(super) load: Vec<f64>,
    pub(super) gradient: Vec<f64>,
}

/// Where the contact is on its way through the period.
enum Memory {
    /// On the virgin curve, not yet reversed (only at the anchor).
    Virgin,
    /// Sliding at ±fP: the memory is wiped.
    Sliding,
    /// On a branch from the last of these reversal samples; each older one is where the
    /// branch before it would resume.
    Reversals(Vec<usize>),
}

/// A sample's point on its branch: the branch (its origin reversal, none for the virgin
/// curve, and direction), the backbone's displacement there, the slip state solved, and
/// the stiffness's rate of change since the sample before on the branch (0 without one).
#[derive(Clone, Copy)]
struct Solved {
    origin: Option<usize>,
    direction: f64,
    relative: f64,
    state: SlipState,
    bend: f64,
}

/// The steady loop of the sampled displacement `u`: first loading along the virgin curve
/// to the sample of largest |u| (the first such sample), then one period from there.
/// One function because every sample's branch, reversal memory and derivative row follow
/// from the sample before: the loop carries that state from step to step.
pub(super) fn steady_loop(element: &FrictionElement, u: &[f64], layout: &Layout) -> SteadyLoop {
    let count = u.len();
    let width = layout.coefficients();
    let limit = element.friction_limit();
    let backbone = Backbone::of(element);
    let anchor = (0..count).fold(0, |best, n| if u[n].abs() > u[best].abs() { n } else { best });
    let mut load = vec![0.0; count];
    let mut gradient = vec![0.0; count * width];
    let mut direction = if u[anchor] < 0.0 { -1.0 } else { 1.0 };
    let mut memory = Memory::Virgin;
    let mut last_solved: Option<Solved> = None;
    for step in 0..count {
        let n = (anchor + step) % count;
        if step > 0 {
            let previous = (n + count - 1) % count;
            if (u[n] - u[previous]) * direction < 0.0 {
                direction = -direction;
                memory = match memory {
                    Memory::Reversals(mut reversals) => {
                        reversals.push(previous);
                        Memory::Reversals(reversals)
                    }
                    Memory::Virgin | Memory::Sliding => Memory::Reversals(vec![previous]),
                };
            }
        }
        if let Memory::Reversals(reversals) = &mut memory {
            // A branch that passes the reversal before its own closes that inner loop and
            // continues the branch the loop interrupted. The first reversal stays: the
            // anchor is an extreme of the period, and a saturated one is left by sliding.
            while reversals.len() >= 3 && direction * (u[n] - u[reversals[reversals.len() - 2]]) >= 0.0 {
                reversals.truncate(reversals.len() - 2);
            }
        }
        // The branch from (u_r, Q_r): Q = Q_r ± 2 g⁻¹(|u − u_r|/2); the virgin curve is the
        // branch from the origin without the doubling.
        let (origin, scale) = match &memory {
            Memory::Virgin => (None, 1.0),
            Memory::Reversals(reversals) => (reversals.last().copied(), 2.0),
            Memory::Sliding => {
                load[n] = direction * limit;
                continue;
            }
        };
        let (u_origin, q_origin) = origin.map_or((0.0, 0.0), |r| (u[r], load[r]));
        let relative = direction * (u[n] - u_origin) / scale;
        // On the branch of the previous sample, its slip state extrapolated to second order
        // (the stiffness's rate of change from the sample before, where that was on the
        // branch too) starts Newton's method a few digits from the root.
        let same_branch = last_solved.filter(|on| on.origin == origin && on.direction == direction);
        let guess = same_branch.map(|on| {
            let step = relative - on.relative;
            on.state.load + (on.state.stiffness + 0.5 * on.bend * step) * step
        });
        let state = backbone.slip_state_from(relative, guess);
        last_solved = state.map(|state| Solved {
            origin,
            direction,
            relative,
            state,
            bend: same_branch.map_or(0.0, |on| {
                let bend = (state.stiffness - on.state.stiffness) / (relative - on.relative);
                if bend.is_finite() {
                    bend
                } else {
                    0.0
                }
            }),
        });
        let value = state.map(|state| q_origin + direction * scale * state.load);
        match (state, value) {
            (Some(state), Some(value)) if direction * value < limit => {
                load[n] = value;
                // dQ = k (du − du_r) + dQ_r, k the stiffness of the branch.
                let row = n * width;
                for (j, b) in layout.at(n).iter().enumerate() {
                    gradient[row + j] = state.stiffness * b;
                }
                if let Some(r) = origin {
                    for j in 0..width {
                        gradient[row + j] += gradient[r * width + j] - state.stiffness * layout.at(r)[j];
                    }
                }
            }
            _ => {
                load[n] = direction * limit;
                memory = Memory::Sliding;
            }
        }
    }
    SteadyLoop { load, gradient }
}
