//! A periodic load path and how it is read: harmonics `k,P_cos,P_sin,Q_cos,Q_sin`, or one
//! period of equally spaced samples `P,Q` taken as their trigonometric interpolant.

use crate::compliance::AdmissibilityError;
use crate::decimal::decimal;
use crate::doubts::if_decided;
use crate::quad::QuadError;
use crate::real::{Precision, Real};

/// The most harmonics a path may have (k ≤ 64).
pub const MAX_HARMONICS: usize = 64;

/// The most samples a sampled path may have.
pub const MAX_SAMPLES: usize = 1_000_000;

/// How far the samples may lie from their interpolant truncated to [`MAX_HARMONICS`],
/// relative to the largest sample: beyond it the path needs more harmonics than allowed.
const TRUNCATION_TOLERANCE: f64 = 1e-10;

/// Why a path cannot be computed.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PathError {
    /// The file is not a path in the expected form.
    #[error("{0}")]
    Malformed(String),
    /// More harmonics than [`MAX_HARMONICS`].
    #[error("the path has harmonic k = {found}, beyond the limit of {MAX_HARMONICS} harmonics")]
    TooManyHarmonics {
        /// The highest harmonic found.
        found: usize,
    },
    /// More samples than [`MAX_SAMPLES`].
    #[error("the path has more than {MAX_SAMPLES} samples, the limit")]
    TooManySamples,
    /// Samples whose interpolant has significant harmonics beyond [`MAX_HARMONICS`].
    #[error(
        "the samples differ from their first {MAX_HARMONICS} harmonics by {deviation:.1e} of the largest load: the path needs more than the limit of {MAX_HARMONICS} harmonics"
    )]
    NeedsMoreHarmonics {
        /// The largest deviation, relative to the largest sample.
        deviation: f64,
    },
    /// P ≤ 0 somewhere.
    #[error("the contact separates: P = {load:e} ≤ 0 at θ = {theta:.6} rad; the normal load must stay positive")]
    Separation {
        /// The angle of the lowest normal load.
        theta: f64,
        /// The lowest normal load.
        load: f64,
    },
    /// |Q| ≥ fP somewhere: gross slip under force driving.
    #[error(
        "gross slip: {sign}Q − fP = {excess:e} ≥ 0 at θ = {theta:.6} rad; force driving needs |Q| < fP throughout"
    )]
    GrossSlip {
        /// The angle where the friction limit is exceeded most.
        theta: f64,
        /// `+` or `−`.
        sign: &'static str,
        /// The excess ±Q − fP there.
        excess: f64,
    },
    /// Displacement driving with a normal load that varies.
    #[error(
        "displacement driving needs a constant normal load, but P has harmonic k = {harmonic}: give P's harmonics k ≥ 1 as 0, drive by force (Q), or simulate it with `microslip simulate --drive displacement`, which follows a varying P"
    )]
    VaryingNormalLoad {
        /// The first harmonic k ≥ 1 of P that is not zero.
        harmonic: usize,
    },
    /// f or λ out of range.
    #[error("{0}")]
    Contact(String),
    /// The compliance is not physical over the loads of the path.
    #[error(transparent)]
    Compliance(#[from] AdmissibilityError),
    /// The integrals did not converge.
    #[error(transparent)]
    Quadrature(#[from] QuadError),
}

impl PathError {
    /// Whether it is a boundary of the theory (separation, gross slip, f or λ), which
    /// the path's decimals decide exactly and a rounded copy of them may cross.
    pub fn is_boundary(&self) -> bool {
        matches!(
            self,
            PathError::Separation { .. } | PathError::GrossSlip { .. } | PathError::Contact(_)
        )
    }
}

/// Σₖ cₖ cos kθ + sₖ sin kθ, k = 0 … K (s₀ unused).
#[derive(Clone, Debug, PartialEq)]
pub struct TrigPoly<R> {
    /// cₖ.
    pub cos: Vec<R>,
    /// sₖ.
    pub sin: Vec<R>,
}

/// cos kθ and sin kθ for k = 0 … K at one θ.
pub struct Multiples<R> {
    cos: Vec<R>,
    sin: Vec<R>,
}

impl<R: Real> Multiples<R> {
    /// cos kθ.
    pub fn cos(&self, k: usize) -> R {
        self.cos[k].clone()
    }

    /// sin kθ.
    pub fn sin(&self, k: usize) -> R {
        self.sin[k].clone()
    }

    /// The multiples of θ up to `highest`, by the angle-addition recurrence.
    pub fn of(theta: &R, highest: usize) -> Self {
        let (s1, c1) = theta.sin_cos();
        let mut cos = vec![theta.int(1)];
        let mut sin = vec![theta.int(0)];
        for k in 1..=highest {
            let (c, s): (R, R) = (cos[k - 1].clone(), sin[k - 1].clone());
            cos.push(c.clone() * &c1 - s.clone() * &s1);
            sin.push(s * &c1 + c * &s1);
        }
        Multiples { cos, sin }
    }
}

/// sinc z = sin z / z and its derivative (z cos z − sin z)/z², given sin z and cos z.
/// Where z lies in the square |Re z|, |Im z| ≤ m ≤ 1 (both are analytic at 0, where the
/// quotients are not) by their Taylor series to the precision's ε, each tail enclosed in
/// a square of twice its first term's bound at |w| ≤ √2·m, where the terms fall at least
/// fourfold.
fn sinc_and_rate<R: Real>(z: &R, sin: &R, cos: &R) -> (R, R) {
    let reach = z.centred_square();
    let most = match reach.real_span() {
        Some((_, most)) => most,
        None => z.abs().to_f64_lossy(),
    };
    if most.is_nan() || most > 1.0 {
        return (sin.clone() / z, (z.clone() * cos - sin) / &z.square());
    }
    if most == 0.0 {
        return (z.int(1), z.int(0));
    }
    // log2 of a bound of |w|² on the square.
    let log2_square = (2.0 * most * most).log2() + 1e-9;
    let goal = -f64::from(z.precision().in_bits()) - 10.0;
    let square = z.square();
    let (mut sinc, mut rate) = (z.int(1), z.int(0));
    // (−1)^j z^(2j)/(2j+1)!, and (−1)^j z^(2j−1)/(2j+1)!, whose 2j-fold is the rate's term.
    let (mut term, mut odd) = (z.int(1), z.int(0));
    // log2 (2j+1)!.
    let mut log2_factorial = 0.0;
    let mut j: i64 = 0;
    loop {
        let next = j + 1;
        let grows = ((2 * next) * (2 * next + 1)) as f64;
        if next as f64 * log2_square - (log2_factorial + grows.log2()) < goal || next > MOST_SINC_TERMS {
            break;
        }
        let divisor = z.int((2 * next) * (2 * next + 1));
        term = -(term * &square) / &divisor;
        odd = if next == 1 {
            -(z.clone() / &divisor)
        } else {
            -(odd * &square) / &divisor
        };
        sinc += &term;
        rate += &(odd.clone() * &z.int(2 * next));
        log2_factorial += grows.log2();
        j = next;
    }
    // The tails from N = j + 1 on: 2·|w|^(2N)/(2N+1)! and 2·2N·|w|^(2N−1)/(2N+1)!, each
    // as a square about zero (the unit square, doubled for the rounding of m).
    let n = (j + 1) as f64;
    let log2_tail_factorial = log2_factorial + ((2.0 * n) * (2.0 * n + 1.0)).log2();
    let unit = reach / &R::from_f64(most, z.precision());
    let bound = |log2: f64| {
        unit.clone()
            .times_power_of_two((log2 + 2.0).ceil().clamp(-1e9, 1e9) as i32)
    };
    sinc += &bound(1.0 + n * log2_square - log2_tail_factorial);
    rate += &bound(1.0 + (2.0 * n).log2() + (n - 0.5) * log2_square - log2_tail_factorial);
    (sinc, rate)
}

/// The most terms of a sinc series: enough for 2^−1000000 at |z| ≤ 1.
const MOST_SINC_TERMS: i64 = 60_000;

impl<R: Real> TrigPoly<R> {
    /// The zero polynomial with harmonics up to `highest`.
    pub fn zero(highest: usize, like: &R) -> Self {
        TrigPoly {
            cos: vec![like.int(0); highest + 1],
            sin: vec![like.int(0); highest + 1],
        }
    }

    /// The highest harmonic K.
    pub fn highest(&self) -> usize {
        self.cos.len() - 1
    }

    /// The value at the angle whose multiples are given.
    pub fn at(&self, multiples: &Multiples<R>) -> R {
        let mut sum = self.cos[0].clone();
        for k in 1..self.cos.len() {
            sum += self.cos[k].clone() * &multiples.cos[k] + self.sin[k].clone() * &multiples.sin[k];
        }
        sum
    }

    /// The value at θ.
    pub fn value(&self, theta: &R) -> R {
        self.at(&Multiples::of(theta, self.highest()))
    }

    /// d/dθ.
    pub fn derivative(&self) -> Self {
        let mut result = TrigPoly::zero(self.highest(), &self.cos[0]);
        for k in 1..self.cos.len() {
            let kk = self.cos[0].int(k as i64);
            result.cos[k] = self.sin[k].clone() * &kk;
            result.sin[k] = -(self.cos[k].clone() * &kk);
        }
        result
    }

    /// The divided difference D(a, b) = (p(a) − p(b))/(a − b) and its derivative in a,
    /// analytic in both, a = b included (D(a, a) = p'(a)): with σ = (a + b)/2 and
    /// δ = (a − b)/2, D = Σ k·sinc(kδ)·(s_k cos kσ − c_k sin kσ). Where p(a) = p(b) has a
    /// root a other than b near a turning point of p, D has a simple one, which Krawczyk's
    /// test encloses where p' vanishes beside it.
    pub fn divided_difference(&self, a: &R, b: &R) -> (R, R) {
        let half = a.ratio(1, 2);
        let (middle, offset) = ((a.clone() + b) * &half, (a.clone() - b) * &half);
        let highest = self.highest();
        let (around, apart) = (Multiples::of(&middle, highest), Multiples::of(&offset, highest));
        let mut value = a.int(0);
        let mut rate = a.int(0);
        for k in 1..=highest {
            let factor = a.int(k as i64);
            let (sinc, sinc_rate) = sinc_and_rate(&(offset.clone() * &factor), &apart.sin(k), &apart.cos(k));
            let along = self.sin[k].clone() * &around.cos(k) - &(self.cos[k].clone() * &around.sin(k));
            let along_rate =
                -(self.cos[k].clone() * &around.cos(k) + &(self.sin[k].clone() * &around.sin(k))) * &factor;
            value += &(sinc.clone() * &along * &factor);
            rate += &((sinc_rate * &along * &factor + &(sinc * &along_rate)) * &factor * &half);
        }
        (value, rate)
    }

    /// `self + sign · other` (same highest harmonic).
    pub fn combined(&self, other: &Self, sign: i64) -> Self {
        let weight = self.cos[0].int(sign);
        let mix = |a: &[R], b: &[R]| {
            a.iter()
                .zip(b)
                .map(|(x, y)| x.clone() + &(y.clone() * &weight))
                .collect()
        };
        TrigPoly {
            cos: mix(&self.cos, &other.cos),
            sin: mix(&self.sin, &other.sin),
        }
    }

    /// `self` times a constant.
    pub fn scaled(&self, factor: &R) -> Self {
        TrigPoly {
            cos: self.cos.iter().map(|c| c.clone() * factor).collect(),
            sin: self.sin.iter().map(|s| s.clone() * factor).collect(),
        }
    }

    /// Whether every coefficient but the constant is zero.
    pub fn is_constant(&self) -> bool {
        let zero = self.cos[0].int(0);
        self.cos[1..].iter().chain(&self.sin[1..]).all(|c| *c == zero)
    }

    /// The polynomial at θ + shift (a time shift of the path).
    pub fn shifted(&self, shift: &R) -> Self {
        let multiples = Multiples::of(shift, self.highest());
        let mut result = self.clone();
        for k in 1..self.cos.len() {
            let (c, s) = (&multiples.cos[k], &multiples.sin[k]);
            // cos k(θ + δ) = cos kθ cos kδ − sin kθ sin kδ, sin k(θ + δ) = sin kθ cos kδ + cos kθ sin kδ.
            result.cos[k] = self.cos[k].clone() * c + self.sin[k].clone() * s;
            result.sin[k] = self.sin[k].clone() * c - self.cos[k].clone() * s;
        }
        result
    }
}

/// A periodic load path: the normal load P(θ) and the tangential load Q(θ).
#[derive(Clone, Debug, PartialEq)]
pub struct LoadPath<R> {
    /// P(θ).
    pub normal: TrigPoly<R>,
    /// Q(θ).
    pub tangential: TrigPoly<R>,
}

impl<R: Real> LoadPath<R> {
    /// One harmonic in each: P0 + P1 cos θ and Q0 + Q1 cos(θ − φ), the paper's cycle.
    pub fn harmonic(p0: &R, p1: &R, q0: &R, q1: &R, phase: &R) -> Self {
        let (sin, cos) = phase.sin_cos();
        let zero = p0.int(0);
        LoadPath {
            normal: TrigPoly {
                cos: vec![p0.clone(), p1.clone()],
                sin: vec![zero.clone(), zero.clone()],
            },
            tangential: TrigPoly {
                cos: vec![q0.clone(), q1.clone() * &cos],
                sin: vec![zero, q1.clone() * &sin],
            },
        }
    }

    /// The highest harmonic of either load.
    pub fn highest(&self) -> usize {
        self.normal.highest()
    }
}

/// The cells of one CSV line, trimmed, with its 1-based line number; blank lines and
/// lines starting with `#` are skipped.
fn records(text: &str) -> impl Iterator<Item = (usize, Vec<&str>)> {
    text.lines()
        .enumerate()
        .map(|(i, line)| (i + 1, line.trim()))
        .filter(|(_, line)| !line.is_empty() && !line.starts_with('#'))
        .map(|(n, line)| (n, line.split(',').map(str::trim).collect()))
}

/// The positions of the named columns in a header line.
fn columns(header: &[&str], line: usize, names: &[&str]) -> Result<Vec<usize>, PathError> {
    names
        .iter()
        .map(|name| {
            header.iter().position(|cell| cell == name).ok_or_else(|| {
                PathError::Malformed(format!(
                    "line {line}: the header lacks the column {name} (expected {})",
                    names.join(",")
                ))
            })
        })
        .collect()
}

fn number<R: Real>(cells: &[&str], at: usize, line: usize, name: &str, precision: Precision) -> Result<R, PathError> {
    let text = cells.get(at).copied().unwrap_or("");
    let value = R::parse_decimal(text, precision)
        .map_err(|_| PathError::Malformed(format!("line {line}: {name} = '{text}' is not a decimal number")))?;
    if value.is_finite() {
        Ok(value)
    } else {
        Err(PathError::Malformed(format!(
            "line {line}: {name} = '{text}' is not finite"
        )))
    }
}

/// What the file prescribes besides P: the tangential load Q (force driving) or the
/// tangential displacement u (displacement driving).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Drive {
    /// Q(θ) is given; u follows.
    #[default]
    Force,
    /// u(θ) is given (in the units of the outputs' u, λ f times the approach); Q follows.
    Displacement,
}

