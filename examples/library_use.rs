//! W for one load cycle in f64, and the same cycle carried exactly to 200 bits: the
//! library's code is generic over the number type.
use microslip::compliance::PowerLaw;
use microslip::cycle::{LoadCycle, ValidCycle};
use microslip::dissipation::{dissipation, Options};
use rug::Float;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // P = 1 + 0.4 cos θ, Q = 0.5 cos(θ − 0.4π), f = λ = 1, and v'(P) = 1/P (v = ln P).
    let cycle = LoadCycle {
        mean_normal_load: 1.0,
        normal_amplitude: 0.4,
        mean_tangential_load: 0.0,
        tangential_amplitude: 0.5,
        phase: 0.4 * std::f64::consts::PI,
        friction: 1.0,
        compliance_ratio: 1.0,
    };
    // Validated once; a cycle the theory does not cover is refused with the reason.
    let cycle = ValidCycle::new(cycle)?;
    let compliance = PowerLaw {
        coefficient: 1.0,
        exponent: -1.0,
    };
    let w = dissipation(&cycle, &compliance, &Options::default())?;
    println!(
        "W = {:.12e} (error estimate {:.1e}, {})",
        w.total,
        w.error_estimate,
        w.method.description()
    );

    // The same binary64 inputs at 200 bits (about 60 digits) vouch for the f64 run.
    let at_200_bits = |x: f64| Float::with_val(200, x);
    let precise = PowerLaw {
        coefficient: at_200_bits(1.0),
        exponent: at_200_bits(-1.0),
    };
    let reference = dissipation(&cycle.into_inner().map(at_200_bits), &precise, &Options::default())?;
    assert!((w.total - reference.total.to_f64()).abs() <= w.error_estimate);
    Ok(())
}
