//! The friction element under a periodic normal load P(t): Masing's rules no longer hold,
//! so the contact is the spring bed `microslip simulate` follows, stepped sample by sample
//! through the period, and the Jacobian is that of the discrete map. Each element's
//! tangential force is piecewise linear in the samples of u: stuck since a sample m (where
//! it last slipped or entered contact) it is its force there plus k (u_n − u_m); slipping,
//! it is at its capacity, which P alone sets. So dQ_n/dU = Σ_stuck k (B_n − B_m) / λ, B
//! the Fourier basis at the samples.

use super::fourier::Layout;
use super::spring_bed::SpringBed;

/// The most periods stepped before the steady state is taken as reached; the state repeats
/// after the second (checked by the tests).
const MOST_PERIODS: usize = 8;

/// Where an element's elastic displacement was last set free of u: the displacement then is
/// (1 − share)·u_m + share·u_{m−1} (share > 0 for an element that entered contact part of
/// the way through the step to sample m), or 0 for the unloaded contact's first loading.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Anchor {
    Unloaded,
    Sample { sample: usize, share: f64 },
}

/// One element: in contact or not, stuck or slipping, and its elastic displacement
/// e = held + u − origin, held and origin fixed since its anchor.
#[derive(Clone, Copy, Debug)]
struct ElementState {
    in_contact: bool,
    sticking: bool,
    held: f64,
    origin: f64,
    anchor: Anchor,
}

/// The normal load's samples and what each element can hold at them.
pub(super) struct LoadedBed<'a> {
    pub(super) bed: &'a SpringBed,
    /// P(t_n).
    pub(super) normal_load: &'a [f64],
    /// v(P(t_n)).
    pub(super) approach: &'a [f64],
    /// λ f n_base / K(0) at each sample: the base element's capacity as a displacement.
    pub(super) base_capacity: &'a [f64],
    /// How many elements touch at each sample (a prefix of the bed, the base first).
    pub(super) touching: &'a [usize],
    /// λ f.
    pub(super) scale: f64,
    /// λ.
    pub(super) compliance_ratio: f64,
}

/// Q(t_n) and dQ(t_n)/dU (row n) over the steady period (and, for the tests, the periods
/// stepped until the state repeated).
pub(super) struct SteadyPeriod {
    pub(super) load: Vec<f64>,
    pub(super) gradient: Vec<f64>,
    #[cfg(test)]
    pub(super) periods: usize,
}

/// The running sums over the stuck elements in contact: Σ k and Σ k·(their anchor's basis),
/// so that dQ_n/dU = (Σ k · B_n − Σ k · A)/λ.
struct StuckSums<'a> {
    layout: &'a Layout,
    stiffness: f64,
    anchors: Vec<f64>,
}

impl StuckSums<'_> {
    /// Adds (sign = 1) or removes (−1) an element of stiffness k anchored at `anchor`.
    fn change(&mut self, sign: f64, k: f64, anchor: Anchor) {
        self.stiffness += sign * k;
        if let Anchor::Sample { sample, share } = anchor {
            let count = self.layout.time_points();
            let at = self.layout.at(sample);
            let before = self.layout.at((sample + count - 1) % count);
            for ((sum, a), b) in self.anchors.iter_mut().zip(at).zip(before) {
                *sum += sign * k * ((1.0 - share) * a + share * b);
            }
        }
    }
}

