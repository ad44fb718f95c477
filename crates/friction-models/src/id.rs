//! The models of friction-lab by name: what each is, its equation and the parameters it
//! reads ([`Entry`]), one entry per model, so that a model is described in one place. How a
//! model is built from its parameters is [`crate::catalog`].

use crate::model::{CurveAxis, Variant};
use serde::Serialize;
use std::fmt;

/// The models of friction-lab: the paper's six, then the reference models.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub enum ModelId {
    /// Adhesion (static) + viscous + Stribeck, eqs. (1)–(4).
    Av,
    /// Coulomb + static + Stribeck, eqs. (5)–(6).
    Cs,
    /// Coulomb + viscous + static + Stribeck, eq. (7).
    Cvs,
    /// Dahl + viscous, eq. (8).
    Dv,
    /// Static + Dahl, eq. (10).
    Sd,
    /// Static + viscous + Dahl, eq. (11).
    Sv,
    /// Coulomb friction alone.
    Coulomb,
    /// Viscous friction alone.
    Viscous,
    /// Coulomb friction with stiction (break-away at F_s).
    Static,
    /// The classical Stribeck curve with stiction and viscous friction.
    Stribeck,
    /// Dahl's model alone.
    Dahl,
    /// Karnopp's stick-band model.
    Karnopp,
    /// The LuGre model.
    LuGre,
    /// LuGre with velocity-dependent damping σ1·exp(−(v/v_d)²).
    LuGreVd,
    /// The elasto-plastic model of Dupont et al. (2002).
    ElastoPlastic,
    /// The generalized Maxwell-slip model of Al-Bender, Lampaert and Swevers (2005).
    Gms,
}

/// What the catalog knows of one model: the text every listing, figure and file prints, and
/// how its curve is drawn. One entry per model, in the order of [`ModelId::ALL`] (the enum's
/// declaration order), so that a model is described in one place.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Entry {
    /// The name the command line takes and prints.
    pub name: &'static str,
    /// What the model combines, in words.
    pub title: &'static str,
    /// The equations of the paper the model implements, or its literature source.
    pub source: &'static str,
    /// The model's equation as implemented, in plain text (the `odd` reading).
    pub equation: &'static str,
    /// The equation exactly as printed, for the models whose printed form differs.
    pub printed: Option<&'static str>,
    /// The parameters the model reads.
    pub parameters: &'static [&'static str],
    /// How the model's curve is drawn.
    pub axis: CurveAxis,
}

