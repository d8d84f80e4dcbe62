//! The planner corpus report (issue 26): plans every drawing of `planner/corpus/` at 100,
//! 300, 1000 and 3000 tiles through the public library API and prints a table.
//!
//! ```text
//! cargo bench -p foldchain-planner --bench corpus -- [--tiles 100,300,1000,3000]
//!     [--ladder N] [--timeout 30] [--filter TEXT] [--markdown FILE] [--json FILE]
//! ```
//!
//! `--ladder N` asks N, 1.5 N, 2 N, 3 N, 5 N and 10 N tiles (at most [`LADDER_CAP`]) instead
//! of `--tiles`: issue 26's "if a drawing plans at N tiles, it plans at every count from N to
//! 10 N", sampled. Whatever the counts, the report lists every case of a one-piece drawing
//! refused (or timed out) at a count above one at which the same drawing planned.
//!
//! Each plan runs in its own process (this binary again, with `--one FILE TILES`), which
//! calls [`foldchain_planner::plan_svg_file`] with `PlanOptions::default().with_tiles(n)` and
//! prints the plan's JSON. Its CPU time (user + system, all its threads) is the growth of
//! `getrusage(RUSAGE_CHILDREN)` across the child's life. A child that has used more than
//! the CPU limit (`--timeout`, seconds of CPU read from `/proc/PID/stat` while it runs, so
//! that the limit does not depend on how loaded the machine is), or twenty times that in
//! wall-clock time, is killed and reported as a timeout. The empty-region measure is this
//! report's own ([`empty_region`]), not the planner's.
//!
//! Columns: drawing, tiles asked, exit (0 planned, 1 refused, 2 bad input, `timeout`), CPU
//! seconds, tiles, U-turns, quarter turns, covered share, outside share (both as the plan
//! reports them), the largest empty region in tile areas and, for a drawing the README marks
//! `islands`, the area of the islands the planner leaves out (tile areas), which its empty
//! region is measured without. The drawings and which of them
//! are one piece come from `planner/corpus/README.md`.

mod empty_region;

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode, Stdio};
use std::time::{Duration, Instant};

use foldchain_planner::{plan_svg_file, Plan, PlanOptions, Shape};
use nix::sys::resource::{getrusage, UsageWho};

/// Tile counts asked by default.
const TILES: [usize; 4] = [100, 300, 1000, 3000];
/// The ladder's shares of N (`--ladder N`).
const LADDER: [f64; 6] = [1.0, 1.5, 2.0, 3.0, 5.0, 10.0];
/// The ladder's largest count.
const LADDER_CAP: usize = 3000;
/// Per-plan time limit by default, seconds of CPU time (and twenty times that of wall-clock
/// time).
const TIMEOUT_S: f64 = 30.0;
/// The wall-clock limit as a multiple of the CPU limit: a child that sleeps cannot hang the
/// report.
const WALL_FACTOR: f64 = 20.0;
/// An empty region larger than this (tile areas) counts against a plan (issue 26).
const EMPTY_LIMIT: f64 = 2.0;
/// A tile count farther than this share from the request counts against a plan.
const COUNT_TOLERANCE: f64 = 0.03;

/// One drawing listed in the corpus README.
struct Drawing {
    /// Path below `planner/corpus/`.
    name: String,
    /// One piece: a chain can fill it.
    connected: bool,
    /// One piece with islands the planner leaves out (README: `islands`): measured over what
    /// it plans, the islands' area reported apart ([`empty_region::measure`]).
    islands: bool,
}

/// How a case ended.
#[derive(Clone, Debug, serde::Serialize)]
struct Case {
    drawing: String,
    connected: bool,
    /// One piece with islands left out (README: `islands`).
    islands: bool,
    tiles_asked: usize,
    /// "0", "1", "2" or "timeout" (or "crash" for any other end).
    exit: String,
    cpu_s: f64,
    tiles: Option<usize>,
    u_turns: Option<usize>,
    quarter_turns: Option<usize>,
    covered: Option<f64>,
    outside: Option<f64>,
    /// Largest empty region, tile areas (0 when none).
    empty_tiles: Option<f64>,
    /// Area of the islands left out (tile areas), for a drawing with islands.
    left_out_tiles: Option<f64>,
    /// The first line of the refusal or error.
    message: Option<String>,
}

fn corpus_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus")
}