impl Drive {
    /// The name of the prescribed tangential quantity's column: `Q` or `u`.
    pub fn column(self) -> &'static str {
        match self {
            Drive::Force => "Q",
            Drive::Displacement => "u",
        }
    }

    /// `force` or `displacement`, as `--drive` and the JSON name it.
    pub fn name(self) -> &'static str {
        match self {
            Drive::Force => "force",
            Drive::Displacement => "displacement",
        }
    }
}

/// A path from CSV text with the header `k,P_cos,P_sin,Q_cos,Q_sin` (any order), one line
/// per harmonic k (0 … 64, each at most once, missing ones zero), read exactly at `precision`.
pub fn read_harmonics<R: Real>(text: &str, precision: Precision) -> Result<LoadPath<R>, PathError> {
    read_driven_harmonics(text, precision, Drive::Force)
}

/// [`read_harmonics`], with the columns `u_cos,u_sin` in place of `Q_cos,Q_sin` under
/// displacement driving (the path's `tangential` then holds u).
pub fn read_driven_harmonics<R: Real>(
    text: &str,
    precision: Precision,
    drive: Drive,
) -> Result<LoadPath<R>, PathError> {
    let (cos_name, sin_name) = match drive {
        Drive::Force => ("Q_cos", "Q_sin"),
        Drive::Displacement => ("u_cos", "u_sin"),
    };
    let names = ["k", "P_cos", "P_sin", cos_name, sin_name];
    let mut lines = records(text);
    let (header_line, header) = lines
        .next()
        .ok_or_else(|| PathError::Malformed(format!("the file is empty; expected the header {}", names.join(","))))?;
    let at = columns(&header, header_line, &names)?;
    let zero = R::from_i64(0, precision);
    let mut rows: Vec<(usize, [R; 4])> = Vec::new();
    for (line, cells) in lines {
        let k_text = cells.get(at[0]).copied().unwrap_or("");
        let k: usize = k_text
            .parse()
            .map_err(|_| PathError::Malformed(format!("line {line}: k = '{k_text}' is not a whole number ≥ 0")))?;
        if k > MAX_HARMONICS {
            return Err(PathError::TooManyHarmonics { found: k });
        }
        if rows.iter().any(|(seen, _)| *seen == k) {
            return Err(PathError::Malformed(format!(
                "line {line}: harmonic k = {k} is given twice"
            )));
        }
        let value = |i: usize| number::<R>(&cells, at[i], line, names[i], precision);
        rows.push((k, [value(1)?, value(2)?, value(3)?, value(4)?]));
    }
    if rows.is_empty() {
        return Err(PathError::Malformed(
            "the file has a header but no harmonics".to_string(),
        ));
    }
    let highest = rows.iter().map(|(k, _)| *k).max().unwrap_or(0).max(1);
    let mut path = LoadPath {
        normal: TrigPoly::zero(highest, &zero),
        tangential: TrigPoly::zero(highest, &zero),
    };
    for (k, [p_cos, p_sin, q_cos, q_sin]) in rows {
        path.normal.cos[k] = p_cos;
        path.tangential.cos[k] = q_cos;
        if k > 0 {
            path.normal.sin[k] = p_sin;
            path.tangential.sin[k] = q_sin;
        }
    }
    Ok(path)
}