/// The catalog, indexed by `ModelId as usize`.
const ENTRIES: [Entry; 16] = [
    // ModelId::Av
    Entry {
        name: "AV",
        title: "adhesion (static) + viscous + Stribeck",
        source: "paper eqs. (1)-(4)",
        equation: "F = F_s*sign(v) + mu_v*v + S(v); at rest F in [-(F_s + C2), F_s + C1]",
        printed: Some("F = F_s + mu_v*v + S(v); at rest F in [F_s - C2, F_s + C1]"),
        parameters: &["F_s", "mu_v", "C1", "C2", "v_s"],
        axis: CurveAxis::Velocity,
    },
    // ModelId::Cs
    Entry {
        name: "CS",
        title: "Coulomb + static + Stribeck",
        source: "paper eqs. (5)-(6)",
        equation: "F = F_c*sign(v) + S(v); at rest |F| <= F_s",
        printed: None,
        parameters: &["F_c", "F_s", "C1", "C2", "v_s"],
        axis: CurveAxis::Velocity,
    },
    // ModelId::Cvs
    Entry {
        name: "CVS",
        title: "Coulomb + viscous + static + Stribeck",
        source: "paper eq. (7)",
        equation: "F = F_c*sign(v) + mu_v*v + S(v); at rest |F| <= F_s",
        printed: None,
        parameters: &["F_c", "F_s", "mu_v", "C1", "C2", "v_s"],
        axis: CurveAxis::Velocity,
    },
    // ModelId::Dv
    Entry {
        name: "DV",
        title: "Dahl + viscous",
        source: "paper eqs. (8)-(9)",
        equation: "F = mu_v*v + z, dz/dt = sigma*(v - |v|*z/F_c); at rest F = z",
        printed: None,
        parameters: &["mu_v", "sigma", "F_c"],
        axis: CurveAxis::Displacement,
    },
    // ModelId::Sd
    Entry {
        name: "SD",
        title: "static + Dahl",
        source: "paper eq. (10)",
        equation: "F = F_s*sign(v) + z, dz/dt = sigma*(v - |v|*z/F_c); at rest F in [z - F_s, z + F_s]",
        printed: Some("F = F_s + z, dz/dt = sigma*(v - |v|*z/F_c); at rest F = F_s + z"),
        parameters: &["F_s", "sigma", "F_c"],
        axis: CurveAxis::Displacement,
    },
    // ModelId::Sv
    Entry {
        name: "SV",
        title: "static + viscous + Dahl",
        source: "paper eq. (11)",
        equation: "F = F_s*sign(v) + mu_v*v + z, dz/dt = sigma*(v - |v|*z/F_c); at rest F in [z - F_s, z + F_s]",
        printed: Some("F = F_s + mu_v*v + z, dz/dt = sigma*(v - |v|*z/F_c); at rest F = F_s + z"),
        parameters: &["F_s", "mu_v", "sigma", "F_c"],
        axis: CurveAxis::Displacement,
    },
    // ModelId::Coulomb
    Entry {
        name: "coulomb",
        title: "Coulomb",
        source: "classical term",
        equation: "F = F_c*sign(v); at rest |F| <= F_c",
        printed: None,
        parameters: &["F_c"],
        axis: CurveAxis::Velocity,
    },
    // ModelId::Viscous
    Entry {
        name: "viscous",
        title: "viscous",
        source: "classical term",
        equation: "F = mu_v*v",
        printed: None,
        parameters: &["mu_v"],
        axis: CurveAxis::Velocity,
    },
    // ModelId::Static
    Entry {
        name: "static",
        title: "Coulomb with stiction",
        source: "classical stiction model (Armstrong-Helouvry et al. 1994)",
        equation: "F = F_c*sign(v); at rest |F| <= F_s",
        printed: None,
        parameters: &["F_c", "F_s"],
        axis: CurveAxis::Velocity,
    },
    // ModelId::Stribeck
    Entry {
        name: "stribeck",
        title: "Stribeck curve with stiction and viscous friction",
        source: "Armstrong-Helouvry et al. (1994), Olsson et al. (1998)",
        equation: "F = (F_c + (F_s - F_c)*exp(-(v/v_s)^2))*sign(v) + mu_v*v; at rest |F| <= F_s",
        printed: None,
        parameters: &["F_c", "F_s", "mu_v", "v_s"],
        axis: CurveAxis::Velocity,
    },
    // ModelId::Dahl
    Entry {
        name: "dahl",
        title: "Dahl (1968)",
        source: "Dahl (1968, 1976)",
        equation: "F = z, dz/dt = sigma*(v - |v|*z/F_c)",
        printed: None,
        parameters: &["sigma", "F_c"],
        axis: CurveAxis::Displacement,
    },
    // ModelId::Karnopp
    Entry {
        name: "karnopp",
        title: "Karnopp (1985) stick band",
        source: "Karnopp (1985)",
        equation: "F = F_c*sign(v) + mu_v*v for |v| >= dv; F = clamp(F_applied, -F_s, F_s) for |v| < dv",
        printed: None,
        parameters: &["F_c", "F_s", "mu_v", "dv"],
        axis: CurveAxis::Velocity,
    },
    // ModelId::LuGre
    Entry {
        name: "lugre",
        title: "LuGre (Canudas de Wit et al. 1995)",
        source: "Canudas de Wit, Olsson, Astrom, Lischinsky (1995)",
        equation: "F = sigma0*z + sigma1*dz/dt + sigma2*v, dz/dt = v - sigma0*|v|*z/g(v), g(v) = F_c + (F_s - F_c)*exp(-(v/v_s)^2)",
        printed: None,
        parameters: &["sigma0", "sigma1", "sigma2", "F_c", "F_s", "v_s"],
        axis: CurveAxis::Velocity,
    },
    // ModelId::LuGreVd
    Entry {
        name: "lugre-vd",
        title: "LuGre with velocity-dependent damping",
        source: "Canudas de Wit et al. (1995) eq. (10); Olsson, Astrom, Canudas de Wit, Gafvert, Lischinsky (1998)",
        equation: "F = sigma0*z + sigma1*exp(-(v/v_d)^2)*dz/dt + sigma2*v, dz/dt = v - sigma0*|v|*z/g(v), g(v) = F_c + (F_s - F_c)*exp(-(v/v_s)^2)",
        printed: None,
        parameters: &["sigma0", "sigma1", "sigma2", "F_c", "F_s", "v_s", "v_d"],
        axis: CurveAxis::Velocity,
    },
    // ModelId::ElastoPlastic
    Entry {
        name: "elasto-plastic",
        title: "elasto-plastic (Dupont et al. 2002)",
        source: "Dupont, Hayward, Armstrong, Altpeter (2002), IEEE TAC 47(5)",
        equation: "F = sigma0*z + sigma1*dz/dt + sigma2*v, dz/dt = v - alpha(z,v)*sigma0*|v|*z/g(v); alpha = 0 for |z| <= z_ba = r_ba*min(F_c, F_s)/sigma0 or sign(z) != sign(v), 1 for |z| >= z_max = g(v)/sigma0, sin ramp between",
        printed: None,
        parameters: &["sigma0", "sigma1", "sigma2", "F_c", "F_s", "v_s", "r_ba"],
        axis: CurveAxis::Velocity,
    },
    // ModelId::Gms
    Entry {
        name: "gms",
        title: "generalized Maxwell-slip (Al-Bender et al. 2005)",
        source: "Al-Bender, Lampaert, Swevers (2005), IEEE TAC 50(11)",
        equation: "F = sum_i (k_i*z_i + sigma_i*dz_i/dt) + sigma2*v, dz_i/dt = sign(v)*min(|v|, (C/k_i)*(alpha_i - k_i*z_i*sign(v)/g(v))), k_i = sigma0/n, alpha_i = (2i-1)/n^2, sigma_i = sigma1/n, n = n_gms, C = C_gms",
        printed: None,
        parameters: &[
                "sigma0", "sigma1", "sigma2", "F_c", "F_s", "v_s", "n_gms", "C_gms",
            ],
        axis: CurveAxis::Velocity,
    },
];

