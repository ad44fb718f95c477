//! Named, validated parameters: the specification table every parameter set is checked
//! against, and the friction parameters with their named sets (`paper`, `lugre-1995`).

use serde::Serialize;
use std::fmt;
use thiserror::Error;

/// The allowed interval of one parameter; every bound excludes NaN, and ±∞ is never allowed.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Range {
    /// Lower bound.
    pub min: f64,
    /// Whether `min` itself is allowed.
    pub min_inclusive: bool,
    /// Upper bound (`f64::INFINITY` for none).
    pub max: f64,
    /// Whether `max` itself is allowed.
    pub max_inclusive: bool,
}

impl Range {
    /// (0, ∞): strictly positive and finite.
    pub const POSITIVE: Range = Range {
        min: 0.0,
        min_inclusive: false,
        max: f64::INFINITY,
        max_inclusive: false,
    };
    /// (0, 1): a fraction strictly between its ends.
    pub const OPEN_UNIT: Range = Range {
        min: 0.0,
        min_inclusive: false,
        max: 1.0,
        max_inclusive: false,
    };
    /// [1, 16]: the number of GMS slip blocks ([`crate::MAX_STATES`] at most).
    pub const GMS_BLOCKS: Range = Range {
        min: 1.0,
        min_inclusive: true,
        max: crate::model::MAX_STATES as f64,
        max_inclusive: true,
    };
    /// [0, ∞): non-negative and finite.
    pub const NON_NEGATIVE: Range = Range {
        min: 0.0,
        min_inclusive: true,
        max: f64::INFINITY,
        max_inclusive: false,
    };
    /// (−∞, ∞): any finite number.
    pub const FINITE: Range = Range {
        min: f64::NEG_INFINITY,
        min_inclusive: false,
        max: f64::INFINITY,
        max_inclusive: false,
    };

    /// Whether `value` lies in the range (NaN and ±∞ never do).
    pub fn contains(&self, value: f64) -> bool {
        let above = if self.min_inclusive {
            value >= self.min
        } else {
            value > self.min
        };
        let below = if self.max_inclusive {
            value <= self.max
        } else {
            value < self.max
        };
        value.is_finite() && above && below
    }
}

impl fmt::Display for Range {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let open = if self.min_inclusive { '[' } else { '(' };
        let close = if self.max_inclusive { ']' } else { ')' };
        write!(f, "{open}{}, {}{close}", show(self.min), show(self.max))
    }
}

/// `x` in the fewest digits that read back to the same double, positional between 1e-3 and
/// 1e6 (`0.0025`, `4127`) and with an exponent outside (`3.2e-6`, `8.2e82`), so that no
/// number spells out a run of zeros; `inf`, `-inf`, `NaN` as such. Every number a message,
/// a range or a table of friction-lab shows is written this way.
pub fn show(x: f64) -> String {
    if x.is_finite() && x != 0.0 && !(1e-3..1e6).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        x.to_string()
    }
}

/// ` UNIT` after a range, or nothing for a dimensionless quantity (unit `1` or none).
pub fn unit_suffix(unit: &str) -> String {
    match unit {
        "" | "1" => String::new(),
        unit => format!(" {unit}"),
    }
}

/// What is known of one parameter: its name (as `--set` takes it), unit, meaning and range.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ParamSpec {
    /// The name used by `--set`, TOML files and listings.
    pub name: &'static str,
    /// SI unit.
    pub unit: &'static str,
    /// One line on what the parameter is.
    pub meaning: &'static str,
    /// The allowed values.
    pub range: Range,
}

/// " (did you mean `NAME`?)" for the one of `known` closest to `name`, where one is close: at
/// an edit distance (Levenshtein's, letters compared without case) of at most a third of
/// `name`'s length, and at least 1 (`vbelt` → `v_belt`, `Fs` → `F_s`); else nothing, and
/// nothing for a name of one letter (every other one-letter name is one edit away).
pub fn did_you_mean<'a>(name: &str, known: impl IntoIterator<Item = &'a str>) -> String {
    let lower = name.to_lowercase();
    let allowed = match name.chars().count() {
        0 | 1 => return String::new(),
        n => (n / 3).max(1),
    };
    (known.into_iter())
        .map(|k| (edit_distance(&lower, &k.to_lowercase()), k))
        .filter(|&(d, _)| d <= allowed)
        .min_by_key(|&(d, _)| d)
        .map_or(String::new(), |(_, k)| format!(" (did you mean `{k}`?)"))
}

