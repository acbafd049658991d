//! The event decomposition of the steady cycle.
//!
//! With q = Q/f, x = ξ₋/f = q − P and y = ξ₊/f = q + P, the memory is one function F(s)
//! of the activation load, non-increasing with F' ≥ −2, F(P) = x, and every change is a
//! clamp F ← min(y − 2s, max(x, F)) plus the elements that enter at F = x while P rises.
//! Between consecutive turning points of P, x and y the three are monotone, so the clamp
//! acts from one side only and the slip fronts s₋ = inf{F ≤ x}, s₊ = inf{F + 2s ≥ y} move
//! through the memory left at the interval's start. Their formula changes only where a
//! front crosses the end of one of its pieces (a flat piece crossed at once is a
//! wipe-out), where P crosses one, or where a front meets the top of the contact; the
//! cycle is split there, so that every piece's integrand is smooth, and each segment's
//! fronts take one formula (a piece of the memory, or the top of the contact) throughout.
//! The memory itself, its pieces and its update are `super::memory`.

use crate::compliance::Compliance;
use crate::doubts::{if_decided, undecided};
use crate::real::Real;

use super::input::{padded, LoadPath, Multiples, PathError, TrigPoly};
use super::memory::{Break, Known, Memory, Origin, Piece, Position, Shape, Signs};
use super::top::TopSearch;
use super::Contact;

/// Sample points per harmonic when isolating the roots of a trigonometric polynomial.
const SAMPLES_PER_HARMONIC: usize = 64;

/// The loads and their rates, scaled by f: P and q = Q/f.
#[derive(Clone, Debug)]
pub(crate) struct Loads<R> {
    normal: TrigPoly<R>,
    tangential: TrigPoly<R>,
    normal_rate: TrigPoly<R>,
    tangential_rate: TrigPoly<R>,
    /// x = q − P and y = q + P, whose level sets hold the slip fronts.
    slip_variables: [TrigPoly<R>; 2],
    /// The same loads in f64 where the precision is higher: where Newton's steps on them,
    /// at a few nanoseconds each, end is where a root's steps at the working precision start.
    guide: Option<Box<Loads<f64>>>,
}

/// P, q and their rates at one angle.
#[derive(Clone, Debug)]
pub(crate) struct Point<R> {
    pub theta: R,
    pub p: R,
    pub q: R,
    pub dp: R,
    pub dq: R,
}

impl<R: Real> Point<R> {
    pub fn x(&self) -> R {
        self.q.clone() - &self.p
    }
    pub fn y(&self) -> R {
        self.q.clone() + &self.p
    }
    pub fn dx(&self) -> R {
        self.dq.clone() - &self.dp
    }
    pub fn dy(&self) -> R {
        self.dq.clone() + &self.dp
    }
    /// x = q − P, against which the forward front moves (`forward`), or y = q + P.
    pub fn slip_variable(&self, forward: bool) -> R {
        if forward {
            self.x()
        } else {
            self.y()
        }
    }
    /// x' (`forward`) or y'.
    pub fn slip_rate_of(&self, forward: bool) -> R {
        if forward {
            self.dx()
        } else {
            self.dy()
        }
    }
    /// (x − value, x').
    pub(crate) fn x_and_rate(&self, value: &R) -> (R, R) {
        (self.x() - value, self.dx())
    }
    /// (y − value, y').
    pub(crate) fn y_and_rate(&self, value: &R) -> (R, R) {
        (self.y() - value, self.dy())
    }
    /// (P − value, P').
    pub(crate) fn p_and_rate(&self, value: &R) -> (R, R) {
        (self.p.clone() - value, self.dp.clone())
    }
}

impl<R: Real> Loads<R> {
    fn new(path: &LoadPath<R>, friction: &R) -> Self {
        let path = padded(path);
        let inverse = friction.int(1) / friction;
        let tangential = path.tangential.scaled(&inverse);
        let guide =
            (friction.precision().in_bits() > f64::MANTISSA_DIGITS || friction.real_span().is_some()).then(|| {
                let rough = |poly: &TrigPoly<R>| TrigPoly {
                    cos: poly.cos.iter().map(Real::to_f64_lossy).collect(),
                    sin: poly.sin.iter().map(Real::to_f64_lossy).collect(),
                };
                let rough_path = LoadPath {
                    normal: rough(&path.normal),
                    tangential: rough(&path.tangential),
                };
                Box::new(Loads::new(&rough_path, &friction.to_f64_lossy()))
            });
        Loads {
            normal_rate: path.normal.derivative(),
            tangential_rate: tangential.derivative(),
            slip_variables: [
                tangential.combined(&path.normal, -1),
                tangential.combined(&path.normal, 1),
            ],
            normal: path.normal,
            tangential,
            guide,
        }
    }

    /// Where Newton's steps for `load`(θ) = `value` on [a, b] start: the f64 root of the
    /// guide, where f64 brackets one (the solver keeps it only inside its own bracket). A
    /// bracket that f64's rounding loses is no doubt about the working precision's root.
    pub(crate) fn start_for(&self, load: fn(&Point<f64>, &f64) -> (f64, f64), value: &R, a: &R, b: &R) -> Option<R> {
        let guide = self.guide.as_ref()?;
        let value = value.to_f64_lossy();
        let solved = || {
            solve(
                |t: &f64| load(&guide.at(t), &value),
                &a.to_f64_lossy(),
                &b.to_f64_lossy(),
            )
        };
        let root = if_decided(solved)?;
        root.is_finite().then(|| R::from_f64(root, a.precision()))
    }

    /// The divided difference (x(a) − x(b))/(a − b) (`forward`) or (y(a) − y(b))/(a − b),
    /// and its derivative in a.
    pub(crate) fn slip_variable_difference(&self, a: &R, b: &R, forward: bool) -> (R, R) {
        self.slip_variables[usize::from(!forward)].divided_difference(a, b)
    }

    /// The highest harmonic of the loads.
    #[cfg_attr(not(feature = "certified"), allow(dead_code))]
    pub(crate) fn highest_harmonic(&self) -> usize {
        self.normal.highest().max(self.tangential.highest())
    }

    pub fn at(&self, theta: &R) -> Point<R> {
        let multiples = Multiples::of(theta, self.normal.highest());
        Point {
            theta: theta.clone(),
            p: self.normal.at(&multiples),
            q: self.tangential.at(&multiples),
            dp: self.normal_rate.at(&multiples),
            dq: self.tangential_rate.at(&multiples),
        }
    }

    /// Whether q = Q/f is constant: every harmonic k ≥ 1 zero.
    pub(crate) fn tangential_is_constant(&self) -> bool {
        self.tangential.is_constant()
    }

    pub(crate) fn p(&self, theta: &R) -> R {
        self.normal.value(theta)
    }
    pub(crate) fn x(&self, theta: &R) -> R {
        self.at(theta).x()
    }
}

/// The sign of a value: −1, 0 or 1 (an enclosure that holds zero and other numbers is
/// counted as undecided, and taken as 0).
fn sign<R: Real>(value: &R) -> i8 {
    let zero = value.int(0);
    if *value > zero {
        1
    } else if *value < zero {
        -1
    } else {
        0
    }
}

/// The sign of a value where it is decided, `None` for an enclosure that holds zero and
/// other numbers (not counted as a doubt: the caller stops or subdivides there).
pub(crate) fn decided_sign<R: Real>(value: &R) -> Option<i8> {
    if_decided(|| sign(value))
}

/// Whether `a > b` for every number the enclosures hold (for numbers, whether a > b); an
/// undecided comparison answers `false` and is not counted as a doubt.
fn surely_greater<R: Real>(a: &R, b: &R) -> bool {
    if_decided(|| *a > *b).unwrap_or(false)
}

/// Whether `x` lies strictly between `a` and `b` (either order), decided.
fn surely_between<R: Real>(x: &R, a: &R, b: &R) -> bool {
    (surely_greater(x, a) && surely_greater(b, x)) || (surely_greater(x, b) && surely_greater(a, x))
}

