//! A value of a system file set by its path, `TABLE.WHICH.KEY` (docs/systems.md, "Changing a
//! value of the file"): a sweep over the disc speed of a brake model, or a coupling stiffness,
//! without a file per value.
//!
//! - `TABLE` is `body`, `anchor`, `spring`, `contact`, `force` or `controller`;
//! - `WHICH` is the entry's 1-based index in its table, or a name: a body's or an anchor's
//!   own, or for a contact, a force and a controller the name of the body it acts on (an index
//!   when several act on that body); a spring has no name, only its index;
//! - `KEY` is a number of the entry (`m`, `x0`, `v0`; `x0`, `v`; `k`, `c`;
//!   `surface_velocity`; `constant`, `rate`; `kp`, `ki`, `kd`, `saturation`), or for a contact
//!   a friction parameter its model reads (`F_c`, `sigma`, …), set as in its `params`.

use super::FileSystem;

/// The tables of a system file and the numbers each holds.
const KEYS: [(&str, &[&str]); 6] = [
    ("body", &["m", "x0", "v0"]),
    ("anchor", &["x0", "v"]),
    ("spring", &["k", "c"]),
    (
        "contact",
        &["surface_velocity", "a friction parameter of its model"],
    ),
    ("force", &["constant", "rate"]),
    ("controller", &["kp", "ki", "kd", "saturation"]),
];

