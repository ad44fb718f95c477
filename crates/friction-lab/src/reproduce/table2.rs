//! Table 2 decided by simulation for the paper's six models and the reference models
//! (`table2.md`, `table2.json`; [`crate::study::Table2Study`]).

use super::Part;
use crate::error::AppError;
use crate::study::{conduct, Output, Table2Study};
use scenarios::phenomena::cost::{SYSTEMS, TARGET_ERROR};
use scenarios::phenomena::{catalog_laws, Phenomenon, Protocol};

/// The report's section on Table 2: every model of the catalog at its own parameter set,
/// under the default protocol.
pub struct Table2;

impl Part for Table2 {
    fn heading(&self) -> String {
        "Table 2, decided by simulation".into()
    }

    fn conduct(&self, target: &mut Output) -> Result<String, AppError> {
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
        let hunting: Vec<String> = (table.rows.iter())
            .filter(|(_, row)| {
                row.iter()
                    .any(|(p, c)| *p == Phenomenon::HUNTING && c.measured == Ok(true))
            })
            .map(|(law, _)| law.to_string())
            .collect();
        let ratios: Vec<f64> = (0..table.rows.len())
            .flat_map(|i| (0..SYSTEMS.len()).map(move |s| (i, s)))
            .filter_map(|(i, s)| table.cost.relative_work(i, s))
            .collect();
        let (least, most) = ratios
            .iter()
            .fold((f64::INFINITY, 0.0_f64), |(a, b), &r| (a.min(r), b.max(r)));
        Ok(format!(
            "[table2.md](table2.md) (and table2.json) decides every cell of the paper's Table 2 \
             by a simulated protocol, for the six models and the reference models: \
             {disagreements} of the paper's 42 claims disagree with the simulations. The \
             protocols are described in docs/phenomena.md.\n\n\
             Its last two rows are the paper's two criteria for choosing a model. Closed-loop \
             hunting (the servo rig, the 1995 PID at a set point): {} hunt. Simulation cost \
             (the counted work of the cheapest adequate run on the belt and on two masses, to a \
             grid error of {TARGET_ERROR:e}): {least:.2} to {most:.2} times Coulomb's; the wall \
             times are in table2-timing.csv.\n",
            hunting.join(", ")
        ))
    }
}
