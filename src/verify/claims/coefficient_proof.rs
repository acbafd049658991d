//! Claim 2 proven: I(ρ, φ) < 0 for every ρ > 0 and 0 < φ < π, by Arb ball arithmetic on
//! an adaptive subdivision of five charts that together cover the half-plane
//! w = ρe^{iφ}, Im w > 0 (proofs/small-amplitude-coefficient.md, "The proof of claim 2").
//!
//! On each chart a normalised coefficient N = I/g is evaluated, with g > 0 a factor that
//! vanishes where I does (ρ² sin²φ below ρ = 1; ρ³ above it; the distance to w = ±1
//! near the two corners where I has no single limit), and rewritten so that it is finite
//! on the chart's closed rectangle, the limits ρ → 0, ρ → ∞ and φ → 0, π included; in one
//! wedge at w = −1, where N itself vanishes to sixth order, its slope in the distance
//! instead. A box is proven when the enclosure lies below zero; otherwise it is bisected.
//! Every form used is an identity wherever its denominators are non-zero and the arguments
//! of its arctangents have the sign it assumes: a denominator whose ball reaches zero
//! makes the enclosure non-finite, and a sign that is not certain on the whole box makes
//! the form refuse (non-finite), so which form a box uses is a matter of accuracy only,
//! never of soundness.

use std::time::Instant;

use rug::Float;

use crate::ball::{hull, watch, Ball};
use crate::real::{Precision, Real};
use crate::verify::{ClaimReport, Proof};

/// Claim 2 proven: I(ρ, φ) < 0 for every ρ > 0 and 0 < φ < π, by Arb balls on an adaptive
/// subdivision of five charts whose closed rectangles take in ρ → 0, ρ → ∞ and φ → 0, π;
/// and I(ρ, 0) = 0 for ρ ≤ 1, where both terms of the closed form carry the factor sin φ
/// (and at ρ = 1, the limit, I = O(|ρe^{iφ} − 1|) on the corner chart). Not proven (a box left undecided) is a failure, with the first such box named.
pub fn coefficient_is_negative() -> ClaimReport {
    let outcome = prove_claim();
    let proven = outcome.proven();
    let note = if proven {
        format!(
            "proved with Arb balls: {} boxes in {:.2} s, ρ → 0, ∞ and φ → 0, π included (proofs/small-amplitude-coefficient.md); I(ρ,0) = 0 for ρ ≤ 1 exactly (factor sin φ)",
            outcome.boxes_evaluated, outcome.seconds
        )
    } else {
        format!(
            "not proved: {} of {} boxes undecided, the first {:?}",
            outcome.unproven.len(),
            outcome.boxes_evaluated,
            outcome.unproven[0]
        )
    };
    ClaimReport {
        claim: "2 I(ρ,φ) < 0 for all ρ > 0, 0 < φ < π; I(ρ,0) = 0 for ρ ≤ 1".to_string(),
        precision: format!("{BITS} bits"),
        cases: usize::try_from(outcome.boxes_evaluated).unwrap_or(usize::MAX),
        worst_error: if proven { 0.0 } else { f64::INFINITY },
        tolerance: 0.0,
        passed: proven,
        note,
        proof: proven.then_some(Proof::Subdivision {
            boxes: outcome.boxes_evaluated,
            seconds: outcome.seconds,
        }),
    }
}

/// The working precision of the boxes.
pub const BITS: u32 = 96;

/// The corner rectangles cut out of the charts in ρ and φ = πu. Near w = 1: |ρ − 1| ≤ 2⁻¹⁰
/// (in t = 1/ρ, t ≥ 1 − 2⁻¹⁰) and u ≤ 2⁻¹², inside the disc |w − 1| ≤ 2⁻⁹. Near w = −1, where
/// the two terms of the chart in ρ, each of size 1/(1 − ρ), cancel to about −4/3:
/// |ρ − 1| ≤ 1/15 (ρ ≥ 15/16, t ≥ 15/16) and u ≥ 63/64, inside the disc |w + 1| ≤ 1/8.
const SLIP_ONSET_SIDE: f64 = 1.0 / 1024.0;
const SLIP_ONSET_PHASE: f64 = 1.0 / 4096.0;
const ANTI_PHASE_SIDE: f64 = 1.0 / 16.0;
const ANTI_PHASE_PHASE: f64 = 1.0 / 64.0;
/// The radius of the corner chart around w = 1.
pub const SLIP_ONSET_RADIUS: f64 = 1.0 / 512.0;
/// The radius of the corner charts around w = −1.
pub const ANTI_PHASE_RADIUS: f64 = 1.0 / 8.0;

