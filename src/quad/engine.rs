//! The one way to integrate a list of one-dimensional integrals ("pieces", e.g. the
//! parts of the four segments) to a common relative tolerance.
//!
//! Each piece starts with Gauss–Legendre rules of doubling degree, which converge
//! geometrically when the integrand is analytic well beyond the interval. Callers
//! split their intervals so that near-singularities lie at ends, and map the narrow
//! ones away ([`super::sinh_map`]). Where the doubling still stalls (the largest rule,
//! or two doublings without a tenfold gain) the piece falls back to tanh–sinh, whose
//! nodes crowd double-exponentially toward the ends; where that stalls too, the
//! piece has met the rounding noise of its integrand. Each piece reports which of
//! these ended it ([`Stop`]).
//!
//! A deadline is kept ahead of the work, not after it: no rule is applied whose
//! predicted cost (its points times the time per point of the last rule applied) would
//! end past the deadline, and node tables stop computing at it.

use std::sync::Arc;
use std::time::{Duration, Instant};

use super::gauss_legendre::{node_table_before, NodeTable};
use super::{tanh_sinh, Estimate};
use crate::real::{Precision, Real};

/// ∫ₛₜₐᵣₜ^ₑₙd integrand: one piece of a sum of integrals.
pub struct Piece<'a, R> {
    /// What the piece is (a segment's name, or a closed form's term), for messages.
    pub label: &'static str,
    /// The integrand.
    pub integrand: Box<dyn Fn(&R) -> R + 'a>,
    /// Lower limit.
    pub start: R,
    /// Upper limit.
    pub end: R,
}

impl<'a, R> Piece<'a, R> {
    /// ∫ₛₜₐᵣₜ^ₑₙd `integrand`, named `label`.
    pub fn new(label: &'static str, start: R, end: R, integrand: impl Fn(&R) -> R + 'a) -> Self {
        Piece {
            label,
            integrand: Box::new(integrand),
            start,
            end,
        }
    }
}

/// Every piece integrated once with a given Gauss–Legendre rule, no refinement: for
/// checking a converged result with another rule.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FixedRule {
    /// The rule for every piece.
    pub points: usize,
    /// The rule of each piece in turn (as [`Integrated::check_rules`] gives them for the
    /// same pieces); where the count differs, `points` for all.
    pub per_piece: Option<Vec<usize>>,
    /// How each piece's error is sized.
    pub error: RuleError,
}

impl FixedRule {
    /// The largest rule applied to any piece.
    pub fn largest(&self) -> usize {
        self.per_piece.iter().flatten().copied().fold(self.points, usize::max)
    }
}

/// How a fixed rule sizes each piece's error.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RuleError {
    /// By the change from the rule of a quarter of the points (a fifth more evaluations):
    /// the rule alone cannot tell a converged piece from one whose peak its nodes miss.
    QuarterRule,
    /// By the rounding floor only, where the value is only compared with an independent
    /// one (as a check of a converged result is).
    RoundingFloor,
}

/// How far to drive the pieces.
#[derive(Clone, Debug)]
pub struct Settings<R> {
    /// Target error relative to the scale Σ|pieces|.
    pub relative_tolerance: R,
    /// The first Gauss–Legendre rule of the doubling sequence.
    pub first_points: usize,
    /// The largest Gauss–Legendre rule before tanh–sinh takes over.
    pub max_points: usize,
    /// Integrate with fixed rules instead of converging.
    pub fixed: Option<FixedRule>,
    /// Give up with [`QuadError::OutOfTime`] rather than run past this instant.
    pub deadline: Option<Instant>,
}

impl<R> Settings<R> {
    /// Converge to `relative_tolerance` from 16 points up to 512, with no deadline.
    pub fn new(relative_tolerance: R) -> Self {
        Settings {
            relative_tolerance,
            first_points: 16,
            max_points: 512,
            fixed: None,
            deadline: None,
        }
    }
}

