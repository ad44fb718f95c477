//! How every model of [`ModelId`] is built from a [`FrictionParams`]: the composite models
//! as sums of the classical terms, the bristle models (LuGre, its variants, GMS) as their own
//! laws.

use crate::composite::{Composite, Dahl};
use crate::gms::Gms;
use crate::id::ModelId;
use crate::lugre::LuGre;
use crate::model::{FrictionModel, Variant};
use crate::params::{FrictionParams, ParamError, Parameters};

impl ModelId {
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
