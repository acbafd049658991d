//! Arb balls (FLINT's `acb`): a [`Real`] whose every value is a ball that contains the
//! exact value of what it computes, so that the same generic code that runs in f64 and
//! MPFR yields rigorous enclosures.
//!
//! A [`Ball`] is a complex ball. Values built through [`Real`] (inputs, constants, the
//! cycle's geometry) are real: their imaginary part is exactly zero, and every function
//! takes its real Arb form (`sqrt` of a ball reaching below zero is indeterminate, as
//! f64 gives NaN). Complex values appear only when Arb's integration bounds an integrand
//! on a complex ball around a piece of the real axis; there each function is the analytic
//! continuation of its real form along that piece, and a function that is not analytic
//! on the ball (a branch cut is touched, `abs` or a comparison cannot decide the sign of
//! the real part) yields an indeterminate ball, which makes Arb subdivide.
//!
//! Comparisons are the soundness trap of running branching code on balls: two
//! overlapping balls are neither `<` nor `>=`. Such a comparison answers `false`, as f64
//! does for NaN, and is counted; [`watch`] reports the count of a computation, and a
//! result reached through an undecided comparison must not be trusted (the certified
//! driver retries at a higher precision or refuses). Balls are compared by their real
//! parts, which on a complex ball is the branch the real points inside it take.

use std::cmp::Ordering;
use std::ffi::{c_char, CString};
use std::fmt;
use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Rem, RemAssign, Sub, SubAssign};

use flint_sys::acb::*;
use flint_sys::acb_types::acb_struct;
use flint_sys::arb::*;
use flint_sys::arb_types::{arb_struct, mag_struct};
use flint_sys::arf::{
    arf_abs_bound_lt_2exp_si, arf_clear, arf_get_d, arf_get_mpfr, arf_init, arf_is_zero, arf_rnd_t_ARF_RND_NEAR,
    arf_set_mag,
};
use flint_sys::arf_types::arf_struct;
use flint_sys::mag::{mag_clear, mag_cmp, mag_init, mag_is_zero, mag_mul_2exp_si};

use flint_sys::deps::{__mpfr_struct, mpfr_rnd_t_MPFR_RNDD, mpfr_rnd_t_MPFR_RNDU};
use num_traits::ToPrimitive;
use rug::float::Round;
use rug::Float;

use crate::doubts::{analytic_required, not_analytic, undecided};
pub use crate::doubts::{locate_doubts, watch, Doubts};
use crate::real::{ParseRealError, Precision, Real};

/// A complex Arb ball at a working precision; real wherever [`Real`] built it.
pub struct Ball {
    raw: acb_struct,
    precision: u32,
}

// SAFETY: a ball owns its limbs exclusively and nothing mutates through a shared
// reference; FLINT's functions are thread-safe on distinct objects.
unsafe impl Send for Ball {}
unsafe impl Sync for Ball {}

/// An Arb magnitude (an upper or lower bound of a non-negative number), cleared on drop.
pub struct Mag(pub(crate) mag_struct);

impl Mag {
    /// An upper bound of |`scale`| times 2^−`goal_bits`, or zero where there is no scale:
    /// the absolute error a rule may stop at.
    pub(crate) fn tolerance(scale: Option<&Ball>, goal_bits: u32) -> Mag {
        let mut magnitude = Mag::new();
        if let Some(scale) = scale {
            // SAFETY: both initialised.
            unsafe {
                acb_get_mag(&mut magnitude.0, scale.as_raw());
                mag_mul_2exp_si(&mut magnitude.0, &magnitude.0, -i64::from(goal_bits));
            }
        }
        magnitude
    }

    /// Whether the magnitude is exactly zero.
    pub(crate) fn is_zero(&self) -> bool {
        // SAFETY: initialised.
        unsafe { mag_is_zero(&self.0) != 0 }
    }

    pub(crate) fn new() -> Mag {
        let mut m = mag_struct::default();
        // SAFETY: initialised here, cleared on drop.
        unsafe { mag_init(&mut m) };
        Mag(m)
    }

    pub(crate) fn of(x: f64) -> Mag {
        let mut m = Mag::new();
        // SAFETY: initialised. Exact for a dyadic x (the ellipses' half axes).
        unsafe { flint_sys::mag::mag_set_d(&mut m.0, x) };
        m
    }
}

impl Drop for Mag {
    fn drop(&mut self) {
        // SAFETY: initialised in `new`.
        unsafe { mag_clear(&mut self.0) }
    }
}

/// The binary exponent beyond which a ball's decimal exponent is not printed: 2^61, so
/// that decimal exponents stay far inside i64.
pub const MOST_DECIMAL_BINARY_EXPONENT: i64 = 1 << 61;

/// `x` into `out` rounded in the direction `round`, as MPFR rounds a result past its
/// exponent range: below it to 0 or the least positive number, beyond it to the largest
/// finite number or infinity, whichever lies on the side of `x` that `round` asks for
/// (`arf_get_mpfr` leaves such an exponent out of range, which MPFR does not expect).
///
/// # Safety
/// `x` must be an initialised arf.
unsafe fn outward_into_mpfr(out: &mut Float, x: &arf_struct, round: Round) {
    let direction = match round {
        Round::Down => mpfr_rnd_t_MPFR_RNDD,
        _ => mpfr_rnd_t_MPFR_RNDU,
    };
    // SAFETY: `x` is initialised (the caller's promise).
    let (zero, exponent, negative) = unsafe {
        (
            arf_is_zero(x) != 0,
            arf_abs_bound_lt_2exp_si(x),
            flint_sys::arf::arf_sgn(x) < 0,
        )
    };
    let (low, high) = (i64::from(rug::float::exp_min()), i64::from(rug::float::exp_max()));
    if zero || (low..=high).contains(&exponent) || !unsafe { flint_sys::arf::arf_is_finite(x) != 0 } {
        // SAFETY: `out` is an initialised MPFR number; the exponent is within range.
        unsafe { arf_get_mpfr(out.as_raw_mut().cast::<__mpfr_struct>(), x, direction) };
        return;
    }
    let toward_zero = (round == Round::Down) != negative;
    *out = if exponent < low {
        // Below the range: 0 on the side of zero, the least number away from it.
        let mut least = Float::new(out.prec());
        if !toward_zero {
            least.next_up();
        }
        if negative {
            -least
        } else {
            least
        }
    } else {
        // Beyond the range: the largest finite number toward zero, infinity away from it.
        let mut largest = Float::with_val(out.prec(), rug::float::Special::Infinity);
        if toward_zero {
            largest.next_down();
        }
        if negative {
            -largest
        } else {
            largest
        }
    };
}