/// Why the pieces could not be integrated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum QuadError {
    /// Neither rule reached the tolerance on some piece.
    #[error("the integrals did not converge: relative change {relative_error:.2e} at {points} points per piece, {requested:.2e} requested")]
    NotConverged {
        /// The Gauss–Legendre rule reached on the piece.
        points: usize,
        /// The error reached, relative to the sum of the pieces.
        relative_error: f64,
        /// The relative tolerance asked for.
        requested: f64,
    },
    /// The next step (a rule, a tanh–sinh level, a node table) would have ended past the
    /// deadline, or it had passed.
    #[error("the time budget ran out before the integrals converged")]
    OutOfTime,
    /// An integrand produced NaN or infinity.
    #[error("the {piece} integral is not finite")]
    NotFinite {
        /// The piece's label.
        piece: &'static str,
    },
}

/// Why a piece's integration ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    /// The piece is empty (its limits coincide): zero, exactly.
    Empty,
    /// The last doubling changed the value by no more than the piece's share of the tolerance.
    Converged,
    /// The last doubling's change lies below the rounding floor 64ε·∫|f| of a cancelling
    /// integrand, though above the share: the change is rounding, not error.
    RoundingFloor,
    /// The error predicted from the last two changes is safely below the share
    /// (`predicted_error`), one doubling early.
    Predicted,
    /// Gauss–Legendre stalled and tanh–sinh converged.
    TanhSinh,
    /// Both rules reached the rounding noise of the integrand, within a small multiple of
    /// the share; the noise is the error estimate. The value is Gauss–Legendre's.
    Noise,
    /// A fixed rule applied once, as asked ([`FixedRule`]).
    Fixed,
}

/// The rule that gave a piece's value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rule {
    /// Gauss–Legendre with this many points.
    GaussLegendre(usize),
    /// Tanh–sinh, after Gauss–Legendre rules up to this many points stalled.
    TanhSinh {
        /// The largest Gauss–Legendre rule applied to the piece.
        after: usize,
    },
}

impl Rule {
    /// The largest Gauss–Legendre rule applied to the piece.
    pub fn gauss_legendre_points(self) -> usize {
        match self {
            Rule::GaussLegendre(points) | Rule::TanhSinh { after: points } => points,
        }
    }
}

/// One piece's result.
#[derive(Clone, Debug)]
pub struct PieceEstimate<R> {
    /// Its value, error estimate, evaluations, and whether it met its share of the
    /// tolerance (all but [`Stop::Noise`]).
    pub estimate: Estimate<R>,
    /// ∫|f| by the last Gauss–Legendre rule applied to it: the scale of its rounding.
    pub magnitude: R,
    /// The rule that gave its value.
    pub rule: Rule,
    /// Why its integration ended.
    pub stop: Stop,
}

impl<R> PieceEstimate<R> {
    /// Whether Gauss–Legendre stalled on it (tanh–sinh finished it, or both met noise).
    fn stalled(&self) -> bool {
        matches!(self.stop, Stop::TanhSinh | Stop::Noise)
    }
}

/// The pieces integrated.
#[derive(Clone, Debug)]
pub struct Integrated<R> {
    /// Each piece's result, in the order given.
    pub pieces: Vec<PieceEstimate<R>>,
    /// The sum of the pieces' error estimates.
    pub error: R,
    /// Integrand evaluations spent over all pieces.
    pub evaluations: usize,
    /// The largest Gauss–Legendre rule used on any piece.
    pub largest_rule: usize,
}

impl<R: Real> Integrated<R> {
    /// The pieces' values, in the order given.
    pub fn values(&self) -> impl Iterator<Item = &R> {
        self.pieces.iter().map(|piece| &piece.estimate.value)
    }

