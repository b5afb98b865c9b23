//! Where commands write: one rule for every output (each command's `-o`, `convert`'s OUT,
//! `split -o DIR`), applied here before the command runs.
//!
//! - A file output's missing directories are created. An existing file is replaced whole
//!   (the new one is written beside it under a temporary name and renamed over it, so it
//!   is never seen half written); a directory in its place is refused.
//! - `split -o DIR`: DIR and its missing parents are created, and an empty DIR is used. A
//!   DIR that is not empty is refused unless `--overwrite` is given, and then only when it
//!   holds nothing but a previous split's files (its `manifest.json` and the pieces it
//!   lists): those are removed before the new pieces are written, so that no stale
//!   component file is left beside the new manifest. Other files are never removed.
//!
//! The checks and the directories are made before any work, so that a long job is not
//! refused at its end; a command that fails removes the directories made for it (those
//! still empty). Refusals are failures (exit 1): they are about what is on disk.

use std::collections::HashSet;
use std::ffi::OsString;
use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use clap::ArgMatches;

/// The directories made for a command's outputs, outermost first.
#[derive(Debug, Default)]
pub struct Prepared {
    made: Vec<PathBuf>,
}

impl Prepared {
    /// Removes the directories made for a command that failed, innermost first, each only
    /// when empty.
    pub fn undo(self) {
        for dir in self.made.iter().rev() {
            let _ = std::fs::remove_dir(dir);
        }
    }

    /// Makes `dir` and its missing parents, remembering which were made.
    fn make_dir(&mut self, dir: &Path) -> Result<()> {
        let missing: Vec<&Path> = dir
            .ancestors()
            .take_while(|d| !d.as_os_str().is_empty() && std::fs::symlink_metadata(d).is_err())
            .collect();
        if let Some(file) = dir
            .ancestors()
            .find(|d| !d.as_os_str().is_empty() && d.exists())
            .filter(|d| !d.is_dir())
        {
            bail!(
                "cannot make the directory {}: {} is a file",
                dir.display(),
                file.display()
            );
        }
        std::fs::create_dir_all(dir)
            .with_context(|| format!("creating the directory {}", dir.display()))?;
        self.made
            .extend(missing.into_iter().rev().map(Path::to_path_buf));
        Ok(())
    }
}

/// Checks the output the command line names (the argument `output` of the command run,
/// a directory for `split`) and makes its missing directories, as the module says.
pub fn prepare(matches: &ArgMatches) -> Result<Prepared> {
    let mut command = Vec::new();
    let mut m = matches;
    while let Some((name, sub)) = m.subcommand() {
        command.push(name);
        m = sub;
    }
    let mut prepared = Prepared::default();
    let Some(path) = m.try_get_one::<PathBuf>("output").ok().flatten() else {
        return Ok(prepared);
    };
    if command.first() == Some(&"split") {
        split_leftovers(path, m.get_flag("overwrite"))?;
        prepared.make_dir(path)?;
    } else {
        if path.is_dir() {
            bail!("{} is a directory: name the file to write", path.display());
        }
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            prepared.make_dir(dir)?;
        }
    }
    Ok(prepared)
}

/// The files of a previous split in `dir`, to remove before a new split is written there
/// (`manifest.json` first): none when `dir` is missing or empty. Refused: `dir` not a
/// directory; not empty without `overwrite`; holding anything but a previous split's
/// files (no manifest, or an entry the manifest does not list).
pub fn split_leftovers(dir: &Path, overwrite: bool) -> Result<Vec<PathBuf>> {
    if std::fs::symlink_metadata(dir).is_err() {
        return Ok(Vec::new());
    }
    if !dir.is_dir() {
        bail!(
            "{} is not a directory: `split -o` names the directory the pieces go in",
            dir.display()
        );
    }
    let mut entries: Vec<(OsString, bool)> = std::fs::read_dir(dir)
        .and_then(|d| {
            d.map(|e| e.and_then(|e| Ok((e.file_name(), e.file_type()?.is_file()))))
                .collect()
        })
        .with_context(|| format!("reading the directory {}", dir.display()))?;
    if entries.is_empty() {
        return Ok(Vec::new());
    }
    if !overwrite {
        bail!(
            "{} is not empty: give --overwrite to replace the split written there, or name \
             a new directory",
            dir.display()
        );
    }
    let manifest = dir.join("manifest.json");
    let ours = match std::fs::read(&manifest) {
        Ok(bytes) => split_files(&bytes).with_context(|| {
            format!(
                "{}: not a split's manifest, so {} is not replaced",
                manifest.display(),
                dir.display()
            )
        })?,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => bail!(
            "{} holds files but no manifest.json: it is not a split's output, and --overwrite \
             replaces only that",
            dir.display()
        ),
        Err(e) => return Err(e).with_context(|| format!("reading {}", manifest.display())),
    };
    let foreign: Vec<String> = entries
        .iter()
        .filter(|(name, is_file)| !(*is_file && is_ours(name, &ours)))
        .map(|(name, _)| name.to_string_lossy().into_owned())
        .collect();
    if !foreign.is_empty() {
        let shown = foreign
            .iter()
            .take(3)
            .cloned()
            .collect::<Vec<_>>()
            .join(", ");
        let more = match foreign.len() {
            0..=3 => String::new(),
            n => format!(" and {} more", n - 3),
        };
        bail!(
            "{} holds what a split did not write ({shown}{more}): --overwrite removes only a \
             previous split's files; move the others away or name a new directory",
            dir.display()
        );
    }
    // The manifest first: a directory with a manifest always holds the pieces it lists.
    entries.sort_by_key(|(name, _)| name != "manifest.json");
    Ok(entries
        .into_iter()
        .map(|(name, _)| dir.join(name))
        .collect())
}

/// The names of the files a split's manifest says it wrote: the manifest, each group's
/// and component's file, the string file beside a Surpac DTM.
fn split_files(manifest: &[u8]) -> Result<HashSet<String>> {
    let report: meshbool::ops::SplitReport = serde_json::from_slice(manifest)?;
    let mut files: HashSet<String> = ["manifest.json".to_string()].into();
    for g in &report.groups {
        for piece in std::iter::once(&g.piece).chain(&g.components) {
            if let Some(stem) = piece.file.strip_suffix(".dtm") {
                files.insert(format!("{stem}.str"));
            }
            files.insert(piece.file.clone());
        }
    }
    Ok(files)
}

/// Whether the directory entry `name` is one of `ours`, or the temporary file of one of
/// them left by a write that was killed (`.NAME.PID-N.meshbool-tmp`).
fn is_ours(name: &OsString, ours: &HashSet<String>) -> bool {
    let Some(name) = name.to_str() else {
        return false;
    };
    if ours.contains(name) {
        return true;
    }
    name.strip_suffix(".meshbool-tmp")
        .and_then(|n| n.strip_prefix('.'))
        .and_then(|n| n.rsplit_once('.'))
        .is_some_and(|(file, _)| ours.contains(file))
}