impl Drop for Ball {
    fn drop(&mut self) {
        // SAFETY: `raw` was initialised by `acb_init` in `Ball::zero`.
        unsafe { acb_clear(&mut self.raw) }
    }
}

impl Clone for Ball {
    /// A copy; of a real ball only the real part is copied (a fresh ball's imaginary part
    /// is already the exact zero).
    fn clone(&self) -> Self {
        let mut copy = Ball::zero(self.precision);
        // SAFETY: both initialised.
        unsafe {
            if self.is_real() {
                arb_set(&mut copy.raw.real, self.real_part());
            } else {
                acb_set(&mut copy.raw, &self.raw);
            }
        }
        copy
    }
}

impl Ball {
    fn zero(precision: u32) -> Ball {
        let mut raw = acb_struct::default();
        // SAFETY: acb_init initialises the zeroed struct in place; the struct holds no
        // pointer into itself, so moving it afterwards is fine.
        unsafe { acb_init(&mut raw) };
        Ball { raw, precision }
    }

    fn slong_precision(&self) -> i64 {
        i64::from(self.precision)
    }

    /// A copy of an Arb complex ball, to carry `precision`.
    ///
    /// # Safety
    /// `raw` must point to an initialised `acb_struct`.
    pub(crate) unsafe fn from_raw(raw: *const acb_struct, precision: u32) -> Ball {
        let mut copy = Ball::zero(precision);
        acb_set(&mut copy.raw, raw);
        copy
    }

    /// The Arb ball, for FFI.
    pub(crate) fn as_raw(&self) -> &acb_struct {
        &self.raw
    }

    /// The Arb ball at `raw`, read in place (no copy) for the duration of `read`.
    ///
    /// # Safety
    /// `raw` must point to an initialised `acb_struct` that nothing changes or frees
    /// while `read` runs.
    pub(crate) unsafe fn read_in_place<T>(raw: *const acb_struct, precision: u32, read: impl FnOnce(&Ball) -> T) -> T {
        // A bitwise view of the caller's ball: only ever borrowed, and never cleared here
        // (ManuallyDrop), so the caller keeps sole ownership of its limbs.
        let view = std::mem::ManuallyDrop::new(Ball {
            raw: std::ptr::read(raw),
            precision,
        });
        read(&view)
    }

    /// Moves the ball into the Arb ball at `out` (whose old value is cleared), without a copy.
    ///
    /// # Safety
    /// `out` must point to an initialised `acb_struct`.
    pub(crate) unsafe fn move_into(mut self, out: *mut acb_struct) {
        acb_swap(out, &mut self.raw);
    }

    /// A ball from an initialised Arb complex ball (taking it over).
    pub(crate) fn wrap(raw: acb_struct, precision: u32) -> Ball {
        Ball { raw, precision }
    }

    /// The real part, to be changed in place.
    pub(crate) fn real_mut(&mut self) -> &mut arb_struct {
        &mut self.raw.real
    }

    fn real_part(&self) -> &arb_struct {
        &self.raw.real
    }

    /// Whether the imaginary part is exactly zero.
    pub fn is_real(&self) -> bool {
        // FLINT's `acb_is_real` (`arb_is_zero` of the imaginary part), read in place: every
        // arithmetic operation asks it, and FLINT's inline function costs a call from
        // Rust. Zero is a special midpoint (size 0) with exponent 0 and a radius whose
        // mantissa and exponent are 0 (`arf_is_zero`, `mag_is_zero`).
        let imaginary = &self.raw.imag;
        imaginary.mid.size == 0 && imaginary.mid.exp == 0 && imaginary.rad.man == 0 && imaginary.rad.exp == 0
    }

    /// Whether the (real) ball contains the MPFR number `x`.
    pub fn contains(&self, x: &Float) -> bool {
        // SAFETY: initialised; flint-sys's `__mpfr_struct` has MPFR's layout, which rug's is.
        self.is_real() && unsafe { arb_contains_mpfr(self.real_part(), x.as_raw().cast::<__mpfr_struct>()) != 0 }
    }

    /// Whether the ball contains zero.
    pub fn contains_zero(&self) -> bool {
        // SAFETY: initialised.
        unsafe { acb_contains_zero(&self.raw) != 0 }
    }

    /// An upper bound of |x| over the ball.
    fn magnitude(&self) -> Mag {
        let mut bound = Mag::new();
        // SAFETY: both initialised.
        unsafe { acb_get_mag(&mut bound.0, &self.raw) };
        bound
    }

    /// Whether every |x| in the ball is below 2^`log2_factor` times the least |y| in
    /// `scale`: how a value that should be much smaller than another is recognised
    /// without reading either into a float of bounded exponent.
    pub(crate) fn is_below_scaled(&self, scale: &Ball, log2_factor: i64) -> bool {
        let mut least = Mag::new();
        // SAFETY: all initialised; the scaling is in place.
        unsafe {
            acb_get_mag_lower(&mut least.0, &scale.raw);
            mag_mul_2exp_si(&mut least.0, &least.0, log2_factor);
            mag_cmp(&self.magnitude().0, &least.0) < 0
        }
    }

    /// Of two enclosures of one value, the one whose bound on the absolute value is
    /// smaller.
    pub(crate) fn tighter(self, other: Ball) -> Ball {
        // SAFETY: both magnitudes initialised.
        if unsafe { mag_cmp(&other.magnitude().0, &self.magnitude().0) } < 0 {
            other
        } else {
            self
        }
    }