impl LoadedBed<'_> {
    /// What element j holds at sample n, as an elastic displacement: λ f (v(P) − v(s)), or
    /// the base element's share.
    fn capacity(&self, j: usize, n: usize) -> f64 {
        if j == 0 {
            return self.base_capacity[n];
        }
        self.scale * (self.approach[n] - self.bed.approach_at_entry[j]).max(0.0)
    }

    /// The steady period of the sampled displacement `u`: the contact, unloaded, is pressed
    /// to P at the anchor (the first sample of largest |u|), displaced to u there, and then
    /// stepped through the samples, period after period, until its state at the end of a
    /// period is the one at its start; the last period's loads and gradients.
    pub(super) fn steady_period(&self, u: &[f64], layout: &Layout) -> SteadyPeriod {
        let count = u.len();
        let width = layout.coefficients();
        let elements = self.bed.entry.len();
        let anchor = (0..count).fold(0, |best, n| if u[n].abs() > u[best].abs() { n } else { best });
        let mut states = vec![
            ElementState {
                in_contact: false,
                sticking: false,
                held: 0.0,
                origin: 0.0,
                anchor: Anchor::Unloaded,
            };
            elements
        ];
        let mut sums = StuckSums {
            layout,
            stiffness: 0.0,
            anchors: vec![0.0; width],
        };
        // Pressed to P at the anchor with u = 0, the elements below it touching unloaded,
        // then displaced to u there at constant P in one monotone step.
        let first = self.bed.first();
        for (j, state) in states.iter_mut().enumerate().take(self.touching[anchor]).skip(first) {
            state.in_contact = true;
            self.settle(state, &mut sums, j, anchor, u[anchor]);
        }
        let mut load = vec![0.0; count];
        let mut gradient = vec![0.0; count * width];
        let mut periods = 0;
        while periods < MOST_PERIODS {
            periods += 1;
            let start: Vec<(bool, f64)> = states.iter().map(|s| (s.in_contact, s.origin - s.held)).collect();
            sums = self.stuck_sums(&states, layout);
            for step in 1..=count {
                let n = (anchor + step) % count;
                let previous = (n + count - 1) % count;
                load[n] = self.step(&mut states, &mut sums, n, previous, u);
                let row = &mut gradient[n * width..(n + 1) * width];
                for ((entry, b), a) in row.iter_mut().zip(layout.at(n)).zip(&sums.anchors) {
                    *entry = (sums.stiffness * b - a) / self.compliance_ratio;
                }
            }
            let offsets = start.iter().fold(0.0f64, |m, &(_, offset)| m.max(offset.abs()));
            let scale = u.iter().fold(offsets, |m, x| m.max(x.abs()));
            let repeated = states.iter().zip(&start).all(|(s, &(touching, offset))| {
                s.in_contact == touching && (!touching || (s.origin - s.held - offset).abs() <= 1e-13 * scale)
            });
            if repeated {
                break;
            }
        }
        SteadyPeriod {
            load,
            gradient,
            #[cfg(test)]
            periods,
        }
    }

    /// Moves the contact from sample `previous` to sample n: the elements that leave
    /// contact forget their state; those that enter start unloaded where P crosses their
    /// entry load (interpolated in the step), anchored to u there; then every element in
    /// contact sticks where its trial elastic displacement is within its capacity and slips
    /// to the capacity otherwise (anchored there). Returns Q = Σ k e / λ.
    fn step(&self, states: &mut [ElementState], sums: &mut StuckSums, n: usize, previous: usize, u: &[f64]) -> f64 {
        let (load, load_before) = (self.normal_load[n], self.normal_load[previous]);
        let touching = self.touching[n];
        for (j, state) in states
            .iter_mut()
            .enumerate()
            .take(self.touching[previous])
            .skip(touching)
        {
            if state.in_contact && state.sticking {
                sums.change(-1.0, self.bed.stiffness[j], state.anchor);
            }
            state.in_contact = false;
            state.sticking = false;
        }
        let mut force = 0.0;
        for (j, state) in states.iter_mut().enumerate().take(touching).skip(self.bed.first()) {
            if !state.in_contact {
                let entry = self.bed.entry[j];
                let share = if load > load_before && entry > load_before {
                    (load - entry) / (load - load_before)
                } else {
                    1.0
                };
                *state = ElementState {
                    in_contact: true,
                    sticking: false,
                    held: 0.0,
                    origin: (1.0 - share) * u[n] + share * u[previous],
                    anchor: Anchor::Sample { sample: n, share },
                };
            }
            force += self.settle(state, sums, j, n, u[n]);
        }
        force / self.compliance_ratio
    }

    /// Moves element j, in contact, to displacement `u` at sample n: it sticks where its
    /// trial elastic displacement is within its capacity and slips to the capacity otherwise
    /// (anchored there). Returns its force times λ, k e.
    fn settle(&self, state: &mut ElementState, sums: &mut StuckSums, j: usize, n: usize, u: f64) -> f64 {
        let k = self.bed.stiffness[j];
        let capacity = self.capacity(j, n);
        let elastic = state.held + u - state.origin;
        if elastic.abs() <= capacity {
            if !state.sticking {
                state.sticking = true;
                sums.change(1.0, k, state.anchor);
            }
            k * elastic
        } else {
            if state.sticking {
                state.sticking = false;
                sums.change(-1.0, k, state.anchor);
            }
            state.held = capacity.copysign(elastic);
            state.origin = u;
            state.anchor = Anchor::Sample { sample: n, share: 0.0 };
            k * state.held
        }
    }

    /// The sums over the stuck elements formed afresh (at the start of each period, so that
    /// their rounding does not pile up from period to period).
    fn stuck_sums<'b>(&self, states: &[ElementState], layout: &'b Layout) -> StuckSums<'b> {
        let mut sums = StuckSums {
            layout,
            stiffness: 0.0,
            anchors: vec![0.0; layout.coefficients()],
        };
        for (j, state) in states.iter().enumerate() {
            if state.in_contact && state.sticking {
                sums.change(1.0, self.bed.stiffness[j], state.anchor);
            }
        }
        sums
    }
}

#[cfg(test)]
mod tests {
    use super::super::normal_load::tests::loaded_period;

    /// The state at the end of the second period is the one at its start, from deep
    /// microslip to gross slip under the lowest load and with the load's swing reaching
    /// close to separation.
    #[test]
    fn the_state_repeats_after_the_second_period() {
        for normal in [0.05, 0.3, 0.9] {
            for amplitude in [1e-4, 3e-3, 1e-2, 3e-2, 1.0] {
                let displacement = [
                    0.1 * amplitude,
                    amplitude,
                    0.4 * amplitude,
                    0.15 * amplitude,
                    -0.1 * amplitude,
                ];
                let periods = loaded_period(&[0.0, normal, 0.2 * normal, 0.0, 0.05], &displacement).periods;
                assert!(periods <= 2, "P1 = {normal}, u1 = {amplitude}: {periods} periods");
            }
        }
    }
}
