//! A picture of a part drawn from its mesh: an orthographic view from above and in front,
//! flat shaded. [`mesh_png`] rasterises the triangles with a depth buffer (exact occlusion,
//! four samples per pixel); [`mesh_svg`] paints them far to near as vector polygons (small,
//! but long wall triangles can be painted in the wrong order).

use std::fmt::Write as _;

use crate::Mesh;

/// The view: where from, and the picture's size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// Turn about z, degrees (0 looks along +y).
    pub azimuth_deg: f64,
    /// Height of the eye above the bed plane, degrees.
    pub elevation_deg: f64,
    /// Pixels per mm.
    pub scale: f64,
}

impl Default for View {
    /// From the front left and 40 degrees up, 12 px per mm.
    fn default() -> View {
        View {
            azimuth_deg: -25.0,
            elevation_deg: 40.0,
            scale: 12.0,
        }
    }
}

/// The mesh drawn as an SVG document, `title` written under it.
pub fn mesh_svg(mesh: &Mesh, title: &str, view: &View) -> String {
    let (right, up, fwd) = camera(view);
    let light = light();
    let s = view.scale;
    let mut faces: Vec<(f64, [[f64; 2]; 3], f64)> = Vec::new();
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| mesh.vertices[i as usize]);
        let n = mesh.triangle_cross(t);
        let len = dot(n, n).sqrt();
        if len == 0.0 {
            continue;
        }
        let n = n.map(|x| x / len);
        let p = [a, b, c].map(|q| [s * dot(q, right), -s * dot(q, up)]);
        for q in &p {
            for k in 0..2 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
        }
        if dot(n, fwd) >= 0.0 {
            continue;
        }
        let depth = (dot(a, fwd) + dot(b, fwd) + dot(c, fwd)) / 3.0;
        let shade = 0.35 + 0.65 * dot(n, light).max(0.0);
        faces.push((depth, p, shade));
    }
    faces.sort_by(|x, y| y.0.total_cmp(&x.0));
    let pad = 10.0;
    let (w, h) = (hi[0] - lo[0] + 2.0 * pad, hi[1] - lo[1] + 2.0 * pad + 24.0);
    let mut out = String::new();
    let _ = writeln!(
        out,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w:.0}\" height=\"{h:.0}\" viewBox=\"0 0 {w:.1} {h:.1}\">"
    );
    let _ = writeln!(
        out,
        "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>"
    );
    let (ox, oy) = (pad - lo[0], pad - lo[1]);
    for (_, p, shade) in &faces {
        // a warm grey-blue like a printed PLA part
        let col = |base: f64| (base * shade).round().clamp(0.0, 255.0) as u8;
        let (r, g, b) = (col(150.0), col(180.0), col(225.0));
        let _ = writeln!(
            out,
            "<polygon points=\"{:.2},{:.2} {:.2},{:.2} {:.2},{:.2}\" fill=\"rgb({r},{g},{b})\" stroke=\"rgb({r},{g},{b})\" stroke-width=\"0.5\" stroke-linejoin=\"round\"/>",
            p[0][0] + ox,
            p[0][1] + oy,
            p[1][0] + ox,
            p[1][1] + oy,
            p[2][0] + ox,
            p[2][1] + oy
        );
    }
    let _ = writeln!(
        out,
        "<text x=\"{:.1}\" y=\"{:.1}\" font-family=\"sans-serif\" font-size=\"14\" text-anchor=\"middle\" fill=\"#333\">{}</text>",
        0.5 * w,
        h - 8.0,
        title.replace('&', "&amp;").replace('<', "&lt;")
    );
    out.push_str("</svg>\n");
    out
}

/// The dot product of two vectors.
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The direction towards the light in the part's frame, unit length: above the part (+z),
/// towards -x and -y.
fn light() -> [f64; 3] {
    let l = [-0.4, -0.6, 0.9];
    let n = dot(l, l).sqrt();
    l.map(|x| x / n)
}