/// The drawings in the README's table: rows `| `dir/file.svg` | yes/no | ...`.
fn drawings(readme: &str) -> Vec<Drawing> {
    readme
        .lines()
        .filter_map(|line| {
            let cells: Vec<&str> = line.split('|').map(str::trim).collect();
            let name = cells.get(1)?.strip_prefix('`')?.strip_suffix('`')?;
            if !name.ends_with(".svg") {
                return None;
            }
            let (connected, islands) = match *cells.get(2)? {
                "yes" => (true, false),
                // islands: one part, its islands left out at every count (`parts.rs`)
                "islands" => (true, true),
                "no" => (false, false),
                _ => return None,
            };
            Some(Drawing {
                name: name.to_string(),
                connected,
                islands,
            })
        })
        .collect()
}

/// CPU seconds (user + system) of all waited-for children so far.
fn children_cpu() -> f64 {
    getrusage(UsageWho::RUSAGE_CHILDREN).map_or(f64::NAN, |u| {
        let s = |t: nix::sys::time::TimeVal| t.tv_sec() as f64 + t.tv_usec() as f64 * 1e-6;
        s(u.user_time()) + s(u.system_time())
    })
}

/// CPU seconds (user + system, all threads) a running process has used so far, from
/// `/proc/PID/stat` (fields 14 and 15, in clock ticks); `None` where it cannot be read.
fn running_cpu(pid: u32) -> Option<f64> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // the command name (field 2) may hold spaces: count fields after its closing ')'
    let rest = &stat[stat.rfind(')')? + 1..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks: f64 = f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?;
    let per_s = nix::unistd::sysconf(nix::unistd::SysconfVar::CLK_TCK)
        .ok()
        .flatten()
        .filter(|&t| t > 0)
        .unwrap_or(100) as f64;
    Some(ticks / per_s)
}

/// Plans one case in a child process; `timeout` is the CPU limit.
fn run_case(exe: &Path, d: &Drawing, tiles: usize, timeout: Duration) -> Case {
    let path = corpus_dir().join(&d.name);
    let mut case = Case {
        drawing: d.name.clone(),
        connected: d.connected,
        islands: d.islands,
        tiles_asked: tiles,
        exit: String::new(),
        cpu_s: f64::NAN,
        tiles: None,
        u_turns: None,
        quarter_turns: None,
        covered: None,
        outside: None,
        empty_tiles: None,
        left_out_tiles: None,
        message: None,
    };
    let before = children_cpu();
    let child = Command::new(exe)
        .arg("--one")
        .arg(&path)
        .arg(tiles.to_string())
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn();
    let mut child = match child {
        Ok(c) => c,
        Err(e) => {
            case.exit = "crash".into();
            case.message = Some(format!("cannot start: {e}"));
            return case;
        }
    };
    // read both pipes on threads so that a large plan cannot block the child
    let mut out_pipe = child.stdout.take().expect("piped stdout");
    let mut err_pipe = child.stderr.take().expect("piped stderr");
    let out_reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = out_pipe.read_to_string(&mut s);
        s
    });
    let err_reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = err_pipe.read_to_string(&mut s);
        s
    });
    let start = Instant::now();
    let status = loop {
        match child.try_wait() {
            Ok(Some(status)) => break Some(status),
            Ok(None)
                if start.elapsed() >= timeout.mul_f64(WALL_FACTOR)
                    || running_cpu(child.id()).is_some_and(|c| c >= timeout.as_secs_f64()) =>
            {
                let _ = child.kill();
                let _ = child.wait();
                break None;
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(20)),
            Err(_) => break None,
        }
    };
    case.cpu_s = children_cpu() - before;
    let out = out_reader.join().unwrap_or_default();
    let err = err_reader.join().unwrap_or_default();
    let Some(status) = status else {
        case.exit = "timeout".into();
        return case;
    };
    case.exit = status
        .code()
        .map_or_else(|| "crash".to_string(), |c| c.to_string());
    if status.code() != Some(0) {
        case.message = err.lines().next().map(|l| l.chars().take(160).collect());
        return case;
    }
    let plan = match Plan::from_json(&out) {
        Ok(p) => p,
        Err(e) => {
            case.exit = "crash".into();
            case.message = Some(format!("unreadable plan JSON: {e}"));
            return case;
        }
    };
    case.tiles = Some(plan.tiles);
    case.u_turns = Some(plan.u_turns);
    case.quarter_turns = Some(plan.quarter_turns);
    case.covered = Some(plan.metrics.covered_share);
    case.outside = Some(plan.metrics.outside_share);
    if let Some(shape) = std::fs::read(&path)
        .ok()
        .and_then(|data| Shape::from_svg_data(&data, &d.name).ok())
    {
        let centres: Vec<(f64, f64)> = plan.poses.iter().map(|p| (p.x, p.y)).collect();
        let m = empty_region::measure(&shape, &centres, plan.tile_size, d.islands);
        case.empty_tiles = Some(m.largest.map_or(0.0, |r| r.tiles));
        case.left_out_tiles = d.islands.then_some(m.left_out_tiles);
    }
    case
}