    /// The ball is a single number (radius zero).
    pub fn is_exact(&self) -> bool {
        // SAFETY: initialised.
        unsafe { acb_is_exact(&self.raw) != 0 }
    }

    /// The real part's lower and upper end, rounded outward to `bits`.
    pub fn bounds(&self, bits: u32) -> (Float, Float) {
        let (mut lower, mut upper) = (Float::new(bits), Float::new(bits));
        let (mut a, mut b) = (arf_struct::default(), arf_struct::default());
        // SAFETY: the arf values are initialised and cleared here; the rug floats are
        // written through their MPFR pointers with outward rounding.
        unsafe {
            flint_sys::arf::arf_init(&mut a);
            flint_sys::arf::arf_init(&mut b);
            arb_get_interval_arf(&mut a, &mut b, self.real_part(), i64::from(bits));
            outward_into_mpfr(&mut lower, &a, Round::Down);
            outward_into_mpfr(&mut upper, &b, Round::Up);
            flint_sys::arf::arf_clear(&mut a);
            flint_sys::arf::arf_clear(&mut b);
        }
        (lower, upper)
    }

    /// Whether the real part's size (its midpoint's, or its radius's where that is
    /// larger) lies within 2^(±2^61) (10^(±6.9·10¹⁷)), whose decimal exponents the printed
    /// decimals hold; zero does.
    pub fn decimal_exponent_fits(&self) -> bool {
        self.binary_exponent().abs() < MOST_DECIMAL_BINARY_EXPONENT
    }

    /// An e with |x| < 2^e for every x of the real part, the larger of Arb's bounds on
    /// its midpoint and on its radius (saturated far beyond
    /// [`MOST_DECIMAL_BINARY_EXPONENT`]); 0 for an exact zero. A ball that contains zero
    /// has the size of its radius.
    fn binary_exponent(&self) -> i64 {
        let (mid, radius) = (&self.raw.real.mid, &self.raw.real.rad);
        let mut radius_as_arf = arf_struct::default();
        // SAFETY: initialised; the arf is initialised and cleared here.
        unsafe {
            let mid_bound = (arf_is_zero(mid) == 0).then(|| arf_abs_bound_lt_2exp_si(mid));
            let radius_bound = (mag_is_zero(radius) == 0).then(|| {
                arf_init(&mut radius_as_arf);
                arf_set_mag(&mut radius_as_arf, radius);
                let bound = arf_abs_bound_lt_2exp_si(&radius_as_arf);
                arf_clear(&mut radius_as_arf);
                bound
            });
            mid_bound.into_iter().chain(radius_bound).max().unwrap_or(0)
        }
    }

    /// Whether the ball is finite and its size lies beyond 2^(±2^29), where rug's floats
    /// (which end at 2^(±2^30)) no longer hold it with room to spare.
    pub fn is_beyond_mpfr(&self) -> bool {
        const MPFR_SAFE_EXPONENT: i64 = 1 << 29;
        self.is_finite() && self.binary_exponent().abs() > MPFR_SAFE_EXPONENT
    }

    /// The real part as `(scaled, shift)` with the ball = scaled·10^shift and scaled of a
    /// size MPFR holds, where the ball's own size lies beyond 2^(±2^29) (rug's floats end
    /// at 2^(±2^30); W = e^(−P/c)-small at loads of 10⁹ decay loads is such a number);
    /// `None` where it needs no scaling. The scaled ball contains the exact quotient, so
    /// digits it rounds to, shifted, are digits the ball rounds to.
    /// A ball beyond [`Ball::decimal_exponent_fits`] scales to an indeterminate ball,
    /// which determines no digit.
    pub fn decimal_scaled(&self) -> Option<(Ball, i64)> {
        if !self.is_beyond_mpfr() {
            return None;
        }
        let binary = self.binary_exponent();
        if !self.decimal_exponent_fits() {
            return Some((self.indeterminate(), 0));
        }
        // 10^shift within a factor 10 of the ball's midpoint.
        let shift = ((binary - 1) as f64 * std::f64::consts::LOG10_2).floor() as i64;
        let bits = self.precision + 64;
        let mut power = Ball::zero(bits);
        // SAFETY: initialised; the real part is written, the imaginary part stays zero.
        unsafe { arb_ui_pow_ui(power.real_mut(), 10, shift.unsigned_abs(), i64::from(bits)) };
        let scaled = if shift > 0 {
            self.clone() / &power
        } else {
            self.clone() * &power
        };
        Some((scaled, shift))
    }

    /// An upper bound on the real part's radius relative to its midpoint (infinite
    /// where the ball contains zero and is not exactly zero), as a 64-bit float: the
    /// radius of a ball of more than 320 digits is below the range of f64.
    pub fn relative_radius(&self) -> Float {
        if let Some((scaled, _)) = self.decimal_scaled() {
            return scaled.relative_radius();
        }
        let (lower, upper) = self.bounds(self.precision + 64);
        if lower.is_zero() && upper.is_zero() {
            return Float::new(64);
        }
        if !(lower.is_finite() && upper.is_finite()) || (lower.is_sign_negative() != upper.is_sign_negative()) {
            return Float::with_val(64, rug::float::Special::Infinity);
        }
        let up = rug::float::Round::Up;
        let width = Float::with_val_round(64, &upper - &lower, up).0;
        let smallest = Float::with_val_round(64, lower.abs_ref(), rug::float::Round::Down)
            .0
            .min(&Float::with_val_round(64, upper.abs_ref(), rug::float::Round::Down).0);
        Float::with_val_round(64, width / smallest, up).0
    }

    /// (sinh, cosh), entire functions with no Real counterpart, for the sinh map.
    pub fn sinh_cosh(&self) -> (Ball, Ball) {
        self.pair(arb_sinh_cosh, acb_sinh_cosh)
    }