/// The camera's axes for a view: right, up and the direction it looks along.
fn camera(view: &View) -> ([f64; 3], [f64; 3], [f64; 3]) {
    let (az, el) = (
        view.azimuth_deg.to_radians(),
        view.elevation_deg.to_radians(),
    );
    let right = [az.cos(), az.sin(), 0.0];
    let fwd = [-az.sin() * el.cos(), az.cos() * el.cos(), -el.sin()];
    let up = [
        right[1] * fwd[2] - right[2] * fwd[1],
        right[2] * fwd[0] - right[0] * fwd[2],
        right[0] * fwd[1] - right[1] * fwd[0],
    ];
    (right, up, fwd)
}

/// The mesh rasterised with a depth buffer as a PNG image (RGB), `view.scale` pixels per mm,
/// on white; `None` only if the encoder fails.
pub fn mesh_png(mesh: &Mesh, view: &View) -> Option<Vec<u8>> {
    let (right, up, fwd) = camera(view);
    let light = light();
    let ss = 2.0; // samples per pixel along each axis
    let k = view.scale * ss;
    let pts: Vec<[f64; 3]> = mesh
        .vertices
        .iter()
        .map(|&v| [k * dot(v, right), -k * dot(v, up), dot(v, fwd)])
        .collect();
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in &pts {
        for a in 0..2 {
            lo[a] = lo[a].min(p[a]);
            hi[a] = hi[a].max(p[a]);
        }
    }
    if !lo[0].is_finite() {
        return None;
    }
    let pad = 8.0 * ss;
    let w = ((hi[0] - lo[0] + 2.0 * pad).ceil() as usize).clamp(1, 8192);
    let h = ((hi[1] - lo[1] + 2.0 * pad).ceil() as usize).clamp(1, 8192);
    let mut depth = vec![f64::INFINITY; w * h];
    let mut colour = vec![[255u8; 3]; w * h];
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| pts[i as usize]);
        let n = mesh.triangle_cross(t);
        let len = dot(n, n).sqrt();
        if len == 0.0 || dot(n, fwd) >= 0.0 {
            continue;
        }
        let shade = 0.35 + 0.65 * dot(n.map(|x| x / len), light).max(0.0);
        let rgb = [150.0, 180.0, 225.0].map(|c: f64| (c * shade).round().clamp(0.0, 255.0) as u8);
        let to = |p: [f64; 3]| [p[0] - lo[0] + pad, p[1] - lo[1] + pad, p[2]];
        let (a, b, c) = (to(a), to(b), to(c));
        let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        if area.abs() < 1e-12 {
            continue;
        }
        let x0 = a[0].min(b[0]).min(c[0]).floor().max(0.0) as usize;
        let x1 = (a[0].max(b[0]).max(c[0]).ceil() as usize).min(w - 1);
        let y0 = a[1].min(b[1]).min(c[1]).floor().max(0.0) as usize;
        let y1 = (a[1].max(b[1]).max(c[1]).ceil() as usize).min(h - 1);
        for y in y0..=y1 {
            for x in x0..=x1 {
                let p = [x as f64 + 0.5, y as f64 + 0.5];
                let w0 = ((b[0] - p[0]) * (c[1] - p[1]) - (b[1] - p[1]) * (c[0] - p[0])) / area;
                let w1 = ((c[0] - p[0]) * (a[1] - p[1]) - (c[1] - p[1]) * (a[0] - p[0])) / area;
                let w2 = 1.0 - w0 - w1;
                if w0 < -1e-9 || w1 < -1e-9 || w2 < -1e-9 {
                    continue;
                }
                let z = w0 * a[2] + w1 * b[2] + w2 * c[2];
                let i = y * w + x;
                if z < depth[i] {
                    depth[i] = z;
                    colour[i] = rgb;
                }
            }
        }
    }
    // average each 2 x 2 block into one pixel
    let (pw, ph) = (w / 2, h / 2);
    let mut img = Vec::with_capacity(pw * ph * 3);
    for y in 0..ph {
        for x in 0..pw {
            let mut sum = [0u32; 3];
            for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                for (acc, c) in sum.iter_mut().zip(colour[(2 * y + dy) * w + 2 * x + dx]) {
                    *acc += u32::from(c);
                }
            }
            img.extend(sum.map(|s| (s / 4) as u8));
        }
    }
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, pw as u32, ph as u32);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut writer = enc.write_header().ok()?;
        writer.write_image_data(&img).ok()?;
    }
    Some(out)
}