/// The child: plans one case and prints the plan's JSON, or the error and its exit code.
fn plan_one(path: &str, tiles: &str) -> ExitCode {
    let Ok(n) = tiles.parse::<usize>() else {
        eprintln!("bad tile count {tiles}");
        return ExitCode::from(2);
    };
    match plan_svg_file(Path::new(path), &PlanOptions::default().with_tiles(n)) {
        Ok(plan) => {
            println!("{}", plan.to_json());
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("{}", e.to_string().replace('\n', " "));
            ExitCode::from(e.exit_code() as u8)
        }
    }
}

fn opt<T: std::fmt::Display>(v: Option<T>) -> String {
    v.map_or_else(|| "-".to_string(), |v| v.to_string())
}

fn share(v: Option<f64>) -> String {
    v.map_or_else(|| "-".to_string(), |v| format!("{v:.3}"))
}

fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// The ladder's counts from `n`: its shares, at most [`LADDER_CAP`], each once.
fn ladder(n: usize) -> Vec<usize> {
    let mut v: Vec<usize> = LADDER
        .iter()
        .map(|f| ((n as f64 * f).round() as usize).min(LADDER_CAP))
        .collect();
    v.dedup();
    v
}

/// The cases of one-piece drawings refused or timed out at a count above one at which the
/// drawing planned: `drawing at M (exit E; planned at K)`. (A drawing not in one piece is
/// refused at every count: its parts are decided from its outline, not at the count.)
fn ladder_breaks(cases: &[Case]) -> Vec<String> {
    cases
        .iter()
        .filter(|c| c.connected && c.exit != "0")
        .filter_map(|c| {
            let below = cases
                .iter()
                .filter(|o| {
                    o.drawing == c.drawing && o.exit == "0" && o.tiles_asked < c.tiles_asked
                })
                .map(|o| o.tiles_asked)
                .max()?;
            Some(format!(
                "{} at {} (exit {}; planned at {below})",
                c.drawing, c.tiles_asked, c.exit
            ))
        })
        .collect()
}

/// The summary line (over the connected drawings' cases).
fn summary(cases: &[Case], timeout: f64) -> String {
    let conn: Vec<&Case> = cases.iter().filter(|c| c.connected).collect();
    let planned = conn.iter().filter(|c| c.exit == "0").count();
    let timeouts = conn.iter().filter(|c| c.exit == "timeout").count();
    let mut cpu: Vec<f64> = conn.iter().map(|c| c.cpu_s).collect();
    let max = cpu.iter().copied().fold(0.0, f64::max);
    let med = median(&mut cpu);
    let empty = conn
        .iter()
        .filter(|c| c.empty_tiles.is_some_and(|e| e > EMPTY_LIMIT))
        .count();
    let off = conn
        .iter()
        .filter(|c| {
            c.tiles.is_some_and(|t| {
                (t as f64 - c.tiles_asked as f64).abs() > COUNT_TOLERANCE * c.tiles_asked as f64
            })
        })
        .count();
    let others = cases.len() - conn.len();
    let others_refused = cases
        .iter()
        .filter(|c| !c.connected && c.exit != "0")
        .count();
    let breaks = ladder_breaks(cases);
    let islands: Vec<f64> = conn.iter().filter_map(|c| c.left_out_tiles).collect();
    format!(
        "Summary: {planned} of {} connected cases planned ({timeouts} timeouts at {timeout:.0} s of CPU); CPU per case median {med:.2} s, max {max:.2} s; {empty} plans with an empty region > {EMPTY_LIMIT} tile areas; {off} plans with the tile count outside {:.0}% of the request; {} plans of drawings with islands measured without them (islands left out: at most {:.1} tile areas); {others_refused} of {others} cases of drawings not in one piece refused; {} cases refused at a count above one that planned{}",
        conn.len(),
        100.0 * COUNT_TOLERANCE,
        islands.len(),
        islands.iter().copied().fold(0.0, f64::max),
        breaks.len(),
        if breaks.is_empty() {
            String::new()
        } else {
            format!(": {}", breaks.join(", "))
        }
    )
}