/// The entry `which` names among `names` (an entry's name, or the body it acts on, `None` for
/// a spring): a 1-based index, else the one entry of that name.
fn entry(table: &str, which: &str, names: &[Option<&str>]) -> Result<usize, String> {
    if let Ok(i) = which.parse::<usize>() {
        if (1..=names.len()).contains(&i) {
            return Ok(i - 1);
        }
        return Err(format!(
            "[[{table}]] {i} does not exist: the file has {} (indices count from 1)",
            names.len()
        ));
    }
    let named: Vec<usize> = (names.iter().enumerate())
        .filter(|(_, n)| **n == Some(which))
        .map(|(i, _)| i)
        .collect();
    match named[..] {
        [i] => Ok(i),
        [] => {
            let by = match table {
                "body" | "anchor" => format!("no [[{table}]] is named \"{which}\""),
                "spring" => "a [[spring]] is chosen by its index".into(),
                _ => format!("no [[{table}]] acts on a body named \"{which}\""),
            };
            Err(format!("{by}: allowed an index in [1, {}]", names.len()))
        }
        _ => Err(format!(
            "{} [[{table}]] tables act on body \"{which}\": choose one by its index ({})",
            named.len(),
            named
                .iter()
                .map(|i| (i + 1).to_string())
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

impl FileSystem {
    /// Sets the number at `path` (`TABLE.WHICH.KEY`) to `value` and says which number that is:
    /// its table, the entry's 0-based index and its key, so that two spellings of one number
    /// (`controller.mass.kp`, `controller.1.kp`) are seen to be one. The message of a path that
    /// names no number of the file says which part does not and what is allowed.
    pub(super) fn assign(&mut self, path: &str, value: f64) -> Result<Assigned, String> {
        let allowed = || {
            KEYS.map(|(t, keys)| format!("{t}: {}", keys.join(", ")))
                .join("; ")
        };
        let (table, rest) = path.split_once('.').unwrap_or((path, ""));
        let Some((which, key)) = rest.rsplit_once('.') else {
            return Err(format!(
                "`{path}` is no path TABLE.WHICH.KEY (e.g. contact.pad.surface_velocity, \
                 spring.2.k, body.caliper.m)"
            ));
        };
        let unknown = || format!("[[{table}]] has no number `{key}`: allowed {}", allowed());
        let i = match table {
            "body" => {
                let names: Vec<_> = self.body.iter().map(|b| Some(b.name.as_str())).collect();
                let i = entry(table, which, &names)?;
                let b = &mut self.body[i];
                *match key {
                    "m" => &mut b.m,
                    "x0" => &mut b.x0,
                    "v0" => &mut b.v0,
                    _ => return Err(unknown()),
                } = value;
                i
            }
            "anchor" => {
                let names: Vec<_> = self.anchor.iter().map(|a| Some(a.name.as_str())).collect();
                let i = entry(table, which, &names)?;
                let a = &mut self.anchor[i];
                *match key {
                    "x0" => &mut a.x0,
                    "v" => &mut a.v,
                    _ => return Err(unknown()),
                } = value;
                i
            }
            "spring" => {
                let names = vec![None; self.spring.len()];
                let i = entry(table, which, &names)?;
                let s = &mut self.spring[i];
                *match key {
                    "k" => &mut s.k,
                    "c" => &mut s.c,
                    _ => return Err(unknown()),
                } = value;
                i
            }
            "contact" => {
                let names: Vec<_> = self.contact.iter().map(|c| Some(c.body.as_str())).collect();
                let i = entry(table, which, &names)?;
                let c = &mut self.contact[i];
                match key {
                    "surface_velocity" => c.surface_velocity = value,
                    // A friction parameter: checked as the contact's own `params` are.
                    _ => {
                        c.params.insert(key.to_string(), value);
                    }
                }
                i
            }
            "force" => {
                let names: Vec<_> = self.force.iter().map(|f| Some(f.body.as_str())).collect();
                let i = entry(table, which, &names)?;
                let f = &mut self.force[i];
                *match key {
                    "constant" => &mut f.constant,
                    "rate" => &mut f.rate,
                    _ => return Err(unknown()),
                } = value;
                i
            }
            "controller" => {
                let names: Vec<_> = (self.controller.iter())
                    .map(|c| Some(c.body.as_str()))
                    .collect();
                let i = entry(table, which, &names)?;
                let c = &mut self.controller[i];
                match key {
                    "kp" => c.kp = value,
                    "ki" => c.ki = value,
                    "kd" => c.kd = value,
                    "saturation" => c.saturation = Some(value),
                    _ => return Err(unknown()),
                }
                i
            }
            _ => {
                return Err(format!(
                    "`{table}` is no table of a system file: allowed {}",
                    KEYS.map(|(t, _)| t).join(", ")
                ))
            }
        };
        Ok(Assigned {
            table: table.to_string(),
            index: i,
            key: key.to_string(),
        })
    }
}

/// The number of a system file an assignment set: its table, the entry's 0-based index in it,
/// and its key.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) struct Assigned {
    /// The table (`controller`).
    pub table: String,
    /// The entry's index in its table, from 0.
    pub index: usize,
    /// The number's key (`kp`).
    pub key: String,
}

#[cfg(test)]
mod tests {
    use crate::file::parse_with;
    use crate::System;

    /// A two-mass brake: a caliper on its mount, a pad on the caliper, the pad on the disc.
    const BRAKE: &str = r#"
        [[body]]
        name = "caliper"
        m = 2.0
        [[body]]
        name = "pad"
        m = 0.5
        [[anchor]]
        name = "mount"
        [[spring]]
        between = ["mount", "caliper"]
        k = 2e4
        [[spring]]
        between = ["caliper", "pad"]
        k = 5e4
        [[contact]]
        body = "pad"
        surface_velocity = 0.2
        model = "coulomb"
        [[force]]
        body = "pad"
        constant = -10.0
    "#;

    fn with(assignments: &[(&str, f64)]) -> Result<System, String> {
        let owned: Vec<(String, f64)> = (assignments.iter())
            .map(|(p, v)| (p.to_string(), *v))
            .collect();
        parse_with(BRAKE, &owned)
    }

    #[test]
    fn a_path_sets_the_number_it_names() {
        let s = with(&[
            ("body.caliper.m", 3.0),
            ("body.2.v0", 0.1),
            ("spring.2.k", 7e4),
            ("contact.pad.surface_velocity", 0.5),
            ("force.pad.rate", 1.0),
            ("anchor.mount.v", 0.01),
        ])
        .unwrap();
        assert_eq!((s.bodies[0].m, s.bodies[1].v0), (3.0, 0.1));
        assert_eq!((s.springs[0].k, s.springs[1].k), (2e4, 7e4));
        assert_eq!(s.contacts[0].surface_velocity, 0.5);
        assert_eq!(s.anchors[0].v, 0.01);
        // A friction parameter of the contact's model is set as in its `params`: Coulomb's
        // force level is the stick interval's bound.
        let law = with(&[("contact.pad.F_c", 4.0)]).unwrap();
        let stick = law.contacts[0].model.stick_interval(0.0, &[]);
        assert_eq!(stick.upper, 4.0, "{stick:?}");
    }

    #[test]
    fn a_path_that_names_no_number_says_which_part_and_what_is_allowed() {
        let error = |path: &str| with(&[(path, 1.0)]).unwrap_err();
        assert!(error("body.rotor.m").contains("no [[body]] is named \"rotor\""));
        assert!(error("spring.9.k").contains("[[spring]] 9 does not exist: the file has 2"));
        assert!(error("spring.a.k").contains("a [[spring]] is chosen by its index"));
        assert!(error("body.pad.k").contains("[[body]] has no number `k`: allowed body: m"));
        assert!(error("wheel.1.m").contains("`wheel` is no table of a system file"));
        assert!(error("contact.pad.sigma").contains("model `coulomb` does not read it"));
        assert!(error("body.m").contains("is no path TABLE.WHICH.KEY"));
        assert!(error("contact.caliper.F_c").contains("no [[contact]] acts on a body named"));
    }
}