    /// Two functions of one argument computed together, real or complex as for `unary`.
    fn pair(
        &self,
        real: unsafe extern "C" fn(*mut arb_struct, *mut arb_struct, *const arb_struct, i64),
        complex: unsafe extern "C" fn(*mut acb_struct, *mut acb_struct, *const acb_struct, i64),
    ) -> (Ball, Ball) {
        let (mut first, mut second) = (Ball::zero(self.precision), Ball::zero(self.precision));
        // SAFETY: initialised.
        unsafe {
            if self.is_real() {
                real(
                    &mut first.raw.real,
                    &mut second.raw.real,
                    self.real_part(),
                    self.slong_precision(),
                );
            } else {
                complex(&mut first.raw, &mut second.raw, &self.raw, self.slong_precision());
            }
        }
        (first, second)
    }

    /// Whether functions must take their complex, analytic-checked form: on a complex
    /// ball, and on any ball while Arb bounds an integrand (where a real ball's real
    /// form, e.g. |x| across zero, would not be analytic).
    fn complex_context(&self) -> bool {
        analytic_required() || !self.is_real()
    }

    /// The larger (or smaller) of two balls: `real` on real balls; otherwise the one
    /// `first` picks, which must decide.
    fn extreme(
        &self,
        other: &Ball,
        real: unsafe extern "C" fn(*mut arb_struct, *const arb_struct, *const arb_struct, i64),
        first: impl Fn(&Ball, &Ball) -> bool,
    ) -> Ball {
        if self.complex_context() || other.complex_context() {
            return if first(self, other) {
                self.clone()
            } else {
                other.clone()
            };
        }
        self.real_binary(other, real)
    }

    /// `function` of the real parts of `self` and `other`, as a real ball.
    fn real_binary(
        &self,
        other: &Ball,
        function: unsafe extern "C" fn(*mut arb_struct, *const arb_struct, *const arb_struct, i64),
    ) -> Ball {
        let mut result = Ball::zero(self.precision);
        // SAFETY: initialised.
        unsafe {
            function(
                &mut result.raw.real,
                self.real_part(),
                other.real_part(),
                self.slong_precision(),
            )
        };
        result
    }

    /// Applies a real Arb function on real balls and a complex one otherwise.
    fn unary(
        &self,
        real: unsafe extern "C" fn(*mut arb_struct, *const arb_struct, i64),
        complex: unsafe extern "C" fn(*mut acb_struct, *const acb_struct, i64),
    ) -> Ball {
        let mut result = Ball::zero(self.precision);
        // SAFETY: initialised; Arb allows any arguments.
        unsafe {
            if self.is_real() {
                real(&mut result.raw.real, self.real_part(), self.slong_precision());
            } else {
                complex(&mut result.raw, &self.raw, self.slong_precision());
            }
        }
        result
    }

    /// A ball that holds every complex number (not finite).
    pub(crate) fn indeterminate(&self) -> Ball {
        let mut result = Ball::zero(self.precision);
        // SAFETY: initialised.
        unsafe { acb_indeterminate(&mut result.raw) };
        result
    }

    /// The sign of the real part where it is decided (for the continuation of a
    /// function defined piecewise by sign): `Some(true)` for > 0, `Some(false)` for < 0.
    fn real_sign(&self) -> Option<bool> {
        // SAFETY: initialised.
        unsafe {
            if arb_is_positive(self.real_part()) != 0 {
                Some(true)
            } else if arb_is_negative(self.real_part()) != 0 {
                Some(false)
            } else {
                None
            }
        }
    }

    /// The real part's midpoint.
    fn midpoint_f64(&self) -> f64 {
        // SAFETY: initialised.
        unsafe { arf_get_d(&self.raw.real.mid, arf_rnd_t_ARF_RND_NEAR) }
    }

    /// Applies an in-place Arb operation.
    fn in_place(mut self, operation: impl FnOnce(*mut acb_struct, i64)) -> Ball {
        let precision = self.slong_precision();
        operation(&mut self.raw, precision);
        self
    }
}

/// A binary operation: real Arb arithmetic on real balls, complex otherwise; the
/// result carries the left operand's precision, as MPFR's does.
macro_rules! arithmetic {
    ($trait:ident, $method:ident, $assign_trait:ident, $assign:ident, $real:ident, $complex:ident) => {
        impl $trait<&Ball> for Ball {
            type Output = Ball;
            fn $method(mut self, rhs: &Ball) -> Ball {
                self.$assign(rhs);
                self
            }
        }
        impl $trait<Ball> for Ball {
            type Output = Ball;
            fn $method(self, rhs: Ball) -> Ball {
                self.$method(&rhs)
            }
        }
        impl $assign_trait<&Ball> for Ball {
            fn $assign(&mut self, rhs: &Ball) {
                let precision = self.slong_precision();
                let both_real = self.is_real() && rhs.is_real();
                let this: *mut acb_struct = &mut self.raw;
                // SAFETY: initialised; Arb allows the output to alias an input.
                unsafe {
                    if both_real {
                        let real = std::ptr::addr_of_mut!((*this).real);
                        $real(real, real, &rhs.raw.real, precision);
                    } else {
                        $complex(this, this, &rhs.raw, precision);
                    }
                }
            }
        }
        impl $assign_trait<Ball> for Ball {
            fn $assign(&mut self, rhs: Ball) {
                self.$assign(&rhs);
            }
        }
    };
}

arithmetic!(Add, add, AddAssign, add_assign, arb_add, acb_add);
arithmetic!(Sub, sub, SubAssign, sub_assign, arb_sub, acb_sub);
arithmetic!(Mul, mul, MulAssign, mul_assign, arb_mul, acb_mul);
arithmetic!(Div, div, DivAssign, div_assign, arb_div, acb_div);