/// Bisection stops (and the box is left unproven) below this width relative to the chart.
const SMALLEST_WIDTH: f64 = 1.0 / (1u64 << 36) as f64;

/// The five charts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Chart {
    /// ρ ∈ [0, 1], φ = πu, N = I/(ρ² sin²φ).
    BelowOne,
    /// t = 1/ρ ∈ [0, 1], φ = πu, N = I/ρ³.
    AboveOne,
    /// w = 1 + εe^{iπv} (slip sets in: σ₋ = ε), N = I/(ε(1 + cos πv)).
    NearSlipOnset,
    /// w = −1 + εe^{iπv} (Q and P in anti-phase with Q1 = fP1: σ₊ = ε), N = I/ε.
    NearAntiPhase,
    /// The wedge v ≤ [`ANTI_PHASE_WEDGE`] of the anti-phase corner, where I/ε vanishes to
    /// sixth order in v at ε = 0: with I = ε sin²(πv) F(ε, v), the enclosed quantity is
    /// ∂F/∂ε, and F(0, v) < 0 is proven by hand, so ∂F/∂ε < 0 gives I < 0.
    AntiPhaseWedge,
}

/// A box of a chart: x ∈ [x0, x1], y ∈ [y0, y1] in the chart's own coordinates (binary
/// end points, so bisection is exact).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cell {
    /// The chart the box lies in.
    pub chart: Chart,
    /// The box's extent in the chart's x.
    pub x: (f64, f64),
    /// The box's extent in the chart's y.
    pub y: (f64, f64),
}

impl Cell {
    /// The box [x.0, x.1] × [y.0, y.1] of `chart`.
    pub fn new(chart: Chart, x: (f64, f64), y: (f64, f64)) -> Cell {
        Cell { chart, x, y }
    }

    /// The x side relative to the chart's extent in x.
    fn relative_widths(&self) -> (f64, f64) {
        let x_extent = match self.chart {
            Chart::BelowOne | Chart::AboveOne => 1.0,
            Chart::NearSlipOnset => SLIP_ONSET_RADIUS,
            Chart::NearAntiPhase | Chart::AntiPhaseWedge => ANTI_PHASE_RADIUS,
        };
        ((self.x.1 - self.x.0) / x_extent, self.y.1 - self.y.0)
    }

    fn halves(&self) -> (Cell, Cell) {
        let (wx, wy) = self.relative_widths();
        if wx >= wy {
            let middle = 0.5 * (self.x.0 + self.x.1);
            (
                Cell::new(self.chart, (self.x.0, middle), self.y),
                Cell::new(self.chart, (middle, self.x.1), self.y),
            )
        } else {
            let middle = 0.5 * (self.y.0 + self.y.1);
            (
                Cell::new(self.chart, self.x, (self.y.0, middle)),
                Cell::new(self.chart, self.x, (middle, self.y.1)),
            )
        }
    }
}

/// The statement proven: I(ρ, φ) + shift < 0. The claim is shift = 0; a positive shift
/// is a false claim (I → 0 at the edges), which the prover must refuse.
#[derive(Clone, Copy, Debug)]
pub struct Statement {
    /// The shift added to I (0 for the claim itself).
    pub shift: f64,
}

impl Statement {
    /// Claim 2 itself.
    pub const CLAIM: Statement = Statement { shift: 0.0 };
}

