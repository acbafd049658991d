//! W of a path proven: the rigorous enclosure that every printed digit rests on, at
//! constant normal load (force- or displacement-driven) and at a varying one (force-driven).
//!
//! At constant P the contact is a Masing element, and W is the sum over the rainflow
//! cycles of the driving quantity (Q, or u) of the W of a constant-normal-load cycle at
//! each cycle's Q amplitude: half its range of Q, or g⁻¹ of half its range of u, g the
//! initial loading curve (proofs/periodic-loading.md, "Proven W"). On enclosures (f64
//! intervals, then Arb balls at rising precision) the turning points are the proven roots
//! of the derivative (`events::sign_changes`), the path's checks, the rainflow count and
//! g⁻¹'s bracket compare enclosures that must be decided, and each cycle's W is the
//! certified constant-normal-load enclosure ([`crate::digits::enclosure::enclose_dissipation`]), a cycle of u in
//! gross slip adding its sliding to the loop at fP. Where P varies, the steady cycle's
//! segments are built on the enclosures and each is integrated by the rung's rule
//! ([`crate::digits::enclosure::enclose_path_dissipation`]). A path whose comparisons no
//! precision tried decides (two turning values equal), whose fronts or meetings with the
//! top of the contact are not enclosed there, or whose segments need more evaluations
//! than an enclosure is given, is not proven here: its W rests on agreement, saying why.

use std::time::Instant;

use crate::answer::dissipation::DEFAULT_LEAST_DIGITS;
use crate::answer::{Arithmetic, Provenance, Value};
use crate::ball::Ball;
use crate::compliance::Compliance;
use crate::digits::enclosure::{enclose_path_dissipation, CertifiedError, Enclosing, INTERVAL_GOAL_BITS, MAX_BITS};
use crate::digits::{doubled, Ladder, Rung, Stop};
use crate::doubts::watch;
use crate::interval::Interval;
use crate::real::{Precision, Real};

use super::constant_load::{constant_load_w, displacement_cycles, loop_at_friction_limit, ConstantLoadCycle};
pub use super::not_proven::NotProven;
use crate::path::displacement::rainflow_ranges;
use crate::path::events::{check_path, sign_changes, SteadyCycle};
use crate::path::input::{Drive, LoadPath, TrigPoly};
use crate::path::{Contact, PathRequest};

/// W proven to the digits asked for.
#[derive(Clone, Debug)]
pub struct ProvenW {
    /// W by the one printing rule, with the enclosure it was read from.
    pub value: Value,
    /// What vouches for it: an enclosure in f64 intervals or in Arb balls.
    pub provenance: Provenance,
    /// What W is the sum of.
    pub summed: SummedOver,
    /// A lower bound of the lowest load that slips (at constant P, P − (largest Q
    /// amplitude)/f), on which the compliance must be admissible; `None` where a cycle
    /// slides (the slip then reaches load 0).
    pub lowest_slip_load: Option<f64>,
    /// An upper bound of the highest normal load, up to which it must be admissible too.
    pub highest_load: f64,
}

/// What a proven W is the sum of.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SummedOver {
    /// The W of the rainflow cycles of Q (or of u under displacement driving), at constant P.
    RainflowCycles(usize),
    /// The integrals over the smooth segments of the steady cycle, where P varies.
    Segments(usize),
}

/// W as one rung encloses it, with what it is the sum of and the loads it reaches.
struct Enclosed<R> {
    total: R,
    summed: SummedOver,
    lowest_slip_load: Option<f64>,
    highest_load: f64,
}

/// The path, contact and compliance at one precision, as the rung reads them.
type Inputs<R> = (LoadPath<R>, Contact<R>, Box<dyn Compliance<R>>);