impl Rem<&Ball> for Ball {
    type Output = Ball;
    /// x − y·trunc(x/y), the remainder f64's `%` gives; where trunc(x/y) is not one
    /// integer throughout, the ball covers every candidate.
    fn rem(self, rhs: &Ball) -> Ball {
        if self.complex_context() || rhs.complex_context() {
            not_analytic();
            return self.indeterminate();
        }
        let quotient = self.clone() / rhs;
        let mut truncated = Ball::zero(self.precision);
        let mut ceiling = Ball::zero(self.precision);
        let p = self.slong_precision();
        // SAFETY: initialised.
        unsafe {
            arb_floor(&mut truncated.raw.real, quotient.real_part(), p);
            arb_ceil(&mut ceiling.raw.real, quotient.real_part(), p);
            if arb_is_nonnegative(quotient.real_part()) == 0 {
                if arb_is_nonpositive(quotient.real_part()) != 0 {
                    std::mem::swap(&mut truncated, &mut ceiling);
                } else {
                    let floor_copy = truncated.clone();
                    arb_union(&mut truncated.raw.real, floor_copy.real_part(), ceiling.real_part(), p);
                }
            }
        }
        self - &(truncated * rhs)
    }
}

impl Rem<Ball> for Ball {
    type Output = Ball;
    fn rem(self, rhs: Ball) -> Ball {
        self % &rhs
    }
}

impl RemAssign<&Ball> for Ball {
    fn rem_assign(&mut self, rhs: &Ball) {
        *self = self.clone() % rhs;
    }
}

impl RemAssign<Ball> for Ball {
    fn rem_assign(&mut self, rhs: Ball) {
        *self = self.clone() % &rhs;
    }
}

impl Neg for Ball {
    type Output = Ball;
    fn neg(self) -> Ball {
        let real = self.is_real();
        // SAFETY: initialised; in place (a real ball's imaginary part stays the exact zero).
        self.in_place(|raw, _| unsafe {
            if real {
                arb_neg(std::ptr::addr_of_mut!((*raw).real), std::ptr::addr_of!((*raw).real));
            } else {
                acb_neg(raw, raw)
            }
        })
    }
}

impl PartialEq for Ball {
    /// Equal when both are the same exact number; unequal when the real parts are
    /// disjoint; otherwise undecided (counted, and `false`).
    fn eq(&self, other: &Ball) -> bool {
        // SAFETY: initialised.
        unsafe {
            if acb_eq(&self.raw, &other.raw) != 0 {
                true
            } else if arb_ne(self.real_part(), other.real_part()) != 0 || acb_ne(&self.raw, &other.raw) != 0 {
                false
            } else {
                undecided();
                false
            }
        }
    }
}

/// One order relation on the real parts: `certain` decides it true and `refuted` false.
fn decide(
    a: &Ball,
    b: &Ball,
    certain: unsafe extern "C" fn(*const arb_struct, *const arb_struct) -> i32,
    refuted: unsafe extern "C" fn(*const arb_struct, *const arb_struct) -> i32,
) -> bool {
    // SAFETY: initialised.
    unsafe {
        if certain(a.real_part(), b.real_part()) != 0 {
            true
        } else if refuted(a.real_part(), b.real_part()) != 0 {
            false
        } else {
            undecided();
            false
        }
    }
}

impl PartialOrd for Ball {
    fn partial_cmp(&self, other: &Ball) -> Option<Ordering> {
        // SAFETY: initialised.
        unsafe {
            if arb_lt(self.real_part(), other.real_part()) != 0 {
                Some(Ordering::Less)
            } else if arb_gt(self.real_part(), other.real_part()) != 0 {
                Some(Ordering::Greater)
            } else if acb_eq(&self.raw, &other.raw) != 0 {
                Some(Ordering::Equal)
            } else {
                undecided();
                None
            }
        }
    }
    fn lt(&self, other: &Ball) -> bool {
        decide(self, other, arb_lt, arb_ge)
    }
    fn le(&self, other: &Ball) -> bool {
        decide(self, other, arb_le, arb_gt)
    }
    fn gt(&self, other: &Ball) -> bool {
        decide(self, other, arb_gt, arb_le)
    }
    fn ge(&self, other: &Ball) -> bool {
        decide(self, other, arb_ge, arb_lt)
    }
}

impl fmt::Debug for Ball {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let digits = Precision::bits(self.precision).in_decimal_digits().max(1);
        let text = |part: &arb_struct| {
            // SAFETY: arb_get_str returns a NUL-terminated string FLINT allocated.
            unsafe {
                let raw = arb_get_str(part, i64::from(digits), 0);
                let text = std::ffi::CStr::from_ptr(raw).to_string_lossy().into_owned();
                flint_sys::flint::flint_free(raw.cast());
                text
            }
        };
        if self.is_real() {
            write!(f, "{}", text(&self.raw.real))
        } else {
            write!(f, "{} + {}i", text(&self.raw.real), text(&self.raw.imag))
        }
    }
}

impl ToPrimitive for Ball {
    fn to_i64(&self) -> Option<i64> {
        let x = self.midpoint_f64();
        (x.is_finite() && x.abs() < 9.2e18).then_some(x as i64)
    }
    fn to_u64(&self) -> Option<u64> {
        let x = self.midpoint_f64();
        (x.is_finite() && (0.0..1.8e19).contains(&x)).then_some(x as u64)
    }
    fn to_f64(&self) -> Option<f64> {
        Some(self.midpoint_f64())
    }
}

/// Functions with a branch cut: the real Arb form on real balls; on complex balls the
/// principal branch, analytic-checked when Arb bounds an integrand.
fn branch_cut(
    x: &Ball,
    real: unsafe extern "C" fn(*mut arb_struct, *const arb_struct, i64),
    complex_analytic: unsafe extern "C" fn(*mut acb_struct, *const acb_struct, i32, i64),
) -> Ball {
    let mut result = Ball::zero(x.precision);
    let analytic = analytic_required();
    // SAFETY: initialised.
    unsafe {
        if !x.complex_context() {
            real(&mut result.raw.real, x.real_part(), x.slong_precision());
        } else {
            complex_analytic(&mut result.raw, &x.raw, i32::from(analytic), x.slong_precision());
            if analytic && acb_is_finite(&result.raw) == 0 {
                not_analytic();
            }
        }
    }
    result
}

/// Bits beyond the working precision with which an exact input is read (see
/// [`Real::from_rational`] for balls).
const INPUT_GUARD_BITS: u32 = 64;

