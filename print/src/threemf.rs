//! 3MF: the 3D Manufacturing Format's core, a zip holding an XML model in mm with named
//! objects (each a mesh) and build items placing them (a plate places one object many
//! times). PrusaSlicer, Cura and Bambu Studio read it.

use std::fmt::Write as _;
use std::io::Write as _;

use crate::{Mesh, PrintError};

/// The core specification's namespace.
const CORE_NS: &str = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02";

/// An object of a 3MF model: a name and a mesh.
#[derive(Clone, Debug)]
pub struct Object<'a> {
    /// The name slicers show.
    pub name: String,
    /// The mesh, mm.
    pub mesh: &'a Mesh,
}

/// A build item: an object placed by a turn about z and a shift, mm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Item {
    /// Index into the objects.
    pub object: usize,
    /// Turn about the z axis, radians.
    pub angle: f64,
    /// Shift in x, mm.
    pub x: f64,
    /// Shift in y, mm.
    pub y: f64,
}

/// A coordinate with at most 6 decimals (a micrometre's thousandth), trailing zeros dropped.
fn num(out: &mut String, x: f64) {
    let x = if x.abs() < 5e-7 { 0.0 } else { x };
    let s = format!("{x:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    out.push_str(s);
}

/// The model XML.
pub fn model_xml(title: &str, objects: &[Object<'_>], items: &[Item]) -> String {
    let mut x = String::new();
    x.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        x,
        "<model unit=\"millimeter\" xml:lang=\"en-US\" xmlns=\"{CORE_NS}\">"
    );
    let _ = writeln!(x, " <metadata name=\"Title\">{}</metadata>", escape(title));
    x.push_str(" <metadata name=\"Application\">foldchain-print</metadata>\n");
    x.push_str(" <resources>\n");
    for (i, o) in objects.iter().enumerate() {
        let _ = writeln!(
            x,
            "  <object id=\"{}\" type=\"model\" name=\"{}\">\n   <mesh>\n    <vertices>",
            i + 1,
            escape(&o.name)
        );
        for v in &o.mesh.vertices {
            x.push_str("     <vertex x=\"");
            num(&mut x, v[0]);
            x.push_str("\" y=\"");
            num(&mut x, v[1]);
            x.push_str("\" z=\"");
            num(&mut x, v[2]);
            x.push_str("\"/>\n");
        }
        x.push_str("    </vertices>\n    <triangles>\n");
        for t in &o.mesh.triangles {
            let _ = writeln!(
                x,
                "     <triangle v1=\"{}\" v2=\"{}\" v3=\"{}\"/>",
                t[0], t[1], t[2]
            );
        }
        x.push_str("    </triangles>\n   </mesh>\n  </object>\n");
    }
    x.push_str(" </resources>\n <build>\n");
    for it in items {
        let (s, c) = it.angle.sin_cos();
        // 3MF's row-vector 3x4 matrix: m00 m01 m02 m10 m11 m12 m20 m21 m22 m30 m31 m32
        let m = [c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0, it.x, it.y, 0.0];
        let _ = write!(x, "  <item objectid=\"{}\" transform=\"", it.object + 1);
        for (k, v) in m.iter().enumerate() {
            if k > 0 {
                x.push(' ');
            }
            num(&mut x, *v);
        }
        x.push_str("\"/>\n");
    }
    x.push_str(" </build>\n</model>\n");
    x
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

const CONTENT_TYPES: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">
 <Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>
 <Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>
</Types>
"#;

const RELS: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">
 <Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>
</Relationships>
"#;

/// The 3MF file: `objects` placed by `items`; `name` names the file in errors.
pub fn to_3mf(
    name: &str,
    title: &str,
    objects: &[Object<'_>],
    items: &[Item],
) -> Result<Vec<u8>, PrintError> {
    let model = model_xml(title, objects, items);
    let fail = |e: &dyn std::fmt::Display| PrintError::Format {
        name: name.to_string(),
        reason: e.to_string(),
    };
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let opts = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated)
        .compression_level(Some(6));
    for (path, body) in [
        ("[Content_Types].xml", CONTENT_TYPES),
        ("_rels/.rels", RELS),
        ("3D/3dmodel.model", model.as_str()),
    ] {
        zip.start_file(path, opts).map_err(|e| fail(&e))?;
        zip.write_all(body.as_bytes()).map_err(|e| fail(&e))?;
    }
    let cursor = zip.finish().map_err(|e| fail(&e))?;
    Ok(cursor.into_inner())
}

/// A 3MF model read back: its objects and build items.
#[derive(Clone, Debug, Default)]
pub struct Model {
    /// Objects: name and mesh.
    pub objects: Vec<(String, Mesh)>,
    /// Build items (angle from the transform's first row).
    pub items: Vec<Item>,
}

/// The value of attribute `name` in a tag's text.
fn attr<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let start = tag.find(&key)? + key.len();
    let end = tag[start..].find('"')?;
    Some(&tag[start..start + end])
}

/// The mesh of the object read last, for `what` (a vertex, a triangle) read inside it.
fn last_mesh<'a>(model: &'a mut Model, what: &str) -> Result<&'a mut Mesh, String> {
    match model.objects.last_mut() {
        Some((_, mesh)) => Ok(mesh),
        None => Err(format!("{what} outside an object")),
    }
}