/// W of the request proven to the significant digits asked
/// ([`PathRequest::digits_asked`]): one enclosure in f64 intervals where that settles
/// them, else the Arb ladder from the digits' bits up to [`MAX_BITS`]. Without digits
/// asked, W is served as `microslip dissipation` serves it: the digits (up to
/// [`crate::answer::dissipation::DEFAULT_DIGITS`]) the f64 intervals prove, where they prove at least
/// [`DEFAULT_LEAST_DIGITS`].
pub fn proven_w(request: &PathRequest) -> Result<ProvenW, NotProven> {
    let digits = request.digits_asked().max(1);
    let read = |precision: Precision| -> Result<Inputs<_>, NotProven> {
        let inputs = request
            .read::<Interval>(precision)
            .map_err(|_| NotProven::NotCovered("its inputs are not read as f64 intervals"))?;
        Ok((inputs.path, inputs.contact, inputs.compliance))
    };
    // Inputs that f64 intervals do not read inside the theory (λ from ν near 2) go to balls.
    let Ok((path, contact, compliance)) = read(Precision::DOUBLE) else {
        return in_balls(request, digits, false);
    };
    let in_intervals = enclose_path(&path, &contact, compliance.as_ref(), request.drive, INTERVAL_GOAL_BITS);
    if let Err(not_covered @ NotProven::NotCovered(_)) = in_intervals {
        return Err(not_covered);
    }
    if let Ok(enclosed) = &in_intervals {
        let value = enclosed.total.decimal_value(digits);
        let least = match request.digits {
            None => DEFAULT_LEAST_DIGITS,
            Some(_) => digits,
        };
        // An exact zero shows every digit (its `digits()` is u32::MAX).
        if value.digits() >= least {
            return Ok(ProvenW {
                value,
                provenance: Provenance::Certified {
                    bits: 53,
                    arithmetic: Arithmetic::F64Intervals,
                },
                summed: enclosed.summed,
                lowest_slip_load: enclosed.lowest_slip_load,
                highest_load: enclosed.highest_load,
            });
        }
    }
    in_balls(request, digits, !path.normal.is_constant())
}

/// The least working precision of the Arb ladder where P varies.
const LEAST_VARYING_BITS: u32 = 128;

/// The bits that the enclosure's rounding and the sum of the cycles need beyond the
/// digits' own.
const GUARD_BITS: u32 = 12;

/// W by the Arb ladder: balls at the digits' bits and guard bits, doubled until the
/// enclosure settles the digits or the deadline comes.
fn in_balls(request: &PathRequest, digits: u32, varying: bool) -> Result<ProvenW, NotProven> {
    let digit_bits = Precision::decimal_digits(digits).in_bits();
    let mut first = (digit_bits + GUARD_BITS).next_multiple_of(64);
    if varying {
        // The segments' cancellation leaves 64-bit balls short of 15 digits on most paths
        // whose P varies: their ladder starts where it would end.
        first = first.max(LEAST_VARYING_BITS);
    }
    let ladder = Ladder::new(Precision::bits(first), Precision::bits(MAX_BITS)).until(Some(request.deadline));
    let rung = |precision: Precision| {
        let bits = precision.in_bits();
        let inputs = match request.read::<Ball>(precision) {
            Ok(inputs) => inputs,
            // Decided inside the theory already: a comparison undecided at this precision
            // (λ from ν near 2) may be decided at the next.
            Err(_) => return Rung::Short(NotProven::NotCovered("its inputs are not read as balls")),
        };
        let varying = !inputs.path.normal.is_constant();
        let goal = digit_bits + GUARD_BITS + (bits - first);
        let enclosed = enclose_path(
            &inputs.path,
            &inputs.contact,
            inputs.compliance.as_ref(),
            request.drive,
            goal,
        );
        // Digits that arrive after the deadline are out of time all the same.
        if Instant::now() >= request.deadline {
            return Rung::Final(NotProven::OutOfTime { asked: digits });
        }
        match enclosed {
            Ok(enclosed) => {
                let value = enclosed.total.decimal_value(digits);
                if value.digits() >= digits {
                    Rung::Reached(ProvenW {
                        value,
                        provenance: Provenance::Certified {
                            bits,
                            arithmetic: Arithmetic::ArbBalls,
                        },
                        summed: enclosed.summed,
                        lowest_slip_load: enclosed.lowest_slip_load,
                        highest_load: enclosed.highest_load,
                    })
                } else {
                    Rung::Short(NotProven::TooWide {
                        asked: digits,
                        reached: value.digits(),
                        bits,
                    })
                }
            }
            Err(
                error @ (NotProven::NotCovered(_)
                | NotProven::Refused(
                    CertifiedError::Cycle(_) | CertifiedError::TooSteep { .. } | CertifiedError::PathEffort { .. },
                )),
            ) => Rung::Final(error),
            // Where P varies, a segment the rule could not enclose within its evaluations
            // (a front racing near a fold), or a comparison 128 bits left open, is not
            // settled by doubling the precision: one rung past the first, then agreement.
            Err(error) if varying && bits > first => Rung::Final(error),
            Err(error) => Rung::Short(error),
        }
    };
    match ladder.climb(rung, doubled) {
        Ok((proven, _)) => Ok(proven),
        Err(Stop::Final(error) | Stop::Exhausted(error)) => Err(error),
        Err(Stop::OutOfTime { .. }) => Err(NotProven::OutOfTime { asked: digits }),
    }
}

