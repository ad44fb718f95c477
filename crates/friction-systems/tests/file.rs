//! The system file: what it declares, and errors that name the table, the key and the range.

use friction_systems::file::{parse, parse_json};
use friction_systems::{End, Profile};

const TWO_MASSES: &str = r#"
param_set = "paper"

[[body]]
name = "b1"
m = 1.0

[[body]]
name = "b2"
m = 2.0
x0 = 0.1

[[anchor]]
name = "driver"
v = 0.1

[[spring]]
between = ["driver", "b1"]
k = 10.0

[[spring]]
between = ["b1", "b2"]
k = 100.0
c = 0.5

[[contact]]
body = "b1"
model = "coulomb"
params = { F_c = 1.0841 }

[[contact]]
body = "b2"
surface_velocity = 0.2
model = "lugre"

[[force]]
body = "b2"
constant = 1.0
rate = 0.5
"#;

#[test]
fn a_two_mass_file_declares_what_it_says() {
    let s = parse(TWO_MASSES).unwrap();
    assert_eq!(s.bodies.len(), 2);
    assert_eq!(
        (s.bodies[1].m, s.bodies[1].x0, s.bodies[1].v0),
        (2.0, 0.1, 0.0)
    );
    assert_eq!(s.anchors[0].at(2.0), (0.2, 0.1));
    assert_eq!(s.springs[0].a, End::Anchor(0));
    assert_eq!(s.springs[1].b, End::Body(1));
    assert_eq!((s.springs[1].k, s.springs[1].c), (100.0, 0.5));
    assert_eq!(s.contacts[0].model.name(), "coulomb");
    // Coulomb at rest holds up to F_c, as overridden.
    assert_eq!(s.contacts[0].model.stick_interval(0.0, &[]).upper, 1.0841);
    assert_eq!(s.contacts[1].surface_velocity, 0.2);
    assert_eq!(s.contacts[1].model.n_states(), 1);
    assert_eq!(s.forces[0].profile, Profile::Ramp { rate: 0.5 });
}

/// `TWO_MASSES` with the same keys as JSON.
const TWO_MASSES_JSON: &str = r#"{
  "param_set": "paper",
  "body": [{"name": "b1", "m": 1.0}, {"name": "b2", "m": 2.0, "x0": 0.1}],
  "anchor": [{"name": "driver", "v": 0.1}],
  "spring": [{"between": ["driver", "b1"], "k": 10.0},
             {"between": ["b1", "b2"], "k": 100.0, "c": 0.5}],
  "contact": [{"body": "b1", "model": "coulomb", "params": {"F_c": 1.0841}},
              {"body": "b2", "surface_velocity": 0.2, "model": "lugre"}],
  "force": [{"body": "b2", "constant": 1.0, "rate": 0.5}]
}"#;

#[test]
fn the_same_system_as_json_declares_the_same() {
    let (a, b) = (
        parse(TWO_MASSES).unwrap(),
        parse_json(TWO_MASSES_JSON).unwrap(),
    );
    assert_eq!(a.bodies, b.bodies);
    assert_eq!(a.anchors, b.anchors);
    assert_eq!(a.springs, b.springs);
    assert_eq!(a.forces, b.forces);
    assert_eq!(b.contacts[0].model.stick_interval(0.0, &[]).upper, 1.0841);
    assert_eq!(b.contacts[1].surface_velocity, 0.2);
    // Unknown keys are refused in JSON as in TOML.
    let e = parse_json(&TWO_MASSES_JSON.replace("\"x0\"", "\"x00\"")).unwrap_err();
    assert!(e.contains("unknown field `x00`"), "{e}");
}

fn error_of(text: &str) -> String {
    match parse(text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e,
    }
}

