//! Triangle meshes in mm, and the checks a slicer relies on: closed (every edge in exactly
//! two triangles), consistently oriented (each edge run once each way), outward (positive
//! volume), no degenerate triangles.

use std::collections::HashMap;

use crate::region::Pt;

/// A point in space, mm.
pub type Pt3 = [f64; 3];

/// A triangle mesh: vertices and counter-clockwise (seen from outside) triangles.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// The vertices, mm.
    pub vertices: Vec<Pt3>,
    /// The triangles, as indices into `vertices`, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
}

/// What [`Mesh::topology`] found.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize)]
pub struct Topology {
    /// Edges in only one triangle.
    pub open_edges: usize,
    /// Edges in more than two triangles.
    pub non_manifold_edges: usize,
    /// Edges whose two triangles run them the same way (orientation flips there).
    pub misoriented_edges: usize,
    /// Triangles with two equal vertex indices or zero area.
    pub degenerate_triangles: usize,
    /// Edges in all.
    pub edges: usize,
}

impl Topology {
    /// Whether the mesh is closed, manifold and consistently oriented.
    pub fn is_sound(&self) -> bool {
        self.open_edges == 0
            && self.non_manifold_edges == 0
            && self.misoriented_edges == 0
            && self.degenerate_triangles == 0
    }
}

/// Builds a mesh, welding vertices given at exactly the same coordinates.
#[derive(Debug, Default)]
pub struct MeshBuilder {
    mesh: Mesh,
    index: HashMap<[u64; 3], u32>,
}

impl MeshBuilder {
    /// An empty mesh.
    pub fn new() -> MeshBuilder {
        MeshBuilder::default()
    }

    /// The index of the vertex at `p` (added when new). `-0.0` is welded to `0.0`.
    pub fn vertex(&mut self, p: Pt3) -> u32 {
        let key = p.map(|c| (c + 0.0).to_bits());
        *self.index.entry(key).or_insert_with(|| {
            self.mesh.vertices.push(p);
            (self.mesh.vertices.len() - 1) as u32
        })
    }

    /// Adds the triangle `a b c` (counter-clockwise seen from outside).
    pub fn triangle(&mut self, a: Pt3, b: Pt3, c: Pt3) {
        let t = [self.vertex(a), self.vertex(b), self.vertex(c)];
        self.mesh.triangles.push(t);
    }

    /// Adds a planar triangle at height `z`, facing up or down.
    pub fn flat(&mut self, t: [Pt; 3], z: f64, up: bool) {
        let [a, b, c] = t.map(|p| [p[0], p[1], z]);
        if up {
            self.triangle(a, b, c);
        } else {
            self.triangle(a, c, b);
        }
    }

    /// Adds the vertical wall under the edge `a -> b` from `z0` to `z1`, facing right of its
    /// direction (outwards when the solid lies on the edge's left).
    pub fn wall(&mut self, a: Pt, b: Pt, z0: f64, z1: f64) {
        let (a0, b0) = ([a[0], a[1], z0], [b[0], b[1], z0]);
        let (a1, b1) = ([a[0], a[1], z1], [b[0], b[1], z1]);
        self.triangle(a0, b0, b1);
        self.triangle(a0, b1, a1);
    }

    /// The mesh.
    pub fn finish(self) -> Mesh {
        self.mesh
    }
}

impl Mesh {
    /// Closedness, manifoldness and orientation, counted edge by edge.
    pub fn topology(&self) -> Topology {
        // undirected edge -> (uses a->b with a < b, uses b->a)
        let mut edges: HashMap<(u32, u32), (u32, u32)> = HashMap::new();
        let mut degenerate = 0;
        for t in &self.triangles {
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || self.triangle_area(t) <= 0.0 {
                degenerate += 1;
            }
            for i in 0..3 {
                let (a, b) = (t[i], t[(i + 1) % 3]);
                let e = edges.entry((a.min(b), a.max(b))).or_insert((0, 0));
                if a < b {
                    e.0 += 1;
                } else {
                    e.1 += 1;
                }
            }
        }
        let mut topo = Topology {
            degenerate_triangles: degenerate,
            edges: edges.len(),
            ..Topology::default()
        };
        for &(fwd, back) in edges.values() {
            match fwd + back {
                1 => topo.open_edges += 1,
                2 if fwd != 1 => topo.misoriented_edges += 1,
                2 => {}
                _ => topo.non_manifold_edges += 1,
            }
        }
        topo
    }

