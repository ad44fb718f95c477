//! Output files prepared in memory and written together as one folder: a command that fails
//! while computing writes nothing, and a folder appears whole or not at all. The files are
//! written into a temporary folder beside the target (`.friction-lab-XXXXXX`), which is then
//! renamed into place; a target folder that friction-lab wrote before (it holds the marker
//! file [`MARKER`]) is replaced, and any other non-empty folder is refused.
//!
//! A command stopped by a signal writes what it computed as a partial result, marked so in the
//! marker's first line (`status: stopped`, where a complete folder says `status: complete`).
//! It never replaces a complete folder: if the target holds one, the partial result is written
//! beside it, as `<name>.stopped` ([`Written::kept`]).
//!
//! A run killed while writing leaves its temporary folder behind; the next run into the same
//! parent folder removes it. A run still writing holds a lock on its temporary folder's marker
//! (an advisory file lock, which the system releases when the process ends), so runs that
//! write side by side into one parent folder (a shell loop in the background, a cluster
//! job array) never remove each other's folders.

use crate::destination::{MARKER, NAME_MAX, TEMPORARY_PREFIX};
use crate::error::AppError;
use crate::figure::{self, Drawn};
use crate::output::{share_folder, to_json, write_file, Table};
use crate::plot::{self, Plot};
use crate::progress::Progress;
use crate::provenance::{Provenance, SIDECAR};
use friction_models::ModelId;
use rayon::prelude::*;
use std::path::{Path, PathBuf};

/// What a file will hold: its bytes, or a figure drawn when the files are written (figures
/// are drawn in parallel there; the bytes do not depend on the thread count).
#[derive(Debug)]
enum Content {
    Bytes(Vec<u8>),
    Table(Table, Vec<u8>),
    Json(serde_json::Value, Vec<u8>),
    Png(Vec<Plot>),
    Svg(Vec<Plot>),
    RasterPng(Box<plot::Raster>),
    RasterSvg(Box<plot::Raster>),
}

impl Content {
    /// The file's bytes, drawing the figure if it is one in `format`.
    fn render(self, path: &Path, format: &plot::Format) -> Result<Vec<u8>, AppError> {
        match self {
            Content::Bytes(b) | Content::Table(_, b) | Content::Json(_, b) => Ok(b),
            Content::Png(plots) => plot::png_panels(&plots, path, format),
            Content::Svg(plots) => plot::svg_panels(&plots, path, format).map(String::into_bytes),
            Content::RasterPng(r) => plot::raster_png(&r, path, format),
            Content::RasterSvg(r) => plot::raster_svg(&r, path, format).map(String::into_bytes),
        }
    }
}

impl Content {
    /// The pixels its PNG holds while drawn (three bytes each): the whole canvas of a figure
    /// or a raster picture; 0 for any other file.
    fn pixels(&self, format: &plot::Format) -> f64 {
        match self {
            Content::Png(plots) => plot::png_pixels(plots, format),
            Content::RasterPng(r) => {
                let (w, h) = format.pixels(r.size(format));
                f64::from(w) * f64::from(h)
            }
            _ => 0.0,
        }
    }
}

/// The most pixels drawn at once, over every figure drawn in parallel: memory for figures is
/// bounded by the pixels in flight (about 3.4 bytes each), not by the number of threads.
pub const PIXELS_IN_FLIGHT: f64 = plot::MAX_PIXELS;

