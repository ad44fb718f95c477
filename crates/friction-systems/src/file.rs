//! The system file of `docs/systems.md`: a TOML file (or the same keys as JSON, `.json`) of
//! `[[body]]`, `[[anchor]]`, `[[spring]]`, `[[contact]]`, `[[force]]` and `[[controller]]`
//! tables, with an optional `param_set` that every contact and compensation starts from. Every error names the file, the table, the key and the allowed range.

use crate::control::{CompensatedAt, Compensation, Controller, Reference};
use crate::system::{End, Profile, System, SystemError};
use friction_models::{FrictionModel, FrictionParams, ModelId, Parameters, Variant};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use thiserror::Error;

mod assign;
mod toml_parts;

/// The largest system file read, TOML or JSON, bytes.
pub const MAX_FILE_BYTES: u64 = 256 << 20;

/// The largest piece of a TOML file parsed at once, bytes. A TOML file is read in parts of a
/// thousand `[[table]]`s, each parsed alone (a whole-document parse holds about 50 bytes of
/// memory a byte of text); a file written with inline arrays (`body = [{...}, ...]`) is one
/// part. JSON is read straight into the system's tables. Memory is then that of the system,
/// about 16 bytes a byte of text (docs/performance.md, "Loading a system file").
pub const MAX_TOML_PART_BYTES: usize = 32 << 20;

/// The longest name of a body or an anchor, bytes.
pub const MAX_NAME_BYTES: usize = 256;

/// The most characters of a name or a word of the file that a message repeats.
const ECHOED: usize = 40;

/// `text` as a message repeats it: whole up to [`ECHOED`] characters, else its beginning
/// with the count of the rest.
fn echo(text: &str) -> String {
    match text.char_indices().nth(ECHOED) {
        None => text.to_string(),
        Some((cut, _)) => format!(
            "{}… ({} more characters)",
            &text[..cut],
            text[cut..].chars().count()
        ),
    }
}

/// A system file (or a system given as JSON text) that cannot be read or does not declare a
/// valid system.
#[derive(Debug, Error)]
#[error("{}: {message}", origin.describe())]
pub struct SystemFileError {
    /// Where the system was declared.
    pub origin: SystemSource,
    /// What is wrong, naming the table and key.
    pub message: String,
}

/// Where a system is declared: a file (TOML, or JSON by its name), or JSON text given as a
/// value (how the Python package hands over `system=dict(...)`, and `--system '{…}'`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SystemSource {
    /// A file.
    File(PathBuf),
    /// The text of a system written as JSON.
    Json(String),
}

impl SystemSource {
    /// A file's path; or JSON text, the value if it starts with `{` (after white space): no
    /// file's name starts so without a folder before it (`./{x}.toml`).
    pub fn parse(value: &str) -> SystemSource {
        match value.trim_start().starts_with('{') {
            true => SystemSource::Json(value.to_string()),
            false => SystemSource::File(PathBuf::from(value)),
        }
    }

    /// How messages name it: `system file PATH`, or `system (given as JSON)`.
    pub fn describe(&self) -> String {
        match self {
            SystemSource::File(path) => format!("system file {}", path.display()),
            SystemSource::Json(_) => "system (given as JSON)".into(),
        }
    }

    /// The name a run's summary gives the system: the file's path, or `system (given as
    /// JSON)`.
    pub fn name(&self) -> String {
        match self {
            SystemSource::File(path) => path.display().to_string(),
            SystemSource::Json(_) => "system (given as JSON)".into(),
        }
    }

    /// The system declared there, each number at a path of `assignments` set first: a file
    /// as [`read_with`] reads it, JSON text as [`parse_json`] parses it.
    pub fn read_with(&self, assignments: &[(String, f64)]) -> Result<System, SystemFileError> {
        match self {
            SystemSource::File(path) => read_with(path, assignments),
            SystemSource::Json(text) => {
                parse_json_with(text, assignments).map_err(|message| SystemFileError {
                    origin: self.clone(),
                    message,
                })
            }
        }
    }
}