/// The point of [a, b] (a < b) where `f` changes sign (f(a) and f(b) of opposite signs
/// or zero; f monotone there), `f` giving its value and derivative: Newton kept inside a
/// shrinking bracket, bisecting where a step would leave it, to the working precision.
///
/// On enclosures the root is proven: the ends' signs must be decided (an undecided one
/// is counted as a doubt), the bracket shrinks only to points whose sign is decided, and
/// the answer is the hull of the last bracket, which holds the root.
pub(crate) fn solve<R: Real>(f: impl Fn(&R) -> (R, R), a: &R, b: &R) -> R {
    solve_between(&f, (a, f(a).0), (b, f(b).0), None)
}

/// [`solve`] with f's values at the ends known already (an entry piece's memory values),
/// and Newton's steps started at `start` where it lies inside the bracket.
pub(crate) fn solve_between<R: Real>(
    f: impl Fn(&R) -> (R, R),
    (a, at_low): (&R, R),
    (b, at_high): (&R, R),
    start: Option<R>,
) -> R {
    let (mut low, mut high) = (a.clone(), b.clone());
    let low_sign = sign(&at_low);
    if low_sign == 0 {
        return low;
    }
    let high_sign = sign(&at_high);
    if high_sign == 0 {
        return high;
    }
    if high_sign == low_sign {
        // No bracket: whatever is returned is not a proven root.
        undecided();
    }
    let two = a.int(2);
    let tolerance = a.abs().max_of(&b.abs()).max_of(&a.int(1)) * &a.epsilon_like() * &a.int(4);
    let middle = (low.clone() + &high) / &two;
    // A number starts Newton from the chord's root, nearer than the middle for the smooth
    // monotone functions solved here; an enclosure from the middle, as proven roots always did.
    let inside = |x: &R| x.is_finite() && surely_between(x, &low, &high);
    let start = match (start.filter(inside), middle.real_span()) {
        (Some(start), _) => start,
        (None, None) => Some(low.clone() - &(at_low.clone() * &(high.clone() - &low) / &(at_high - &at_low)))
            .filter(inside)
            .unwrap_or(middle),
        (None, Some(_)) => middle,
    };
    let mut x = start.midpoint_value();
    let mut candidate = None;
    for _ in 0..a.precision().in_bits() + 8 {
        let (value, slope) = f(&x);
        // A value whose sign the precision cannot decide: the bracket is as narrow as it gets.
        let Some(s) = decided_sign(&value) else {
            candidate = Some(x.clone());
            break;
        };
        if s == 0 {
            return x;
        }
        if s == low_sign {
            low = x.clone();
        } else {
            high = x.clone();
        }
        if !surely_greater(&(high.clone() - &low).abs(), &tolerance) {
            break;
        }
        let newton = x.clone() - &(value / &slope);
        let next = if newton.is_finite() && surely_between(&newton, &low, &high) {
            newton
        } else {
            (low.clone() + &high) / &two
        };
        if !surely_greater(&(next.clone() - &x).abs(), &tolerance) {
            candidate = Some(next);
            break;
        }
        // Iterates are points (an enclosure's midpoint): a step from an enclosure would
        // add its width to the next one's, doubling it every step.
        x = next.midpoint_value();
    }
    let candidate = candidate.unwrap_or_else(|| (low.clone() + &high) / &two);
    if candidate.real_span().is_none() {
        // A number stands for itself.
        return candidate;
    }
    let (low, high) = tightened(&f, &candidate, (low, high), low_sign, &tolerance);
    low.union(&high)
}

/// The root θ near the point `root` of g(θ) = 0, for every g of a family at once (g
/// depends on a value that is real, or a complex box of a quadrature's ellipse), by
/// Krawczyk's test: with Y = 1/g'(root) and a box Θ around the root,
/// K = root − Y g(root) + (1 − Y g'(Θ))(Θ − root) inside Θ's interior proves that Θ holds
/// one root for each g, and K holds them (proofs/periodic-loading.md, "The entry front on
/// complex boxes"). `at_root` encloses g(root) over the family and `slope` is g'(root) at
/// a point; `rate` encloses g' over a box for the whole family. A box that no widening
/// proves is a doubt.
pub(crate) fn krawczyk_root<R: Real>(rate: impl Fn(&R) -> R, at_root: &R, slope: &R, root: &R) -> R {
    let inverse = (slope.int(1) / slope).midpoint_value();
    let step = -(at_root.clone() * &inverse);
    // A box symmetric about the root, twice Newton's step and a few ulps of the root wide.
    let slack = (root.abs() + &root.int(1)) * &root.epsilon_like() * &root.int(64);
    let mut radius = (step.clone() * &root.int(2))
        .centred_square()
        .union(&slack.centred_square());
    for _ in 0..KRAWCZYK_WIDENINGS {
        let theta = root.clone() + &radius;
        let offset = theta.clone() - root;
        let contraction = root.int(1) - &(inverse.clone() * &rate(&theta));
        let enclosure = root.clone() + &step + &(contraction * &offset);
        if enclosure.lies_inside(&theta) {
            return enclosure;
        }
        radius *= &root.int(4);
    }
    undecided();
    root.clone() + &radius
}

/// The angle t ≠ θ (modulo the period) where the slip variable (x `forward`, else y)
/// takes its value at θ, near the point `root`, for every θ in `other` at once (real, or
/// a complex box of a quadrature's ellipse): Krawczyk's test on the divided difference
/// D(t, θ) = (v(t) − v(θ))/(t − θ), θ moved by whole periods to `root`'s, whose root stays
/// simple where t and θ meet at a turning point of v. D(root, θ) is taken in the
/// mean-value form about θ's midpoint m, D(root, m) + ∂D/∂θ(root, θ)·(θ − m), which a
/// box of θ widens far less than D itself (∂D/∂θ(a, b) is ∂D/∂a(b, a): D is symmetric).
pub(crate) fn same_level_angle<R: Real>(loads: &Loads<R>, other: &R, root: &R, forward: bool) -> R {
    let moved = moved_next_to(other, root);
    let middle = moved.midpoint_value();
    // Newton's steps on points from a root good to f64 to about the working precision:
    // Krawczyk's step then doubles its digits once more.
    let mut root = root.midpoint_value();
    let mut digits = f64::MANTISSA_DIGITS;
    while digits < root.precision().in_bits() / 2 {
        let (value, slope) = loads.slip_variable_difference(&root, &middle, forward);
        let next = (root.clone() - &(value / &slope)).midpoint_value();
        if !next.is_finite() {
            break;
        }
        root = next;
        digits *= 2;
    }
    let root = &root;
    let (at_middle, slope) = loads.slip_variable_difference(root, &middle, forward);
    let (_, along_other) = loads.slip_variable_difference(&moved, root, forward);
    let at_root = at_middle + &(along_other * &(moved.clone() - &middle));
    krawczyk_root(
        |t: &R| loads.slip_variable_difference(t, &moved, forward).1,
        &at_root,
        &slope,
        root,
    )
}

/// `angle` moved by the whole periods that bring it nearest `toward` (counted on doubles:
/// any whole number of periods leaves the loads as they are).
fn moved_next_to<R: Real>(angle: &R, toward: &R) -> R {
    let period = angle.pi_like() * &angle.int(2);
    let periods = ((toward.to_f64_lossy() - angle.midpoint_value().to_f64_lossy()) / period.to_f64_lossy()).round();
    angle.clone() + &(period * &angle.int(periods as i64))
}

/// Fourfold widenings of Krawczyk's box before its root is counted undecided.
const KRAWCZYK_WIDENINGS: usize = 3;