/// A data file as the value it was made from ([`Artifacts::data`]).
#[derive(Clone, Copy, Debug)]
pub enum Data<'a> {
    /// A CSV file's table: its columns are [`Table::columns`].
    Table(&'a Table),
    /// A JSON file's document.
    Json(&'a serde_json::Value),
    /// Any other file's bytes (a Markdown report, a table written as text).
    Bytes(&'a [u8]),
}

/// `object` opened by `provenance` ([`Artifacts::stamp`]): its own `provenance`, if it has one,
/// gains the fields it lacks; else `provenance` becomes its first field.
pub fn open_with(
    object: &mut serde_json::Map<String, serde_json::Value>,
    provenance: &serde_json::Value,
) {
    match (object.get_mut("provenance"), provenance.as_object()) {
        (Some(serde_json::Value::Object(own)), Some(given)) => {
            for (key, value) in given {
                own.entry(key.clone()).or_insert_with(|| value.clone());
            }
        }
        _ => {
            let rest = std::mem::take(object);
            object.insert("provenance".into(), provenance.clone());
            object.extend(rest.into_iter().filter(|(key, _)| key != "provenance"));
        }
    }
}

/// Files to write: each path with its content.
#[derive(Debug, Default)]
pub struct Artifacts {
    files: Vec<(PathBuf, Content)>,
    format: plot::Format,
    replace: bool,
}

impl Artifacts {
    /// Draws the figures in `format` when the files are written (default:
    /// [`plot::Format::default`]).
    pub fn set_format(&mut self, format: plot::Format) {
        self.format = format;
    }

    /// Replaces the output folder also where it holds files friction-lab did not write
    /// (`--replace`: they are deleted with it); without it such a folder is refused
    /// ([`crate::destination::check`]).
    pub fn set_replace(&mut self, replace: bool) {
        self.replace = replace;
    }

    /// Adds a file.
    pub fn add(&mut self, path: PathBuf, bytes: Vec<u8>) {
        self.files.push((path, Content::Bytes(bytes)));
    }

    /// Adds `table` as a CSV file (checked now: a non-finite number fails here, naming its
    /// row and column).
    pub fn add_table(&mut self, path: PathBuf, table: Table) -> Result<(), AppError> {
        let bytes = table.to_csv(&path)?;
        self.files.push((path, Content::Table(table, bytes)));
        Ok(())
    }

    /// Adds `value` as a JSON file.
    pub fn add_json<T: serde::Serialize>(
        &mut self,
        path: PathBuf,
        value: &T,
    ) -> Result<(), AppError> {
        let value = serde_json::to_value(value).map_err(|e| AppError::Io {
            path: path.clone(),
            source: std::io::Error::other(e),
        })?;
        let bytes = to_json(&value, &path)?;
        self.files.push((path, Content::Json(value, bytes)));
        Ok(())
    }

    /// Adds a figure as `stem.csv`, `stem.png` and `stem.svg` in `dir`.
    pub fn add_figure(
        &mut self,
        dir: &Path,
        stem: &str,
        title: String,
        model: ModelId,
        curves: &[Drawn],
    ) -> Result<(), AppError> {
        self.add_table(dir.join(format!("{stem}.csv")), figure::table(curves))?;
        self.add_plot(&dir.join(stem), &figure::plot(title, model, curves))
    }

    /// Adds a plot as `stem.png` and `stem.svg`.
    pub fn add_plot(&mut self, stem: &Path, plot: &Plot) -> Result<(), AppError> {
        self.add_panels(stem, std::slice::from_ref(plot))
    }

    /// Adds plots as one figure, in rows of [`plot::PANELS_PER_ROW`] panels, `stem.png` and `stem.svg` (drawn at writing).
    pub fn add_panels(&mut self, stem: &Path, plots: &[Plot]) -> Result<(), AppError> {
        self.files
            .push((stem.with_extension("png"), Content::Png(plots.to_vec())));
        self.files
            .push((stem.with_extension("svg"), Content::Svg(plots.to_vec())));
        Ok(())
    }

    /// Adds a raster picture as `stem.png` and `stem.svg` (drawn at writing).
    pub fn add_raster(&mut self, stem: &Path, raster: &plot::Raster) -> Result<(), AppError> {
        let boxed = || Box::new(raster.clone());
        self.files
            .push((stem.with_extension("png"), Content::RasterPng(boxed())));
        self.files
            .push((stem.with_extension("svg"), Content::RasterSvg(boxed())));
        Ok(())
    }

    /// Names where the files come from: every JSON document that is an object opens with
    /// `provenance` (one the command made already, a study's with the threads its runs were
    /// spread over, keeps its fields and gains those it lacks, the command among them), and
    /// the folder `root` gets the sidecar [`SIDECAR`] with `provenance` (the first document's)
    /// and `files`, the path inside `root` of every other file.
    pub fn stamp(&mut self, root: &Path, provenance: &Provenance) -> Result<(), AppError> {
        let mut stamp = serde_json::to_value(provenance).map_err(|e| AppError::Io {
            path: root.join(SIDECAR),
            source: std::io::Error::other(e),
        })?;
        let mut first = None;
        for (path, content) in &mut self.files {
            if let Content::Json(serde_json::Value::Object(object), bytes) = content {
                open_with(object, &stamp);
                first.get_or_insert_with(|| object["provenance"].clone());
                *bytes = to_json(&serde_json::Value::Object(object.clone()), path)?;
            }
        }
        if let Some(own) = first {
            stamp = own;
        }
        let files: Vec<String> = (self.files.iter())
            .map(|(path, _)| {
                path.strip_prefix(root)
                    .unwrap_or(path)
                    .display()
                    .to_string()
            })
            .collect();
        let sidecar = serde_json::json!({ "provenance": stamp, "files": files });
        self.add_json(root.join(SIDECAR), &sidecar)
    }

    /// The data file written as `name` inside the output folder (`summary.json`), if one is.
    pub fn get(&self, name: &str) -> Option<Data<'_>> {
        (self.data(Path::new("")).into_iter())
            .find_map(|(path, data)| path.file_name().is_some_and(|f| f == name).then_some(data))
    }

    /// The data files (tables, JSON documents, text), each by its path relative to `root`, in
    /// the order they were added, as the values they were made from; figures are left
    /// undrawn. This is what the Python package reads, in memory.
    pub fn data(&self, root: &Path) -> Vec<(PathBuf, Data<'_>)> {
        self.files
            .iter()
            .filter_map(|(path, content)| {
                let data = match content {
                    Content::Bytes(bytes) => Data::Bytes(bytes),
                    Content::Table(table, _) => Data::Table(table),
                    Content::Json(value, _) => Data::Json(value),
                    _ => return None,
                };
                Some((path.strip_prefix(root).unwrap_or(path).to_path_buf(), data))
            })
            .collect()
    }

    /// Writes every file as the folder `root` (every path must lie inside it): into a temporary
    /// folder beside `root`, renamed into place once all files are written. A command stopped
    /// by a signal ([`integrators::interrupt::requested`]) writes a partial result, marked so,
    /// and writes it beside `root` where `root` holds a complete one ([`Written::kept`]).
    pub fn write(self, root: &Path) -> Result<Written, AppError> {
        let parent = match root.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let refuse = |why: String| AppError::OutputFolder {
            path: root.to_path_buf(),
            why,
        };
        crate::destination::check(root, self.replace)?;
        let format = self.format;
        // Every PNG's whole canvas within the pixel limit (one panel is checked when the
        // format is read; panels side by side and a legend below add to it), before anything
        // is made.
        for (path, content) in &self.files {
            let pixels = content.pixels(&format);
            if pixels > plot::MAX_PIXELS {
                return Err(AppError::Usage(format!(
                    "the figure {} would be {:.0} million pixels (its panels and legend at {} \
                     dpi), over the {:.0} million allowed: a smaller {} or {}",
                    path.strip_prefix(root).unwrap_or(path).display(),
                    pixels / 1e6,
                    format.dpi,
                    plot::MAX_PIXELS / 1e6,
                    crate::error::field("figure_size"),
                    crate::error::field("dpi")
                )));
            }
        }
        let stopped = integrators::interrupt::requested();
        let kept = (stopped && holds_stopped(root) == Some(false)).then(|| root.to_path_buf());
        let folder = match &kept {
            Some(_) => stopped_beside(root)?,
            None => root.to_path_buf(),
        };
        std::fs::create_dir_all(&parent)
            .map_err(|e| refuse(format!("its parent folder cannot be created: {e}")))?;
        remove_stale_temporaries(&parent);
        let tmp = tempfile::Builder::new()
            .prefix(TEMPORARY_PREFIX)
            .tempdir_in(&parent)
            .map_err(|e| refuse(format!("no temporary folder can be made beside it: {e}")))?;
        // Held until the folder is in place: the lock tells other runs it is not stale.
        let listed: Vec<&Path> = (self.files.iter())
            .map(|(path, _)| path.strip_prefix(root).unwrap_or(path))
            .collect();
        let _claim = claim(tmp.path(), stopped, &listed)?;
        let what = format!("writing into {}", folder.display());
        let progress = Progress::count(self.files.len(), "files drawn", &what);
        // Figures are drawn here, in parallel, in order, in batches of at most
        // [`PIXELS_IN_FLIGHT`] pixels (one figure at least); the first error (in file order)
        // wins.
        let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::with_capacity(self.files.len());
        let mut pending = self.files.into_iter().peekable();
        while pending.peek().is_some() {
            let (mut batch, mut in_flight) = (Vec::new(), 0.0);
            while let Some((_, content)) = pending.peek() {
                let pixels = content.pixels(&format);
                if !batch.is_empty() && in_flight + pixels > PIXELS_IN_FLIGHT {
                    break;
                }
                in_flight += pixels;
                batch.extend(pending.next());
            }
            let drawn: Vec<(PathBuf, Vec<u8>)> = batch
                .into_par_iter()
                .map(|(path, content)| {
                    let rendered = content.render(&path, &format).map(|bytes| (path, bytes));
                    progress.inc();
                    rendered
                })
                .collect::<Result<_, _>>()?;
            files.extend(drawn);
        }
        progress.finish();
        let progress = Progress::count(files.len(), "files written", &what);
        let needed: u64 = files.iter().map(|(_, b)| b.len() as u64).sum();
        // A failure names the output folder and the file in it, not the temporary folder
        // (removed with `tmp`), and says how much room the whole folder needs.
        let failed = |file: &Path, source: std::io::Error| AppError::Write {
            folder: folder.clone(),
            file: file.to_path_buf(),
            files: files.len(),
            needed,
            source,
        };
        let mut written = Vec::with_capacity(files.len());
        for (path, bytes) in &files {
            let relative = path
                .strip_prefix(root)
                .expect("every output file lies inside the output folder");
            let staged = tmp.path().join(relative);
            if let Some(dir) = staged.parent() {
                std::fs::create_dir_all(dir)
                    .and_then(|_| share_folder(dir))
                    .map_err(|source| failed(relative, source))?;
            }
            write_file(&staged, bytes).map_err(|e| match e {
                AppError::Io { source, .. } => failed(relative, source),
                other => other,
            })?;
            written.push(folder.join(relative));
            progress.inc();
        }
        progress.finish();
        swap_into_place(tmp, &folder)?;
        Ok(Written {
            files: written,
            folder,
            stopped,
            kept,
        })
    }
}

/// What [`Artifacts::write`] wrote, and where.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Written {
    /// The folder written: the target, or the folder beside it that holds a partial result.
    pub folder: PathBuf,
    /// The files written, each by its path inside [`Written::folder`] (the marker not listed).
    pub files: Vec<PathBuf>,
    /// Whether the command was stopped by a signal: the folder holds a partial result.
    pub stopped: bool,
    /// The target, where it held a complete result that the partial one did not replace.
    pub kept: Option<PathBuf>,
}

