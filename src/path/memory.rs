//! The spring bed's memory F(s) = Φ_s − s over the contact, as pieces in the load s; its
//! update over one monotone interval of the path; and the slip fronts it places.
//!
//! The pieces are F = a + b s (b = 0 after forward slip, −2 after backward slip, −1 for
//! the elements that never slip) and entry pieces F(P(θ)) = x(θ), elements that entered
//! while the contact stuck with P rising. A front in an affine piece lies at a load affine
//! in x or y; in an entry piece, at P(θₑ) of the earlier angle θₑ where x (or y) had its
//! current value.
//!
//! On enclosures every comparison of the update must be decided, and in the steady cycle
//! some are ties by construction: at a turning point of x the forward front reaches
//! exactly the level that the same turning point left one period before, and P falls to
//! exactly the load at which it last turned. Values that are one of the path's values at a
//! break (x, y or P at an angle that ends a monotone interval, counted modulo the period)
//! carry that [`Origin`], and two values of one origin compare equal without their
//! enclosures, which overlap, being asked.

use crate::doubts::if_decided;
use crate::real::Real;

use super::events::{decided_sign, same_level_angle, solve, solve_between, Loads, Point};

/// Which of the path's values at a break a memory value is exactly: x, y or P at the
/// break of that index (modulo the number of breaks: the path is periodic).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Origin {
    X(usize),
    Y(usize),
    P(usize),
}

/// A break: its angle and its index, counted modulo the period.
pub(crate) type Break<'a, R> = (&'a R, usize);

/// A value, with the break value it is exactly where it is one.
#[derive(Clone, Debug)]
pub(crate) struct Known<R> {
    pub value: R,
    pub origin: Option<Origin>,
}

impl<R: Real> Known<R> {
    pub fn exactly(value: R, origin: Origin) -> Self {
        Known {
            value,
            origin: Some(origin),
        }
    }

    pub fn plain(value: R) -> Self {
        Known { value, origin: None }
    }

    /// Whether both are one break value (so one number).
    pub fn same(&self, other: &Known<R>) -> bool {
        self.origin.is_some() && self.origin == other.origin
    }

    pub fn le(&self, other: &Known<R>) -> bool {
        self.same(other) || self.value <= other.value
    }
    pub fn ge(&self, other: &Known<R>) -> bool {
        self.same(other) || self.value >= other.value
    }
    pub fn lt(&self, other: &Known<R>) -> bool {
        !self.same(other) && self.value < other.value
    }
    pub fn gt(&self, other: &Known<R>) -> bool {
        !self.same(other) && self.value > other.value
    }
}

/// How a piece of the memory depends on the load s.
#[derive(Clone, Debug)]
pub(crate) enum Shape<R> {
    /// F = a + b s.
    Affine { a: R, b: i64 },
    /// F(P(θ)) = x(θ) for θ in [from, to], P rising there.
    Entry { from: R, to: R },
}

/// One piece of the memory over loads [lo, hi], with F and G = F + 2s at both ends.
#[derive(Clone, Debug)]
pub(crate) struct Piece<R> {
    pub lo: Known<R>,
    pub hi: Known<R>,
    pub f_lo: Known<R>,
    pub f_hi: Known<R>,
    pub g_lo: Known<R>,
    pub g_hi: Known<R>,
    pub shape: Shape<R>,
}

impl<R: Real> Piece<R> {
    /// F = a + b s over [lo, hi]: F is a itself where b = 0, and G is a itself where b = −2.
    fn affine(lo: Known<R>, hi: Known<R>, a: Known<R>, b: i64) -> Self {
        let (f_lo, g_lo) = Self::affine_ends(&lo.value, &a, b);
        let (f_hi, g_hi) = Self::affine_ends(&hi.value, &a, b);
        Piece {
            lo,
            hi,
            f_lo,
            f_hi,
            g_lo,
            g_hi,
            shape: Shape::Affine { a: a.value, b },
        }
    }

    /// F and G of F = a + b s at load s.
    fn affine_ends(s: &R, a: &Known<R>, b: i64) -> (Known<R>, Known<R>) {
        let f = match b {
            0 => a.clone(),
            _ => Known::plain(a.value.clone() + &(s.clone() * &s.int(b))),
        };
        let g = match b {
            -2 => a.clone(),
            _ => Known::plain(f.value.clone() + &(s.clone() * &s.int(2))),
        };
        (f, g)
    }

    /// An entry piece over [lo, hi] = [P(from), P(to)], entered from angle `from` to `to`:
    /// F = x and G = y at its ends, as at the top of the contact where they entered.
    fn entry(lo: Known<R>, hi: Known<R>, from: (R, Known<R>, Known<R>), to: (R, Known<R>, Known<R>)) -> Self {
        Piece {
            lo,
            hi,
            f_lo: from.1,
            f_hi: to.1,
            g_lo: from.2,
            g_hi: to.2,
            shape: Shape::Entry { from: from.0, to: to.0 },
        }
    }