/// A path from CSV text with the header `P,Q`, one line per sample of one period at equal
/// steps of θ from 0 (the last not repeating the first), taken as its trigonometric
/// interpolant, read exactly at `precision`. With N samples the interpolant has harmonics
/// up to N/2 (the Nyquist term cos(Nθ/2) alone when N is even); beyond [`MAX_HARMONICS`]
/// they must vanish to 1e-10 of the largest sample.
pub fn read_samples<R: Real>(text: &str, precision: Precision) -> Result<LoadPath<R>, PathError> {
    read_driven_samples(text, precision, Drive::Force)
}

/// [`read_samples`], with a column `u` in place of `Q` under displacement driving (the
/// path's `tangential` then holds u).
pub fn read_driven_samples<R: Real>(text: &str, precision: Precision, drive: Drive) -> Result<LoadPath<R>, PathError> {
    let tangential_name = drive.column();
    let mut lines = records(text);
    let (header_line, header) = lines
        .next()
        .ok_or_else(|| PathError::Malformed(format!("the file is empty; expected the header P,{tangential_name}")))?;
    let at = columns(&header, header_line, &["P", tangential_name])?;
    let mut normal = Vec::new();
    let mut tangential = Vec::new();
    // Whether every sample of a column is the first one's decimal value, exactly: the same
    // text, or (rarely) another text of the same value.
    let mut equal = [true, true];
    let mut first: Option<[String; 2]> = None;
    for (line, cells) in lines {
        if normal.len() == MAX_SAMPLES {
            return Err(PathError::TooManySamples);
        }
        normal.push(number::<R>(&cells, at[0], line, "P", precision)?);
        tangential.push(number::<R>(&cells, at[1], line, tangential_name, precision)?);
        let texts = [0, 1].map(|i| cells.get(at[i]).copied().unwrap_or("").to_string());
        let first = first.get_or_insert_with(|| texts.clone());
        for i in 0..2 {
            equal[i] = equal[i] && (texts[i] == first[i] || same_value(&texts[i], &first[i]));
        }
    }
    if normal.len() < 3 {
        return Err(PathError::Malformed(format!(
            "the path has {} samples; one period needs at least 3",
            normal.len()
        )));
    }
    Ok(LoadPath {
        normal: interpolant_of(&normal, equal[0])?,
        tangential: interpolant_of(&tangential, equal[1])?,
    })
}

