//! Collision and counting benchmarks: `cargo bench --bench collision [-- MAX_N]`.
//!
//! Prints, for the fold-word count (thesis Table 5.1 extended), the valid count and the wall
//! time for each longest length up to MAX_N (default 22), and the time of the sequential
//! sweep check of serpentine chains from 1,000 to 1,000,000 tiles.

use std::time::Instant;

use foldchain::collision::{check_word, CheckOptions};
use foldchain::count::{count_valid, CountOptions};
use foldchain::{Fold, FoldWord};

/// Rows of `row` tiles joined by tight U-turns that alternate in direction, `tiles` in all.
fn serpentine(tiles: usize, row: usize) -> FoldWord {
    let mut folds = Vec::with_capacity(tiles);
    let mut left = true;
    while folds.len() + 1 < tiles {
        for _ in 0..row.saturating_sub(1) {
            if folds.len() + 1 >= tiles {
                break;
            }
            folds.push(Fold::S);
        }
        let f = if left { Fold::L } else { Fold::R };
        for _ in 0..2 {
            if folds.len() + 1 < tiles {
                folds.push(f);
            }
        }
        left = !left;
    }
    FoldWord::from_folds(folds)
}

fn main() {
    let max_n: usize = std::env::args()
        .skip(1)
        .find_map(|a| a.parse().ok())
        .unwrap_or(22);
    println!("threads: {}", rayon::current_num_threads());
    println!("{:>5} {:>14} {:>10}", "N", "valid(N)", "seconds");
    let mut n = 12;
    while n <= max_n {
        let t = Instant::now();
        let rows = count_valid(&CountOptions::default().with_tiles(n, n), &|_, _| {})
            .expect("valid options");
        println!(
            "{:>5} {:>14} {:>10.3}",
            n,
            rows[0].valid,
            t.elapsed().as_secs_f64()
        );
        n += 2;
    }
    println!();
    println!(
        "{:>9} {:>6} {:>10} {:>8}",
        "tiles", "row", "seconds", "verdict"
    );
    for tiles in [1_000usize, 10_000, 100_000, 1_000_000] {
        let row = (tiles as f64).sqrt().round() as usize;
        let w = serpentine(tiles, row);
        let t = Instant::now();
        let ok = check_word(&w, &CheckOptions::default()).is_ok();
        println!(
            "{:>9} {:>6} {:>10.3} {:>8}",
            tiles,
            row,
            t.elapsed().as_secs_f64(),
            if ok { "valid" } else { "collides" }
        );
    }
}