    /// The load in the piece where F = x (`forward`) or F + 2s = y, the value lying
    /// between the piece's end values.
    pub fn load_where(&self, loads: &Loads<R>, value: &R, forward: bool) -> R {
        match &self.shape {
            Shape::Affine { a, b } => {
                let slope = if forward { *b } else { b + 2 };
                if slope == 0 {
                    return self.lo.value.clone();
                }
                (value.clone() - a) / &a.int(slope)
            }
            Shape::Entry { from, to } => loads.p(&self.load_angle(loads, (from, to), value, forward)),
        }
    }

    /// In an entry piece, the angle θₑ at which the element entered whose memory the
    /// slip variable's `value` reaches: x(θₑ) = x (`forward`) or y(θₑ) = y, bracketed by
    /// the piece's angles.
    fn load_angle(&self, loads: &Loads<R>, (from, to): (&R, &R), value: &R, forward: bool) -> R {
        if forward {
            // F at the piece's ends is x there, computed from their angles as f is.
            let ends = (self.f_lo.value.clone() - value, self.f_hi.value.clone() - value);
            let start = loads.start_for(Point::x_and_rate, value, from, to);
            solve_between(
                |t: &R| loads.at(t).x_and_rate(value),
                (from, ends.0),
                (to, ends.1),
                start,
            )
        } else {
            // y = F + 2s at the ends, but not to the last bit as the angles give it.
            let rate = |t: &R| loads.at(t).y_and_rate(value);
            let start = loads.start_for(Point::y_and_rate, value, from, to);
            solve_between(rate, (from, rate(from).0), (to, rate(to).0), start)
        }
    }

    /// The load of a front in the piece at angle `theta`, where the slip variable (x
    /// `forward`, else y) has `value`: [`Piece::load_where`] on numbers; on enclosures,
    /// real or the complex boxes of a quadrature's ellipse, inside an entry piece the load
    /// at [`Piece::entry_angle_at`].
    pub fn front_at(&self, loads: &Loads<R>, theta: &R, value: &R, forward: bool) -> R {
        match (&self.shape, value.real_span()) {
            (Shape::Entry { .. }, Some(_)) => loads.p(&self.entry_angle_at(loads, theta, value, forward)),
            _ => self.load_where(loads, value, forward),
        }
    }

    /// In an entry piece, on enclosures, the angle θₑ ≠ θ at which the slip variable had
    /// its `value` at `theta`, for every θ in `theta` at once ([`same_level_angle`]), from
    /// a root at the middle: f64's, bracketed in the piece; else bracketed at the working
    /// precision where the signs at the piece's ends are decided; else, at a value that is
    /// an end's to the working precision (a segment's end), that end's angle. Each is the
    /// front's angle at the middle, so the one root the test proves in its box is the
    /// front's (proofs/periodic-loading.md, "Proven W at varying P", the branch).
    pub fn entry_angle_at(&self, loads: &Loads<R>, theta: &R, value: &R, forward: bool) -> R {
        let Shape::Entry { from, to } = &self.shape else {
            return theta.clone();
        };
        let level = value.midpoint_value();
        let rate = if forward { Point::x_and_rate } else { Point::y_and_rate };
        let root = loads
            .start_for(rate, &level, from, to)
            .or_else(|| if_decided(|| self.load_angle(loads, (from, to), &level, forward)))
            .unwrap_or_else(|| {
                let off = |end: &Known<R>| (end.value.clone() - &level).abs().to_f64_lossy();
                let (low, high) = self.slip_ends(forward);
                if off(low) <= off(high) {
                    from.clone()
                } else {
                    to.clone()
                }
            })
            .midpoint_value();
        same_level_angle(loads, theta, &root, forward)
    }

    /// In an entry piece, the angle of its end (`from` at its lower load, `to` at its
    /// upper) whose slip variable's value may be `value`: where a segment ends as its
    /// front reaches the piece's end (the cut solves v = the end's value, v at the end's
    /// angle), the front's entry angle there is that end's exactly, also where v' vanishes
    /// at it and no Krawczyk box about it is proven. Asked only where that box is not: a
    /// fold of θₑ(θ) lies only at a turning point of v, a break, which ends the piece.
    #[cfg_attr(not(feature = "certified"), allow(dead_code))]
    pub(crate) fn end_angle_at(&self, value: &R, forward: bool) -> Option<R> {
        let Shape::Entry { from, to } = &self.shape else {
            return None;
        };
        let (low, high) = self.slip_ends(forward);
        let touches = |end: &Known<R>| !matches!(decided_sign(&(end.value.clone() - value)), Some(-1 | 1));
        match (touches(low), touches(high)) {
            (true, false) => Some(from.clone()),
            (false, true) => Some(to.clone()),
            _ => None,
        }
    }

