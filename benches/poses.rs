//! Benchmark of the core kinematics: exact final poses against `f64` composition.
//!
//! Run with `cargo bench --bench poses`. For chains of 1e3 to 1e6 tiles (a serpentine of
//! straight rows joined by alternating tight U-turns, then a run of a random word) it times
//! [`kinematics::final_poses`] (exact) and [`kinematics::poses_at_angles`] (`f64`
//! composition at the final angles), reports memory per tile and the process' peak RSS, and
//! measures the drift of the `f64` composition from the exact poses. A second table gives the
//! drift of a word that only turns left (the heading winds n/4 times), the worst case for the
//! `f64` composition, whose angle is not reduced modulo 2 pi.
//!
//! Prints Markdown tables for `BENCHMARKS.md`.

use std::f64::consts::TAU;
use std::hint::black_box;
use std::time::{Duration, Instant};

use foldchain::{ExactPose, Fold, FoldWord, Pose, QuarterTurns};

/// Tile width for the `f64` poses, mm (the thesis' tiles); drift is reported in tile widths.
const W: f64 = 30.0;

/// The chain sizes, in tiles.
const SIZES: [usize; 4] = [1_000, 10_000, 100_000, 1_000_000];

/// SplitMix64: a small deterministic generator, so every run times the same words.
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
}

/// A word of `tiles - 1` letters: the first 90% a serpentine of rows of about
/// `sqrt(tiles)` straight tiles joined by tight U-turns (`LL`, then `RR`, alternately), the
/// rest random letters. Returns the word and the number of letters of the serpentine part.
fn serpentine_word(tiles: usize, seed: u64) -> (FoldWord, usize) {
    let letters = tiles - 1;
    let serpentine = letters * 9 / 10;
    let row = ((tiles as f64).sqrt() as usize).max(4);
    let mut folds = Vec::with_capacity(letters);
    let mut left = true;
    while folds.len() < serpentine {
        folds.extend(std::iter::repeat_n(Fold::S, row));
        let turn = if left { Fold::L } else { Fold::R };
        folds.extend([turn, turn]);
        left = !left;
    }
    folds.truncate(serpentine);
    let mut rng = SplitMix(seed);
    while folds.len() < letters {
        folds.push(Fold::ALL[(rng.next() % 3) as usize]);
    }
    (FoldWord::from_folds(folds), serpentine)
}

/// The median wall time of `f`, over enough repetitions to take about a quarter second
/// (at least three).
fn time<T>(mut f: impl FnMut() -> T) -> Duration {
    let start = Instant::now();
    black_box(f());
    let once = start.elapsed().max(Duration::from_nanos(1));
    let reps = ((0.25 / once.as_secs_f64()) as usize).clamp(3, 10_000);
    let mut times: Vec<Duration> = (0..reps)
        .map(|_| {
            let t = Instant::now();
            black_box(f());
            t.elapsed()
        })
        .collect();
    times.sort();
    times[reps / 2]
}

/// Peak resident set size of this process so far, kB (`VmHWM` of `/proc/self/status`).
fn peak_rss_kb() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// The distance between two angles on the circle.
fn angle_gap(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(TAU);
    d.min(TAU - d)
}

/// Drift of the `f64` composition from the exact poses over `range` of tiles:
/// (max centre distance in tile widths, max heading difference in radians).
fn drift(exact: &[ExactPose], float: &[Pose], range: std::ops::Range<usize>) -> (f64, f64) {
    let mut centre: f64 = 0.0;
    let mut heading: f64 = 0.0;
    for k in range {
        let e = exact[k].to_pose(W);
        let f = float[k];
        centre = centre.max((e.x - f.x).hypot(e.y - f.y) / W);
        heading = heading.max(angle_gap(f.angle, e.angle));
    }
    (centre, heading)
}

/// The largest distance of a tile centre from the first, in tile widths.
fn extent(exact: &[ExactPose]) -> f64 {
    exact
        .iter()
        .map(|p| {
            let (x, y) = p.centre.to_f64(1.0);
            x.hypot(y)
        })
        .fold(0.0, f64::max)
}

fn main() {
    println!(
        "sizes: ExactPose {} B, Pose {} B, Fold {} B, angle {} B; tile width {W} mm",
        size_of::<ExactPose>(),
        size_of::<Pose>(),
        size_of::<Fold>(),
        size_of::<f64>()
    );
    println!();
    println!("Serpentine (90%, rows of ~sqrt(n) tiles, tight U-turns) + random word (10%):");
    println!();
    println!(
        "| tiles | exact `final_poses` | ns/tile | f64 `poses_at_angles` | ns/tile \
         | baseline: fill a Vec<ExactPose> | ns/tile | bytes/tile (word+angles+exact+f64) | peak RSS | extent (w) \
         | centre drift, serpentine part (w) | centre drift, all (w) | heading drift (rad) |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for &n in &SIZES {
        let (word, serpentine) = serpentine_word(n, 0x5EED ^ n as u64);
        assert_eq!(word.tiles(), n);
        let angles = word.final_angles();
        let t_exact = time(|| black_box(&word).final_poses());
        let t_float = time(|| Pose::chain_at_angles(black_box(&angles), W));
        // the memory cost alone: a fresh Vec of n poses, every page written
        let t_fill = time(|| {
            (0..n)
                .map(|i| ExactPose {
                    heading: QuarterTurns::new(i as i64),
                    ..ExactPose::default()
                })
                .collect::<Vec<_>>()
        });
        let exact = word.final_poses();
        let float = Pose::chain_at_angles(&angles, W);
        let (d_serp, _) = drift(&exact, &float, 0..serpentine + 1);
        let (d_all, h_all) = drift(&exact, &float, 0..n);
        let bytes =
            size_of::<Fold>() + size_of::<f64>() + size_of::<ExactPose>() + size_of::<Pose>();
        let rss = peak_rss_kb().map_or("n/a".to_string(), |kb| {
            format!("{:.1} MB", kb as f64 / 1024.0)
        });
        println!(
            "| {n} | {:.3} ms | {:.2} | {:.3} ms | {:.2} | {:.3} ms | {:.2} | {bytes} ({:.1} MB) | {rss} | {:.0} | {d_serp:.2e} | {d_all:.2e} | {h_all:.2e} |",
            t_exact.as_secs_f64() * 1e3,
            t_exact.as_secs_f64() * 1e9 / n as f64,
            t_float.as_secs_f64() * 1e3,
            t_float.as_secs_f64() * 1e9 / n as f64,
            t_fill.as_secs_f64() * 1e3,
            t_fill.as_secs_f64() * 1e9 / n as f64,
            (bytes * n) as f64 / 1e6,
            extent(&exact),
        );
    }
    println!();
    println!("Winding word (every joint L: the heading turns n/4 times):");
    println!();
    println!("| tiles | quarter turns | centre drift (w) | heading drift (rad) |");
    println!("|---:|---:|---:|---:|");
    for &n in &SIZES {
        let word = FoldWord::from_folds(vec![Fold::L; n - 1]);
        let exact = word.final_poses();
        let float = Pose::chain_at_angles(&word.final_angles(), W);
        let (d, h) = drift(&exact, &float, 0..n);
        println!("| {n} | {} | {d:.2e} | {h:.2e} |", n - 1);
    }
    println!();
    if let Some(kb) = peak_rss_kb() {
        println!("peak RSS of the whole run: {:.1} MB", kb as f64 / 1024.0);
    }
}