/// A bracket (low < high, f of sign `low_sign` at low and of the other at high) shrunk to
/// points just either side of `x` where f's sign is decided and right: Newton approaches
/// a root from one side, and the other end would otherwise stay where it was.
fn tightened<R: Real>(
    f: &impl Fn(&R) -> (R, R),
    x: &R,
    (mut low, mut high): (R, R),
    low_sign: i8,
    tolerance: &R,
) -> (R, R) {
    let mut step = tolerance.clone();
    let (mut low_done, mut high_done) = (false, false);
    for _ in 0..TIGHTENING_STEPS {
        if !low_done {
            let left = x.clone() - &step;
            if surely_greater(&left, &low) && decided_sign(&f(&left).0) == Some(low_sign) {
                low = left;
                low_done = true;
            }
        }
        if !high_done {
            let right = x.clone() + &step;
            if surely_greater(&high, &right) && decided_sign(&f(&right).0) == Some(-low_sign) {
                high = right;
                high_done = true;
            }
        }
        if low_done && high_done {
            break;
        }
        step *= &x.int(16);
    }
    (low, high)
}

/// Sixteen-fold widenings of the step either side of a root before the bracket is kept.
const TIGHTENING_STEPS: usize = 16;

/// The point of [a, b] where the predicate turns (false at a, true at b), by bisection;
/// on enclosures the hull of the last bracket, whose ends' predicates were decided.
fn bisect_predicate<R: Real>(turned: impl Fn(&R) -> bool, a: &R, b: &R) -> R {
    let (mut low, mut high) = (a.clone(), b.clone());
    let two = a.int(2);
    for _ in 0..a.precision().in_bits() + 8 {
        let middle = (low.clone() + &high) / &two;
        if !surely_between(&middle, &low, &high) {
            break;
        }
        match if_decided(|| turned(&middle)) {
            Some(true) => high = middle,
            Some(false) => low = middle,
            None => break,
        }
    }
    ((low.clone() + &high) / &two).union(&low).union(&high)
}

/// Where the samples of a trigonometric polynomial lie: step·j plus this offset (in
/// radians, not a rational multiple of π), so that the roots of ordinary paths, at 0, π/2
/// or π, fall between samples, where enclosures decide the samples' signs.
fn sample_offset<R: Real>(like: &R) -> R {
    like.ratio(1, 8)
}

/// The angles in [0, 2π) where a trigonometric polynomial changes sign, increasing (on
/// enclosures, one that holds 2π may stay there): sampled, then every sample interval searched by [`Isolation`], which
/// proves the intervals it drops root-free and refines each sign change where the
/// polynomial is proven monotone. On enclosures each root is an enclosure, and every
/// question left undecided is counted as a doubt.
pub(crate) fn sign_changes<R: Real>(poly: &TrigPoly<R>) -> Vec<R> {
    // A coefficient whose enclosure holds 0 and others leaves the polynomial to the search,
    // which proves where it has no root.
    if if_decided(|| poly.is_constant()).unwrap_or(false) {
        return Vec::new();
    }
    let like = &poly.cos[0];
    let count = SAMPLES_PER_HARMONIC * poly.highest().max(1);
    let step = like.pi_like() * &like.int(2) / &like.int(count as i64);
    let offset = sample_offset(like);
    let angle = |j: usize| step.clone() * &like.int(j as i64) + &offset;
    let values: Vec<R> = (0..count).map(|j| poly.value(&angle(j))).collect();
    let isolation = Isolation::new(poly);
    let mut roots = Vec::new();
    for j in 0..count {
        let (before, here, after) = (
            sign(&values[(j + count - 1) % count]),
            sign(&values[j]),
            sign(&values[(j + 1) % count]),
        );
        if here == 0 && before * after < 0 {
            roots.push(angle(j));
        }
        isolation.search(
            (&angle(j), &values[j]),
            (&angle(j + 1), &values[(j + 1) % count]),
            0,
            &mut roots,
        );
    }
    // Into [0, 2π) where that is decided (a root at 2π itself, as a sine's, is kept there
    // on enclosures): in increasing order from 0.
    let period = like.pi_like() * &like.int(2);
    let (past_period, within): (Vec<R>, Vec<R>) = roots
        .into_iter()
        .partition(|root| if_decided(|| *root >= period).unwrap_or(false));
    past_period
        .into_iter()
        .map(|root| root - &period)
        .chain(within)
        .collect()
}

/// Bounds that make root isolation safe: |f'| ≤ Σ k|aₖ| and |f''| ≤ Σ k²|aₖ|, |aₖ| the
/// amplitude of harmonic k.
struct Isolation<'a, R> {
    poly: &'a TrigPoly<R>,
    rate: TrigPoly<R>,
    rate_bound: R,
    curvature_bound: R,
}

/// Halvings of a sample interval before a sign change is taken as one root.
const MAX_HALVINGS: u32 = 16;

impl<'a, R: Real> Isolation<'a, R> {
    fn new(poly: &'a TrigPoly<R>) -> Self {
        let like = &poly.cos[0];
        let (mut rate_bound, mut curvature_bound) = (like.int(0), like.int(0));
        for k in 1..=poly.highest() {
            let amplitude = poly.cos[k].hypot(&poly.sin[k]);
            let kk = like.int(k as i64);
            rate_bound += amplitude.clone() * &kk;
            curvature_bound += amplitude * &kk * &kk;
        }
        // A margin for the rounding of the values compared with the bounds.
        let margin = like.int(1) + &(like.epsilon_like() * &like.int(1 << 20));
        Isolation {
            poly,
            rate: poly.derivative(),
            rate_bound: rate_bound * &margin,
            curvature_bound: curvature_bound * &margin,
        }
    }

    /// The root in (a, b) where f changes sign between them and is monotone.
    fn root(&self, (a, fa): (&R, &R), (b, fb): (&R, &R), roots: &mut Vec<R>) {
        if sign(fa) * sign(fb) < 0 {
            roots.push(solve(|t: &R| (self.poly.value(t), self.rate.value(t)), a, b));
        }
    }

    /// Pushes the sign changes strictly inside (a, b), in increasing order.
    fn search(&self, (a, fa): (&R, &R), (b, fb): (&R, &R), depth: u32, roots: &mut Vec<R>) {
        let width = b.clone() - a;
        // f cannot reach 0 from both ends within the interval.
        if surely_greater(&(fa.abs() + &fb.abs()), &(self.rate_bound.clone() * &width)) {
            return;
        }
        let two = a.int(2);
        let middle = (a.clone() + b) / &two;
        let curvature_reach = self.curvature_bound.clone() * &width / &two;
        if surely_greater(&self.rate.value(&middle).abs(), &curvature_reach) {
            // f' keeps its sign over [a, b]: at most one root, where the signs differ.
            self.root((a, fa), (b, fb), roots);
            return;
        }
        if depth >= MAX_HALVINGS {
            // Neither root-free nor monotone at the finest halving (a multiple root, or
            // one the rounding hides): a sign change is taken as one root, unproven.
            undecided();
            self.root((a, fa), (b, fb), roots);
            return;
        }
        let fm = self.poly.value(&middle);
        self.search((a, fa), (&middle, &fm), depth + 1, roots);
        if decided_sign(&fm) == Some(0) && sign(fa) * sign(fb) < 0 {
            roots.push(middle.clone());
        }
        self.search((&middle, &fm), (b, fb), depth + 1, roots);
    }
}

/// The extreme of a trigonometric polynomial over the period, and where: the largest
/// (`largest`) or smallest value at its turning points (at 0 for a constant). Where two
/// turning values are too close for the enclosures to order, the extreme is enclosed by
/// both (their hull), and the angle is the first of them: a place to name, where the
/// hull of two angles (of 0 and 2π, the same point) would name neither.
pub(crate) fn extreme<R: Real>(poly: &TrigPoly<R>, largest: bool) -> (R, R) {
    let zero = poly.cos[0].int(0);
    let mut candidates = sign_changes(&poly.derivative());
    candidates.push(zero);
    let mut best: Option<(R, R)> = None;
    for theta in candidates {
        let value = poly.value(&theta);
        best = Some(match best {
            None => (theta, value),
            Some((at, b)) => match if_decided(|| if largest { value > b } else { value < b }) {
                Some(true) => (theta, value),
                Some(false) => (at, b),
                None => (at, b.union(&value)),
            },
        });
    }
    best.unwrap_or_else(|| (poly.cos[0].int(0), poly.cos[0].clone()))
}