    /// The values at the piece's lower and upper ends that the slip variable meets: F
    /// (against x, `forward`) or G = F + 2s (against y).
    fn slip_ends(&self, forward: bool) -> (&Known<R>, &Known<R>) {
        if forward {
            (&self.f_lo, &self.f_hi)
        } else {
            (&self.g_lo, &self.g_hi)
        }
    }

    /// The piece cut to end at load `s` inside it.
    fn cut_at(&mut self, loads: &Loads<R>, s: &Known<R>) {
        match &mut self.shape {
            Shape::Affine { a, b } => {
                let a = match *b {
                    0 => self.f_lo.clone(),
                    -2 => self.g_lo.clone(),
                    _ => Known::plain(a.clone()),
                };
                let b = *b;
                (self.f_hi, self.g_hi) = Self::affine_ends(&s.value, &a, b);
            }
            Shape::Entry { from, to } => {
                let theta = solve(|t: &R| loads.at(t).p_and_rate(&s.value), from, to);
                self.f_hi = Known::plain(loads.x(&theta));
                self.g_hi = Known::plain(self.f_hi.value.clone() + &(s.value.clone() * &s.value.int(2)));
                *to = theta;
            }
        }
        self.hi = s.clone();
    }
}

/// Where a front lies in the piece it reaches.
#[derive(Clone, Debug)]
pub(crate) enum Position<R> {
    /// At the piece's lower end.
    Low,
    /// At its upper end.
    High,
    /// Inside, at this load.
    Inside(R),
}

/// A slip front: the piece of the memory it lies in, and where.
#[derive(Clone, Debug)]
pub(crate) struct Front<R> {
    pub piece: usize,
    pub position: Position<R>,
}

/// The memory F(s) over [floor, P], pieces in increasing s.
#[derive(Clone, Debug)]
pub(crate) struct Memory<R> {
    pub pieces: Vec<Piece<R>>,
}

impl<R: Real> Memory<R> {
    /// The state at the break where x is largest, from which one period reaches the
    /// steady state: the elements below the lowest slip load s_T = (min y − max x)/2 hold
    /// Φ = c = (max x + min y)/2 (F = c − s) and never slip, F(s_T) = max x and
    /// G(s_T) = min y; every element above s_T has just slipped forward (F = max x).
    pub fn at_largest_x(floor: &R, largest_x: Known<R>, smallest_y: Known<R>, top: Known<R>) -> Self {
        let two = floor.int(2);
        let lowest_slip = Known::plain((smallest_y.value.clone() - &largest_x.value) / &two);
        let center = Known::plain((smallest_y.value.clone() + &largest_x.value) / &two);
        let mut stick = Piece::affine(Known::plain(floor.clone()), lowest_slip.clone(), center, -1);
        stick.f_hi = largest_x.clone();
        stick.g_hi = smallest_y;
        let slipped = Piece::affine(lowest_slip, top, largest_x, 0);
        let mut memory = Memory {
            pieces: vec![stick, slipped],
        };
        memory.join();
        memory
    }

    fn top(&self) -> Known<R> {
        self.pieces
            .last()
            .map(|p| p.hi.clone())
            .unwrap_or_else(|| unreachable!("a memory has pieces"))
    }

    /// The front at inf{s : F(s) ≤ x} (`forward`) or inf{s : F(s) + 2s ≥ y}; `None` when
    /// that set is empty.
    pub fn front(&self, loads: &Loads<R>, value: &Known<R>, forward: bool) -> Option<Front<R>> {
        let reached = |end: &Known<R>| if forward { end.le(value) } else { end.ge(value) };
        let (index, piece) = self
            .pieces
            .iter()
            .enumerate()
            .find(|(_, p)| reached(if forward { &p.f_hi } else { &p.g_hi }))?;
        let (low_end, high_end) = if forward {
            (&piece.f_lo, &piece.f_hi)
        } else {
            (&piece.g_lo, &piece.g_hi)
        };
        let position = if reached(low_end) {
            Position::Low
        } else if value.same(high_end) {
            Position::High
        } else {
            Position::Inside(piece.load_where(loads, &value.value, forward))
        };
        Some(Front { piece: index, position })
    }

    /// The load of a front.
    pub fn load_of(&self, front: &Front<R>) -> Known<R> {
        let piece = &self.pieces[front.piece];
        match &front.position {
            Position::Low => piece.lo.clone(),
            Position::High => piece.hi.clone(),
            Position::Inside(s) => Known::plain(s.clone()),
        }
    }

