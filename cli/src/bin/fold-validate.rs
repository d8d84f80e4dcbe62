//! `fold-validate`: the event engine and the reference force integrator against a tight
//! reference, error against run time, on the thesis' scenes (issue 6).
//!
//! Prints the work-precision table (or `--json`), writes `work-precision.svg` and
//! `work-precision.json` into the output directory. Exit 0, or 2 for bad input.
//!
//! `--stiff` runs the stiff study instead ([`foldchain_validation::stiff`]): each stiff case
//! and non-stiff control with both integrators, their step counts, printed as a table (or
//! `--json`); nothing is written.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::bail;
use clap::Parser;
use foldchain::physics::ForceLaw;
const FORCE_LAW_NAMES: [&str; 2] = ForceLaw::NAMES;
use foldchain::Design;
use foldchain_cli::choices::DynamicsChoice;
use foldchain_cli::experiments::experiments;
use foldchain_cli::numbers::number_in;
use foldchain_cli::output::OutputDir;
use foldchain_cli::progress::{Progress, ProgressMode};
use foldchain_cli::report::{finish, parse_args_with};
use foldchain_cli::{errln, outln};
use foldchain_validation::scenes::all_scenes;
use foldchain_validation::stiff::STIFF_CASES;
use foldchain_validation::stiff::{run_stiff_study, select_cases};
use foldchain_validation::{validate, ValidateOptions};

/// Runs every scene with a reference at a tight tolerance, then the event engine and each
/// integrator (Dormand-Prince 5(4), ROS2) along a ladder of tolerances, and reports each
/// one's error (event times over the duration, final poses in tile widths) and wall time.
#[derive(Parser, Debug)]
#[command(
    name = "fold-validate",
    version,
    about = "Measures the event engine and the integrators against a tight force-integrated reference on the thesis' scenes: errors against run time (the work-precision table and plot)."
)]
struct Args {
    /// Print the rows as JSON instead of the table.
    #[arg(long)]
    json: bool,
    /// No progress on stderr.
    #[arg(long)]
    quiet: bool,
    /// Run only this scene (repeatable), e.g. "3-tile SL".
    #[arg(long = "scene")]
    scenes: Vec<String>,
    /// Output directory for the plot and the JSON.
    #[arg(long, default_value = "out/validate")]
    out: PathBuf,
    /// Tolerance of the reference run.
    #[arg(long, default_value_t = ValidateOptions::default().reference_tolerance, conflicts_with = "quick", value_parser = reference_tolerance_arg)]
    reference_tolerance: f64,
    /// Quicker ladders (Dormand-Prince 1e-3 to 1e-6, ROS2 1e-2 to 1e-4; reference 1e-9).
    #[arg(long)]
    quick: bool,
    /// Run the stiff study instead: step counts of both integrators on the stiff cases and
    /// the non-stiff controls (about 10 s in release, most of it Dormand-Prince on the
    /// stiffest case).
    #[arg(long, conflicts_with_all = ["scenes", "quick", "reference_tolerance", "out"])]
    stiff: bool,
    /// Run the thesis' experiments instead (section 7.3: the four three-tile configurations
    /// and SL-SR-SL) in the reference with both pair laws and both dynamics, against what the
    /// thesis observed; writes their energy pictures (figures 7.7, 7.8) into --out. Exit 1 if
    /// any model disagrees with an observation.
    #[arg(long, conflicts_with_all = ["scenes", "quick", "reference_tolerance", "stiff"])]
    experiments: bool,
    /// With --stiff: run only this case (repeatable), e.g. "SLLS rot x1e7".
    #[arg(long = "case", requires = "stiff")]
    cases: Vec<String>,
    /// The pair law of the reference and of the engine's force rule: dipole (point dipoles,
    /// thesis 6.11/6.12) or cylinder (the thesis' 3 x 5 mm magnets as uniformly magnetised
    /// cylinders, tabulated).
    #[arg(long, default_value = "dipole", value_parser = FORCE_LAW_NAMES)]
    force_law: String,
    /// The reference's dynamics: overdamped (first order, the stiff limit) or inertial
    /// (mass, drag, bouncing walls; docs/physics.md, "Physical parameters").
    #[arg(long, value_enum, default_value_t = DynamicsChoice::Overdamped)]
    dynamics: DynamicsChoice,
}

fn reference_tolerance_arg(s: &str) -> Result<f64, String> {
    number_in(
        s,
        1e-13,
        1e-6,
        "",
        "tighter than 1e-13 is below the arithmetic's rounding",
    )
}

fn options(args: &Args) -> anyhow::Result<ValidateOptions> {
    let t = args.reference_tolerance;
    let mut o = ValidateOptions::default().with_scenes(args.scenes.clone());
    o.model.force_law = force_law(&args.force_law)?;
    o.model.dynamics = args.dynamics.to_dynamics();
    o.reference_tolerance = t;
    if args.quick {
        o.dopri5 = vec![1e-3, 1e-4, 1e-5, 1e-6];
        o.ros2 = vec![1e-2, 1e-3, 1e-4];
        o.reference_tolerance = t.max(1e-9);
    }
    Ok(o)
}