fn markdown(cases: &[Case], summary: &str) -> String {
    let mut s = String::from(
        "| drawing | one piece | tiles asked | exit | CPU s | tiles | U-turns | quarter turns | covered | outside | largest empty (tile areas) | islands left out (tile areas) |\n|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    for c in cases {
        s.push_str(&row(c));
        s.push('\n');
    }
    s.push('\n');
    s.push_str(summary);
    s.push('\n');
    s
}

/// One case as a Markdown table row.
fn row(c: &Case) -> String {
    format!(
        "| {} | {} | {} | {} | {:.2} | {} | {} | {} | {} | {} | {} | {} |",
        c.drawing,
        match (c.connected, c.islands) {
            (true, true) => "islands",
            (true, false) => "yes",
            _ => "no",
        },
        c.tiles_asked,
        c.exit,
        c.cpu_s,
        opt(c.tiles),
        opt(c.u_turns),
        opt(c.quarter_turns),
        share(c.covered),
        share(c.outside),
        c.empty_tiles
            .map_or_else(|| "-".to_string(), |e| format!("{e:.1}")),
        c.left_out_tiles
            .map_or_else(|| "-".to_string(), |e| format!("{e:.1}")),
    )
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("--one") && args.len() == 3 {
        return plan_one(&args[1], &args[2]);
    }
    let mut tiles: Vec<usize> = TILES.to_vec();
    let mut timeout = TIMEOUT_S;
    let mut filter: Option<String> = None;
    let (mut md_out, mut json_out) = (None, None);
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = || it.next().cloned().unwrap_or_default();
        match a.as_str() {
            "--bench" => {}
            "--tiles" => {
                tiles = value()
                    .split(',')
                    .filter_map(|t| t.trim().parse().ok())
                    .collect()
            }
            "--ladder" => match value().trim().parse::<usize>() {
                Ok(n) if n > 0 => tiles = ladder(n),
                _ => {
                    eprintln!("corpus: --ladder takes a tile count");
                    return ExitCode::from(2);
                }
            },
            "--timeout" => timeout = value().parse().unwrap_or(TIMEOUT_S),
            "--filter" => filter = Some(value()),
            "--markdown" => md_out = Some(value()),
            "--json" => json_out = Some(value()),
            other => {
                eprintln!("corpus: unknown argument {other}");
                return ExitCode::from(2);
            }
        }
    }
    let readme = match std::fs::read_to_string(corpus_dir().join("README.md")) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("corpus: cannot read the corpus README: {e}");
            return ExitCode::from(2);
        }
    };
    let exe = match std::env::current_exe() {
        Ok(e) => e,
        Err(e) => {
            eprintln!("corpus: cannot find this program: {e}");
            return ExitCode::from(2);
        }
    };
    let list: Vec<Drawing> = drawings(&readme)
        .into_iter()
        .filter(|d| filter.as_ref().is_none_or(|f| d.name.contains(f.as_str())))
        .collect();
    let mut cases = Vec::new();
    let total = list.len() * tiles.len();
    for d in &list {
        for &n in &tiles {
            let c = run_case(&exe, d, n, Duration::from_secs_f64(timeout));
            eprintln!(
                "[{}/{}] {}{}",
                cases.len() + 1,
                total,
                row(&c),
                c.message
                    .as_ref()
                    .map_or(String::new(), |m| format!(" {m}"))
            );
            cases.push(c);
        }
    }
    let line = summary(&cases, timeout);
    let md = markdown(&cases, &line);
    print!("{md}");
    if let Some(p) = md_out {
        if let Err(e) = std::fs::write(&p, &md) {
            eprintln!("corpus: cannot write {p}: {e}");
        }
    }
    if let Some(p) = json_out {
        let json = serde_json::json!({
            "timeout_s": timeout,
            "cases": cases,
            "more_tiles_refused": ladder_breaks(&cases),
            "summary": line
        });
        if let Err(e) = std::fs::write(&p, serde_json::to_string_pretty(&json).unwrap_or_default())
        {
            eprintln!("corpus: cannot write {p}: {e}");
        }
    }
    ExitCode::SUCCESS
}
