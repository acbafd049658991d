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
use crate::doubts::watch;
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
        .map(|part| part_piece(cycle, segment, compliance, &part[0], &part[1]))
        .collect()
}

/// The bisections that place a cut where a segment's front changes over from racing θ.
const CHANGE_OVER_BISECTIONS: usize = 20;

/// One part [`start`, `end`] of a segment, in θ or in the racing front's entry angle.
fn part_piece<'a, R: Enclosing>(
    cycle: &'a SteadyCycle<R>,
    segment: &'a Segment<R>,
    compliance: &'a dyn Compliance<R>,
    start: &R,
    end: &R,
) -> CertifiedPiece<'a, R> {
    // The integrand at real points, and for the rule's bound on complex boxes with the
    // slope changes as plain differences ([`SlopeChanges`]).
    let piece = |start: R, end: R, integrand: &dyn Fn(SlopeChanges) -> PieceIntegrand<'a, R>| CertifiedPiece {
        group: 0,
        label: "path segment",
        start,
        end,
        integrand: integrand(SlopeChanges::Own),
        bound: Some(integrand(SlopeChanges::Plain)),
        evaluations: Cell::new(0),
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

/// W of the steady cycle `cycle`, enclosed with the rung's rule aiming at `goal_bits`
/// relative to a rough W; an error where a segment's integral has no enclosure.
pub fn enclose_path_dissipation<R: Enclosing>(
    cycle: &SteadyCycle<R>,
    contact: &Contact<R>,
    compliance: &dyn Compliance<R>,
    goal_bits: u32,
) -> Result<R, CertifiedError> {
    let bits = cycle.lowest_slip.precision().in_bits();
    let (pieces, doubts) = watch(|| {
        cycle
            .segments
            .iter()
            .flat_map(|segment| segment_pieces(cycle, segment, compliance))
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
    let (sums, _) = integrate_pieces(&pieces, 1, goal_bits, bits, None)?;
    let scale = contact.compliance_ratio.clone() * &contact.friction.square();
    Ok((sums[0].clone() + &error.centred_square()) * &scale)
}
