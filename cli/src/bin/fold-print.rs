//! `fold-print`: from a chain, a plan or a shape to printable tiles, plates and an assembly
//! sheet. Exit 0 with the files written, 1 when a shape cannot be planned, 2 for bad input.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{bail, Context};
use clap::Parser;
use foldchain::timeline::TileDesigns;
use foldchain_cli::choices::{FormatChoice, PrinterChoice};
use foldchain_cli::inputs::{
    plan_options, read_chain, read_plan_file, refuse_overwrite_in, ChainInput,
};
use foldchain_cli::numbers::{count_in, in_range};
use foldchain_cli::output::{create_dir_all, OutputDir};
use foldchain_cli::progress::{Progress, ProgressMode};
use foldchain_cli::record::{first_foreign, not_ours};
use foldchain_cli::report::{finish, parse_args};
use foldchain_cli::run_name::{inline_name, stem};
use foldchain_cli::{errln, outln};
use foldchain_planner::Turns;
use foldchain_print::{is_job_file, print_job, Bed, PartOptions, PrintError, PrintOptions, Source};

/// Printable tiles, plates and an assembly sheet for a chain, a plan or a shape.
#[derive(Parser, Debug)]
#[command(
    name = "fold-print",
    version,
    after_help = "Examples:
  fold-print SLLS --out u-turn                   the four parts of a tight U-turn
  fold-print shapes/key.svg --tiles 171 --out print
  fold-print --plan key-plan.json --printer resin --format stl --out key-resin
  fold-print S*40 --bed 180,180 --spacing 4 --out strip

Writes into --out DIR: parts/PART.3mf (one per part the chain uses: SS, RS, SR, RR, LR, RL;
a part turned by 180 degrees is the other tile type it reads as) with a picture parts/PART.png,
plates/plate-K.3mf (the bill of materials laid out on the bed), assembly.svg (the chain tile by
tile: type, part, orientation, the RI's side and the magnets' poles) and parts.json (counts,
volumes, printing time estimates and their basis). Only these names are replaced; anything
else in DIR is left alone.

Channels are the magnet's diameter plus --clearance wide (default: twice the printer's
tolerance plus the magnet's, 0.25 mm FDM, 0.15 mm resin). See docs/printing.md.

Exit codes: 0 written, 1 the shape cannot be planned, 2 bad input."
)]
struct Args {
    #[command(flatten)]
    input: ChainInput,
    /// The printer: its tolerance sets the default clearance.
    #[arg(long, value_enum, default_value_t = PrinterChoice::Fdm)]
    printer: PrinterChoice,
    /// Channel width minus magnet diameter, 0 to 2 mm (default from --printer).
    #[arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = in_range(0.0, 2.0, "mm", ""))]
    clearance: Option<f64>,
    /// Tile height, 0.5 to 1000 mm (the thesis' 7.5 by default).
    #[arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = in_range(0.5, 1000.0, "mm", ""))]
    height: Option<f64>,
    /// Floor under the channels, 0.1 to 1000 mm, less than the height (default 1.2).
    #[arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = in_range(0.1, 1000.0, "mm", ""))]
    floor: Option<f64>,
    /// The output directory (created if needed).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// The parts' and plates' file format.
    #[arg(long, value_enum, default_value_t = FormatChoice::ThreeMf)]
    format: FormatChoice,
    /// The print bed, mm: W,H.
    #[arg(long, value_name = "W,H", default_value = "250,210")]
    bed: String,
    /// Gap between neighbouring tiles on a plate, 0 to 1000 mm.
    #[arg(long, value_name = "MM", default_value = "5", allow_hyphen_values = true, value_parser = in_range(0.0, 1000.0, "mm", ""))]
    spacing: f64,
    /// Print parts.json on stdout instead of the summary.
    #[arg(long)]
    json: bool,
    /// No progress on stderr (planning a shape and writing a long chain's plates take
    /// seconds).
    #[arg(long)]
    quiet: bool,
    /// SHAPE.svg only: about this many tiles.
    #[arg(long, value_parser = tiles_arg)]
    tiles: Option<usize>,
    /// SHAPE.svg only: tight, loose or auto.
    #[arg(long)]
    turns: Option<Turns>,
}