/// The outcome of a proof attempt.
#[derive(Clone, Debug)]
pub struct ProofOutcome {
    /// Boxes whose enclosure was computed (proven ones and those split).
    pub boxes_evaluated: u64,
    /// Boxes proven (they tile the region proven).
    pub boxes_proven: u64,
    /// Boxes given up on (bisected down to the smallest width, or past the budget).
    pub unproven: Vec<Cell>,
    /// Wall-clock seconds.
    pub seconds: f64,
}

impl ProofOutcome {
    /// Whether every box of the attempt was proven.
    pub fn proven(&self) -> bool {
        self.unproven.is_empty()
    }
}

/// The wedge of the anti-phase corner proven through ∂F/∂ε ([`Chart::AntiPhaseWedge`]):
/// w = −1 + εe^{iπv} with v below this (ρ just below 1, φ just below π).
pub const ANTI_PHASE_WEDGE: f64 = 3.0 / 8.0;

/// The starting boxes: the charts in ρ and in 1/ρ less the corner rectangles, the two
/// corner half-discs (the one at w = −1 in two parts: outside and inside the wedge).
pub fn initial_cells() -> Vec<Cell> {
    let (near, nearer) = (1.0 - ANTI_PHASE_SIDE, 1.0 - SLIP_ONSET_SIDE);
    let (low, high) = (SLIP_ONSET_PHASE, 1.0 - ANTI_PHASE_PHASE);
    let mut cells = Vec::new();
    for chart in [Chart::BelowOne, Chart::AboveOne] {
        cells.push(Cell::new(chart, (0.0, near), (0.0, 1.0)));
        cells.push(Cell::new(chart, (near, nearer), (0.0, high)));
        cells.push(Cell::new(chart, (nearer, 1.0), (low, high)));
    }
    cells.push(Cell::new(Chart::NearSlipOnset, (0.0, SLIP_ONSET_RADIUS), (0.0, 1.0)));
    cells.push(Cell::new(
        Chart::NearAntiPhase,
        (0.0, ANTI_PHASE_RADIUS),
        (ANTI_PHASE_WEDGE, 1.0),
    ));
    cells.push(Cell::new(
        Chart::AntiPhaseWedge,
        (0.0, ANTI_PHASE_RADIUS),
        (0.0, ANTI_PHASE_WEDGE),
    ));
    cells
}

/// Tries to prove `statement` on every box of `cells` (and on the halves of those it
/// cannot decide), evaluating at most `budget` boxes.
pub fn prove(statement: Statement, cells: Vec<Cell>, budget: u64) -> ProofOutcome {
    let started = Instant::now();
    let mut stack = cells;
    let (mut evaluated, mut proven) = (0u64, 0u64);
    let mut unproven = Vec::new();
    while let Some(cell) = stack.pop() {
        if evaluated >= budget {
            unproven.push(cell);
            continue;
        }
        evaluated += 1;
        if cell_is_negative(&cell, statement) {
            proven += 1;
            continue;
        }
        let (wx, wy) = cell.relative_widths();
        if wx.max(wy) < SMALLEST_WIDTH {
            unproven.push(cell);
            continue;
        }
        let (a, b) = cell.halves();
        stack.push(b);
        stack.push(a);
    }
    ProofOutcome {
        boxes_evaluated: evaluated,
        boxes_proven: proven,
        unproven,
        seconds: started.elapsed().as_secs_f64(),
    }
}

/// Claim 2 on the whole half-plane.
pub fn prove_claim() -> ProofOutcome {
    prove(Statement::CLAIM, initial_cells(), 2_000_000)
}

/// Whether the enclosure of N + shift/g on the box is finite and below zero, with no
/// comparison left undecided on the way.
fn cell_is_negative(cell: &Cell, statement: Statement) -> bool {
    let (negative, doubts) = watch(|| {
        let value = normalised(cell, statement);
        value.is_finite() && value < value.int(0)
    });
    negative && doubts.none()
}

fn precision() -> Precision {
    Precision::bits(BITS)
}

/// The ball [lo, hi] of two binary numbers.
fn span((lo, hi): (f64, f64)) -> Ball {
    hull(&Ball::from_f64(lo, precision()), &Ball::from_f64(hi, precision()))
}

