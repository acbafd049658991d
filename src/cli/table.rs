//! `microslip table`: Ŵ against φ for Persson's compliance (the paper's Fig. 5).

use microslip::case::{Case, CaseText};
use microslip::dissipation::{dissipation, Options};
use microslip::real::{Precision, Real};

use super::report::Failure;

pub fn run() -> Result<String, Failure> {
    let amplitudes = ["0.2", "0.4", "0.5", "0.6"];
    let mut out = String::from("Ŵ = W/(γσλf²) for v' = γσ/P, P0 = 1, P1 = 0.4, f = 1 (f64)\n   φ/π");
    for q1 in amplitudes {
        out.push_str(&format!("   Q1 = {q1:<11}"));
    }
    for tenths in 0..=10 {
        out.push_str(&format!("\n  {:>4.1}", f64::from(tenths) / 10.0));
        for q1 in amplitudes {
            let case = CaseText {
                p0: "1".into(),
                p1: "0.4".into(),
                q0: "0".into(),
                q1: q1.into(),
                phi: format!("{}pi", f64::from(tenths) / 10.0),
                friction: "1".into(),
                lambda: Some("1".into()),
                nu: None,
                compliance: "persson:gamma=1,sigma=1".into(),
            };
            let Case { cycle, compliance } = case.spec()?.at::<f64>(Precision::DOUBLE)?;
            let cell = match dissipation(&cycle, compliance.as_ref(), &Options::default()) {
                Ok(result) => result.total.to_scientific(8),
                Err(_) => "gross slip".to_string(),
            };
            out.push_str(&format!("   {cell:<16}"));
        }
    }
    Ok(out)
}
