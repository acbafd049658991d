//! `microslip series`: the coefficients Iₙ, or a case's partial sums beside W.

use clap::{ArgGroup, Args};

use serde::Serialize;

use microslip::answer::series::{coefficient_answers, partial_sum_answers, PartialSums};
use microslip::answer::{Answer, Provenance};
use microslip::case::CaseText;
use microslip::compliance::{spec_help, spec_summary};

use super::case::Answer as AnswerArgs;
use super::json::{printed, ShapeInputs, ValueEnvelope, ValueReport};
use super::report::Failure;
use super::series_remainder::{read_ratio, remainders, Remainders, WithinAnswer};

/// `--rho` for the coefficients Iₙ alone, or a case (`--p0 … --compliance`) for its partial sums.
#[derive(Args)]
#[command(mut_arg("digits", |digits| digits.help(
    "Significant digits (1–1000), proven by rigorous enclosures; without it, 15 proven digits (and \
     the f64 values of Iₙ beside them in JSON)"
)))]
#[command(group(ArgGroup::new("source").args(["rho", "p0"]).required(true)))]
#[command(group(ArgGroup::new("ratio").args(["lambda", "nu"])))]
pub struct SeriesArgs {
    /// ρ = Q1/(f P1) (> 0): print I₀ … I_N.
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["p0", "compliance"])]
    pub rho: Option<String>,
    /// The phase φ: radians (`1.2`), a multiple of π (`pi/2`, `3pi/4`, `0.4pi`, `π/2`), plus or minus
    /// radians (`pi-1e-6`), or degrees (`72deg`, `72°`); read exactly
    #[arg(long, allow_hyphen_values = true)]
    pub phi: String,
    /// The highest order N (with `--within`, 1 if not given).
    #[arg(long, required_unless_present = "within")]
    pub order: Option<usize>,
    /// With a case: the largest P1 (ρ = Q1/(fP1), φ, P0, Q0, f, λ and the compliance kept) at
    /// which |W − W₁| ≤ R·|W| is proven by the series' remainder bound.
    #[arg(long, value_name = "R", allow_hyphen_values = true, requires = "p0")]
    pub within: Option<String>,
    /// Mean normal load P0 (with a case).
    #[arg(long, allow_hyphen_values = true, requires_all = ["p1", "q1", "friction", "ratio", "compliance"])]
    pub p0: Option<String>,
    /// Normal load amplitude P1.
    #[arg(long, allow_hyphen_values = true)]
    pub p1: Option<String>,
    /// Mean tangential load Q0.
    #[arg(long, allow_hyphen_values = true, default_value = "0")]
    pub q0: String,
    /// Tangential load amplitude Q1.
    #[arg(long, allow_hyphen_values = true)]
    pub q1: Option<String>,
    /// Coulomb friction coefficient f.
    #[arg(long, allow_hyphen_values = true)]
    pub friction: Option<String>,
    /// Tangential/normal compliance ratio λ, in [1, 2].
    #[arg(long, allow_hyphen_values = true, conflicts_with = "nu")]
    pub lambda: Option<String>,
    /// Poisson's ratio ν.
    #[arg(long, allow_hyphen_values = true)]
    pub nu: Option<String>,
    #[arg(long, allow_hyphen_values = true, requires = "p0", help = spec_summary(), long_help = spec_help())]
    pub compliance: Option<String>,
    #[command(flatten)]
    pub answer: AnswerArgs,
}

/// Why an answer is exact, where it is.
pub fn exact_reason(answer: &Answer) -> Option<&'static str> {
    match &answer.provenance {
        Provenance::Exact(reason) => Some(reason.reason()),
        _ => None,
    }
}

/// `value   (provenance)`, as a line of text shows an answer.
pub fn shown(answer: &Answer) -> String {
    format!("{}   ({})", answer.value.decimal, answer.provenance)
}

/// `microslip series --rho … --json`.
#[derive(Serialize)]
struct SeriesReport<'a> {
    /// The fewest digits printed of any coefficient.
    digits: u32,
    /// I₀ … I_N as printed.
    coefficients: Vec<Option<String>>,
    /// I₀ … I_N in binary64 (runs without --digits).
    coefficients_f64: Option<Vec<f64>>,
    /// I₀ … I_N, each with what vouches for it.
    values: Vec<ValueReport>,
    inputs: ShapeInputs<'a>,
}

