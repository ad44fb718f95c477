//! The friction laws `--model` names: the catalog's, and laws registered by name while the
//! program runs (the Python package registers a law written in Python here, so that every
//! check, default and output of a run is the one the catalog's laws get).

use crate::error::{field, AppError};
use friction_models::{FrictionModel, FrictionParams, ModelId, Parameters, Variant};
use registry::{Named, Registry};
use scenarios::Law;
use std::collections::BTreeMap;
use std::sync::Arc;

/// The parameters `model` of the catalog reads, with their values in `p`.
pub fn used_parameters(model: ModelId, p: &FrictionParams) -> BTreeMap<&'static str, f64> {
    model
        .parameters()
        .iter()
        .map(|&n| (n, p.value(n).expect("models name existing parameters")))
        .collect()
}

/// The laws registered by name while the program runs, beside the catalog's models
/// ([`ModelId`], a closed list): the one registry type of solvers, rigs and Table 2's rows.
pub static LAWS: Registry<ModelChoice> = Registry::new("law", "laws", &[]);

/// Registers `law` under its name, replacing a law registered before under the same name;
/// refused (with the reason) when the name is not a non-empty word without commas, or a
/// model of the catalog has it (in any case), since `--model NAME` would then mean two laws.
pub fn register(law: Arc<dyn FrictionModel>) -> Result<(), String> {
    let name = law.name().to_string();
    if ModelId::from_name(&name).is_ok() {
        return Err(format!(
            "a law cannot be named `{name}`: the catalog has a model of that name \
             (`friction-lab models` lists them); choose another name"
        ));
    }
    LAWS.register(ModelChoice::Registered(law)).map(|_| ())
}

/// The law registered under `name`, if any.
pub fn registered(name: &str) -> Option<Arc<dyn FrictionModel>> {
    match LAWS.find(name)? {
        ModelChoice::Registered(law) => Some(law),
        ModelChoice::Catalog(_) => None,
    }
}

/// The law `--model` names: a model of the catalog, or a law registered by name.
#[derive(Clone, Debug)]
pub enum ModelChoice {
    /// A model `friction-lab models` lists.
    Catalog(ModelId),
    /// A registered law ([`register`]).
    Registered(Arc<dyn FrictionModel>),
}

impl ModelChoice {
    /// The law at a contact: the catalog's model in `variant`, or the registered law (which
    /// has no variants).
    pub fn law(&self, variant: Variant) -> Law {
        match self {
            ModelChoice::Catalog(model) => Law::Catalog {
                model: *model,
                variant,
            },
            ModelChoice::Registered(law) => Law::Own(Arc::clone(law)),
        }
    }

    /// The model of the catalog, if it is one.
    pub fn catalog(&self) -> Option<ModelId> {
        match self {
            ModelChoice::Catalog(model) => Some(*model),
            ModelChoice::Registered(_) => None,
        }
    }

    /// The parameters the law reads, with their values in `p`, as a summary reports them:
    /// a model of the catalog's ([`used_parameters`]); none of a registered law, whose
    /// parameters are its own.
    pub fn parameters_read(&self, p: &FrictionParams) -> BTreeMap<String, f64> {
        self.catalog()
            .map(|m| used_parameters(m, p))
            .unwrap_or_default()
            .into_iter()
            .map(|(name, value)| (name.to_string(), value))
            .collect()
    }

    /// The name, as `--model` takes it.
    pub fn name(&self) -> &str {
        match self {
            ModelChoice::Catalog(model) => model.name(),
            ModelChoice::Registered(law) => law.name(),
        }
    }
}

/// Found in [`LAWS`] by its name.
impl Named for ModelChoice {
    fn name(&self) -> &str {
        ModelChoice::name(self)
    }
}

impl std::fmt::Display for ModelChoice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for ModelChoice {
    type Err = String;
    /// A model of the catalog by name, or else a registered law; when neither has the name,
    /// the catalog's message with the registered laws' names.
    fn from_str(s: &str) -> Result<Self, String> {
        ModelId::from_name(s)
            .map(ModelChoice::Catalog)
            .or_else(|e| {
                if let Some(law) = registered(s) {
                    return Ok(ModelChoice::Registered(law));
                }
                let names = LAWS.names();
                Err(if names.is_empty() {
                    e
                } else {
                    format!("{e}; registered laws: {}", names.join(", "))
                })
            })
    }
}

/// Refuses `name`, swept by `option` (a sweep's axis, a stiffness study's parameter), when it
/// is a friction parameter the run does not read, so that every value would give the same
/// run: one `model` does not list, or `epsilon` (the width of the regularised treatment of
/// v = 0) where `unread_epsilon` names the treatment asked for, which does not read it.
pub fn check_read(
    option: &str,
    name: &str,
    model: Option<ModelId>,
    unread_epsilon: Option<&str>,
) -> Result<(), AppError> {
    if FrictionParams::spec(name).is_none() {
        return Ok(());
    }
    if name == "epsilon" {
        if let Some(treatment) = unread_epsilon {
            return Err(AppError::Usage(format!(
                "option `{}`: parameter `epsilon` is read only under {} regularized, not \
                 {treatment}: every value would give the same run",
                field(option),
                field("switching")
            )));
        }
    } else if let Some(why) = model.and_then(|m| m.unread(name)) {
        return Err(AppError::Usage(format!(
            "option `{}`: {why}: every value would give the same run",
            field(option)
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use friction_models::{Partials, SignLaw, StatePartials, StickInterval};

    /// Coulomb's law F = 2·sign(v), under a name of its own.
    #[derive(Debug)]
    struct Named(&'static str);

    impl FrictionModel for Named {
        fn name(&self) -> &str {
            self.0
        }
        fn n_states(&self) -> usize {
            0
        }
        fn evaluate(
            &self,
            _x: f64,
            v: f64,
            _z: &[f64],
            law: SignLaw,
            _rate: &mut [f64],
            _states: &mut [StatePartials],
        ) -> (f64, Partials) {
            let b = law.branches(v);
            (
                2.0 * (b.plus - b.minus),
                Partials {
                    force_dx: 0.0,
                    force_dv: 2.0 * 2.0 * b.dplus_dv,
                },
            )
        }
        fn stick_interval(&self, _x: f64, _z: &[f64]) -> StickInterval {
            StickInterval {
                lower: -2.0,
                upper: 2.0,
            }
        }
    }

    #[test]
    fn a_registered_law_is_chosen_by_name_and_a_catalog_name_is_refused() {
        let unknown = "no-such-law".parse::<ModelChoice>().unwrap_err();
        assert!(unknown.contains("no-such-law"), "{unknown}");
        register(Arc::new(Named("two-newton-coulomb"))).unwrap();
        let choice: ModelChoice = "two-newton-coulomb".parse().unwrap();
        assert!(choice.catalog().is_none());
        assert_eq!(choice.to_string(), "two-newton-coulomb");
        // The catalog's names stay the catalog's.
        let coulomb: ModelChoice = "coulomb".parse().unwrap();
        assert_eq!(coulomb.catalog(), Some(ModelId::Coulomb));
        let e = register(Arc::new(Named("coulomb"))).unwrap_err();
        assert!(e.contains("the catalog has a model of that name"), "{e}");
        let e = register(Arc::new(Named("a,b"))).unwrap_err();
        assert!(e.contains("without commas"), "{e}");
        assert_eq!(LAWS.names(), ["two-newton-coulomb"]);
    }
}