/// A load or margin for a refusal's message: the digits its enclosure proves
/// ([`Real::to_f64_quoted`]); where it proves none, an undecided comparison, so that a
/// finer precision quotes it.
pub(crate) fn quoted<R: Real>(value: &R) -> f64 {
    value.to_f64_quoted().unwrap_or_else(|| {
        undecided();
        value.to_f64_lossy()
    })
}

/// Checks that the path stays in contact (P > 0) and free of gross slip (|Q| < fP, decided on
/// q ∓ P with q = Q/f and quoted as ±Q − fP), naming the angle where it fails; returns the
/// lowest slipping load s_T = [min(q + P) − max(q − P)]/2.
fn validate<R: Real>(loads: &Loads<R>, friction: &R) -> Result<R, PathError> {
    let zero = loads.normal.cos[0].int(0);
    let (theta, lowest) = extreme(&loads.normal, false);
    if lowest <= zero {
        return Err(PathError::Separation {
            theta: theta.to_f64_lossy(),
            load: quoted(&lowest),
        });
    }
    let x = loads.tangential.combined(&loads.normal, -1);
    let y = loads.tangential.combined(&loads.normal, 1);
    let (theta_x, largest_x) = extreme(&x, true);
    let (theta_y, smallest_y) = extreme(&y, false);
    for (theta, excess, sign) in [(theta_x, largest_x.clone(), "+"), (theta_y, -smallest_y.clone(), "−")] {
        if excess >= zero {
            return Err(PathError::GrossSlip {
                theta: theta.to_f64_lossy(),
                sign,
                excess: quoted(&(excess * friction)),
            });
        }
    }
    Ok((smallest_y - &largest_x) / &zero.int(2))
}

/// The index of the largest (or smallest) of the values at the breaks: the first of
/// equal numbers; on enclosures an undecided comparison is counted as a doubt.
fn extreme_break<R: Real>(values: &[R], largest: bool) -> usize {
    let mut best = 0;
    for (index, value) in values.iter().enumerate().skip(1) {
        let better = if largest {
            *value > values[best]
        } else {
            *value < values[best]
        };
        if better {
            best = index;
        }
    }
    best
}

/// Checks that the path stays in contact and free of gross slip, as [`SteadyCycle::new`]
/// does before it builds the cycle: by the crude bounds of [`clearly_inside`] where they
/// decide it, else at the turning points.
pub(crate) fn check_path<R: Real>(path: &LoadPath<R>, contact: &Contact<R>) -> Result<(), PathError> {
    contact.validate()?;
    let loads = Loads::new(path, &contact.friction);
    if clearly_inside(&loads) {
        return Ok(());
    }
    validate(&loads, &contact.friction).map(|_| ())
}

/// Checks that the contact is valid and the path stays in contact (P > 0), as the
/// displacement-driven simulation needs (gross slip is allowed there): by the bound of
/// [`clearly_inside`] on P where it decides it, else at P's lowest turning point.
pub(crate) fn check_contact_and_separation<R: Real>(path: &LoadPath<R>, contact: &Contact<R>) -> Result<(), PathError> {
    contact.validate()?;
    let normal = &path.normal;
    let zero = normal.cos[0].int(0);
    if if_decided(|| normal.cos[0].clone() - &spread(normal) > zero) == Some(true) {
        return Ok(());
    }
    let (theta, lowest) = extreme(normal, false);
    if lowest <= zero {
        return Err(PathError::Separation {
            theta: theta.to_f64_lossy(),
            load: quoted(&lowest),
        });
    }
    Ok(())
}

/// Σₖ (|aₖ| + |bₖ|) over k ≥ 1: a bound of how far the polynomial strays from c₀.
fn spread<R: Real>(poly: &TrigPoly<R>) -> R {
    let zero = poly.cos[0].int(0);
    poly.cos[1..]
        .iter()
        .chain(&poly.sin[1..])
        .fold(zero, |sum, c| sum + &c.abs())
}

/// Whether the path keeps clear of separation and gross slip by the bound of each
/// polynomial's range c₀ ± Σₖ (|aₖ| + |bₖ|), decided without its turning points: a
/// multiple root of a derivative, which no precision isolates, does not matter there.
/// `false` where the bounds do not decide it.
fn clearly_inside<R: Real>(loads: &Loads<R>) -> bool {
    if_decided(|| {
        let zero = loads.normal.cos[0].int(0);
        let x = loads.tangential.combined(&loads.normal, -1);
        let y = loads.tangential.combined(&loads.normal, 1);
        loads.normal.cos[0].clone() - &spread(&loads.normal) > zero
            && x.cos[0].clone() + &spread(&x) < zero
            && y.cos[0].clone() - &spread(&y) > zero
    }) == Some(true)
}

/// How the slip terms form the slope changes v'(s) − v'(P): by the compliance's own form,
/// free of cancellation at real points, or as the plain difference of two slopes, the
/// same analytic function, whose enclosure on a complex box a compliance's own form (a
/// root raised to powers and divided, for Hertz) can widen far more.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SlopeChanges {
    /// [`Compliance::slope_change`].
    Own,
    /// v'(s) − v'(P).
    Plain,
}

/// A piece of the steady cycle on which the slip fronts are smooth functions of θ.
#[derive(Clone, Debug)]
pub struct Segment<R> {
    /// The first angle.
    pub start: R,
    /// The last angle.
    pub end: R,
    /// Where the forward front s₋ lies over the segment.
    forward: FrontFormula<R>,
    /// Where the backward front s₊ lies.
    backward: FrontFormula<R>,
}

/// Where a slip front lies over a segment, as a function of the angle: chosen once, at
/// the segment's middle, since the segment ends wherever it would change.
#[derive(Clone, Debug)]
enum FrontFormula<R> {
    /// Its slip is not under way, or the front is at the top of the contact: s = P, and
    /// this slip adds nothing to the displacement.
    AtTop,
    /// At a fixed load: the end of a piece that the front has not left.
    AtLoad(R),
    /// Inside this piece of the memory at the interval's start.
    InPiece(Piece<R>),
}

/// The steady cycle of a path: its smooth segments, each with the formulas of its slip
/// fronts.
#[derive(Clone, Debug)]
pub struct SteadyCycle<R> {
    pub(crate) loads: Loads<R>,
    /// The segments, covering [start, start + 2π] in order.
    pub segments: Vec<Segment<R>>,
    /// The angle where the cycle is taken to start (a turning point).
    pub start: R,
    /// The lowest slipping load s_T: elements below it stick throughout.
    pub lowest_slip: R,
    /// The highest normal load of the path.
    pub highest_load: R,
    /// The windows where P falls through a piece of elements that entered in stick with a
    /// front under way, searched for where the front meets the top of the contact: the
    /// cuts that are found by sampling, and proven afterwards ([`SteadyCycle::sampled_cut_error`]).
    #[cfg_attr(not(feature = "certified"), allow(dead_code))]
    pub(crate) top_searches: Vec<TopSearch<R>>,
}

/// The slip fronts at one angle: (s₋, s₊), each at the top of the contact when its slip
/// is not under way.
pub(crate) struct Fronts<R> {
    pub forward: R,
    pub backward: R,
}

