//! A prism with pockets, as a closed mesh: a plate of a given outline and height from which
//! pockets (plane regions strictly inside the outline and apart from each other) are cut from
//! their own floor up through the top. The channels and the engraved mark of a tile are
//! such pockets.
//!
//! Faces: the bottom (the outline), the outline's walls, each pocket's walls and floor, and
//! the top (the outline less every pocket). Plane faces are triangulated by `spade`'s
//! constrained Delaunay triangulation on exactly the contours' vertices (no point is added,
//! no edge split), so every contour edge at a height is shared by one wall triangle and one
//! face triangle, and the mesh is closed by construction; [`crate::Mesh::topology`] checks it.

use spade::handles::FixedFaceHandle;
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

use crate::mesh::{Mesh, MeshBuilder};
use crate::region::{signed_area, Contour, Pt, Region};

/// A pocket: a region cut from `floor` (mm above the bottom) up through the top.
#[derive(Clone, Debug)]
pub struct Pocket {
    /// Its floor's height, mm.
    pub floor: f64,
    /// Its outline.
    pub region: Region,
}

/// The triangles of the region the contours bound by the even-odd rule, counter-clockwise.
/// An error when two contours cross or share a point.
pub fn triangulate(contours: &[&Contour]) -> Result<Vec<[Pt; 3]>, String> {
    let mut vertices = Vec::new();
    let mut edges = Vec::new();
    for c in contours {
        let first = vertices.len();
        let n = c.len();
        if n < 3 {
            return Err(format!("a contour of {n} points"));
        }
        for (i, p) in c.iter().enumerate() {
            vertices.push(Point2::new(p[0], p[1]));
            edges.push([first + i, first + (i + 1) % n]);
        }
    }
    let mut conflicts = 0usize;
    let cdt = ConstrainedDelaunayTriangulation::<Point2<f64>>::try_bulk_load_cdt(
        vertices.clone(),
        edges,
        |_| conflicts += 1,
    )
    .map_err(|e| format!("{e:?}"))?;
    if cdt.num_vertices() != vertices.len() {
        return Err(format!(
            "{} of {} points coincide",
            vertices.len() - cdt.num_vertices(),
            vertices.len()
        ));
    }
    if conflicts > 0 {
        return Err(format!("{conflicts} contour edges cross another"));
    }
    // even-odd parity by flood fill from the hull: crossing a contour edge flips it
    let mut parity: Vec<Option<bool>> = vec![None; cdt.num_inner_faces() + 1];
    let mut stack: Vec<FixedFaceHandle<spade::handles::InnerTag>> = Vec::new();
    for e in cdt.convex_hull() {
        for side in [e, e.rev()] {
            if let Some(inner) = side.face().as_inner() {
                let idx = inner.fix().index();
                if parity[idx].is_none() {
                    parity[idx] = Some(e.is_constraint_edge());
                    stack.push(inner.fix());
                }
            }
        }
    }
    while let Some(f) = stack.pop() {
        let here = parity[f.index()].unwrap_or(false);
        for e in cdt.face(f).adjacent_edges() {
            if let Some(next) = e.rev().face().as_inner() {
                let idx = next.fix().index();
                if parity[idx].is_none() {
                    parity[idx] = Some(here ^ e.is_constraint_edge());
                    stack.push(next.fix());
                }
            }
        }
    }
    let mut out = Vec::new();
    for f in cdt.inner_faces() {
        if parity[f.fix().index()] != Some(true) {
            continue;
        }
        let [a, b, c] = f.vertices().map(|v| {
            let p = v.position();
            [p.x, p.y]
        });
        let t = if signed_area(&[a, b, c]) < 0.0 {
            [a, c, b]
        } else {
            [a, b, c]
        };
        out.push(t);
    }
    Ok(out)
}

/// Which face could not be triangulated, and why.
#[derive(Clone, Debug)]
pub struct FaceError {
    /// The face: `bottom`, `top` or `pocket floor`.
    pub face: &'static str,
    /// Why.
    pub reason: String,
}

/// The closed mesh of the prism of `outline` (counter-clockwise) and `height` with `pockets`
/// cut. The caller keeps pockets inside the outline and apart from each other.
pub fn prism_with_pockets(
    outline: &Contour,
    height: f64,
    pockets: &[Pocket],
) -> Result<Mesh, FaceError> {
    let mut b = MeshBuilder::new();
    let err = |face: &'static str| move |reason: String| FaceError { face, reason };
    for t in triangulate(&[outline]).map_err(err("bottom"))? {
        b.flat(t, 0.0, false);
    }
    let n = outline.len();
    for i in 0..n {
        b.wall(outline[i], outline[(i + 1) % n], 0.0, height);
    }
    let mut top: Vec<&Contour> = vec![outline];
    for p in pockets {
        let cs: Vec<&Contour> = p.region.iter().flatten().collect();
        for t in triangulate(&cs).map_err(err("pocket floor"))? {
            b.flat(t, p.floor, true);
        }
        for c in &cs {
            // the solid lies outside the pocket: walk each contour with the pocket on the
            // right (i_overlay gives outer contours counter-clockwise, holes clockwise)
            let m = c.len();
            for i in 0..m {
                b.wall(c[(i + 1) % m], c[i], p.floor, height);
            }
        }
        top.extend(cs);
    }
    for t in triangulate(&top).map_err(err("top"))? {
        b.flat(t, height, true);
    }
    Ok(b.finish())
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use crate::region::{disc, union};

    #[test]
    fn a_square_with_a_round_pocket_and_a_ring_pocket_is_closed() {
        let outline = vec![[0.0, 0.0], [20.0, 0.0], [20.0, 10.0], [0.0, 10.0]];
        let hole = union(&[disc([5.0, 5.0], 2.0, 0.01)]);
        // a ring: a disc with a hole, whose island stays at full height
        let mut ring = union(&[disc([14.0, 5.0], 3.0, 0.01)]);
        let mut inner = disc([14.0, 5.0], 1.0, 0.01);
        inner.reverse();
        ring[0].push(inner);
        let pockets = [
            Pocket {
                floor: 1.0,
                region: hole.clone(),
            },
            Pocket {
                floor: 4.0,
                region: ring.clone(),
            },
        ];
        let m = prism_with_pockets(&outline, 5.0, &pockets).unwrap();
        let topo = m.topology();
        assert!(topo.is_sound(), "{topo:?}");
        let want =
            200.0 * 5.0 - crate::region::area(&hole) * 4.0 - crate::region::area(&ring) * 1.0;
        assert!((m.volume() - want).abs() < 1e-9, "{} vs {want}", m.volume());
    }

    #[test]
    fn crossing_contours_are_an_error_not_a_panic() {
        let a = vec![[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]];
        let b = vec![[2.0, 2.0], [6.0, 2.0], [6.0, 6.0], [2.0, 6.0]];
        assert!(triangulate(&[&a, &b]).is_err());
        assert!(triangulate(&[&a, &a]).is_err());
    }
}
