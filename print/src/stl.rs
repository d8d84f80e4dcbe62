//! Binary STL: one mesh, little-endian f32 coordinates in mm (STL has no unit; every slicer
//! reads millimetres).

use crate::Mesh;

/// The mesh as binary STL bytes, `name` in the 80-byte header.
pub fn to_stl(mesh: &Mesh, name: &str) -> Vec<u8> {
    let mut out = Vec::with_capacity(84 + 50 * mesh.triangles.len());
    let mut header = [b' '; 80];
    let text = format!("foldchain-print {name}");
    for (h, b) in header
        .iter_mut()
        .zip(text.bytes().filter(|b| b.is_ascii_graphic() || *b == b' '))
    {
        *h = b;
    }
    // a header starting "solid" makes some readers take binary STL for ASCII
    out.extend_from_slice(&header);
    out.extend_from_slice(&(mesh.triangles.len() as u32).to_le_bytes());
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| mesh.vertices[i as usize]);
        let n = mesh.triangle_cross(t);
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let n = if len > 0.0 {
            n.map(|x| x / len)
        } else {
            [0.0; 3]
        };
        for x in n.iter().chain(a.iter()).chain(b.iter()).chain(c.iter()) {
            out.extend_from_slice(&(*x as f32).to_le_bytes());
        }
        out.extend_from_slice(&0u16.to_le_bytes());
    }
    out
}

/// Reads binary STL bytes back into a mesh, welding equal vertices (for tests and checks).
pub fn from_stl(bytes: &[u8]) -> Option<Mesh> {
    let n = u32::from_le_bytes(bytes.get(80..84)?.try_into().ok()?) as usize;
    if bytes.len() != 84 + 50 * n {
        return None;
    }
    let mut b = crate::MeshBuilder::new();
    for i in 0..n {
        let rec = &bytes[84 + 50 * i..84 + 50 * (i + 1)];
        let f = |k: usize| -> f64 {
            let o = 12 + 4 * k;
            f64::from(f32::from_le_bytes([
                rec[o],
                rec[o + 1],
                rec[o + 2],
                rec[o + 3],
            ]))
        };
        let p = |j: usize| [f(3 * j), f(3 * j + 1), f(3 * j + 2)];
        b.triangle(p(0), p(1), p(2));
    }
    Some(b.finish())
}