/// The pair law named on the command line, for the thesis' magnets (every scene uses them).
fn force_law(name: &str) -> anyhow::Result<ForceLaw> {
    match ForceLaw::named(name, &Design::thesis()) {
        Some(law) => Ok(law),
        None => bail!("--force-law {name}: expected one of {FORCE_LAW_NAMES:?}"),
    }
}

/// `--stiff`: the study's table or JSON.
fn stiff(args: &Args) -> anyhow::Result<String> {
    let cases = select_cases(&args.cases)?;
    let progress = Progress::new("fold-validate", "", ProgressMode::detect(args.quiet));
    let study = run_stiff_study(&cases, &mut |case, method| {
        progress.stage(&format!("stiff: {case}: {}", method.name()));
    });
    progress.finish();
    let study = study?;
    Ok(if args.json {
        format!("{}\n", study.to_json())
    } else {
        study.to_table()
    })
}

/// The help's closing text: examples, the scene and case names, the exit codes.
fn after_help() -> String {
    let scenes: Vec<String> = all_scenes()
        .iter()
        .map(|s| format!("  \"{}\"", s.name))
        .collect();
    let cases: Vec<String> = STIFF_CASES
        .iter()
        .map(|c| format!("  \"{}\"", c.name))
        .collect();
    format!(
        "Examples:
  fold-validate --quick                  every scene, shorter ladders (about 30 s)
  fold-validate --scene \"3-tile SL\" --json
  fold-validate --stiff --case \"SLLS rot x1e7\"
  fold-validate --experiments --out out/experiments

Scenes (--scene):
{}

Stiff cases (--stiff --case):
{}

Writes work-precision.svg and work-precision.json into --out (not with --stiff), or with
--experiments the energy pictures experiment-7-3-sl.svg etc.
Exit codes: 0 done (with --experiments: every model agrees with the thesis' observations),
1 a model disagrees with an observed experiment (--experiments), 2 bad input.",
        scenes.join("\n"),
        cases.join("\n")
    )
}

fn main() -> ExitCode {
    match parse_args_with::<Args>("fold-validate", |c| c.after_help(after_help())) {
        Ok(args) => finish("fold-validate", run(&args)),
        Err(code) => code,
    }
}

fn run(args: &Args) -> anyhow::Result<u8> {
    // a user's file under a name this run writes is refused before the work
    let written = |n: &str| {
        (n.starts_with("experiment-") && n.ends_with(".svg")) || n.starts_with("work-precision.")
    };
    if let Some(file) = foldchain_cli::record::first_foreign(&args.out, "", &written) {
        bail!(
            "--out {}: {}",
            file.display(),
            foldchain_cli::record::not_ours(&args.out)
        );
    }
    if args.experiments {
        let progress = Progress::new("fold-validate", "", ProgressMode::detect(args.quiet));
        progress.stage("the thesis' experiments in four models");
        let report = experiments(&args.out, args.json);
        progress.finish();
        let report = report?;
        foldchain_cli::stdout::text(&report.text);
        if !args.json {
            for f in &report.files {
                outln!("wrote {}", f.display());
            }
        }
        if report.all_agree() {
            return Ok(0);
        }
        errln!("fold-validate: the model disagrees with an observed experiment");
        return Ok(1);
    }
    if args.stiff {
        foldchain_cli::stdout::text(&stiff(args)?);
        return Ok(0);
    }
    let opts = options(args)?;
    // the output is checked before the work: a file in the way fails now, not after it
    if args.out.exists() && !args.out.is_dir() {
        bail!(
            "--out {}: exists and is not a directory",
            args.out.display()
        );
    }
    let progress = Progress::new("fold-validate", "", ProgressMode::detect(args.quiet));
    let v = validate(&opts, &mut |scene, method, tol| {
        progress.stage(&format!(
            "{scene}: {method}{}",
            tol.map(|t| format!(" at {t:.0e}")).unwrap_or_default()
        ));
    });
    progress.finish();
    let v = v?;
    let mut out = OutputDir::create(&args.out)?;
    out.claim(["work-precision.svg", "work-precision.json"])?;
    out.write("work-precision.svg", v.to_svg().as_bytes())?;
    out.write("work-precision.json", v.to_json().as_bytes())?;
    let files: Vec<_> = out.written().iter().map(|f| args.out.join(f)).collect();
    if args.json {
        outln!("{}", v.to_json());
    } else {
        foldchain_cli::stdout::text(&v.to_table());
        for f in files {
            outln!("wrote {}", f.display());
        }
    }
    Ok(0)
}