/// atan(x)/x (1 at 0) on a real ball: even and decreasing in |x|, so enclosed by its
/// values at the ends of the ball's range of |x|.
fn atanc(x: &Ball) -> Ball {
    let (lo, hi) = x.bounds(BITS + 32);
    let one = Ball::from_i64(1, precision());
    if !(lo.is_finite() && hi.is_finite()) {
        return one.clone() / &one.int(0);
    }
    let (lo, hi) = (lo.abs(), hi.abs());
    let largest = if lo > hi { lo.clone() } else { hi.clone() };
    let smallest = if x.contains_zero() {
        Float::new(BITS + 32)
    } else if lo < hi {
        lo
    } else {
        hi
    };
    let at = |point: &Float| {
        if point.is_zero() {
            one.clone()
        } else {
            let p = Ball::from_float(point, precision());
            p.atan2(&one) / &p
        }
    };
    hull(&at(&largest), &at(&smallest))
}

/// `x` where it is certainly positive on the whole ball; otherwise an indeterminate ball,
/// so that a form assuming the sign refuses.
fn positive(x: Ball) -> Ball {
    let (lower, _) = x.bounds(BITS + 32);
    if lower > 0 {
        x
    } else {
        x.int(0) / &x.int(0)
    }
}

/// The arctangent of a real ball.
fn atan(x: &Ball) -> Ball {
    x.atan2(&x.int(1))
}

/// atan2(y, x) ∈ [0, π] for y ≥ 0: through the arctangent of y/x or x/y wherever the
/// sign of the divisor is certain on the whole ball (then the form is exact there and
/// finite where y reaches 0), and Arb's atan2 otherwise.
fn upper_angle(y: &Ball, x: &Ball) -> Ball {
    let bits = BITS + 32;
    let (x_low, x_high) = x.bounds(bits);
    let (y_low, _) = y.bounds(bits);
    let pi = Ball::pi(precision());
    if x_low > 0 {
        atan(&(y.clone() / x))
    } else if x_high < 0 {
        pi - &atan(&(y.clone() / &-x.clone()))
    } else if y_low > 0 {
        pi / &y.int(2) - &atan(&(x.clone() / y))
    } else {
        y.atan2(x)
    }
}

/// N + shift/g on the box, g the chart's normalising factor.
pub fn normalised(cell: &Cell, statement: Statement) -> Ball {
    let (x, y) = (span(cell.x), span(cell.y));
    let angle = Ball::pi(precision()) * &y;
    let (value, factor) = match cell.chart {
        Chart::BelowOne => below_one(&x, &angle, cell.x.1 < 1.0),
        Chart::AboveOne => above_one(&x, &angle),
        Chart::NearSlipOnset => near_slip_onset(&x, &angle, cell.y.0 >= 0.75),
        Chart::NearAntiPhase => near_anti_phase(&x, &angle, cell.y),
        Chart::AntiPhaseWedge => {
            // The wedge's lemma proves the sign of I alone: a shifted statement is refused.
            if statement.shift != 0.0 {
                return x.int(0) / &x.int(0);
            }
            return wedge_slope(&x, &angle);
        }
    };
    if statement.shift == 0.0 {
        value
    } else {
        value + &(Ball::from_f64(statement.shift, precision()) / &factor)
    }
}

/// (sin φ, cos φ, sin²(φ/2), cos²(φ/2)).
fn trig(angle: &Ball) -> (Ball, Ball, Ball, Ball) {
    let (sin, cos) = angle.sin_cos();
    let (half_sin, half_cos) = (angle.clone() / &angle.int(2)).sin_cos();
    (sin, cos, half_sin.square(), half_cos.square())
}

/// Z of the closed form, from σ₊² − 4e² (`plus_excess`), σ₊σ₋, σ₋², σ₊² and 4e².
fn z_term(plus_excess: &Ball, product: &Ball, minus_sq: &Ball, plus_sq: &Ball, four_e_sq: &Ball) -> Ball {
    plus_excess.square() - &(product.clone() * plus_excess * &plus_excess.int(11))
        + &(minus_sq.clone() * &(plus_sq.clone() * &plus_sq.int(27) - four_e_sq))
        - &(minus_sq.clone() * product)
}