impl Real for Ball {
    fn precision(&self) -> Precision {
        Precision::bits(self.precision)
    }
    fn from_f64(x: f64, precision: Precision) -> Self {
        let mut ball = Ball::zero(precision.in_bits().max(53));
        // SAFETY: initialised; exact.
        unsafe { arb_set_d(&mut ball.raw.real, x) };
        ball
    }
    fn from_i64(n: i64, precision: Precision) -> Self {
        let mut ball = Ball::zero(precision.in_bits());
        // SAFETY: initialised; exact.
        unsafe { arb_set_si(&mut ball.raw.real, n) };
        ball
    }
    fn from_float(x: &Float, precision: Precision) -> Self {
        let mut ball = Ball::zero(precision.in_bits());
        // SAFETY: initialised; exact (the ball is the MPFR number itself).
        unsafe { flint_sys::arf::arf_set_mpfr(&mut ball.raw.real.mid, x.as_raw().cast::<__mpfr_struct>()) };
        ball
    }
    fn parse_decimal(text: &str, precision: Precision) -> Result<Self, ParseRealError> {
        let error = || ParseRealError { text: text.to_string() };
        let trimmed = text.trim();
        // Arb also reads "inf", "nan" and "[m +/- r]"; only plain decimals are numbers here.
        if trimmed.is_empty()
            || !trimmed.chars().any(|c| c.is_ascii_digit())
            || !trimmed
                .chars()
                .all(|c| c.is_ascii_digit() || matches!(c, '.' | 'e' | 'E' | '+' | '-'))
        {
            return Err(error());
        }
        let c_text = CString::new(trimmed).map_err(|_| error())?;
        let mut ball = Ball::zero(precision.in_bits());
        // SAFETY: initialised; a NUL-terminated string. Arb returns a ball containing
        // the exact decimal.
        let status = unsafe {
            arb_set_str(
                &mut ball.raw.real,
                c_text.as_ptr().cast::<c_char>(),
                ball.slong_precision(),
            )
        };
        if status != 0 || !ball.is_finite() {
            return Err(error());
        }
        Ok(ball)
    }
    fn from_rational(x: &rug::Rational, precision: Precision) -> Self {
        // Numerator and denominator exactly, then one ball division: a ball containing x,
        // its midpoint rounded INPUT_GUARD_BITS below the working precision, so that a
        // difference of two close inputs (P0 − P1 near separation) keeps its relative
        // accuracy; operations on it still work at `precision`.
        let guarded = Precision::bits(precision.in_bits() + INPUT_GUARD_BITS);
        let exact = |n: &rug::Integer| Ball::from_float(&Float::with_val(n.significant_bits().max(1), n), guarded);
        let mut ball = exact(x.numer()) / exact(x.denom());
        ball.precision = precision.in_bits();
        ball
    }
    fn enclose_pi_multiple(multiple: &rug::Rational, offset: &rug::Rational, precision: Precision) -> Option<Self> {
        Some(super::enclose_pi_multiple(multiple, offset, precision))
    }
    fn pi(precision: Precision) -> Self {
        let mut ball = Ball::zero(precision.in_bits());
        // SAFETY: initialised.
        unsafe { arb_const_pi(&mut ball.raw.real, ball.slong_precision()) };
        ball
    }
    fn epsilon(precision: Precision) -> Self {
        Ball::from_i64(1, precision).times_power_of_two(1 - precision.in_bits() as i32)
    }
    fn smallest_full_precision(precision: Precision) -> Self {
        // Arb's exponents are integers of any size, so a ball keeps its precision however
        // small it is; this floor, 2^(−2^4096), lies below e^(−P/c) at every load the input
        // can give (MPFR's, 2^(−2^28), is passed by e^(−P/c) at P = 2·10⁸ c), and a W too
        // small to print is refused by its size ([`Ball::decimal_exponent_fits`]).
        let mut exponent: flint_sys::flint::fmpz = 0;
        // SAFETY: the fmpz is initialised and cleared here; the ball is initialised and
        // scaled in place.
        unsafe {
            flint_sys::fmpz::fmpz_init(&mut exponent);
            flint_sys::fmpz::fmpz_set_si(&mut exponent, -1);
            flint_sys::fmpz::fmpz_mul_2exp(&mut exponent, &exponent, 4096);
            let floor = Ball::from_i64(1, precision).in_place(|raw, _| acb_mul_2exp_fmpz(raw, raw, &exponent));
            flint_sys::fmpz::fmpz_clear(&mut exponent);
            floor
        }
    }