impl<R: Real> SteadyCycle<R> {
    /// The steady cycle of `path` on a contact: validates the path, runs one cycle from a
    /// state whose permanent stick zone is right (after it every element that slips has
    /// forgotten the start), and splits the next cycle into smooth segments.
    pub fn new(path: &LoadPath<R>, contact: &Contact<R>) -> Result<Self, PathError> {
        contact.validate()?;
        let loads = Loads::new(path, &contact.friction);
        let lowest_slip = validate(&loads, &contact.friction)?;
        let highest_load = extreme(&loads.normal, true).1;
        let like = lowest_slip.clone();
        let tau = like.pi_like() * &like.int(2);
        // At constant P, x' = y' = q': their turning points are found once.
        let rates = if if_decided(|| loads.normal_rate.is_constant()).unwrap_or(false) {
            vec![loads.tangential_rate.clone()]
        } else {
            vec![
                loads.normal_rate.clone(),
                loads.tangential_rate.combined(&loads.normal_rate, -1),
                loads.tangential_rate.combined(&loads.normal_rate, 1),
            ]
        };
        let mut breaks: Vec<R> = rates.iter().flat_map(sign_changes).collect();
        breaks.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        breaks.dedup();
        if breaks.is_empty() {
            // Neither P nor Q varies: nothing moves.
            breaks.push(like.int(0));
        }
        let count = breaks.len();
        let start = breaks[0].clone();
        let mut bounds = breaks.clone();
        bounds.push(start.clone() + &tau);
        // Each monotone interval with the indices of its breaks, modulo the period.
        let intervals: Vec<(Break<'_, R>, Break<'_, R>, Signs)> = bounds
            .windows(2)
            .enumerate()
            .map(|(i, w)| {
                let middle = loads.at(&((w[0].clone() + &w[1]) / &like.int(2)));
                let signs = Signs {
                    p: sign(&middle.dp),
                    x: sign(&middle.dx()),
                    y: sign(&middle.dy()),
                };
                ((&w[0], i), (&w[1], (i + 1) % count), signs)
            })
            .collect();
        // From the break where x is largest, one period reaches the steady state; the
        // intervals up to the period's end then bring it to the cycle's start.
        let floor = lowest_slip.clone() / &like.int(2);
        let values = |value: &dyn Fn(&Point<R>) -> R| breaks.iter().map(|b| value(&loads.at(b))).collect::<Vec<R>>();
        let largest_x = extreme_break(&values(&Point::x), true);
        let smallest_y = extreme_break(&values(&Point::y), false);
        let at_largest_x = loads.at(&breaks[largest_x]);
        let mut memory = Memory::at_largest_x(
            &floor,
            Known::exactly(at_largest_x.x(), Origin::X(largest_x)),
            Known::exactly(loads.at(&breaks[smallest_y]).y(), Origin::Y(smallest_y)),
            Known::exactly(at_largest_x.p.clone(), Origin::P(largest_x)),
        );
        for (a, b, signs) in intervals[largest_x..].iter().chain(&intervals) {
            memory.advance(&loads, *a, *b, *signs);
        }
        // Where x' or y' is smallest between sign changes, a front in an entry piece moves
        // fastest: its formula is split there too.
        let inflections = Inflections {
            forward: sign_changes(&loads.tangential_rate.combined(&loads.normal_rate, -1).derivative()),
            backward: sign_changes(&loads.tangential_rate.combined(&loads.normal_rate, 1).derivative()),
            period: tau.clone(),
        };
        let mut segments = Vec::new();
        let mut top_searches = Vec::new();
        for (a, b, signs) in &intervals {
            let (pieces, searches) = split(&loads, &memory, &inflections, *a, *b, *signs);
            top_searches.extend(searches);
            for (start, end) in pieces {
                let middle = ((start.clone() + &end) / &like.int(2)).midpoint_value();
                let point = loads.at(&middle);
                segments.push(Segment {
                    forward: front_formula(&loads, &memory, signs.x > 0, &point, true),
                    backward: front_formula(&loads, &memory, signs.y < 0, &point, false),
                    start,
                    end,
                });
            }
            memory.advance(&loads, *a, *b, *signs);
        }
        Ok(SteadyCycle {
            loads,
            segments,
            start,
            lowest_slip,
            highest_load,
            top_searches,
        })
    }

    /// The slip fronts at θ in `segment`.
    pub(crate) fn fronts(&self, segment: &Segment<R>, point: &Point<R>) -> Fronts<R> {
        Fronts {
            forward: self.front_load(&segment.forward, point, true),
            backward: self.front_load(&segment.backward, point, false),
        }
    }

    /// The load of a front by its formula at `point`.
    fn front_load(&self, formula: &FrontFormula<R>, point: &Point<R>, forward: bool) -> R {
        match formula {
            FrontFormula::AtTop => point.p.clone(),
            FrontFormula::AtLoad(s) => s.clone(),
            FrontFormula::InPiece(piece) => {
                let value = point.slip_variable(forward);
                piece.front_at(&self.loads, &point.theta, &value, forward)
            }
        }
    }

    /// dU/dθ at θ in `segment`, U = u/(λf): v'(P) q' + (v'(s₋) − v'(P)) x' + (v'(s₊) − v'(P)) y'.
    pub fn displacement_rate(&self, segment: &Segment<R>, theta: &R, compliance: &dyn Compliance<R>) -> R {
        let point = self.loads.at(theta);
        let slip = self.slip_rate(segment, &point, compliance);
        compliance.slope(&point.p) * &point.dq + &slip
    }

    /// The part of dU/dθ that slip adds, (v'(s₋) − v'(P)) x' + (v'(s₊) − v'(P)) y'.
    pub(crate) fn slip_rate(&self, segment: &Segment<R>, point: &Point<R>, compliance: &dyn Compliance<R>) -> R {
        self.slip_rate_with(segment, point, compliance, None, SlopeChanges::Own)
    }

    /// [`SteadyCycle::slip_rate`] with one front's load `known` (forward or not, and the
    /// load) rather than found from the memory, the slope changes formed as `changes` says.
    pub(crate) fn slip_rate_with(
        &self,
        segment: &Segment<R>,
        point: &Point<R>,
        compliance: &dyn Compliance<R>,
        known: Option<(bool, &R)>,
        changes: SlopeChanges,
    ) -> R {
        let mut rate = point.p.int(0);
        for (formula, forward) in [(&segment.forward, true), (&segment.backward, false)] {
            if let FrontFormula::AtTop = formula {
                continue;
            }
            let front = match known {
                Some((which, load)) if which == forward => load.clone(),
                _ => self.front_load(formula, point, forward),
            };
            let difference = || compliance.slope(&front) - &compliance.slope(&point.p);
            // The compliance's own form asks where the gap lies (a series near 0): on an
            // enclosure that straddles 0 (a front at the top) the plain difference, an
            // enclosure of the same value, serves.
            let change = if changes == SlopeChanges::Plain {
                difference()
            } else {
                if_decided(|| compliance.slope_change(&point.p, &(front.clone() - &point.p))).unwrap_or_else(difference)
            };
            rate += &(change * &point.slip_rate_of(forward));
        }
        rate
    }

    /// The front of `segment` inside a piece of elements that entered in stick that, at
    /// the point `middle` of it, moves faster than θ (|v'(θ)| > |v'(θₑ)|), if one does:
    /// forward or not. Near it the segment is integrated in the entry angle θₑ, in which
    /// the fold where v'(θₑ) vanishes is no singularity. Asked on enclosures; the choice
    /// does not bear on rigour.
    #[cfg_attr(not(feature = "certified"), allow(dead_code))]
    pub(crate) fn racing_entry_front(&self, segment: &Segment<R>, middle: &R) -> Option<bool> {
        let middle = middle.midpoint_value();
        let now = self.loads.at(&middle);
        for (formula, forward) in [(&segment.forward, true), (&segment.backward, false)] {
            let FrontFormula::InPiece(piece) = formula else {
                continue;
            };
            if !matches!(piece.shape, Shape::Entry { .. }) {
                continue;
            }
            let value = now.slip_variable(forward);
            let Some(entered) = if_decided(|| piece.entry_angle_at(&self.loads, &middle, &value, forward)) else {
                continue;
            };
            let then = self.loads.at(&entered);
            let rate = |point: &Point<R>| point.slip_rate_of(forward).abs().to_f64_lossy();
            if rate(&now) > rate(&then) {
                return Some(forward);
            }
        }
        None
    }

