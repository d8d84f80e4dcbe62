//! Counting benchmark: `cargo bench --bench count [-- MAX_N]`.
//!
//! For each longest length N from 12 to MAX_N (default 24), counts every length up to N in one
//! search and prints the valid count at N, the search nodes (words searched, mirror images
//! once: the sum over lengths t <= N of (valid(t) + 1) / 2, the node count of
//! `../shared/bench/ref-enum.c` for the same tree), the wall time and the nanoseconds per node
//! times the threads (`RAYON_NUM_THREADS=1` for one core).

use std::time::Instant;

use foldchain::count::CountOptions;

fn main() {
    let max_n: usize = std::env::args()
        .skip(1)
        .find_map(|a| a.parse().ok())
        .unwrap_or(24);
    let threads = rayon::current_num_threads();
    println!("threads: {threads}");
    println!(
        "{:>5} {:>14} {:>14} {:>10} {:>16}",
        "N", "valid(N)", "nodes", "seconds", "ns/node x threads"
    );
    for n in 12..=max_n {
        let t = Instant::now();
        let rows = CountOptions::default()
            .with_tiles(1, n)
            .count_valid(&|_, _| {})
            .expect("valid options");
        let secs = t.elapsed().as_secs_f64();
        let nodes: u128 = rows.iter().map(|r| r.valid.div_ceil(2)).sum();
        let valid = rows.last().map_or(0, |r| r.valid);
        println!(
            "{:>5} {:>14} {:>14} {:>10.3} {:>16.1}",
            n,
            valid,
            nodes,
            secs,
            secs * 1e9 * threads as f64 / nodes as f64
        );
    }
}
