//! Checks shared by the planner's integration tests: a plan is consistent with itself and
//! with the exact kinematics, and its final tiles do not overlap, tested by plain geometry
//! written here (not by the planner's own collision check).

#![allow(dead_code)] // each test file uses its part
#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::path::{Path, PathBuf};

use foldchain_planner::{plan_svg_file, Plan, PlanOptions};

/// A sample shape's path.
pub fn sample(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shapes")
        .join(name)
}

/// A drawing of the planner corpus (`planner/corpus/{name}`).
pub fn corpus(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("corpus")
        .join(name)
}

/// The plan of corpus drawing `name` for about `tiles` tiles with the default options;
/// a refusal fails the test, naming the drawing and the count.
pub fn plan_corpus(name: &str, tiles: usize) -> Plan {
    plan_svg_file(&corpus(name), &PlanOptions::default().with_tiles(tiles))
        .unwrap_or_else(|e| panic!("{name} at {tiles}: {e}"))
}

/// Overlap allowed between two tiles, as a share of the tile width: touching tiles (every
/// pair of neighbours along the chain shares a face) meet at depth 0 up to rounding of
/// coordinates of a few hundred units (about 1e-13 w); any real overlap is far larger.
pub const OVERLAP_TOLERANCE: f64 = 1e-9;

/// The octagon of a tile of width `w` (across flats) centred at `(x, y)` with its faces
/// square to `heading_deg`, as its eight corners in order: they lie at 22.5 + 45 k degrees
/// from the heading, `w / (2 cos 22.5 deg)` from the centre.
pub fn octagon(x: f64, y: f64, heading_deg: f64, w: f64) -> [(f64, f64); 8] {
    let r = 0.5 * w / 22.5f64.to_radians().cos();
    std::array::from_fn(|k| {
        let a = (heading_deg + 22.5 + 45.0 * k as f64).to_radians();
        (x + r * a.cos(), y + r * a.sin())
    })
}

/// How deep two convex polygons overlap: the least overlap of their projections over every
/// edge normal of either (separating axis theorem); zero or less when they are apart or
/// touch.
pub fn overlap_depth(a: &[(f64, f64)], b: &[(f64, f64)]) -> f64 {
    let mut depth = f64::INFINITY;
    for poly in [a, b] {
        for i in 0..poly.len() {
            let (p, q) = (poly[i], poly[(i + 1) % poly.len()]);
            let (nx, ny) = (q.1 - p.1, p.0 - q.0);
            let len = nx.hypot(ny);
            let (nx, ny) = (nx / len, ny / len);
            let span = |poly: &[(f64, f64)]| {
                poly.iter()
                    .map(|&(x, y)| x * nx + y * ny)
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                        (lo.min(v), hi.max(v))
                    })
            };
            let (a0, a1) = span(a);
            let (b0, b1) = span(b);
            depth = depth.min(a1.min(b1) - a0.max(b0));
        }
    }
    depth
}

/// The deepest overlap between any two tiles of the plan's final configuration (tile
/// widths), with the pair.
pub fn deepest_overlap(p: &Plan) -> (f64, usize, usize) {
    let w = p.tile_size;
    let octs: Vec<[(f64, f64); 8]> = p
        .poses
        .iter()
        .map(|q| octagon(q.x, q.y, q.heading_deg, w))
        .collect();
    // corners lie w / (2 cos 22.5 deg) < 0.55 w from the centre: farther pairs cannot meet
    let reach = 1.1 * w;
    let mut worst = (f64::NEG_INFINITY, 0, 0);
    for i in 0..octs.len() {
        for j in i + 1..octs.len() {
            let (a, b) = (p.poses[i], p.poses[j]);
            if (a.x - b.x).abs() > reach || (a.y - b.y).abs() > reach {
                continue;
            }
            let d = overlap_depth(&octs[i], &octs[j]) / w;
            if d > worst.0 {
                worst = (d, i, j);
            }
        }
    }
    worst
}

/// The plan is consistent and its tiles do not overlap: word, tile list, parts list and
/// poses agree; the poses are the exact kinematics through `chain_to_svg`; neighbours are
/// one tile width apart; no LR/RL tile is used; and no two final octagons overlap by more
/// than [`OVERLAP_TOLERANCE`].
pub fn assert_sound(p: &Plan) {
    let word = p.fold_word().unwrap();
    assert_eq!(word.tiles(), p.tiles);
    assert_eq!(word.to_chain().to_tile_list(), p.tile_list);
    assert_eq!(p.poses.len(), p.tiles);
    assert_eq!(p.bom.values().sum::<usize>(), p.tiles);
    assert!(word.first_opposite_pair().is_none(), "LR/RL tiles used");
    let m = p.chain_to_svg;
    let exact = word.final_poses();
    assert_eq!(exact.len(), p.poses.len());
    for (e, q) in exact.iter().zip(&p.poses) {
        let (x, y) = e.centre.to_f64(1.0);
        let (sx, sy) = (m[0] * x + m[2] * y + m[4], m[1] * x + m[3] * y + m[5]);
        assert!((sx - q.x).abs() < 1e-6 * p.tile_size && (sy - q.y).abs() < 1e-6 * p.tile_size);
    }
    // neighbouring centres are w apart (straight, or diagonal across a fold)
    for pair in p.poses.windows(2) {
        let d = (pair[1].x - pair[0].x).hypot(pair[1].y - pair[0].y);
        assert!((d - p.tile_size).abs() < 1e-6 * p.tile_size, "step {d}");
    }
    let (depth, i, j) = deepest_overlap(p);
    assert!(
        depth <= OVERLAP_TOLERANCE,
        "tiles {i} and {j} overlap by {depth} tile widths: {}",
        p.summary()
    );
}

/// The share of a shape a serpentine's tiles can cover at most: one octagon (area
/// 2 (sqrt2 - 1) w^2) per column w wide and row pitch tall (sqrt2 w tight, (1 + sqrt2) w
/// loose).
pub fn row_density(loose: bool) -> f64 {
    let pitch = if loose {
        1.0 + 2f64.sqrt()
    } else {
        2f64.sqrt()
    };
    2.0 * (2f64.sqrt() - 1.0) / pitch
}
