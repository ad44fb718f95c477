//! Output files prepared in memory and written together, so that a command that fails
//! while computing writes nothing at all.

use crate::error::AppError;
use crate::figure::{self, Drawn};
use crate::output::{create_dir, to_json, write_atomic};
use crate::plot::{self, Plot};
use friction_models::ModelId;
use std::path::{Path, PathBuf};

/// Files to write: each path with its bytes.
#[derive(Debug, Default)]
pub struct Artifacts {
    files: Vec<(PathBuf, Vec<u8>)>,
}

impl Artifacts {
    /// Adds a file.
    pub fn add(&mut self, path: PathBuf, bytes: Vec<u8>) {
        self.files.push((path, bytes));
    }

    /// Adds `value` as a JSON file.
    pub fn add_json<T: serde::Serialize>(
        &mut self,
        path: PathBuf,
        value: &T,
    ) -> Result<(), AppError> {
        let bytes = to_json(value, &path)?;
        self.add(path, bytes);
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
        let csv = dir.join(format!("{stem}.csv"));
        let bytes = figure::table(curves).to_csv(&csv)?;
        self.add(csv, bytes);
        self.add_plot(&dir.join(stem), &figure::plot(title, model, curves))
    }

    /// Adds a plot as `stem.png` and `stem.svg`.
    pub fn add_plot(&mut self, stem: &Path, plot: &Plot) -> Result<(), AppError> {
        let png = stem.with_extension("png");
        let bytes = plot::png(plot, &png)?;
        self.add(png, bytes);
        let svg = stem.with_extension("svg");
        let text = plot::svg(plot, &svg)?;
        self.add(svg, text.into_bytes());
        Ok(())
    }

    /// Adds a raster picture as `stem.png` and `stem.svg`.
    pub fn add_raster(&mut self, stem: &Path, raster: &plot::Raster) -> Result<(), AppError> {
        let png = stem.with_extension("png");
        let bytes = plot::raster_png(raster, &png)?;
        self.add(png, bytes);
        let svg = stem.with_extension("svg");
        let text = plot::raster_svg(raster, &svg)?;
        self.add(svg, text.into_bytes());
        Ok(())
    }

    /// Writes every file, creating folders as needed; each file appears whole or not at all.
    pub fn write(self) -> Result<Vec<PathBuf>, AppError> {
        let mut written = Vec::with_capacity(self.files.len());
        for (path, bytes) in self.files {
            if let Some(dir) = path.parent() {
                create_dir(dir)?;
            }
            write_atomic(&path, &bytes)?;
            written.push(path);
        }
        Ok(written)
    }
}
