//! The designs of a chain's tiles, what every run starts from: one global [`Design`] with
//! optional per-tile `s` and `e` (so sequential and simultaneous stretches can mix in one
//! chain), their JSON file form, and `s` given in millimetres or as a fraction of `e`.
//!
//! The file form is either a plain [`Design`] object or
//! `{"global": {...Design...}, "tiles": [{"from": 10, "to": 19, "s": 0.0}, ...]}`, where each
//! entry sets `s` and/or `e` (mm) of tiles `from..=to` (0 = the tile at the reaction
//! initiator); later entries win. Tile width, `d`, `c` and the magnets stay global: the tiles
//! of one chain share their outline.

use std::path::{Path, PathBuf};

use crate::{Design, DesignError};

/// `s` as given on a command line: millimetres, or a fraction of each tile's `e`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SValue {
    /// Millimetres.
    Millimetres(f64),
    /// A fraction of `e` (`e/3` is `FractionOfE(1/3)`).
    FractionOfE(f64),
}

impl SValue {
    /// Reads `0.3`, `0.3mm`, `1e-3` (a number in any float notation is millimetres), `e/3`,
    /// `2e/9`, `0.25e`, `0.25*e` or `e`.
    pub fn parse(text: &str) -> Result<SValue, DesignsError> {
        let bad = || DesignsError::BadS {
            text: text.to_string(),
        };
        let t: String = text.chars().filter(|c| !c.is_whitespace()).collect();
        let t = t.to_ascii_lowercase();
        let num = |s: &str| -> Result<f64, DesignsError> {
            if s.is_empty() {
                return Ok(1.0);
            }
            let v: f64 = s.parse().map_err(|_| bad())?;
            Ok(v)
        };
        let plain = t.strip_suffix("mm").unwrap_or(&t).parse::<f64>();
        let value = if let Ok(v) = plain {
            // a number first: `1e-3` is a millimetre value, not a fraction of e
            SValue::Millimetres(v)
        } else if let Some(pos) = t.find('e').filter(|_| !t.ends_with("mm")) {
            // a fraction of e: [k][*]e[/n]
            let (before, after) = t.split_at(pos);
            let k = num(before.strip_suffix('*').unwrap_or(before))?;
            let rest = &after[1..];
            let n = match rest.strip_prefix('/') {
                Some(n) => {
                    let n: f64 = n.parse().map_err(|_| bad())?;
                    if n.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
                        return Err(bad());
                    }
                    n
                }
                None if rest.is_empty() => 1.0,
                None => return Err(bad()),
            };
            SValue::FractionOfE(k / n)
        } else {
            let mm = t.strip_suffix("mm").unwrap_or(&t);
            let v: f64 = mm.parse().map_err(|_| bad())?;
            SValue::Millimetres(v)
        };
        let v = match value {
            SValue::Millimetres(v) | SValue::FractionOfE(v) => v,
        };
        if !v.is_finite() || v < 0.0 {
            return Err(bad());
        }
        Ok(value)
    }

    /// The value in mm for a tile with path part `e` (mm).
    pub fn to_mm(self, e: f64) -> f64 {
        match self {
            SValue::Millimetres(v) => v,
            SValue::FractionOfE(k) => k * e,
        }
    }
}

/// `s` and/or `e` set for a range of tiles.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct TileOverride {
    /// First tile (0 = at the reaction initiator).
    pub from: usize,
    /// Last tile, inclusive.
    pub to: usize,
    /// `s` of these tiles, mm.
    #[serde(default)]
    pub s: Option<f64>,
    /// `e` of these tiles, mm.
    #[serde(default)]
    pub e: Option<f64>,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct DesignFileJson {
    #[serde(default)]
    global: Design,
    #[serde(default)]
    tiles: Vec<TileOverride>,
}

/// The largest design file read: 256 MiB, room for a per-tile override of every tile of the
/// longest chain fold-run takes (2,000,000 tiles, about 100 bytes each).
const MAX_DESIGN_FILE_BYTES: u64 = 256 << 20;

