//! The families a SPEC may name, their parameters and their v': the one list the parser
//! reads its families and keys from, and that the command line's help prints.

use crate::compliance::table::TABLE_KEYS;

/// A family of the SPEC language.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Family {
    /// Its name, as written before the `:`.
    pub name: &'static str,
    /// Its keys, as written `key=value` after the `:` (a table's first is its file).
    pub keys: &'static [&'static str],
    /// Its compliance, as a formula in its keys.
    pub compliance: &'static str,
    /// A SPEC of the family, as one would write it.
    pub example: &'static str,
}

/// The family that reads a CSV table of measured data.
pub const TABLE: &str = "table";

/// Every family, in the order the help lists them.
pub const FAMILIES: [Family; 8] = [
    Family {
        name: "power",
        example: "power:c=1,beta=-1",
        keys: &["c", "beta"],
        compliance: "v' = c·P^beta",
    },
    Family {
        name: "persson",
        example: "persson:gamma=1,sigma=1",
        keys: &["gamma", "sigma"],
        compliance: "v' = gamma·sigma/P (gamma, sigma > 0)",
    },
    Family {
        name: "hertz",
        example: "hertz:r=1,estar=1",
        keys: &["r", "estar"],
        compliance: "v = (9P²/(16·r·estar²))^(1/3) (r, estar > 0)",
    },
    Family {
        name: "poly",
        example: "poly:p0=1,coeffs=2;-0.5;-0.1",
        keys: &["p0", "coeffs"],
        compliance: "v' = Σ coeffs[k]·(P − p0)^k, coeffs separated by ';'",
    },
    Family {
        name: "rational",
        example: "rational:a=0.1,b=1,c=0.5",
        keys: &["a", "b", "c"],
        compliance: "v' = a + b/(P + c)",
    },
    Family {
        name: "exp",
        example: "exp:a=1,c=1,d=0.1",
        keys: &["a", "c", "d"],
        compliance: "v' = a·exp(−P/c) + d (c > 0)",
    },
    Family {
        name: "const",
        example: "const:c=1",
        keys: &["c"],
        compliance: "v' = c",
    },
    Family {
        name: TABLE,
        example: "table:loads.csv,smoothing=1e-3",
        keys: &TABLE_KEYS,
        compliance: "v' from a CSV file with columns load and approach, or load and slope \
                     (units allowed: 'Load [N]'); smoothing=TOL (relative, default 0) fits noisy \
                     data that are not concave; never extrapolated",
    },
];

/// The names of every family.
pub fn family_names() -> [&'static str; FAMILIES.len()] {
    FAMILIES.map(|family| family.name)
}

impl Family {
    /// The family as written: `power:c=…,beta=…`, `table:FILE[,smoothing=TOL]`.
    pub fn usage(&self) -> String {
        match self.keys.split_first() {
            Some((file, options)) if self.name == TABLE => {
                let options: String = options
                    .iter()
                    .map(|key| format!("[,{key}={}]", option_value(key)))
                    .collect();
                format!("{}:{}{options}", self.name, file.to_uppercase())
            }
            _ => {
                let keys: Vec<String> = self.keys.iter().map(|key| format!("{key}=…")).collect();
                format!("{}:{}", self.name, keys.join(","))
            }
        }
    }
}

/// What a table option's value is, as the help names it.
fn option_value(key: &str) -> &'static str {
    match key {
        "smoothing" => "TOL",
        _ => "VALUE",
    }
}

/// The SPEC language for a help text: its grammar, then one line per family.
pub fn spec_help() -> String {
    let width = FAMILIES.iter().map(|f| f.usage().chars().count()).max().unwrap_or(0);
    let mut text = String::from(
        "Normal compliance SPEC: terms joined by `+`, each a family with its parameters, optionally \
         scaled (`0.5*const:c=1`); v' > 0 and v'' ≤ 0 are needed. Families:",
    );
    for family in &FAMILIES {
        let usage = family.usage();
        let pad = width - usage.chars().count();
        let example = if family.name == TABLE {
            format!("e.g. {}", family.example)
        } else {
            format!("e.g. `{}`", family.example)
        };
        text.push_str(&format!("\n  {usage}{:pad$}  {}; {example}", "", family.compliance));
    }
    text.push_str("\nExample: `persson:gamma=1,sigma=1+const:c=0.5`.");
    text
}

/// The families in brief, for a one-line help.
pub fn spec_summary() -> String {
    let names: Vec<String> = FAMILIES
        .iter()
        .map(|family| {
            if family.name == TABLE {
                Family::usage(family)
            } else {
                family.name.to_string()
            }
        })
        .collect();
    format!(
        "Normal compliance SPEC, e.g. `persson:gamma=1,sigma=1`; families {} (all parameters: --help)",
        names.join(", ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_example_is_read_by_the_parser_with_exactly_its_family_keys() {
        for family in FAMILIES.iter().filter(|family| family.name != TABLE) {
            assert!(
                super::super::ComplianceSpec::parse(family.example).is_ok(),
                "{}",
                family.example
            );
            let (name, parameters) = family.example.split_once(':').unwrap();
            let keys: Vec<&str> = parameters
                .split(',')
                .filter_map(|p| p.split_once('='))
                .map(|(k, _)| k)
                .collect();
            assert_eq!(
                (name, keys.as_slice()),
                (family.name, family.keys),
                "{}",
                family.example
            );
            // A key the family does not take is refused, naming the ones it does.
            let wrong = format!("{}:{}", family.name, "nokey=1");
            let error = super::super::ComplianceSpec::parse(&wrong).unwrap_err().to_string();
            assert!(error.contains(&family.keys.join(", ")), "{error}");
        }
    }

    #[test]
    fn usages_read_as_written() {
        assert_eq!(FAMILIES[0].usage(), "power:c=…,beta=…");
        assert_eq!(FAMILIES[7].usage(), "table:FILE[,smoothing=TOL]");
    }
}