    /// A triangle's area, mm^2.
    pub fn triangle_area(&self, t: &[u32; 3]) -> f64 {
        let n = self.triangle_cross(t);
        0.5 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt()
    }

    /// The cross product of a triangle's edges from its first corner to the second and the
    /// third: along its outward normal (corners counter-clockwise seen from outside), twice
    /// its area long, mm^2.
    pub fn triangle_cross(&self, t: &[u32; 3]) -> [f64; 3] {
        let [a, b, c] = t.map(|i| self.vertices[i as usize]);
        let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ]
    }

    /// The enclosed volume, mm^3 (positive when the triangles face outwards).
    pub fn volume(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.vertices[i as usize]);
                a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                    + a[2] * (b[0] * c[1] - b[1] * c[0])
            })
            .sum::<f64>()
            / 6.0
    }

    /// The surface area, mm^2.
    pub fn surface_area(&self) -> f64 {
        self.triangles.iter().map(|t| self.triangle_area(t)).sum()
    }

    /// The least and greatest corner of the bounding box.
    pub fn bounds(&self) -> (Pt3, Pt3) {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for v in &self.vertices {
            for k in 0..3 {
                lo[k] = lo[k].min(v[k]);
                hi[k] = hi[k].max(v[k]);
            }
        }
        (lo, hi)
    }

    /// The mesh turned by `angle` radians about the z axis through the origin.
    pub fn rotated_z(&self, angle: f64) -> Mesh {
        let (s, c) = angle.sin_cos();
        Mesh {
            vertices: self
                .vertices
                .iter()
                .map(|v| [c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]])
                .collect(),
            triangles: self.triangles.clone(),
        }
    }

    /// The cross-section at height `z`: the segments where the triangles meet the plane
    /// (a plane through vertices is moved up by 1e-9 mm so that it meets none).
    pub fn section(&self, z: f64) -> Vec<(Pt, Pt)> {
        let z = if self.vertices.iter().any(|v| v[2] == z) {
            z + 1e-9
        } else {
            z
        };
        let mut out = Vec::new();
        for t in &self.triangles {
            let p = t.map(|i| self.vertices[i as usize]);
            let mut hits = Vec::with_capacity(2);
            for i in 0..3 {
                let (a, b) = (p[i], p[(i + 1) % 3]);
                if (a[2] < z) != (b[2] < z) {
                    let f = (z - a[2]) / (b[2] - a[2]);
                    hits.push([a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])]);
                }
            }
            if hits.len() == 2 {
                out.push((hits[0], hits[1]));
            }
        }
        out
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    fn cube() -> Mesh {
        let mut b = MeshBuilder::new();
        let sq = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        b.flat([sq[0], sq[1], sq[2]], 0.0, false);
        b.flat([sq[0], sq[2], sq[3]], 0.0, false);
        b.flat([sq[0], sq[1], sq[2]], 1.0, true);
        b.flat([sq[0], sq[2], sq[3]], 1.0, true);
        for i in 0..4 {
            b.wall(sq[i], sq[(i + 1) % 4], 0.0, 1.0);
        }
        b.finish()
    }

    #[test]
    fn a_cube_is_sound_and_a_flipped_face_is_seen() {
        let c = cube();
        assert_eq!(c.vertices.len(), 8);
        assert!(c.topology().is_sound(), "{:?}", c.topology());
        assert!((c.volume() - 1.0).abs() < 1e-12);
        assert!((c.surface_area() - 6.0).abs() < 1e-12);
        assert_eq!(c.section(0.5).len(), 8);
        let mut bad = c.clone();
        bad.triangles[0].swap(1, 2);
        assert_eq!(bad.topology().misoriented_edges, 3);
        let mut open = c;
        open.triangles.pop();
        assert_eq!(open.topology().open_edges, 3);
    }
}