    /// Forgets every element above load `s`.
    fn truncate(&mut self, loads: &Loads<R>, s: &Known<R>) {
        while self.pieces.len() > 1 && self.pieces.last().is_some_and(|p| p.lo.ge(s)) {
            self.pieces.pop();
        }
        if let Some(last) = self.pieces.last_mut() {
            if last.hi.gt(s) && last.lo.lt(s) {
                last.cut_at(loads, s);
            }
        }
    }

    /// Forgets every element above a front, which then slips from it: its load.
    fn truncate_at(&mut self, loads: &Loads<R>, front: &Front<R>) -> Known<R> {
        let load = self.load_of(front);
        match &front.position {
            Position::Low => self.pieces.truncate(front.piece),
            Position::High => self.pieces.truncate(front.piece + 1),
            Position::Inside(_) => {
                self.pieces.truncate(front.piece + 1);
                if let Some(last) = self.pieces.last_mut() {
                    last.cut_at(loads, &load);
                }
            }
        }
        load
    }

    /// The memory at the end of a monotone interval from the memory at its start: `from`
    /// and `to` the angles of its breaks and their indices (modulo the period).
    pub fn advance(&mut self, loads: &Loads<R>, (a, start): Break<'_, R>, (b, end): Break<'_, R>, signs: Signs) {
        let (at_start, at_end) = (loads.at(a), loads.at(b));
        let end_p = Known::exactly(at_end.p.clone(), Origin::P(end));
        let end_x = Known::exactly(at_end.x(), Origin::X(end));
        let end_y = Known::exactly(at_end.y(), Origin::Y(end));
        let top = self.top();
        if end_p.gt(&top) {
            let piece = if signs.x < 0 && signs.y > 0 {
                let from = (
                    a.clone(),
                    Known::exactly(at_start.x(), Origin::X(start)),
                    Known::exactly(at_start.y(), Origin::Y(start)),
                );
                Piece::entry(top, end_p.clone(), from, (b.clone(), end_x.clone(), end_y.clone()))
            } else if signs.x >= 0 && signs.y > 0 {
                Piece::affine(top, end_p.clone(), end_x.clone(), 0)
            } else {
                Piece::affine(top, end_p.clone(), end_y.clone(), -2)
            };
            self.pieces.push(piece);
        } else if end_p.lt(&top) {
            self.truncate(loads, &end_p);
        }
        if signs.x > 0 {
            if let Some(front) = self.front(loads, &end_x, true) {
                let load = self.truncate_at(loads, &front);
                // F = x at the front, where the piece below was cut.
                if let (Position::Inside(_), Some(below)) = (&front.position, self.pieces.last_mut()) {
                    below.f_hi = end_x.clone();
                }
                self.pieces.push(Piece::affine(load, end_p.clone(), end_x.clone(), 0));
                self.pin_top(&end_x, &end_y);
            }
        }
        if signs.y < 0 {
            if let Some(front) = self.front(loads, &end_y, false) {
                let load = self.truncate_at(loads, &front);
                // G = y at the front, where the piece below was cut.
                if let (Position::Inside(_), Some(below)) = (&front.position, self.pieces.last_mut()) {
                    below.g_hi = end_y.clone();
                }
                self.pieces.push(Piece::affine(load, end_p, end_y.clone(), -2));
                self.pin_top(&end_x, &end_y);
            }
        }
        self.pieces.retain(|p| p.hi.gt(&p.lo));
        if self.pieces.is_empty() {
            unreachable!("the permanent stick piece stays below every front");
        }
        self.pin_top(&end_x, &end_y);
        self.join();
    }

    /// F = x and G = y at the top of the contact once the clamp of the interval is done
    /// (it pinches there), whichever piece holds the top: after a front's slip, and at
    /// the interval's end.
    fn pin_top(&mut self, x: &Known<R>, y: &Known<R>) {
        if let Some(top) = self.pieces.last_mut() {
            top.f_hi = x.clone();
            top.g_hi = y.clone();
        }
    }

    /// One value at each join of two pieces: F and G are continuous, and a piece's upper
    /// end is the next one's lower end; where one of the two enclosures is a break value
    /// (it has an [`Origin`]), both ends take it.
    fn join(&mut self) {
        for i in 1..self.pieces.len() {
            let (below, above) = self.pieces.split_at_mut(i);
            let (below, above) = (&mut below[i - 1], &mut above[0]);
            for (high, low) in [(&mut below.f_hi, &mut above.f_lo), (&mut below.g_hi, &mut above.g_lo)] {
                if low.origin.is_some() || high.origin.is_none() {
                    *high = low.clone();
                } else {
                    *low = high.clone();
                }
            }
        }
    }
}

/// The directions of P, x and y over a monotone interval.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Signs {
    pub p: i8,
    pub x: i8,
    pub y: i8,
}
