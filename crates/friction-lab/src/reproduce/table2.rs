//! Table 2 decided by simulation for the paper's six models and the reference models
//! (`table2.md`, `table2.json`; [`crate::study::Table2Study`]).

use super::Part;
use crate::error::AppError;
use crate::study::{conduct, Table2Study, Target};
use scenarios::phenomena::{catalog_laws, Phenomenon, Protocol};

/// The report's section on Table 2: every model of the catalog at its own parameter set,
/// under the default protocol.
pub struct Table2;

impl Part for Table2 {
    fn heading(&self) -> String {
        "Table 2, decided by simulation".into()
    }

    fn conduct(&self, target: &mut Target) -> Result<String, AppError> {
        let laws = catalog_laws();
        let study = Table2Study {
            phenomena: &Phenomenon::ALL,
            laws: &laws,
            protocol: Protocol::default(),
            parameters: None,
        };
        let table = conduct(&study, target, "table2")?;
        if let Some(failure) = target.failure.take() {
            return Err(failure);
        }
        let disagreements = (table.rows.iter())
            .flat_map(|(_, r)| r.iter())
            .filter(|(_, c)| c.disagrees())
            .count();
        Ok(format!(
            "[table2.md](table2.md) (and table2.json) decides every cell of the paper's Table 2 \
             by a simulated protocol, for the six models and the reference models: \
             {disagreements} of the paper's 42 claims disagree with the simulations. The \
             protocols are described in docs/phenomena.md.\n"
        ))
    }
}