/// The Levenshtein distance of `a` and `b`: the fewest insertions, deletions and
/// substitutions of one character that make one the other.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let substituted = diagonal + usize::from(ca != cb);
            diagonal = row[j + 1];
            row[j + 1] = substituted.min(row[j] + 1).min(diagonal + 1);
        }
    }
    row[b.len()]
}

/// A parameter that could not be accepted.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ParamError {
    /// A name that no parameter has.
    #[error("unknown parameter `{name}`{}; known parameters: {known}", did_you_mean(name, known.split(", ")))]
    Unknown {
        /// The name given.
        name: String,
        /// The known names, comma-separated.
        known: String,
    },
    /// A value outside the parameter's range (NaN and ±∞ included).
    #[error("parameter `{name}` = {} is out of range: allowed {range}{}", show(*.value), unit_suffix(.unit))]
    OutOfRange {
        /// Parameter name.
        name: String,
        /// The rejected value.
        value: f64,
        /// The allowed range, as text.
        range: String,
        /// The parameter's unit.
        unit: String,
    },
    /// A value that is in range on its own but not for the chosen model.
    #[error("parameter `{name}` = {} is not allowed here: {reason}", show(*.value))]
    Invalid {
        /// Parameter name.
        name: String,
        /// The rejected value.
        value: f64,
        /// Why, with the allowed range.
        reason: String,
    },
    /// A named parameter set that does not exist.
    #[error("unknown parameter set `{name}`; known sets: {known}")]
    UnknownSet {
        /// The name given.
        name: String,
        /// The known set names.
        known: String,
    },
}

/// A struct of named `f64` parameters, each described by a [`ParamSpec`].
pub trait Parameters {
    /// The specification of every parameter, in listing order.
    fn specs() -> &'static [ParamSpec];
    /// The storage of the parameter called `name`, if there is one.
    fn slot(&mut self, name: &str) -> Option<&mut f64>;
    /// The value of the parameter called `name`, if there is one.
    fn value(&self, name: &str) -> Option<f64>;

    /// The specification of the parameter called `name`.
    fn spec(name: &str) -> Option<&'static ParamSpec> {
        Self::specs().iter().find(|s| s.name == name)
    }

    /// Sets one parameter after checking its range.
    fn set(&mut self, name: &str, value: f64) -> Result<(), ParamError> {
        let spec = Self::spec(name).ok_or_else(|| ParamError::Unknown {
            name: name.to_string(),
            known: Self::specs()
                .iter()
                .map(|s| s.name)
                .collect::<Vec<_>>()
                .join(", "),
        })?;
        check(spec, value)?;
        *self.slot(name).expect("every spec has a slot") = value;
        Ok(())
    }

    /// Checks every parameter against its range.
    fn validate(&self) -> Result<(), ParamError> {
        Self::specs()
            .iter()
            .try_for_each(|spec| check(spec, self.value(spec.name).expect("every spec has a slot")))
    }
}

/// Checks one value against its specification.
pub fn check(spec: &ParamSpec, value: f64) -> Result<(), ParamError> {
    if spec.range.contains(value) {
        Ok(())
    } else {
        Err(ParamError::OutOfRange {
            name: spec.name.to_string(),
            value,
            range: spec.range.to_string(),
            unit: spec.unit.to_string(),
        })
    }
}

