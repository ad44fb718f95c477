//! Every model by name: what it is, its equation, the parameters it reads, and how it is
//! built from a [`FrictionParams`].

use crate::composite::{Composite, Dahl};
use crate::gms::Gms;
use crate::lugre::LuGre;
use crate::model::{FrictionModel, Variant};
use crate::params::{FrictionParams, ParamError, Parameters};
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

/// How a model's curve is drawn (`friction-lab curve`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum CurveAxis {
    /// Force against velocity in steady sliding (Figures 2–4).
    Velocity,
    /// Force against displacement under the paper's prescribed motion (Figures 5–7).
    Displacement,
}

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

    /// The name the command line takes and prints.
    pub fn name(self) -> &'static str {
        match self {
            ModelId::Av => "AV",
            ModelId::Cs => "CS",
            ModelId::Cvs => "CVS",
            ModelId::Dv => "DV",
            ModelId::Sd => "SD",
            ModelId::Sv => "SV",
            ModelId::Coulomb => "coulomb",
            ModelId::Viscous => "viscous",
            ModelId::Static => "static",
            ModelId::Stribeck => "stribeck",
            ModelId::Dahl => "dahl",
            ModelId::Karnopp => "karnopp",
            ModelId::LuGre => "lugre",
            ModelId::LuGreVd => "lugre-vd",
            ModelId::ElastoPlastic => "elasto-plastic",
            ModelId::Gms => "gms",
        }
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
        match self {
            ModelId::Av => "adhesion (static) + viscous + Stribeck",
            ModelId::Cs => "Coulomb + static + Stribeck",
            ModelId::Cvs => "Coulomb + viscous + static + Stribeck",
            ModelId::Dv => "Dahl + viscous",
            ModelId::Sd => "static + Dahl",
            ModelId::Sv => "static + viscous + Dahl",
            ModelId::Coulomb => "Coulomb",
            ModelId::Viscous => "viscous",
            ModelId::Static => "Coulomb with stiction",
            ModelId::Stribeck => "Stribeck curve with stiction and viscous friction",
            ModelId::Dahl => "Dahl (1968)",
            ModelId::Karnopp => "Karnopp (1985) stick band",
            ModelId::LuGre => "LuGre (Canudas de Wit et al. 1995)",
            ModelId::LuGreVd => "LuGre with velocity-dependent damping",
            ModelId::ElastoPlastic => "elasto-plastic (Dupont et al. 2002)",
            ModelId::Gms => "generalized Maxwell-slip (Al-Bender et al. 2005)",
        }
    }

    /// The equations of the paper the model implements, or its literature source.
    pub fn source(self) -> &'static str {
        match self {
            ModelId::Av => "paper eqs. (1)-(4)",
            ModelId::Cs => "paper eqs. (5)-(6)",
            ModelId::Cvs => "paper eq. (7)",
            ModelId::Dv => "paper eqs. (8)-(9)",
            ModelId::Sd => "paper eq. (10)",
            ModelId::Sv => "paper eq. (11)",
            ModelId::Coulomb | ModelId::Viscous => "classical term",
            ModelId::Static => "classical stiction model (Armstrong-Helouvry et al. 1994)",
            ModelId::Stribeck => "Armstrong-Helouvry et al. (1994), Olsson et al. (1998)",
            ModelId::Dahl => "Dahl (1968, 1976)",
            ModelId::Karnopp => "Karnopp (1985)",
            ModelId::LuGre => "Canudas de Wit, Olsson, Astrom, Lischinsky (1995)",
            ModelId::LuGreVd => {
                "Canudas de Wit et al. (1995) eq. (10); Olsson, Astrom, Canudas de Wit, Gafvert, Lischinsky (1998)"
            }
            ModelId::ElastoPlastic => "Dupont, Hayward, Armstrong, Altpeter (2002), IEEE TAC 47(5)",
            ModelId::Gms => "Al-Bender, Lampaert, Swevers (2005), IEEE TAC 50(11)",
        }
    }

    /// The model's equation as implemented, in plain text, for the given variant.
    pub fn equation(self, variant: Variant) -> &'static str {
        let printed = variant == Variant::Printed;
        match self {
            ModelId::Av if printed => "F = F_s + mu_v*v + S(v); at rest F in [F_s - C2, F_s + C1]",
            ModelId::Av => "F = F_s*sign(v) + mu_v*v + S(v); at rest F in [-(F_s + C2), F_s + C1]",
            ModelId::Cs => "F = F_c*sign(v) + S(v); at rest |F| <= F_s",
            ModelId::Cvs => "F = F_c*sign(v) + mu_v*v + S(v); at rest |F| <= F_s",
            ModelId::Dv => "F = mu_v*v + z, dz/dt = sigma*(v - |v|*z/F_c); at rest F = z",
            ModelId::Sd if printed => "F = F_s + z, dz/dt = sigma*(v - |v|*z/F_c); at rest F = F_s + z",
            ModelId::Sd => "F = F_s*sign(v) + z, dz/dt = sigma*(v - |v|*z/F_c); at rest F in [z - F_s, z + F_s]",
            ModelId::Sv if printed => "F = F_s + mu_v*v + z, dz/dt = sigma*(v - |v|*z/F_c); at rest F = F_s + z",
            ModelId::Sv => "F = F_s*sign(v) + mu_v*v + z, dz/dt = sigma*(v - |v|*z/F_c); at rest F in [z - F_s, z + F_s]",
            ModelId::Coulomb => "F = F_c*sign(v); at rest |F| <= F_c",
            ModelId::Viscous => "F = mu_v*v",
            ModelId::Static => "F = F_c*sign(v); at rest |F| <= F_s",
            ModelId::Stribeck => "F = (F_c + (F_s - F_c)*exp(-(v/v_s)^2))*sign(v) + mu_v*v; at rest |F| <= F_s",
            ModelId::Dahl => "F = z, dz/dt = sigma*(v - |v|*z/F_c)",
            ModelId::Karnopp => "F = F_c*sign(v) + mu_v*v for |v| >= dv; F = clamp(F_applied, -F_s, F_s) for |v| < dv",
            ModelId::LuGre => "F = sigma0*z + sigma1*dz/dt + sigma2*v, dz/dt = v - sigma0*|v|*z/g(v), g(v) = F_c + (F_s - F_c)*exp(-(v/v_s)^2)",
            ModelId::LuGreVd => "F = sigma0*z + sigma1*exp(-(v/v_d)^2)*dz/dt + sigma2*v, dz/dt = v - sigma0*|v|*z/g(v), g(v) = F_c + (F_s - F_c)*exp(-(v/v_s)^2)",
            ModelId::ElastoPlastic => "F = sigma0*z + sigma1*dz/dt + sigma2*v, dz/dt = v - alpha(z,v)*sigma0*|v|*z/g(v); alpha = 0 for |z| <= z_ba = r_ba*min(F_c, F_s)/sigma0 or sign(z) != sign(v), 1 for |z| >= z_max = g(v)/sigma0, sin ramp between",
            ModelId::Gms => "F = sum_i (k_i*z_i + sigma_i*dz_i/dt) + sigma2*v, dz_i/dt = sign(v)*min(|v|, (C/k_i)*(alpha_i - k_i*z_i*sign(v)/g(v))), k_i = sigma0/n, alpha_i = (2i-1)/n^2, sigma_i = sigma1/n, n = n_gms, C = C_gms",
        }
    }

    /// Whether the printed form differs from the sign-consistent one (AV, SD, SV).
    pub fn has_printed_form(self) -> bool {
        matches!(self, ModelId::Av | ModelId::Sd | ModelId::Sv)
    }

    /// The parameters the model reads.
    pub fn parameters(self) -> &'static [&'static str] {
        match self {
            ModelId::Av => &["F_s", "mu_v", "C1", "C2", "v_s"],
            ModelId::Cs => &["F_c", "F_s", "C1", "C2", "v_s"],
            ModelId::Cvs => &["F_c", "F_s", "mu_v", "C1", "C2", "v_s"],
            ModelId::Dv => &["mu_v", "sigma", "F_c"],
            ModelId::Sd => &["F_s", "sigma", "F_c"],
            ModelId::Sv => &["F_s", "mu_v", "sigma", "F_c"],
            ModelId::Coulomb => &["F_c"],
            ModelId::Viscous => &["mu_v"],
            ModelId::Static => &["F_c", "F_s"],
            ModelId::Stribeck => &["F_c", "F_s", "mu_v", "v_s"],
            ModelId::Dahl => &["sigma", "F_c"],
            ModelId::Karnopp => &["F_c", "F_s", "mu_v", "dv"],
            ModelId::LuGre => &["sigma0", "sigma1", "sigma2", "F_c", "F_s", "v_s"],
            ModelId::LuGreVd => &["sigma0", "sigma1", "sigma2", "F_c", "F_s", "v_s", "v_d"],
            ModelId::ElastoPlastic => &["sigma0", "sigma1", "sigma2", "F_c", "F_s", "v_s", "r_ba"],
            ModelId::Gms => &[
                "sigma0", "sigma1", "sigma2", "F_c", "F_s", "v_s", "n_gms", "C_gms",
            ],
        }
    }

    /// How the model's curve is drawn: Dahl-type models against displacement, the rest
    /// against velocity (LuGre in steady sliding).
    pub fn curve_axis(self) -> CurveAxis {
        match self {
            ModelId::Dv | ModelId::Sd | ModelId::Sv | ModelId::Dahl => CurveAxis::Displacement,
            _ => CurveAxis::Velocity,
        }
    }

    /// Builds the model from validated parameters.
    pub fn build(
        self,
        variant: Variant,
        p: &FrictionParams,
    ) -> Result<Box<dyn FrictionModel>, ParamError> {
        p.validate()?;
        let signed = variant == Variant::Odd;
        let dahl = Some(Dahl {
            sigma: p.sigma,
            f_c: p.f_c,
        });
        let base = Composite {
            v_s: p.v_s,
            ..Composite::empty(self)
        };
        let model = match self {
            ModelId::Av => Composite {
                static_level: p.f_s,
                static_signed: signed,
                viscous: p.mu_v,
                stribeck: (p.c1, p.c2),
                ..base
            },
            ModelId::Cs | ModelId::Cvs => Composite {
                coulomb: p.f_c,
                viscous: if self == ModelId::Cvs { p.mu_v } else { 0.0 },
                stribeck: (p.c1, p.c2),
                break_away: Some(p.f_s),
                ..base
            },
            ModelId::Dv => Composite {
                viscous: p.mu_v,
                dahl,
                ..base
            },
            ModelId::Sd | ModelId::Sv => Composite {
                static_level: p.f_s,
                static_signed: signed,
                viscous: if self == ModelId::Sv { p.mu_v } else { 0.0 },
                dahl,
                ..base
            },
            ModelId::Coulomb => Composite {
                coulomb: p.f_c,
                ..base
            },
            ModelId::Viscous => Composite {
                viscous: p.mu_v,
                ..base
            },
            ModelId::Static => Composite {
                coulomb: p.f_c,
                break_away: Some(p.f_s),
                ..base
            },
            ModelId::Stribeck => Composite {
                coulomb: p.f_c,
                viscous: p.mu_v,
                stribeck: (p.f_s - p.f_c, p.f_s - p.f_c),
                ..base
            },
            ModelId::Dahl => Composite { dahl, ..base },
            ModelId::Karnopp => Composite {
                coulomb: p.f_c,
                viscous: p.mu_v,
                break_away: Some(p.f_s),
                band: p.dv,
                ..base
            },
            ModelId::LuGre | ModelId::LuGreVd | ModelId::ElastoPlastic | ModelId::Gms => {
                if p.f_s <= 0.0 {
                    return Err(ParamError::Invalid {
                        name: "F_s".into(),
                        value: p.f_s,
                        reason: format!(
                            "{} divides by g(v) = F_c + (F_s - F_c)*exp(-(v/v_s)^2), \
                             which needs F_s in (0, inf) N",
                            self.name()
                        ),
                    });
                }
                if self == ModelId::Gms {
                    return gms(p);
                }
                return Ok(Box::new(LuGre {
                    id: self,
                    sigma0: p.sigma0,
                    sigma1: p.sigma1,
                    sigma2: p.sigma2,
                    f_c: p.f_c,
                    f_s: p.f_s,
                    v_s: p.v_s,
                    damping_decay: (self == ModelId::LuGreVd).then_some(p.v_d),
                    // z_ba below z_max = g(v)/σ0 at every v: a fraction of min(F_c, F_s)/σ0.
                    break_away: (self == ModelId::ElastoPlastic)
                        .then_some(p.r_ba * p.f_c.min(p.f_s) / p.sigma0),
                }));
            }
        };
        Ok(Box::new(model))
    }
}

/// GMS from the parameters: `n_gms` must be a whole number of blocks.
fn gms(p: &FrictionParams) -> Result<Box<dyn FrictionModel>, ParamError> {
    if p.n_gms.fract() != 0.0 {
        return Err(ParamError::Invalid {
            name: "n_gms".into(),
            value: p.n_gms,
            reason: "the number of slip blocks must be a whole number in [1, 16]".into(),
        });
    }
    Ok(Box::new(Gms {
        blocks: Gms::blocks(p.n_gms as usize, p.sigma0, p.sigma1),
        attraction: p.c_gms,
        sigma2: p.sigma2,
        f_c: p.f_c,
        f_s: p.f_s,
        v_s: p.v_s,
    }))
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