/// Whether two decimals denote the same number exactly.
fn same_value(a: &str, b: &str) -> bool {
    matches!((decimal(a), decimal(b)), (Some(a), Some(b)) if a == b)
}

/// The trigonometric interpolant of N equally spaced samples, its harmonics up to
/// min(N/2, [`MAX_HARMONICS`]); refused when the samples need more.
pub fn interpolant<R: Real>(samples: &[R]) -> Result<TrigPoly<R>, PathError> {
    interpolant_of(samples, false)
}

/// [`interpolant`], the samples known `equal` (their decimals are one number) or not.
fn interpolant_of<R: Real>(samples: &[R], equal: bool) -> Result<TrigPoly<R>, PathError> {
    let n = samples.len();
    let like = &samples[0];
    let highest = (n / 2).min(MAX_HARMONICS);
    let mut poly = TrigPoly::zero(highest, like);
    // Equal samples are a constant exactly (their sums of cosines would leave rounding);
    // enclosures that overlap are not known equal by comparing them, and the sums then
    // enclose the constant.
    if equal || samples.iter().all(|sample| if_decided(|| sample == like) == Some(true)) {
        poly.cos[0] = like.clone();
        return Ok(poly);
    }
    let step = like.pi_like() * &like.int(2) / &like.int(n as i64);
    let count = like.int(n as i64);
    // cos and sin of kθ_j = 2π·(jk mod N)/N from one table of the N angles, each formed
    // once: a recurrence in k would compound its rounding (on enclosures, their widths)
    // with every harmonic.
    let table: Vec<(R, R)> = (0..n).map(|m| (step.clone() * &like.int(m as i64)).sin_cos()).collect();
    for (j, sample) in samples.iter().enumerate() {
        for k in 0..=highest {
            let (sin, cos) = &table[(j * k) % n];
            poly.cos[k] += sample.clone() * cos;
            poly.sin[k] += sample.clone() * sin;
        }
    }
    for k in 0..=highest {
        // The constant and the Nyquist term cos(Nθ/2) appear once in the sum, the others twice.
        let weight = if k == 0 || 2 * k == n {
            count.clone()
        } else {
            count.clone() / &like.int(2)
        };
        poly.cos[k] /= &weight;
        poly.sin[k] = if k == 0 || 2 * k == n {
            like.int(0)
        } else {
            poly.sin[k].clone() / &weight
        };
    }
    if highest < n / 2 {
        let deviation = truncation_deviation(samples, &poly, &table);
        if deviation > TRUNCATION_TOLERANCE {
            return Err(PathError::NeedsMoreHarmonics { deviation });
        }
    }
    Ok(poly)
}