fn main() -> ExitCode {
    match parse_args::<Args>("fold-print") {
        Ok(args) => finish("fold-print", run(&args).map(|()| 0)),
        Err(code) => code,
    }
}

fn tiles_arg(s: &str) -> Result<usize, String> {
    count_in(s, 1, 2_000_000, "tiles").map(|n| n as usize)
}

/// `W,H` in mm.
fn bed_size(text: &str) -> anyhow::Result<(f64, f64)> {
    let parse = |s: &str| {
        s.trim()
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite() && *v > 0.0)
    };
    match text.split_once(',') {
        Some((w, h)) => match (parse(w), parse(h)) {
            (Some(w), Some(h)) => Ok((w, h)),
            _ => bail!("--bed {text:?}: expected W,H in mm, two numbers > 0, e.g. 250,210"),
        },
        None => bail!("--bed {text:?}: expected W,H in mm, e.g. 250,210"),
    }
}

/// The checked options and the chain's source, from the arguments.
fn options(args: &Args) -> anyhow::Result<(Source, TileDesigns, PrintOptions, Vec<PathBuf>)> {
    let mut inputs: Vec<PathBuf> = Vec::new();
    let shape_opts = args.tiles.is_some() || args.turns.is_some();
    let source = match (&args.input.chain, &args.input.plan) {
        (Some(_), Some(_)) => bail!("give either CHAIN or --plan, not both"),
        (None, None) => bail!(
            "no chain: give CHAIN (a tile list, fold word, file or SHAPE.svg) or --plan PLAN.json"
        ),
        (None, Some(p)) => {
            if shape_opts {
                bail!("--tiles and --turns apply only to a SHAPE.svg");
            }
            let (_, plan) = read_plan_file(p)?;
            inputs.push(p.clone());
            Source::Plan {
                plan: Box::new(plan),
                name: stem(p),
            }
        }
        (Some(arg), None) if arg.to_ascii_lowercase().ends_with(".svg") => {
            let po = plan_options(args.tiles, None, args.turns);
            inputs.push(PathBuf::from(arg));
            Source::Shape {
                path: PathBuf::from(arg),
                options: po,
            }
        }
        (Some(arg), None) => {
            if shape_opts {
                bail!("--tiles and --turns apply only to a SHAPE.svg");
            }
            let chain = read_chain(arg)?;
            let name = if Path::new(arg).is_file() {
                inputs.push(PathBuf::from(arg));
                stem(Path::new(arg))
            } else {
                inline_name(arg, &chain)
            };
            Source::Chain { chain, name }
        }
    };
    let designs = args.input.designs()?;
    inputs.extend(args.input.design.clone());
    let mut part = PartOptions::for_printer(args.printer.to_printer());
    if let Some(c) = args.clearance {
        part = part.with_clearance(c);
    }
    if let Some(h) = args.height {
        part = part.with_height(h);
    }
    if let Some(f) = args.floor {
        part = part.with_floor(f);
    }
    part.validate().context("--clearance/--height/--floor")?;
    let (width, depth) = bed_size(&args.bed)?;
    let bed = Bed {
        width,
        depth,
        spacing: args.spacing,
    };
    bed.validate().context("--bed/--spacing")?;
    let opts = PrintOptions {
        part,
        bed,
        format: args.format.to_format(),
    };
    Ok((source, designs, opts, inputs))
}