impl Written {
    /// The line the command prints: "wrote N files into FOLDER".
    pub fn line(&self) -> String {
        format!(
            "wrote {} files into {}",
            self.files.len(),
            self.folder.display()
        )
    }

    /// For a partial result, what the user must know: where it is, and what was kept.
    pub fn stop_note(&self) -> Option<String> {
        if !self.stopped {
            return None;
        }
        Some(match &self.kept {
            Some(kept) => format!(
                "stopped by a signal: the partial result is in {}; {} keeps the complete \
                 result of an earlier run",
                self.folder.display(),
                kept.display()
            ),
            None => format!(
                "stopped by a signal: {} holds a partial result (its {MARKER} says \
                 `{STOPPED_STATUS}`)",
                self.folder.display()
            ),
        })
    }
}

/// The paragraph at the top of a report (report.md, table2.md) written by a command that a
/// signal stopped: the result is partial, and `what` says how.
pub fn stopped_banner(what: &str) -> String {
    format!(
        "**Partial result: the command was stopped by a signal (exit 130).** The runs in \
         progress ended at their next step; {what}.\n\n"
    )
}

/// The marker's first line in a complete folder.
pub const COMPLETE_STATUS: &str = "status: complete";

/// The marker's first line in a folder that holds what a stopped command computed.
pub const STOPPED_STATUS: &str = "status: stopped";