/// The largest distance of the samples from the interpolant `poly` truncated to its
/// harmonics, relative to the largest sample, in f64 at any precision: it is compared with
/// [`TRUNCATION_TOLERANCE`], far above f64's rounding, so the verdict is the same at every
/// precision, at a fraction of the cost in enclosures or MPFR. Each value is summed from
/// `table`'s cosines and sines of the N angles, as the interpolant was.
fn truncation_deviation<R: Real>(samples: &[R], poly: &TrigPoly<R>, table: &[(R, R)]) -> f64 {
    let n = samples.len();
    let double = |x: &R| x.to_f64_lossy();
    let (cos, sin): (Vec<f64>, Vec<f64>) = (
        poly.cos.iter().map(double).collect(),
        poly.sin.iter().map(double).collect(),
    );
    let table: Vec<(f64, f64)> = table.iter().map(|(sin, cos)| (double(sin), double(cos))).collect();
    let largest = samples.iter().map(|sample| double(sample).abs()).fold(0.0, f64::max);
    let deviation = samples
        .iter()
        .enumerate()
        .map(|(j, sample)| {
            let value: f64 = (0..cos.len())
                .map(|k| {
                    let (sine, cosine) = table[(j * k) % n];
                    cos[k] * cosine + sin[k] * sine
                })
                .sum();
            (value - double(sample)).abs()
        })
        .fold(0.0, f64::max);
    deviation / largest.max(f64::MIN_POSITIVE)
}