/// W of the path as the rung encloses it: at constant P over its rainflow cycles, else
/// over the steady cycle's segments (force driving only: a displacement-driven path
/// whose P varies is refused before it is read here).
fn enclose_path<R: Enclosing>(
    path: &LoadPath<R>,
    contact: &Contact<R>,
    compliance: &dyn Compliance<R>,
    drive: Drive,
    goal_bits: u32,
) -> Result<Enclosed<R>, NotProven> {
    if path.normal.is_constant() {
        return enclose_constant_load(path, contact, compliance, drive, goal_bits);
    }
    if drive == Drive::Displacement {
        return Err(NotProven::NotCovered(
            "its normal load varies under displacement driving",
        ));
    }
    enclose_varying_load(path, contact, compliance, goal_bits)
}

/// W where P varies, over the steady cycle built on the rung's enclosures (every
/// comparison decided, every cut a proven root), each segment enclosed by the rung's rule.
fn enclose_varying_load<R: Enclosing>(
    path: &LoadPath<R>,
    contact: &Contact<R>,
    compliance: &dyn Compliance<R>,
    goal_bits: u32,
) -> Result<Enclosed<R>, NotProven> {
    let bits = contact.friction.precision().in_bits();
    let (cycle, doubts) = watch(|| SteadyCycle::new(path, contact));
    if !doubts.none() {
        return Err(NotProven::Undecided { bits });
    }
    let cycle = cycle.map_err(|_| NotProven::Undecided { bits })?;
    let total = enclose_path_dissipation(&cycle, contact, compliance, goal_bits).map_err(NotProven::Refused)?;
    let lowest_slip_load = cycle
        .lowest_slip
        .real_span()
        .map(|(low, _)| low)
        .filter(|low| *low > 0.0);
    let highest_load = cycle.highest_load.real_span().map_or(f64::INFINITY, |(_, high)| high);
    Ok(Enclosed {
        total,
        summed: SummedOver::Segments(cycle.segments.len()),
        lowest_slip_load,
        highest_load,
    })
}