#[test]
fn every_error_names_the_table_the_key_and_the_range() {
    let cases = [
        (
            TWO_MASSES.replace("m = 2.0", "m = -2.0"),
            "[[body]] \"b2\": `m` = -2 is out of range: allowed (0, inf)",
        ),
        (
            TWO_MASSES.replace("k = 100.0", "k = -1.0"),
            "[[spring]] 2: `k` = -1 is out of range: allowed [0, inf)",
        ),
        (
            TWO_MASSES.replace("F_c = 1.0841", "F_c = -1.0"),
            "[[contact]] 1: `params.F_c`: parameter `F_c` = -1 is out of range: allowed (0, inf) N",
        ),
        (
            TWO_MASSES.replace("F_c = 1.0841", "mu = 1.0"),
            "[[contact]] 1: `params.mu`: unknown parameter `mu`",
        ),
        (
            TWO_MASSES.replace("F_c = 1.0841", "sigma0 = 1e4"),
            "[[contact]] 1: `params.sigma0`: model `coulomb` does not read it (it reads: F_c)",
        ),
        (
            TWO_MASSES.replace("model = \"lugre\"", "model = \"stribek\""),
            "[[contact]] 2: `model`: unknown model `stribek`",
        ),
        (
            TWO_MASSES.replace("between = [\"b1\", \"b2\"]", "between = [\"b1\", \"b3\"]"),
            "[[spring]] 2: `between` names \"b3\", which is no body or anchor of the file",
        ),
        (
            TWO_MASSES.replace(
                "body = \"b2\"\nsurface_velocity",
                "body = \"b1\"\nsurface_velocity",
            ),
            "[[contact]] 2: body \"b1\" has a contact already: a body has at most one contact",
        ),
        (
            TWO_MASSES.replace("name = \"driver\"", "name = \"b1\""),
            "[[anchor]] \"b1\": the name is used twice",
        ),
        (
            TWO_MASSES.replace("x0 = 0.1", "mass = 0.1"),
            "unknown field `mass`, expected one of `name`, `m`, `x0`, `v0`",
        ),
        (
            TWO_MASSES.replace("param_set = \"paper\"", "param_set = \"steel\""),
            "`param_set`: unknown parameter set `steel`",
        ),
        (
            TWO_MASSES.replace("m = 1.0", "m = \"heavy\""),
            "invalid type: string \"heavy\", expected f64",
        ),
        (
            TWO_MASSES.replace(
                "between = [\"b1\", \"b2\"]",
                "between = [\"b1\", \"b2\", \"driver\"]",
            ),
            "[[spring]] 2: `between` names 3 ends: allowed exactly two",
        ),
        (
            TWO_MASSES.replace("between = [\"b1\", \"b2\"]", "between = [\"b1\"]"),
            "[[spring]] 2: `between` names 1 ends: allowed exactly two",
        ),
        (
            TWO_MASSES.replace("name = \"b2\"", "name = \"\""),
            "[[body]] 2: `name` is 0 bytes long: allowed 1 to 256",
        ),
        (
            TWO_MASSES.replace(
                "name = \"driver\"",
                &format!("name = \"{}\"", "d".repeat(300)),
            ),
            "[[anchor]] 1: `name` is 300 bytes long: allowed 1 to 256",
        ),
        (
            // A name or a word of the file is repeated up to 40 characters, never whole.
            TWO_MASSES.replace(
                "model = \"lugre\"",
                &format!("model = \"{}\"", "x".repeat(100_000)),
            ),
            &format!(
                "`model`: unknown model `{}… (99960 more characters)`",
                "x".repeat(40)
            ),
        ),
    ];
    for (text, expected) in &cases {
        let e = error_of(text);
        assert!(
            e.len() < 1000,
            "the message repeats too much: {} bytes",
            e.len()
        );
        assert!(e.contains(expected), "expected `{expected}` in:\n{e}");
    }
    // A TOML syntax or type error says where.
    assert!(error_of("[[body]]\nname = \"a\"\nm = ").contains("line 3"));
}