/// Whether the folder `dir` holds friction-lab's output, and then whether it is a partial
/// result: `Some(true)` where its marker says [`STOPPED_STATUS`], `Some(false)` for a complete
/// one (a marker of a version before the status line counts as complete), `None` without a
/// marker.
fn holds_stopped(dir: &Path) -> Option<bool> {
    std::fs::read_to_string(dir.join(MARKER))
        .ok()
        .map(|text| text.lines().next() == Some(STOPPED_STATUS))
}

/// The folder beside `root` for a partial result that must not replace `root`'s complete one:
/// `<name>.stopped`, or `<name>.stopped-2`, `-3`, … where a folder of that name exists and is
/// not itself a partial result (the name shortened to stay within [`NAME_MAX`] bytes).
fn stopped_beside(root: &Path) -> Result<PathBuf, AppError> {
    let name = root
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    for k in 1..=STOPPED_CANDIDATES {
        let suffix = if k == 1 {
            ".stopped".to_string()
        } else {
            format!(".stopped-{k}")
        };
        let mut end = name.len().min(NAME_MAX - suffix.len());
        while !name.is_char_boundary(end) {
            end -= 1;
        }
        let candidate = root.with_file_name(format!("{}{suffix}", &name[..end]));
        if std::fs::symlink_metadata(&candidate).is_err() || holds_stopped(&candidate) == Some(true)
        {
            return Ok(candidate);
        }
    }
    Err(AppError::OutputFolder {
        path: root.to_path_buf(),
        why: format!(
            "the command was stopped and its partial result must not replace the complete one \
             in it, but the {STOPPED_CANDIDATES} names beside it for a partial result are taken"
        ),
    })
}