/// W at constant P as an enclosure over its rainflow cycles, with a lower bound of the
/// lowest load that slips (`None` where a cycle slides) and P: the turning values of the
/// driving quantity (Q, or u under displacement driving; rotated to start and end at the
/// largest) counted by the three-point rule, each cycle's W enclosed with the rung's own
/// rule aiming at `goal_bits`.
fn enclose_constant_load<R: Enclosing>(
    path: &LoadPath<R>,
    contact: &Contact<R>,
    compliance: &dyn Compliance<R>,
    drive: Drive,
    goal_bits: u32,
) -> Result<Enclosed<R>, NotProven> {
    let load = path.normal.cos[0].clone();
    let bits = load.precision().in_bits();
    let (cycles, doubts) = watch(|| {
        if drive == Drive::Force {
            check_path(path, contact).map_err(|_| NotProven::Undecided { bits })?;
        }
        let ranges = rainflow_ranges(&turning_values(&path.tangential));
        match drive {
            Drive::Force => Ok(ranges
                .into_iter()
                .map(|range| ConstantLoadCycle::Loop(range / &load.int(2)))
                .collect()),
            Drive::Displacement => displacement_cycles(&load, contact, compliance, &ranges),
        }
    });
    if !doubts.none() {
        return Err(NotProven::Undecided { bits });
    }
    let cycles: Vec<ConstantLoadCycle<R>> = cycles?;
    let lowest_slip_load = lowest_slip_load(&load, contact, &cycles);
    let mut total = load.int(0);
    // The loop at fP, shared by every cycle in gross slip.
    let mut limit_loop: Option<R> = None;
    for cycle in &cycles {
        let w = match cycle {
            ConstantLoadCycle::Loop(amplitude) => constant_load_w(&load, amplitude, contact, compliance, goal_bits)?,
            ConstantLoadCycle::Sliding(slid) => {
                let limit_w = match &limit_loop {
                    Some(w) => w.clone(),
                    None => limit_loop
                        .insert(loop_at_friction_limit(&load, contact, compliance, goal_bits)?)
                        .clone(),
                };
                limit_w + &(contact.friction.clone() * &load * &load.int(2) * slid)
            }
        };
        total += &w;
    }
    Ok(Enclosed {
        total,
        summed: SummedOver::RainflowCycles(cycles.len()),
        lowest_slip_load,
        highest_load: load.real_span().map_or(f64::INFINITY, |(_, high)| high),
    })
}

/// A lower bound of P − a/f over the cycles' Q amplitudes a (the load down to which a
/// Masing loop of amplitude a slips); `None` where a cycle slides, or the bound is not a
/// positive load.
fn lowest_slip_load<R: Real>(load: &R, contact: &Contact<R>, cycles: &[ConstantLoadCycle<R>]) -> Option<f64> {
    cycles.iter().try_fold(f64::INFINITY, |lowest, cycle| match cycle {
        ConstantLoadCycle::Loop(amplitude) => {
            let (below, _) = (load.clone() - &(amplitude.clone() / &contact.friction)).real_span()?;
            (below > 0.0).then_some(lowest.min(below))
        }
        ConstantLoadCycle::Sliding(_) => None,
    })
}

/// The values of the driving quantity (Q, or u) at its turning points, from the largest
/// round to it again: where the three-point rainflow count closes every cycle.
fn turning_values<R: Real>(tangential: &TrigPoly<R>) -> Vec<R> {
    let rate = tangential.derivative();
    let values: Vec<R> = sign_changes(&rate)
        .iter()
        .map(|theta| value_at_turning_point(tangential, &rate, theta))
        .collect();
    if values.is_empty() {
        return values;
    }
    let mut largest = 0;
    for (index, value) in values.iter().enumerate().skip(1) {
        if *value > values[largest] {
            largest = index;
        }
    }
    let mut rotated: Vec<R> = values[largest..].iter().chain(&values[..largest]).cloned().collect();
    rotated.push(values[largest].clone());
    rotated
}

/// The polynomial at an enclosure θ of a root of its `rate`, by the mean-value form
/// p(m) + p'(θ)(θ − m) about θ's midpoint m: p' nearly vanishes on θ, so the value is
/// about as narrow as p(m) alone, where p on θ itself would be |p'|-wide only where p'
/// is not small (a number θ gives p(θ)).
fn value_at_turning_point<R: Real>(poly: &TrigPoly<R>, rate: &TrigPoly<R>, theta: &R) -> R {
    let middle = theta.midpoint_value();
    poly.value(&middle) + &(rate.value(theta) * &(theta.clone() - &middle))
}
