//! `fold-validate`: the event engine and the reference force integrator against a tight
//! reference, error against run time, on the thesis' scenes (issue 6).
//!
//! Prints the work-precision table (or `--json`), writes `work-precision.svg` and
//! `work-precision.json` into the output directory. Exit 0, or 2 for bad input.
//!
//! `--stiff` runs the stiff study instead ([`foldchain::reference::stiff`]): each stiff case
//! and non-stiff control with both integrators, their step counts, printed as a table (or
//! `--json`); nothing is written.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::bail;
use clap::Parser;
use foldchain::reference::stiff::{run_stiff_study, select_cases};
use foldchain::reference::validate::{validate, ValidateOptions};
use foldchain_cli::output::OutputDir;

/// Runs every scene with a reference at a tight tolerance, then the event engine and each
/// integrator (Dormand-Prince 5(4), ROS2) along a ladder of tolerances, and reports each
/// one's error (event times over the duration, final poses in tile widths) and wall time.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// Print the rows as JSON instead of the table.
    #[arg(long)]
    json: bool,
    /// Run only this scene (repeatable), e.g. "3-tile SL".
    #[arg(long = "scene")]
    scenes: Vec<String>,
    /// Output directory for the plot and the JSON.
    #[arg(long, default_value = "out/validate")]
    out: PathBuf,
    /// Tolerance of the reference run.
    #[arg(long, default_value_t = ValidateOptions::default().reference_tolerance)]
    reference_tolerance: f64,
    /// Quicker ladders (Dormand-Prince 1e-3 to 1e-6, ROS2 1e-2 to 1e-4; reference 1e-9).
    #[arg(long)]
    quick: bool,
    /// Run the stiff study instead: step counts of both integrators on the stiff cases and
    /// the non-stiff controls (about 10 s in release, most of it Dormand-Prince on the
    /// stiffest case).
    #[arg(long, conflicts_with_all = ["scenes", "quick", "reference_tolerance", "out"])]
    stiff: bool,
    /// With --stiff: run only this case (repeatable), e.g. "SLLS rot x1e7".
    #[arg(long = "case", requires = "stiff")]
    cases: Vec<String>,
}

fn options(args: &Args) -> anyhow::Result<ValidateOptions> {
    let t = args.reference_tolerance;
    if !(t > 0.0 && t <= 1e-6) {
        bail!("--reference-tolerance {t}: expected a number in (0, 1e-6]");
    }
    let mut o = ValidateOptions::default().with_scenes(args.scenes.clone());
    o.reference_tolerance = t;
    if args.quick {
        o.dopri5 = vec![1e-3, 1e-4, 1e-5, 1e-6];
        o.ros2 = vec![1e-2, 1e-3, 1e-4];
        o.reference_tolerance = t.max(1e-9);
    }
    Ok(o)
}

/// `--stiff`: the study's table or JSON.
fn stiff(args: &Args) -> anyhow::Result<String> {
    let cases = select_cases(&args.cases)?;
    let quiet = args.json;
    let study = run_stiff_study(&cases, &mut |case, method| {
        if !quiet {
            eprintln!("fold-validate: stiff: {case}: {}", method.name());
        }
    })?;
    Ok(if args.json {
        format!("{}\n", study.to_json())
    } else {
        study.to_table()
    })
}

fn main() -> ExitCode {
    let args = Args::parse();
    if args.stiff {
        return match stiff(&args) {
            Ok(text) => {
                print!("{text}");
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("fold-validate: {e:#}");
                ExitCode::from(2)
            }
        };
    }
    let result = options(&args).and_then(|opts| {
        let quiet = args.json;
        let v = validate(&opts, &mut |scene, method, tol| {
            if !quiet {
                eprintln!(
                    "fold-validate: {scene}: {method}{}",
                    tol.map(|t| format!(" at {t:.0e}")).unwrap_or_default()
                );
            }
        })?;
        let mut out = OutputDir::create(&args.out)?;
        out.write("work-precision.svg", v.to_svg().as_bytes())?;
        out.write("work-precision.json", v.to_json().as_bytes())?;
        let files: Vec<_> = out.written().iter().map(|f| args.out.join(f)).collect();
        Ok((v, files))
    });
    match result {
        Ok((v, files)) => {
            if args.json {
                println!("{}", v.to_json());
            } else {
                print!("{}", v.to_table());
                for f in files {
                    println!("wrote {}", f.display());
                }
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("fold-validate: {e:#}");
            ExitCode::from(2)
        }
    }
}