    /// The entry angle θₑ of the front (`forward` or not) of `segment` at `theta` (a
    /// segment's end), where its formula puts it inside an entry piece
    /// ([`Piece::entry_angle_at`]), or the piece's end angle where the front reaches it
    /// there ([`Piece::end_angle_at`]); undecided otherwise.
    #[cfg_attr(not(feature = "certified"), allow(dead_code))]
    pub(crate) fn entry_angle(&self, segment: &Segment<R>, theta: &R, forward: bool) -> R {
        let formula = if forward { &segment.forward } else { &segment.backward };
        match formula {
            FrontFormula::InPiece(piece) => {
                let value = self.loads.at(theta).slip_variable(forward);
                if_decided(|| piece.entry_angle_at(&self.loads, theta, &value, forward))
                    .or_else(|| piece.end_angle_at(&value, forward))
                    .unwrap_or_else(|| {
                        undecided();
                        theta.clone()
                    })
            }
            _ => theta.clone(),
        }
    }

    /// The angle θ of `segment` at which the front (`forward` or not) reaches the
    /// element that entered at `entered`: v(θ) = v(θₑ), for every θₑ in `entered` at once
    /// ([`same_level_angle`]), from the root at the middle bracketed by the segment's ends
    /// (the nearer end where the signs there are not decided).
    pub(crate) fn current_angle(&self, segment: &Segment<R>, entered: &R, forward: bool) -> R {
        let level = self.loads.at(&entered.midpoint_value()).slip_variable(forward);
        let (start, end) = (segment.start.midpoint_value(), segment.end.midpoint_value());
        let offset = |t: &R| {
            let point = self.loads.at(t);
            (point.slip_variable(forward) - &level, point.slip_rate_of(forward))
        };
        let guided = self.loads.start_for(
            if forward { Point::x_and_rate } else { Point::y_and_rate },
            &level,
            &start,
            &end,
        );
        let root = guided
            .or_else(|| if_decided(|| solve(offset, &start, &end)))
            .unwrap_or_else(|| {
                let off = |t: &R| offset(t).0.abs().to_f64_lossy();
                if off(&start) <= off(&end) {
                    start.clone()
                } else {
                    end.clone()
                }
            })
            .midpoint_value();
        same_level_angle(&self.loads, entered, &root, forward)
    }

    /// dθ/dθₑ at [`SteadyCycle::current_angle`] `theta`: with D(a, b) the divided
    /// difference of the slip variable, D(θ, θₑ) = 0 gives −∂D/∂b / ∂D/∂a, which stays
    /// finite where both v'(θ) and v'(θₑ) vanish (θ and θₑ meeting at a turning point),
    /// unlike v'(θₑ)/v'(θ).
    pub(crate) fn current_angle_rate(&self, theta: &R, entered: &R, forward: bool) -> R {
        let moved = moved_next_to(entered, theta);
        let (_, along_entry) = self.loads.slip_variable_difference(&moved, theta, forward);
        let (_, along_current) = self.loads.slip_variable_difference(theta, &moved, forward);
        -(along_entry / &along_current)
    }

    /// The mean of q = Q/f over the cycle.
    pub(crate) fn mean_tangential(&self) -> R {
        self.loads.tangential.cos[0].clone()
    }

    /// P, q = Q/f and their rates at θ.
    pub(crate) fn point(&self, theta: &R) -> Point<R> {
        self.loads.at(theta)
    }
}

/// The formula of a front over a segment, read at the segment's middle `point` from the
/// memory at its interval's start: `active` where its slip is under way there.
fn front_formula<R: Real>(
    loads: &Loads<R>,
    memory: &Memory<R>,
    active: bool,
    point: &Point<R>,
    forward: bool,
) -> FrontFormula<R> {
    if !active {
        return FrontFormula::AtTop;
    }
    let value = Known::plain(point.slip_variable(forward));
    let Some(front) = memory.front(loads, &value, forward) else {
        return FrontFormula::AtTop;
    };
    if memory.load_of(&front).value >= point.p {
        return FrontFormula::AtTop;
    }
    let piece = &memory.pieces[front.piece];
    match front.position {
        Position::Low => FrontFormula::AtLoad(piece.lo.value.clone()),
        Position::High => FrontFormula::AtLoad(piece.hi.value.clone()),
        Position::Inside(_) => FrontFormula::InPiece(piece.clone()),
    }
}

/// A load less a value, with its rate: what [`solve`] takes to find where the load has the value.
type Offset<R> = dyn Fn(&Point<R>, &R) -> (R, R);

/// The angles in [0, 2π) where x'' (`forward`) and y'' (`backward`) change sign.
struct Inflections<R> {
    forward: Vec<R>,
    backward: Vec<R>,
    period: R,
}

impl<R: Real> Inflections<R> {
    /// Those inside an entry piece of the memory (in either of the two periods its angles span).
    fn inside_entries(&self, memory: &Memory<R>, forward: bool) -> Vec<R> {
        let angles = if forward { &self.forward } else { &self.backward };
        let mut inside = Vec::new();
        for piece in &memory.pieces {
            if let Shape::Entry { from, to } = &piece.shape {
                for angle in angles {
                    for candidate in [angle.clone(), angle.clone() + &self.period] {
                        if candidate > *from && candidate < *to {
                            inside.push(candidate);
                        }
                    }
                }
            }
        }
        inside
    }
}

/// The interval [a, b] split where a front's formula changes: a front crossing an end of a
/// piece of the memory, P crossing one, and a front meeting the top of the contact; and
/// the windows searched for the top (P falling through an entry piece with a front under
/// way), whose cuts are found by sampling and proven afterwards ([`TopSearch`]).
fn split<R: Real>(
    loads: &Loads<R>,
    memory: &Memory<R>,
    inflections: &Inflections<R>,
    (a, first): Break<'_, R>,
    (b, last): Break<'_, R>,
    signs: Signs,
) -> (Vec<(R, R)>, Vec<TopSearch<R>>) {
    let mut nodes = vec![a.clone()];
    nodes.extend(crossings(loads, memory, inflections, (a, first), (b, last), signs));
    nodes.push(b.clone());
    // Where a front meets the top of the contact (P falling onto it, or it onto P).
    let capped = |t: &R, forward: bool| {
        let point = loads.at(t);
        let value = point.slip_variable(forward);
        memory
            .front(loads, &Known::plain(value), forward)
            .is_none_or(|front| memory.load_of(&front).value >= point.p)
    };
    // Where P rises a front lies at or below P(a) < P (F(P(a)) = x(a) ≤ x forward,
    // G(P(a)) = y(a) ≥ y backward), and where P falls through an affine piece the front
    // meets the top only where x or y crosses its level, a cut already: only where P falls
    // through an entry piece is the window searched.
    let through_entry = |u: &R, v: &R| {
        let load = loads.p(&((u.clone() + v) / &u.int(2)));
        if signs.p >= 0 {
            return None;
        }
        let piece = memory.pieces.iter().find(|p| p.hi.value >= load)?;
        matches!(piece.shape, Shape::Entry { .. }).then(|| piece.clone())
    };
    let mut pieces = Vec::new();
    let mut searches = Vec::new();
    for w in nodes.windows(2) {
        let mut inner = Vec::new();
        let entered = through_entry(&w[0], &w[1]);
        for (active, forward) in [(signs.x > 0, true), (signs.y < 0, false)] {
            let (true, Some(entered)) = (active, &entered) else {
                continue;
            };
            let mut search = TopSearch {
                window: (w[0].clone(), w[1].clone()),
                cut: None,
                forward,
                entered: entered.clone(),
            };
            let quarter = |k: i64| w[0].clone() + &((w[1].clone() - &w[0]) * &w[0].ratio(k, 4));
            // Tested just inside the ends: at an end the front may sit exactly at the top.
            let (first, last) = (
                quarter(0) + &((w[1].clone() - &w[0]) * &w[0].ratio(1, 1 << 20)),
                quarter(4) - &((w[1].clone() - &w[0]) * &w[0].ratio(1, 1 << 20)),
            );
            // Undecided samples leave the window to the proof after it, which then fails
            // wherever the front does meet the top.
            let sampled = (
                if_decided(|| capped(&first, forward)),
                if_decided(|| capped(&last, forward)),
            );
            if let (Some(at_first), Some(at_last)) = sampled {
                if at_first != at_last {
                    let cut = bisect_predicate(|t: &R| capped(t, forward) == at_last, &first, &last);
                    search.cut = Some(cut.clone());
                    inner.push(cut);
                }
            }
            searches.push(search);
        }
        inner.sort_by(|u, v| u.partial_cmp(v).unwrap_or(std::cmp::Ordering::Equal));
        let mut previous = w[0].clone();
        for cut in inner {
            pieces.push((previous, cut.clone()));
            previous = cut;
        }
        pieces.push((previous, w[1].clone()));
    }
    pieces.retain(|(u, v)| v > u);
    (pieces, searches)
}

