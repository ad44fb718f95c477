//! Composite friction laws: a sum of the classical terms of [`crate::terms`].
//!
//! `F = static + F_c·sign(v) + μ_v·v + S(v) + z`, where each coefficient is zero for a term
//! the model does not have and z is the Dahl state (`ż = σ·(v − |v|·z/F_c)`). The six
//! models of the paper and the classical reference laws (Coulomb, viscous, static, Stribeck,
//! Dahl, Karnopp) are all values of this one struct; see [`crate::catalog`].

use crate::id::ModelId;
use crate::model::{
    CurveAxis, FrictionModel, Partials, StatePartials, StickInterval, StictionLevels,
};
use crate::sign::{Direction, SignLaw};
use crate::terms::{self, Term};

/// Coefficients of Dahl's law.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dahl {
    /// Asperity stiffness σ, N/m.
    pub sigma: f64,
    /// Saturation force F_c, N.
    pub f_c: f64,
}

/// A friction law built from the classical terms.
#[derive(Clone, Debug, PartialEq)]
pub struct Composite {
    /// Which model this is.
    pub id: ModelId,
    /// Level of the static term (0 without one), N.
    pub static_level: f64,
    /// Whether the static term carries sign(v) (the "odd" reading) or not (as printed).
    pub static_signed: bool,
    /// Coulomb level (0 without the term), N.
    pub coulomb: f64,
    /// Viscous coefficient (0 without the term), N·s/m.
    pub viscous: f64,
    /// Stribeck amplitudes for v > 0 and v < 0 (0 without the term), N.
    pub stribeck: (f64, f64),
    /// Stribeck velocity, m/s.
    pub v_s: f64,
    /// Dahl's law, for models with a Dahl state.
    pub dahl: Option<Dahl>,
    /// An explicit break-away level `F_b` (stick while |F − F_smooth| ≤ F_b), as eqs. (6)–(7)
    /// state it; `None` takes the one-sided limits of the force as v → 0±.
    pub break_away: Option<f64>,
    /// Half-width of a Karnopp stick band, m/s (0 for none).
    pub band: f64,
}

impl Composite {
    /// A law with no terms at all, to be filled in by the catalog.
    pub fn empty(id: ModelId) -> Self {
        Composite {
            id,
            static_level: 0.0,
            static_signed: true,
            coulomb: 0.0,
            viscous: 0.0,
            stribeck: (0.0, 0.0),
            v_s: 1.0,
            dahl: None,
            break_away: None,
            band: 0.0,
        }
    }

    /// The memoryless part of the force, F − z, with its v-derivative.
    fn memoryless(&self, v: f64, law: SignLaw) -> Term {
        let b = law.branches(v);
        terms::static_level(self.static_level, self.static_signed, &b)
            + terms::coulomb(self.coulomb, &b)
            + terms::viscous(self.viscous, v)
            + terms::stribeck(self.stribeck.0, self.stribeck.1, self.v_s, v, &b)
    }
}

impl FrictionModel for Composite {
    fn name(&self) -> &str {
        self.id.name()
    }

    fn curve_axis(&self) -> CurveAxis {
        self.id.curve_axis()
    }

    /// Coulomb (F_c, F_c, 0), viscous (0, 0, μ_v), static (F_c, F_s, 0) and Karnopp (F_c,
    /// F_s, μ_v): the catalog's laws of that form; `None` for the others (a Stribeck term, a
    /// static term in slip, a Dahl state).
    fn stiction_levels(&self) -> Option<StictionLevels> {
        let (f_c, f_v) = (self.coulomb, self.viscous);
        match self.id {
            ModelId::Coulomb | ModelId::Viscous | ModelId::Static | ModelId::Karnopp => {
                Some(StictionLevels {
                    f_c,
                    f_s: self.break_away.unwrap_or(f_c),
                    f_v,
                })
            }
            _ => None,
        }
    }

    fn n_states(&self) -> usize {
        usize::from(self.dahl.is_some())
    }

    /// `F = F_memoryless(v) + z`, `ż` of Dahl's law (eq. 4) when the model has it.
    #[inline]
    fn evaluate(
        &self,
        _x: f64,
        v: f64,
        z: &[f64],
        law: SignLaw,
        rate: &mut [f64],
        states: &mut [StatePartials],
    ) -> (f64, Partials) {
        let f = self.memoryless(v, law);
        let partials = Partials {
            force_dx: 0.0,
            force_dv: f.dv,
        };
        let Some(d) = self.dahl else {
            return (f.value, partials);
        };
        let r = terms::dahl_rate(d.sigma, d.f_c, v, z[0], &law.branches(v));
        rate[0] = r.rate;
        states[0] = StatePartials {
            force_dz: 1.0,
            rate_dx: 0.0,
            rate_dv: r.dv,
            rate_dz: r.dz,
        };
        (f.value + z[0], partials)
    }

    fn stick_interval(&self, x: f64, z: &[f64]) -> StickInterval {
        let at_rest = |law| self.force(x, 0.0, z, law);
        match self.break_away {
            Some(level) => {
                let smooth = at_rest(SignLaw::Discontinuous);
                StickInterval {
                    lower: smooth - level,
                    upper: smooth + level,
                }
            }
            None => StickInterval {
                lower: at_rest(SignLaw::Frozen(Direction::Negative)),
                upper: at_rest(SignLaw::Frozen(Direction::Positive)),
            },
        }
    }

    fn steady_state(&self, v: f64, z: &mut [f64]) {
        if let Some(d) = self.dahl {
            z[0] = d.f_c * SignLaw::Discontinuous.branches(v).sign();
        }
    }

    fn state_after_displacement(&self, z0: &[f64], dx: f64, z: &mut [f64]) -> bool {
        let Some(d) = self.dahl else { return false };
        z[0] = terms::dahl_after_displacement(d.sigma, d.f_c, z0[0], dx);
        true
    }

    fn stick_band(&self) -> f64 {
        self.band
    }

    /// The classical terms are functions of v (and Dahl's state), never of x.
    fn depends_on_position(&self) -> bool {
        false
    }

    /// `static + F_c·sign(v) + μ_v·v` is affine in v on each side of rest; the Stribeck
    /// exponential and Dahl's state are not.
    fn affine_in_velocity(&self) -> bool {
        self.stribeck == (0.0, 0.0) && self.dahl.is_none()
    }
}