/// The slip-line amplitudes of the homogeneous closed form at (r, e) = (x, 1) or (1, x),
/// x ∈ [0, 1]: σ∓² = (1 − x)² + 4x sin²(φ/2) or cos²(φ/2), no cancellation in either.
struct SlipLines {
    sin: Ball,
    cos: Ball,
    half_sin_sq: Ball,
    /// 1 − x.
    gap: Ball,
    minus_sq: Ball,
    plus_sq: Ball,
    minus: Ball,
    plus: Ball,
    /// σ₊σ₋.
    product: Ball,
    /// 1 − x².
    gap_span: Ball,
}

impl SlipLines {
    fn of(x: &Ball, phase: &Ball) -> SlipLines {
        let (sin, cos, half_sin_sq, half_cos_sq) = trig(phase);
        let gap = x.int(1) - x;
        let four_x = x.clone() * &x.int(4);
        let minus_sq = gap.square() + &(four_x.clone() * &half_sin_sq);
        let plus_sq = gap.square() + &(four_x * &half_cos_sq);
        let (minus, plus) = (minus_sq.sqrt(), plus_sq.sqrt());
        let product = plus.clone() * &minus;
        let gap_span = gap.clone() * &(x.int(1) + x);
        SlipLines {
            sin,
            cos,
            half_sin_sq,
            gap,
            minus_sq,
            plus_sq,
            minus,
            plus,
            product,
            gap_span,
        }
    }
}

/// I/(ρ² sin²φ) for ρ ∈ [0, 1], and ρ² sin²φ. With Y = ρ sin φ, S² − 4 = 8Y²/(σ₊σ₋ + 1 − ρ²),
/// and the slip term is ρ cos φ (A/Y)/(σ₊ + σ₋), A = atan2(2Y, 1 − ρ²); below ρ = 1
/// A/Y = 2 atanc(2Y/(1 − ρ²))/(1 − ρ²), finite at Y = 0.
fn below_one(rho: &Ball, phase: &Ball, strictly_below: bool) -> (Ball, Ball) {
    let lines = SlipLines::of(rho, phase);
    let plus_excess = -(lines.gap * &(rho.clone() + &rho.int(3))) - &(rho.clone() * &lines.half_sin_sq * &rho.int(4));
    let z = z_term(
        &plus_excess,
        &lines.product,
        &lines.minus_sq,
        &lines.plus_sq,
        &rho.int(4),
    );
    let stick = z / &(lines.minus_sq.clone() * &lines.plus * &(lines.product + &lines.gap_span) * &rho.int(12));
    let y = rho.clone() * &lines.sin;
    let angle_over_y = if strictly_below {
        let gap_span = positive(lines.gap_span.clone());
        atanc(&(y.clone() * &rho.int(2) / &gap_span)) * &rho.int(2) / &gap_span
    } else {
        upper_angle(&(y.clone() * &rho.int(2)), &lines.gap_span) / &y
    };
    let slip = rho.clone() * &lines.cos * &angle_over_y / &(lines.plus + &lines.minus);
    (-stick - &slip, y.square())
}

/// I/ρ³ for ρ ≥ 1 as a function of t = 1/ρ ∈ [0, 1], and ρ³ = 1/t³: the homogeneous
/// closed form at (r, e) = (1, t), finite at t = 0 (ρ = ∞, where it is −2/3).
fn above_one(t: &Ball, phase: &Ball) -> (Ball, Ball) {
    let lines = SlipLines::of(t, phase);
    let sum_excess = (lines.product.clone() + &lines.gap_span) * &t.int(2);
    let plus_excess =
        lines.gap * &(t.int(1) + &(t.clone() * &t.int(3))) - &(t.clone() * &lines.half_sin_sq * &t.int(4));
    let z = z_term(
        &plus_excess,
        &lines.product,
        &lines.minus_sq,
        &lines.plus_sq,
        &(t.square() * &t.int(4)),
    );
    let stick = sum_excess * &z / &(lines.minus_sq * &lines.plus * &t.int(96));
    // The slip angle atan2(2t sin φ, t² − 1) ∈ [π/2, π].
    let slip_angle = upper_angle(&(t.clone() * &lines.sin * &t.int(2)), &-lines.gap_span);
    let slip = t.square() * &lines.sin * &lines.cos * &slip_angle / &(lines.plus + &lines.minus);
    (-stick - &slip, one_over_cube(t))
}