/// Declares a struct of `f64` parameters together with its [`ParamSpec`] table, so that the
/// field, the name users type and the range are written once.
#[macro_export]
macro_rules! parameters {
    (
        $(#[$meta:meta])*
        pub struct $ty:ident {
            $( $(#[doc = $doc:literal])* $field:ident: $name:literal, $unit:literal, $range:expr, $meaning:literal; )*
        }
    ) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
        pub struct $ty {
            $( $(#[doc = $doc])* #[serde(rename = $name)] pub $field: f64, )*
        }

        impl $crate::params::Parameters for $ty {
            fn specs() -> &'static [$crate::params::ParamSpec] {
                const SPECS: &[$crate::params::ParamSpec] = &[
                    $( $crate::params::ParamSpec { name: $name, unit: $unit, meaning: $meaning, range: $range }, )*
                ];
                SPECS
            }
            fn slot(&mut self, name: &str) -> Option<&mut f64> {
                match name {
                    $( $name => Some(&mut self.$field), )*
                    _ => None,
                }
            }
            fn value(&self, name: &str) -> Option<f64> {
                match name {
                    $( $name => Some(self.$field), )*
                    _ => None,
                }
            }
        }
    };
}

parameters! {
    /// The friction parameters shared by all models (each model reads the ones it uses).
    pub struct FrictionParams {
        /// Static (break-away) level F_s = μ_s·F_N.
        f_s: "F_s", "N", Range::NON_NEGATIVE, "static (break-away) force level F_s = mu_s*F_N";
        /// Coulomb (kinetic) level F_c, also the Dahl saturation force F_fc.
        f_c: "F_c", "N", Range::POSITIVE, "Coulomb (kinetic) force level, also the Dahl saturation level";
        /// Viscous coefficient μ_v.
        mu_v: "mu_v", "N*s/m", Range::NON_NEGATIVE, "viscous coefficient";
        /// Stribeck velocity Ẋ_s.
        v_s: "v_s", "m/s", Range::POSITIVE, "Stribeck velocity";
        /// Dahl asperity stiffness σ.
        sigma: "sigma", "N/m", Range::POSITIVE, "Dahl asperity stiffness";
        /// Stribeck amplitude for v > 0.
        c1: "C1", "N", Range::NON_NEGATIVE, "Stribeck amplitude for v > 0";
        /// Stribeck amplitude for v < 0.
        c2: "C2", "N", Range::NON_NEGATIVE, "Stribeck amplitude for v < 0";
        /// LuGre bristle stiffness σ0.
        sigma0: "sigma0", "N/m", Range::POSITIVE, "LuGre bristle stiffness";
        /// LuGre bristle damping σ1.
        sigma1: "sigma1", "N*s/m", Range::NON_NEGATIVE, "LuGre bristle damping";
        /// LuGre viscous coefficient σ2.
        sigma2: "sigma2", "N*s/m", Range::NON_NEGATIVE, "LuGre viscous coefficient";
        /// Karnopp stick band half-width Δv.
        dv: "dv", "m/s", Range::POSITIVE, "Karnopp stick band half-width";
        /// Regularisation width ε of sign(v) ≈ tanh(v/ε).
        epsilon: "epsilon", "m/s", Range::POSITIVE, "regularisation width of sign(v) ~ tanh(v/epsilon)";
        /// Decay velocity v_d of LuGre's velocity-dependent damping σ1·exp(−(v/v_d)²).
        v_d: "v_d", "m/s", Range::POSITIVE, "decay velocity of LuGre's damping sigma1*exp(-(v/v_d)^2) (lugre-vd)";
        /// The elasto-plastic break-away displacement z_ba as a fraction of min(F_c, F_s)/σ0.
        r_ba: "r_ba", "1", Range::OPEN_UNIT, "elasto-plastic break-away displacement z_ba as a fraction of min(F_c, F_s)/sigma0";
        /// Number n of GMS slip blocks (an integer).
        n_gms: "n_gms", "1", Range::GMS_BLOCKS, "number of slip blocks of GMS (an integer, 1 to 16)";
        /// Attraction C of GMS's slip law dF_i/dt = sign(v)*C*(alpha_i - F_i/s(v)).
        c_gms: "C_gms", "N/s", Range::POSITIVE, "attraction of GMS's slip law dF_i/dt = sign(v)*C*(alpha_i - F_i/s(v))";
    }
}

/// The names of the named parameter sets, in listing order.
pub const PARAM_SETS: &[&str] = &["paper", "lugre-1995"];

impl FrictionParams {
    /// Table 1 of the paper, read as `docs/models.md` fixes it (F_c = 6 N, F_s = 0.75·10 N,
    /// C1 = C2 = F_s − F_c), with the LuGre values of Canudas de Wit et al. (1995).
    pub fn paper() -> Self {
        FrictionParams {
            f_s: 0.75 * 10.0,
            f_c: 6.0,
            mu_v: 0.5,
            v_s: 0.1,
            sigma: 5.0,
            c1: 1.5,
            c2: 1.5,
            sigma0: 1e5,
            sigma1: 1e5_f64.sqrt(),
            sigma2: 0.4,
            dv: 1e-3,
            epsilon: 1e-3,
            v_d: 0.1,
            r_ba: 0.5,
            n_gms: 4.0,
            c_gms: 1e4 * 7.5,
        }
    }

    /// Canudas de Wit, Olsson, Åström and Lischinsky (1995), IEEE TAC 40(3), section II:
    /// σ0 = 1e5 N/m, σ1 = √1e5 N·s/m, σ2 = 0.4 N·s/m, F_c = 1 N, F_s = 1.5 N, v_s = 1e-3 m/s.
    /// The other models read the same levels: μ_v = σ2, σ = σ0, C1 = C2 = F_s − F_c, and
    /// the widths dv and ε are a hundredth of v_s. GMS takes four blocks and C = 1e4·F_s per
    /// second (its slip law relaxes in 0.1 ms), in both sets.
    pub fn lugre_1995() -> Self {
        FrictionParams {
            f_s: 1.5,
            f_c: 1.0,
            mu_v: 0.4,
            v_s: 1e-3,
            sigma: 1e5,
            c1: 0.5,
            c2: 0.5,
            sigma0: 1e5,
            sigma1: 1e5_f64.sqrt(),
            sigma2: 0.4,
            dv: 1e-5,
            epsilon: 1e-5,
            v_d: 1e-3,
            r_ba: 0.5,
            n_gms: 4.0,
            c_gms: 1e4 * 1.5,
        }
    }

    /// The named set `name` (`paper` or `lugre-1995`).
    pub fn named(name: &str) -> Result<Self, ParamError> {
        match name {
            "paper" => Ok(Self::paper()),
            "lugre-1995" => Ok(Self::lugre_1995()),
            _ => Err(ParamError::UnknownSet {
                name: name.to_string(),
                known: PARAM_SETS.join(", "),
            }),
        }
    }
}

impl Default for FrictionParams {
    fn default() -> Self {
        Self::paper()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_back_exactly_and_never_spell_out_runs_of_zeros() {
        let cases = [
            (8.207037550189949e82, "8.207037550189949e82"),
            (3.1781835350686016e-6, "3.1781835350686016e-6"),
            (-1e-300, "-1e-300"),
            (5e-324, "5e-324"),
            (1e6, "1e6"),
            (999999.9999999999, "999999.9999999999"),
            (0.0025, "0.0025"),
            (1e-3, "0.001"),
            (9.999999999999998e-4, "9.999999999999998e-4"),
            (4127.0, "4127"),
            (0.0, "0"),
        ];
        for (x, text) in cases {
            assert_eq!(show(x), text);
            assert_eq!(show(x).parse::<f64>().unwrap().to_bits(), x.to_bits());
        }
    }

    #[test]
    fn named_sets_are_valid() {
        for name in PARAM_SETS {
            FrictionParams::named(name).unwrap().validate().unwrap();
        }
    }

    #[test]
    fn out_of_range_names_the_parameter_value_and_range() {
        let mut p = FrictionParams::paper();
        let err = p.set("v_s", 0.0).unwrap_err();
        assert_eq!(
            err.to_string(),
            "parameter `v_s` = 0 is out of range: allowed (0, inf) m/s"
        );
        assert!(p.set("mu_v", -1.0).is_err());
        assert!(p.set("F_c", f64::NAN).is_err());
        assert!(p.set("F_s", f64::INFINITY).is_err());
        assert_eq!(
            p.v_s, 0.1,
            "a rejected value leaves the parameter unchanged"
        );
    }

    #[test]
    fn unknown_parameter_lists_the_known_ones() {
        let err = FrictionParams::paper().set("mu_s", 0.7).unwrap_err();
        let text = err.to_string();
        assert!(text.starts_with("unknown parameter `mu_s`"), "{text}");
        assert!(text.contains("F_s, F_c, mu_v"), "{text}");
        // A name one edit from a known one is suggested; one far from all is not.
        let near = FrictionParams::paper()
            .set("fs", 0.7)
            .unwrap_err()
            .to_string();
        assert!(
            near.starts_with("unknown parameter `fs` (did you mean `F_s`?);"),
            "{near}"
        );
        let far = FrictionParams::paper().set("stiffness", 1.0).unwrap_err();
        assert!(!far.to_string().contains("did you mean"), "{far}");
    }

    #[test]
    fn the_closest_name_is_suggested_within_a_third_of_the_length() {
        let known = ["v_belt", "k", "c", "sigma_0"];
        assert_eq!(did_you_mean("vbelt", known), " (did you mean `v_belt`?)");
        assert_eq!(did_you_mean("Sigma0", known), " (did you mean `sigma_0`?)");
        assert_eq!(did_you_mean("mass", known), "");
        assert_eq!(did_you_mean("m", known), "");
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
    }

    #[test]
    fn unknown_set_is_rejected() {
        let err = FrictionParams::named("steel").unwrap_err();
        assert_eq!(
            err.to_string(),
            "unknown parameter set `steel`; known sets: paper, lugre-1995"
        );
    }

    #[test]
    fn every_spec_has_a_slot_with_the_paper_value() {
        let p = FrictionParams::paper();
        assert_eq!(p.value("C2"), Some(1.5));
        assert_eq!(p.value("F_s"), Some(7.5));
        assert_eq!(FrictionParams::specs().len(), 16);
        assert_eq!((p.value("v_d"), p.value("r_ba")), (Some(0.1), Some(0.5)));
    }
}