/// `microslip series` with a case `--json`: W as `dissipation --json` prints it, and the
/// partial sums W_N beside it.
#[derive(Serialize)]
struct PartialSumsReport<'a> {
    #[serde(rename = "W")]
    w: Option<String>,
    #[serde(rename = "W_f64")]
    w_f64: Option<f64>,
    #[serde(flatten)]
    envelope: ValueEnvelope,
    partial_sums: Vec<PartialSumReport>,
    /// W_N − W for N = 1 … order.
    differences: Vec<ValueReport>,
    /// W enclosed by the series alone: the tightest W_N ± its remainder bound.
    series_w: ValueReport,
    /// With `--within`.
    within: Option<WithinAnswer>,
    inputs: &'a CaseText,
}

/// A partial sum W_N with its proven bound on |W − W_N|.
#[derive(Serialize)]
struct PartialSumReport {
    #[serde(flatten)]
    value: ValueReport,
    /// An upper bound on |W − W_N|, 3 digits rounded up.
    remainder_bound: String,
    /// Whether W ≥ W_N is proven (as for a completely monotone v' at even N).
    lower_bound_of_w: bool,
}

pub fn run(args: &SeriesArgs) -> Result<String, Failure> {
    match &args.p0 {
        Some(p0) => case_series(args, p0),
        None => {
            let rho = args
                .rho
                .as_deref()
                .ok_or_else(|| Failure::refused("give --rho, or a case with --p0 … --compliance"))?;
            coefficients(args, rho)
        }
    }
}

/// `series --rho ρ --phi φ --order N`: the coefficients I₀ … I_N.
fn coefficients(args: &SeriesArgs, rho: &str) -> Result<String, Failure> {
    let order = args
        .order
        .ok_or_else(|| Failure::refused("--order is needed with --rho"))?;
    let answers = coefficient_answers(rho, &args.phi, order, args.answer.digits, args.answer.max_seconds)
        .map_err(|error| Failure::of(&error, false))?;
    if args.answer.json {
        let in_f64: Option<Vec<f64>> = answers
            .iter()
            .map(|answer| match answer.provenance {
                Provenance::Exact(_) => Some(0.0),
                _ => answer.value.binary64,
            })
            .collect();
        let report = SeriesReport {
            digits: answers.iter().map(Answer::digits).min().unwrap_or(0),
            coefficients: answers.iter().map(|a| printed(&a.value)).collect(),
            coefficients_f64: in_f64.filter(|_| args.answer.digits.is_none()),
            values: answers.iter().map(ValueReport::of).collect(),
            inputs: ShapeInputs { rho, phi: &args.phi },
        };
        return Ok(serde_json::to_string(&report)?);
    }
    let rows: Vec<String> = answers
        .iter()
        .enumerate()
        .map(|(n, answer)| format!("I_{n:<3} = {}", shown(answer)))
        .collect();
    Ok(format!(
        "Iₙ(ρ = {rho}, φ = {}), n = 0 … {}:\n{}",
        args.phi,
        order,
        rows.join("\n")
    ))
}