/// Its text as given on a command line: a path, or JSON text ([`SystemSource::parse`]).
impl std::str::FromStr for SystemSource {
    type Err = std::convert::Infallible;
    fn from_str(value: &str) -> Result<SystemSource, Self::Err> {
        Ok(SystemSource::parse(value))
    }
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct FileSystem {
    param_set: Option<String>,
    #[serde(default)]
    body: Vec<FileBody>,
    #[serde(default)]
    anchor: Vec<FileAnchor>,
    #[serde(default)]
    spring: Vec<FileSpring>,
    #[serde(default)]
    contact: Vec<FileContact>,
    #[serde(default)]
    force: Vec<FileForce>,
    #[serde(default)]
    controller: Vec<FileController>,
}

impl FileSystem {
    /// Appends the tables of a later part of the same file (whose root keys are all in the
    /// first part).
    fn append(&mut self, mut part: FileSystem) {
        self.param_set = self.param_set.take().or(part.param_set);
        self.body.append(&mut part.body);
        self.anchor.append(&mut part.anchor);
        self.spring.append(&mut part.spring);
        self.contact.append(&mut part.contact);
        self.force.append(&mut part.force);
        self.controller.append(&mut part.controller);
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileBody {
    name: String,
    m: f64,
    #[serde(default)]
    x0: f64,
    #[serde(default)]
    v0: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileAnchor {
    name: String,
    #[serde(default)]
    x0: f64,
    #[serde(default)]
    v: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileSpring {
    between: Vec<String>,
    k: f64,
    #[serde(default)]
    c: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileContact {
    body: String,
    #[serde(default)]
    surface_velocity: f64,
    model: String,
    variant: Option<String>,
    #[serde(default)]
    params: BTreeMap<String, f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileForce {
    body: String,
    #[serde(default)]
    constant: f64,
    #[serde(default)]
    rate: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileController {
    body: String,
    // Each gain given, 0 for a term not wanted: a gain left out ran as 0 without a word.
    kp: f64,
    ki: f64,
    kd: f64,
    reference: Reference,
    saturation: Option<f64>,
    compensation: Option<FileCompensation>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileCompensation {
    model: String,
    variant: Option<String>,
    #[serde(default)]
    params: BTreeMap<String, f64>,
    #[serde(default)]
    velocity: CompensatedAt,
}

/// Reads the system declared in the file at `path` (at most [`MAX_FILE_BYTES`]): JSON if its
/// name ends `.json`, TOML otherwise.
pub fn read(path: &Path) -> Result<System, SystemFileError> {
    read_with(path, &[])
}

/// Reads the system of the file at `path` as [`read`] does, each number at a path of
/// `assignments` (`TABLE.WHICH.KEY`, docs/systems.md) set to its value first.
pub fn read_with(path: &Path, assignments: &[(String, f64)]) -> Result<System, SystemFileError> {
    let error = |message: String| SystemFileError {
        origin: SystemSource::File(path.to_path_buf()),
        message,
    };
    let json = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"));
    let limit = MAX_FILE_BYTES;
    let file = std::fs::File::open(path).map_err(|e| error(e.to_string()))?;
    let mut text = String::new();
    file.take(limit + 1)
        .read_to_string(&mut text)
        .map_err(|e| error(e.to_string()))?;
    if text.len() as u64 > limit {
        return Err(error(format!(
            "larger than {limit} bytes, the most a system file may hold"
        )));
    }
    if json {
        parse_json_with(&text, assignments)
    } else {
        parse_with(&text, assignments)
    }
    .map_err(error)
}

/// `file` with each number at a path of `assignments` set; a bad path or value is named, and
/// so are two paths that set one number (by name and by index, or twice alike): only the last
/// would be used.
fn assigned(mut file: FileSystem, assignments: &[(String, f64)]) -> Result<FileSystem, String> {
    let mut set: Vec<(assign::Assigned, &str)> = Vec::with_capacity(assignments.len());
    for (path, value) in assignments {
        let number = (file.assign(path, *value)).map_err(|e| format!("`{path}` = {value}: {e}"))?;
        if let Some((_, first)) = set.iter().find(|(n, _)| *n == number) {
            return Err(format!(
                "`{first}` and `{path}` set the same number, {} of [[{}]] {}: set each number \
                 once (only the last would be used)",
                number.key,
                number.table,
                number.index + 1
            ));
        }
        set.push((number, path));
    }
    Ok(file)
}

/// Parses the text of a system file.
pub fn parse(text: &str) -> Result<System, String> {
    parse_with(text, &[])
}

/// Parses the text of a system file, each number at a path of `assignments`
/// (`TABLE.WHICH.KEY`) set to its value first.
pub fn parse_with(text: &str, assignments: &[(String, f64)]) -> Result<System, String> {
    build(assigned(parse_toml(text)?, assignments)?)
}

/// The tables of the text of a TOML system file, read in parts.
fn parse_toml(text: &str) -> Result<FileSystem, String> {
    let mut file = FileSystem::default();
    for (offset, part) in toml_parts::parts(text) {
        if part.len() > MAX_TOML_PART_BYTES {
            return Err(format!(
                "{} bytes from line {} are one piece: a TOML system file is read {} \
                 `[[table]]`s at a time, each piece at most {MAX_TOML_PART_BYTES} bytes (write \
                 the tables as `[[body]]`, `[[spring]]`, ... headers rather than inline arrays, \
                 or write the file as JSON)",
                part.len(),
                text[..offset].matches('\n').count() + 1,
                toml_parts::PART_TABLES
            ));
        }
        let part: FileSystem =
            toml::from_str(part).map_err(|e| toml_parts::message(text, offset, &e))?;
        file.append(part);
    }
    Ok(file)
}

/// Parses a system written as JSON with the keys and tables of the TOML file (each
/// `[[table]]` an array of objects): how the Python package hands over `system=dict(...)`.
pub fn parse_json(text: &str) -> Result<System, String> {
    parse_json_with(text, &[])
}

/// [`parse_json`], each number at a path of `assignments` (`TABLE.WHICH.KEY`) set to its
/// value first.
pub fn parse_json_with(text: &str, assignments: &[(String, f64)]) -> Result<System, String> {
    build(assigned(
        serde_json::from_str(text).map_err(|e| e.to_string())?,
        assignments,
    )?)
}

/// The system a parsed file declares.
fn build(file: FileSystem) -> Result<System, String> {
    let base = match &file.param_set {
        Some(name) => FrictionParams::named(name).map_err(|e| format!("`param_set`: {e}"))?,
        None => FrictionParams::paper(),
    };
    let mut s = System::default();
    let check_name = |table: &str, i: usize, name: &str| {
        if name.is_empty() || name.len() > MAX_NAME_BYTES {
            return Err(format!(
                "[[{table}]] {}: `name` is {} bytes long: allowed 1 to {MAX_NAME_BYTES}",
                i + 1,
                name.len()
            ));
        }
        Ok(())
    };
    for (i, b) in file.body.iter().enumerate() {
        check_name("body", i, &b.name)?;
    }
    for (i, a) in file.anchor.iter().enumerate() {
        check_name("anchor", i, &a.name)?;
    }
    for b in &file.body {
        s.add_body(&b.name, b.m, b.x0, b.v0);
    }
    for a in &file.anchor {
        s.add_anchor(&a.name, a.x0, a.v);
    }
    s.check_names().map_err(|e| e.to_string())?;
    // Every name once, looked up per end: a file of N bodies loads in O(N log N).
    let ends: BTreeMap<&str, End> = (s.bodies.iter().enumerate())
        .map(|(i, b)| (b.name.as_str(), End::Body(i)))
        .chain(
            s.anchors
                .iter()
                .enumerate()
                .map(|(i, a)| (a.name.as_str(), End::Anchor(i))),
        )
        .collect();
    let end = |table: &str, i: usize, key: &str, name: &str| -> Result<End, String> {
        ends.get(name).copied().ok_or_else(|| {
            format!(
                "[[{table}]] {}: `{key}` names \"{}\", which is no body or anchor of the file",
                i + 1,
                echo(name)
            )
        })
    };
    let body = |table: &str, i: usize, name: &str| match end(table, i, "body", name)? {
        End::Body(b) => Ok(b),
        End::Anchor(_) => Err(format!(
            "[[{table}]] {}: `body` names the anchor \"{}\"; allowed: the name of a [[body]]",
            i + 1,
            echo(name)
        )),
    };
    let mut springs = Vec::new();
    for (i, sp) in file.spring.iter().enumerate() {
        let [a, b] = sp.between.as_slice() else {
            return Err(format!(
                "[[spring]] {}: `between` names {} ends: allowed exactly two (a body and a \
                 body or an anchor)",
                i + 1,
                sp.between.len()
            ));
        };
        springs.push((
            end("spring", i, "between", a)?,
            end("spring", i, "between", b)?,
            sp.k,
            sp.c,
        ));
    }
    let mut contacts = Vec::new();
    for (i, c) in file.contact.iter().enumerate() {
        let b = body("contact", i, &c.body)?;
        let model = law(
            ("contact", i, ""),
            (&c.model, c.variant.as_deref(), &c.params),
            &base,
        )?;
        contacts.push((b, c.surface_velocity, model));
    }
    let mut forces = Vec::new();
    for (i, f) in file.force.iter().enumerate() {
        forces.push((body("force", i, &f.body)?, f.constant, f.rate));
    }
    let mut controllers = Vec::new();
    for (i, c) in file.controller.iter().enumerate() {
        let compensation = match &c.compensation {
            Some(k) => Some(Compensation {
                model: law(
                    ("controller", i, "compensation."),
                    (&k.model, k.variant.as_deref(), &k.params),
                    &base,
                )?,
                at: k.velocity,
            }),
            None => None,
        };
        controllers.push(Controller {
            body: body("controller", i, &c.body)?,
            kp: c.kp,
            ki: c.ki,
            kd: c.kd,
            reference: c.reference.clone(),
            saturation: c.saturation,
            compensation,
        });
    }
    for (a, b, k, c) in springs {
        s.add_spring(a, b, k, c);
    }
    for (b, v, model) in contacts {
        s.add_contact(b, v, model);
    }
    for (b, constant, rate) in forces {
        let profile = if rate == 0.0 {
            Profile::None
        } else {
            Profile::Ramp { rate }
        };
        s.add_force(b, constant, profile);
    }
    for c in controllers {
        s.add_controller(c);
    }
    s.validate().map_err(|e: SystemError| e.to_string())?;
    Ok(s)
}

/// The law a table declares: `model` (of the catalog), its `variant` and its `params` over
/// the file's parameter set `base`. `(table, i, prefix)` name the place in messages: the
/// keys are `{prefix}model`, `{prefix}params.NAME`, … of the `i`-th `[[table]]`.
fn law(
    (table, i, prefix): (&str, usize, &str),
    (model, variant, params): (&str, Option<&str>, &BTreeMap<String, f64>),
    base: &FrictionParams,
) -> Result<Arc<dyn FrictionModel>, String> {
    let at = |key: &str, e: String| format!("[[{table}]] {}: `{prefix}{key}`: {e}", i + 1);
    let id = ModelId::from_name(model).map_err(|_| {
        at(
            "model",
            format!(
                "unknown model `{}`; known models: {}",
                echo(model),
                ModelId::ALL.map(ModelId::name).join(", ")
            ),
        )
    })?;
    let variant = match variant {
        Some(v) => v.parse::<Variant>().map_err(|e| at("variant", e))?,
        None => Variant::Odd,
    };
    let mut p = *base;
    for (name, &value) in params {
        p.set(name, value)
            .map_err(|e| at(&format!("params.{name}"), e.to_string()))?;
        // A known parameter the law does not read would change nothing: a slip of the pen.
        if !id.parameters().contains(&name.as_str()) {
            return Err(at(
                &format!("params.{name}"),
                format!(
                    "model `{id}` does not read it (it reads: {})",
                    id.parameters().join(", ")
                ),
            ));
        }
    }
    id.build(variant, &p)
        .map(Arc::from)
        .map_err(|e| at("params", e.to_string()))
}
