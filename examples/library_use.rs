//! W for one load cycle, proven: the case built from numbers and exact decimals, W to the
//! 12–15 digits a rigorous enclosure of the exact value proves, then to 40.
use std::time::Duration;

use microslip::answer::dissipation::dissipation_of;
use microslip::case::CaseText;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // P = 1 + 0.4 cos θ, Q = 0.5 cos(θ − 0.4π), f = λ = 1, and Persson's v'(P) = γσ/P.
    // A case the theory does not cover (gross slip, separation, …) is refused here.
    let case = CaseText::builder()
        .p0(1)
        .p1(0.4)
        .q1(0.5)
        .phi("0.4pi")
        .friction(1)
        .lambda(1)
        .compliance("persson:gamma=1,sigma=1")
        .build()?;
    let budget = Duration::from_secs(60);
    let w = dissipation_of(&case, None, budget)?.answer;
    println!("W = {} ({})", w.value.decimal, w.provenance);
    // The exact W lies in the enclosure, every number of which rounds to the digits printed.
    let (lower, upper) = w.value.enclosure_f64().ok_or("no enclosure")?;
    assert!(lower <= upper && upper - lower < 1e-13);
    // More digits, proven the same way.
    let precise = dissipation_of(&case, Some(40), budget)?.answer;
    assert!(precise.value.decimal.to_string().starts_with("4.0624757924582385709"));
    Ok(())
}