/// The angles in (a, b), in order, where a front crosses an end of a piece of the memory
/// or P crosses one: where the front's formula changes. F and G are continuous, so one
/// piece's upper end is the next one's lower end: each join is taken once.
fn crossings<R: Real>(
    loads: &Loads<R>,
    memory: &Memory<R>,
    inflections: &Inflections<R>,
    (a, first): Break<'_, R>,
    (b, last): Break<'_, R>,
    signs: Signs,
) -> Vec<R> {
    let (start, end) = (loads.at(a), loads.at(b));
    let mut cuts: Vec<R> = Vec::new();
    let between = |v: &Known<R>, u: &Known<R>, w: &Known<R>| (v.gt(u) && v.lt(w)) || (v.gt(w) && v.lt(u));
    let mut add_crossings = |values: Vec<Known<R>>, low: Known<R>, high: Known<R>, f: &Offset<R>| {
        for v in values {
            if between(&v, &low, &high) {
                cuts.push(solve(|t: &R| f(&loads.at(t), &v.value), a, b));
            }
        }
    };
    // A flat piece's two ends are one value: each value once, or its crossing is found twice.
    let ends = |low: &dyn Fn(&Piece<R>) -> Known<R>, high: &dyn Fn(&Piece<R>) -> Known<R>| -> Vec<Known<R>> {
        let mut values: Vec<Known<R>> = memory
            .pieces
            .first()
            .map(low)
            .into_iter()
            .chain(memory.pieces.iter().map(high))
            .collect();
        values.dedup_by(|next, previous| next.same(previous));
        values
    };
    // Each active front crosses its own values: F's (forward, against x) or G's (backward,
    // against y) at the pieces' ends, and at the inflections inside entry pieces. Where P
    // falls through a piece F = a (flat) or G = a (left by backward slip), a front meets
    // the top where x = a or y = a (F(P) = x or G(P) = y there): a front's own values hold
    // its kind of level, and with one front under way a falling P needs the other's too.
    for forward in [true, false] {
        let active = |forward: bool| if forward { signs.x > 0 } else { signs.y < 0 };
        let values = if active(forward) {
            let mut values = match forward {
                true => ends(&|p| p.f_lo.clone(), &|p| p.f_hi.clone()),
                false => ends(&|p| p.g_lo.clone(), &|p| p.g_hi.clone()),
            };
            values.extend(
                inflections
                    .inside_entries(memory, forward)
                    .iter()
                    .map(|t| Known::plain(loads.at(t).slip_variable(forward))),
            );
            values
        } else if signs.p < 0 && active(!forward) {
            let level = |p: &Piece<R>| match (&p.shape, forward) {
                (Shape::Affine { b: 0, .. }, true) => Some(p.f_lo.clone()),
                (Shape::Affine { b: -2, .. }, false) => Some(p.g_lo.clone()),
                _ => None,
            };
            memory.pieces.iter().filter_map(level).collect()
        } else {
            continue;
        };
        let origin = if forward { Origin::X } else { Origin::Y };
        let (low, high) = (
            Known::exactly(start.slip_variable(forward), origin(first)),
            Known::exactly(end.slip_variable(forward), origin(last)),
        );
        let rate: &Offset<R> = if forward {
            &Point::x_and_rate
        } else {
            &Point::y_and_rate
        };
        add_crossings(values, low, high, rate);
    }
    if signs.p < 0 {
        let values = ends(&|p| p.lo.clone(), &|p| p.hi.clone());
        let (low, high) = (
            Known::exactly(start.p.clone(), Origin::P(first)),
            Known::exactly(end.p.clone(), Origin::P(last)),
        );
        add_crossings(values, low, high, &Point::p_and_rate);
    }
    cuts.sort_by(|u, v| u.partial_cmp(v).unwrap_or(std::cmp::Ordering::Equal));
    cuts.dedup();
    cuts
}

#[cfg(all(test, feature = "certified"))]
mod tests {
    use rug::Float;

    use super::*;
    use crate::ball::Ball;
    use crate::doubts::watch;
    use crate::interval::Interval;
    use crate::real::Precision;

    /// A trigonometric polynomial with coefficients read from decimals at `precision`.
    fn poly<R: Real>(cos: &[&str], sin: &[&str], precision: Precision) -> TrigPoly<R> {
        let read = |texts: &[&str]| {
            texts
                .iter()
                .map(|text| R::parse_decimal(text, precision).expect("a decimal"))
                .collect()
        };
        TrigPoly {
            cos: read(cos),
            sin: read(sin),
        }
    }

    const COS: [&str; 3] = ["0.05", "0.3", "0.15"];
    const SIN: [&str; 3] = ["0", "0.2", "-0.1"];

    /// The roots at 256 bits of MPFR, the reference the enclosures must hold.
    fn reference_roots(cos: &[&str], sin: &[&str]) -> Vec<Float> {
        sign_changes(&poly::<Float>(cos, sin, Precision::bits(256)))
    }

    #[test]
    fn the_divided_difference_is_the_difference_quotient_and_the_slope_where_its_ends_meet() {
        let precision = Precision::bits(256);
        let p = poly::<Float>(&COS, &SIN, precision);
        let read = |text: &str| Float::with_val(256, Float::parse(text).unwrap());
        for (a, b) in [("0.7", "2.1"), ("1.3", "1.30001"), ("2.5", "2.5"), ("0.2", "-3.9")] {
            let (a, b) = (read(a), read(b));
            let (value, rate) = p.divided_difference(&a, &b);
            let expected = if a == b {
                p.derivative().value(&a)
            } else {
                (p.value(&a) - p.value(&b)) / (a.clone() - &b)
            };
            assert!(Float::with_val(256, &value - &expected).abs() < 1e-70, "{a} {b}");
            // The rate against a central difference in a.
            let h = read("1e-25");
            let ahead = p.divided_difference(&(a.clone() + &h), &b).0;
            let behind = p.divided_difference(&(a.clone() - &h), &b).0;
            let slope = (ahead - behind) / (h * 2u32);
            let off = Float::with_val(256, &rate - &slope).abs();
            assert!(off < 1e-40, "{a} {b}: {off}");
        }
        // On balls: the series near a = b and the quotient apart both hold the MPFR values.
        let q = poly::<Ball>(&COS, &SIN, Precision::bits(128));
        for (a, b) in [("1.3", "1.30001"), ("0.7", "2.1")] {
            let (ball_a, ball_b) = (
                Ball::parse_decimal(a, Precision::bits(128)).unwrap(),
                Ball::parse_decimal(b, Precision::bits(128)).unwrap(),
            );
            let ((value, rate), doubts) = watch(|| q.divided_difference(&ball_a, &ball_b));
            assert!(doubts.none());
            let (reference, reference_rate) = p.divided_difference(&read(a), &read(b));
            assert!(value.contains(&reference) && rate.contains(&reference_rate), "{a} {b}");
            assert!(value.relative_radius() < 1e-30, "{a} {b}: {value:?}");
        }
    }