/// How many names [`stopped_beside`] tries.
const STOPPED_CANDIDATES: usize = 100;

/// The marker's text after its status line.
const MARKER_TEXT: &str = "This folder was written by friction-lab; the next run into it \
    replaces it whole, unless it then holds files not listed below (--replace replaces those \
    too).\n";

/// What the marker adds in a folder that holds a partial result.
const STOPPED_TEXT: &str = "A signal stopped the command that wrote it: it holds what was \
    computed until then, a partial result.\n";

/// Writes the marker (its first line the status: [`COMPLETE_STATUS`], or [`STOPPED_STATUS`]
/// when `stopped`; then the folder's `files`, one a line after
/// [`crate::destination::FILES_LINE`]) into the temporary folder `tmp` and returns it open and
/// locked: the marker is written under another name, locked, then renamed (the lock stays
/// with the file), so no other run ever sees the marker unlocked while this one lives.
fn claim(tmp: &Path, stopped: bool, files: &[&Path]) -> Result<std::fs::File, AppError> {
    let (pending, marker) = (tmp.join(CLAIM), tmp.join(MARKER));
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| AppError::Io { path, source }
    };
    let file = std::fs::File::create(&pending).map_err(io(&pending))?;
    file.lock().map_err(io(&pending))?;
    let mut text = if stopped {
        format!("{STOPPED_STATUS}\n{MARKER_TEXT}{STOPPED_TEXT}")
    } else {
        format!("{COMPLETE_STATUS}\n{MARKER_TEXT}")
    };
    text.push_str(crate::destination::FILES_LINE);
    text.push('\n');
    for file in files {
        text.push_str(&file.to_string_lossy());
        text.push('\n');
    }
    write_file(&pending, text.as_bytes())?;
    std::fs::rename(&pending, &marker).map_err(io(&marker))?;
    Ok(file)
}

/// The marker's name while [`claim`] writes and locks it.
const CLAIM: &str = ".friction-lab-claim";

/// Whether the temporary folder `dir` is one a friction-lab run left behind: it holds a marker
/// that no living run has locked ([`claim`]).
fn stale(dir: &Path) -> bool {
    std::fs::File::open(dir.join(MARKER)).is_ok_and(|marker| marker.try_lock().is_ok())
}

/// Removes temporary folders of friction-lab runs that were killed before they finished
/// (recognised by their prefix and their unlocked marker file: [`stale`]).
fn remove_stale_temporaries(parent: &Path) {
    let Ok(entries) = std::fs::read_dir(parent) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let ours = entry
            .file_name()
            .to_str()
            .is_some_and(|n| n.starts_with(TEMPORARY_PREFIX) && n != MARKER);
        if ours && path.is_dir() && stale(&path) {
            let _ = std::fs::remove_dir_all(&path);
        }
    }
}

/// Renames the finished temporary folder to `root`, setting a previous output aside first
/// and removing it after.
fn swap_into_place(tmp: tempfile::TempDir, root: &Path) -> Result<(), AppError> {
    let io = |source| AppError::Io {
        path: root.to_path_buf(),
        source,
    };
    let old = if root.exists() {
        let aside = tempfile::Builder::new()
            .prefix(TEMPORARY_PREFIX)
            .tempdir_in(tmp.path().parent().unwrap_or(Path::new(".")))
            .map_err(io)?
            .keep();
        std::fs::remove_dir(&aside).map_err(io)?;
        std::fs::rename(root, &aside).map_err(io)?;
        Some(aside)
    } else {
        None
    };
    share_folder(tmp.path()).map_err(io)?;
    std::fs::rename(tmp.path(), root).map_err(io)?;
    // The temporary folder now is the output: nothing left to delete.
    let _ = tmp.keep();
    if let Some(old) = old {
        let _ = std::fs::remove_dir_all(old);
    }
    Ok(())
}