/// `series` of a case: W, the partial sums W_N with their proven remainder bounds, and
/// with `--within R` the largest P1 at which the cubic law is proven within R.
fn case_series(args: &SeriesArgs, p0: &str) -> Result<String, Failure> {
    let missing = || Failure::refused("a case needs --p0, --p1, --q1, --friction, --lambda or --nu, and --compliance");
    let case = CaseText {
        p0: p0.to_string(),
        p1: args.p1.clone().ok_or_else(missing)?,
        q0: args.q0.clone(),
        q1: args.q1.clone().ok_or_else(missing)?,
        phi: args.phi.clone(),
        friction: args.friction.clone().ok_or_else(missing)?,
        lambda: args.lambda.clone(),
        nu: args.nu.clone(),
        compliance: args.compliance.clone().ok_or_else(missing)?,
    };
    let order = args.order.unwrap_or(1);
    let ratio = args.within.as_deref().map(read_ratio).transpose()?;
    let sums = partial_sum_answers(&case, order, args.answer.digits, args.answer.max_seconds)
        .map_err(|error| Failure::of(&error, false))?;
    let all_exact = exact_reason(&sums.dissipation);
    if let (Some(reason), Some(_)) = (all_exact, ratio) {
        return Err(Failure::refused(format!(
            "W = 0 exactly here ({reason}): the cubic law is exact at every P1 and --within has nothing to bound; drop --within"
        )));
    }
    let remainders = match all_exact {
        Some(_) => None,
        None => Some(remainders(&case, order, ratio)?),
    };
    if args.answer.json {
        let report = PartialSumsReport {
            w: printed(&sums.dissipation.value),
            w_f64: sums.dissipation.value.binary64,
            envelope: ValueEnvelope::of(&sums.dissipation),
            partial_sums: sums
                .sums
                .iter()
                .enumerate()
                .map(|(n, sum)| PartialSumReport {
                    value: ValueReport::of(sum),
                    remainder_bound: remainders.as_ref().map_or("0".to_string(), |r| r.bounds[n].clone()),
                    lower_bound_of_w: remainders.as_ref().is_some_and(|r| r.from_below[n]),
                })
                .collect(),
            differences: sums.differences.iter().map(ValueReport::of).collect(),
            series_w: ValueReport::of(remainders.as_ref().map_or(&sums.dissipation, |r| &r.series_w)),
            within: remainders.as_ref().and_then(|r| r.within.clone()),
            inputs: &case,
        };
        return Ok(serde_json::to_string(&report)?);
    }
    if let Some(reason) = all_exact {
        return Ok(format!("W = 0 and W_N = 0 for N = 1 … {order} (exact: {reason})"));
    }
    Ok(partial_sums_text(&sums, remainders.as_ref(), args.within.as_deref()))
}

/// The partial sums as a table of text, with W from the series alone and the `--within`
/// line where they were asked.
fn partial_sums_text(sums: &PartialSums, remainders: Option<&Remainders>, ratio: Option<&str>) -> String {
    let width = sums
        .sums
        .iter()
        .map(|sum| sum.value.decimal.to_string().chars().count())
        .max()
        .unwrap_or(0)
        .max(24);
    let bounds = remainders.map(|r| r.bounds.clone()).unwrap_or_default();
    let mut out = format!(
        "W (four-segment) = {}\n   N  {:<width$}  {:<12}  W_N − W",
        shown(&sums.dissipation),
        "W_N (series to order N)",
        "|W − W_N| ≤"
    );
    for (n, (sum, difference)) in sums.sums.iter().zip(&sums.differences).enumerate() {
        out.push_str(&format!(
            "\n{:>4}  {:<width$}  {:<12}  {}",
            n + 1,
            sum.value.decimal.to_string(),
            bounds.get(n).map_or("", String::as_str),
            shown(difference)
        ));
    }
    let provenance = sums
        .sums
        .first()
        .map(|sum| sum.provenance.to_string())
        .unwrap_or_default();
    out.push_str(&format!("\nW_N: {provenance}"));
    if let Some(remainders) = remainders {
        let from_below: Vec<String> = (1..)
            .zip(&remainders.from_below)
            .filter(|(_, &above)| above)
            .map(|(n, _)| n.to_string())
            .collect();
        if !from_below.is_empty() {
            out.push_str(&format!(
                "\nW ≥ W_N proven for N = {}: W_N ≤ W ≤ W_N + its bound",
                from_below.join(", ")
            ));
        }
        out.push_str(&format!(
            "\nW from the series alone (the narrowest enclosure the W_N and their bounds give) = {}",
            shown(&remainders.series_w)
        ));
        if let Some(within) = &remainders.within {
            out.push_str(&within_line(within, ratio.unwrap_or_default()));
        }
    }
    out
}

/// The `--within` answer as a line of text.
fn within_line(within: &WithinAnswer, ratio: &str) -> String {
    let Some(p1) = &within.p1_max else {
        return format!(
            "\n--within {ratio}: not proven at any P1 tried (down to 1e-12 P0); the cycle leaves the theory at P1 = {}",
            within.theory_end
        );
    };
    match within.limited_by {
        "remainder" => format!(
            "\n--within {ratio}: |W − W₁| ≤ {ratio}·|W| is proven up to P1 = {p1} (ρ, φ, P0, Q0, f, λ kept); the theory ends at P1 = {}",
            within.theory_end
        ),
        limit => format!(
            "\n--within {ratio}: the cycle leaves the theory ({limit}) at P1 = {} before the bound reaches {ratio}·|W|; proven up to P1 = {p1}",
            within.theory_end
        ),
    }
}
