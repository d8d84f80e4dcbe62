//! The printed tiles measured on their meshes (issue 30's "must show"): the nine tile types
//! of the thesis design are closed, manifold and consistently oriented, 30 mm across flats
//! and 7.5 mm high; each channel is as wide as the magnet plus the clearance at the middle
//! of its path; a disc of the magnet's diameter swept along each path from its rest point to
//! its final point stays inside its channel. Every measure is taken from the triangles (a
//! cross-section of the mesh), not from the regions they were built from.

use foldchain::magnet_path::PathEnd;
use foldchain::tolerance::Printer;
use foldchain::{Design, Tile};
use foldchain_print::{Mesh, PartOptions, TilePart};
use proptest::prelude::*;

type Pt = [f64; 2];

/// How far along `dir` from `p` the first section segment lies.
fn ray_hit(section: &[(Pt, Pt)], p: Pt, dir: Pt) -> f64 {
    let mut best = f64::INFINITY;
    for &(a, b) in section {
        let e = [b[0] - a[0], b[1] - a[1]];
        let den = dir[0] * e[1] - dir[1] * e[0];
        if den.abs() < 1e-15 {
            continue;
        }
        let w = [a[0] - p[0], a[1] - p[1]];
        let t = (w[0] * e[1] - w[1] * e[0]) / den;
        let s = (w[0] * dir[1] - w[1] * dir[0]) / den;
        if t > 0.0 && (0.0..=1.0).contains(&s) {
            best = best.min(t);
        }
    }
    best
}

fn dist_to_segment(p: Pt, a: Pt, b: Pt) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let l2 = d[0] * d[0] + d[1] * d[1];
    let t = if l2 > 0.0 {
        (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p[0] - a[0] - t * d[0]).hypot(p[1] - a[1] - t * d[1])
}

/// Whether `p` lies in the material of the section (an odd number of crossings to +x).
fn in_material(section: &[(Pt, Pt)], p: Pt) -> bool {
    let mut odd = false;
    for &(a, b) in section {
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if x > p[0] {
                odd = !odd;
            }
        }
    }
    odd
}

/// The extent of the mesh's vertices along a unit direction in the plane.
fn extent(m: &Mesh, dir: Pt) -> f64 {
    let proj = m.vertices.iter().map(|v| v[0] * dir[0] + v[1] * dir[1]);
    let (lo, hi) = proj.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
        (lo.min(x), hi.max(x))
    });
    hi - lo
}

/// Checks one part on its mesh; returns the channel widths measured at the paths' middles.
fn check_part(part: &TilePart) -> [f64; 2] {
    let tile = part.tile;
    let opts = &part.options;
    let d = &part.design;
    let m = &part.mesh;
    let topo = m.topology();
    assert!(topo.is_sound(), "{tile}: {topo:?}");
    assert!(m.volume() > 0.0, "{tile}: faces point inwards");
    // across flats in all four flat directions, and the height
    let h = std::f64::consts::FRAC_1_SQRT_2;
    for dir in [[1.0, 0.0], [0.0, 1.0], [h, h], [h, -h]] {
        let w = extent(m, dir);
        assert!(
            (w - d.tile_width).abs() < 0.01,
            "{tile}: {w} across {dir:?}"
        );
    }
    let (lo, hi) = m.bounds();
    assert!(
        lo[2].abs() < 1e-12 && (hi[2] - opts.height).abs() < 0.01,
        "{tile}"
    );
    // the magnet's centre of mass lies below the wall top
    assert!(opts.floor + 0.5 * d.magnet_height < opts.height);
    // a cross-section through the channels, below the engraved mark
    let z = opts.floor + 0.5 * (opts.height - opts.mark_depth - opts.floor);
    let section = m.section(z);
    let want = d.magnet_diameter + opts.clearance;
    let mut widths = [0.0; 2];
    for (k, end) in [PathEnd::First, PathEnd::Second].into_iter().enumerate() {
        let path = part.channel(end).path;
        let len = path.length();
        let ((x, y), (tx, ty)) = path.point_and_tangent_at(0.5 * len);
        let n = [-ty, tx];
        let width = ray_hit(&section, [x, y], n) + ray_hit(&section, [x, y], [-n[0], -n[1]]);
        assert!(
            (width - want).abs() < 0.01,
            "{tile} {end:?}: channel {width} mm wide at the path's middle, want {want}"
        );
        widths[k] = width;
        // the magnet's disc swept from rest to final point: its centre in the channel's void,
        // every wall at least a magnet radius away
        let r = 0.5 * d.magnet_diameter;
        let steps = 400;
        for i in 0..=steps {
            let u = len * i as f64 / steps as f64;
            let (px, py) = path.point_at(u);
            let p = [px, py];
            assert!(
                !in_material(&section, p),
                "{tile} {end:?}: u {u} in material"
            );
            let nearest = section
                .iter()
                .map(|&(a, b)| dist_to_segment(p, a, b))
                .fold(f64::INFINITY, f64::min);
            assert!(
                nearest >= r + 0.5 * opts.clearance - 0.01,
                "{tile} {end:?}: at u = {u:.3} mm a wall is {nearest:.4} mm from the magnet's centre (radius {r})"
            );
        }
    }
    widths
}