/// Pads both loads to the same highest harmonic.
pub(crate) fn padded<R: Real>(path: &LoadPath<R>) -> LoadPath<R> {
    let highest = path.normal.highest().max(path.tangential.highest());
    let pad = |poly: &TrigPoly<R>| {
        let mut result = TrigPoly::zero(highest, &poly.cos[0]);
        result.cos[..poly.cos.len()].clone_from_slice(&poly.cos);
        result.sin[..poly.sin.len()].clone_from_slice(&poly.sin);
        result
    };
    LoadPath {
        normal: pad(&path.normal),
        tangential: pad(&path.tangential),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_of_a_two_harmonic_path_give_back_its_harmonics() {
        let path = read_harmonics::<f64>(
            "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0.1,0\n1,0.2,0.1,0.3,-0.2\n2,0.05,-0.02,0.1,0.07\n",
            Precision::DOUBLE,
        )
        .unwrap();
        for n in [5, 6, 64, 200] {
            let step = 2.0 * std::f64::consts::PI / n as f64;
            let samples: Vec<(f64, f64)> = (0..n)
                .map(|j| {
                    (
                        path.normal.value(&(step * j as f64)),
                        path.tangential.value(&(step * j as f64)),
                    )
                })
                .collect();
            let text: String = std::iter::once("P,Q\n".to_string())
                .chain(samples.iter().map(|(p, q)| format!("{p:e},{q:e}\n")))
                .collect();
            let sampled = read_samples::<f64>(&text, Precision::DOUBLE).unwrap();
            for theta in [0.1, 1.3, 4.0] {
                let (p, q) = (sampled.normal.value(&theta), sampled.tangential.value(&theta));
                assert!((p - path.normal.value(&theta)).abs() < 1e-14, "N = {n}");
                assert!((q - path.tangential.value(&theta)).abs() < 1e-14, "N = {n}");
            }
        }
    }

    #[test]
    fn the_nyquist_term_reproduces_even_samples() {
        // Four samples of P: the interpolant passes through every one.
        let text = "P,Q\n1,0\n2,0.5\n0.5,0\n3,-0.1\n";
        let path = read_samples::<f64>(text, Precision::DOUBLE).unwrap();
        for (j, p) in [1.0, 2.0, 0.5, 3.0].iter().enumerate() {
            let theta = j as f64 * std::f64::consts::FRAC_PI_2;
            assert!((path.normal.value(&theta) - p).abs() < 1e-14);
        }
    }

    #[test]
    fn limits_and_malformed_lines_are_named() {
        let too_high = read_harmonics::<f64>("k,P_cos,P_sin,Q_cos,Q_sin\n65,1,0,0,0\n", Precision::DOUBLE);
        assert_eq!(too_high, Err(PathError::TooManyHarmonics { found: 65 }));
        let bad = read_harmonics::<f64>("k,P_cos,P_sin,Q_cos,Q_sin\n0,1,x,0,0\n", Precision::DOUBLE);
        assert!(matches!(bad, Err(PathError::Malformed(m)) if m.contains("line 2") && m.contains("P_sin")));
        let header = read_samples::<f64>("P,R\n1,2\n", Precision::DOUBLE);
        assert!(matches!(header, Err(PathError::Malformed(m)) if m.contains("column Q")));
        // 400 samples of a path with a 100th harmonic.
        let text: String = std::iter::once("P,Q\n".to_string())
            .chain((0..400).map(|j| {
                format!(
                    "{},0\n",
                    1.0 + 0.1 * (100.0 * j as f64 * std::f64::consts::TAU / 400.0).cos()
                )
            }))
            .collect();
        assert!(matches!(
            read_samples::<f64>(&text, Precision::DOUBLE),
            Err(PathError::NeedsMoreHarmonics { .. })
        ));
    }

    #[test]
    fn samples_beyond_the_harmonic_limit_are_refused_alike_at_every_precision() {
        // 400 samples of 1 + 0.1 cos kθ: k = 100 lies beyond the limit of 64, k = 60 within.
        let samples = |k: f64| -> String {
            std::iter::once("P,Q\n".to_string())
                .chain((0..400).map(|j| {
                    format!(
                        "{},0\n",
                        1.0 + 0.1 * (k * j as f64 * std::f64::consts::TAU / 400.0).cos()
                    )
                }))
                .collect()
        };
        let (beyond, within) = (samples(100.0), samples(60.0));
        // The truncated interpolant is 1: the samples stray from it by 0.1 of the largest, 1.1.
        let refused = |deviation: Option<f64>| deviation.is_some_and(|d| (d - 0.1 / 1.1).abs() < 1e-9);
        let deviation = |result: Result<(), PathError>| match result {
            Err(PathError::NeedsMoreHarmonics { deviation }) => Some(deviation),
            _ => None,
        };
        let bits = Precision::bits(128);
        assert!(refused(deviation(
            read_samples::<f64>(&beyond, Precision::DOUBLE).map(|_| ())
        )));
        assert!(refused(deviation(
            read_samples::<crate::interval::Interval>(&beyond, Precision::DOUBLE).map(|_| ())
        )));
        assert!(refused(deviation(
            read_samples::<rug::Float>(&beyond, bits).map(|_| ())
        )));
        let harmonic = |path: LoadPath<f64>| path.normal.cos[60];
        assert!((harmonic(read_samples::<f64>(&within, Precision::DOUBLE).unwrap()) - 0.1).abs() < 1e-14);
        let interval = read_samples::<crate::interval::Interval>(&within, Precision::DOUBLE).unwrap();
        assert!((interval.normal.cos[60].to_f64_lossy() - 0.1).abs() < 1e-14);
        let float = read_samples::<rug::Float>(&within, bits).unwrap();
        assert!((float.normal.cos[60].to_f64_lossy() - 0.1).abs() < 1e-14);
    }
}