    /// For each piece in turn, the Gauss–Legendre rule a check by a finer fixed rule
    /// ([`FixedRule::per_piece`]) should start from: the piece's own rule where
    /// Gauss–Legendre finished it, and where it stalled (a near-singularity at an end, or
    /// noise) the largest rule used on any piece, the most a rule has shown to resolve.
    pub fn check_rules(&self) -> Vec<usize> {
        self.pieces
            .iter()
            .map(|piece| {
                if piece.stalled() {
                    self.largest_rule
                } else {
                    piece.rule.gauss_legendre_points()
                }
            })
            .collect()
    }

    /// Why each piece's integration ended, in the order given.
    pub fn stops(&self) -> Vec<Stop> {
        self.pieces.iter().map(|piece| piece.stop).collect()
    }
}

/// Tanh–sinh levels allowed after Gauss–Legendre gives up (each doubles the nodes).
const MAX_TANH_SINH_LEVEL: u32 = 16;

/// How far above its share of the tolerance a piece may end when both rules have
/// reached its rounding noise, the noise then being its error estimate. Beyond this
/// the working precision is too low for the tolerance, and the piece is refused.
const NOISE_MARGIN: i64 = 100;

/// The deadline, kept ahead of the work by predicting each step's cost from the time
/// per integrand evaluation of the last rule applied; and the rules applied so far, each
/// fetched from the shared node cache once per integration rather than once per piece.
struct Clock<R> {
    deadline: Option<Instant>,
    /// The measured time per point of the last rule applied (zero before the first).
    per_point: Duration,
    rules: Vec<(usize, Precision, Arc<NodeTable<R>>)>,
}

impl<R: Real> Clock<R> {
    fn new(deadline: Option<Instant>) -> Self {
        Clock {
            deadline,
            per_point: Duration::ZERO,
            rules: Vec::new(),
        }
    }

    /// The `points`-point rule at `precision`, or `None` when computing it would run past
    /// the deadline.
    fn rule(&mut self, points: usize, precision: Precision) -> Option<Arc<NodeTable<R>>> {
        let known = self
            .rules
            .iter()
            .find(|(n, bits, _)| *n == points && *bits == precision);
        if let Some((_, _, rule)) = known {
            return Some(Arc::clone(rule));
        }
        let rule = node_table_before::<R>(points, precision, self.deadline)?;
        self.rules.push((points, precision, Arc::clone(&rule)));
        Some(rule)
    }

    /// Whether a rule of `points` points may start: it is predicted to end by the deadline.
    fn allows(&self, points: usize) -> Result<(), QuadError> {
        let Some(deadline) = self.deadline else {
            return Ok(());
        };
        let predicted = self.per_point.saturating_mul(u32::try_from(points).unwrap_or(u32::MAX));
        if Instant::now() + predicted >= deadline {
            return Err(QuadError::OutOfTime);
        }
        Ok(())
    }

    /// The piece by the `points`-point rule, with the rule applied to |f| (see
    /// `NodeTable::integrate_with_magnitude`); the time per point is recorded.
    fn gauss(&mut self, piece: &Piece<'_, R>, points: usize) -> Result<(R, R), QuadError> {
        if piece.start == piece.end {
            return Ok((piece.start.int(0), piece.start.int(0)));
        }
        self.allows(points)?;
        let table = self.rule(points, piece.start.precision()).ok_or(QuadError::OutOfTime)?;
        let started = self.deadline.map(|_| Instant::now());
        let (value, magnitude) = table.integrate_with_magnitude(&piece.integrand, &piece.start, &piece.end);
        if let Some(started) = started {
            self.per_point = started.elapsed() / u32::try_from(points.max(1)).unwrap_or(u32::MAX);
        }
        Ok((finite(value, piece)?, magnitude))
    }
}

/// The rounding floor of a rule's value: 64ε·∫|f|. Changes below it are noise, not error.
fn rounding_floor<R: Real>(magnitude: &R) -> R {
    magnitude.clone() * &magnitude.epsilon_like() * &magnitude.int(64)
}

fn finite<R: Real>(value: R, piece: &Piece<'_, R>) -> Result<R, QuadError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(QuadError::NotFinite { piece: piece.label })
    }
}