/// Why a design could not be read or used.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum DesignsError {
    /// The file could not be read.
    #[error("cannot read design file {}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        #[source]
        source: std::io::Error,
    },
    /// The JSON is not a design.
    #[error("{origin}: bad design JSON: {reason} (expected a design object such as {{\"s\": 0.3, \"e\": 4.7}} or {{\"global\": {{...}}, \"tiles\": [{{\"from\": 0, \"to\": 9, \"s\": 0.1}}]}})")]
    Json {
        /// Where it came from.
        origin: String,
        /// What serde said.
        reason: String,
    },
    /// A parameter out of range.
    #[error("{origin}: {source}")]
    Parameter {
        /// Where it came from (`design`, or `tiles a..=b of the design`).
        origin: String,
        /// The parameter error.
        #[source]
        source: DesignError,
    },
    /// A tile range that is empty or reversed.
    #[error("{origin}: tile range {from}..={to} is reversed")]
    BadRange {
        /// Where it came from.
        origin: String,
        /// First tile.
        from: usize,
        /// Last tile.
        to: usize,
    },
    /// A value of `s` that could not be read ([`SValue::parse`]).
    #[error("bad value of s '{text}': expected a length in mm (0.3, 0.3mm) or a fraction of e (e/3, 0.25e, 0.25*e), finite and >= 0")]
    BadS {
        /// The text given.
        text: String,
    },
}

/// The designs of every tile of a chain: a global design and per-tile overrides.
#[derive(Clone, Debug, PartialEq)]
pub struct TileDesigns {
    global: Design,
    overrides: Vec<TileOverride>,
    s_for_all: Option<SValue>,
}

impl Default for TileDesigns {
    fn default() -> TileDesigns {
        TileDesigns::global(Design::thesis())
    }
}

/// What kind of JSON value `v` is, for a message.
fn json_kind(v: &serde_json::Value) -> &'static str {
    match v {
        serde_json::Value::Null => "null",
        serde_json::Value::Bool(_) => "boolean",
        serde_json::Value::Number(_) => "number",
        serde_json::Value::String(_) => "string",
        serde_json::Value::Array(_) => "array",
        serde_json::Value::Object(_) => "object",
    }
}

impl TileDesigns {
    /// One design for every tile.
    pub fn global(design: Design) -> TileDesigns {
        TileDesigns {
            global: design,
            overrides: Vec::new(),
            s_for_all: None,
        }
    }

    /// Reads the JSON form (see the module documentation); `origin` names it in errors.
    pub fn from_json(text: &str, origin: &str) -> Result<TileDesigns, DesignsError> {
        let json_err = |e: serde_json::Error| DesignsError::Json {
            origin: origin.to_string(),
            reason: e.to_string(),
        };
        let value: serde_json::Value = serde_json::from_str(text).map_err(json_err)?;
        // serde would read an array as the design's fields in order (`[1, 2]`: a tile 1 mm
        // wide with d = 2 mm) and report a range error about a field never written
        let global = value.get("global");
        let tiles = value.get("tiles").and_then(|t| t.as_array());
        let objects = std::iter::once(("the design", Some(&value)))
            .chain(std::iter::once(("`global`", global)))
            .chain(
                tiles
                    .into_iter()
                    .flatten()
                    .map(|t| ("a `tiles` entry", Some(t))),
            );
        for (what, v) in objects {
            if let Some(v) = v.filter(|v| !v.is_object()) {
                return Err(DesignsError::Json {
                    origin: origin.to_string(),
                    reason: format!(
                        "{what} is a JSON {} where an object {{...}} was expected",
                        json_kind(v)
                    ),
                });
            }
        }
        let is_file_form = value
            .as_object()
            .is_some_and(|o| o.contains_key("global") || o.contains_key("tiles"));
        let designs = if is_file_form {
            let f: DesignFileJson = serde_json::from_value(value).map_err(json_err)?;
            TileDesigns {
                global: f.global,
                overrides: f.tiles,
                s_for_all: None,
            }
        } else {
            TileDesigns::global(serde_json::from_value(value).map_err(json_err)?)
        };
        designs.check_ranges(origin)?;
        Ok(designs)
    }