/// A chain of `n` bodies as `[[table]]`s, the same as JSON, and the line of body `at`'s mass.
fn chain(n: usize, at: usize) -> (String, String, usize) {
    let mut toml = String::from("param_set = \"paper\"\n[[anchor]]\nname = \"d\"\nv = 0.1\n");
    let mut bodies = Vec::new();
    let mut line = 0;
    for i in 1..=n {
        toml += &format!("[[body]]\nname = \"b{i}\"\n");
        if i == at {
            line = toml.matches('\n').count() + 1;
        }
        toml += &format!("m = {i}\n[[spring]]\nbetween = [\"d\", \"b{i}\"]\nk = 9\n");
        bodies.push(format!(r#"{{"name": "b{i}", "m": {i}}}"#));
    }
    let springs: Vec<String> = (1..=n)
        .map(|i| format!(r#"{{"between": ["d", "b{i}"], "k": 9}}"#))
        .collect();
    let json = format!(
        r#"{{"param_set": "paper", "anchor": [{{"name": "d", "v": 0.1}}], "body": [{}], "spring": [{}]}}"#,
        bodies.join(","),
        springs.join(",")
    );
    (toml, json, line)
}

#[test]
fn a_long_file_read_in_parts_declares_what_it_says() {
    // 5000 bodies and 5000 springs: ten parts of a thousand tables.
    let (toml, json, _) = chain(5000, 0);
    let (a, b) = (parse(&toml).unwrap(), parse_json(&json).unwrap());
    assert_eq!(a.bodies.len(), 5000);
    assert_eq!(a.bodies, b.bodies);
    assert_eq!(a.anchors, b.anchors);
    assert_eq!(a.springs, b.springs);
    assert_eq!(a.bodies[4321].name, "b4322");
}

#[test]
fn an_error_in_a_later_part_is_placed_in_the_whole_file() {
    let (toml, _, line) = chain(5000, 4500);
    // A syntax error: the message is the `toml` crate's for the whole document, line and all.
    let broken = toml.replace("m = 4500\n", "m = \n");
    let whole = toml::from_str::<toml::Table>(&broken)
        .unwrap_err()
        .to_string();
    let e = error_of(&broken);
    assert_eq!(e, whole.trim());
    assert!(
        e.starts_with(&format!("TOML parse error at line {line}, column 5")),
        "{e}"
    );
    // A value of the wrong type, placed likewise.
    let e = error_of(&toml.replace("m = 4500\n", "m = \"x\"\n"));
    assert!(
        e.starts_with(&format!("TOML parse error at line {line}, column 5")),
        "{e}"
    );
    assert!(e.contains(&format!("{line} | m = \"x\"")), "{e}");
}

#[test]
fn a_root_array_extended_by_headers_is_refused_as_toml_refuses_it() {
    // `body = [...]` and then `[[body]]` headers beyond the first part: TOML forbids
    // extending a static array, and reading in parts must not hide it.
    let (toml, _, _) = chain(3000, 0);
    let text = toml.replace(
        "param_set = \"paper\"\n",
        "param_set = \"paper\"\nbody = [{name = \"b0\", m = 1}]\n",
    );
    assert!(toml::from_str::<toml::Table>(&text).is_err());
    let e = error_of(&text);
    assert!(e.starts_with("TOML parse error"), "{e}");
}

#[test]
fn an_inline_array_larger_than_a_part_is_refused_with_the_way_out() {
    let row = "{name = \"b\", m = 1},\n";
    let text = format!(
        "[[anchor]]\nname = \"d\"\nbody = [\n{}]\n",
        row.repeat(friction_systems::file::MAX_TOML_PART_BYTES / row.len() + 1)
    );
    let e = error_of(&text);
    assert!(
        e.contains("bytes from line 1 are one piece")
            && e.contains("at most 33554432 bytes")
            && e.contains("or write the file as JSON"),
        "{e}"
    );
}