fn run(args: &Args) -> anyhow::Result<()> {
    let (source, designs, opts, inputs) = options(args)?;
    let input_refs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
    let out = &args.out;
    refuse_overwrite_in(&input_refs, out, &is_job_file, "--out")?;
    for sub in ["parts", "plates"] {
        let owned = |n: &str| is_job_file(&format!("{sub}/{n}"));
        refuse_overwrite_in(&input_refs, &out.join(sub), &owned, "--out")?;
    }
    // refused before the work, not after it
    if out.exists() && !out.is_dir() {
        anyhow::bail!(
            "--out {}: exists and is not a directory; give a directory for the parts and plates",
            out.display()
        );
    }
    for sub in ["", "parts", "plates"] {
        if let Some(file) = first_foreign(out, sub, &is_job_file) {
            anyhow::bail!("--out {}: {}", file.display(), not_ours(out));
        }
    }
    let progress = Progress::new("fold-print", "files", ProgressMode::detect(args.quiet));
    progress.stage("planning and building the parts");
    // a shape that cannot be planned keeps the planner's own exit code (1)
    let job = print_job(&source, &designs, &opts).map_err(|e| match e {
        PrintError::Plan(p) => anyhow::Error::new(p),
        e => anyhow::Error::new(e),
    });
    let job = match job {
        Ok(job) => job,
        Err(e) => {
            progress.finish();
            return Err(e);
        }
    };
    let mut root = OutputDir::create(out)?;
    // a file of the user's under a name this run writes is refused before anything is written
    root.claim(job.files.iter().map(|f| f.path.as_str()))?;
    create_dir_all(&out.join("parts"))?;
    create_dir_all(&out.join("plates"))?;
    let total = job.files.len() as u64;
    for (i, f) in job.files.iter().enumerate() {
        progress.update("writing", i as u64, total);
        root.write(&f.path, &f.bytes)?;
    }
    progress.finish();
    // files of an earlier run under our names that this run did not write (a sixth plate
    // when there are five now), and torn temporary files of ours
    for sub in ["parts", "plates"] {
        let ours = |n: &str| is_job_file(&format!("{sub}/{n}"));
        root.remove_stale_in(sub, &ours, &ours)?;
    }
    let r = &job.report;
    // the plan's own warnings (a count off the request, a part left empty), as fold-plan
    // says them
    foldchain_cli::report::print_plan_warnings("fold-print", &r.plan_warnings);
    if args.json {
        let text = String::from_utf8_lossy(
            &job.files
                .iter()
                .find(|f| f.path == "parts.json")
                .map(|f| f.bytes.clone())
                .unwrap_or_default(),
        )
        .into_owned();
        foldchain_cli::stdout::text(&text);
        return Ok(());
    }
    outln!(
        "{}: {}, {}, {} of {} x {} mm; clearance {:.3} mm ({})",
        r.name,
        plural(r.tiles, "tile", "tiles"),
        plural(r.parts.len(), "part", "parts"),
        plural(r.plates.len(), "plate", "plates"),
        opts.bed.width,
        opts.bed.depth,
        r.clearance_mm,
        args.printer
    );
    for p in &r.parts {
        outln!(
            "  {:<6} x{:<5} reads {}/{}  {:>7.0} mm3  thinnest wall {:.2} mm  {}",
            p.label,
            p.count,
            p.reads[0],
            p.reads[1],
            p.volume_mm3,
            p.thinnest_wall_mm,
            p.file
        );
    }
    for p in &r.plates {
        outln!(
            "  {}: {} tiles, {:.0} mm3, about {:.0} min",
            p.file,
            p.tiles,
            p.volume_mm3,
            p.print_minutes
        );
    }
    outln!(
        "  magnets: {} ({} x {} mm); total {:.0} mm3, about {:.1} h of printing (parts.json says how it is estimated)",
        r.magnets.count,
        r.magnets.diameter_mm,
        r.magnets.height_mm,
        r.total_volume_mm3,
        r.total_print_minutes / 60.0
    );
    outln!(
        "  wrote {} files into {}",
        root.written().len(),
        out.display()
    );
    for w in &r.design_warnings {
        errln!("fold-print: warning: {w}");
    }
    Ok(())
}

/// `n` and the noun in the number it takes: `1 plate`, `2 plates`.
fn plural(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}