    /// Reads a design file.
    pub fn from_file(path: &Path) -> Result<TileDesigns, DesignsError> {
        let read = |source| DesignsError::Read {
            path: path.to_path_buf(),
            source,
        };
        // at most MAX_DESIGN_FILE_BYTES: a device that never ends (`/dev/zero`) or a huge
        // file is refused once that much is read, not read into memory whole
        let mut bytes = Vec::new();
        std::io::Read::read_to_end(
            &mut std::io::Read::take(
                std::fs::File::open(path).map_err(read)?,
                MAX_DESIGN_FILE_BYTES + 1,
            ),
            &mut bytes,
        )
        .map_err(read)?;
        if bytes.len() as u64 > MAX_DESIGN_FILE_BYTES {
            return Err(read(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                "larger than 256 MiB: a design file holds a design and per-tile overrides",
            )));
        }
        let text = String::from_utf8(bytes).map_err(|e| {
            read(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!("not UTF-8 text ({e})"),
            ))
        })?;
        TileDesigns::from_json(&text, &path.display().to_string())
    }

    /// One global design with per-tile overrides (later entries win), as the file form
    /// gives them.
    pub(crate) fn with_overrides(global: Design, overrides: Vec<TileOverride>) -> TileDesigns {
        TileDesigns {
            global,
            overrides,
            s_for_all: None,
        }
    }

    /// The same designs with `s` set for every tile (a fraction of `e` uses each tile's `e`).
    pub fn with_s(mut self, s: SValue) -> TileDesigns {
        self.s_for_all = Some(s);
        self
    }

    /// The same designs with the global design edited by `edit` (the physical parameters a
    /// command line sets: per-tile overrides change only `s` and `e`, so every tile follows).
    pub fn with_global(mut self, edit: impl FnOnce(&mut Design)) -> TileDesigns {
        edit(&mut self.global);
        self
    }

    /// The global design (with `s` from [`TileDesigns::with_s`] applied).
    pub fn global_design(&self) -> Design {
        let mut d = self.global;
        if let Some(s) = self.s_for_all {
            d.s = s.to_mm(d.e);
        }
        d
    }

    /// Checks every parameter of every design (not the inequalities: a design that breaks
    /// them runs and stalls where the geometry says): [`Design::validate`].
    pub fn validate(&self, origin: &str) -> Result<(), DesignsError> {
        self.check_each(origin, Design::validate)
    }

    /// [`TileDesigns::validate`] and the physical ranges of a design file or a command line
    /// ([`Design::check_ranges`]); [`TileDesigns::from_json`] applies it.
    pub fn check_ranges(&self, origin: &str) -> Result<(), DesignsError> {
        self.check_each(origin, Design::check_ranges)
    }

    fn check_each(
        &self,
        origin: &str,
        check: fn(&Design) -> Result<(), DesignError>,
    ) -> Result<(), DesignsError> {
        check(&self.global_design()).map_err(|source| DesignsError::Parameter {
            origin: origin.to_string(),
            source,
        })?;
        for o in &self.overrides {
            if o.from > o.to {
                return Err(DesignsError::BadRange {
                    origin: origin.to_string(),
                    from: o.from,
                    to: o.to,
                });
            }
            check(&self.apply(self.global_design(), o)).map_err(|source| {
                DesignsError::Parameter {
                    origin: format!("{origin}: tiles {}..={}", o.from, o.to),
                    source,
                }
            })?;
        }
        Ok(())
    }

    fn apply(&self, mut d: Design, o: &TileOverride) -> Design {
        if let Some(e) = o.e {
            d.e = e;
        }
        match self.s_for_all {
            Some(s) => d.s = s.to_mm(d.e),
            None => {
                if let Some(s) = o.s {
                    d.s = s;
                }
            }
        }
        d
    }

    /// Whether any tile differs from the global design.
    pub fn has_overrides(&self) -> bool {
        !self.overrides.is_empty()
    }

    /// The distinct designs of a chain of `tiles` tiles and, per tile, the index of its
    /// design (all 0 when there are no overrides: then the vector is empty).
    pub fn resolve(&self, tiles: usize) -> (Vec<Design>, Vec<u32>) {
        let global = self.global_design();
        if self.overrides.is_empty() {
            return (vec![global], Vec::new());
        }
        let mut designs = vec![global];
        let mut index = vec![0u32; tiles];
        for o in &self.overrides {
            if o.from >= tiles {
                continue;
            }
            let to = o.to.min(tiles - 1);
            // Overrides compose: apply this one on top of what each tile has so far.
            for slot in &mut index[o.from..=to] {
                let d = self.apply(designs[*slot as usize], o);
                *slot = match designs.iter().position(|x| *x == d) {
                    Some(p) => p as u32,
                    None => {
                        designs.push(d);
                        (designs.len() - 1) as u32
                    }
                };
            }
        }
        (designs, index)
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    #[test]
    fn s_values() {
        assert_eq!(SValue::parse("0.3").unwrap(), SValue::Millimetres(0.3));
        assert_eq!(SValue::parse("0.3mm").unwrap(), SValue::Millimetres(0.3));
        assert_eq!(
            SValue::parse("e/3").unwrap(),
            SValue::FractionOfE(1.0 / 3.0)
        );
        assert_eq!(SValue::parse("0.25e").unwrap(), SValue::FractionOfE(0.25));
        assert_eq!(SValue::parse("0.25*e").unwrap(), SValue::FractionOfE(0.25));
        assert_eq!(
            SValue::parse("2e/9").unwrap(),
            SValue::FractionOfE(2.0 / 9.0)
        );
        assert_eq!(SValue::parse("0").unwrap(), SValue::Millimetres(0.0));
        // float notation is a number of mm, not a fraction of e
        assert_eq!(SValue::parse("1e-3").unwrap(), SValue::Millimetres(1e-3));
        assert_eq!(SValue::parse("3E-1mm").unwrap(), SValue::Millimetres(0.3));
        assert!(SValue::parse("inf").is_err() && SValue::parse("NaN").is_err());
        for bad in ["-0.1", "NaN", "inf", "e/0", "x", "", "e/-3", "0.3m", "1e/x"] {
            assert!(SValue::parse(bad).is_err(), "{bad}");
        }
        assert!(SValue::parse("-1")
            .unwrap_err()
            .to_string()
            .contains("'-1'"));
    }

    #[test]
    fn design_files() {
        let d = TileDesigns::from_json(r#"{"s": 0.2}"#, "x.json").unwrap();
        assert_eq!(d.global_design().s, 0.2);
        let d = TileDesigns::from_json(
            r#"{"global": {"s": 0.3}, "tiles": [{"from": 2, "to": 3, "s": 0.0}]}"#,
            "x.json",
        )
        .unwrap();
        let (designs, index) = d.resolve(6);
        assert_eq!(designs.len(), 2);
        assert_eq!(index, vec![0, 0, 1, 1, 0, 0]);
        assert_eq!(designs[1].s, 0.0);
        let e = TileDesigns::from_json(r#"{"s": -1}"#, "x.json").unwrap_err();
        assert!(
            e.to_string().contains("x.json") && e.to_string().contains("`s`"),
            "{e}"
        );
        let e = TileDesigns::from_json(r#"{"q": 1}"#, "x.json").unwrap_err();
        assert!(e.to_string().contains("unknown field"), "{e}");
        let e = TileDesigns::from_json("{", "x.json").unwrap_err();
        assert!(e.to_string().contains("bad design JSON"), "{e}");
        for text in [
            "[1, 2]",
            "3",
            "null",
            "\"s\"",
            r#"{"global": [1, 2]}"#,
            r#"{"tiles": [[0, 1]]}"#,
        ] {
            let e = TileDesigns::from_json(text, "d.json").unwrap_err();
            assert!(e.to_string().contains("where an object"), "{text}: {e}");
        }
        let e = TileDesigns::from_json(r#"{"tiles": [{"from": 3, "to": 1}]}"#, "x").unwrap_err();
        assert!(e.to_string().contains("reversed"), "{e}");
        let e = TileDesigns::from_json(r#"{"tiles": [{"from": 0, "to": 1, "e": -2}]}"#, "x")
            .unwrap_err();
        assert!(e.to_string().contains("tiles 0..=1"), "{e}");
        // --s with a fraction of e uses each tile's own e
        let d = TileDesigns::from_json(r#"{"tiles": [{"from": 1, "to": 1, "e": 3.0}]}"#, "x")
            .unwrap()
            .with_s(SValue::FractionOfE(1.0 / 3.0));
        let (designs, index) = d.resolve(3);
        assert!((designs[index[1] as usize].s - 1.0).abs() < 1e-15);
        assert!((designs[index[0] as usize].s - 4.7 / 3.0).abs() < 1e-15);
    }
}
