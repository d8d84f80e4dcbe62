//! Collision benchmark: `cargo bench --bench collision`.
//!
//! Prints the time of the sequential sweep check of serpentine chains from 1,000 to 1,000,000
//! tiles. (The counting benchmark is `benches/count.rs`.)

use std::time::Instant;

use foldchain::collision::{check_word, CheckOptions};
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