fn one_over_cube(t: &Ball) -> Ball {
    t.int(1) / &(t.square() * t)
}

/// I/(ε(1 + cos α)) at w = 1 + εe^{iα}: σ₋ = ε, σ₊² = 4 + 4ε cos α + ε², 1 − ρ² = −ε(2cos α + ε),
/// Z = ε²Ẑ; (S² − 4)/ε = 2(σ₊ + 2cos α + ε) = 8 sin²α/(σ₊ − 2cos α − ε), the second form
/// (`past_three_quarters`) where 1 + cos α → 0, with the slip angle atan2(2 sin α, −(2cos α + ε))
/// through atanc.
fn near_slip_onset(epsilon: &Ball, alpha: &Ball, past_three_quarters: bool) -> (Ball, Ball) {
    let (sin, cos, half_sin_sq, half_cos_sq) = trig(alpha);
    let two = epsilon.int(2);
    let one_plus_cos = half_cos_sq * &two;
    let one_minus_cos = half_sin_sq * &two;
    let plus_sq = epsilon.square() + &(epsilon.clone() * &cos * &epsilon.int(4)) + &epsilon.int(4);
    let plus = plus_sq.sqrt();
    let line = cos.clone() * &two + epsilon; // 2cos α + ε
    let quarter = cos.clone() * &epsilon.int(4) + epsilon; // (σ₊² − 4)/ε
    let z_hat = quarter.square() - &(plus.clone() * &quarter * &epsilon.int(11)) + &(plus_sq * &epsilon.int(27))
        - &epsilon.int(4)
        - &(epsilon.clone() * &plus);
    let chord = plus.clone() - epsilon; // σ₊ − σ₋
    let (excess, slip) = if past_three_quarters {
        let lean = positive(-line); // −(2cos α + ε) > 0
        let excess = one_minus_cos.clone() * &epsilon.int(8) / &(plus.clone() - &(cos.clone() * &two) - epsilon);
        let ratio = sin.clone() * &two / &lean;
        let slip = chord * &one_minus_cos * &atanc(&ratio) * &two / &(lean * &epsilon.int(4));
        (excess, slip)
    } else {
        let excess = (plus.clone() + &line) * &two / &one_plus_cos;
        let angle = upper_angle(&(sin.clone() * &two), &-line);
        let slip = sin * &chord * &angle / &(one_plus_cos.clone() * &epsilon.int(4));
        (excess, slip)
    };
    let stick = excess * &z_hat / &(plus * &epsilon.int(96));
    let factor = epsilon.clone() * &one_plus_cos;
    (-stick - &slip, factor)
}