/// Reads a 3MF file as this module writes it (one model part; objects with meshes; build
/// items with transforms): for checking written files.
pub fn read_3mf(bytes: &[u8]) -> Result<Model, String> {
    use std::io::Read as _;
    let mut zip =
        zip::ZipArchive::new(std::io::Cursor::new(bytes)).map_err(|e| format!("not a zip: {e}"))?;
    let mut xml = String::new();
    zip.by_name("3D/3dmodel.model")
        .map_err(|e| format!("no 3D/3dmodel.model: {e}"))?
        .read_to_string(&mut xml)
        .map_err(|e| e.to_string())?;
    if !xml.contains("unit=\"millimeter\"") {
        return Err("the model's unit is not millimetre".into());
    }
    let mut model = Model::default();
    let mut ids: Vec<String> = Vec::new();
    let num = |t: &str, n: &str| -> Result<f64, String> {
        attr(t, n)
            .and_then(|v| v.parse::<f64>().ok())
            .ok_or_else(|| format!("bad {n} in {t}"))
    };
    for tag in xml.split('<').skip(1) {
        let tag = tag.split('>').next().unwrap_or("");
        if tag.starts_with("object ") {
            ids.push(attr(tag, "id").unwrap_or("").to_string());
            let name = attr(tag, "name").unwrap_or("").to_string();
            model.objects.push((name, Mesh::default()));
        } else if tag.starts_with("vertex ") {
            let v = [num(tag, "x")?, num(tag, "y")?, num(tag, "z")?];
            last_mesh(&mut model, "a vertex")?.vertices.push(v);
        } else if tag.starts_with("triangle ") {
            let t = [num(tag, "v1")?, num(tag, "v2")?, num(tag, "v3")?].map(|x| x as u32);
            last_mesh(&mut model, "a triangle")?.triangles.push(t);
        } else if tag.starts_with("item ") {
            let id = attr(tag, "objectid").unwrap_or("");
            let object = ids
                .iter()
                .position(|i| i == id)
                .ok_or_else(|| format!("item of unknown object {id}"))?;
            let m: Vec<f64> = attr(tag, "transform")
                .unwrap_or("1 0 0 0 1 0 0 0 1 0 0 0")
                .split_whitespace()
                .filter_map(|x| x.parse().ok())
                .collect();
            if m.len() != 12 {
                return Err(format!("bad transform in {tag}"));
            }
            model.items.push(Item {
                object,
                angle: m[1].atan2(m[0]),
                x: m[9],
                y: m[10],
            });
        }
    }
    Ok(model)
}
