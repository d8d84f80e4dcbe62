//! The scenes `fold-validate` runs: the thesis' three-tile experiments, a 20-tile straight
//! chain at three values of `s`, and the 107-tile square.
//!
//! The square is built here, not read from the planner (the core crate cannot depend on
//! it): nine serpentine rows joined by tight U-turns (one LL or RR tile each, alternating),
//! ten straight joints per row, the word cut at 106 joints. Rows are 11 tiles long and
//! `sqrt2 w` apart, so the square is about 11 w by 9 sqrt2 w (330 mm by 382 mm on 30 mm
//! tiles), as the thesis' 107-tile square with tight turns.

use foldchain::timeline::TileDesigns;
use foldchain::{Chain, Design};

/// One scene.
#[derive(Clone, Debug)]
pub struct Scene {
    /// Short name (table and JSON).
    pub name: &'static str,
    /// What it shows.
    pub description: &'static str,
    /// The chain.
    pub chain: Chain,
    /// The designs.
    pub designs: TileDesigns,
}

/// The fold word of the 107-tile square (see the module documentation).
pub fn square_107_word() -> String {
    let mut w = String::new();
    let mut left = true;
    while w.len() < 106 {
        w.push_str("SSSSSSSSSS");
        w.push_str(if left { "LL" } else { "RR" });
        left = !left;
    }
    w.truncate(106);
    w
}

fn scene(name: &'static str, description: &'static str, word: &str, s: f64) -> Option<Scene> {
    // every word here is built from S, L and R only, so parsing cannot fail
    Some(Scene {
        name,
        description,
        chain: Chain::parse(word).ok()?,
        designs: TileDesigns::global(Design::thesis().with_s(s)),
    })
}

/// Every scene, in table order.
pub fn all_scenes() -> Vec<Scene> {
    let e = Design::thesis().e;
    vec![
        scene(
            "3-tile SL",
            "thesis 7.3: linear propagation, then a 90 degree fold",
            "SL",
            0.3,
        ),
        scene(
            "3-tile LL",
            "thesis 7.3: two folds making 180 degrees",
            "LL",
            0.3,
        ),
        scene(
            "20-tile s=0",
            "straight chain, simultaneous limit",
            "S*19",
            0.0,
        ),
        scene("20-tile s=0.3", "straight chain, thesis s", "S*19", 0.3),
        scene(
            "20-tile s=e/3",
            "straight chain, sequential edge",
            "S*19",
            e / 3.0,
        ),
        scene(
            "107-tile square",
            "serpentine square with tight U-turns",
            &square_107_word(),
            0.3,
        ),
    ]
    .into_iter()
    .flatten()
    .collect()
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    #[test]
    fn square_has_107_tiles_and_16_folds() {
        let w = square_107_word();
        assert_eq!(w.len(), 106);
        assert_eq!(Chain::parse(&w).unwrap().len(), 107);
        // eight tight U-turns of two folds each
        assert_eq!(w.chars().filter(|&c| c != 'S').count(), 16);
    }

    #[test]
    #[ignore = "slow: simulates the 107-tile square (tens of seconds on two cores); .ci/run runs it"]
    fn square_folds_cleanly() {
        let chain = Chain::parse(&square_107_word()).unwrap();
        let (_, summary) = foldchain::simulate(
            &chain,
            &TileDesigns::default(),
            &foldchain::engine::EngineOptions::default(),
            &foldchain::collision::CheckOptions::default(),
        )
        .unwrap();
        assert!(summary.completed, "{summary:?}");
        assert_eq!(summary.folds.len(), 16);
    }
}