/// I/ε at w = −1 + εe^{iα}: σ₊ = ε, σ₋² = 4 − 4ε cos α + ε², 1 − ρ² = ε(2cos α − ε), Z = εẐ;
/// (S² − 4)/ε = 2(σ₋ − 2cos α + ε) = 8 sin²α/(σ₋ + 2cos α − ε), the second form where
/// cos α > 0; the slip angle atan2(2 sin α, 2cos α − ε).
fn near_anti_phase(epsilon: &Ball, alpha: &Ball, v: (f64, f64)) -> (Ball, Ball) {
    let (sin, cos, _, _) = trig(alpha);
    let two = epsilon.int(2);
    let minus_sq = epsilon.square() - &(epsilon.clone() * &cos * &epsilon.int(4)) + &epsilon.int(4);
    let minus = minus_sq.sqrt();
    let line = cos.clone() * &two - epsilon; // 2cos α − ε
    let z_hat = epsilon.square() * epsilon - &(epsilon.clone() * &epsilon.int(12))
        + &(cos.clone() * &epsilon.int(16))
        + &(epsilon.clone() * &minus_sq * &epsilon.int(27))
        + &(minus.clone() * &(epsilon.int(4) - &epsilon.square()) * &epsilon.int(11))
        - &(minus_sq.clone() * &minus);
    let excess = if v.1 <= 0.5 {
        sin.square() * &epsilon.int(8) / &(minus.clone() + &line)
    } else {
        (minus.clone() - &line) * &two
    };
    let angle = upper_angle(&(sin.clone() * &two), &line);
    let stick = excess * &z_hat / &(minus_sq * &epsilon.int(96));
    let slip = sin * &(minus - epsilon) * &angle / &epsilon.int(4);
    (-stick + &slip, epsilon.clone())
}

/// ∂F/∂ε at w = −1 + εe^{iα}, where I = ε sin²α F and, with σ₋² = 4 − 4ε cos α + ε²,
/// D = σ₋ + 2cos α − ε, L = 2cos α − ε and Q = atan(2 sin α/L)/sin α (α < π/2, ε < 2cos α),
/// F = −Ẑ/(12σ₋²D) + (σ₋ − ε)Q/4. Here σ₋' = −L/σ₋, D' = σ₋' − 1, Q' = 2/(L² + 4 sin²α).
fn wedge_slope(epsilon: &Ball, alpha: &Ball) -> Ball {
    let (sin, cos) = alpha.sin_cos();
    let e = epsilon;
    let minus_sq = e.square() - &(e.clone() * &cos * &e.int(4)) + &e.int(4);
    let minus = minus_sq.sqrt();
    let line = positive(cos.clone() * &e.int(2) - e);
    let denominator = minus.clone() + &line;
    let z_hat = e.square() * e - &(e.clone() * &e.int(12))
        + &(cos.clone() * &e.int(16))
        + &(e.clone() * &minus_sq * &e.int(27))
        + &(minus.clone() * &(e.int(4) - &e.square()) * &e.int(11))
        - &(minus_sq.clone() * &minus);
    let minus_sq_slope = e.clone() * &e.int(2) - &(cos.clone() * &e.int(4));
    let minus_slope = -(line.clone() / &minus);
    let denominator_slope = minus_slope.clone() - &e.int(1);
    let four_less = e.int(4) - &e.square();
    let z_slope = e.square() * &e.int(3) - &e.int(12)
        + &(minus_sq.clone() * &e.int(27))
        + &(e.clone() * &minus_sq_slope * &e.int(27))
        + &(minus_slope.clone() * &four_less * &e.int(11))
        - &(e.clone() * &minus * &e.int(22))
        - &(minus_sq.clone() * &minus_slope * &e.int(3));
    let ratio = sin.clone() * &e.int(2) / &line;
    let q = atanc(&ratio) * &e.int(2) / &line;
    let q_slope = e.int(2) / &(line.square() + &(sin.square() * &e.int(4)));
    let stick_slope = (z_slope * &minus_sq * &denominator
        - &(z_hat * &(minus_sq_slope * &denominator + &(minus_sq.clone() * &denominator_slope))))
        / &(minus_sq.square() * &denominator.square() * &e.int(12));
    -stick_slope + &((minus_slope - &e.int(1)) * &q / &e.int(4)) + &((minus - e) * &q_slope / &e.int(4))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The boxes and time per starting cell (a measurement, proofs/small-amplitude-coefficient.md):
    /// `cargo test --release --lib coefficient_proof -- --ignored --nocapture`.
    #[test]
    #[ignore]
    fn boxes_per_starting_cell() {
        for cell in initial_cells() {
            let outcome = prove(Statement::CLAIM, vec![cell], 400_000);
            eprintln!("{cell:?}: {} boxes, {:.2} s", outcome.boxes_evaluated, outcome.seconds);
            assert!(outcome.proven());
        }
    }
}
