//! Benchmark of the reference integrator (issue 16): wall time and work counters of
//! [`foldchain::reference::run_reference`] on the 107-tile square of `fold-validate` and on
//! straight chains of growing length.
//!
//! Run with `cargo bench --bench reference` (every case), or name cases:
//! `cargo bench --bench reference -- square` (the square only), `-- straight` (the straight
//! chains only), `-- square-1e-6` (Dormand-Prince at 1e-6 on the square only). Each case is
//! run three times and the median wall time printed, with the process' CPU time per run
//! (user and system, from `/proc/self/stat`) since the machine is shared. On the square the
//! event-time error against a reference run at 1e-10 (`err_time`, as `fold-validate`
//! computes it) is printed too.
//!
//! Prints a Markdown table for `BENCHMARKS.md`.

use std::time::Instant;

use foldchain::reference::{run_reference, Method, ReferenceOptions, ReferenceRun};
use foldchain::timeline::TileDesigns;
use foldchain::{Chain, Design};
use foldchain_validation::compare_events;
use foldchain_validation::scenes::all_scenes;

/// CPU seconds (user + system) of this process so far, from `/proc/self/stat` (fields 14
/// and 15, in clock ticks of 1/100 s on Linux); `None` where that file is missing.
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // the command name may hold spaces: fields start after its closing parenthesis
    let rest = &stat[stat.rfind(')')? + 2..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let utime: f64 = fields.get(11)?.parse().ok()?;
    let stime: f64 = fields.get(12)?.parse().ok()?;
    Some((utime + stime) / 100.0)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// One case: runs it three times, prints a row.
fn case(
    name: &str,
    chain: &Chain,
    designs: &TileDesigns,
    method: Method,
    tol: f64,
    reference: Option<&ReferenceRun>,
) {
    let opts = ReferenceOptions::default()
        .with_method(method)
        .with_tolerance(tol);
    let mut walls = Vec::new();
    let mut cpus = Vec::new();
    let mut last = None;
    for _ in 0..3 {
        let c0 = cpu_seconds();
        let t0 = Instant::now();
        let run = run_reference(chain, designs, &opts).expect("the bench's chains are valid");
        walls.push(t0.elapsed().as_secs_f64());
        if let (Some(a), Some(b)) = (c0, cpu_seconds()) {
            cpus.push(b - a);
        }
        last = Some(run);
    }
    let run = last.expect("three runs");
    let err = reference
        .map(|r| {
            format!(
                "{:.3e}",
                compare_events(&r.events, &run.events, r.duration()).error_time
            )
        })
        .unwrap_or_else(|| "-".into());
    let cpu = if cpus.is_empty() {
        "-".into()
    } else {
        format!("{:.3}", median(cpus))
    };
    let s = run.stats;
    println!(
        "| {name} | {} | {tol:e} | {:.3} | {cpu} | {} | {} | {} | {} | {} | {err} | {} |",
        method.name(),
        median(walls),
        s.accepted,
        s.rejected,
        s.rhs,
        s.event_steps,
        run.events.len(),
        run.result(),
    );
}

fn main() {
    let filters: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    let wanted = |name: &str| filters.is_empty() || filters.iter().any(|f| name.contains(f));
    println!("| case | method | tol | wall s (median of 3) | CPU s (median) | steps | rejected | rhs | event steps | events | err_time | outcome |");
    println!("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|");
    let square = all_scenes()
        .into_iter()
        .find(|s| s.name == "107-tile square")
        .expect("the square is a scene");
    let square_cases = [
        (Method::Dopri5, 1e-3),
        (Method::Dopri5, 1e-6),
        (Method::Dopri5, 1e-8),
        (Method::Ros2, 1e-5),
    ];
    let names: Vec<String> = square_cases
        .iter()
        .map(|(m, t)| format!("square-{}-{t:e}", m.name()))
        .collect();
    if names.iter().any(|n| wanted(n)) {
        let reference = run_reference(
            &square.chain,
            &square.designs,
            &ReferenceOptions::default().with_tolerance(1e-10),
        )
        .expect("the square is valid");
        for ((method, tol), n) in square_cases.iter().zip(&names) {
            if wanted(n) {
                case(
                    "107-tile square",
                    &square.chain,
                    &square.designs,
                    *method,
                    *tol,
                    Some(&reference),
                );
            }
        }
    }
    let designs = TileDesigns::global(Design::thesis().with_s(0.3));
    for tiles in [50usize, 100, 200, 400] {
        let name = format!("straight-{tiles}");
        if !wanted(&name) {
            continue;
        }
        let chain = Chain::parse(&format!("S*{}", tiles - 1)).expect("a straight word");
        case(
            &format!("S*{} ({tiles} tiles)", tiles - 1),
            &chain,
            &designs,
            Method::Dopri5,
            1e-6,
            None,
        );
    }
}
