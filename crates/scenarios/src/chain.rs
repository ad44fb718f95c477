//! The Burridge–Knopoff chain of `docs/systems.md` kept with what it is built from, so that a study
//! can build it again with one parameter changed (a stiffness study over `k_chain`, `m` or a
//! parameter of its law).

use crate::error::ScenarioError;
use crate::run::Law;
use friction_models::{FrictionParams, Parameters};
use friction_systems::chain::ChainParams;
use friction_systems::System;

/// The chain from its parameters and one law: block i's law is `law` built from `friction`
/// with its force levels scaled by `1 + spread·sin(i)` ([`ChainParams::build`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ChainSource {
    /// N, m, k_chain, k_driver, v_driver and spread.
    pub chain: ChainParams,
    /// Every block's law.
    pub law: Law,
    /// The friction parameters the law is built from (before the scaling along the chain).
    pub friction: FrictionParams,
}

impl ChainSource {
    /// The chain.
    pub fn build(&self) -> Result<System, ScenarioError> {
        Ok(self.chain.build(&self.friction, |p| self.law.build(p))?)
    }

    /// What it is, for titles: "chain of N MODEL".
    pub fn name(&self) -> String {
        format!("chain of {} {}", self.chain.n_bodies, self.law)
    }

    /// The same chain with the chain parameter or friction parameter `name` at `value`. A
    /// friction parameter the law of the catalog does not read is refused, since every value
    /// would build the same chain; so is `epsilon`, which the law does not read either (a
    /// system's regularisation width is the study case's, [`crate::cases::SystemCase`]).
    pub fn with(&self, name: &str, value: f64) -> Result<ChainSource, ScenarioError> {
        let mut source = self.clone();
        if source.chain.set(name, value)? {
            return Ok(source);
        }
        if FrictionParams::spec(name).is_none() {
            return Err(ScenarioError::Invalid(format!(
                "unknown parameter `{name}` of the chain{}; known: {}, and the friction \
                 parameters its law reads",
                friction_models::params::did_you_mean(
                    name,
                    (friction_systems::chain::CHAIN_PARAMETERS
                        .iter()
                        .map(|p| p.0))
                    .chain(FrictionParams::specs().iter().map(|s| s.name))
                ),
                friction_systems::chain::CHAIN_PARAMETERS
                    .map(|p| p.0)
                    .join(", ")
            )));
        }
        if let Some(why) = self.law.catalog().and_then(|m| m.unread(name)) {
            return Err(ScenarioError::Invalid(format!(
                "{why}: every value would give the same runs"
            )));
        }
        source.friction.set(name, value)?;
        Ok(source)
    }
}
