//! W of a periodic path whose normal load varies, enclosed: the steady cycle's segments
//! (built on the rung's enclosures, every comparison decided) each integrated by the
//! rung's own rule, the integrand [`work_rate`] evaluated on the rule's complex boxes,
//! where a front inside a piece of elements that entered in stick is enclosed by
//! Krawczyk's test ([`crate::path::events::krawczyk_root`]); W is λf² times the sum,
//! widened by the bound of what the cuts found by sampling may leave
//! ([`SteadyCycle::sampled_cut_error`]; proofs/periodic-loading.md, "Proven W at varying P").

use std::cell::Cell;

use super::enclosing::{CertifiedPiece, Enclosing, PieceIntegrand};
use super::pieces::integrate_pieces;
use super::CertifiedError;
use crate::compliance::Compliance;
use crate::doubts::{undecided, watch};
use crate::path::dissipation::{work_rate_in_entry_angle, work_rate_with, SlopeChanges};
use crate::path::events::Segment;
use crate::path::{Contact, SteadyCycle};

/// The integrals of one segment: in θ, or, where a front inside an entry piece races
/// ahead of θ ([`SteadyCycle::racing_entry_front`]), in that front's entry angle θₑ, from
/// θₑ at the part's start to θₑ at its end (in increasing order, the integrand's sign
/// turned where they fall). A segment whose ends race differently is cut where they
/// change over (found on doubles: any cut splits the integral exactly).
fn segment_pieces<'a, R: Enclosing>(
    cycle: &'a SteadyCycle<R>,
    segment: &'a Segment<R>,
    compliance: &'a dyn Compliance<R>,
    left: &'a Cell<i64>,
) -> Vec<CertifiedPiece<'a, R>> {
    let (start, end) = (segment.start.midpoint_value(), segment.end.midpoint_value());
    let at = |share: f64| start.clone() + &((end.clone() - &start) * &R::from_f64(share, start.precision()));
    let racing = |theta: &R| cycle.racing_entry_front(segment, theta);
    let (first, last) = (racing(&at(1.0 / 64.0)), racing(&at(63.0 / 64.0)));
    let mut cuts = vec![segment.start.clone()];
    if first != last {
        let (mut low, mut high) = (1.0 / 64.0, 63.0 / 64.0);
        for _ in 0..CHANGE_OVER_BISECTIONS {
            let middle = (low + high) / 2.0;
            if racing(&at(middle)) == first {
                low = middle;
            } else {
                high = middle;
            }
        }
        cuts.push(at((low + high) / 2.0).midpoint_value());
    }
    cuts.push(segment.end.clone());
    cuts.windows(2)
        .map(|part| part_piece(cycle, segment, compliance, (&part[0], &part[1]), left))
        .collect()
}

/// The bisections that place a cut where a segment's front changes over from racing θ.
const CHANGE_OVER_BISECTIONS: usize = 20;

/// One part [`start`, `end`] of a segment, in θ or in the racing front's entry angle; its
/// evaluations drawn from the path's `left` (none past it: the evaluation is undecided).
fn part_piece<'a, R: Enclosing>(
    cycle: &'a SteadyCycle<R>,
    segment: &'a Segment<R>,
    compliance: &'a dyn Compliance<R>,
    (start, end): (&R, &R),
    left: &'a Cell<i64>,
) -> CertifiedPiece<'a, R> {
    // The integrand at real points, and for the rule's bound on complex boxes with the
    // slope changes as plain differences ([`SlopeChanges`]).
    let piece = |start: R, end: R, integrand: &dyn Fn(SlopeChanges) -> PieceIntegrand<'a, R>| {
        let counted = |integrand: PieceIntegrand<'a, R>| -> PieceIntegrand<'a, R> {
            Box::new(move |x: &R| {
                left.set(left.get() - 1);
                if left.get() < 0 {
                    undecided();
                }
                integrand(x)
            })
        };
        CertifiedPiece {
            group: 0,
            label: "path segment",
            start,
            end,
            integrand: counted(integrand(SlopeChanges::Own)),
            bound: Some(counted(integrand(SlopeChanges::Plain))),
            evaluations: Cell::new(0),
        }
    };
    let middle = (start.clone() + end) / &start.int(2);
    let Some(forward) = cycle.racing_entry_front(segment, &middle) else {
        return piece(start.clone(), end.clone(), &|changes| {
            Box::new(move |theta: &R| work_rate_with(cycle, segment, theta, compliance, changes))
        });
    };
    let (first, last) = (
        cycle.entry_angle(segment, start, forward),
        cycle.entry_angle(segment, end, forward),
    );
    let in_entry_angle =
        move |entered: &R, changes| work_rate_in_entry_angle(cycle, segment, entered, forward, compliance, changes);
    if first < last {
        piece(first, last, &|changes| {
            Box::new(move |entered: &R| in_entry_angle(entered, changes))
        })
    } else {
        piece(last, first, &|changes| {
            Box::new(move |entered: &R| -in_entry_angle(entered, changes))
        })
    }
}

/// The integrand evaluations one enclosure of a path's W may spend over all its
/// segments, times the path's highest harmonic (an evaluation's cost grows with it): the
/// cost of a proof stays bounded by work, whatever the clock, and a path that needs more
/// rests on agreement, saying so (about 10 s on 128-bit balls).
const MOST_PATH_WORK: i64 = 100_000;

/// W of the steady cycle `cycle`, enclosed with the rung's rule aiming at `goal_bits`
/// relative to a rough W; an error where a segment's integral has no enclosure.
pub fn enclose_path_dissipation<R: Enclosing>(
    cycle: &SteadyCycle<R>,
    contact: &Contact<R>,
    compliance: &dyn Compliance<R>,
    goal_bits: u32,
) -> Result<R, CertifiedError> {
    let bits = cycle.lowest_slip.precision().in_bits();
    let given = MOST_PATH_WORK / i64::try_from(cycle.loads.highest_harmonic().max(1)).unwrap_or(i64::MAX);
    let left = Cell::new(given);
    let (pieces, doubts) = watch(|| {
        cycle
            .segments
            .iter()
            .flat_map(|segment| segment_pieces(cycle, segment, compliance, &left))
            .collect::<Vec<CertifiedPiece<'_, R>>>()
    });
    if !doubts.none() {
        return Err(CertifiedError::PathFronts {
            bits,
            what: "a front's entry angle at a segment's end, or the order of two of them, is undecided",
        });
    }
    let (error, doubts) = watch(|| cycle.sampled_cut_error(compliance));
    let error = match error {
        Some(error) if doubts.none() => error,
        _ => {
            return Err(CertifiedError::PathFronts {
                bits,
                what: "where a front meets the top of the contact as P falls through elements that entered \
                       in stick is not proven to lie in the small regions that its sampling found",
            })
        }
    };
    let (sums, _) = integrate_pieces(&pieces, 1, goal_bits, bits, None).map_err(|error| {
        if left.get() < 0 {
            CertifiedError::PathEffort {
                bits,
                evaluations: given,
            }
        } else {
            error
        }
    })?;
    let scale = contact.compliance_ratio.clone() * &contact.friction.square();
    Ok((sums[0].clone() + &error.centred_square()) * &scale)
}