    fn sqrt(&self) -> Self {
        branch_cut(self, arb_sqrt, acb_sqrt_analytic)
    }
    fn cbrt(&self) -> Self {
        // The real cube root is odd; continue it from whichever side of zero the ball is on.
        let root = |x: &Ball| {
            let mut result = Ball::zero(x.precision);
            // SAFETY: initialised.
            unsafe {
                if x.is_real() {
                    arb_root_ui(&mut result.raw.real, x.real_part(), 3, x.slong_precision());
                } else {
                    acb_root_ui(&mut result.raw, &x.raw, 3, x.slong_precision());
                }
            }
            result
        };
        match self.real_sign() {
            Some(true) => root(self),
            Some(false) => -root(&-self.clone()),
            None if !self.complex_context() => {
                // Straddling zero: cbrt is increasing, so [−∛|a|, ∛b] covers the image.
                let magnitude = self.abs();
                let bound = root(&magnitude);
                let mut result = Ball::zero(self.precision);
                // SAFETY: initialised.
                unsafe {
                    let mut negative = arb_struct::default();
                    arb_init(&mut negative);
                    arb_neg(&mut negative, bound.real_part());
                    arb_union(
                        &mut result.raw.real,
                        &negative,
                        bound.real_part(),
                        self.slong_precision(),
                    );
                    arb_clear(&mut negative);
                }
                result
            }
            None => {
                not_analytic();
                self.indeterminate()
            }
        }
    }
    fn ln(&self) -> Self {
        branch_cut(self, arb_log, acb_log_analytic)
    }
    fn ln_1p(&self) -> Self {
        if analytic_required() {
            // log(1 + z) is analytic where Re z > −1.
            let shifted = self.clone() + &self.int(1);
            if shifted.real_sign() != Some(true) {
                not_analytic();
                return self.indeterminate();
            }
        }
        self.unary(arb_log1p, acb_log1p)
    }
    fn exp(&self) -> Self {
        self.unary(arb_exp, acb_exp)
    }
    fn exp_m1(&self) -> Self {
        self.unary(arb_expm1, acb_expm1)
    }
    fn powr(&self, exponent: &Self) -> Self {
        if !(self.complex_context() || exponent.complex_context()) {
            return self.real_binary(exponent, arb_pow);
        }
        let mut result = Ball::zero(self.precision);
        let analytic = analytic_required();
        // SAFETY: initialised.
        unsafe {
            acb_pow_analytic(
                &mut result.raw,
                &self.raw,
                &exponent.raw,
                i32::from(analytic),
                self.slong_precision(),
            );
            if analytic && acb_is_finite(&result.raw) == 0 {
                not_analytic();
            }
        }
        result
    }
    fn powi(&self, exponent: i32) -> Self {
        let mut result = Ball::zero(self.precision);
        // SAFETY: initialised; an integer power has no branch cut.
        unsafe {
            if self.is_real() {
                arb_pow_ui(
                    &mut result.raw.real,
                    self.real_part(),
                    u64::from(exponent.unsigned_abs()),
                    self.slong_precision(),
                );
            } else {
                acb_pow_ui(
                    &mut result.raw,
                    &self.raw,
                    u64::from(exponent.unsigned_abs()),
                    self.slong_precision(),
                );
            }
        }
        if exponent < 0 {
            self.int(1) / &result
        } else {
            result
        }
    }
    /// Arb's square, without the copy of `self` a product needs.
    fn square(&self) -> Self {
        self.unary(arb_sqr, acb_sqr)
    }
    /// Exact: Arb shifts the exponents of midpoint and radius.
    fn times_power_of_two(self, exponent: i32) -> Self {
        // SAFETY: initialised; in place.
        self.in_place(|raw, _| unsafe { acb_mul_2exp_si(raw, raw, i64::from(exponent)) })
    }
    fn sin(&self) -> Self {
        self.unary(arb_sin, acb_sin)
    }
    fn cos(&self) -> Self {
        self.unary(arb_cos, acb_cos)
    }
    fn sinh_cosh(&self) -> (Self, Self) {
        Ball::sinh_cosh(self)
    }
    fn sin_cos(&self) -> (Self, Self) {
        self.pair(arb_sin_cos, acb_sin_cos)
    }
    fn hypot(&self, other: &Self) -> Self {
        if !(self.complex_context() || other.complex_context()) {
            self.real_binary(other, arb_hypot)
        } else {
            (self.square() + &other.square()).sqrt()
        }
    }
    fn atan2(&self, x: &Self) -> Self {
        if self.complex_context() || x.complex_context() {
            not_analytic();
            return self.indeterminate();
        }
        self.real_binary(x, arb_atan2)
    }
    fn abs(&self) -> Self {
        if !self.complex_context() {
            let mut result = Ball::zero(self.precision);
            // SAFETY: initialised.
            unsafe { arb_abs(&mut result.raw.real, self.real_part()) };
            return result;
        }
        match self.real_sign() {
            Some(true) => self.clone(),
            Some(false) => -self.clone(),
            None => {
                undecided();
                self.indeterminate()
            }
        }
    }
    fn floor(&self) -> Self {
        let mut result = Ball::zero(self.precision);
        // SAFETY: initialised.
        unsafe { arb_floor(&mut result.raw.real, self.real_part(), self.slong_precision()) };
        // On a complex ball floor is analytic (constant) only where it is one integer.
        if self.complex_context() && !result.is_exact() {
            not_analytic();
            return self.indeterminate();
        }
        result
    }
    fn is_finite(&self) -> bool {
        // SAFETY: initialised.
        unsafe { acb_is_finite(&self.raw) != 0 }
    }
    /// On real balls Arb's max, which needs no decision (max is continuous): equal
    /// inputs such as Q1 = fP1 stay decidable. On complex balls, by the real parts.
    fn max_of(&self, other: &Self) -> Self {
        self.extreme(other, arb_max, |a, b| a >= b)
    }
    /// On real balls Arb's min; on complex balls, by the real parts.
    fn min_of(&self, other: &Self) -> Self {
        self.extreme(other, arb_min, |a, b| a <= b)
    }
    fn to_scientific(&self, digits: usize) -> String {
        let mut mid = Float::new(self.precision.max(64));
        // SAFETY: initialised; rounding to nearest into an MPFR number.
        unsafe {
            arf_get_mpfr(
                mid.as_raw_mut().cast::<__mpfr_struct>(),
                &self.raw.real.mid,
                flint_sys::deps::mpfr_rnd_t_MPFR_RNDN,
            )
        };
        Real::to_scientific(&mid, digits)
    }
    fn real_span(&self) -> Option<(f64, f64)> {
        let (mut lower, mut upper) = (arf_struct::default(), arf_struct::default());
        // SAFETY: the arf values are initialised and cleared here; each end is rounded
        // outward to 53 bits, then read as the f64 it is (rounded outward again).
        unsafe {
            flint_sys::arf::arf_init(&mut lower);
            flint_sys::arf::arf_init(&mut upper);
            arb_get_lbound_arf(&mut lower, self.real_part(), 53);
            arb_get_ubound_arf(&mut upper, self.real_part(), 53);
            let span = (
                arf_get_d(&lower, flint_sys::arf::arf_rnd_t_ARF_RND_FLOOR),
                arf_get_d(&upper, flint_sys::arf::arf_rnd_t_ARF_RND_CEIL),
            );
            flint_sys::arf::arf_clear(&mut lower);
            flint_sys::arf::arf_clear(&mut upper);
            Some(span)
        }
    }
    fn lies_inside(&self, outer: &Ball) -> bool {
        // SAFETY: initialised balls, read only.
        unsafe {
            let real = arb_contains_interior(&outer.raw.real, &self.raw.real) != 0;
            let imaginary = arb_contains_interior(&outer.raw.imag, &self.raw.imag) != 0;
            real && (imaginary || (self.is_real() && outer.is_real()))
        }
    }
    fn real_ends(&self) -> (Ball, Ball) {
        let (mut lower, mut upper) = (Ball::zero(self.precision), Ball::zero(self.precision));
        let bits = self.slong_precision();
        // SAFETY: initialised; each end is rounded outward to the working precision and
        // set as an exact midpoint, the radius left zero.
        unsafe {
            let (mut low, mut high) = (arf_struct::default(), arf_struct::default());
            arf_init(&mut low);
            arf_init(&mut high);
            arb_get_lbound_arf(&mut low, self.real_part(), bits);
            arb_get_ubound_arf(&mut high, self.real_part(), bits);
            arb_set_arf(lower.real_mut(), &low);
            arb_set_arf(upper.real_mut(), &high);
            arf_clear(&mut low);
            arf_clear(&mut high);
        }
        (lower, upper)
    }
    fn centred_square(&self) -> Ball {
        let reach = self.magnitude();
        let mut result = Ball::zero(self.precision);
        // SAFETY: initialised; each part gets the radius |self| about a zero midpoint.
        unsafe {
            arb_add_error_mag(&mut result.raw.real, &reach.0);
            if !self.is_real() {
                arb_add_error_mag(&mut result.raw.imag, &reach.0);
            }
        }
        result
    }
    fn midpoint_value(&self) -> Ball {
        let mut result = Ball::zero(self.precision);
        // SAFETY: initialised; the midpoint is copied exactly, the radius left zero.
        unsafe { arb_get_mid_arb(result.real_mut(), self.real_part()) };
        result
    }
    fn union(&self, other: &Ball) -> Ball {
        let mut result = Ball::zero(self.precision.max(other.precision));
        // SAFETY: initialised.
        unsafe { acb_union(&mut result.raw, &self.raw, &other.raw, result.slong_precision()) };
        result
    }
}