#[test]
fn nine_thesis_tiles_are_closed_sized_and_hold_their_magnets() {
    for printer in [Printer::Fdm, Printer::Resin] {
        let opts = PartOptions::for_printer(printer);
        for tile in Tile::ALL {
            let part = TilePart::new(tile, &Design::thesis(), &opts).unwrap();
            let w = check_part(&part);
            if printer == Printer::Fdm && tile == Tile::ALL[4] {
                println!(
                    "{tile}: {} triangles, {:.1} mm3, channel widths {:.4} {:.4} mm, thinnest wall {:.3} mm ({})",
                    part.mesh.triangles.len(),
                    part.volume(),
                    w[0],
                    w[1],
                    part.thinnest_wall.thickness,
                    part.thinnest_wall.place
                );
            }
        }
    }
}

#[test]
fn a_turned_part_is_the_same_solid() {
    // SL turned by 180 degrees is RS: the same volume, and the same extents
    let opts = PartOptions::default();
    for tile in Tile::ALL {
        let a = TilePart::new(tile, &Design::thesis(), &opts).unwrap();
        let b = TilePart::new(tile.turned(), &Design::thesis(), &opts).unwrap();
        assert!((a.volume() - b.volume()).abs() < 1e-3, "{tile}");
    }
}

#[test]
fn stl_keeps_the_mesh_sound() {
    let part = TilePart::new(
        "LL".parse().unwrap(),
        &Design::thesis(),
        &PartOptions::default(),
    )
    .unwrap();
    let bytes = foldchain_print::to_stl(&part.mesh, "LL");
    let back = foldchain_print::from_stl(&bytes).unwrap();
    assert_eq!(back.vertices.len(), part.mesh.vertices.len());
    assert!(back.topology().is_sound(), "{:?}", back.topology());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    /// Any design in range either builds a sound, correctly sized part or is refused with an
    /// error; it never panics.
    #[test]
    fn designs_build_sound_parts_or_clear_errors(
        w in 20.0f64..60.0,
        s in 0.0f64..0.6,
        e_share in 0.1f64..0.33,
        wall in 0.3f64..2.0,
        dia in 1.5f64..5.0,
        clearance in 0.0f64..0.4,
        tile in 0usize..9,
    ) {
        let design = Design {
            e: e_share * w,
            s,
            wall,
            magnet_diameter: dia,
            ..Design::thesis().with_tile_width(w)
        };
        let opts = PartOptions::default().with_clearance(clearance);
        match TilePart::new(Tile::ALL[tile], &design, &opts) {
            Ok(part) => {
                check_part(&part);
            }
            Err(e) => {
                let text = e.to_string();
                prop_assert!(!text.is_empty());
            }
        }
    }
}