impl ModelId {
    /// Every model, the paper's six first.
    pub const ALL: [ModelId; 16] = [
        ModelId::Av,
        ModelId::Cs,
        ModelId::Cvs,
        ModelId::Dv,
        ModelId::Sd,
        ModelId::Sv,
        ModelId::Coulomb,
        ModelId::Viscous,
        ModelId::Static,
        ModelId::Stribeck,
        ModelId::Dahl,
        ModelId::Karnopp,
        ModelId::LuGre,
        ModelId::LuGreVd,
        ModelId::ElastoPlastic,
        ModelId::Gms,
    ];

    /// The paper's six models: the first six of [`ModelId::ALL`].
    pub const PAPER: &'static [ModelId] = ModelId::ALL.split_at(6).0;

    /// The model's catalog entry.
    pub fn entry(self) -> &'static Entry {
        &ENTRIES[self as usize]
    }

    /// The name the command line takes and prints.
    pub fn name(self) -> &'static str {
        self.entry().name
    }

    /// The model called `name` (case-insensitive).
    pub fn from_name(name: &str) -> Result<ModelId, String> {
        ModelId::ALL
            .into_iter()
            .find(|m| m.name().eq_ignore_ascii_case(name))
            .ok_or_else(|| {
                let known: Vec<_> = ModelId::ALL.iter().map(|m| m.name()).collect();
                format!("unknown model `{name}`; known models: {}", known.join(", "))
            })
    }

    /// Whether the paper defines this model.
    pub fn in_paper(self) -> bool {
        ModelId::PAPER.contains(&self)
    }

    /// What the model combines, in words.
    pub fn title(self) -> &'static str {
        self.entry().title
    }

    /// The equations of the paper the model implements, or its literature source.
    pub fn source(self) -> &'static str {
        self.entry().source
    }

    /// The model's equation as implemented, in plain text, for the given variant.
    pub fn equation(self, variant: Variant) -> &'static str {
        match (variant, self.entry().printed) {
            (Variant::Printed, Some(printed)) => printed,
            _ => self.entry().equation,
        }
    }

    /// Whether the printed form differs from the sign-consistent one (AV, SD, SV).
    pub fn has_printed_form(self) -> bool {
        self.entry().printed.is_some()
    }

    /// The parameters the model reads.
    pub fn parameters(self) -> &'static [&'static str] {
        self.entry().parameters
    }

    /// `None` if the model reads parameter `name`; else the reason a value of it changes
    /// nothing: "parameter `name` is not read by model `M` (it reads: …)".
    pub fn unread(self, name: &str) -> Option<String> {
        let read = self.parameters();
        (!read.contains(&name)).then(|| {
            format!(
                "parameter `{name}` is not read by model `{self}` (it reads: {})",
                read.join(", ")
            )
        })
    }

    /// How the model's curve is drawn: Dahl-type models against displacement, the rest
    /// against velocity (LuGre, its variants and GMS in steady sliding).
    pub fn curve_axis(self) -> CurveAxis {
        self.entry().axis
    }
}

impl fmt::Display for ModelId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for ModelId {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        ModelId::from_name(s)
    }
}