/// The smallest ball that contains both real balls.
pub fn hull(a: &Ball, b: &Ball) -> Ball {
    a.union(b)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ball(text: &str, bits: u32) -> Ball {
        Ball::parse_decimal(text, Precision::bits(bits)).unwrap()
    }

    #[test]
    fn exact_decimals_are_contained() {
        let tenth = ball("0.1", 128);
        let exact = Float::with_val(1024, Float::parse("0.1").unwrap());
        assert!(tenth.contains(&exact));
        assert!(!tenth.contains(&Float::with_val(1024, 0.1f64)));
    }

    #[test]
    fn realness_is_read_as_flint_reads_it() {
        let tenth = ball("0.1", 64);
        let zero = ball("0", 64);
        let complex = {
            let mut z = ball("0", 64);
            // SAFETY: initialised; the imaginary part set to a ball around 1/10.
            unsafe { arb_set(&mut z.raw.imag, tenth.real_part()) };
            z
        };
        let wide_zero = {
            let mut z = ball("0", 64);
            // SAFETY: initialised; the imaginary part [0 ± 1].
            unsafe { arb_add_error_2exp_si(&mut z.raw.imag, 0) };
            z
        };
        let infinite = {
            let mut z = ball("0", 64);
            // SAFETY: initialised; the imaginary part +∞.
            unsafe { arb_pos_inf(&mut z.raw.imag) };
            z
        };
        for b in [
            &tenth,
            &zero,
            &complex,
            &wide_zero,
            &infinite,
            &(tenth.clone() / &zero),
            &zero.indeterminate(),
        ] {
            // SAFETY: initialised.
            assert_eq!(b.is_real(), unsafe { acb_is_real(&b.raw) } != 0, "{b:?}");
        }
        assert!(tenth.is_real() && zero.is_real() && !complex.is_real() && !wide_zero.is_real());
    }

    #[test]
    fn real_shortcuts_enclose_the_exact_values() {
        let exact = |text: &str| Float::with_val(1024, Float::parse(text).unwrap());
        let tenth = ball("0.1", 64);
        // Powers of two are exact shifts: the ball stays the one around 1/10.
        let fifth = tenth.clone().times_power_of_two(1);
        assert!(fifth.contains(&exact("0.2")) && fifth.is_real());
        assert!(tenth.clone().times_power_of_two(-3).contains(&exact("0.0125")));
        assert!(tenth.square().contains(&exact("0.01")));
        let third = ball("1", 64) / &ball("-3", 64);
        assert!(third.square().contains(&(Float::with_val(1024, 1) / 9u32)));
        // Copies and negations of real balls stay real and keep the exact value inside.
        let negative = -tenth.clone();
        assert!(negative.is_real() && negative.contains(&exact("-0.1")));
        assert!(tenth.clone().contains(&exact("0.1")));
    }

    #[test]
    fn balls_are_read_in_place_and_moved_out_without_a_copy() {
        let third = ball("1", 128) / &ball("3", 128);
        let mut out = Ball::zero(128);
        // SAFETY: both initialised; `third` is not changed while it is read.
        let doubled = unsafe { Ball::read_in_place(third.as_raw(), 128, |x| x.clone() + x) };
        // SAFETY: initialised.
        unsafe { doubled.move_into(&mut out.raw) };
        let exact_third: Float = Float::with_val(1024, 1) / 3;
        assert!(out.contains(&(exact_third.clone() * 2)));
        assert!(third.contains(&exact_third));
    }

    #[test]
    fn overlapping_comparisons_are_counted() {
        let a = ball("1", 64);
        let b = ball("0.1", 64) * &a.int(10);
        let ((), doubts) = watch(|| {
            assert!(!a.lt(&b) && !a.ge(&b));
        });
        assert_eq!(doubts.undecided_comparisons, 2);
        let ((), doubts) = watch(|| assert!(a < a.int(2) && a.int(2) >= a));
        assert!(doubts.none());
    }
}