/// Each piece to an absolute accuracy of `relative_tolerance` × Σ|pieces| / (number of
/// pieces): the scale of the sum, which is what a cancelling sum can be trusted to.
/// Fails with `NotConverged` when neither rule gets there.
pub fn integrate<R: Real>(pieces: &[Piece<'_, R>], settings: &Settings<R>) -> Result<Integrated<R>, QuadError> {
    match &settings.fixed {
        Some(fixed) => integrate_fixed(pieces, fixed, settings),
        None => converge(pieces, settings),
    }
}

fn integrate_fixed<R: Real>(
    pieces: &[Piece<'_, R>],
    fixed: &FixedRule,
    settings: &Settings<R>,
) -> Result<Integrated<R>, QuadError> {
    let sizes: Vec<usize> = match &fixed.per_piece {
        Some(sizes) if sizes.len() == pieces.len() => sizes.clone(),
        _ => vec![fixed.points; pieces.len()],
    };
    let mut clock = Clock::new(settings.deadline);
    let mut results = Vec::with_capacity(pieces.len());
    let mut error = settings.relative_tolerance.int(0);
    let mut evaluations = 0;
    for (piece, &size) in pieces.iter().zip(&sizes) {
        let (value, magnitude) = clock.gauss(piece, size)?;
        let mut piece_evaluations = size;
        let floor = rounding_floor(&magnitude);
        let piece_error = match fixed.error {
            RuleError::QuarterRule => {
                let coarse_points = (size / 4).max(1);
                let (coarse, _) = clock.gauss(piece, coarse_points)?;
                piece_evaluations += coarse_points;
                (value.clone() - &coarse).abs().max_of(&floor)
            }
            RuleError::RoundingFloor => floor,
        };
        error += &piece_error;
        evaluations += piece_evaluations;
        results.push(PieceEstimate {
            estimate: Estimate {
                value,
                error: piece_error,
                evaluations: piece_evaluations,
                converged: true,
            },
            magnitude,
            rule: Rule::GaussLegendre(size),
            stop: Stop::Fixed,
        });
    }
    Ok(Integrated {
        pieces: results,
        error,
        evaluations,
        largest_rule: sizes.iter().copied().max().unwrap_or(fixed.points),
    })
}

/// Refines every piece in turn, each held to its share of the tolerance as the scale of
/// the sum is known at its turn.
fn converge<R: Real>(pieces: &[Piece<'_, R>], settings: &Settings<R>) -> Result<Integrated<R>, QuadError> {
    let first_points = settings.first_points.max(2);
    let max_points = settings.max_points.max(first_points);
    let mut clock = Clock::new(settings.deadline);
    let mut results = first_look(pieces, first_points, &mut clock)?;
    for (i, piece) in pieces.iter().enumerate() {
        if results[i].stop == Stop::Empty {
            continue;
        }
        let allowed = share(&results, &settings.relative_tolerance);
        match Refinement::new(results[i].clone(), &allowed).run(piece, max_points, &mut clock) {
            Ok(refined) => results[i] = refined,
            Err(Refused::Quadrature(error)) => return Err(error),
            Err(Refused::Spread { result, spread, points }) => {
                results[i] = *result;
                return Err(not_converged(&results, &spread, &settings.relative_tolerance, points));
            }
        }
    }
    let zero = settings.relative_tolerance.int(0);
    let error = results.iter().fold(zero, |acc, piece| acc + &piece.estimate.error);
    let evaluations = results.iter().map(|piece| piece.estimate.evaluations).sum();
    let largest_rule = results
        .iter()
        .map(|piece| piece.rule.gauss_legendre_points())
        .fold(first_points, usize::max);
    Ok(Integrated {
        pieces: results,
        error,
        evaluations,
        largest_rule,
    })
}

/// Every piece by the first rule: the scale of the sum, and each piece's start.
fn first_look<R: Real>(
    pieces: &[Piece<'_, R>],
    first_points: usize,
    clock: &mut Clock<R>,
) -> Result<Vec<PieceEstimate<R>>, QuadError> {
    pieces
        .iter()
        .map(|piece| {
            let (value, magnitude) = clock.gauss(piece, first_points)?;
            let empty = piece.start == piece.end;
            Ok(PieceEstimate {
                estimate: Estimate {
                    error: value.int(0),
                    value,
                    evaluations: first_points,
                    converged: true,
                },
                magnitude,
                rule: Rule::GaussLegendre(first_points),
                stop: if empty { Stop::Empty } else { Stop::Converged },
            })
        })
        .collect()
}

/// A piece's share of the tolerance: `relative_tolerance` × Σ|pieces| / (number of pieces).
fn share<R: Real>(results: &[PieceEstimate<R>], relative_tolerance: &R) -> R {
    let scale = results.iter().fold(relative_tolerance.int(0), |acc, piece| {
        acc + &piece.estimate.value.abs()
    });
    scale * relative_tolerance / &relative_tolerance.int(results.len().max(1) as i64)
}

/// Why a piece's refinement failed.
enum Refused<R> {
    Quadrature(QuadError),
    /// Both rules stalled with this spread, beyond the noise margin, at `points`.
    Spread {
        result: Box<PieceEstimate<R>>,
        spread: R,
        points: usize,
    },
}

impl<R> From<QuadError> for Refused<R> {
    fn from(error: QuadError) -> Self {
        Refused::Quadrature(error)
    }
}

/// One piece's doubling of the Gauss–Legendre rule, with what its stop criteria need.
struct Refinement<'s, R> {
    result: PieceEstimate<R>,
    /// The piece's share of the tolerance.
    allowed: &'s R,
    /// The last doubling's change.
    previous_change: Option<R>,
    /// The smallest change yet, and how many doublings running failed to bring the change
    /// below a tenth of it.
    smallest_change: Option<R>,
    stalled: u32,
}

impl<'s, R: Real> Refinement<'s, R> {
    fn new(result: PieceEstimate<R>, allowed: &'s R) -> Self {
        Refinement {
            result,
            allowed,
            previous_change: None,
            smallest_change: None,
            stalled: 0,
        }
    }

    fn points(&self) -> usize {
        self.result.rule.gauss_legendre_points()
    }

    /// Doubles the rule until a stop criterion holds, or hands the piece to tanh–sinh
    /// where the doubling stalls (the largest rule, or two doublings without a tenfold gain).
    fn run(
        mut self,
        piece: &Piece<'_, R>,
        max_points: usize,
        clock: &mut Clock<R>,
    ) -> Result<PieceEstimate<R>, Refused<R>> {
        loop {
            if self.points() * 2 > max_points || self.stalled >= 2 {
                return self.finish_by_tanh_sinh(piece, clock);
            }
            let points = self.points() * 2;
            let (refined, magnitude) = clock.gauss(piece, points)?;
            if let Some(stop) = self.record(refined, magnitude, points) {
                self.result.stop = stop;
                return Ok(self.result);
            }
        }
    }

    /// Takes the value of the doubled rule; the stop, where one holds.
    fn record(&mut self, refined: R, magnitude: R, points: usize) -> Option<Stop> {
        let result = &mut self.result;
        result.rule = Rule::GaussLegendre(points);
        result.estimate.evaluations += points;
        let change = (refined.clone() - &result.estimate.value).abs();
        result.estimate.value = refined;
        let floor = rounding_floor(&magnitude);
        result.magnitude = magnitude;
        // Converged to the tolerance, or to the rounding floor of a cancelling integrand.
        if change <= *self.allowed || change <= floor {
            let stop = if change <= *self.allowed {
                Stop::Converged
            } else {
                Stop::RoundingFloor
            };
            result.estimate.error = change.max_of(&floor);
            return Some(stop);
        }
        if let Some(predicted) = predicted_error(&change, self.previous_change.as_ref(), self.allowed) {
            result.estimate.error = predicted;
            return Some(Stop::Predicted);
        }
        let gained = self
            .smallest_change
            .as_ref()
            .is_none_or(|smallest| change.clone() * &change.int(10) <= *smallest);
        self.stalled = if gained { 0 } else { self.stalled + 1 };
        if gained {
            self.smallest_change = Some(change.clone());
        }
        self.previous_change = Some(change);
        None
    }

    /// Gauss–Legendre stalled: a near-singularity at an end, or the rounding noise of the
    /// integrand. Tanh–sinh resolves the first and tells the second: where the two rules
    /// agree with each other and with themselves to within NOISE_MARGIN × the share, the
    /// piece has reached its noise, and that spread is its error.
    fn finish_by_tanh_sinh(mut self, piece: &Piece<'_, R>, clock: &Clock<R>) -> Result<PieceEstimate<R>, Refused<R>> {
        let (start, end) = (&piece.start, &piece.end);
        let estimate = match clock.deadline {
            Some(deadline) => tanh_sinh::integrate_before(
                &piece.integrand,
                start,
                end,
                self.allowed,
                MAX_TANH_SINH_LEVEL,
                deadline,
            )
            .ok_or(QuadError::OutOfTime)?,
            None => tanh_sinh::integrate(&piece.integrand, start, end, self.allowed, MAX_TANH_SINH_LEVEL),
        };
        let points = self.points();
        let result = &mut self.result;
        result.estimate.evaluations += estimate.evaluations;
        let value = finite(estimate.value, piece)?;
        if estimate.converged {
            result.estimate.value = value;
            result.estimate.error = estimate.error;
            result.rule = Rule::TanhSinh { after: points };
            result.stop = Stop::TanhSinh;
            return Ok(self.result);
        }
        let last_change = self.previous_change.clone().unwrap_or_else(|| estimate.error.clone());
        let spread = (value - &result.estimate.value)
            .abs()
            .max_of(&estimate.error)
            .max_of(&last_change);
        if spread > self.allowed.clone() * &spread.int(NOISE_MARGIN) {
            return Err(Refused::Spread {
                result: Box::new(self.result),
                spread,
                points,
            });
        }
        result.estimate.error = spread;
        result.estimate.converged = false;
        result.stop = Stop::Noise;
        Ok(self.result)
    }
}

/// The error of the latest rule predicted from the last two changes, when the
/// prediction is safely below `allowed`.
///
/// With d = |I_2n − I_n| ≈ E(n) and d' = |I_n − I_{n/2}| ≈ E(n/2), the last doubling
/// gained a factor d'/d. Gauss–Legendre on an analytic integrand squares the error per
/// doubling once asymptotic (E(2n) ≈ d³/d'²), but while a nearby singularity still shapes
/// the convergence the gains grow more slowly, which the earlier changes do not show
/// (proofs/quadrature.md, "The convergence driver's early stop"). So the prediction
/// assumes only that the next doubling gains as much as the last, E(2n) ≈ d²/d'. It is
/// trusted only when the last doubling gained at least three digits (d < d'/1000) and
/// 100× the prediction clears `allowed`; that is the error reported.
fn predicted_error<R: Real>(change: &R, previous: Option<&R>, allowed: &R) -> Option<R> {
    let previous = previous?;
    if change.clone() * &change.int(1000) >= *previous {
        return None;
    }
    let reported = change.clone() * change / previous * &change.int(100);
    (reported <= *allowed).then_some(reported)
}

fn not_converged<R: Real>(results: &[PieceEstimate<R>], error: &R, relative_tolerance: &R, points: usize) -> QuadError {
    let zero = relative_tolerance.int(0);
    let total = results
        .iter()
        .fold(zero.clone(), |acc, piece| acc + &piece.estimate.value)
        .abs();
    let scale = total.max_of(&relative_tolerance.epsilon_like());
    QuadError::NotConverged {
        points,
        relative_error: (error.clone() / &scale).to_f64_lossy(),
        requested: relative_tolerance.to_f64_lossy(),
    }
}
