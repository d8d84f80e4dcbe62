//! Planning options: scale and turn style, with documented defaults.

/// How the serpentine rows are joined.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Turns {
    /// One LL or RR tile per U-turn: row pitch sqrt2 * w.
    Tight,
    /// Fold, one straight tile, fold: no LL/RR tiles, row pitch (1 + sqrt2) * w.
    Loose,
    /// Both are planned and the better fit is kept (the default).
    #[default]
    Auto,
}

impl std::str::FromStr for Turns {
    type Err = String;
    fn from_str(s: &str) -> Result<Turns, String> {
        match s.to_ascii_lowercase().as_str() {
            "tight" => Ok(Turns::Tight),
            "loose" => Ok(Turns::Loose),
            "auto" => Ok(Turns::Auto),
            _ => Err(format!("bad turns '{s}': expected tight, loose or auto")),
        }
    }
}

impl std::fmt::Display for Turns {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Turns::Tight => "tight",
            Turns::Loose => "loose",
            Turns::Auto => "auto",
        })
    }
}

/// Default number of tiles when neither `tiles` nor `tile_size` is given.
pub const DEFAULT_TILES: usize = 200;

/// Options of a plan. Default: about [`DEFAULT_TILES`] tiles, [`Turns::Auto`].
#[derive(Clone, Debug, PartialEq, Default)]
pub struct PlanOptions {
    /// About this many tiles (the tile size is searched to come near it). Ignored when
    /// `tile_size` is set.
    pub tiles: Option<usize>,
    /// The tile width (across flats) in SVG user units.
    pub tile_size: Option<f64>,
    /// The turn style.
    pub turns: Turns,
}

impl PlanOptions {
    /// About `n` tiles.
    pub fn with_tiles(mut self, n: usize) -> PlanOptions {
        self.tiles = Some(n);
        self
    }

    /// Tiles of width `w` in SVG user units.
    pub fn with_tile_size(mut self, w: f64) -> PlanOptions {
        self.tile_size = Some(w);
        self
    }

    /// The turn style.
    pub fn with_turns(mut self, turns: Turns) -> PlanOptions {
        self.turns = turns;
        self
    }
}
