//! Reading what a user names on the command line, and guarding their files: a chain given
//! inline or as a file (with a clear message when it is neither), a chain from fold-plan's
//! JSON and the outline of the shape it was planned for, and the refusal to write an output
//! over an input.

use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail, Context};
use foldchain::Chain;
use foldchain_planner::{Plan, Shape};

/// Reads a chain argument: a fold word, a tile list, JSON, or a file holding one. A name that
/// looks like a file (it has an extension or a directory) but is not there gets "no such
/// file, and not a fold word", with a pointer to `fold-plan`/`fold-run` for SVG shapes.
pub fn read_chain(arg: &str) -> anyhow::Result<Chain> {
    match Chain::read_arg(arg) {
        Ok(chain) => Ok(chain),
        Err(e) => {
            let path = Path::new(arg.trim());
            let looks_like_a_file = path.extension().is_some() || arg.contains(['/', '\\']);
            let svg = path
                .extension()
                .is_some_and(|x| x.eq_ignore_ascii_case("svg"));
            if svg && path.is_file() {
                bail!(
                    "{arg}: an SVG shape is not a chain; plan it with `fold-plan {arg}` or fold it with `fold-run {arg}`"
                );
            }
            if looks_like_a_file && !path.exists() {
                let hint = if svg {
                    " (an SVG shape goes to fold-plan or fold-run)"
                } else {
                    ""
                };
                bail!("{arg}: no such file, and not a fold word or tile list{hint}");
            }
            Err(e.into())
        }
    }
}

/// The path as it will be once written: the canonical form of an existing file, or of its
/// directory joined with its name (links resolved) when it does not exist yet.
fn resolved(p: &Path) -> PathBuf {
    if let Ok(c) = p.canonicalize() {
        return c;
    }
    let dir = match p.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    match (dir.canonicalize(), p.file_name()) {
        (Ok(d), Some(name)) => d.join(name),
        _ => p.to_path_buf(),
    }
}

/// Refuses (before any work) an output that is one of the inputs, after resolving links:
/// `what` names the output's flag.
pub fn refuse_overwrite(inputs: &[&Path], output: &Path, what: &str) -> anyhow::Result<()> {
    let out = resolved(output);
    for input in inputs {
        if resolved(input) == out {
            bail!(
                "{what} {}: is the input file {}; refusing to overwrite it (choose another output)",
                output.display(),
                input.display()
            );
        }
    }
    Ok(())
}

/// Refuses an output directory that would replace one of the inputs: an input that lies in
/// `dir` under one of the names `is_output` claims.
pub fn refuse_overwrite_in(
    inputs: &[&Path],
    dir: &Path,
    is_output: &dyn Fn(&str) -> bool,
    what: &str,
) -> anyhow::Result<()> {
    let dir = resolved(dir);
    for input in inputs {
        let r = resolved(input);
        let inside = r.parent() == Some(dir.as_path());
        let named = r
            .file_name()
            .is_some_and(|n| is_output(&n.to_string_lossy()));
        if inside && named {
            bail!(
                "{what} {}: would overwrite the input file {}; refusing (choose another output directory)",
                dir.display(),
                input.display()
            );
        }
    }
    Ok(())
}

/// Reads the chain designed by a plan file (`fold-plan --out` or `--json`), and the plan.
pub fn read_plan_file(path: &Path) -> anyhow::Result<(Chain, Plan)> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read plan file {}", path.display()))?;
    let plan = Plan::from_json(&text).map_err(|e| {
        anyhow!(
            "{}: not a fold-plan JSON file: {e} (expected the object `fold-plan --json` writes)",
            path.display()
        )
    })?;
    let word = plan
        .fold_word()
        .with_context(|| format!("{}: bad fold word in the plan", path.display()))?;
    let chain = word.to_chain();
    if chain.to_tile_list() != plan.tile_list.trim() || chain.len() != plan.tiles {
        bail!(
            "{}: the plan's word ({} tiles) and its tile_list/tiles ({} tiles) disagree: the file was edited by hand or is damaged",
            path.display(),
            chain.len(),
            plan.tiles
        );
    }
    Ok((chain, plan))
}

/// The outline of the shape in `shape_path` in the chain's own frame, in tile widths (tile
/// 0 at the origin heading +x, y up): the plan's `chain_to_svg` map inverted. `None` when
/// the file cannot be read again or the map is singular.
pub fn target_outline(plan: &Plan, shape_path: &Path) -> Option<Vec<Vec<(f64, f64)>>> {
    let data = std::fs::read(shape_path).ok()?;
    let shape = Shape::from_svg_data(&data, &shape_path.display().to_string()).ok()?;
    let [a, b, c, d, e, f] = plan.chain_to_svg;
    let det = a * d - b * c;
    if !det.is_finite() || det.abs() < 1e-300 {
        return None;
    }
    // the shape's rings are y up; SVG user units are y down
    let to_chain = |(x, y): (f64, f64)| {
        let (sx, sy) = (x - e, -y - f);
        ((d * sx - c * sy) / det, (a * sy - b * sx) / det)
    };
    Some(
        shape
            .rings()
            .map(|r| r.points.iter().map(|p| to_chain((p.x, p.y))).collect())
            .collect(),
    )
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    #[test]
    fn a_missing_file_is_not_read_as_a_fold_word() {
        let e = read_chain("nope.txt").unwrap_err().to_string();
        assert!(e.contains("no such file, and not a fold word"), "{e}");
        let e = read_chain("dir/sq.svg").unwrap_err().to_string();
        assert!(e.contains("fold-plan or fold-run"), "{e}");
        // a word is still a word
        assert_eq!(read_chain("SLLS").unwrap().len(), 5);
    }

    #[test]
    fn an_output_equal_to_an_input_is_refused_through_links() {
        let dir = std::env::temp_dir().join(format!("foldchain-inputs-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let f = dir.join("sq.svg");
        std::fs::write(&f, "x").unwrap();
        let dotted = dir.join(".").join("sq.svg");
        assert!(refuse_overwrite(&[&f], &dotted, "--preview").is_err());
        assert!(refuse_overwrite(&[&f], &dir.join("other.svg"), "--preview").is_ok());
        #[cfg(unix)]
        {
            let link = dir.join("link.svg");
            let _ = std::fs::remove_file(&link);
            std::os::unix::fs::symlink(&f, &link).unwrap();
            assert!(refuse_overwrite(&[&f], &link, "--out").is_err());
        }
        let ours = |n: &str| n == "summary.json";
        let s = dir.join("summary.json");
        std::fs::write(&s, "{}").unwrap();
        assert!(refuse_overwrite_in(&[&s], &dir, &ours, "--out").is_err());
        assert!(refuse_overwrite_in(&[&f], &dir, &ours, "--out").is_ok());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
