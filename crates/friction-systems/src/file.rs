//! The system file of `systems.md`: a TOML file (or the same keys as JSON, `.json`) of `[[body]]`, `[[anchor]]`, `[[spring]]`,
//! `[[contact]]` and `[[force]]` tables, with an optional `param_set` that every contact
//! starts from. Every error names the file, the table, the key and the allowed range.

use crate::system::{End, Profile, System, SystemError};
use friction_models::{FrictionModel, FrictionParams, ModelId, Parameters, Variant};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use thiserror::Error;

/// The largest system file read, bytes.
pub const MAX_FILE_BYTES: u64 = 64 << 20;

/// A system file that cannot be read or does not declare a valid system.
#[derive(Debug, Error)]
#[error("system file {}: {message}", path.display())]
pub struct SystemFileError {
    /// The file.
    pub path: PathBuf,
    /// What is wrong, naming the table and key.
    pub message: String,
}

#[derive(Deserialize)]
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
    between: [String; 2],
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

/// Reads the system declared in the file at `path` (at most [`MAX_FILE_BYTES`]).
pub fn read(path: &Path) -> Result<System, SystemFileError> {
    let error = |message: String| SystemFileError {
        path: path.to_path_buf(),
        message,
    };
    let file = std::fs::File::open(path).map_err(|e| error(e.to_string()))?;
    let mut text = String::new();
    file.take(MAX_FILE_BYTES + 1)
        .read_to_string(&mut text)
        .map_err(|e| error(e.to_string()))?;
    if text.len() as u64 > MAX_FILE_BYTES {
        return Err(error(format!(
            "larger than {MAX_FILE_BYTES} bytes, the most a system file may hold"
        )));
    }
    let json = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"));
    if json {
        parse_json(&text)
    } else {
        parse(&text)
    }
    .map_err(error)
}

/// Parses the text of a system file.
pub fn parse(text: &str) -> Result<System, String> {
    build(toml::from_str(text).map_err(|e| e.to_string().trim().to_string())?)
}

/// Parses a system written as JSON with the keys and tables of the TOML file (each
/// `[[table]]` an array of objects): how the Python package hands over `system=dict(...)`.
pub fn parse_json(text: &str) -> Result<System, String> {
    build(serde_json::from_str(text).map_err(|e| e.to_string())?)
}

/// The system a parsed file declares.
fn build(file: FileSystem) -> Result<System, String> {
    let base = match &file.param_set {
        Some(name) => FrictionParams::named(name).map_err(|e| format!("`param_set`: {e}"))?,
        None => FrictionParams::paper(),
    };
    let mut s = System::default();
    for b in &file.body {
        s.add_body(&b.name, b.m, b.x0, b.v0);
    }
    for a in &file.anchor {
        s.add_anchor(&a.name, a.x0, a.v);
    }
    s.check_names().map_err(|e| e.to_string())?;
    let end = |table: &str, i: usize, key: &str, name: &str| -> Result<End, String> {
        if let Some(b) = s.bodies.iter().position(|b| b.name == name) {
            Ok(End::Body(b))
        } else if let Some(a) = s.anchors.iter().position(|a| a.name == name) {
            Ok(End::Anchor(a))
        } else {
            Err(format!(
                "[[{table}]] {}: `{key}` names \"{name}\", which is no body or anchor of the file",
                i + 1
            ))
        }
    };
    let body = |table: &str, i: usize, name: &str| match end(table, i, "body", name)? {
        End::Body(b) => Ok(b),
        End::Anchor(_) => Err(format!(
            "[[{table}]] {}: `body` names the anchor \"{name}\"; allowed: the name of a [[body]]",
            i + 1
        )),
    };
    let mut springs = Vec::new();
    for (i, sp) in file.spring.iter().enumerate() {
        let a = end("spring", i, "between", &sp.between[0])?;
        let b = end("spring", i, "between", &sp.between[1])?;
        springs.push((a, b, sp.k, sp.c));
    }
    let mut contacts = Vec::new();
    for (i, c) in file.contact.iter().enumerate() {
        let b = body("contact", i, &c.body)?;
        contacts.push((b, c.surface_velocity, contact_model(i, c, &base)?));
    }
    let mut forces = Vec::new();
    for (i, f) in file.force.iter().enumerate() {
        forces.push((body("force", i, &f.body)?, f.constant, f.rate));
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
    s.validate().map_err(|e: SystemError| e.to_string())?;
    Ok(s)
}

fn contact_model(
    i: usize,
    c: &FileContact,
    base: &FrictionParams,
) -> Result<Arc<dyn FrictionModel>, String> {
    let at = |key: &str, e: String| format!("[[contact]] {}: `{key}`: {e}", i + 1);
    let id = ModelId::from_name(&c.model).map_err(|e| at("model", e))?;
    let variant = match &c.variant {
        Some(v) => v.parse::<Variant>().map_err(|e| at("variant", e))?,
        None => Variant::Odd,
    };
    let mut p = *base;
    for (name, &value) in &c.params {
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