    #[test]
    fn a_fronts_angle_is_enclosed_by_krawczyk_on_points_complex_boxes_and_at_a_turning_point() {
        // One harmonic, f = 1: x = q − P = 0.2 cos θ − 1, so x(t) = x(θ) at t = 2π − θ.
        let loads_in = |precision: Precision| -> Loads<Ball> {
            let path = LoadPath {
                normal: poly(&["1", "0.3"], &["0", "0"], precision),
                tangential: poly(&["0", "0.5"], &["0", "0"], precision),
            };
            Loads::new(&path, &Ball::from_i64(1, precision))
        };
        let precision = Precision::bits(128);
        let loads = loads_in(precision);
        let tau = Ball::pi(precision) * &Ball::from_i64(2, precision);
        // 3.1415 lies 9.3e-5 before π, where x turns: t and θ meet there.
        for theta in ["0.7", "3.1415", "5.9"] {
            let theta = Ball::parse_decimal(theta, precision).unwrap();
            let exact = tau.clone() - &theta;
            let near = exact.midpoint_value() + &Ball::parse_decimal("1e-12", precision).unwrap();
            let (angle, doubts) = watch(|| same_level_angle(&loads, &theta, &near, true));
            assert!(doubts.none(), "{theta:?}");
            assert!((angle.clone() - &exact).contains_zero(), "{theta:?}: {angle:?}");
            assert!(angle.relative_radius() < 1e-30, "{theta:?}: {angle:?}");
        }
        // A complex box of θ in f64 intervals: its enclosure holds 2π − θ at every corner.
        let path = LoadPath {
            normal: poly::<Interval>(&["1", "0.3"], &["0", "0"], Precision::DOUBLE),
            tangential: poly(&["0", "0.5"], &["0", "0"], Precision::DOUBLE),
        };
        let loads = Loads::new(&path, &Interval::new(1.0, 1.0));
        let theta = Interval::rectangle((0.69, 0.71), (-0.01, 0.01));
        let near = Interval::new(5.583, 5.583);
        let (angle, doubts) = crate::doubts::watch(|| {
            crate::doubts::with_analytic(true, || same_level_angle(&loads, &theta, &near, true))
        });
        assert!(doubts.none(), "{angle:?}");
        let (re, im) = (angle.real_bounds(), angle.imaginary_bounds());
        let tau = 2.0 * std::f64::consts::PI;
        assert!(re.0 <= tau - 0.71 && tau - 0.69 <= re.1, "{angle:?}");
        assert!(im.0 <= -0.01 && 0.01 <= im.1, "{angle:?}");
        assert!(re.1 - re.0 < 0.1 && im.1 - im.0 < 0.1, "{angle:?}");
    }

    #[test]
    fn roots_in_balls_are_proven_enclosures_of_the_mpfr_roots() {
        for (cos, sin) in [(&COS[..], &SIN[..]), (&["1", "0.4"][..], &["0", "0"][..])] {
            let reference = reference_roots(cos, sin);
            for bits in [64, 128, 256] {
                let precision = Precision::bits(bits);
                let (roots, doubts) = watch(|| sign_changes(&poly::<Ball>(cos, sin, precision)));
                assert!(doubts.none(), "{bits} bits: {doubts:?}");
                assert_eq!(roots.len(), reference.len(), "{bits} bits");
                for (root, exact) in roots.iter().zip(&reference) {
                    assert!(root.contains(exact), "{bits} bits: {root:?} misses {exact}");
                    // As narrow as the precision resolves a simple root.
                    assert!(root.relative_radius() < Float::with_val(64, 2f64.powi(8 - bits as i32)));
                }
            }
        }
    }

    #[test]
    fn roots_in_f64_intervals_are_proven_and_narrow() {
        let reference = reference_roots(&COS, &SIN);
        let (roots, doubts) = watch(|| sign_changes(&poly::<Interval>(&COS, &SIN, Precision::DOUBLE)));
        assert!(doubts.none(), "{doubts:?}");
        assert_eq!(roots.len(), reference.len());
        for (root, exact) in roots.iter().zip(&reference) {
            let (lo, hi) = root.real_span().expect("an interval");
            assert!(
                Float::with_val(256, lo) <= *exact && *exact <= Float::with_val(256, hi),
                "{root:?} misses {exact}"
            );
            assert!(hi - lo < 1e-13, "{root:?}");
        }
    }

    /// q' = −sin θ (0.4 + 0.4 cos θ) has a triple root at π: no sample interval around it is
    /// proven monotone or root-free, and the doubt refuses the enclosure.
    #[test]
    fn a_multiple_root_is_a_doubt_not_a_proven_root() {
        let (_, doubts) = watch(|| {
            sign_changes(&poly::<Interval>(
                &["0", "0", "0"],
                &["0", "-0.4", "-0.2"],
                Precision::DOUBLE,
            ))
        });
        assert!(!doubts.none());
    }

    /// Roots exactly at 0 and π (an unshifted cosine's turning points) lie between the
    /// samples and are proven; the largest value is enclosed where two maxima tie.
    #[test]
    fn roots_at_multiples_of_pi_and_tied_maxima_are_decided() {
        let precision = Precision::bits(128);
        let (roots, doubts) = watch(|| sign_changes(&poly::<Ball>(&["0", "0"], &["0", "-0.3"], precision)));
        assert!(doubts.none(), "{doubts:?}");
        assert_eq!(roots.len(), 2);
        let pi = Float::with_val(256, rug::float::Constant::Pi);
        assert!(roots[0].contains(&pi), "{:?}", roots[0]);
        // At 2π itself, which no enclosure places below 2π.
        assert!(roots[1].contains(&(pi * 2u32)), "{:?}", roots[1]);
        // cos 2θ: maxima 1 at 0 and at π.
        let ((_, largest), doubts) =
            watch(|| extreme(&poly::<Ball>(&["0", "0", "1"], &["0", "0", "0"], precision), true));
        assert!(doubts.none(), "{doubts:?}");
        assert!(largest.contains(&Float::with_val(64, 1)), "{largest:?}");
    }

    /// In the steady cycle some memory values are equal by construction (a turning value
    /// met again one period later, F = x at the top, one value at each join): on f64
    /// intervals and on 128-bit balls the memory's update answers every comparison, its
    /// ties by the values' origins, for paths of two and three harmonics in P and Q.
    #[test]
    fn the_memory_update_of_a_varying_load_decides_every_comparison_on_enclosures() {
        fn check<R: Real>(precision: Precision) {
            // P's cosines and sines, then Q's.
            let paths: [[&[&str]; 4]; 2] = [
                [
                    &["1", "0.3", "0"],
                    &["0", "0", "0.1"],
                    &["0", "0.3", "0.1"],
                    &["0", "0.1", "0.05"],
                ],
                [
                    &["1", "0.25", "-0.05", "0.02"],
                    &["0", "0.1", "0.08", "0"],
                    &["0.05", "0.2", "0.07", "-0.03"],
                    &["0", "-0.15", "0.06", "0.02"],
                ],
            ];
            for [p_cos, p_sin, q_cos, q_sin] in paths {
                let path = LoadPath {
                    normal: poly::<R>(p_cos, p_sin, precision),
                    tangential: poly::<R>(q_cos, q_sin, precision),
                };
                let one = R::from_i64(1, precision);
                let contact = Contact {
                    friction: one.clone(),
                    compliance_ratio: one,
                };
                let (cycle, _, sites) = crate::doubts::locate_doubts(|| SteadyCycle::new(&path, &contact));
                assert!(cycle.is_ok(), "{p_cos:?}: {cycle:?}");
                let in_memory: Vec<&String> = sites
                    .iter()
                    .filter(|site| site.contains("Memory<R>::advance") || site.contains("Memory<R>::at_largest_x"))
                    .collect();
                assert!(
                    in_memory.is_empty(),
                    "{p_cos:?} at {} bits: {in_memory:?}",
                    precision.in_bits()
                );
            }
        }
        check::<Interval>(Precision::DOUBLE);
        check::<Ball>(Precision::bits(128));
    }
}
